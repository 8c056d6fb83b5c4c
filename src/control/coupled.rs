//! The coupled variant of a [`StepLearner`](super::step_learner::StepLearner) of `step-x` and
//! `step-y`: one learner for both planes, with two outputs (dF, dW) over both planes' inputs.
//!
//! Its input is the sagittal learner's `(theta_E, theta_E_dot, F_R)` followed by the lateral
//! learner's mirrored `(lean, lean rate, W_R - 2 delta)`; its outputs are the sagittal offset
//! dF and the width offset dW. At touch-down each plane's rule turns its own plane's outcome
//! into a gradient, and the one approximator is trained towards `y(x_i) + eta (G_x, G_y)` at
//! every input recorded in the step: so what the walker learned from a sagittal error can
//! change the width it steps with in a leaning state, and the other way round. The learner
//! holds the safeguards of [`FootstepLearner`](super::learner::FootstepLearner) with the same
//! [`LearnerConfig`]: the prior (dF = dW = 0 over both planes' prior boxes), the gain guard
//! (on the larger of the two outputs' gains, one scale for both), anti-windup per plane, the
//! trust region over all six inputs, learning from falls, dead zone, leakage and train share.
//! It does not take `max_step_error` or [`TrustFallback::Nominal`]: it refuses them.
//!
//! The walker calls it through [`FootstepPolicy`], which hands over both planes at once.

use super::learner::{
    GuardError, Guarded, LearnerConfig, LearnerError, LearnerInput, TouchDownReport, TrustFallback,
    clamped_at_fall, guarded_update, is_reach, radical_inverse, windup,
};
use super::policy::{FootstepPolicy, StepReports};
use super::step_parameter::{LearnSet, PerParameter, StepParameter};
use super::step_samples::{StepSamples, trust_share};
use crate::approx::{FunctionApproximator, InputBox};
use crate::rules::{LearningRule, StepOutcome};
use crate::stats::MeanStd;

/// Number of inputs of the coupled learner's approximator: both planes' three.
pub const COUPLED_INPUTS: usize = 6;

/// The planes, in output order: sagittal (dF), lateral (dW).
const PLANES: usize = 2;

/// Bases of the Halton sequence the prior is spread over (the first six primes).
const HALTON_BASES: [usize; COUPLED_INPUTS] = [2, 3, 5, 7, 11, 13];

/// Names of the six inputs, for errors.
const INPUT_NAMES: [&str; COUPLED_INPUTS] = [
    "theta_e",
    "theta_e_dot",
    "f_r",
    "lateral lean",
    "lateral lean rate",
    "lateral f_r",
];

/// One learner of both planes' footstep offsets (see the module docs).
pub struct CoupledLearner<A: FunctionApproximator, R: LearningRule> {
    approx: A,
    /// The sagittal and the lateral rule.
    rules: [R; PLANES],
    config: LearnerConfig,
    /// Inputs recorded in this step (at most `max_samples_per_step`, thinned as the sagittal
    /// learner's are), each with each plane's reach.
    step: StepSamples<[f64; COUPLED_INPUTS], [[f64; 2]; PLANES]>,
    /// Mean and std of the trained inputs per axis (the trust region).
    trained: [MeanStd; COUPLED_INPUTS],
    /// Each plane's exploration perturbation of this step.
    exploration: [f64; PLANES],
}

impl<A: FunctionApproximator, R: LearningRule> std::fmt::Debug for CoupledLearner<A, R> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CoupledLearner")
            .field("config", &self.config)
            .field("recorded", &self.step.inputs.len())
            .finish_non_exhaustive()
    }
}

/// The coupled learner's input box: the sagittal box `bounds` (theta_E, theta_E_dot, F_R)
/// for both planes (approximator factories of a coupled run receive it).
pub fn coupled_bounds(bounds: &InputBox) -> Result<InputBox, crate::approx::ApproxError> {
    InputBox::new(
        [bounds.lo.as_slice(), &bounds.lo].concat(),
        [bounds.hi.as_slice(), &bounds.hi].concat(),
    )
}

