//! `steplearn replay RUN_DIR (--push K | --time A..B) --out FILE.html`: push K or a span of a
//! finished run, re-simulated and drawn in 3D in one self-contained page.
//!
//! A run is bit-reproducible from its `run-config.toml`: [`record_moment()`] reads it, checks
//! that this registry would write the same identity (same experiment, approximator, rule,
//! settings, protocol and results format), asks the experiment for its [`ReplayPlan`] (the
//! trials it walks for the run's seed, built by its own functions,
//! [`crate::experiments::Replayable`]) and runs them with [`run_trial`], the trial code every
//! experiment uses, with a [`Recorder`] attached. [`page()`] writes the recording as one HTML
//! page with three.js inlined ([`THREE_VERSION`]).
//!
//! A plan of long trials (one per walker, the learned one learning throughout) is walked from
//! its start to the end of the moment replayed, a push or a span; a plan of one episode per
//! push replays push K after the learner has learned from the episodes before it. An
//! experiment without a replay is a [`ReplayError::Unsupported`]. [`moments`] picks a telling
//! moment of a run for the results pages.

pub mod moments;
mod page;
mod record;

use crate::bench::{BenchError, Registry};
use crate::control::LearnerConfig;
use crate::control::LearnerError;
use crate::experiments::ExperimentError;
use crate::experiments::RunContext;
use crate::experiments::protocol::{ProtocolTables, Table};
use crate::experiments::settings::Settings;
use crate::experiments::sweep::{IDENTITY_FILE, RunSpec};
use crate::experiments::trial::{TrialError, TrialSetup, run_trial};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use thiserror::Error;

