//! The error type shared by every function approximator.

use thiserror::Error;

/// What can go wrong when configuring, training, querying, saving or loading an approximator.
///
/// Every fallible call on an approximator reports one of these instead of panicking, and a
/// call that fails leaves the model exactly as it was.
#[derive(Debug, Error)]
pub enum ApproxError {
    /// A slice had the wrong length.
    #[error("{what}: expected length {expected}, got {got}")]
    DimensionMismatch {
        /// Which argument was wrong (e.g. `"input x"`).
        what: &'static str,
        /// The length the model needs.
        expected: usize,
        /// The length it was given.
        got: usize,
    },
    /// An input or target held NaN or an infinity.
    #[error("{what}[{index}] is not finite ({value})")]
    NonFinite {
        /// Which argument was wrong.
        what: &'static str,
        /// Position of the first offending element.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// An input or target too large in magnitude for the model to hold: training on it would
    /// push the model past what a saved model may contain.
    #[error("{what}[{index}] = {value} is beyond the model's range (|value| <= {limit})")]
    OutOfRange {
        /// Which argument was wrong.
        what: &'static str,
        /// Position of the first offending element.
        index: usize,
        /// The offending value.
        value: f64,
        /// The largest magnitude accepted.
        limit: f64,
    },
    /// A configuration parameter is out of its valid range.
    #[error("invalid configuration: {param} {reason}")]
    InvalidConfig {
        /// The parameter's name, as in the config's setter.
        param: &'static str,
        /// Why it is invalid (e.g. `"must be in (0, 1), got 1.5"`).
        reason: String,
    },
    /// A saved model could not be read back or violates the model's invariants.
    #[error("corrupt or incompatible saved model: {0}")]
    Corrupt(String),
    /// An approximator supplied by the user (e.g. a Python object run through the bench) failed;
    /// the message names its original error.
    #[error("the user's approximator failed: {0}")]
    External(String),
    /// Reading or writing a model file failed.
    #[error("i/o error: {0}")]
    Io(#[from] std::io::Error),
}

impl ApproxError {
    /// Shorthand for [`ApproxError::InvalidConfig`].
    pub fn config(param: &'static str, reason: impl Into<String>) -> Self {
        ApproxError::InvalidConfig {
            param,
            reason: reason.into(),
        }
    }
}

/// Checks that `v` has length `expected` and holds only finite numbers.
///
/// This is the one input check every approximator runs before touching its state.
pub fn check_vector(what: &'static str, v: &[f64], expected: usize) -> Result<(), ApproxError> {
    if v.len() != expected {
        return Err(ApproxError::DimensionMismatch {
            what,
            expected,
            got: v.len(),
        });
    }
    match v.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(ApproxError::NonFinite {
            what,
            index,
            value: v[index],
        }),
        None => Ok(()),
    }
}

/// Checks that an output buffer has length `expected` (its contents are overwritten).
pub fn check_output(what: &'static str, y: &[f64], expected: usize) -> Result<(), ApproxError> {
    if y.len() != expected {
        return Err(ApproxError::DimensionMismatch {
            what,
            expected,
            got: y.len(),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn check_vector_reports_length_and_non_finite() {
        assert!(check_vector("x", &[1.0, 2.0], 2).is_ok());
        assert!(matches!(
            check_vector("x", &[1.0], 2),
            Err(ApproxError::DimensionMismatch {
                expected: 2,
                got: 1,
                ..
            })
        ));
        assert!(matches!(
            check_vector("x", &[1.0, f64::NAN], 2),
            Err(ApproxError::NonFinite { index: 1, .. })
        ));
        assert!(matches!(
            check_vector("x", &[f64::INFINITY, 0.0], 2),
            Err(ApproxError::NonFinite { index: 0, .. })
        ));
    }
}
