//! Two uncoupled learners, one per plane: the paper's sagittal learner and a lateral one.
//!
//! The lateral learner is an ordinary footstep learner (any approximator, any rule) that the
//! walker feeds the frontal plane's quantities, mirrored so that left and right steps are the
//! same problem: positive points to the side of the swing leg. Its input is (lean, lean rate,
//! 0), where the lean is the trunk's roll towards the swing leg; its outcome at touch-down is
//! that lean and rate as theta_E and its rate, and the width error `W - W_R` (the feet's
//! lateral distance against the controller's `2 delta`) as F_E. Its offset widens (dW > 0) or
//! narrows the step; the walker's step-width range is its reach, so the anti-windup stops it at
//! the width floor. With the pendulum-cart rule the gradient is the frontal-plane analogue of
//! eq. (5), `G = lambda_E - p_theta tanh(p_F W_E)`: a trunk still leaning towards the swing
//! leg at touch-down asks for a wider step, a step wider than the reference for a narrower
//! one (see `docs/lateral.md`).

use super::learner::{LearnerError, LearnerInput, TouchDownReport};
use super::walker::FootstepPolicy;
use crate::rules::StepOutcome;

/// A sagittal and a lateral policy, uncoupled: each learns from its own plane only.
#[derive(Debug, Clone)]
pub struct TwoPlanes<S, L> {
    /// The sagittal learner (the paper's).
    pub sagittal: S,
    /// The lateral learner, fed the mirrored frontal plane.
    pub lateral: L,
}

impl<S: FootstepPolicy, L: FootstepPolicy> FootstepPolicy for TwoPlanes<S, L> {
    fn offset(&mut self, input: LearnerInput) -> Result<f64, LearnerError> {
        self.sagittal.offset(input)
    }
    fn set_reach(&mut self, lo: f64, hi: f64) -> Result<(), LearnerError> {
        self.sagittal.set_reach(lo, hi)
    }
    fn touch_down(&mut self, outcome: &StepOutcome) -> Result<TouchDownReport, LearnerError> {
        self.sagittal.touch_down(outcome)
    }
    fn fall(&mut self, outcome: &StepOutcome) -> Result<Option<TouchDownReport>, LearnerError> {
        self.sagittal.fall(outcome)
    }
    fn discard_step(&mut self) {
        self.sagittal.discard_step()
    }
    fn lateral_offset(&mut self, input: LearnerInput) -> Result<Option<f64>, LearnerError> {
        self.lateral.offset(input).map(Some)
    }
    fn set_lateral_reach(&mut self, lo: f64, hi: f64) -> Result<(), LearnerError> {
        self.lateral.set_reach(lo, hi)
    }
    fn lateral_touch_down(
        &mut self,
        outcome: &StepOutcome,
    ) -> Result<Option<TouchDownReport>, LearnerError> {
        self.lateral.touch_down(outcome).map(Some)
    }
    fn lateral_fall(
        &mut self,
        outcome: &StepOutcome,
    ) -> Result<Option<TouchDownReport>, LearnerError> {
        self.lateral.fall(outcome)
    }
    fn discard_lateral_step(&mut self) {
        self.lateral.discard_step()
    }
}
