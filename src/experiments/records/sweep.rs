//! The ablation sweep: every approximator x rule x experiment x seed as independent runs with
//! stable ids, run in parallel (rayon), sharded for clusters, resumable, and merged into a table.
//!
//! Layout of a sweep directory: one sub-directory per run, named by [`RunSpec::id`], holding
//! whatever the runner writes (CSV, SVG) plus `run.json` ([`RunInfo`]: the spec and the wall
//! time) and, written last and atomically, `summary.json`. A run whose `summary.json` exists
//! and parses is finished: a later sweep over the same directory skips it, so an interrupted
//! sweep resumes where it stopped, and shards of one grid can share a directory.
//!
//! Results do not depend on the number of threads: each run sees only its spec (the seed
//! included) and writes only its own directory.
//!
//! On a cluster, run shard `I` of `N` as one task (`--shard I/N`, 0-based, e.g. a Slurm array
//! `--array=0-(N-1)` with `--shard $SLURM_ARRAY_TASK_ID/N`) and call `steplearn merge` ([`crate::experiments::ablation::merge`]) when all are done.

use crate::config::limits::MAX_SEEDS;
use crate::control::LearnSet;
use crate::experiments::summary::{Summary, check_name};
use crate::report::{ReportError, write_file};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;
use std::time::Instant;
use thiserror::Error;

/// Name of the result file of a run (its presence marks the run as finished).
pub const SUMMARY_FILE: &str = "summary.json";
/// Name of the bookkeeping file of a run.
pub const RECORD_FILE: &str = "run.json";
/// A finished run's identity ([`Runner::identity`]): everything that determines its results.
/// A finished run is reused only when this file is the same, byte for byte.
pub const IDENTITY_FILE: &str = "run-config.toml";

/// What can go wrong when setting up, running or merging a sweep (failures of single runs are
/// reported per run in [`RunStatus::Failed`], not here).
#[derive(Debug, Error)]
pub enum SweepError {
    /// A `--shard` argument is malformed or out of range.
    #[error("invalid shard {given:?}: {reason} (expected I/N with 0 <= I < N, e.g. 3/10)")]
    InvalidShard {
        /// The argument.
        given: String,
        /// What is wrong.
        reason: String,
    },
    /// The grid is empty or holds a bad name.
    #[error("invalid sweep grid: {0}")]
    InvalidGrid(String),
    /// The thread pool could not be built.
    #[error("thread pool: {0}")]
    ThreadPool(String),
    /// Creating or reading the sweep directory failed, or writing the table failed.
    #[error(transparent)]
    Report(#[from] ReportError),
}

/// One run: which experiment, approximator, rule, seed and (optionally) set of learned step
/// parameters.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunSpec {
    /// Experiment name (lowercase letters, digits and `-`).
    pub experiment: String,
    /// Approximator name (lowercase letters, digits and `-`).
    pub approx: String,
    /// Learning rule name (lowercase letters, digits and `-`).
    pub rule: String,
    /// The seed.
    pub seed: u64,
    /// The step parameters the run's learners learn; `None`: whatever the runner's settings
    /// say (`settings.learner.learn`). The bench always gives one ([`SweepGrid::learn`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub learn: Option<LearnSet>,
}

impl PartialOrd for RunSpec {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for RunSpec {
    /// By experiment, approximator, rule, seed, then set (no set first; sets by their names).
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        (&self.experiment, &self.approx, &self.rule, self.seed)
            .cmp(&(&other.experiment, &other.approx, &other.rule, other.seed))
            .then_with(|| {
                self.learn
                    .map(|s| s.names())
                    .cmp(&other.learn.map(|s| s.names()))
            })
    }
}

impl RunSpec {
    /// The stable id, also the run's directory name: `experiment__approx__rule__sSEED`, e.g.
    /// `stability__lwpr__pendulum-cart__s3`, for the paper's set (`step-x`) or none given;
    /// any other set adds its names joined by `+`:
    /// `stability__lwpr__pendulum-cart__s3__step-x+step-time`.
    pub fn id(&self) -> String {
        let mut id = format!(
            "{}__{}__{}__s{}",
            self.experiment, self.approx, self.rule, self.seed
        );
        if let Some(set) = self.learn.filter(|s| !s.is_paper()) {
            id.push_str("__");
            id.push_str(&set.names().join("+"));
        }
        id
    }

