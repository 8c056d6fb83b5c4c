//! The paper's ablation table (`steplearn merge`): every run of a sweep directory read back,
//! one row per approximator x rule with experiments C and D over its seeds and the run times.

use crate::experiments::records::sweep::{RECORD_FILE, RunInfo, SUMMARY_FILE, Stat, SweepError};
use crate::experiments::robustness::{self, RobustnessSummary};
use crate::experiments::stability::{self, StabilitySummary};
use crate::experiments::summary::{Summary, TypedResult};
use crate::report::{ReportError, Shortest, write_file, write_rows};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The experiments of the ablation sweep (`steplearn sweep`): C and D.
pub const EXPERIMENTS: [&str; 2] = [stability::NAME, robustness::NAME];

/// The experiment whose push count `steplearn sweep --pushes` sets: C.
pub const PUSHED: &str = stability::NAME;

/// The files [`Merged::write`] writes: the table in Markdown and in CSV.
pub const TABLE_FILES: [&str; 2] = ["ablation.md", "ablation.csv"];

/// A file [`merge`] could not use.
#[derive(Debug, Clone, PartialEq)]
pub struct MergeProblem {
    /// The file.
    pub path: PathBuf,
    /// Why.
    pub message: String,
}

impl std::fmt::Display for MergeProblem {
    /// `path: message`, without repeating a path the message already starts with.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let path = self.path.display().to_string();
        if self.message.starts_with(&path) {
            f.write_str(&self.message)
        } else {
            write!(f, "{path}: {}", self.message)
        }
    }
}

/// A row of `ablation.csv` ([`Merged::csv_rows`]): the field names are the column names.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct AblationCsvRow<'a> {
    /// Approximator.
    pub approx: &'a str,
    /// Rule.
    pub rule: &'a str,
    /// Seeds with a stability summary.
    pub stability_seeds: usize,
    /// I50 of the open-loop walker (Ns), mean over seeds.
    pub i50_open_loop_ns_mean: Shortest,
    /// Its sample std.
    pub i50_open_loop_ns_std: Shortest,
    /// I50 of the model (Ns), mean over seeds.
    pub i50_model_ns_mean: Shortest,
    /// Its sample std.
    pub i50_model_ns_std: Shortest,
    /// I50 of the learned walker (Ns), mean over seeds.
    pub i50_learned_ns_mean: Shortest,
    /// Its sample std.
    pub i50_learned_ns_std: Shortest,
    /// Falls of the learned walker in C, over seeds.
    pub learned_falls: u64,
    /// Pushes it received in C, over seeds.
    pub learned_pushes: u64,
    /// Seeds with a robustness summary.
    pub robustness_seeds: usize,
    /// Seeds on which D absorbed a push within its first three.
    pub absorbed_within_3_pushes: usize,
    /// Pushes until the first absorbed one in D, mean over seeds.
    pub pushes_until_absorbed_mean: Shortest,
    /// Its sample std.
    pub pushes_until_absorbed_std: Shortest,
    /// Falls in D, mean over seeds.
    pub robustness_falls_mean: Shortest,
    /// Its sample std.
    pub robustness_falls_std: Shortest,
    /// Pushes absorbed in D with learning, over seeds.
    pub absorbed_learned: u64,
    /// The same without learning.
    pub absorbed_no_learning: u64,
    /// Runs with a recorded run time.
    pub runs_timed: usize,
    /// Run time (s), mean over runs.
    pub run_time_s_mean: Shortest,
    /// Its sample std.
    pub run_time_s_std: Shortest,
}

/// One row of the ablation table: an approximator x rule pair over its seeds.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct AblationRow {
    /// Approximator.
    pub approx: String,
    /// Rule name.
    pub rule: String,
    /// Experiment C: impulse at 50% falls (Ns) over seeds, open-loop.
    pub i50_open_loop: Stat,
    /// Same, Capture Step model.
    pub i50_model: Stat,
    /// Same, learned.
    pub i50_learned: Stat,
    /// Experiment C, learned controller: falls and pushes summed over seeds.
    pub learned_falls_pushes: (u64, u64),
    /// Experiment D: number of seeds.
    pub robustness_seeds: usize,
    /// Experiment D: seeds whose first absorbed push was among the first three.
    pub absorbed_within_3: usize,
    /// Experiment D: pushes until the first absorbed one, over the seeds where one was.
    pub pushes_until_absorbed: Stat,
    /// Experiment D: falls per run.
    pub robustness_falls: Stat,
    /// Experiment D: pushes absorbed by the learner and by the same walker without learning,
    /// summed over the seeds that ran both.
    pub absorbed_vs_no_learning: (u64, u64),
    /// Wall time per run (s) over every finished run of this pair with a `run.json`.
    pub run_time_s: Stat,
}

