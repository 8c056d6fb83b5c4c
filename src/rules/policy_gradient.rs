//! A model-free baseline: episodic REINFORCE with a running-mean baseline on a Gaussian policy
//! over the footstep offset dF, whose mean is the learner's approximator.

use super::{LearningRule, RuleError, StepOutcome};
use rand::SeedableRng;
use rand::rngs::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use serde::{Deserialize, Serialize};

/// The ChaCha stream the rule draws from, so that its perturbations are independent of other
/// generators seeded with the same run seed (the push schedules).
const STREAM: u64 = 0x5047_5f65_7870_6c72;

/// The parameters of [`PolicyGradient`]; the serde form inside [`super::RuleConfig`]
/// (`{"rule": "policy-gradient", "sigma": 0.02}`; missing fields take their defaults).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PolicyGradientParams {
    /// Standard deviation of the exploration perturbation eps added to dF for a whole step (m;
    /// finite, > 0). Default 0.02.
    pub sigma: f64,
    /// Trunk angle scale of the reward (rad; finite, > 0). Default 0.15 (the paper's p_theta).
    pub s_theta: f64,
    /// Step size error scale of the reward (m; finite, > 0). Default 1/30 (1 / the paper's p_F).
    pub s_f: f64,
    /// The reward of a step that ended in a fall is -`fall_penalty`, and no step costs more
    /// (finite, > 0). Default 10.
    pub fall_penalty: f64,
    /// Rate of the baseline's exponential running mean of the reward (in (0, 1]). Default 0.1.
    pub baseline_rate: f64,
    /// Step size of the ascent: G = scale (r - b) eps / sigma^2 (m^2 per unit reward; finite,
    /// > 0). Default 0.001.
    pub scale: f64,
}

impl Default for PolicyGradientParams {
    /// sigma = 0.02 m, s_theta = 0.15 rad, s_F = 1/30 m, fall penalty 10, baseline rate 0.1,
    /// scale 0.001 (docs/policy-gradient.md: how they were chosen).
    fn default() -> Self {
        PolicyGradientParams {
            sigma: 0.02,
            s_theta: 0.15,
            s_f: 1.0 / 30.0,
            fall_penalty: 10.0,
            baseline_rate: 0.1,
            scale: 0.001,
        }
    }
}

/// An error for parameter `param` with `value` and what it must be.
fn invalid(param: &'static str, must: &str, value: f64) -> RuleError {
    RuleError::InvalidParameter {
        param,
        reason: format!("must be {must}, got {value}"),
    }
}

impl PolicyGradientParams {
    /// Checks every parameter (see the fields).
    pub fn validate(&self) -> Result<(), RuleError> {
        for (param, value) in [
            ("sigma", self.sigma),
            ("s_theta", self.s_theta),
            ("s_f", self.s_f),
            ("fall_penalty", self.fall_penalty),
            ("scale", self.scale),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(invalid(param, "finite and > 0", value));
            }
        }
        if !(self.baseline_rate > 0.0 && self.baseline_rate <= 1.0) {
            return Err(invalid("baseline_rate", "in (0, 1]", self.baseline_rate));
        }
        Ok(())
    }
}

/// What [`PolicyGradient`] keeps between steps: its seed, the position of its generator, its
/// baseline and the number of steps learned from (the form of [`LearningRule::state`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PolicyGradientState {
    /// The seed of the last [`LearningRule::reseed`] (0 if never reseeded).
    pub seed: u64,
    /// The generator's word position, high and low 64 bits.
    pub word_pos: [u64; 2],
    /// The baseline b (meaningless while `steps` is 0).
    pub baseline: f64,
    /// Steps learned from.
    pub steps: u64,
}

/// REINFORCE with a baseline (Williams 1992) on the Gaussian policy dF = mean(x) + eps,
/// eps ~ N(0, sigma^2) drawn once per step, whose mean is the learner's approximator.
///
/// The reward of a step is r = -min((theta_E / s_theta)^2 + (F_E / s_F)^2, fall_penalty), or
/// -`fall_penalty` if it ended in a fall (no step is worse than a fall, and the bounded reward
/// bounds G); the baseline b is the exponential running mean of r (the first reward
/// initialises it). [`LearningRule::learn`] returns G = scale (r - b) eps / sigma^2, so that
/// the learner's update (the mean at the step's inputs moves by eta G, gain-guarded) is the
/// REINFORCE ascent on the expected reward. [`LearningRule::gradient`] alone is 0: the rule
/// learns nothing from an outcome without its perturbation.
#[derive(Debug)]
pub struct PolicyGradient {
    params: PolicyGradientParams,
    seed: u64,
    rng: ChaCha8Rng,
    baseline: f64,
    steps: u64,
}