    /// Whether `summary` is the result of this run.
    fn matches(&self, summary: &Summary) -> bool {
        summary.experiment() == self.experiment
            && summary.approx == self.approx
            && summary.rule == self.rule
            && summary.seed == self.seed
            && self.learn.is_none_or(|set| summary.learn == set)
    }
}

/// Checks that no set of learned step parameters is given twice; the error names the set.
pub(crate) fn check_distinct_sets(sets: &[LearnSet]) -> Result<(), String> {
    match sets
        .iter()
        .enumerate()
        .find(|(i, set)| sets[..*i].contains(set))
    {
        Some((_, set)) => Err(format!("learned set {set} selected twice")),
        None => Ok(()),
    }
}

/// The grid of runs: the product of its lists.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepGrid {
    /// Experiment names.
    pub experiments: Vec<String>,
    /// Approximator names.
    pub approx: Vec<String>,
    /// Rule names.
    pub rules: Vec<String>,
    /// Seeds.
    pub seeds: Vec<u64>,
    /// Sets of learned step parameters, each a dimension of the grid like the approximators;
    /// empty (the default): one run per combination with the runner's settings' set
    /// ([`RunSpec::learn`] `None`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub learn: Vec<LearnSet>,
}

impl SweepGrid {
    /// The product of the given names with seeds `0..n_seeds` (more than
    /// [`crate::config::limits::MAX_SEEDS`] seeds: [`SweepGrid::runs`] refuses the grid).
    pub fn new(experiments: &[&str], approx: &[&str], rules: &[&str], n_seeds: u64) -> Self {
        let owned = |v: &[&str]| v.iter().map(|s| s.to_string()).collect();
        SweepGrid {
            experiments: owned(experiments),
            approx: owned(approx),
            rules: owned(rules),
            seeds: (0..n_seeds.min(MAX_SEEDS + 1)).collect(),
            learn: Vec::new(),
        }
    }

    /// The sets of the grid's runs: [`SweepGrid::learn`], or `[None]` when it is empty.
    pub fn learn_sets(&self) -> Vec<Option<LearnSet>> {
        if self.learn.is_empty() {
            vec![None]
        } else {
            self.learn.iter().copied().map(Some).collect()
        }
    }

    /// Every run, in a fixed order (experiment, approximator, rule, set, seed; each list in the
    /// order given). Errors on an empty list, a bad approximator name or duplicates.
    pub fn runs(&self) -> Result<Vec<RunSpec>, SweepError> {
        for (what, len) in [
            ("experiments", self.experiments.len()),
            ("approx", self.approx.len()),
            ("rules", self.rules.len()),
            ("seeds", self.seeds.len()),
        ] {
            if len == 0 {
                return Err(SweepError::InvalidGrid(format!("{what} is empty")));
            }
        }
        if self.seeds.len() as u64 > MAX_SEEDS {
            return Err(SweepError::InvalidGrid(format!(
                "more than {MAX_SEEDS} seeds"
            )));
        }
        for (what, names) in [
            ("experiment", &self.experiments),
            ("approximator", &self.approx),
            ("rule", &self.rules),
        ] {
            for n in names {
                check_name(what, n).map_err(SweepError::InvalidGrid)?;
            }
        }
        check_distinct_sets(&self.learn).map_err(SweepError::InvalidGrid)?;
        let sets = self.learn_sets();
        let mut runs = Vec::new();
        for experiment in &self.experiments {
            for approx in &self.approx {
                for rule in &self.rules {
                    for &learn in &sets {
                        for &seed in &self.seeds {
                            runs.push(RunSpec {
                                experiment: experiment.clone(),
                                approx: approx.clone(),
                                rule: rule.clone(),
                                seed,
                                learn,
                            });
                        }
                    }
                }
            }
        }
        let mut ids: Vec<String> = runs.iter().map(RunSpec::id).collect();
        ids.sort();
        if let Some(w) = ids.windows(2).find(|w| w[0] == w[1]) {
            return Err(SweepError::InvalidGrid(format!("duplicate run {}", w[0])));
        }
        Ok(runs)
    }
}

/// Shard `index` of `count` (0-based): the runs at positions `index, index + count, ...` of
/// the grid's order. Parsed from `"I/N"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard, 0-based.
    pub index: usize,
    /// Number of shards (>= 1).
    pub count: usize,
}

impl Shard {
    /// The whole grid as one shard.
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// Checks `index < count` and `count >= 1`.
    pub fn new(index: usize, count: usize) -> Result<Self, SweepError> {
        let given = format!("{index}/{count}");
        if count == 0 {
            return Err(SweepError::InvalidShard {
                given,
                reason: "the number of shards must be at least 1".into(),
            });
        }
        if index >= count {
            return Err(SweepError::InvalidShard {
                given,
                reason: format!("shard index must be below {count} (shards are 0-based)"),
            });
        }
        Ok(Shard { index, count })
    }

