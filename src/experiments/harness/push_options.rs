//! The command line's push options (`--pushes`, `--impulse-range`, `--push-direction`) and why
//! an experiment refuses them.

use crate::config::ConfigError;
use thiserror::Error;

/// The command line's push options (`--pushes`, `--impulse-range`, `--push-direction`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PushOptions {
    /// Number of pushes, if given.
    pub pushes: Option<usize>,
    /// Impulse range (Ns), if given.
    pub impulse_range: Option<(f64, f64)>,
    /// Unit push direction, if given (otherwise the protocol's, e.g. from a config file).
    pub direction: Option<[f64; 3]>,
}

/// Why push options do not apply to an experiment.
#[derive(Debug, Error)]
pub enum PushOptionsError {
    /// The experiment takes no push options at all.
    #[error("{experiment} takes no push options")]
    NotTaken {
        /// The experiment's name.
        experiment: String,
    },
    /// The experiment has no pushes.
    #[error("the {experiment} experiment has no pushes")]
    NoPushes {
        /// The experiment's name.
        experiment: String,
    },
    /// One of the options does not apply to this experiment.
    #[error("{experiment} {why}: {option} does not apply")]
    NotApplicable {
        /// The experiment's name.
        experiment: String,
        /// The option, as written on the command line.
        option: &'static str,
        /// What about the experiment makes it not apply.
        why: &'static str,
    },
    /// The experiment pushes with one impulse, and a range was given.
    #[error("{experiment} pushes with one impulse: give --impulse-range A,A (got {lo},{hi})")]
    NotSingleImpulse {
        /// The experiment's name.
        experiment: String,
        /// The range's low end (Ns).
        lo: f64,
        /// The range's high end (Ns).
        hi: f64,
    },
    /// The protocol with the options applied is not valid.
    #[error(transparent)]
    Config(#[from] ConfigError),
}

impl PushOptions {
    /// Whether no option is given.
    pub fn is_empty(&self) -> bool {
        self.pushes.is_none() && self.impulse_range.is_none() && self.direction.is_none()
    }

    /// The single impulse of experiment `kind`, which pushes with one impulse (`A,A`), if given.
    pub fn single_impulse(&self, kind: &str) -> Result<Option<f64>, PushOptionsError> {
        match self.impulse_range {
            Some((lo, hi)) if lo != hi => Err(PushOptionsError::NotSingleImpulse {
                experiment: kind.to_string(),
                lo,
                hi,
            }),
            Some((a, _)) => Ok(Some(a)),
            None => Ok(None),
        }
    }

    /// Sets the push count, the one impulse and the direction of an experiment of `kind` that
    /// pushes with one impulse, where the options give them.
    pub fn apply_single(
        &self,
        kind: &str,
        pushes: &mut usize,
        impulse: &mut f64,
        direction: &mut [f64; 3],
    ) -> Result<(), PushOptionsError> {
        let single = self.single_impulse(kind)?;
        *pushes = self.pushes.unwrap_or(*pushes);
        *impulse = single.unwrap_or(*impulse);
        *direction = self.direction.unwrap_or(*direction);
        Ok(())
    }
}
