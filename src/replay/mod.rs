//! `steplearn replay RUN_DIR --push K --out FILE.html`: push K of a finished run, re-simulated
//! and drawn in 3D in one self-contained page.
//!
//! A run is bit-reproducible from its `run-config.toml`: [`record()`] reads it, checks that this
//! registry would write the same identity (same experiment, approximator, rule, settings,
//! protocol and results format), rebuilds the experiment's trials for the run's seed with the
//! experiment's own functions, and runs them with [`run_trial`], the trial code every
//! experiment uses, with a [`Recorder`] attached. [`page()`] writes the recording as one HTML
//! page with three.js inlined ([`page::THREE_VERSION`]).
//!
//! Supported so far: experiment D (`robustness`): push K's episode of the learned walker
//! (after learning from the episodes before it, as in the run) and of the walker without
//! learning. Other experiments are a [`ReplayError::Unsupported`].

pub mod page;
pub mod record;

use crate::bench::{BenchError, Registry};
use crate::control::learner::LearnerError;
use crate::experiments::ExperimentKind;
use crate::experiments::experiment::RunContext;
use crate::experiments::protocol::{ProtocolTables, Table};
use crate::experiments::robustness::{self, RobustnessProtocol};
use crate::experiments::settings::Settings;
use crate::experiments::sweep::{IDENTITY_FILE, RunSpec};
use crate::experiments::trial::{TrialError, run_trial};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use thiserror::Error;

pub use page::{embedded_replay, page};
pub use record::{Frame, Recorder, Touchdown, Walk};

/// Seconds recorded before the push.
pub const BEFORE_PUSH_S: f64 = 1.0;
/// Seconds between two recorded frames (50 Hz).
pub const FRAME_S: f64 = 0.02;

/// What can stop a replay.
#[derive(Debug, Error)]
pub enum ReplayError {
    /// The run directory or its `run-config.toml` is missing.
    #[error(
        "{0}: no run here (no {IDENTITY_FILE}; give the directory `steplearn experiment --out` wrote)"
    )]
    MissingRun(PathBuf),
    /// The run's `run-config.toml` cannot be read or parsed.
    #[error("{path}: not a run configuration: {reason}")]
    Corrupt {
        /// The file.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// This binary would not reproduce the run (another steplearn version, or another
    /// registry's approximator or rule).
    #[error(
        "{0}: this steplearn would not reproduce the run (its identity differs from what this binary writes for the same run)"
    )]
    NotReproducible(PathBuf),
    /// The run's experiment has no replay yet.
    #[error("experiment `{0}` has no replay yet (supported: robustness)")]
    Unsupported(String),
    /// The push number is not one of the run's pushes.
    #[error("push {push} is out of range: the run has pushes 1..={pushes}")]
    PushOutOfRange {
        /// The push asked for (1-based).
        push: usize,
        /// How many pushes the run has.
        pushes: usize,
    },
    /// The registry cannot build the run's learner.
    #[error("registry: {0}")]
    Registry(#[from] BenchError),
    /// The learner failed.
    #[error("learner: {0}")]
    Learner(#[from] LearnerError),
    /// A trial failed.
    #[error("trial: {0}")]
    Trial(#[from] TrialError),
    /// Writing or reading a page failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The error.
        source: std::io::Error,
    },
    /// A page holds no replay data, or data that does not parse.
    #[error("no replay data in the page: {0}")]
    Page(String),
}

/// What `run-config.toml` records (see `Registry::run_identity`).
#[derive(Debug, Clone, Deserialize)]
pub struct RunConfig {
    /// The results format.
    pub format: u32,
    /// The experiment's name.
    pub experiment: String,
    /// The approximator's name.
    pub approx: String,
    /// The rule's name.
    pub rule: String,
    /// The seed.
    pub seed: u64,
    /// The whole settings.
    pub settings: Settings,
    /// The experiment's protocol table.
    #[serde(default)]
    pub protocol: Option<Table>,
}

impl RunConfig {
    /// Reads `dir/run-config.toml`.
    pub fn read(dir: &Path) -> Result<(Self, String), ReplayError> {
        let path = dir.join(IDENTITY_FILE);
        if !path.is_file() {
            return Err(ReplayError::MissingRun(dir.to_path_buf()));
        }
        let text = std::fs::read_to_string(&path).map_err(|e| ReplayError::Corrupt {
            path: path.clone(),
            reason: e.to_string(),
        })?;
        let config = toml::from_str(&text).map_err(|e| ReplayError::Corrupt {
            path: path.clone(),
            reason: e.to_string(),
        })?;
        Ok((config, text))
    }

    /// The protocol tables with this run's table.
    fn protocols(&self) -> ProtocolTables {
        let mut tables = ProtocolTables::default();
        tables.set_table(&self.experiment, self.protocol.clone());
        tables
    }
}

/// One push, replayed by every walker of the experiment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Replay {
    /// The experiment's name.
    pub experiment: String,
    /// The approximator's name.
    pub approx: String,
    /// The rule's name.
    pub rule: String,
    /// The run's seed.
    pub seed: u64,
    /// The push (1-based).
    pub push: usize,
    /// Its impulse (Ns).
    pub impulse: f64,
    /// Its direction (world unit vector).
    pub direction: [f64; 3],
    /// The push window (s): a fall within it after the push counts.
    pub window_s: f64,
    /// One recording per walker.
    pub walks: Vec<Walk>,
}