    /// The runs of this shard, in grid order.
    pub fn select(&self, runs: &[RunSpec]) -> Vec<RunSpec> {
        runs.iter()
            .enumerate()
            .filter(|(i, _)| i % self.count == self.index)
            .map(|(_, r)| r.clone())
            .collect()
    }
}

impl std::str::FromStr for Shard {
    type Err = SweepError;
    fn from_str(s: &str) -> Result<Self, SweepError> {
        let bad = |reason: &str| SweepError::InvalidShard {
            given: s.to_string(),
            reason: reason.to_string(),
        };
        let (i, n) = s.split_once('/').ok_or_else(|| bad("missing '/'"))?;
        let parse = |part: &str| {
            part.trim()
                .parse::<usize>()
                .map_err(|_| bad(&format!("{part:?} is not a non-negative integer")))
        };
        let (index, count) = (parse(i)?, parse(n)?);
        Shard::new(index, count).map_err(|e| match e {
            SweepError::InvalidShard { reason, .. } => bad(&reason),
            other => other,
        })
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// The error a runner reports for one run.
pub type RunError = Box<dyn std::error::Error + Send + Sync>;

/// Executes one run. It may write any files into `dir` (created for it, empty or holding a
/// previous unfinished attempt) and returns the run's [`Summary`]; the sweep writes
/// `summary.json` itself, last. It must depend only on `spec` (seed included), never on
/// timing or thread count. Implemented for closures `Fn(&RunSpec, &Path) -> Result<Summary,
/// RunError>`.
pub trait Runner: Sync {
    /// Runs `spec`, writing extra outputs into `dir`.
    fn run(&self, spec: &RunSpec, dir: &Path) -> Result<Summary, RunError>;

    /// Everything that determines the results of `spec` (the run, the resolved settings and
    /// protocol, the results format), as text: recorded as [`IDENTITY_FILE`] in the run's
    /// directory, and a finished run is reused only if its record is the same. `None` (the
    /// default, and for closures): a finished run is reused whatever produced it.
    fn identity(&self, spec: &RunSpec) -> Result<Option<String>, RunError> {
        let _ = spec;
        Ok(None)
    }

    /// Checks a summary read back from a run's directory beyond what every summary must hold
    /// (its experiment's own fields, [`crate::experiments::Experiment::check_result`]); a
    /// summary that fails is not a finished run. By default (and for closures) every readable
    /// summary passes.
    fn check(&self, summary: &Summary) -> Result<(), ReportError> {
        let _ = summary;
        Ok(())
    }
}

impl<F> Runner for F
where
    F: Fn(&RunSpec, &Path) -> Result<Summary, RunError> + Sync,
{
    fn run(&self, spec: &RunSpec, dir: &Path) -> Result<Summary, RunError> {
        self(spec, dir)
    }
}

/// `run.json`: bookkeeping of a finished run (kept out of `summary.json`, whose fields are
/// fixed by the command-line contract).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunInfo {
    /// [`RunSpec::id`].
    pub id: String,
    /// The spec.
    pub spec: RunSpec,
    /// Wall-clock time of the runner (s).
    pub wall_time_s: f64,
    /// The steplearn version that made the run (empty in records written before it was
    /// recorded). Kept out of the run's identity, so that a new release does not make every
    /// finished run stale; [`IDENTITY_FILE`]'s results format does that when results change.
    #[serde(default)]
    pub steplearn_version: String,
}

/// How one run of a sweep ended.
#[derive(Debug, Clone, PartialEq)]
pub enum RunStatus {
    /// Ran and wrote its summary.
    Done {
        /// Wall-clock time (s).
        wall_time_s: f64,
    },
    /// A valid `summary.json` of the same run (the same identity, where the runner gives one)
    /// was already there.
    Skipped,
    /// The runner failed or panicked, its summary did not match the spec, or an existing
    /// `summary.json` is malformed (left untouched); no summary was written.
    Failed(String),
}

/// One run's spec and status.
#[derive(Debug, Clone, PartialEq)]
pub struct RunOutcome {
    /// The run.
    pub spec: RunSpec,
    /// How it ended.
    pub status: RunStatus,
}

/// Settings of [`run_sweep`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SweepOptions {
    /// Worker threads; `None` uses rayon's global pool.
    pub threads: Option<usize>,
}

