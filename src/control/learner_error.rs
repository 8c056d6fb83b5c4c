//! What the learner refuses: invalid settings, a wrongly shaped approximator, non-finite
//! values, and the approximator's or rule's own errors.

use crate::approx::ApproxError;
use crate::rules::RuleError;
use thiserror::Error;

/// Errors of the learner. A rejected call leaves the learner as it was (see each method).
#[derive(Debug, Error)]
pub enum LearnerError {
    /// The configuration is invalid.
    #[error("invalid learner configuration: {param} {reason}")]
    InvalidConfig {
        /// The field's name.
        param: &'static str,
        /// Why, with the value.
        reason: String,
    },
    /// The rule rejected a saved rule state (see [`LearningRule::set_state`](crate::rules::LearningRule::set_state)).
    #[error("rule: {0}")]
    Rule(#[from] RuleError),
    /// The approximator does not map the learner's inputs to its outputs.
    #[error(
        "approximator must map {} inputs to {} outputs, it maps {inputs} to {outputs}",
        expected.0,
        expected.1
    )]
    WrongApproximatorShape {
        /// The inputs and outputs the learner needs.
        expected: (usize, usize),
        /// Its input dimension.
        inputs: usize,
        /// Its output dimension.
        outputs: usize,
    },
    /// A query input or a step outcome held NaN or an infinity.
    #[error("{what} is not finite: {value}")]
    NonFinite {
        /// What was not finite (e.g. `"theta_e"`, `"gradient G"`).
        what: &'static str,
        /// The value.
        value: f64,
    },
    /// The approximator rejected a call; `applied` training samples of this touch-down had
    /// already been applied (0 unless the approximator fails on a sample the learner had
    /// checked to be finite).
    #[error("approximator error after {applied} applied updates: {source}")]
    Approx {
        /// Updates of this touch-down applied before the error.
        applied: usize,
        /// The approximator's error.
        source: ApproxError,
    },
}

impl LearnerError {
    pub(crate) fn config(param: &'static str, reason: impl Into<String>) -> Self {
        LearnerError::InvalidConfig {
            param,
            reason: reason.into(),
        }
    }

    pub(crate) fn approx(source: ApproxError) -> Self {
        LearnerError::Approx { applied: 0, source }
    }
}
