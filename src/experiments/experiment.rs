//! The one abstraction every experiment implements, the paper's and a user's.

use super::error::ExperimentError;
use super::paired::Paired;
use super::protocol::{ProtocolTables, Table};
use super::replay_plan::{Moment, ReplayPlan};
use super::settings::Settings;
use crate::approx::{ApproxError, BoxedApproximator, InputBox, Stacked};
use crate::config::ConfigError;
use crate::control::StepLearner;
use crate::control::WalkerConfig;
use crate::control::coupled::{CoupledLearner, coupled_bounds};
use crate::control::{FootstepLearner, InputGrid, LearnerConfig, LearnerError};
use crate::control::{LearnSet, Plane, StepParameter};
use crate::experiments::summary::{ExperimentResult, Summary};
use crate::report::ReportError;
use crate::rules::{LearningRule, SoleTilt, StepTime};
use std::path::Path;

use super::push_options::{PushOptions, PushOptionsError};

/// The learner every experiment runs: the run's approximator and rule, chosen by name.
pub type RunLearner = FootstepLearner<BoxedApproximator, Box<dyn LearningRule>>;

/// A learner of a set of step parameters: one [`RunLearner`] per parameter.
pub type RunStepLearner = StepLearner<BoxedApproximator, Box<dyn LearningRule>>;

/// The coupled learner of a run (both planes in one model): two of the run's approximators
/// over both planes' inputs, one per output, and the run's rule for each plane.
pub type CoupledRunLearner = CoupledLearner<Stacked<BoxedApproximator>, Box<dyn LearningRule>>;

/// What a run's learners are made of: its approximator and its rule, chosen by name. Each call
/// gives a fresh one. Every learner of a run, whatever its shape, is assembled from these by
/// [`RunContext`], so an experiment never builds a learner any other way.
pub trait RunComponents: Sync {
    /// A fresh, untrained approximator of the run over `bounds` (its input box).
    fn approximator(&self, bounds: &InputBox) -> Result<BoxedApproximator, ApproxError>;
    /// A fresh rule of the run.
    fn rule(&self) -> Box<dyn LearningRule>;
}

/// What one run of an experiment is given.
pub struct RunContext<'a> {
    /// The robot, walker and learner settings (`settings.scale` is the protocols' length
    /// fraction: 1 the paper's, 0.1 `--quick`).
    pub settings: &'a Settings,
    /// The config's protocol tables (each experiment reads its own, `[protocols.<name>]`).
    pub protocols: &'a ProtocolTables,
    /// The run's seed.
    pub seed: u64,
    /// The approximator's registered name.
    pub approx: &'a str,
    /// The rule's registered name.
    pub rule: &'a str,
    /// The run's approximator and rule, from which [`RunContext`]'s `make_*` methods build
    /// every learner (each rule reseeded with the run's seed, so that a rule that explores
    /// explores differently per seed, reproducibly).
    pub components: &'a dyn RunComponents,
}

/// The box the learner's inputs are spread over ([`InputGrid::default`]'s): what a run's
/// approximators are sized from.
pub fn learner_bounds() -> Result<InputBox, ApproxError> {
    InputGrid::default().input_box()
}

/// A fresh, untrained learner of `parameter` with `config` from `components`: an approximator
/// over [`learner_bounds`], the components' rule for `step-x` and `step-y` and the LIPM
/// step-time rule ([`StepTime`]) for `step-time` and the LIPM ankle rule ([`SoleTilt`]) for
/// `ankle-pitch` and `ankle-roll`, in the plane `config` names for it (the
/// frontal one for the stance width of `walker`). Its rule is not reseeded
/// ([`RunContext::make_parameter_learner`] reseeds it with the run's seed). A learner reads
/// one plane: `config` learning `parameter` in both is an error (see
/// [`RunContext::make_learner_of`]).
pub fn parameter_learner(
    components: &dyn RunComponents,
    parameter: StepParameter,
    config: LearnerConfig,
    walker: &WalkerConfig,
) -> Result<RunLearner, LearnerError> {
    let rule: Box<dyn LearningRule> = match parameter {
        StepParameter::StepX | StepParameter::StepY => components.rule(),
        StepParameter::StepTime => match config.planes(parameter).single() {
            Some(plane) => Box::new(step_time_rule(plane, walker)),
            // Refused with the reason by the learner.
            None => Box::new(StepTime::default()),
        },
        StepParameter::AnklePitch | StepParameter::AnkleRoll => {
            Box::new(sole_tilt_rule(parameter, walker))
        }
    };
    learner_with_rule(components, parameter, config, rule)
}

/// The LIPM step-time rule in `plane` with `walker`'s controller `C`: [`StepTime`]'s
/// sagittal one, or the frontal one for the stance of `walker`
/// ([`WalkerConfig::stance_width`]).
pub fn step_time_rule(plane: Plane, walker: &WalkerConfig) -> StepTime {
    let rule = match plane {
        Plane::Sagittal => StepTime::default(),
        Plane::Frontal => StepTime::frontal(walker.stance_width()),
    };
    StepTime {
        c: walker.capture_step.c,
        ..rule
    }
}

