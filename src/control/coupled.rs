//! The coupled variant of [`TwoPlanes`](super::two_planes::TwoPlanes): one learner for both
//! planes, with two outputs (dF, dW) over both planes' inputs.
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
//! The walker calls it through [`FootstepPolicy::offsets`], [`FootstepPolicy::touch_downs`] and
//! [`FootstepPolicy::falls`], which hand over both planes at once. Through the one-plane
//! methods ([`FootstepPolicy::offset`] and the others a sagittal walker calls) it is a sagittal
//! learner with the lateral plane at rest (its inputs and outcome zero, no width offset).

use super::learner::{
    GUARD_RETRIES, LearnerConfig, LearnerError, LearnerInput, TouchDownReport, TrustFallback,
    is_reach, radical_inverse, windup,
};
use super::walker::FootstepPolicy;
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
    /// Inputs recorded in this step (at most `max_samples_per_step`; thinned as the sagittal
    /// learner's are).
    recorded: Vec<[f64; COUPLED_INPUTS]>,
    /// Per recorded input, each plane's reach.
    reach: Vec<[[f64; 2]; PLANES]>,
    last_recorded: bool,
    stride: usize,
    queries: usize,
    /// Mean and std of the trained inputs per axis (the trust region).
    trained: [MeanStd; COUPLED_INPUTS],
    /// Each plane's exploration perturbation of this step.
    exploration: [f64; PLANES],
}