impl<A: FunctionApproximator + Clone, R: LearningRule> CoupledLearner<A, R> {
    /// A learner around `approx` (6 inputs, 2 outputs) with the sagittal and the lateral rule,
    /// holding the prior of `config` over both planes (its box for each plane's three inputs).
    pub fn new(approx: A, rules: [R; PLANES], config: LearnerConfig) -> Result<Self, LearnerError> {
        config.validate()?;
        if config.max_step_error.is_some() {
            return Err(LearnerError::InvalidConfig {
                param: "max_step_error",
                reason: "is not supported by the coupled learner".into(),
            });
        }
        if config.trust_fallback == TrustFallback::Nominal {
            return Err(LearnerError::InvalidConfig {
                param: "trust_fallback",
                reason: "nominal is not supported by the coupled learner".into(),
            });
        }
        if approx.input_dim() != COUPLED_INPUTS || approx.output_dim() != PLANES {
            return Err(LearnerError::InvalidConfig {
                param: "approximator",
                reason: format!(
                    "the coupled learner needs {COUPLED_INPUTS} inputs and {PLANES} outputs, it \
                     maps {} to {}",
                    approx.input_dim(),
                    approx.output_dim()
                ),
            });
        }
        let mut learner = CoupledLearner {
            approx,
            rules,
            config,
            step: StepSamples::with_capacity(config.max_samples_per_step),
            trained: [MeanStd::new(); COUPLED_INPUTS],
            exploration: [0.0; PLANES],
        };
        for i in 0..config.prior.samples {
            learner
                .approx
                .update(&learner.prior_point(i), &[0.0; PLANES])
                .map_err(|source| LearnerError::Approx { applied: 0, source })?;
        }
        Ok(learner)
    }

    /// The settings.
    pub fn config(&self) -> &LearnerConfig {
        &self.config
    }

    /// The approximator.
    pub fn approximator(&self) -> &A {
        &self.approx
    }

    /// Reseeds both rules' randomness with `seed`.
    pub fn reseed(&mut self, seed: u64) {
        for r in &mut self.rules {
            r.reseed(seed);
        }
    }

    /// The `i`-th point of the prior: Halton over the prior's box, for each plane.
    fn prior_point(&self, i: usize) -> [f64; COUPLED_INPUTS] {
        let (lo, hi) = (
            self.config.prior.lo.to_array(),
            self.config.prior.hi.to_array(),
        );
        std::array::from_fn(|a| {
            let (l, h) = (lo[a % 3], hi[a % 3]);
            l + (h - l) * radical_inverse(i + 1, HALTON_BASES[a])
        })
    }

    /// The raw outputs `(dF, dW)` at `x`.
    pub fn predict(&self, x: &[f64; COUPLED_INPUTS]) -> Result<[f64; PLANES], LearnerError> {
        predict_at(&self.approx, x)
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
        let x: [f64; COUPLED_INPUTS] = std::array::from_fn(|a| if a < 3 { s[a] } else { l[a - 3] });
        for (what, v) in INPUT_NAMES.into_iter().zip(x) {
            if !v.is_finite() {
                return Err(LearnerError::NonFinite { what, value: v });
            }
        }
        let trust = self.trust(&x);
        let mut y = self.predict(&x)?.map(|v| v * trust);
        if self.step.queries == 0 {
            for (e, rule) in self.exploration.iter_mut().zip(&mut self.rules) {
                let v = rule.explore();
                if !v.is_finite() {
                    return Err(LearnerError::NonFinite {
                        what: "exploration",
                        value: v,
                    });
                }
                *e = v;
            }
        }
        for (v, e) in y.iter_mut().zip(self.exploration) {
            *v += e;
            if let Some(m) = self.config.max_offset {
                *v = v.clamp(-m, m);
            }
        }
        self.step.record(
            x,
            [[f64::NEG_INFINITY, f64::INFINITY]; PLANES],
            self.config.max_samples_per_step,
        );
        Ok(y)
    }

    /// The share of the offsets applied at `x` (1 without a trust region).
    fn trust(&self, x: &[f64; COUPLED_INPUTS]) -> f64 {
        let Some(k) = self.config.trust_region else {
            return 1.0;
        };
        let (lo, hi) = (
            self.config.prior.lo.to_array(),
            self.config.prior.hi.to_array(),
        );
        trust_share(k, x, &self.trained, |a| {
            self.trained[a]
                .population_std()
                .max(0.02 * (hi[a % 3] - lo[a % 3]))
        })
    }

    /// The offsets of `plane` (0 sagittal, 1 lateral) that could change the step at the last
    /// query (see [`FootstepLearner::set_reach`](super::learner::FootstepLearner::set_reach)).
    pub fn set_reach(&mut self, plane: usize, lo: f64, hi: f64) -> Result<(), LearnerError> {
        if !is_reach(lo, hi) || plane >= PLANES {
            return Err(LearnerError::InvalidConfig {
                param: "reach",
                reason: format!("needs plane 0 or 1 and lo <= hi, got {plane}: [{lo}, {hi}]"),
            });
        }
        if let Some(r) = self.step.last_reach_mut() {
            r[plane] = [lo, hi];
        }
        Ok(())
    }