/// The LIPM ankle rule ([`SoleTilt`]) of `parameter` for `walker`: the roll's
/// ([`SoleTilt::roll`]) for `ankle-roll`, else the pitch's, with its controller's `C` and its
/// gait's period as the time the centre of pressure acts.
pub fn sole_tilt_rule(parameter: StepParameter, walker: &WalkerConfig) -> SoleTilt {
    let rule = match parameter {
        StepParameter::AnkleRoll => SoleTilt::roll(),
        _ => SoleTilt::pitch(),
    };
    SoleTilt {
        c: walker.capture_step.c,
        step_time: walker.motion.period,
        ..rule
    }
}

/// A fresh, untrained `step-x` learner with `config` from `components` (the paper's learner).
pub fn step_x_learner(
    components: &dyn RunComponents,
    config: LearnerConfig,
) -> Result<RunLearner, LearnerError> {
    learner_with_rule(components, StepParameter::StepX, config, components.rule())
}

fn learner_with_rule(
    components: &dyn RunComponents,
    parameter: StepParameter,
    config: LearnerConfig,
    rule: Box<dyn LearningRule>,
) -> Result<RunLearner, LearnerError> {
    let bounds = learner_bounds().map_err(LearnerError::approx)?;
    let approx = components
        .approximator(&bounds)
        .map_err(LearnerError::approx)?;
    FootstepLearner::for_parameters(approx, [rule], [parameter], config)
}

impl RunContext<'_> {
    /// A fresh `step-x` learner with the settings' learner config.
    pub fn make_learner(&self) -> Result<RunLearner, LearnerError> {
        self.make_learner_with(self.settings.learner)
    }

    /// A fresh `step-x` learner with `config` (an experiment that compares learner settings).
    pub fn make_learner_with(&self, config: LearnerConfig) -> Result<RunLearner, LearnerError> {
        self.make_parameter_learner(StepParameter::StepX, config)
    }

    /// A fresh learner of one step parameter with `config`: the run's approximator over the
    /// learner's inputs, the run's rule for `step-x` and `step-y`, the LIPM step-time rule
    /// ([`StepTime`]) for `step-time` in its plane and the LIPM ankle rule ([`SoleTilt`]) for
    /// `ankle-pitch` and `ankle-roll`, the parameter's own settings ([`LearnerConfig::offset`]).
    pub fn make_parameter_learner(
        &self,
        parameter: StepParameter,
        config: LearnerConfig,
    ) -> Result<RunLearner, LearnerError> {
        let mut learner =
            parameter_learner(self.components, parameter, config, &self.settings.walker)?;
        learner.reseed(self.seed);
        Ok(learner)
    }

    /// A fresh learner of `set` with the settings' learner config: one
    /// [`Self::make_parameter_learner`] per parameter and plane it is learned in (the step
    /// time in `both` planes has one per plane, with [`LearnerConfig::part`]'s settings).
    pub fn make_learner_of(&self, set: LearnSet) -> Result<RunStepLearner, LearnerError> {
        let config = LearnerConfig {
            learn: set,
            ..self.settings.learner
        };
        config.check()?;
        let mut learners = Vec::new();
        for p in set.iter() {
            let planes = config.planes(p);
            for plane in planes.iter() {
                let one = match planes.single() {
                    Some(_) => config,
                    None => config.part(p, plane),
                };
                learners.push((p, self.make_parameter_learner(p, one)?));
            }
        }
        StepLearner::new(learners)
    }

    /// A fresh learner of the settings' set (`[settings.learner] learn`, `--learn`).
    pub fn make_step_learner(&self) -> Result<RunStepLearner, LearnerError> {
        self.make_learner_of(self.settings.learner.learn)
    }

    /// A fresh coupled learner (`step-x` and `step-y` from one model over both planes' inputs,
    /// [`coupled_bounds`]) with the settings' learner config: two of the run's approximators
    /// stacked, one per output, and a rule of the run for each plane.
    pub fn make_coupled_learner(&self) -> Result<CoupledRunLearner, LearnerError> {
        let bounds = learner_bounds()
            .and_then(|b| coupled_bounds(&b))
            .map_err(LearnerError::approx)?;
        let head = || {
            self.components
                .approximator(&bounds)
                .map_err(LearnerError::approx)
        };
        let stacked = Stacked::new(vec![head()?, head()?]).map_err(LearnerError::approx)?;
        let rules = [self.components.rule(), self.components.rule()];
        let mut learner = CoupledLearner::new(stacked, rules, self.settings.learner)?;
        learner.reseed(self.seed);
        Ok(learner)
    }
}

/// A figure of an experiment over seeds, for the leaderboard: its name (with its unit) and
/// its mean over the seeds that have it.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Headline {
    /// What it is, with its unit, e.g. `"I50 learned (Ns)"`.
    pub name: String,
    /// Mean over seeds (NaN where no seed has it; written as `null`).
    pub mean: f64,
}