/// The merged results of a sweep directory.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Merged {
    /// One row per approximator x rule, sorted by approximator then rule.
    pub rows: Vec<AblationRow>,
    /// Summaries read.
    pub runs_read: usize,
    /// Run directories without a `summary.json` (unfinished runs).
    pub unfinished: Vec<PathBuf>,
    /// Files that could not be read; they are left out of the table.
    pub problems: Vec<MergeProblem>,
}

impl Merged {
    /// The ablation table in Markdown (mean ± std over seeds).
    pub fn to_markdown(&self) -> String {
        let mut s = String::from(
            "| approx | rule | C: I50 open-loop (Ns) | C: I50 model (Ns) | C: I50 learned (Ns) \
             | C: learned falls / pushes | D: absorbed within 3 pushes | D: pushes to first \
             absorbed | D: falls | D: absorbed, learned / no learning | run time (s) |\n\
             |---|---|---|---|---|---|---|---|---|---|---|\n",
        );
        for r in &self.rows {
            let (falls, pushes) = r.learned_falls_pushes;
            let fp = if r.i50_learned.n > 0 {
                format!("{falls} / {pushes}")
            } else {
                "-".into()
            };
            let absorbed = if r.robustness_seeds > 0 {
                format!("{} / {}", r.absorbed_within_3, r.robustness_seeds)
            } else {
                "-".into()
            };
            let (al, an) = r.absorbed_vs_no_learning;
            s.push_str(&format!(
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {al} / {an} | {} |\n",
                r.approx,
                r.rule,
                r.i50_open_loop.markdown(),
                r.i50_model.markdown(),
                r.i50_learned.markdown(),
                fp,
                absorbed,
                r.pushes_until_absorbed.markdown(),
                r.robustness_falls.markdown(),
                r.run_time_s.markdown(),
            ));
        }
        s
    }

    /// The ablation table as CSV rows (the file [`Merged::write`] writes); empty cells for
    /// statistics over no data.
    pub fn csv_rows(&self) -> Vec<AblationCsvRow<'_>> {
        self.rows
            .iter()
            .map(|r| AblationCsvRow {
                approx: &r.approx,
                rule: &r.rule,
                stability_seeds: r.i50_learned.n,
                i50_open_loop_ns_mean: Shortest(r.i50_open_loop.mean),
                i50_open_loop_ns_std: Shortest(r.i50_open_loop.std),
                i50_model_ns_mean: Shortest(r.i50_model.mean),
                i50_model_ns_std: Shortest(r.i50_model.std),
                i50_learned_ns_mean: Shortest(r.i50_learned.mean),
                i50_learned_ns_std: Shortest(r.i50_learned.std),
                learned_falls: r.learned_falls_pushes.0,
                learned_pushes: r.learned_falls_pushes.1,
                robustness_seeds: r.robustness_seeds,
                absorbed_within_3_pushes: r.absorbed_within_3,
                pushes_until_absorbed_mean: Shortest(r.pushes_until_absorbed.mean),
                pushes_until_absorbed_std: Shortest(r.pushes_until_absorbed.std),
                robustness_falls_mean: Shortest(r.robustness_falls.mean),
                robustness_falls_std: Shortest(r.robustness_falls.std),
                absorbed_learned: r.absorbed_vs_no_learning.0,
                absorbed_no_learning: r.absorbed_vs_no_learning.1,
                runs_timed: r.run_time_s.n,
                run_time_s_mean: Shortest(r.run_time_s.mean),
                run_time_s_std: Shortest(r.run_time_s.std),
            })
            .collect()
    }

    /// Writes `ablation.md` and `ablation.csv` into `dir` (atomically).
    pub fn write(&self, dir: &Path) -> Result<(), SweepError> {
        write_file(&dir.join(TABLE_FILES[0]), self.to_markdown().as_bytes())?;
        write_rows(&dir.join(TABLE_FILES[1]), &self.csv_rows())?;
        Ok(())
    }
}

/// A summary's typed result where the table reads one.
enum Typed {
    Stability(StabilitySummary),
    Robustness(RobustnessSummary),
    Other,
}

#[derive(Default)]
struct Collected {
    i50: [Vec<f64>; 3],
    learned_falls_pushes: (u64, u64),
    robustness_seeds: usize,
    absorbed_within_3: usize,
    pushes_until_absorbed: Vec<f64>,
    robustness_falls: Vec<f64>,
    absorbed_vs_no_learning: (u64, u64),
    run_time_s: Vec<f64>,
}

/// The sort key of a rule in the ablation table: the built-in rules in their declared order,
/// then any other by name.
fn rule_order(rule: &str) -> (usize, String) {
    use strum::VariantArray;
    let rank = crate::rules::RuleKind::VARIANTS
        .iter()
        .position(|k| <&str>::from(*k) == rule)
        .unwrap_or(usize::MAX);
    (rank, rule.to_string())
}

