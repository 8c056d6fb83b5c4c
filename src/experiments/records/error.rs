//! The error type of the experiments.

use crate::config::ConfigError;
use crate::control::LearnerError;
use crate::experiments::trial::TrialError;
use crate::report::ReportError;
use thiserror::Error;

/// What can stop an experiment.
#[derive(Debug, Error)]
pub enum ExperimentError {
    /// A trial failed.
    #[error(transparent)]
    Trial(#[from] TrialError),
    /// The learner could not be built or failed.
    #[error("learner: {0}")]
    Learner(#[from] LearnerError),
    /// Analysing or writing the results failed.
    #[error(transparent)]
    Report(#[from] ReportError),
    /// A settings or protocol value is out of range (names the field).
    #[error("invalid config: {0}")]
    Config(#[from] ConfigError),
    /// The experiment's settings are invalid.
    #[error("invalid experiment settings: {0}")]
    Invalid(String),
    /// The run finished but left nothing the experiment measures (e.g. every push of B ended
    /// in a fall, so there is no recovery to align).
    #[error("nothing to measure: {0}")]
    NothingToMeasure(String),
}