fn create_dir(path: &Path) -> Result<(), ReportError> {
    std::fs::create_dir_all(path).map_err(|e| ReportError::io(path, e))
}

fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "non-string panic payload".into())
}

/// Whether the finished run in `dir` is the run of `identity`: `Ok` to reuse it, otherwise
/// why not (naming the first difference and how to proceed).
pub(crate) fn check_identity(dir: &Path, identity: &str) -> Result<(), String> {
    let path = dir.join(IDENTITY_FILE);
    let how = format!(
        "choose another output directory, or delete {} to run it again",
        dir.display()
    );
    match std::fs::read_to_string(&path) {
        Ok(existing) if existing == identity => Ok(()),
        Ok(existing) => {
            let differs = existing
                .lines()
                .zip(identity.lines())
                .find(|(a, b)| a != b)
                .map(|(a, b)| format!("recorded `{a}`, asked `{b}`"))
                .unwrap_or_else(|| "the recorded configuration has other keys".to_string());
            Err(format!(
                "{} holds a finished run of another configuration ({differs}); {how}",
                dir.display()
            ))
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Err(format!(
            "{} holds a finished run without a recorded configuration ({IDENTITY_FILE}), so \
             whether it matches cannot be told; {how}",
            dir.display()
        )),
        Err(e) => Err(format!("cannot read {}: {e}", path.display())),
    }
}

/// Whether `out` holds a finished run of `spec` that `runner` would produce now: a readable
/// summary, and the same identity where the runner records one.
pub fn is_current(runner: &dyn Runner, spec: &RunSpec, out: &Path) -> bool {
    let dir = out.join(spec.id());
    dir.join(SUMMARY_FILE).exists()
        && match runner.identity(spec) {
            Ok(None) => true,
            Ok(Some(identity)) => check_identity(&dir, &identity).is_ok(),
            Err(_) => false,
        }
}

/// The summary of the finished run of `spec` under `out` if it is current
/// ([`is_current`]), read and checked by `runner` ([`Runner::check`]); `None` if it is not
/// current; an error if it cannot be read or fails the check.
pub fn read_current(
    runner: &dyn Runner,
    spec: &RunSpec,
    out: &Path,
) -> Result<Option<Summary>, ReportError> {
    if !is_current(runner, spec, out) {
        return Ok(None);
    }
    read_checked(runner, &out.join(spec.id()).join(SUMMARY_FILE)).map(Some)
}

/// The summary at `path`, read and checked by `runner` ([`Runner::check`]); a summary the
/// runner refuses is a [`ReportError::Parse`] naming the file.
fn read_checked(runner: &dyn Runner, path: &Path) -> Result<Summary, ReportError> {
    let summary = Summary::read(path)?;
    runner.check(&summary).map_err(|e| ReportError::Parse {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    Ok(summary)
}

/// The file in a run's directory that a worker holds locked while it computes the run (an
/// advisory lock of the operating system, released when the worker ends or dies), so that
/// workers sharing a directory compute each run once.
pub const CLAIM_FILE: &str = "claim.lock";

/// The status of a run whose `summary.json` exists: reused, or why not.
fn existing(dir: &Path, identity: Option<&str>, runner: &dyn Runner) -> RunStatus {
    if let Err(e) = read_checked(runner, &dir.join(SUMMARY_FILE)) {
        return RunStatus::Failed(format!(
            "existing result is unreadable and was left untouched (delete it to re-run): {e}"
        ));
    }
    match identity.map(|i| check_identity(dir, i)) {
        None | Some(Ok(())) => RunStatus::Skipped,
        Some(Err(why)) => RunStatus::Failed(why),
    }
}

/// Claims the run in `dir`: its claim file locked by this worker. With `wait`, waits while
/// another worker holds it; without, `None` if another does.
fn claim(dir: &Path, wait: bool) -> Result<Option<std::fs::File>, ReportError> {
    let path = dir.join(CLAIM_FILE);
    let io = |e| ReportError::io(&path, e);
    let file = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .map_err(io)?;
    if wait {
        file.lock().map_err(io)?;
        return Ok(Some(file));
    }
    match file.try_lock() {
        Ok(()) => Ok(Some(file)),
        Err(std::fs::TryLockError::WouldBlock) => Ok(None),
        Err(std::fs::TryLockError::Error(e)) => Err(io(e)),
    }
}

/// Runs `spec` unless it is finished or another worker holds it: `None` in that last case
/// (never with `wait`, which waits for the other worker and then takes what it left).
fn run_one(spec: &RunSpec, out: &Path, runner: &dyn Runner, wait: bool) -> Option<RunStatus> {
    let dir = out.join(spec.id());
    let summary_path = dir.join(SUMMARY_FILE);
    let identity = match runner.identity(spec) {
        Ok(identity) => identity,
        Err(e) => return Some(RunStatus::Failed(format!("invalid run: {e}"))),
    };
    if summary_path.exists() {
        return Some(existing(&dir, identity.as_deref(), runner));
    }
    if let Err(e) = create_dir(&dir) {
        return Some(RunStatus::Failed(e.to_string()));
    }
    let _claim = match claim(&dir, wait) {
        Ok(Some(file)) => file,
        Ok(None) => return None,
        Err(e) => return Some(RunStatus::Failed(format!("claiming the run failed: {e}"))),
    };
    // Another worker may have finished it before this one held the claim.
    if summary_path.exists() {
        return Some(existing(&dir, identity.as_deref(), runner));
    }
    Some(compute(spec, &dir, runner, identity))
}

/// Computes a claimed run into `dir` and writes its record, identity and summary.
fn compute(spec: &RunSpec, dir: &Path, runner: &dyn Runner, identity: Option<String>) -> RunStatus {
    let summary_path = dir.join(SUMMARY_FILE);
    let start = Instant::now();
    let result = catch_unwind(AssertUnwindSafe(|| runner.run(spec, dir)));
    let wall_time_s = start.elapsed().as_secs_f64();
    let summary = match result {
        Ok(Ok(summary)) => summary,
        Ok(Err(e)) => return RunStatus::Failed(format!("run failed: {e}")),
        Err(payload) => {
            return RunStatus::Failed(format!("run panicked: {}", panic_message(&*payload)));
        }
    };
    if !spec.matches(&summary) {
        return RunStatus::Failed(format!(
            "runner returned the summary of another run ({} / {} / {} / seed {})",
            summary.experiment(),
            summary.approx,
            summary.rule,
            summary.seed
        ));
    }
    let record = RunInfo {
        id: spec.id(),
        spec: spec.clone(),
        wall_time_s,
        steplearn_version: env!("CARGO_PKG_VERSION").to_string(),
    };
    let written = serde_json::to_string_pretty(&record)
        .map_err(|e| ReportError::invalid(e.to_string()))
        .and_then(|json| write_file(&dir.join(RECORD_FILE), json.as_bytes()))
        .and_then(|()| match &identity {
            Some(i) => write_file(&dir.join(IDENTITY_FILE), i.as_bytes()),
            None => Ok(()),
        })
        .and_then(|()| summary.write(&summary_path));
    match written {
        Ok(()) => RunStatus::Done { wall_time_s },
        Err(e) => RunStatus::Failed(format!("writing the result failed: {e}")),
    }
}

/// Runs `runs` in parallel into `out` (created if needed), skipping finished runs. Returns one
/// outcome per run, in the order of `runs`; `on_finished` is called (from worker threads) as
/// each run ends, e.g. to advance a progress bar. A failing run does not stop the others.
///
/// Any number of processes may share `out`: each run is claimed ([`CLAIM_FILE`]) while it is
/// computed, so it is computed once. A worker first runs what no other holds, then waits for
/// the runs others hold and takes what they left (finished: skipped; not, because the other
/// worker died: computed), so every worker returns with the whole selection finished.
pub fn run_sweep(
    runs: &[RunSpec],
    out: &Path,
    runner: &dyn Runner,
    options: &SweepOptions,
    on_finished: &(dyn Fn(&RunOutcome) + Sync),
) -> Result<Vec<RunOutcome>, SweepError> {
    create_dir(out)?;
    let finish = |spec: &RunSpec, status: RunStatus| {
        let outcome = RunOutcome {
            spec: spec.clone(),
            status,
        };
        on_finished(&outcome);
        outcome
    };
    let work = || -> Vec<RunOutcome> {
        let first: Vec<Option<RunOutcome>> = runs
            .par_iter()
            .map(|spec| run_one(spec, out, runner, false).map(|s| finish(spec, s)))
            .collect();
        runs.par_iter()
            .zip(first)
            .map(|(spec, outcome)| {
                outcome.unwrap_or_else(|| {
                    let status = run_one(spec, out, runner, true).unwrap_or_else(|| {
                        RunStatus::Failed("the run stayed claimed by another worker".into())
                    });
                    finish(spec, status)
                })
            })
            .collect()
    };
    match options.threads {
        None => Ok(work()),
        Some(n) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| SweepError::ThreadPool(e.to_string()))?;
            Ok(pool.install(work))
        }
    }
}

/// Mean, standard deviation (n - 1) and count of some values.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Stat {
    /// Mean (NaN when empty).
    pub mean: f64,
    /// Sample standard deviation (0 for one value, NaN when empty).
    pub std: f64,
    /// Number of values.
    pub n: usize,
}