/// Reads every run's `summary.json` (and `run.json`) under `dir` and builds the ablation table
/// of experiments C and D with run times. Malformed files are listed in
/// [`Merged::problems`] with their path and skipped; tracking and disturbance runs count in
/// `runs_read` and run time only. Errors only if `dir` itself cannot be read.
pub fn merge(dir: &Path) -> Result<Merged, SweepError> {
    let entries = std::fs::read_dir(dir).map_err(|e| ReportError::io(dir, e))?;
    let mut run_dirs: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_dir())
        .collect();
    run_dirs.sort();
    let mut merged = Merged::default();
    // Rows by approximator, then the built-in rules in their order, then other rules by name.
    let mut groups: BTreeMap<(String, (usize, String)), Collected> = BTreeMap::new();
    for run_dir in run_dirs {
        let summary_path = run_dir.join(SUMMARY_FILE);
        if !summary_path.exists() {
            merged.unfinished.push(run_dir);
            continue;
        }
        let summary = match Summary::read(&summary_path) {
            Ok(s) => s,
            Err(e) => {
                merged.problems.push(MergeProblem {
                    path: summary_path,
                    message: e.to_string(),
                });
                continue;
            }
        };
        merged.runs_read += 1;
        let group = groups
            .entry((summary.approx.clone(), rule_order(&summary.rule)))
            .or_default();
        let record_path = run_dir.join(RECORD_FILE);
        if record_path.exists() {
            let record = std::fs::read_to_string(&record_path)
                .map_err(|e| e.to_string())
                .and_then(|t| serde_json::from_str::<RunInfo>(&t).map_err(|e| e.to_string()));
            match record {
                Ok(r) if r.wall_time_s.is_finite() && r.wall_time_s >= 0.0 => {
                    group.run_time_s.push(r.wall_time_s)
                }
                Ok(r) => merged.problems.push(MergeProblem {
                    path: record_path,
                    message: format!("wall_time_s {} is not a duration", r.wall_time_s),
                }),
                Err(message) => merged.problems.push(MergeProblem {
                    path: record_path,
                    message,
                }),
            }
        }
        let typed = if summary.experiment() == StabilitySummary::EXPERIMENT {
            StabilitySummary::from_result(&summary.result).map(Typed::Stability)
        } else if summary.experiment() == RobustnessSummary::EXPERIMENT {
            RobustnessSummary::from_result(&summary.result).map(Typed::Robustness)
        } else {
            Ok(Typed::Other)
        };
        match typed {
            Err(e) => merged.problems.push(MergeProblem {
                path: summary_path,
                message: e.to_string(),
            }),
            Ok(Typed::Stability(StabilitySummary { controllers, .. })) => {
                for (i, c) in [
                    controllers.open_loop,
                    controllers.model,
                    controllers.learned,
                ]
                .iter()
                .enumerate()
                {
                    group.i50[i].push(c.impulse_at_50pct_fall_ns);
                }
                group.learned_falls_pushes.0 += u64::from(controllers.learned.falls);
                group.learned_falls_pushes.1 += u64::from(controllers.learned.pushes);
            }
            Ok(Typed::Robustness(RobustnessSummary {
                pushes_until_first_absorbed,
                falls,
                absorbed_by_push,
                no_learning,
                ..
            })) => {
                if let Some(b) = no_learning {
                    let count = |v: &[bool]| v.iter().filter(|&&a| a).count() as u64;
                    group.absorbed_vs_no_learning.0 += count(&absorbed_by_push);
                    group.absorbed_vs_no_learning.1 += count(&b.absorbed_by_push);
                }
                group.robustness_seeds += 1;
                group.robustness_falls.push(f64::from(falls));
                if let Some(n) = pushes_until_first_absorbed {
                    group.pushes_until_absorbed.push(f64::from(n));
                    group.absorbed_within_3 += usize::from(n <= 3);
                }
            }
            Ok(Typed::Other) => {}
        }
    }
    merged.rows = groups
        .into_iter()
        .map(|((approx, (_, rule)), c)| AblationRow {
            approx,
            rule,
            i50_open_loop: Stat::of(&c.i50[0]),
            i50_model: Stat::of(&c.i50[1]),
            i50_learned: Stat::of(&c.i50[2]),
            learned_falls_pushes: c.learned_falls_pushes,
            robustness_seeds: c.robustness_seeds,
            absorbed_within_3: c.absorbed_within_3,
            pushes_until_absorbed: Stat::of(&c.pushes_until_absorbed),
            robustness_falls: Stat::of(&c.robustness_falls),
            absorbed_vs_no_learning: c.absorbed_vs_no_learning,
            run_time_s: Stat::of(&c.run_time_s),
        })
        .collect();
    Ok(merged)
}
