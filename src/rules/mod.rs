//! Learning rules: from what happened in a step to the gradient G that trains the learner.
//!
//! The paper's rule is [`PendulumCart`] (eq. 5). Every rule sees the same [`StepOutcome`],
//! measured at touch-down, and returns one number: how much larger (G > 0) the step taken
//! under the conditions seen during that step should have been.

//!
//! | rule | G | what it ablates |
//! |---|---|---|
//! | [`PendulumCart`] | theta_E - p_theta tanh(p_F F_E) | the paper's rule |
//! | [`BalanceOnly`] | theta_E | drops reference tracking |
//! | [`TrackingOnly`] | -p_theta tanh(p_F F_E) | drops balance |
//! | [`Linear`] | theta_E - p_theta p_F F_E | drops the saturation |
//! | [`RateDamped`] | theta_E + k theta_E_dot - p_theta tanh(p_F F_E) | adds the trunk rate |
//! | [`PolicyGradient`] | (r - b) eps / sigma^2 * scale | model-free baseline (REINFORCE) |
//!
//! A gradient rule implements only [`LearningRule::gradient`]. A rule that explores (a
//! reinforcement-learning rule such as [`PolicyGradient`]) also implements the provided methods
//! [`LearningRule::reseed`], [`LearningRule::explore`], [`LearningRule::learn`] and, so that a
//! saved learner continues bit for bit, [`LearningRule::state`] and
//! [`LearningRule::set_state`]; their defaults leave a gradient rule exactly as it was.
//!
//! [`RuleConfig`] is the serde form of any of them (selected by a [`RuleKind`] name on the
//! command line) and builds a validated `Box<dyn LearningRule>`.

mod balance_only;
mod config;
mod linear;
mod pendulum_cart;
mod policy_gradient;
mod rate_damped;
mod sole_tilt;
mod step_time;
mod tracking_only;

pub use balance_only::BalanceOnly;
pub use config::{RuleConfig, RuleError, RuleKind};
pub use linear::Linear;
pub use pendulum_cart::PendulumCart;
pub use policy_gradient::{PolicyGradient, PolicyGradientParams, PolicyGradientState};
pub use rate_damped::RateDamped;
pub use sole_tilt::SoleTilt;
pub use step_time::StepTime;
pub use tracking_only::TrackingOnly;

use serde::{Deserialize, Serialize};

/// What the trainer measures at the touch-down that ends a step.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct StepOutcome {
    /// Trunk deviation angle theta_E = theta_hat - theta_R (rad), eq. (2); positive = leaning forward.
    pub theta_e: f64,
    /// Its rate (rad/s).
    pub theta_e_dot: f64,
    /// Step size error F_E = F_hat - F_R (m), eq. (1).
    pub f_e: f64,
    /// The reference step size F_R (m) in force during the step.
    pub f_r: f64,
}

/// A rule that turns a step's outcome into the learning gradient G.
///
/// Only [`Self::gradient`] is required. The provided methods let a rule explore: the learner
/// calls [`Self::explore`] once at the first query of every step and adds the perturbation it
/// returns to every offset of that step, then calls [`Self::learn`] at the step's end with the
/// outcome, that perturbation and whether the step ended in a fall. Their defaults (no
/// perturbation, G = [`Self::gradient`], no state) keep a gradient rule unchanged bit for bit.
pub trait LearningRule: Send + Sync {
    /// The gradient G for the step that just ended.
    fn gradient(&self, step: &StepOutcome) -> f64;

    /// Seeds the rule's randomness (the learner of a run passes the run's seed). Default: none.
    fn reseed(&mut self, seed: u64) {
        let _ = seed;
    }

    /// The perturbation of the offset (m) for the step that starts now, held for the whole
    /// step. Default: 0 (no exploration).
    fn explore(&mut self) -> f64 {
        0.0
    }

    /// The G to train with for the step that just ended: `exploration` is the perturbation
    /// [`Self::explore`] returned for it (0 if the step made no query) and `fell` whether it
    /// ended in a fall. Default: [`Self::gradient`].
    fn learn(&mut self, step: &StepOutcome, exploration: f64, fell: bool) -> f64 {
        let _ = (exploration, fell);
        self.gradient(step)
    }

    /// The rule's state (e.g. its baseline and random generator) for a learner's checkpoint;
    /// `None` for a stateless rule (the default).
    fn state(&self) -> Option<serde_json::Value> {
        None
    }

    /// Restores a state written by [`Self::state`]. Default: an error, the rule keeps none.
    fn set_state(&mut self, state: &serde_json::Value) -> Result<(), RuleError> {
        let _ = state;
        Err(RuleError::InvalidState(
            "this rule keeps no state".to_string(),
        ))
    }
}

impl<R: LearningRule + ?Sized> LearningRule for Box<R> {
    fn gradient(&self, step: &StepOutcome) -> f64 {
        (**self).gradient(step)
    }
    fn reseed(&mut self, seed: u64) {
        (**self).reseed(seed)
    }
    fn explore(&mut self) -> f64 {
        (**self).explore()
    }
    fn learn(&mut self, step: &StepOutcome, exploration: f64, fell: bool) -> f64 {
        (**self).learn(step, exploration, fell)
    }
    fn state(&self) -> Option<serde_json::Value> {
        (**self).state()
    }
    fn set_state(&mut self, state: &serde_json::Value) -> Result<(), RuleError> {
        (**self).set_state(state)
    }
}

