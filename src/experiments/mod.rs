//! The experiments, generic over approximator and learning rule. Each module here is one
//! concept at one path: the harness every experiment shares ([`settings`], [`trial`],
//! [`schedule`], [`protocol`], ...), the records and reports of runs ([`summary`],
//! [`config_file`], [`sweep`], [`paired`], ...), the experiments themselves, one file each
//! ([`tracking`], [`disturbance`], [`stability`], [`robustness`], [`omnidirectional`]), collected
//! by [`paper`], [`beyond`] and [`builtin`], and the paper's reproduction ([`reproduce`],
//! [`claims_table`], [`ablation`]). The contract between them is here: the [`Experiment`] trait
//! and the [`RunContext`] that builds a run's learners.

mod experiment;
pub(crate) mod harness;
pub(crate) mod records;
pub(crate) mod suite;

pub use harness::{
    aligned, catch_step, compare, fall_causes, footstep_env, protocol, replay_plan, robot_setup,
    schedule, settings, trial,
};
pub use records::{claim, config_file, config_keys, index_page, paired, summary, sweep};
pub use suite::reproduction::{ablation, claims_table, reproduce};
pub use suite::{beyond, builtin, paper};
pub use suite::{disturbance, omnidirectional, robustness, stability, tracking};

pub(crate) use harness::push_options;
pub(crate) use records::error;

pub use error::ExperimentError;
pub use experiment::{
    CoupledRunLearner, Experiment, Headline, Replayable, RunComponents, RunContext, RunLearner,
    RunStepLearner, learner_bounds, parameter_learner, sole_tilt_rule, step_time_rule,
    step_x_learner,
};
pub use push_options::{PushOptions, PushOptionsError};
pub use suite::reproduction::ExperimentKind;
