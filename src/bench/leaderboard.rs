//! The leaderboard of a bench: one row per (approximator, rule, set, experiment) with the
//! experiment's headline figures, its paired comparisons of the learned walker against the
//! model over seeds, and the same comparisons against a baseline combination.

use super::{BenchError, Registry};
use crate::control::LearnSet;
use crate::experiments::index_page::ReplayLink;
use crate::experiments::paired::{Paired, Verdict};
use crate::experiments::summary::Summary;
use crate::experiments::sweep::{RunSpec, Runner, SweepGrid, read_current};
use crate::experiments::{Experiment, Headline};
use crate::report::forest::{ForestPanel, ForestRow, forest_plot};
use crate::report::html::HtmlPage;
use crate::report::{ReportError, Shortest, write_file, write_rows};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// File names the leaderboard writes.
pub const LEADERBOARD_FILES: [&str; 5] = [
    "leaderboard.json",
    "leaderboard.md",
    "leaderboard.csv",
    "forest.svg",
    "index.html",
];

/// One paired comparison over seeds (the statistics of [`crate::experiments::paired`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Comparison {
    /// What is compared, with its unit and sign convention.
    pub quantity: String,
    /// Mean of the per-seed values (`null` without any).
    pub mean: f64,
    /// Two-sided 95% Student-t interval of the mean (`null`s with fewer than two seeds).
    pub ci95: [f64; 2],
    /// `"better"`, `"level"` or `"worse"` for the learned walker (or the combination against
    /// the baseline); `null` with fewer than two seeds.
    pub verdict: Option<Verdict>,
    /// The value at which the two sides are equal (0 for differences, 1 for ratios).
    pub null: f64,
    /// Seeds that have the figure.
    pub seeds: usize,
}

impl From<&Paired> for Comparison {
    fn from(p: &Paired) -> Self {
        Comparison {
            quantity: p.quantity.clone(),
            mean: p.mean,
            ci95: [p.ci95.0, p.ci95.1],
            verdict: p.verdict,
            null: p.null,
            seeds: p.values.len(),
        }
    }
}

impl Comparison {
    /// `mean [lo, hi] verdict`, or `-`.
    pub(crate) fn cell(&self) -> String {
        match self.verdict {
            Some(v) => format!(
                "{:.3} [{:.3}, {:.3}] {v}",
                self.mean, self.ci95[0], self.ci95[1]
            ),
            None if self.mean.is_finite() => format!("{:.3} (one seed)", self.mean),
            None => "-".into(),
        }
    }
}

/// One (approximator, rule, set of learned parameters, experiment).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LeaderboardRow {
    /// Approximator name.
    pub approx: String,
    /// Rule name.
    pub rule: String,
    /// The step parameters the runs' learners learned.
    pub learn: LearnSet,
    /// Experiment name.
    pub experiment: String,
    /// The seeds whose runs finished.
    pub seeds: Vec<u64>,
    /// The experiment's headline figures (means over seeds).
    pub headline: Vec<Headline>,
    /// The learned walker against the model, paired by seed.
    pub vs_model: Vec<Comparison>,
    /// This combination's per-seed comparison values minus the baseline's (learning the same
    /// set), paired by seed (empty for the baseline itself).
    pub vs_baseline: Vec<Comparison>,
    /// The robot the runs walked on, in a bench over several robots (its directory name,
    /// [`crate::bench::RobotColumn::id`]); absent in a bench over one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub robot: Option<String>,
}

/// The approximator and rule every combination is compared with.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Combination {
    /// Approximator name.
    pub approx: String,
    /// Rule name.
    pub rule: String,
}

/// The leaderboard of a bench directory.
///
/// Written as `leaderboard.json` (the contract: `"rows"`, each with `"approx"`, `"rule"`,
/// `"learn"` (the learned step parameters, a list of names), `"experiment"`, `"vs_model"` and `"vs_baseline"` lists of `{"quantity", "mean", "ci95",
/// "verdict"}`), `leaderboard.md`, `leaderboard.csv` (one line per comparison or headline
/// figure), `forest.svg` (each combination's first comparison per experiment) and `index.html`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Leaderboard {
    /// The baseline combination.
    pub baseline: Combination,
    /// The protocols' scale (1 = the paper's).
    pub scale: f64,
    /// The seeds selected.
    pub seeds: Vec<u64>,
    /// One row per (approximator, rule, set, experiment) in selection order.
    pub rows: Vec<LeaderboardRow>,
    /// Runs of the selection without a finished summary (by id).
    pub missing: Vec<String>,
}

