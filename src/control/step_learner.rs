//! One learner for any set of step parameters.
//!
//! A [`StepLearner`] learns each parameter of its [`LearnSet`] with a [`FootstepLearner`] of
//! its own (the uncoupled setting): its own approximator over that parameter's inputs, and its
//! own rule, which turns that parameter's outcome into the gradient G. Every safeguard of the
//! footstep learner (prior, gain guard, anti-windup against the parameter's reach, trust
//! region, learning from falls, dead zone, leakage, `max_step_error`, the nominal fallback)
//! and its checkpoints therefore work for every parameter, and a user's rule for any parameter
//! plugs in as the learner's rule does. The built-in rules per parameter: the run's rule for
//! `step-x` and `step-y` (the lateral learner sees the mirrored frontal plane, see
//! [`super::policy`]), [`StepTime`](crate::rules::StepTime) for `step-time`.

use super::learner::{FootstepLearner, LearnerError, LearnerInput, SavedLearner};
use super::policy::{FootstepPolicy, StepReports};
use super::step_parameter::{LearnSet, PerParameter, StepParameter};
use crate::approx::{FunctionApproximator, Persist};
use crate::rules::{LearningRule, StepOutcome};
use serde::{Deserialize, Serialize};

/// One [`FootstepLearner`] per learned step parameter (see the module docs).
pub struct StepLearner<A: FunctionApproximator, R: LearningRule> {
    /// In the order of [`StepParameter::ALL`], each parameter once.
    learners: Vec<(StepParameter, FootstepLearner<A, R>)>,
    set: LearnSet,
}

impl<A: FunctionApproximator, R: LearningRule> std::fmt::Debug for StepLearner<A, R> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StepLearner")
            .field("learn", &self.set.to_string())
            .finish_non_exhaustive()
    }
}

/// A [`StepLearner`]'s checkpoint: each parameter's learner's.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SavedStepLearner<A> {
    /// Each learned parameter with its learner's checkpoint.
    pub learners: Vec<(StepParameter, SavedLearner<A>)>,
}

impl<A: FunctionApproximator, R: LearningRule> StepLearner<A, R> {
    /// The learner of `learners`, one per parameter (any order; each parameter at most once,
    /// at least one).
    pub fn new(
        mut learners: Vec<(StepParameter, FootstepLearner<A, R>)>,
    ) -> Result<Self, LearnerError> {
        let parameters: Vec<StepParameter> = learners.iter().map(|(p, _)| *p).collect();
        let set = LearnSet::of(&parameters).map_err(|e| LearnerError::InvalidConfig {
            param: "learn",
            reason: e.to_string(),
        })?;
        learners.sort_by_key(|(p, _)| p.index());
        Ok(StepLearner { learners, set })
    }

    /// The learner of `parameter`, if it is learned.
    pub fn learner(&self, parameter: StepParameter) -> Option<&FootstepLearner<A, R>> {
        self.learners
            .iter()
            .find(|(p, _)| *p == parameter)
            .map(|(_, l)| l)
    }

    /// Every learned parameter with its learner, in order.
    pub fn learners(&self) -> impl Iterator<Item = (StepParameter, &FootstepLearner<A, R>)> {
        self.learners.iter().map(|(p, l)| (*p, l))
    }

    /// Reseeds every parameter's rule with `seed`.
    pub fn reseed(&mut self, seed: u64) {
        for (_, l) in &mut self.learners {
            l.reseed(seed);
        }
    }
}

impl<A: FunctionApproximator + Persist + Clone, R: LearningRule> StepLearner<A, R> {
    /// A checkpoint of every parameter's learner (see [`FootstepLearner::checkpoint`]).
    pub fn checkpoint(&self) -> SavedStepLearner<A> {
        SavedStepLearner {
            learners: self
                .learners
                .iter()
                .map(|(p, l)| (*p, l.checkpoint()))
                .collect(),
        }
    }

    /// The learner of a checkpoint, each parameter's rule from `rule`: it continues bit for bit
    /// as the learner that wrote it. Errors as [`FootstepLearner::from_checkpoint`], or if the
    /// checkpoint names a parameter twice or none.
    pub fn from_checkpoint(
        saved: SavedStepLearner<A>,
        mut rule: impl FnMut(StepParameter) -> R,
    ) -> Result<Self, LearnerError> {
        let learners = saved
            .learners
            .into_iter()
            .map(|(p, s)| Ok((p, FootstepLearner::from_checkpoint(s, rule(p))?)))
            .collect::<Result<Vec<_>, LearnerError>>()?;
        Self::new(learners)
    }
}

impl<A: FunctionApproximator + Clone, R: LearningRule> FootstepPolicy for StepLearner<A, R> {
    fn learns(&self) -> LearnSet {
        self.set
    }
    fn offsets(
        &mut self,
        inputs: &PerParameter<LearnerInput>,
    ) -> Result<PerParameter<f64>, LearnerError> {
        let mut out = PerParameter::default();
        for (p, l) in &mut self.learners {
            out[*p] = l.query(inputs[*p])?;
        }
        Ok(out)
    }
    fn set_reach(&mut self, reach: &PerParameter<[f64; 2]>) -> Result<(), LearnerError> {
        for (p, l) in &mut self.learners {
            let [lo, hi] = reach[*p];
            l.set_reach(lo, hi)?;
        }
        Ok(())
    }
    fn touch_down(
        &mut self,
        outcomes: &PerParameter<StepOutcome>,
    ) -> Result<StepReports, LearnerError> {
        let mut out = StepReports::default();
        for (p, l) in &mut self.learners {
            out[*p] = Some(l.touch_down(&outcomes[*p])?);
        }
        Ok(out)
    }
    fn fall(&mut self, outcomes: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError> {
        let mut out = StepReports::default();
        for (p, l) in &mut self.learners {
            out[*p] = l.fall(&outcomes[*p])?;
        }
        Ok(out)
    }
    fn discard_step(&mut self) {
        for (_, l) in &mut self.learners {
            l.discard_step();
        }
    }
}
