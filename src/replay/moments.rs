//! A telling moment of a finished run, as its experiment picks it from the tables the run
//! wrote ([`crate::experiments::Replayable::telling_moment`]), and the replays of the results
//! page of `steplearn reproduce` and of the page of `steplearn bench` (its best and its worst
//! row), written beside their `index.html`.

use super::{Moment, ReplayError, RunConfig, moment_to_file, summary_line};
use crate::bench::Registry;
use crate::bench::{Leaderboard, LeaderboardRow};
use crate::experiments::index_page::ReplayLink;
use crate::experiments::paired::Verdict;
use crate::experiments::sweep::RunSpec;
use std::path::Path;

/// The file name of experiment `experiment`'s replay beside `index.html`.
pub fn replay_file_name(experiment: &str) -> String {
    format!("replay-{experiment}.html")
}

/// A telling moment of the run in `dir`, as its experiment picks it
/// ([`crate::experiments::Replayable::telling_moment`]), with a one-line description.
pub fn telling_moment(registry: &Registry, dir: &Path) -> Result<(Moment, String), ReplayError> {
    let (config, _) = RunConfig::read(dir)?;
    let experiment = registry.find_experiment(&config.experiment)?;
    let replayable = experiment
        .replay()
        .ok_or_else(|| ReplayError::Unsupported(config.experiment.clone()))?;
    Ok(replayable.telling_moment(&config.settings, &config.protocols(), config.seed, dir)?)
}

/// Writes the replay of a telling moment of each run in `runs` (one per experiment) into
/// `out` as [`replay_file_name`], and returns the links for the results page. A run that
/// cannot be replayed is left out with a warning on stderr: the page is written regardless.
pub fn write_results_replays(
    registry: &Registry,
    out: &Path,
    runs: &[(String, std::path::PathBuf)],
) -> Vec<ReplayLink> {
    let mut links = Vec::new();
    for (experiment, dir) in runs {
        let file = replay_file_name(experiment);
        if let Some(caption) = write_replay(registry, out, &file, dir, "") {
            links.push(ReplayLink {
                experiment: experiment.clone(),
                file,
                caption,
            });
        }
    }
    links
}

/// Writes the replay of a telling moment of the run in `dir` to `out/file`, printing its
/// summary line on stderr; returns the link's caption, `label` first, or `None` with a
/// warning on stderr if the run cannot be replayed.
fn write_replay(
    registry: &Registry,
    out: &Path,
    file: &str,
    dir: &Path,
    label: &str,
) -> Option<String> {
    let page = out.join(file);
    let written = telling_moment(registry, dir)
        .and_then(|(moment, why)| moment_to_file(registry, dir, moment, &page).map(|r| (r, why)));
    match written {
        Ok((replay, why)) => {
            eprintln!("{}", summary_line(&replay, &page));
            let run = dir
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            Some(format!(
                "{label}{run}, {why} ({} walkers side by side)",
                replay.walks.len()
            ))
        }
        Err(e) => {
            eprintln!("no replay of {}: {e}", dir.display());
            None
        }
    }
}

/// The file names of the bench page's replays of its best and its worst row.
pub const BENCH_REPLAY_FILES: [&str; 2] = ["replay-best.html", "replay-worst.html"];

/// A row's standing against the model: verdicts better minus verdicts worse.
fn standing(row: &LeaderboardRow) -> isize {
    let count = |v: Verdict| row.vs_model.iter().filter(|c| c.verdict == Some(v)).count();
    count(Verdict::Better) as isize - count(Verdict::Worse) as isize
}

/// The best and the worst row of `leaderboard` among those whose experiment (in `registry`)
/// has a replay and with a finished run: the most and the fewest verdicts better minus worse
/// against the model (ties: the first row for the best, the last for the worst). `None`
/// without such a row.
pub fn best_and_worst<'a>(
    registry: &Registry,
    leaderboard: &'a Leaderboard,
) -> Option<(&'a LeaderboardRow, &'a LeaderboardRow)> {
    let replayed = |name: &str| {
        registry
            .find_experiment(name)
            .is_ok_and(|e| e.replay().is_some())
    };
    let rows: Vec<&LeaderboardRow> = leaderboard
        .rows
        .iter()
        .filter(|r| !r.seeds.is_empty() && replayed(&r.experiment))
        .collect();
    let best = rows.iter().rev().max_by_key(|r| standing(r))?;
    let worst = rows.iter().min_by_key(|r| standing(r))?;
    Some((best, worst))
}

/// Writes the replays of the bench page (`index.html` in `out`): a telling moment of its best
/// and of its worst row ([`best_and_worst`]) as [`BENCH_REPLAY_FILES`], the best row's of its
/// first seed's run, the worst row's of its last seed's (so that a bench of one row shows two
/// runs). Returns the links for the page; a run that cannot be replayed is left out with a
/// warning on stderr, and the page is written regardless.
pub fn write_bench_replays(
    registry: &Registry,
    out: &Path,
    leaderboard: &Leaderboard,
) -> Vec<ReplayLink> {
    let Some((best, worst)) = best_and_worst(registry, leaderboard) else {
        return Vec::new();
    };
    let picks = [
        ("best", best, best.seeds.first()),
        ("worst", worst, worst.seeds.last()),
    ];
    let mut links = Vec::new();
    for ((which, row, seed), file) in picks.into_iter().zip(BENCH_REPLAY_FILES) {
        let Some(&seed) = seed else { continue };
        let spec = RunSpec {
            experiment: row.experiment.clone(),
            approx: row.approx.clone(),
            rule: row.rule.clone(),
            seed,
            learn: Some(row.learn),
        };
        let label = format!(
            "the {which} row ({} + {} [{}], {}): ",
            row.approx, row.rule, row.learn, row.experiment
        );
        if let Some(caption) = write_replay(registry, out, file, &out.join(spec.id()), &label) {
            links.push(ReplayLink {
                experiment: row.experiment.clone(),
                file: file.to_string(),
                caption,
            });
        }
    }
    links
}