    /// Forgets the current step without learning.
    pub fn discard_step(&mut self) {
        self.step.clear();
        self.exploration = [0.0; PLANES];
    }

    /// Ends the step with both planes' outcomes (sagittal, lateral): each plane's rule gives
    /// its G and the approximator is trained towards `y + eta (G_x, G_y)` at every recorded
    /// input, under the gain guard and anti-windup. Returns each plane's report. Checked
    /// rejections change nothing; an approximator failing mid-update discards the step.
    pub fn touch_down(
        &mut self,
        outcomes: [&StepOutcome; PLANES],
    ) -> Result<[TouchDownReport; PLANES], LearnerError> {
        self.end_step(outcomes, false)
    }

    /// The step in progress ended in a fall: with `learn_from_falls`, learns from it as from a
    /// touch-down with each plane's theta_E clamped as the sagittal learner clamps it;
    /// otherwise forgets it.
    pub fn fall(
        &mut self,
        outcomes: [&StepOutcome; PLANES],
    ) -> Result<Option<[TouchDownReport; PLANES]>, LearnerError> {
        if !self.config.learn_from_falls || self.step.inputs.is_empty() {
            self.discard_step();
            return Ok(None);
        }
        let clamped = outcomes.map(|o| clamped_at_fall(o, self.config.fall_theta_limit));
        match self.end_step([&clamped[0], &clamped[1]], true) {
            Ok(r) => Ok(Some(r)),
            Err(e) => {
                self.discard_step();
                Err(e)
            }
        }
    }

    fn end_step(
        &mut self,
        outcomes: [&StepOutcome; PLANES],
        fell: bool,
    ) -> Result<[TouchDownReport; PLANES], LearnerError> {
        for o in outcomes {
            for (what, v) in [
                ("theta_e", o.theta_e),
                ("theta_e_dot", o.theta_e_dot),
                ("f_e", o.f_e),
                ("f_r", o.f_r),
            ] {
                if !v.is_finite() {
                    return Err(LearnerError::NonFinite { what, value: v });
                }
            }
        }
        let mut raw = [0.0; PLANES];
        for k in 0..PLANES {
            raw[k] = self.rules[k].learn(outcomes[k], self.exploration[k], fell);
            if !raw[k].is_finite() {
                return Err(LearnerError::NonFinite {
                    what: "gradient G",
                    value: raw[k],
                });
            }
        }
        let dz = self.config.dead_zone;
        let g = raw.map(|g| g.signum() * (g.abs() - dz).max(0.0));
        let step = g.map(|g| self.config.eta * g);
        let first = self.step.first_trained(self.config.train_share);
        let samples = self.step.inputs.len() - first;
        let mut before = Vec::with_capacity(samples);
        let mut desired = Vec::with_capacity(samples);
        for (x, reach) in self.step.inputs[first..]
            .iter()
            .zip(&self.step.reach[first..])
        {
            let b = self.predict(x)?;
            let mut d = [0.0; PLANES];
            for k in 0..PLANES {
                let mut change = step[k] - self.config.leakage * b[k];
                if self.config.anti_windup {
                    change = windup(change, b[k], reach[k]);
                }
                if !(b[k] + change).is_finite() {
                    return Err(LearnerError::NonFinite {
                        what: "training target",
                        value: b[k] + change,
                    });
                }
                d[k] = change;
            }
            before.push(b);
            desired.push(d);
        }
        let asked: [f64; PLANES] =
            std::array::from_fn(|k| desired.iter().map(|d: &[f64; PLANES]| d[k] * d[k]).sum());
        let gain_of = |k: usize, response: f64| {
            if g[k] == 0.0 {
                0.0
            } else {
                response * step[k] / g[k]
            }
        };
        let guard = self
            .config
            .max_gain
            .filter(|_| asked.iter().any(|a| *a > 0.0));
        let inputs = &self.step.inputs[first..];
        let guarded = guarded_update(
            &mut self.approx,
            guard,
            |approx, scale| train_towards(approx, inputs, &before, &desired, scale),
            |approx| response(approx, inputs, &before, &desired, asked),
            |r: &[f64; PLANES]| {
                (0..PLANES)
                    .map(|k| gain_of(k, r[k]).abs())
                    .fold(0.0, f64::max)
            },
        );
        let Guarded {
            scale,
            first: first_response,
            applied: response,
        } = match guarded {
            Ok(g) => g,
            Err(GuardError::Apply(e)) => {
                self.discard_step();
                return Err(e);
            }
            Err(GuardError::Measure(e)) => return Err(e),
        };
        if scale > 0.0 {
            self.step.add_trained(first, &mut self.trained);
        }
        self.discard_step();
        Ok(std::array::from_fn(|k| TouchDownReport {
            gradient: raw[k],
            samples,
            response: first_response[k],
            gain: gain_of(k, response[k]),
            scale,
        }))
    }
}

