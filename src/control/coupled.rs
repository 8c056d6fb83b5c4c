//! The coupled shape of the one learner ([`OffsetLearner`]): both planes' footstep offsets
//! (dF, dW) from one approximator with two outputs over both planes' inputs.
//!
//! Its input is the sagittal learner's `(theta_E, theta_E_dot, F_R)` followed by the lateral
//! learner's mirrored `(lean, lean rate, W_R - 2 delta)`; its outputs are the sagittal offset
//! dF and the width offset dW. At touch-down each plane's rule turns its own plane's outcome
//! into a gradient, and the one approximator is trained towards `y(x_i) + eta (G_x, G_y)` at
//! every input recorded in the step: so what the walker learned from a sagittal error can
//! change the width it steps with in a leaning state, and the other way round. It is the same
//! implementation as the uncoupled [`FootstepLearner`](super::learner::FootstepLearner), so
//! every safeguard of [`LearnerConfig`] holds for both offsets.
//!
//! The walker calls it through [`FootstepPolicy`], which hands over both planes at once. Its
//! checkpoints are the one learner's ([`OffsetLearner::checkpoint`], `save`, `load_with`): the
//! second offset's reach, last value, exploration and rule state are saved beside the first's.

use super::policy::{FootstepPolicy, StepReports, gate_weight};
use super::step_parameter::{LearnSet, PerParameter, Plane, StepParameter};
use super::{LearnerConfig, LearnerError, LearnerInput, OffsetLearner, TouchDownReport};
use crate::approx::{FunctionApproximator, InputBox};
use crate::rules::{LearningRule, StepOutcome};

/// Number of inputs of the coupled learner's approximator: both planes' three.
pub const COUPLED_INPUTS: usize = 6;

/// The planes, in output order: sagittal (dF), lateral (dW).
const PLANES: usize = 2;

/// One learner of both planes' footstep offsets (see the module docs).
pub type CoupledLearner<A, R> = OffsetLearner<A, R, COUPLED_INPUTS, PLANES>;

/// The coupled learner's input box: the sagittal box `bounds` (theta_E, theta_E_dot, F_R)
/// for both planes (approximator factories of a coupled run receive it).
pub fn coupled_bounds(bounds: &InputBox) -> Result<InputBox, crate::approx::ApproxError> {
    InputBox::new(
        [bounds.lo.as_slice(), &bounds.lo].concat(),
        [bounds.hi.as_slice(), &bounds.hi].concat(),
    )
}

/// The two planes in output order.
const PLANE_PARAMETERS: [StepParameter; PLANES] = [StepParameter::StepX, StepParameter::StepY];

impl<A: FunctionApproximator, R: LearningRule> OffsetLearner<A, R, COUPLED_INPUTS, PLANES> {
    /// A learner around `approx` (6 inputs, 2 outputs) with the sagittal and the lateral rule,
    /// holding the prior of `config` over both planes (its box for each plane's three inputs);
    /// each output has its parameter's settings (`step-x`, `step-y`,
    /// [`LearnerConfig::offset`]).
    pub fn new(approx: A, rules: [R; PLANES], config: LearnerConfig) -> Result<Self, LearnerError> {
        Self::for_parameters(approx, rules, PLANE_PARAMETERS, config)
    }

    /// The raw outputs `(dF, dW)` at `x`.
    pub fn predict(&self, x: &[f64; COUPLED_INPUTS]) -> Result<[f64; PLANES], LearnerError> {
        self.predict_all(x)
    }

    /// The control-tick query with both planes' inputs: returns `(dF, dW)` (each with its
    /// rule's exploration of this step, clamped to `max_offset` if set) and records the input
    /// for the touch-down update. On error nothing is recorded.
    pub fn query(
        &mut self,
        sagittal: LearnerInput,
        lateral: LearnerInput,
    ) -> Result<[f64; PLANES], LearnerError> {
        let (s, l) = (sagittal.to_array(), lateral.to_array());
        self.query_all(std::array::from_fn(|a| if a < 3 { s[a] } else { l[a - 3] }))
    }