impl Clone for PolicyGradient {
    /// The same parameters, state and generator position.
    fn clone(&self) -> Self {
        let mut rng = Self::generator(self.seed);
        rng.set_word_pos(self.rng.get_word_pos());
        PolicyGradient {
            params: self.params,
            seed: self.seed,
            rng,
            baseline: self.baseline,
            steps: self.steps,
        }
    }
}

impl Default for PolicyGradient {
    /// The default parameters, seed 0.
    fn default() -> Self {
        Self::unchecked(PolicyGradientParams::default())
    }
}

impl PolicyGradient {
    /// The rule with `params` (validated), seed 0.
    pub fn new(params: PolicyGradientParams) -> Result<Self, RuleError> {
        params.validate()?;
        Ok(Self::unchecked(params))
    }

    fn unchecked(params: PolicyGradientParams) -> Self {
        PolicyGradient {
            params,
            seed: 0,
            rng: Self::generator(0),
            baseline: 0.0,
            steps: 0,
        }
    }

    fn generator(seed: u64) -> ChaCha8Rng {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(STREAM);
        rng
    }

    /// The parameters.
    pub fn params(&self) -> &PolicyGradientParams {
        &self.params
    }

    /// The baseline b, `None` before the first step learned from.
    pub fn baseline(&self) -> Option<f64> {
        (self.steps > 0).then_some(self.baseline)
    }

    /// The reward of a step: -min((theta_E / s_theta)^2 + (F_E / s_F)^2, fall_penalty), or
    /// -`fall_penalty` if `fell` (NaN if the outcome is not finite).
    pub fn reward(&self, step: &StepOutcome, fell: bool) -> f64 {
        if fell {
            -self.params.fall_penalty
        } else if !(step.theta_e.is_finite() && step.f_e.is_finite()) {
            f64::NAN
        } else {
            let a = step.theta_e / self.params.s_theta;
            let e = step.f_e / self.params.s_f;
            -(a * a + e * e).min(self.params.fall_penalty)
        }
    }

    /// The state as [`LearningRule::state`] serializes it.
    pub fn snapshot(&self) -> PolicyGradientState {
        let pos = self.rng.get_word_pos();
        PolicyGradientState {
            seed: self.seed,
            word_pos: [(pos >> 64) as u64, pos as u64],
            baseline: self.baseline,
            steps: self.steps,
        }
    }

    /// Continues from `state` (written by [`Self::snapshot`]); a non-finite baseline is an
    /// error and leaves the rule as it was.
    pub fn restore(&mut self, state: &PolicyGradientState) -> Result<(), RuleError> {
        if !state.baseline.is_finite() {
            return Err(RuleError::InvalidState(format!(
                "baseline must be finite, got {}",
                state.baseline
            )));
        }
        let mut rng = Self::generator(state.seed);
        rng.set_word_pos((u128::from(state.word_pos[0]) << 64) | u128::from(state.word_pos[1]));
        self.seed = state.seed;
        self.rng = rng;
        self.baseline = state.baseline;
        self.steps = state.steps;
        Ok(())
    }
}

impl LearningRule for PolicyGradient {
    /// 0: without the step's perturbation there is no estimate (see [`LearningRule::learn`]).
    fn gradient(&self, _step: &StepOutcome) -> f64 {
        0.0
    }

    /// Restarts the perturbation sequence from `seed` (the baseline is kept).
    fn reseed(&mut self, seed: u64) {
        self.seed = seed;
        self.rng = Self::generator(seed);
    }

    /// eps = sigma z, z a standard normal draw.
    fn explore(&mut self) -> f64 {
        let z: f64 = StandardNormal.sample(&mut self.rng);
        self.params.sigma * z
    }

