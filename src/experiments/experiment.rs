//! The one abstraction every experiment implements, and the registry the command line,
//! `reproduce`, `sweep` and `merge` find them in.
//!
//! An experiment is a unit type in its own file implementing [`Experiment`]: it adjusts its
//! protocol to the command line's push options, runs with the learners a [`RunContext`] builds
//! (one approximator and rule per run), writes its CSV and figures, and returns its part of
//! `summary.json`. [`registry`] lists them in the paper's order.

use super::ExperimentKind;
use super::error::ExperimentError;
use super::run::Protocols;
use super::settings::Settings;
use crate::approx::AnyApproximator;
use crate::control::learner::{FootstepLearner, LearnerConfig, LearnerError};
use crate::experiments::summary::ExperimentResult;
use crate::rules::LearningRule;
use std::path::Path;

/// The learner every experiment runs: the run's approximator and rule, chosen by name.
pub type RunLearner = FootstepLearner<AnyApproximator, Box<dyn LearningRule>>;

/// What one run of an experiment is given.
pub struct RunContext<'a> {
    /// The robot, walker and learner settings.
    pub settings: &'a Settings,
    /// Every experiment's protocol (each reads its own).
    pub protocols: &'a Protocols,
    /// The run's seed.
    pub seed: u64,
    /// Builds a fresh, untrained learner of the run's approximator and rule with `config`.
    pub learner: &'a (dyn Fn(LearnerConfig) -> Result<RunLearner, LearnerError> + Sync),
}

impl RunContext<'_> {
    /// A fresh learner with the settings' learner config.
    pub fn make_learner(&self) -> Result<RunLearner, LearnerError> {
        (self.learner)(self.settings.learner)
    }
}

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

impl PushOptions {
    /// The single impulse of an experiment that pushes with one impulse (`A,A`), if given.
    pub fn single_impulse(&self, kind: ExperimentKind) -> Result<Option<f64>, String> {
        match self.impulse_range {
            Some((a, b)) if a != b => Err(format!(
                "{kind} pushes with one impulse: give --impulse-range A,A (got {a},{b})"
            )),
            Some((a, _)) => Ok(Some(a)),
            None => Ok(None),
        }
    }

    /// Sets the push count, the one impulse and the direction of an experiment of `kind` that
    /// pushes with one impulse, where the options give them.
    pub fn apply_single(
        &self,
        kind: ExperimentKind,
        pushes: &mut usize,
        impulse: &mut f64,
        direction: &mut [f64; 3],
    ) -> Result<(), String> {
        let single = self.single_impulse(kind)?;
        *pushes = self.pushes.unwrap_or(*pushes);
        *impulse = single.unwrap_or(*impulse);
        *direction = self.direction.unwrap_or(*direction);
        Ok(())
    }
}

/// One experiment of the paper (or a user's).
pub trait Experiment: Sync {
    /// Its name on the command line, in run ids and in `summary.json`.
    fn kind(&self) -> ExperimentKind;

    /// Applies the command line's push options to its protocol in `protocols`; an error if
    /// they do not apply (an experiment without pushes, one impulse given as a range).
    fn apply_push_options(
        &self,
        protocols: &mut Protocols,
        options: &PushOptions,
    ) -> Result<(), String>;

    /// Runs it, writes its CSV and figures into `dir` and returns its summary result.
    fn run(&self, ctx: &RunContext<'_>, dir: &Path) -> Result<ExperimentResult, ExperimentError>;
}

/// Every experiment, in the paper's order (A-D).
pub fn registry() -> [&'static dyn Experiment; 4] {
    [
        &super::tracking::Tracking,
        &super::disturbance::Disturbance,
        &super::stability::Stability,
        &super::robustness::Robustness,
    ]
}

impl ExperimentKind {
    /// The registered experiment of this name.
    pub fn experiment(self) -> &'static dyn Experiment {
        registry()
            .into_iter()
            .find(|e| e.kind() == self)
            .expect("every ExperimentKind is registered (tested)")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use strum::VariantArray;

    #[test]
    fn every_kind_is_registered_once_in_order() {
        let kinds: Vec<ExperimentKind> = registry().iter().map(|e| e.kind()).collect();
        assert_eq!(kinds, ExperimentKind::VARIANTS.to_vec());
        for &k in ExperimentKind::VARIANTS {
            assert_eq!(k.experiment().kind(), k);
        }
    }
}