impl Headline {
    /// The mean of the finite `values` as the figure `name`.
    pub fn mean_of(name: &str, values: impl IntoIterator<Item = f64>) -> Self {
        let s = crate::stats::MeanStd::of(values.into_iter().filter(|v| v.is_finite()));
        Headline {
            name: name.to_string(),
            mean: if s.count() == 0 { f64::NAN } else { s.mean() },
        }
    }
}

/// One experiment: the paper's or a user's.
///
/// A user's experiment builds its walkers with the public harness
/// ([`crate::experiments::settings::Settings::trial`], [`crate::experiments::trial`]), its
/// learners with [`RunContext::make_learner`], and reports a
/// [`crate::experiments::summary::CustomResult`].
///
/// An experiment is a type in its own file implementing [`Experiment`]: it adjusts its
/// protocol to the command line's push options, runs with the learners a [`RunContext`] builds
/// (one approximator and rule per run, whatever their types), writes its CSV and figures,
/// returns its part of `summary.json`, and compares the learned walker with the model over
/// seeds for the leaderboard. `steplearn::bench::Registry` holds them by name.
pub trait Experiment: Send + Sync {
    /// Its name on the command line, in run ids and in `summary.json` (lowercase letters,
    /// digits and `-`).
    fn name(&self) -> &str;

    /// What it measures, in one line.
    fn description(&self) -> &str {
        ""
    }

    /// Its whole protocol table in `tables` (`[protocols.<name>]`, its defaults where the
    /// table leaves keys out), checked; `None` for an experiment without a protocol. A config
    /// is valid only if every registered experiment accepts its table; this is also what a
    /// run's recorded configuration holds. By default: no protocol, and a table for it is an
    /// error. An experiment with a typed protocol returns `tables.resolve::<P>(self.name())`.
    fn protocol(&self, tables: &ProtocolTables) -> Result<Option<Table>, ConfigError> {
        match tables.table(self.name()) {
            Some(_) => Err(ConfigError::new(
                format!("protocols.{}", self.name()),
                "this experiment takes no protocol",
            )),
            None => Ok(None),
        }
    }

    /// Applies the command line's push options to its protocol table; an error if they do not
    /// apply (by default: an experiment that takes none).
    fn apply_push_options(
        &self,
        protocols: &mut ProtocolTables,
        options: &PushOptions,
    ) -> Result<(), PushOptionsError> {
        let _ = protocols;
        if options.is_empty() {
            Ok(())
        } else {
            Err(PushOptionsError::NotTaken {
                experiment: self.name().to_string(),
            })
        }
    }

    /// Runs it, writes its CSV and figures into `dir` and returns its summary result. It must
    /// depend only on the context (the seed included), never on timing or thread count.
    fn run(&self, ctx: &RunContext<'_>, dir: &Path) -> Result<ExperimentResult, ExperimentError>;

    /// Checks a result of this experiment, as its `run` returns it or as read back from
    /// `summary.json`: the invariants of its own fields that JSON cannot state (finite
    /// numbers, counts that add up). Runs whose result fails are not counted as finished and
    /// are left out of tables. By default any result is accepted; an experiment with a
    /// [`crate::experiments::summary::TypedResult`] returns `T::from_result(result).map(|_| ())`.
    fn check_result(&self, result: &ExperimentResult) -> Result<(), ReportError> {
        let _ = result;
        Ok(())
    }

    /// The learned walker against the model, paired by seed over `runs` (this experiment's
    /// summaries of one approximator and rule, in seed order): the leaderboard's verdicts.
    fn versus_model(&self, runs: &[&Summary]) -> Vec<Paired>;

    /// Its headline figures over `runs` (as for [`Experiment::versus_model`]), for the
    /// leaderboard's columns.
    fn headline(&self, runs: &[&Summary]) -> Vec<Headline> {
        let _ = runs;
        Vec::new()
    }

    /// How `steplearn replay` re-simulates its runs and which moment of a run it shows on the
    /// results page; `None` (the default) for an experiment without a replay.
    fn replay(&self) -> Option<&dyn Replayable> {
        None
    }
}

/// An experiment whose runs `steplearn replay` can re-simulate: the trials it walks for a
/// run's seed, settings and protocol, and a telling moment of a finished run.
pub trait Replayable: Sync {
    /// How to re-simulate the run with `settings`, `protocols` (the run's recorded ones) and
    /// `seed`: the experiment's own trials, built by its own functions.
    fn replay_plan(
        &self,
        settings: &Settings,
        protocols: &ProtocolTables,
        seed: u64,
    ) -> Result<ReplayPlan, ExperimentError>;

    /// A telling moment of the finished run in `dir` (made with `settings`, `protocols` and
    /// `seed`), read from the tables it wrote, with a one-line description.
    fn telling_moment(
        &self,
        settings: &Settings,
        protocols: &ProtocolTables,
        seed: u64,
        dir: &Path,
    ) -> Result<(Moment, String), ExperimentError>;
}
