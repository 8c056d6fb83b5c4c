//! A telling moment of a finished run, read from the tables the run wrote, and the replays of
//! the results page of `steplearn reproduce` and of the page of `steplearn bench` (its best
//! and its worst row), written beside their `index.html`.
//!
//! - B, C: the push (C: of smallest impulse) where one walker fell and the other recovered;
//!   else the first push (C: of smallest impulse) where one fell; else push 1.
//! - D: the first push the learned walker absorbed and the walker without learning did not;
//!   else the first where they differ; else push 1.
//! - A: the largest reference change in the run's first two minutes, from 1 s before it to the
//!   protocol's horizon after it.

use super::{Moment, ReplayError, RunConfig, moment_to_file, replayed, summary_line};
use crate::bench::Registry;
use crate::bench::leaderboard::{Leaderboard, LeaderboardRow};
use crate::experiments::ExperimentKind;
use crate::experiments::index_page::ReplayLink;
use crate::experiments::paired::Verdict;
use crate::experiments::sweep::{IDENTITY_FILE, RunSpec};
use crate::experiments::tracking::{self, TrackingProtocol};
use crate::report::csv_read::read_rows;
use serde::Deserialize;
use serde::de::DeserializeOwned;
use std::path::Path;

/// The file name of experiment `experiment`'s replay beside `index.html`.
pub fn replay_file_name(experiment: &str) -> String {
    format!("replay-{experiment}.html")
}

fn corrupt(path: &Path, reason: &str) -> ReplayError {
    ReplayError::Corrupt {
        path: path.to_path_buf(),
        reason: reason.to_string(),
    }
}

/// The rows of a CSV table the run wrote ([`read_rows`]), its errors as the run's.
fn table<R: DeserializeOwned>(path: &Path) -> Result<Vec<R>, ReplayError> {
    read_rows(path).map_err(|e| corrupt(path, &e.to_string()))
}

/// A push of a pushes table of B or C (`pushes.csv`, `disturbance_pushes.csv`).
#[derive(Deserialize)]
struct PushRow {
    controller: String,
    impulse_ns: f64,
    fell: bool,
}

/// A push of `robustness_pushes.csv`; `no_learning_fell` is empty where the run had no walker
/// without learning.
#[derive(Deserialize)]
struct RobustnessRow {
    fell: bool,
    #[serde(default)]
    no_learning_fell: Option<bool>,
}

/// (impulse, fell) per push of `controller` in a pushes table of B or C.
fn pushes_of(path: &Path, controller: &str) -> Result<Vec<(f64, bool)>, ReplayError> {
    Ok(table::<PushRow>(path)?
        .into_iter()
        .filter(|r| r.controller == controller)
        .map(|r| (r.impulse_ns, r.fell))
        .collect())
}

/// How a walker came out of a push, in a moment's description.
fn outcome(fell: bool) -> &'static str {
    if fell { "fell" } else { "absorbed it" }
}

/// The push (1-based) where `a` and `b` differ, of smallest impulse (ties: the first); else
/// the first where either fell, of smallest impulse; else push 1.
fn differing_push(a: &[(f64, bool)], b: &[(f64, bool)]) -> usize {
    let pick = |pred: &dyn Fn(bool, bool) -> bool| {
        a.iter()
            .zip(b)
            .enumerate()
            .filter(|(_, (x, y))| pred(x.1, y.1))
            .min_by(|(i, (x, _)), (j, (y, _))| x.0.total_cmp(&y.0).then(i.cmp(j)))
            .map(|(i, _)| i + 1)
    };
    pick(&|x, y| x != y)
        .or_else(|| pick(&|x, y| x || y))
        .unwrap_or(1)
}