    /// G = scale (r - b) eps / sigma^2, then b moves toward r. A non-finite reward returns NaN
    /// and changes nothing.
    fn learn(&mut self, step: &StepOutcome, exploration: f64, fell: bool) -> f64 {
        let r = self.reward(step, fell);
        if !r.is_finite() || !exploration.is_finite() {
            return f64::NAN;
        }
        if self.steps == 0 {
            self.baseline = r;
        }
        let advantage = r - self.baseline;
        self.baseline += self.params.baseline_rate * (r - self.baseline);
        self.steps = self.steps.saturating_add(1);
        let sigma = self.params.sigma;
        self.params.scale * advantage * exploration / (sigma * sigma)
    }

    fn state(&self) -> Option<serde_json::Value> {
        serde_json::to_value(self.snapshot()).ok()
    }

    fn set_state(&mut self, state: &serde_json::Value) -> Result<(), RuleError> {
        let state = PolicyGradientState::deserialize(state)
            .map_err(|e| RuleError::InvalidState(e.to_string()))?;
        self.restore(&state)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn upright() -> StepOutcome {
        StepOutcome::default()
    }

    #[test]
    fn reward_and_gradient_by_hand() {
        let mut pg = PolicyGradient::new(PolicyGradientParams {
            sigma: 0.02,
            scale: 0.001,
            ..PolicyGradientParams::default()
        })
        .unwrap();
        let step = StepOutcome {
            theta_e: 0.15,
            f_e: 1.0 / 30.0,
            ..StepOutcome::default()
        };
        assert!((pg.reward(&step, false) + 2.0).abs() < 1e-12);
        assert_eq!(pg.reward(&step, true), -10.0);
        assert_eq!(pg.gradient(&step), 0.0);
        // the first step sets the baseline: no advantage
        assert_eq!(pg.learn(&upright(), 0.01, false), 0.0);
        assert_eq!(pg.baseline(), Some(0.0));
        // r = -2, b = 0: G = 0.001 * -2 * 0.01 / 0.0004 = -0.05; b -> -0.2
        let g = pg.learn(&step, 0.01, false);
        assert!((g + 0.05).abs() < 1e-12, "{g}");
        assert!((pg.baseline().unwrap() + 0.2).abs() < 1e-12);
        // a fall with a negative perturbation asks for a larger offset
        assert!(pg.learn(&step, -0.01, true) > 0.0);
        // no step costs more than a fall
        let wild = StepOutcome {
            f_e: 3.0,
            ..StepOutcome::default()
        };
        assert_eq!(pg.reward(&wild, false), -10.0);
    }

    #[test]
    fn non_finite_input_changes_nothing() {
        let mut pg = PolicyGradient::default();
        pg.learn(&upright(), 0.01, false);
        let before = pg.snapshot();
        let nan = StepOutcome {
            theta_e: f64::NAN,
            ..StepOutcome::default()
        };
        assert!(pg.learn(&nan, 0.01, false).is_nan());
        assert!(pg.learn(&upright(), f64::INFINITY, false).is_nan());
        assert_eq!(pg.snapshot(), before);
    }

    #[test]
    fn state_round_trips_and_bad_state_is_rejected() {
        let mut pg = PolicyGradient::default();
        pg.reseed(9);
        for _ in 0..5 {
            let eps = pg.explore();
            pg.learn(&upright(), eps, false);
        }
        let state = pg.state().unwrap();
        let mut other = PolicyGradient::default();
        other.set_state(&state).unwrap();
        assert_eq!(other.snapshot(), pg.snapshot());
        for _ in 0..5 {
            assert_eq!(other.explore().to_bits(), pg.explore().to_bits());
        }
        let before = other.snapshot();
        for bad in [
            serde_json::json!({"seed": 1}),
            serde_json::json!({"seed": 1, "word_pos": [0, 0], "baseline": 0.0, "steps": 0, "x": 1}),
            serde_json::json!(3),
        ] {
            assert!(matches!(
                other.set_state(&bad),
                Err(RuleError::InvalidState(_))
            ));
        }
        let nan = PolicyGradientState {
            baseline: f64::NAN,
            ..before
        };
        assert!(matches!(
            other.restore(&nan),
            Err(RuleError::InvalidState(_))
        ));
        assert_eq!(other.snapshot(), before);
    }
}