impl Stat {
    /// Statistics of `values`.
    pub fn of(values: &[f64]) -> Stat {
        let n = values.len();
        if n == 0 {
            return Stat {
                mean: f64::NAN,
                std: f64::NAN,
                n,
            };
        }
        let s = crate::stats::MeanStd::of(values.iter().copied());
        Stat {
            mean: s.mean(),
            std: s.sample_std(),
            n,
        }
    }

    /// `mean ± std` with two decimals, the mean alone for one value, `-` for none.
    pub fn markdown(&self) -> String {
        match self.n {
            0 => "-".into(),
            1 => format!("{:.2}", self.mean),
            _ => format!("{:.2} ± {:.2}", self.mean, self.std),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::Shortest;

    #[test]
    fn shard_parsing_validates() {
        assert_eq!("3/10".parse::<Shard>().unwrap(), Shard::new(3, 10).unwrap());
        assert_eq!(" 0 / 1 ".parse::<Shard>().unwrap(), Shard::ALL);
        for bad in [
            "", "3", "3/0", "0/0", "10/10", "11/10", "-1/3", "a/3", "1/b", "1/2/3", "1.5/3",
        ] {
            let err = bad.parse::<Shard>().unwrap_err();
            assert!(
                matches!(err, SweepError::InvalidShard { .. }),
                "{bad}: {err}"
            );
            assert!(err.to_string().contains("I/N"));
        }
        assert_eq!(Shard::new(2, 5).unwrap().to_string(), "2/5");
    }

    #[test]
    fn shards_partition_the_grid() {
        let runs = SweepGrid::new(&["a", "b", "c", "d"], &["lwpr", "rbf"], &["r1", "r2"], 3)
            .runs()
            .unwrap();
        assert_eq!(runs.len(), 4 * 2 * 2 * 3);
        for n in [1, 2, 7, 200] {
            let mut all: Vec<RunSpec> = (0..n)
                .flat_map(|i| Shard::new(i, n).unwrap().select(&runs))
                .collect();
            all.sort();
            let mut want = runs.clone();
            want.sort();
            assert_eq!(all, want, "{n} shards");
        }
    }

    #[test]
    fn ids_are_stable_and_grids_validated() {
        let spec = RunSpec {
            experiment: "stability".into(),
            approx: "kernel-ridge".into(),
            rule: "rate-damped".into(),
            seed: 42,
            learn: None,
        };
        assert_eq!(spec.id(), "stability__kernel-ridge__rate-damped__s42");
        let paper = RunSpec {
            learn: Some(LearnSet::default()),
            ..spec.clone()
        };
        assert_eq!(paper.id(), spec.id(), "the paper's set keeps today's id");
        let xt = RunSpec {
            learn: Some("step-time,step-x".parse().unwrap()),
            ..spec.clone()
        };
        assert_eq!(
            xt.id(),
            "stability__kernel-ridge__rate-damped__s42__step-x+step-time"
        );
        let mut grid = SweepGrid::new(&["stability"], &["lwpr"], &["pendulum-cart"], 1);
        grid.approx.push("Bad_Name".into());
        assert!(matches!(grid.runs(), Err(SweepError::InvalidGrid(_))));
        grid.approx = vec!["lwpr".into(), "lwpr".into()];
        assert!(matches!(grid.runs(), Err(SweepError::InvalidGrid(_))));
        grid.approx.clear();
        assert!(matches!(grid.runs(), Err(SweepError::InvalidGrid(_))));
    }

    #[test]
    fn stats_and_markdown() {
        let s = Stat::of(&[1.0, 3.0]);
        assert_eq!((s.mean, s.n), (2.0, 2));
        assert!((s.std - 2f64.sqrt()).abs() < 1e-15);
        assert_eq!(s.markdown(), "2.00 ± 1.41");
        assert_eq!(Stat::of(&[]).markdown(), "-");
        assert_eq!(Shortest(f64::NAN).to_string(), "");
        assert_eq!(Shortest(0.25).to_string(), "0.25");
    }
}