use crate::experiments::replay_plan::{Moment, ReplayPlan, ReplayWalker};
pub use page::{THREE_LICENSE, THREE_VERSION, embedded_replay, page};
pub use record::{DrawnShape, Frame, Recorder, Touchdown, Walk, drawn_bodies};

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
    #[error("experiment `{0}` has no replay (it does not implement `Replayable`)")]
    Unsupported(String),
    /// A span that is not `0 <= from < to`, both finite.
    #[error("bad time span {from}..{to}: {reason}")]
    BadSpan {
        /// Its start (s).
        from: f64,
        /// Its end (s).
        to: f64,
        /// What is wrong.
        reason: String,
    },
    /// A span that ends after the run's trial.
    #[error("time span ends at {to} s, after the run's trial ({length} s)")]
    SpanOutOfRange {
        /// The span's end (s).
        to: f64,
        /// The trial's length (s).
        length: f64,
    },
    /// `--push` for a run without pushes.
    #[error("experiment `{0}` has no pushes: give --time A..B")]
    NoPushes(String),
    /// `--time` for a run of one episode per push.
    #[error("experiment `{0}` is one short episode per push: give --push K")]
    NoSpan(String),
    /// The experiment cannot build its trial.
    #[error("experiment: {0}")]
    Experiment(#[from] ExperimentError),
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
    pub(crate) fn protocols(&self) -> ProtocolTables {
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
    /// The push (1-based); 0 for a span.
    pub push: usize,
    /// Its impulse (Ns).
    pub impulse: f64,
    /// Its direction (world unit vector).
    pub direction: [f64; 3],
    /// The push window (s): a fall within it after the push counts.
    pub window_s: f64,
    /// The replayed span `[from, to]` of trial time (s) for `--time`; `None` for a push.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub span: Option<[f64; 2]>,
    /// The reference step size F_R over a span: `[time, F_R]` at its start and at every change
    /// within it (empty for a push).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub changes: Vec<[f64; 2]>,
    /// One recording per walker.
    pub walks: Vec<Walk>,
}

/// Re-simulates push `push` (1-based) of the run in `dir` with `registry`.
pub fn record(registry: &Registry, dir: &Path, push: usize) -> Result<Replay, ReplayError> {
    record_moment(registry, dir, Moment::Push(push))
}

/// Re-simulates the span `[from, to]` (trial time, s) of the run in `dir` with `registry`
/// (`steplearn replay --time A..B`).
pub fn record_span(
    registry: &Registry,
    dir: &Path,
    from: f64,
    to: f64,
) -> Result<Replay, ReplayError> {
    record_moment(registry, dir, Moment::Span(from, to))
}

/// Checks a span's numbers: finite, `0 <= from < to`.
pub fn check_span(from: f64, to: f64) -> Result<(), ReplayError> {
    let reason = if !(from.is_finite() && to.is_finite()) {
        "both ends must be finite numbers"
    } else if from < 0.0 {
        "the start must be >= 0"
    } else if from >= to {
        "the start must be before the end"
    } else {
        return Ok(());
    };
    Err(ReplayError::BadSpan {
        from,
        to,
        reason: reason.into(),
    })
}

/// Re-simulates `moment` of the run in `dir` with `registry`.
pub fn record_moment(
    registry: &Registry,
    dir: &Path,
    moment: Moment,
) -> Result<Replay, ReplayError> {
    if let Moment::Span(from, to) = moment {
        check_span(from, to)?;
    }
    let (config, text) = RunConfig::read(dir)?;
    let protocols = config.protocols();
    let spec = RunSpec {
        experiment: config.experiment.clone(),
        approx: config.approx.clone(),
        rule: config.rule.clone(),
        seed: config.seed,
        learn: None,
    };
    let experiment = registry.find_experiment(&config.experiment)?;
    let replayable = experiment
        .replay()
        .ok_or_else(|| ReplayError::Unsupported(config.experiment.clone()))?;
    let identity = registry.run_identity(&spec, &config.settings, &protocols)?;
    if identity != text {
        return Err(ReplayError::NotReproducible(dir.join(IDENTITY_FILE)));
    }
    let components = registry.components(&config.approx, &config.rule, &config.settings.lwpr)?;
    let ctx = RunContext {
        settings: &config.settings,
        protocols: &protocols,
        seed: config.seed,
        approx: &config.approx,
        rule: &config.rule,
        components: &components,
    };
    match replayable.replay_plan(&config.settings, &protocols, config.seed)? {
        ReplayPlan::Episodes {
            episodes,
            learner,
            impulse,
            direction,
        } => {
            let Moment::Push(push) = moment else {
                return Err(ReplayError::NoSpan(config.experiment));
            };
            replay_episodes(&ctx, &config, &episodes, *learner, impulse, direction, push)
        }
        ReplayPlan::Trials {
            walkers,
            direction,
            after_push_s,
            pushes,
        } => {
            if matches!(moment, Moment::Push(_)) && !pushes {
                return Err(ReplayError::NoPushes(config.experiment));
            }
            replay_trials(&ctx, &config, walkers, direction, after_push_s, moment)
        }
    }
}

/// `moment` of a run of one long trial per walker (`walkers`, the experiment's plan): every
/// walker walks its trial from the start to the moment's end, recorded over the moment.
fn replay_trials(
    ctx: &RunContext<'_>,
    config: &RunConfig,
    walkers: Vec<ReplayWalker>,
    direction: [f64; 3],
    after: f64,
    moment: Moment,
) -> Result<Replay, ReplayError> {
    let Some(first) = walkers.first() else {
        return Err(ReplayError::Unsupported(config.experiment.clone()));
    };
    let reference = first.setup.reference.clone();
    let (mut push_no, mut impulse, mut span, mut changes) = (0, 0.0, None, Vec::new());
    let trials: Vec<(ReplayWalker, Recorder)> = match moment {
        Moment::Push(push) => {
            check_push(push, first.setup.pushes.len())?;
            (push_no, impulse) = (push, first.setup.pushes[push - 1].impulse);
            walkers
                .into_iter()
                .map(|mut w| {
                    // The pushes after K cannot change what comes before them.
                    w.setup.pushes.truncate(push);
                    let recorder = Recorder::around_push(push, BEFORE_PUSH_S, after, FRAME_S)
                        .for_sim(&w.setup.sim);
                    (w, recorder)
                })
                .collect()
        }
        Moment::Span(from, to) => {
            let length = first.setup.duration_s;
            if to > length {
                return Err(ReplayError::SpanOutOfRange { to, length });
            }
            span = Some([from, to]);
            changes = std::iter::once(from)
                .chain(
                    reference
                        .change_times()
                        .into_iter()
                        .filter(|&t| t > from && t <= to),
                )
                .map(|t| [record::round(t), record::round(reference.at(t))])
                .collect();
            walkers
                .into_iter()
                .map(|mut w| {
                    // Nothing after `to` can change what comes before it.
                    w.setup.duration_s = to;
                    let recorder = Recorder::new(from, to, FRAME_S).for_sim(&w.setup.sim);
                    (w, recorder)
                })
                .collect()
        }
    };
    let walks = walk_all(ctx, trials)?;
    Ok(Replay {
        experiment: config.experiment.clone(),
        approx: config.approx.clone(),
        rule: config.rule.clone(),
        seed: config.seed,
        push: push_no,
        impulse,
        direction,
        window_s: ctx.settings.push_window_s,
        span,
        changes,
        walks,
    })
}

/// Runs every walker's trial from its start as the run did (the learned one with the run's
/// learner), on the rayon pool, and returns their recordings in order.
fn walk_all(
    ctx: &RunContext<'_>,
    trials: Vec<(ReplayWalker, Recorder)>,
) -> Result<Vec<Walk>, ReplayError> {
    use rayon::prelude::*;
    trials
        .into_par_iter()
        .map(|(walker, mut recorder)| {
            if walker.learns {
                let mut learner = ctx.make_step_learner()?;
                run_trial(&walker.setup, Some(&mut learner), &mut [&mut recorder])?;
            } else {
                run_trial(&walker.setup, None, &mut [&mut recorder])?;
            }
            Ok(recorder.finish(&walker.name))
        })
        .collect()
}

fn check_push(push: usize, pushes: usize) -> Result<(), ReplayError> {
    if push == 0 || push > pushes {
        return Err(ReplayError::PushOutOfRange { push, pushes });
    }
    Ok(())
}

/// Push `push` of a run of one episode per push: the run's learner learns from the
/// `episodes` before it, then walks push `push`'s episode beside the walker without learning.
fn replay_episodes(
    ctx: &RunContext<'_>,
    config: &RunConfig,
    episodes: &[TrialSetup],
    learner: LearnerConfig,
    impulse: f64,
    direction: [f64; 3],
    push: usize,
) -> Result<Replay, ReplayError> {
    check_push(push, episodes.len())?;
    // The run's learner, built as the run built it (`RunContext`, reseeded with its seed).
    let mut learner = ctx.make_learner_with(learner)?;
    // The episodes before push K, as the run walked them: the learner learns from them.
    for setup in &episodes[..push - 1] {
        run_trial(setup, Some(&mut learner), &mut [])?;
    }
    let setup = &episodes[push - 1];
    let push_time = setup.pushes.first().map_or(0.0, |p| p.time);
    let from = (push_time - BEFORE_PUSH_S).max(0.0);
    let to = setup.duration_s;
    let mut learned = Recorder::new(from, to, FRAME_S).for_sim(&setup.sim);
    run_trial(setup, Some(&mut learner), &mut [&mut learned])?;
    let mut without = Recorder::new(from, to, FRAME_S).for_sim(&setup.sim);
    run_trial(setup, None, &mut [&mut without])?;
    Ok(Replay {
        experiment: config.experiment.clone(),
        approx: config.approx.clone(),
        rule: config.rule.clone(),
        seed: config.seed,
        push,
        impulse,
        direction,
        window_s: ctx.settings.push_window_s,
        span: None,
        changes: Vec::new(),
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
    moment_to_file(registry, dir, Moment::Push(push), out)
}

/// [`record_moment()`], then writes the page to `out`.
pub fn moment_to_file(
    registry: &Registry,
    dir: &Path,
    moment: Moment,
    out: &Path,
) -> Result<Replay, ReplayError> {
    let replay = record_moment(registry, dir, moment)?;
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
                match (replay.span, w.fell) {
                    (Some(_), _) if w.fall_time.is_some() => "fell",
                    (Some(_), _) => "walked",
                    (None, true) => "fell",
                    (None, false) => "absorbed",
                },
                w.frames.len()
            )
        })
        .collect();
    format!(
        "{}: {} of {} seed {}; {}",
        out.display(),
        moment_name(replay),
        replay.experiment,
        replay.seed,
        walks.join("; ")
    )
}

/// `push K` or `A..B s`.
pub fn moment_name(replay: &Replay) -> String {
    match replay.span {
        Some([from, to]) => format!("{from}..{to} s"),
        None => format!("push {}", replay.push),
    }
}