/// A telling moment of the run in `dir` (see the module's documentation), with a one-line
/// description.
pub fn telling_moment(dir: &Path) -> Result<(Moment, String), ReplayError> {
    let (config, _) = RunConfig::read(dir)?;
    let kind = replayed(&config.experiment)
        .ok_or_else(|| ReplayError::Unsupported(config.experiment.clone()))?;
    let differ = |a: &[(f64, bool)], b: &[(f64, bool)], an: &str, bn: &str| {
        let k = differing_push(a, b);
        let fell = |x: &[(f64, bool)]| x.get(k - 1).is_some_and(|p| p.1);
        let impulse = a.get(k - 1).map_or(0.0, |p| p.0);
        (
            Moment::Push(k),
            format!(
                "push {k} ({impulse:.1} Ns): {an} {}, {bn} {}",
                outcome(fell(a)),
                outcome(fell(b))
            ),
        )
    };
    Ok(match kind {
        ExperimentKind::Stability => {
            let path = dir.join("pushes.csv");
            let (l, m) = (pushes_of(&path, "learned")?, pushes_of(&path, "model")?);
            differ(&l, &m, "learned", "model")
        }
        ExperimentKind::Disturbance => {
            let path = dir.join("disturbance_pushes.csv");
            let (l, m) = (pushes_of(&path, "learned")?, pushes_of(&path, "model")?);
            // B's pushes all have one impulse: the first that differs.
            differ(&l, &m, "learned", "model")
        }
        ExperimentKind::Robustness => {
            let rows: Vec<RobustnessRow> = table(&dir.join("robustness_pushes.csv"))?;
            // Equal impulses: the first push that differs.
            let learned: Vec<(f64, bool)> = rows.iter().map(|r| (0.0, r.fell)).collect();
            let without: Vec<(f64, bool)> = rows
                .iter()
                .map(|r| (0.0, r.no_learning_fell.unwrap_or(false)))
                .collect();
            let k = learned
                .iter()
                .zip(&without)
                .position(|(l, w)| !l.1 && w.1)
                .map_or_else(|| differing_push(&learned, &without), |i| i + 1);
            let (l, w) = (
                learned.get(k - 1).is_some_and(|p| p.1),
                without.get(k - 1).is_some_and(|p| p.1),
            );
            (
                Moment::Push(k),
                format!(
                    "push {k}: learned {}, without learning {}",
                    outcome(l),
                    outcome(w)
                ),
            )
        }
        ExperimentKind::Tracking => {
            let protocol: TrackingProtocol = config
                .protocols()
                .get(&config.experiment)
                .map_err(|e| corrupt(&dir.join(IDENTITY_FILE), &e.to_string()))?;
            let setup = tracking::trial_setup(&config.settings, &protocol, config.seed)?;
            let reference = &setup.reference;
            let last = (setup.duration_s - protocol.horizon_s).min(120.0);
            let jump = |t: f64| (reference.at(t) - reference.at(t - 1e-6)).abs();
            let change = reference
                .change_times()
                .into_iter()
                .filter(|&t| t >= 1.0 && t <= last)
                .max_by(|&a, &b| jump(a).total_cmp(&jump(b)))
                .ok_or_else(|| corrupt(&dir.join(IDENTITY_FILE), "no reference change"))?;
            let (from, to) = (change - 1.0, change + protocol.horizon_s);
            let (from, to) = (super::record::round(from), super::record::round(to));
            (
                Moment::Span(from, to),
                format!(
                    "the reference change at {change:.2} s (F_R {:.3} to {:.3} m), {from}..{to} s",
                    reference.at(change - 1e-6),
                    reference.at(change)
                ),
            )
        }
    })
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
    let written = telling_moment(dir)
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

/// The best and the worst row of `leaderboard` among those whose experiment has a replay
/// ([`super::REPLAYED`]) and with a finished run: the most and the fewest verdicts better minus worse
/// against the model (ties: the first row for the best, the last for the worst). `None`
/// without such a row.
pub fn best_and_worst(leaderboard: &Leaderboard) -> Option<(&LeaderboardRow, &LeaderboardRow)> {
    let rows: Vec<&LeaderboardRow> = leaderboard
        .rows
        .iter()
        .filter(|r| !r.seeds.is_empty() && replayed(&r.experiment).is_some())
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
    let Some((best, worst)) = best_and_worst(leaderboard) else {
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