/// Re-simulates push `push` (1-based) of the run in `dir` with `registry`.
pub fn record(registry: &Registry, dir: &Path, push: usize) -> Result<Replay, ReplayError> {
    let (config, text) = RunConfig::read(dir)?;
    let protocols = config.protocols();
    let spec = RunSpec {
        experiment: config.experiment.clone(),
        approx: config.approx.clone(),
        rule: config.rule.clone(),
        seed: config.seed,
        learn: None,
    };
    let robustness: &str = ExperimentKind::Robustness.into();
    if config.experiment != robustness {
        return Err(ReplayError::Unsupported(config.experiment));
    }
    let identity = registry.run_identity(&spec, &config.settings, &protocols)?;
    if identity != text {
        return Err(ReplayError::NotReproducible(dir.join(IDENTITY_FILE)));
    }
    let protocol: RobustnessProtocol =
        protocols
            .get(&config.experiment)
            .map_err(|e| ReplayError::Corrupt {
                path: dir.join(IDENTITY_FILE),
                reason: e.to_string(),
            })?;
    replay_robustness(registry, &config, &protocol, push)
}

fn replay_robustness(
    registry: &Registry,
    config: &RunConfig,
    protocol: &RobustnessProtocol,
    push: usize,
) -> Result<Replay, ReplayError> {
    let settings = &config.settings;
    let times = robustness::push_times(settings, protocol, config.seed);
    if push == 0 || push > times.len() {
        return Err(ReplayError::PushOutOfRange {
            push,
            pushes: times.len(),
        });
    }
    // The run's learner, built as the run built it (`RunContext`, reseeded with its seed).
    let components = registry.components(&config.approx, &config.rule, &settings.lwpr)?;
    let protocols = config.protocols();
    let ctx = RunContext {
        settings,
        protocols: &protocols,
        seed: config.seed,
        approx: &config.approx,
        rule: &config.rule,
        components: &components,
    };
    let mut learner = ctx.make_learner_with(robustness::learner_config(settings, protocol))?;
    // The episodes before push K, as the run walked them: the learner learns from them.
    for &t in &times[..push - 1] {
        run_trial(
            &robustness::episode_setup(settings, protocol, t),
            Some(&mut learner),
            &mut [],
        )?;
    }
    let push_time = times[push - 1];
    let setup = robustness::episode_setup(settings, protocol, push_time);
    let from = (push_time - BEFORE_PUSH_S).max(0.0);
    let to = setup.duration_s;
    let mut learned = Recorder::new(from, to, FRAME_S);
    run_trial(&setup, Some(&mut learner), &mut [&mut learned])?;
    let mut without = Recorder::new(from, to, FRAME_S);
    run_trial(&setup, None, &mut [&mut without])?;
    Ok(Replay {
        experiment: config.experiment.clone(),
        approx: config.approx.clone(),
        rule: config.rule.clone(),
        seed: config.seed,
        push,
        impulse: protocol.impulse,
        direction: protocol.direction,
        window_s: settings.push_window_s,
        walks: vec![
            learned.finish("learned"),
            without.finish("no learning (dF = 0)"),
        ],
    })
}

/// [`record()`], then writes the page to `out`.
pub fn replay_to_file(
    registry: &Registry,
    dir: &Path,
    push: usize,
    out: &Path,
) -> Result<Replay, ReplayError> {
    let replay = record(registry, dir, push)?;
    let html = page(&replay)?;
    // Atomically: a failed write leaves an existing file as it was.
    crate::atomic_file::write_atomic(out, html.as_bytes()).map_err(|source| ReplayError::Io {
        path: out.to_path_buf(),
        source,
    })?;
    Ok(replay)
}

/// One line on what a written replay holds, for the command line.
pub fn summary_line(replay: &Replay, out: &Path) -> String {
    let walks: Vec<String> = replay
        .walks
        .iter()
        .map(|w| {
            format!(
                "{}: {} ({} frames)",
                w.name,
                if w.fell { "fell" } else { "absorbed" },
                w.frames.len()
            )
        })
        .collect();
    format!(
        "{}: push {} of {} seed {}; {}",
        out.display(),
        replay.push,
        replay.experiment,
        replay.seed,
        walks.join("; ")
    )
}