/// The per-seed value of every comparison of `experiment` on one run (NaN where the run does
/// not have it).
fn per_seed(experiment: &dyn Experiment, run: &Summary) -> Vec<(Paired, f64)> {
    experiment
        .versus_model(&[run])
        .into_iter()
        .map(|p| {
            let v = p.values.first().copied().unwrap_or(f64::NAN);
            (p, v)
        })
        .collect()
}

/// Paired differences of `runs`' comparison values minus `base`'s, seed by seed.
fn versus_baseline(
    experiment: &dyn Experiment,
    runs: &[Summary],
    base: &[Summary],
) -> Vec<Comparison> {
    let mut diffs: Vec<(Paired, Vec<f64>)> = Vec::new();
    for run in runs {
        let Some(b) = base.iter().find(|b| b.seed == run.seed) else {
            continue;
        };
        let (mine, theirs) = (per_seed(experiment, run), per_seed(experiment, b));
        for (k, ((p, v), (_, w))) in mine.into_iter().zip(theirs).enumerate() {
            if diffs.len() <= k {
                diffs.push((p, Vec::new()));
            }
            diffs[k].1.push(v - w);
        }
    }
    diffs
        .iter()
        .map(|(p, d)| {
            let q = format!("{}: this - baseline", p.quantity);
            Comparison::from(&Paired::new(&q, d, 0.0, p.direction))
        })
        .collect()
}

/// A row of `leaderboard.csv`.
#[derive(Debug, Clone, Default, Serialize)]
struct CsvRow<'a> {
    approx: &'a str,
    rule: &'a str,
    experiment: &'a str,
    against: &'a str,
    quantity: &'a str,
    mean: Shortest,
    ci95_lo: Shortest,
    ci95_hi: Shortest,
    verdict: &'a str,
    seeds: usize,
    /// The set of learned parameters, last so that the columns before it stay where they were.
    learn: String,
}

impl Leaderboard {
    /// Reads the finished runs of `grid` under `out` and builds the leaderboard: a row per
    /// experiment, approximator, rule and set of [`SweepGrid::learn`] (the paper's set when
    /// it is empty). A summary that cannot be read is an error naming it.
    pub fn collect(
        registry: &Registry,
        grid: &SweepGrid,
        out: &Path,
        baseline: &(String, String),
        scale: f64,
        runner: &dyn Runner,
    ) -> Result<Self, BenchError> {
        let mut rows = Vec::new();
        let mut missing = Vec::new();
        let sets = if grid.learn.is_empty() {
            vec![LearnSet::default()]
        } else {
            grid.learn.clone()
        };
        let read = |experiment: &str,
                    approx: &str,
                    rule: &str,
                    learn: LearnSet,
                    missing: &mut Vec<String>| {
            let mut runs = Vec::new();
            for &seed in &grid.seeds {
                let spec = RunSpec {
                    experiment: experiment.to_string(),
                    approx: approx.to_string(),
                    rule: rule.to_string(),
                    seed,
                    learn: Some(learn),
                };
                match read_current(runner, &spec, out)? {
                    Some(summary) => runs.push(summary),
                    None => missing.push(spec.id()),
                }
            }
            Ok::<_, ReportError>(runs)
        };
        for name in &grid.experiments {
            let experiment = registry.find_experiment(name)?;
            let bases = sets
                .iter()
                .map(|&set| read(name, &baseline.0, &baseline.1, set, &mut Vec::new()))
                .collect::<Result<Vec<_>, _>>()?;
            for approx in &grid.approx {
                for rule in &grid.rules {
                    for (&learn, base) in sets.iter().zip(&bases) {
                        let runs = read(name, approx, rule, learn, &mut missing)?;
                        let refs: Vec<&Summary> = runs.iter().collect();
                        let is_base = (approx, rule) == (&baseline.0, &baseline.1);
                        rows.push(LeaderboardRow {
                            approx: approx.clone(),
                            rule: rule.clone(),
                            learn,
                            experiment: name.clone(),
                            seeds: runs.iter().map(|s| s.seed).collect(),
                            headline: experiment.headline(&refs),
                            vs_model: experiment
                                .versus_model(&refs)
                                .iter()
                                .map(Comparison::from)
                                .collect(),
                            vs_baseline: if is_base {
                                Vec::new()
                            } else {
                                versus_baseline(experiment, &runs, base)
                            },
                            robot: None,
                        });
                    }
                }
            }
        }
        Ok(Leaderboard {
            baseline: Combination {
                approx: baseline.0.clone(),
                rule: baseline.1.clone(),
            },
            scale,
            seeds: grid.seeds.clone(),
            rows,
            missing,
        })
    }

