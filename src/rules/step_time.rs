//! The step-time rule: the pendulum-cart gradient carried over to the step time T through the
//! LIPM.
//!
//! Derivation (sagittal LIPM, `C = sqrt(g/h)`): at touch-down the pendulum-cart error
//! `G = theta_E - p_theta tanh(p_F F_E)` of eq. (5) says how far the trunk still falls past the
//! new foot; read as a capture-point error it is `e = h G` (m, positive: the capture point lies
//! ahead of where the foot landed). During the step the capture point `xi` moves away from the
//! support's ZMP `z` as `d xi / dt = C (xi - z)`, so landing `dT` earlier leaves it
//! `C (xi - z) dT` less far, while the foot lands where the controller aims for the earlier
//! time. With `xi - z ~ F_hat + e` at touch-down (the realised step length plus what was still
//! missing), the squared error `e^2 / 2` changes with T as
//! `d(e^2/2)/dT = C e (F_hat + e)`, and the descent direction is
//!
//! `G_T = -C e (F_hat + e) = -C h G (F_hat + h G)` (s, per unit learning rate),
//!
//! which the learner adds as eq. (6) adds `G` to dF. After a forward push (`G > 0`,
//! `F_hat > 0`) and after a backward one (`G < 0`, `F_hat < 0`) it asks to step sooner; a
//! step that stopped the trunk short (`G` and `F_hat` of opposite sign, `|e| < |F_hat|`) asks
//! to step later. Stepping in place `F_hat` and `e` are small and `G_T` is second order in
//! them, so the nominal gait's timing is left alone.
//!
//! The frontal plane (the step time learned from the lean sideways, mirrored to the swing
//! leg's side) is the same pendulum with the width for the step: `F_hat` is the realised width
//! `W = 2 delta + F_E + F_R` (the outcome's `F_E + F_R` is the width beyond the stance in
//! place, `2 delta`), so `G_T = -C h G (W + h G)` with the frontal G. Stepping in place the
//! frontal G is about 0 and so is `G_T`; pushed towards the swing leg (`G > 0`) it asks to
//! step sooner; pushed a little towards the support leg (`-W < h G < 0`) to step later, the
//! capture point coming back inside; pushed beyond the support foot (`h G < -W`) sooner
//! again.

use super::{LearningRule, PendulumCart, StepOutcome, pendulum_height};
use serde::{Deserialize, Serialize};

/// `G_T = -C h G (F_hat + h G)`, `G` the pendulum-cart gradient, `h = g / C^2` (see the module
/// docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct StepTime {
    /// LIPM constant `C = sqrt(g/h)` (1/s): the controller's.
    pub c: f64,
    /// The pendulum-cart error's trunk-angle tolerance (rad; eq. 5).
    pub p_theta: f64,
    /// The pendulum-cart error's step-error gain (1/m; eq. 5).
    pub p_f: f64,
    /// Scale of `G_T` (1: the LIPM's derivative as written); with the learner's eta, the
    /// learning rate of the step time.
    pub scale: f64,
    /// The realised step where the outcome's `F_E + F_R` is 0 (m): 0 in the sagittal plane,
    /// the stance width in place `2 delta` in the frontal plane ([`Self::frontal`]).
    pub stance: f64,
}

impl Default for StepTime {
    /// The built-in humanoid's `C` ([`crate::robot::HUMANOID_C`]) and the paper's `p_theta`
    /// and `p_F`.
    fn default() -> Self {
        let pc = PendulumCart::default();
        StepTime {
            c: crate::robot::HUMANOID_C,
            p_theta: pc.p_theta,
            p_f: pc.p_f,
            scale: 1.0,
            stance: 0.0,
        }
    }
}

impl StepTime {
    /// The rule in the frontal plane, for a gait whose feet stand `stance` apart in place
    /// (m, the Capture Step controller's `2 delta`).
    pub fn frontal(stance: f64) -> Self {
        StepTime {
            stance,
            ..StepTime::default()
        }
    }

    /// The pendulum height `h = g / C^2` (m).
    pub fn height(&self) -> f64 {
        pendulum_height(self.c)
    }
}

impl LearningRule for StepTime {
    fn gradient(&self, step: &StepOutcome) -> f64 {
        let g = PendulumCart {
            p_theta: self.p_theta,
            p_f: self.p_f,
        }
        .gradient(step);
        let e = self.height() * g;
        let realised = self.stance + step.f_e + step.f_r;
        -self.scale * self.c * e * (realised + e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outcome(theta_e: f64, f_hat: f64) -> StepOutcome {
        StepOutcome {
            theta_e,
            theta_e_dot: 0.0,
            f_e: f_hat,
            f_r: 0.0,
        }
    }

    #[test]
    fn pushes_either_way_ask_to_step_sooner() {
        let r = StepTime::default();
        // Forward: leaning forward after a long forward step.
        assert!(r.gradient(&outcome(0.2, 0.3)) < 0.0);
        // Backward: leaning back after a backward step.
        assert!(r.gradient(&outcome(-0.2, -0.2)) < 0.0);
    }

    #[test]
    fn the_gradient_matches_the_formula_and_is_second_order_in_place() {
        let r = StepTime::default();
        let s = outcome(0.1, 0.25);
        let g = 0.1 - 0.15 * (30.0f64 * 0.25).tanh();
        let e = r.height() * g;
        assert!((r.gradient(&s) + 2.95 * e * (0.25 + e)).abs() < 1e-12);
        // Upright on the reference: nothing to learn.
        assert_eq!(r.gradient(&outcome(0.0, 0.0)), 0.0);
        // Small errors teach quadratically less.
        let small = r.gradient(&outcome(0.001, 0.0)).abs();
        let big = r.gradient(&outcome(0.01, 0.0)).abs();
        assert!((big / small - 100.0).abs() < 1e-6);
    }

    #[test]
    fn in_the_frontal_plane_the_width_is_the_step() {
        let r = StepTime::frontal(0.24);
        // In place: nothing to learn.
        assert_eq!(r.gradient(&outcome(0.0, 0.0)), 0.0);
        // Pushed towards the swing leg: sooner, more than the sagittal rule at the same error.
        let out = outcome(0.05, 0.0);
        assert!(r.gradient(&out) < StepTime::default().gradient(&out));
        assert!(r.gradient(&out) < 0.0);
        // The formula with the width for the step.
        let g = 0.05;
        let e = r.height() * g;
        assert!((r.gradient(&out) + 2.95 * e * (0.24 + e)).abs() < 1e-12);
        // Pushed a little towards the support leg: later; beyond the support foot: sooner.
        assert!(r.gradient(&outcome(-0.05, 0.0)) > 0.0);
        assert!(r.gradient(&outcome(-0.5, 0.0)) < 0.0);
    }

    #[test]
    fn a_step_that_stopped_the_trunk_short_asks_to_step_later() {
        // A long forward step and the trunk now leaning back a little.
        let r = StepTime::default();
        assert!(r.gradient(&outcome(-0.02, 0.3)) > 0.0);
    }
}
