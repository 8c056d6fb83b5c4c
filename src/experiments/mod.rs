//! The experiments, generic over approximator and learning rule, in three parts: the
//! [`harness`] every experiment shares, the [`records`] and reports of runs, and the
//! experiments themselves, one file each in [`suite`], which also holds the paper's
//! reproduction (its claims and its ablation table, [`suite::reproduction`]); [`experiment`] is
//! the contract between them (the [`Experiment`] trait and the [`RunContext`] that builds a
//! run's learners).

pub mod experiment;
pub mod harness;
pub mod records;
pub mod suite;

// Every module at its path of old, so that `steplearn::experiments::trial` and the like stay.
pub use harness::{
    aligned, catch_step, compare, fall_causes, footstep_env, protocol, replay_plan, robot_setup,
    schedule, settings, trial,
};
pub use records::{claim, config_file, config_keys, index_page, paired, summary, sweep};
pub use suite::reproduction::{ablation, reproduce};
pub use suite::{disturbance, omnidirectional, robustness, stability, tracking};

pub(crate) use harness::push_options;
pub(crate) use records::error;

pub use config_file::{ConfigFile, ConfigFileError};
pub use error::ExperimentError;
pub use experiment::{Experiment, Headline, PushOptions, PushOptionsError, Replayable, RunContext};
pub use paired::{Paired, Verdict};
pub use protocol::{Protocol, ProtocolTables};
pub use settings::Settings;
pub use suite::reproduction::ExperimentKind;
pub use summary::{CustomResult, ExperimentResult, Summary, TypedResult};
pub use trial::{Observer, TrialError, TrialLog, TrialSetup, run_trial};