    /// The rows of one experiment, in order.
    pub fn experiment_rows(&self, experiment: &str) -> Vec<&LeaderboardRow> {
        self.rows
            .iter()
            .filter(|r| r.experiment == experiment)
            .collect()
    }

    pub(crate) fn experiments(&self) -> Vec<&str> {
        let mut names: Vec<&str> = Vec::new();
        for r in &self.rows {
            if !names.contains(&r.experiment.as_str()) {
                names.push(&r.experiment);
            }
        }
        names
    }

    /// The leaderboard in Markdown: per experiment, one line per combination with its headline
    /// figures, its verdict counts against the model, and its first comparison against the
    /// model and against the baseline.
    pub fn to_markdown(&self) -> String {
        let mut md = format!(
            "# Leaderboard\n\nSeeds {}, protocols at scale {}; baseline **{} + {}**. Each \
             comparison is paired by seed: the mean of the per-seed values and its 95% \
             Student-t interval; better / level / worse is the learned walker's standing (level: \
             no difference beyond the seed-to-seed noise).\n\n",
            describe_seeds(&self.seeds),
            self.scale,
            self.baseline.approx,
            self.baseline.rule
        );
        for name in self.experiments() {
            let rows = self.experiment_rows(name);
            md.push_str(&format!("## {name}\n\n"));
            let heads: Vec<String> = rows
                .first()
                .map(|r| r.headline.iter().map(|h| h.name.clone()).collect())
                .unwrap_or_default();
            let first = |f: fn(&LeaderboardRow) -> &Vec<Comparison>| {
                rows.iter()
                    .find_map(|r| f(r).first().map(|c| c.quantity.clone()))
                    .unwrap_or_else(|| "-".into())
            };
            md.push_str(&format!(
                "First comparison against the model: {}.\n\n",
                first(|r| &r.vs_model)
            ));
            md.push_str("| approx | rule | learn | seeds |");
            for h in &heads {
                md.push_str(&format!(" {h} |"));
            }
            md.push_str(
                " vs model: better / level / worse | first vs model | first vs baseline |\n|",
            );
            md.push_str(&"---|".repeat(heads.len() + 7));
            md.push('\n');
            for r in rows {
                let count = |v: Verdict| r.vs_model.iter().filter(|c| c.verdict == Some(v)).count();
                md.push_str(&format!(
                    "| {} | {} | {} | {} |",
                    r.approx,
                    r.rule,
                    r.learn,
                    r.seeds.len()
                ));
                for h in &r.headline {
                    md.push_str(&format!(" {} |", number(h.mean)));
                }
                md.push_str(&format!(
                    " {} / {} / {} | {} | {} |\n",
                    count(Verdict::Better),
                    count(Verdict::Level),
                    count(Verdict::Worse),
                    r.vs_model.first().map_or("-".into(), Comparison::cell),
                    r.vs_baseline
                        .first()
                        .map_or("(baseline)".into(), Comparison::cell),
                ));
            }
            md.push('\n');
        }
        if !self.missing.is_empty() {
            md.push_str(&format!(
                "{} runs of the selection have not finished (not in the table).\n",
                self.missing.len()
            ));
        }
        md
    }

