//! What can go wrong with a registry or a bench.

use thiserror::Error;

/// Errors of the registry and the bench. Failures of single runs are collected, not fatal:
/// the others run and the leaderboard is written before [`BenchError::RunsFailed`] is returned.
#[derive(Debug, Error)]
pub enum BenchError {
    /// A registration was refused (a name taken twice or malformed).
    #[error("registry: {0}")]
    Registry(String),
    /// A name that is not registered.
    #[error("unknown {what} '{name}' (registered: {known})")]
    Unknown {
        /// `"approximator"`, `"rule"` or `"experiment"`.
        what: String,
        /// The name given.
        name: String,
        /// The registered names.
        known: String,
    },
    /// A selection or setting of the bench is invalid (an empty list, a name twice, seeds or
    /// scale out of range, a baseline outside the selection).
    #[error("{0}")]
    Selection(String),
    /// The approximator of a combination cannot be built (its factory fails on the learner's
    /// input box); found before any run.
    #[error("approximator {approx:?} cannot be built (combination {approx} + {rule}): {reason}")]
    CannotBuild {
        /// The approximator's name.
        approx: String,
        /// The rule's name.
        rule: String,
        /// The factory's error.
        reason: String,
    },
    /// A robot of the bench was refused (its file unreadable, or a robot the walker cannot
    /// take).
    #[error("robot {}: {source}", path.display())]
    Robot {
        /// The URDF file.
        path: std::path::PathBuf,
        /// Why it was refused.
        source: crate::robot::RobotError,
    },
    /// The output directory holds results of another configuration.
    #[error("{0}")]
    ConfigChanged(String),
    /// Setting up or reading the runs failed.
    #[error(transparent)]
    Sweep(#[from] crate::experiments::sweep::SweepError),
    /// Writing the leaderboard failed.
    #[error(transparent)]
    Report(#[from] crate::report::ReportError),
    /// Some runs failed (each with its id and message); the others finished and the
    /// leaderboard covers them.
    #[error("{} of the runs failed: {}", .0.len(), .0.iter().map(|(id, m)| format!("{id}: {m}")).collect::<Vec<_>>().join("; "))]
    RunsFailed(Vec<(String, String)>),
}

impl BenchError {
    pub(crate) fn unknown(what: &str, name: &str, known: &[&str]) -> Self {
        BenchError::Unknown {
            what: what.to_string(),
            name: name.to_string(),
            known: known.join(", "),
        }
    }
}
