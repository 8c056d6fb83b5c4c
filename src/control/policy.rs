//! What the walker asks of a learner: [`FootstepPolicy`], one shape for any set of step
//! parameters.

use super::step_parameter::{FallDirection, Gate, LearnSet, PerParameter, Plane, StepParameter};
use super::{FootstepLearner, LearnerError, LearnerInput, TouchDownReport};
use crate::approx::FunctionApproximator;
use crate::rules::{LearningRule, StepOutcome};

/// What a policy did with a step, per parameter (`None` for a parameter it did not learn from).
pub type StepReports = PerParameter<Option<TouchDownReport>>;

/// The weight `gate` gives `offset`, the output of a learner reading `plane`, at these inputs
/// (the planes' deviation rates: the sagittal input's theta_E_dot, the frontal input's lean
/// rate), `fall` the plane's fall direction held from tick to tick ([`Gate::weight_held`]).
pub(crate) fn gate_weight(
    gate: Gate,
    plane: Plane,
    inputs: &PerParameter<LearnerInput>,
    offset: f64,
    fall: &mut FallDirection,
) -> f64 {
    gate.weight_held(
        plane,
        inputs[StepParameter::StepX].theta_e_dot,
        inputs[StepParameter::StepY].theta_e_dot,
        offset,
        fall,
    )
}

/// A source of learned step offsets: asked every tick, told at touch-down and at falls.
///
/// [`StepLearner`](super::step_learner::StepLearner) is the implementation for any set of
/// parameters; a lone [`FootstepLearner`] is the paper's policy, `step-x` only.
///
/// Every tick the walker hands the policy each parameter's input and asks for its offsets,
/// then tells it each parameter's reach (the offsets that could still change the step); at
/// every touch-down it hands over each parameter's outcome; at a fall, the outcome of the step
/// in progress. A policy answers for the parameters it [`learns`](FootstepPolicy::learns) and
/// ignores the others. The inputs and outcomes of the step parameters:
///
/// - `step-x`, `step-time` and `ankle-pitch`: the sagittal plane, input
///   `(theta_E, theta_E_dot, F_R)`, outcome `(theta_E, theta_E_dot, F_E, F_R)` (eq. 1-2);
/// - `step-y` and `ankle-roll`: the frontal plane mirrored to the swing leg's side, input
///   `(lean, lean rate, W_R - 2 delta)`, outcome the lean, its rate and the width error
///   `W - W_R` (see [`Walker`](super::walker::Walker)).
///
/// A learner whose settings name another plane for its parameter (`step-time` in the frontal
/// plane) reads that plane's input and outcome, those of the footstep offset learned there
/// ([`PerParameter::in_plane`]).
pub trait FootstepPolicy {
    /// The step parameters it learns. Default: `step-x` alone, the paper's.
    fn learns(&self) -> LearnSet {
        LearnSet::default()
    }
    /// The offsets for this tick from each parameter's input (0 for a parameter it does not
    /// learn).
    fn offsets(
        &mut self,
        inputs: &PerParameter<LearnerInput>,
    ) -> Result<PerParameter<f64>, LearnerError>;
    /// The offsets `[lo, hi]` that could change the step at this tick, per parameter (after
    /// [`Self::offsets`]).
    fn set_reach(&mut self, reach: &PerParameter<[f64; 2]>) -> Result<(), LearnerError>;
    /// The step that just ended: learn from each parameter's outcome.
    fn touch_down(
        &mut self,
        outcomes: &PerParameter<StepOutcome>,
    ) -> Result<StepReports, LearnerError>;
    /// The step in progress ended in a fall: learn from it or forget it (the learner's
    /// setting); the robot is reset afterwards.
    fn fall(&mut self, outcomes: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError>;
    /// Forget the current step without learning.
    fn discard_step(&mut self);
}

impl<A: FunctionApproximator + Clone, R: LearningRule> FootstepPolicy for FootstepLearner<A, R> {
    /// The learner's own parameter ([`FootstepLearner::parameter`]).
    fn learns(&self) -> LearnSet {
        LearnSet::of(&[self.parameter()]).expect("one parameter")
    }
    fn offsets(
        &mut self,
        inputs: &PerParameter<LearnerInput>,
    ) -> Result<PerParameter<f64>, LearnerError> {
        let p = self.parameter();
        let mut out = PerParameter::default();
        let offset = self.query(*inputs.in_plane(p, self.plane()))?;
        let (gate, plane) = (self.settings().gate(p), self.plane());
        let fall = self.fall_direction(plane);
        out[p] = gate_weight(gate, plane, inputs, offset, fall) * offset;
        Ok(out)
    }
    fn set_reach(&mut self, reach: &PerParameter<[f64; 2]>) -> Result<(), LearnerError> {
        let [lo, hi] = reach[self.parameter()];
        FootstepLearner::set_reach(self, lo, hi)
    }
    fn touch_down(
        &mut self,
        outcomes: &PerParameter<StepOutcome>,
    ) -> Result<StepReports, LearnerError> {
        let p = self.parameter();
        let mut out = StepReports::default();
        out[p] = Some(FootstepLearner::touch_down(
            self,
            outcomes.in_plane(p, self.plane()),
        )?);
        Ok(out)
    }
    fn fall(&mut self, outcomes: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError> {
        let p = self.parameter();
        let mut out = StepReports::default();
        out[p] = FootstepLearner::fall(self, outcomes.in_plane(p, self.plane()))?;
        Ok(out)
    }
    fn discard_step(&mut self) {
        FootstepLearner::discard_step(self)
    }
}