    fn csv_rows(&self) -> Vec<CsvRow<'_>> {
        let mut out = Vec::new();
        for r in &self.rows {
            let base = CsvRow {
                approx: &r.approx,
                rule: &r.rule,
                learn: r.learn.to_string(),
                experiment: &r.experiment,
                ..CsvRow::default()
            };
            for h in &r.headline {
                out.push(CsvRow {
                    against: "headline",
                    quantity: &h.name,
                    mean: Shortest(h.mean),
                    ci95_lo: Shortest(f64::NAN),
                    ci95_hi: Shortest(f64::NAN),
                    seeds: r.seeds.len(),
                    ..base.clone()
                });
            }
            for (against, list) in [("model", &r.vs_model), ("baseline", &r.vs_baseline)] {
                for c in list {
                    out.push(CsvRow {
                        against,
                        quantity: &c.quantity,
                        mean: Shortest(c.mean),
                        ci95_lo: Shortest(c.ci95[0]),
                        ci95_hi: Shortest(c.ci95[1]),
                        verdict: match c.verdict {
                            Some(Verdict::Better) => "better",
                            Some(Verdict::Level) => "level",
                            Some(Verdict::Worse) => "worse",
                            None => "",
                        },
                        seeds: c.seeds,
                        ..base.clone()
                    });
                }
            }
        }
        out
    }

    /// The forest plot's panels: per experiment, each combination's first comparison against
    /// the model.
    fn forest_panels(&self) -> Vec<ForestPanel> {
        self.experiments()
            .into_iter()
            .filter_map(|name| {
                let rows = self.experiment_rows(name);
                let first = rows.iter().find_map(|r| r.vs_model.first())?;
                let (quantity, null) = (first.quantity.clone(), first.null);
                Some(ForestPanel {
                    title: format!("{name}: learned against the model (95% interval over seeds)"),
                    x_label: quantity,
                    null,
                    rows: rows
                        .iter()
                        .map(|r| {
                            let c = r.vs_model.first();
                            ForestRow {
                                label: if r.learn.is_paper() {
                                    format!("{} + {}", r.approx, r.rule)
                                } else {
                                    format!("{} + {} [{}]", r.approx, r.rule, r.learn)
                                },
                                mean: c.map_or(f64::NAN, |c| c.mean),
                                lo: c.map_or(f64::NAN, |c| c.ci95[0]),
                                hi: c.map_or(f64::NAN, |c| c.ci95[1]),
                            }
                        })
                        .collect(),
                })
            })
            .collect()
    }

    /// Writes the leaderboard files ([`LEADERBOARD_FILES`]) into `dir`, `index.html` with the
    /// `command` and `config` (TOML) that produced it.
    pub fn write(&self, dir: &Path, command: &str, config: &str) -> Result<(), BenchError> {
        self.write_with_replays(dir, command, config, &[])
    }

    /// [`Leaderboard::write`], with `index.html` linking each of `replays` (pages beside it,
    /// written by the caller) after the forest plot.
    pub fn write_with_replays(
        &self,
        dir: &Path,
        command: &str,
        config: &str,
        replays: &[ReplayLink],
    ) -> Result<(), BenchError> {
        let json =
            serde_json::to_string_pretty(self).map_err(|e| ReportError::invalid(e.to_string()))?;
        write_file(&dir.join(LEADERBOARD_FILES[0]), json.as_bytes())?;
        let md = self.to_markdown();
        write_file(&dir.join(LEADERBOARD_FILES[1]), md.as_bytes())?;
        write_rows(&dir.join(LEADERBOARD_FILES[2]), &self.csv_rows())?;
        let panels = self.forest_panels();
        let mut page = HtmlPage::new("steplearn bench: the leaderboard");
        page.markdown(&md);
        if !panels.is_empty() {
            let path = dir.join(LEADERBOARD_FILES[3]);
            forest_plot(&path, &panels)?;
            let svg = std::fs::read_to_string(&path).map_err(|e| ReportError::io(&path, e))?;
            page.figure(
                &svg,
                "Each combination's first comparison with the model per experiment: the mean \
                 over seeds (dot) and its 95% interval (bar); the grey line is no difference.",
            );
        }
        if !replays.is_empty() {
            page.heading(2, "Replays");
        }
        for r in replays {
            page.link(&r.file, &format!("Replay in 3D: {}", r.caption));
        }
        page.heading(2, "How this page was made");
        page.code(command);
        page.paragraph("The configuration (`steplearn config` format):");
        page.code(config);
        page.write(&dir.join(LEADERBOARD_FILES[4]))?;
        Ok(())
    }
}

fn number(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.3}")
    } else {
        "-".into()
    }
}

pub(crate) fn describe_seeds(seeds: &[u64]) -> String {
    match (seeds.first(), seeds.last()) {
        (Some(a), Some(b)) if seeds.len() > 1 => format!("{a}-{b}"),
        (Some(a), _) => a.to_string(),
        _ => "none".into(),
    }
}