/// Trains `approx` towards `before + scale * desired` at every input.
fn train_towards<A: FunctionApproximator>(
    approx: &mut A,
    inputs: &[[f64; COUPLED_INPUTS]],
    before: &[[f64; PLANES]],
    desired: &[[f64; PLANES]],
    scale: f64,
) -> Result<(), LearnerError> {
    for (applied, ((x, b), d)) in inputs.iter().zip(before).zip(desired).enumerate() {
        let target: [f64; PLANES] = std::array::from_fn(|k| b[k] + scale * d[k]);
        approx
            .update(x, &target)
            .map_err(|source| LearnerError::Approx { applied, source })?;
    }
    Ok(())
}

/// Per output, the share `<dy, d> / <d, d>` of the desired change the predictions at
/// `inputs` moved (0 where nothing was asked).
fn response<A: FunctionApproximator>(
    approx: &A,
    inputs: &[[f64; COUPLED_INPUTS]],
    before: &[[f64; PLANES]],
    desired: &[[f64; PLANES]],
    asked: [f64; PLANES],
) -> Result<[f64; PLANES], LearnerError> {
    let mut moved = [0.0; PLANES];
    for ((x, b), d) in inputs.iter().zip(before).zip(desired) {
        let y = predict_at(approx, x)?;
        for k in 0..PLANES {
            moved[k] += (y[k] - b[k]) * d[k];
        }
    }
    Ok(std::array::from_fn(|k| {
        if asked[k] == 0.0 {
            0.0
        } else {
            moved[k] / asked[k]
        }
    }))
}

/// The outputs `(dF, dW)` of `approx` at `x`, checked to be finite.
fn predict_at<A: FunctionApproximator>(
    approx: &A,
    x: &[f64; COUPLED_INPUTS],
) -> Result<[f64; PLANES], LearnerError> {
    let mut y = [0.0; PLANES];
    approx
        .predict(x, &mut y)
        .map_err(|source| LearnerError::Approx { applied: 0, source })?;
    if let Some(v) = y.iter().find(|v| !v.is_finite()) {
        return Err(LearnerError::NonFinite {
            what: "approximator prediction",
            value: *v,
        });
    }
    Ok(y)
}

impl<A: FunctionApproximator + Clone, R: LearningRule> FootstepPolicy for CoupledLearner<A, R> {
    fn learns(&self) -> LearnSet {
        LearnSet::of(&[StepParameter::StepX, StepParameter::StepY]).expect("two parameters")
    }
    fn offsets(
        &mut self,
        inputs: &PerParameter<LearnerInput>,
    ) -> Result<PerParameter<f64>, LearnerError> {
        let [df, dw] = self.query(inputs[StepParameter::StepX], inputs[StepParameter::StepY])?;
        Ok(PerParameter([df, dw, 0.0]))
    }
    fn set_reach(&mut self, reach: &PerParameter<[f64; 2]>) -> Result<(), LearnerError> {
        for (plane, p) in [StepParameter::StepX, StepParameter::StepY]
            .into_iter()
            .enumerate()
        {
            let [lo, hi] = reach[p];
            CoupledLearner::set_reach(self, plane, lo, hi)?;
        }
        Ok(())
    }
    fn touch_down(
        &mut self,
        outcomes: &PerParameter<StepOutcome>,
    ) -> Result<StepReports, LearnerError> {
        let [s, l] = CoupledLearner::touch_down(
            self,
            [
                &outcomes[StepParameter::StepX],
                &outcomes[StepParameter::StepY],
            ],
        )?;
        Ok(PerParameter([Some(s), Some(l), None]))
    }
    fn fall(&mut self, outcomes: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError> {
        Ok(
            match CoupledLearner::fall(
                self,
                [
                    &outcomes[StepParameter::StepX],
                    &outcomes[StepParameter::StepY],
                ],
            )? {
                Some([s, l]) => PerParameter([Some(s), Some(l), None]),
                None => StepReports::default(),
            },
        )
    }
    fn discard_step(&mut self) {
        CoupledLearner::discard_step(self)
    }
}
