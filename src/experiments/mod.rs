//! The paper's experiments (section V), generic over approximator and learning rule, and the
//! harness that runs and sweeps them.

pub mod aligned;
pub mod catch_step;
pub mod claim;
pub mod compare;
pub mod config_file;
pub mod disturbance;
mod error;
pub mod experiment;
pub mod fall_causes;
pub mod index_page;
mod kind;
pub mod omnidirectional;
pub mod paired;
pub mod protocol;
mod push_options;
pub mod reproduce;
pub mod robustness;
pub mod schedule;
pub mod settings;
pub mod stability;
pub mod suite;
pub mod summary;
pub mod sweep;
pub mod tracking;
pub mod trial;

pub use config_file::{ConfigFile, ConfigFileError};
pub use error::ExperimentError;
pub use experiment::{Experiment, Headline, PushOptions, PushOptionsError, RunContext};
pub use kind::ExperimentKind;
pub use paired::{Paired, Verdict};
pub use protocol::{Protocol, ProtocolTables};
pub use settings::Settings;
pub use summary::{CustomResult, ExperimentResult, Summary};
pub use trial::{Observer, TrialError, TrialLog, TrialSetup, run_trial};