impl<A: FunctionApproximator, R: LearningRule> std::fmt::Debug for CoupledLearner<A, R> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CoupledLearner")
            .field("config", &self.config)
            .field("recorded", &self.recorded.len())
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
        let n = config.max_samples_per_step;
        let mut learner = CoupledLearner {
            approx,
            rules,
            config,
            recorded: Vec::with_capacity(n),
            reach: Vec::with_capacity(n),
            last_recorded: false,
            stride: 1,
            queries: 0,
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
        let mut y = [0.0; PLANES];
        self.approx
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
        if self.queries == 0 {
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
        self.record(x);
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
        let mut z: f64 = 0.0;
        for (a, (&xa, t)) in x.iter().zip(&self.trained).enumerate() {
            if t.count() == 0 {
                return 0.0;
            }
            let std = t.population_std().max(0.02 * (hi[a % 3] - lo[a % 3]));
            z = z.max((xa - t.mean()).abs() / std);
        }
        ((1.5 * k - z) / (0.5 * k)).clamp(0.0, 1.0)
    }

    /// Records `x`, keeping at most `max_samples_per_step` evenly spread over the step.
    fn record(&mut self, x: [f64; COUPLED_INPUTS]) {
        self.last_recorded = false;
        if self.queries.is_multiple_of(self.stride) {
            if self.recorded.len() == self.config.max_samples_per_step {
                let mut keep = 0;
                for i in (0..self.recorded.len()).step_by(2) {
                    self.recorded[keep] = self.recorded[i];
                    self.reach[keep] = self.reach[i];
                    keep += 1;
                }
                self.recorded.truncate(keep);
                self.reach.truncate(keep);
                self.stride *= 2;
            }
            if self.queries.is_multiple_of(self.stride) {
                self.recorded.push(x);
                self.reach
                    .push([[f64::NEG_INFINITY, f64::INFINITY]; PLANES]);
                self.last_recorded = true;
            }
        }
        self.queries += 1;
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
        if self.last_recorded
            && let Some(r) = self.reach.last_mut()
        {
            r[plane] = [lo, hi];
        }
        Ok(())
    }

    /// Forgets the current step without learning.
    pub fn discard_step(&mut self) {
        self.recorded.clear();
        self.reach.clear();
        self.last_recorded = false;
        self.stride = 1;
        self.queries = 0;
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
        if !self.config.learn_from_falls || self.recorded.is_empty() {
            self.discard_step();
            return Ok(None);
        }
        let lim = self.config.fall_theta_limit;
        let clamped = outcomes.map(|o| StepOutcome {
            theta_e: o.theta_e.clamp(-lim, lim),
            theta_e_dot: o.theta_e_dot.clamp(-10.0 * lim, 10.0 * lim),
            ..*o
        });
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
        let n = self.recorded.len();
        let keep = ((n as f64 * self.config.train_share).ceil() as usize).clamp(1, n.max(1));
        let first = n.saturating_sub(keep);
        let mut before = Vec::with_capacity(n - first);
        let mut desired = Vec::with_capacity(n - first);
        for (x, reach) in self.recorded[first..].iter().zip(&self.reach[first..]) {
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
        let original = guard.map(|_| self.approx.clone());
        let mut scale = 1.0;
        let mut first_response = [0.0; PLANES];
        let mut response = [0.0; PLANES];
        for attempt in 0..=GUARD_RETRIES {
            if attempt > 0
                && let Some(o) = &original
            {
                self.approx = o.clone();
            }
            if let Err(e) = self.apply(first, &before, &desired, scale) {
                self.discard_step();
                return Err(e);
            }
            response = self.response(first, &before, &desired, asked)?;
            if attempt == 0 {
                first_response = response;
            }
            let worst = (0..PLANES)
                .map(|k| gain_of(k, response[k]).abs())
                .fold(0.0, f64::max);
            match guard {
                Some(limit) if worst > limit => {
                    if attempt == GUARD_RETRIES {
                        if let Some(o) = original {
                            self.approx = o;
                        }
                        scale = 0.0;
                        response = [0.0; PLANES];
                        break;
                    }
                    scale *= 0.95 * limit / worst;
                }
                _ => break,
            }
        }
        if scale > 0.0 {
            for x in &self.recorded[first..] {
                for (t, v) in self.trained.iter_mut().zip(x) {
                    t.push(*v);
                }
            }
        }
        self.discard_step();
        Ok(std::array::from_fn(|k| TouchDownReport {
            gradient: raw[k],
            samples: n - first,
            response: first_response[k],
            gain: gain_of(k, response[k]),
            scale,
        }))
    }

    /// Trains towards `before + scale * desired` at the recorded inputs from `first` on.
    fn apply(
        &mut self,
        first: usize,
        before: &[[f64; PLANES]],
        desired: &[[f64; PLANES]],
        scale: f64,
    ) -> Result<(), LearnerError> {
        for (applied, ((x, b), d)) in self.recorded[first..]
            .iter()
            .zip(before)
            .zip(desired)
            .enumerate()
        {
            let target: [f64; PLANES] = std::array::from_fn(|k| b[k] + scale * d[k]);
            self.approx
                .update(x, &target)
                .map_err(|source| LearnerError::Approx { applied, source })?;
        }
        Ok(())
    }

    /// Per output, the share `<dy, d> / <d, d>` of the desired change the predictions moved.
    fn response(
        &self,
        first: usize,
        before: &[[f64; PLANES]],
        desired: &[[f64; PLANES]],
        asked: [f64; PLANES],
    ) -> Result<[f64; PLANES], LearnerError> {
        let mut moved = [0.0; PLANES];
        for ((x, b), d) in self.recorded[first..].iter().zip(before).zip(desired) {
            let y = self.predict(x)?;
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
}

/// A plane at rest: the outcome a one-plane call assumes for the other plane.
const AT_REST: StepOutcome = StepOutcome {
    theta_e: 0.0,
    theta_e_dot: 0.0,
    f_e: 0.0,
    f_r: 0.0,
};

impl<A: FunctionApproximator + Clone, R: LearningRule> FootstepPolicy for CoupledLearner<A, R> {
    fn offsets(
        &mut self,
        sagittal: LearnerInput,
        lateral: LearnerInput,
    ) -> Result<(f64, Option<f64>), LearnerError> {
        let [df, dw] = self.query(sagittal, lateral)?;
        Ok((df, Some(dw)))
    }
    fn touch_downs(
        &mut self,
        sagittal: &StepOutcome,
        lateral: &StepOutcome,
    ) -> Result<(TouchDownReport, Option<TouchDownReport>), LearnerError> {
        let [s, l] = self.touch_down([sagittal, lateral])?;
        Ok((s, Some(l)))
    }
    fn falls(
        &mut self,
        sagittal: &StepOutcome,
        lateral: &StepOutcome,
    ) -> Result<(Option<TouchDownReport>, Option<TouchDownReport>), LearnerError> {
        Ok(match self.fall([sagittal, lateral])? {
            Some([s, l]) => (Some(s), Some(l)),
            None => (None, None),
        })
    }
    fn offset(&mut self, input: LearnerInput) -> Result<f64, LearnerError> {
        Ok(self.query(input, LearnerInput::default())?[0])
    }
    fn set_reach(&mut self, lo: f64, hi: f64) -> Result<(), LearnerError> {
        CoupledLearner::set_reach(self, 0, lo, hi)
    }
    fn touch_down(&mut self, outcome: &StepOutcome) -> Result<TouchDownReport, LearnerError> {
        Ok(CoupledLearner::touch_down(self, [outcome, &AT_REST])?[0])
    }
    fn fall(&mut self, outcome: &StepOutcome) -> Result<Option<TouchDownReport>, LearnerError> {
        Ok(CoupledLearner::fall(self, [outcome, &AT_REST])?.map(|[s, _]| s))
    }
    fn discard_step(&mut self) {
        CoupledLearner::discard_step(self)
    }
    fn set_lateral_reach(&mut self, lo: f64, hi: f64) -> Result<(), LearnerError> {
        CoupledLearner::set_reach(self, 1, lo, hi)
    }
    fn discard_lateral_step(&mut self) {
        CoupledLearner::discard_step(self)
    }
}
