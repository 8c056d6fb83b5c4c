//! Errors of the simulated humanoid.

use thiserror::Error;

/// Everything that can go wrong building or stepping the simulated humanoid.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SimError {
    /// A configuration value is out of its valid range (or not finite).
    #[error("invalid sim config: {field} = {value} ({reason})")]
    InvalidConfig {
        /// Dotted name of the offending field.
        field: String,
        /// Its value.
        value: f64,
        /// What the valid range is.
        reason: &'static str,
    },
    /// A joint target is NaN or infinite; nothing was applied.
    #[error("joint target {index} is not finite: {value}")]
    BadTarget {
        /// Joint index (see [`crate::robot::LegJoint::index`]).
        index: usize,
        /// The rejected value.
        value: f64,
    },
    /// A push impulse is NaN or infinite; nothing was applied.
    #[error("push impulse is not finite: {impulse:?}")]
    BadImpulse {
        /// The rejected impulse (N s).
        impulse: [f64; 3],
    },
    /// The physics produced a non-finite or exploding state.
    #[error("simulation blew up at t = {time} s: {what}")]
    BlowUp {
        /// Simulation time of the failure (s).
        time: f64,
        /// What was found.
        what: String,
    },
    /// The robot's description was refused.
    #[error("{0}")]
    Robot(#[from] crate::robot::RobotError),
    /// A config file could not be parsed.
    #[error("cannot parse body config: {0}")]
    Parse(String),
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn positive(field: &str, value: f64) -> Result<(), SimError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(SimError::InvalidConfig {
            field: field.to_string(),
            value,
            reason: "must be finite and > 0",
        })
    }
}

/// Checks that `value` is finite and not negative.
pub(crate) fn non_negative(field: &str, value: f64) -> Result<(), SimError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(SimError::InvalidConfig {
            field: field.to_string(),
            value,
            reason: "must be finite and >= 0",
        })
    }
}

/// Checks that `value` lies in `[lo, hi]`.
pub(crate) fn in_range(field: &str, value: f64, lo: f64, hi: f64) -> Result<(), SimError> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(())
    } else {
        Err(SimError::InvalidConfig {
            field: field.to_string(),
            value,
            reason: "out of range",
        })
    }
}