/// The LIPM's pendulum height `h = g / C^2` (m) for its constant `C = sqrt(g/h)` (1/s): what
/// turns the pendulum-cart error G into a capture-point error `h G` for the rules derived from
/// the LIPM ([`StepTime`], [`SoleTilt`]).
pub fn pendulum_height(c: f64) -> f64 {
    crate::robot::STANDARD_GRAVITY / (c * c)
}

/// The saturated tracking term p_theta tanh(p_F F_E) of eq. (5), shared by every rule that
/// tracks the reference with a bounded pull: |result| <= p_theta for any F_E.
pub fn saturated_tracking(p_theta: f64, p_f: f64, f_e: f64) -> f64 {
    p_theta * (p_f * f_e).tanh()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use strum::VariantArray;

    fn outcome(theta_e: f64, theta_e_dot: f64, f_e: f64) -> StepOutcome {
        StepOutcome {
            theta_e,
            theta_e_dot,
            f_e,
            f_r: 0.1,
        }
    }

    #[test]
    fn paper_rule_matches_eq5_by_hand() {
        let rule = PendulumCart::default();
        // theta_E = 0.2, F_E = 0.01: 0.2 - 0.15 tanh(0.3)
        let g = rule.gradient(&outcome(0.2, 5.0, 0.01));
        assert!((g - (0.2 - 0.15 * 0.291_312_612_451_590_7)).abs() < 1e-12);
        // leaning forward with no step error asks for a larger step
        assert!(rule.gradient(&outcome(0.1, 0.0, 0.0)) > 0.0);
        // overshooting the reference while upright asks for a smaller step
        assert!(rule.gradient(&outcome(0.0, 0.0, 0.05)) < 0.0);
        // a large tilt dominates any step error
        assert!(rule.gradient(&outcome(0.5, 0.0, 10.0)) > 0.0);
    }

    proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig { rng_seed: proptest::test_runner::RngSeed::Fixed(12), failure_persistence: None, ..proptest::prelude::ProptestConfig::default() })]
        #[test]
        fn tracking_term_is_bounded_and_opposes_the_error(
            p_theta in 0.0..1.0f64, p_f in 0.0..100.0f64, f_e in -10.0..10.0f64,
        ) {
            let t = saturated_tracking(p_theta, p_f, f_e);
            prop_assert!(t.abs() <= p_theta);
            let g = TrackingOnly { p_theta, p_f }.gradient(&outcome(0.3, 1.0, f_e));
            prop_assert!(g.abs() <= p_theta);
            prop_assert!(g * f_e <= 0.0);
        }

        #[test]
        fn variants_reduce_to_each_other(
            theta in -1.0..1.0f64, rate in -5.0..5.0f64, f_e in -0.5..0.5f64,
            p_theta in 0.0..0.5f64, p_f in 0.0..60.0f64, k in 0.0..1.0f64,
        ) {
            let s = outcome(theta, rate, f_e);
            let pc = PendulumCart { p_theta, p_f }.gradient(&s);
            // pendulum-cart = balance-only + tracking-only, exactly as written in eq. (5)
            let sum = BalanceOnly.gradient(&s) + TrackingOnly { p_theta, p_f }.gradient(&s);
            prop_assert!((pc - sum).abs() <= 1e-12);
            // rate-damped with k = 0 is pendulum-cart; k adds exactly k * rate
            prop_assert_eq!(RateDamped { p_theta, p_f, k: 0.0 }.gradient(&s), pc);
            let rd = RateDamped { p_theta, p_f, k }.gradient(&s);
            prop_assert!((rd - pc - k * rate).abs() <= 1e-12);
            // p_theta = 0 removes tracking from every variant
            prop_assert_eq!(PendulumCart { p_theta: 0.0, p_f }.gradient(&s), theta);
            prop_assert_eq!(Linear { p_theta: 0.0, p_f }.gradient(&s), theta);
            // linear's tracking pull is at least the saturated one (|tanh u| <= |u|), same sign
            let lin = Linear { p_theta, p_f }.gradient(&s);
            prop_assert!((theta - lin).abs() + 1e-12 >= (theta - pc).abs());
            prop_assert!((theta - lin) * (theta - pc) >= 0.0);
        }

        #[test]
        fn linear_matches_pendulum_cart_for_small_errors(
            theta in -1.0..1.0f64, f_e in -1e-4..1e-4f64,
        ) {
            let s = outcome(theta, 0.0, f_e);
            let pc = PendulumCart::default().gradient(&s);
            let lin = Linear::default().gradient(&s);
            // tanh(u) = u - u^3/3 + ..., |u| <= 3e-3: difference <= 0.15 * u^3 / 3 < 1e-8
            prop_assert!((pc - lin).abs() < 1e-8);
        }

        #[test]
        fn balance_term_is_monotone_in_the_tilt(
            a in -1.0..1.0f64, b in -1.0..1.0f64, f_e in -0.5..0.5f64, rate in -3.0..3.0f64,
        ) {
            let (lo, hi) = if a < b { (a, b) } else { (b, a) };
            for rule in RuleKind::VARIANTS.iter().map(|&k| RuleConfig::from(k).build().unwrap()) {
                prop_assert!(rule.gradient(&outcome(lo, rate, f_e)) <= rule.gradient(&outcome(hi, rate, f_e)));
            }
        }
    }
}