    /// The offsets of `plane` (0 sagittal, 1 lateral) that could change the step at the last
    /// query (see [`FootstepLearner::set_reach`](super::learner::FootstepLearner::set_reach)).
    pub fn set_reach(&mut self, plane: usize, lo: f64, hi: f64) -> Result<(), LearnerError> {
        self.set_reach_of(plane, lo, hi)
    }
}

impl<A: FunctionApproximator + Clone, R: LearningRule> OffsetLearner<A, R, COUPLED_INPUTS, PLANES> {
    /// Ends the step with both planes' outcomes (sagittal, lateral): each plane's rule gives
    /// its G and the approximator is trained towards `y + eta (G_x, G_y)` at every recorded
    /// input, under the gain guard and anti-windup. Returns each plane's report. Checked
    /// rejections change nothing; an approximator failing mid-update discards the step.
    pub fn touch_down(
        &mut self,
        outcomes: [&StepOutcome; PLANES],
    ) -> Result<[TouchDownReport; PLANES], LearnerError> {
        self.touch_down_all(outcomes)
    }

    /// The step in progress ended in a fall: with `learn_from_falls`, learns from it as from a
    /// touch-down with each plane's theta_E clamped as the sagittal learner clamps it;
    /// otherwise forgets it.
    pub fn fall(
        &mut self,
        outcomes: [&StepOutcome; PLANES],
    ) -> Result<Option<[TouchDownReport; PLANES]>, LearnerError> {
        self.fall_all(outcomes)
    }
}

impl<A: FunctionApproximator + Clone, R: LearningRule> FootstepPolicy
    for OffsetLearner<A, R, COUPLED_INPUTS, PLANES>
{
    fn learns(&self) -> LearnSet {
        LearnSet::of(&PLANE_PARAMETERS).expect("two parameters")
    }
    fn offsets(
        &mut self,
        inputs: &PerParameter<LearnerInput>,
    ) -> Result<PerParameter<f64>, LearnerError> {
        let [df, dw] = self.query(inputs[StepParameter::StepX], inputs[StepParameter::StepY])?;
        // Each offset weighted by its parameter's gate in its own plane.
        let mut gate = |p: StepParameter, plane, offset: f64| {
            let g = self.settings().gate(p);
            gate_weight(g, plane, inputs, offset, self.fall_direction(plane)) * offset
        };
        let mut out = PerParameter::default();
        out[StepParameter::StepX] = gate(StepParameter::StepX, Plane::Sagittal, df);
        out[StepParameter::StepY] = gate(StepParameter::StepY, Plane::Frontal, dw);
        Ok(out)
    }
    fn set_reach(&mut self, reach: &PerParameter<[f64; 2]>) -> Result<(), LearnerError> {
        for (plane, p) in PLANE_PARAMETERS.into_iter().enumerate() {
            let [lo, hi] = reach[p];
            self.set_reach_of(plane, lo, hi)?;
        }
        Ok(())
    }
    fn touch_down(
        &mut self,
        outcomes: &PerParameter<StepOutcome>,
    ) -> Result<StepReports, LearnerError> {
        let [s, l] = self.touch_down_all(PLANE_PARAMETERS.map(|p| &outcomes[p]))?;
        Ok(plane_reports([s, l]))
    }
    fn fall(&mut self, outcomes: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError> {
        Ok(
            match self.fall_all(PLANE_PARAMETERS.map(|p| &outcomes[p]))? {
                Some(both) => plane_reports(both),
                None => StepReports::default(),
            },
        )
    }
    fn discard_step(&mut self) {
        OffsetLearner::discard_step(self)
    }
}

/// Both planes' reports as the walker's, at their parameters.
fn plane_reports(reports: [TouchDownReport; PLANES]) -> StepReports {
    let mut out = StepReports::default();
    for (p, r) in PLANE_PARAMETERS.into_iter().zip(reports) {
        out[p] = Some(r);
    }
    out
}
