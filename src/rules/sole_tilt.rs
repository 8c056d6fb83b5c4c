//! The ankle rule: the pendulum-cart gradient carried over to the support sole's tilt (its
//! pitch, `ankle-pitch`, or its roll, `ankle-roll`) through the LIPM.
//!
//! Derivation (LIPM in the rule's plane, `C = sqrt(g/h)`): at touch-down the pendulum-cart
//! error `G = theta_E - p_theta tanh(p_F F_E)` of eq. (5), read as a capture-point error, is
//! `e = h G` (m, positive: the capture point lies beyond where the foot landed, in the
//! direction the plane's theta_E leans). During the step the capture point moves away from the
//! centre of pressure `z` under the support foot as `d xi / dt = C (xi - z)`, so a shift `dz`
//! of the centre of pressure held over a step of duration `T` leaves the capture point
//! `(e^(C T) - 1) dz` less far out at touch-down. The sole's tilt offset `dA` (toe down
//! positive for the pitch; for the roll, the edge on the swing leg's side down, the side the
//! frontal plane is mirrored to) shifts the centre of pressure that way by about `l dA` while
//! it stays inside the sole (`l`, the sole's lever, m per rad). So
//! `de / d(dA) = -(e^(C T) - 1) l`, and the offset that would have cancelled the error (the
//! Gauss-Newton step on `e^2 / 2`, as eq. (6)'s dF moves by about the step error `h G` that
//! `G` stands for) is
//!
//! `G_A = h G / ((e^(C T) - 1) l)` (rad, per unit learning rate),
//!
//! which the learner adds as eq. (6) adds `G` to dF: a trunk still falling forward at
//! touch-down (`G > 0`) asks to press the toe harder in that state next time, one falling
//! backward (`G < 0`) the heel; sideways, a trunk still falling towards the swing leg's side
//! asks to press the sole's edge on that side. It has the sign of the paper's G, scaled:
//! within the sole the centre of pressure does what a longer (or wider) step does beyond it.
//! On the humanoid the pitch's lever is steep (0.02 rad moves the centre of pressure about
//! 0.04 m at first, then the body leans away and it comes back halfway within 0.15 s; test
//! `an_ankle_pitch_offset_moves_the_support_soles_centre_of_pressure`) and the sole's edges
//! are near (0.2 m ahead of the ankle, 0.1 m behind it), so `G_A` is about a third of `G`.
//! The roll's lever is measured the same way (test
//! `an_ankle_roll_offset_moves_the_support_soles_centre_of_pressure_sideways`); the sole's
//! edges lie 0.055 m to either side of the ankle.

use super::{LearningRule, PendulumCart, StepOutcome, StepTime, pendulum_height};
use serde::{Deserialize, Serialize};

/// `G_A = h G / ((e^(C T) - 1) l)`, `G` the pendulum-cart gradient, `h = g / C^2` (see the
/// module docs): the rule of the sole's pitch ([`SoleTilt::pitch`], the default) or of its
/// roll ([`SoleTilt::roll`]), which differ in the lever.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SoleTilt {
    /// LIPM constant `C = sqrt(g/h)` (1/s): the controller's.
    pub c: f64,
    /// The pendulum-cart error's trunk-angle tolerance (rad; eq. 5).
    pub p_theta: f64,
    /// The pendulum-cart error's step-error gain (1/m; eq. 5).
    pub p_f: f64,
    /// The step duration the centre of pressure acts over (s): the gait's period.
    pub step_time: f64,
    /// The sole's lever: how far the centre of pressure moves per radian of the sole's tilt
    /// offset within the sole (m/rad, > 0).
    pub lever: f64,
    /// Scale of `G_A` (1: the LIPM's step as written); with the learner's eta, the learning
    /// rate of the sole's tilt.
    pub scale: f64,
}

impl Default for SoleTilt {
    /// [`SoleTilt::pitch`].
    fn default() -> Self {
        SoleTilt::pitch()
    }
}

impl SoleTilt {
    /// The sole's lever for its roll on the humanoid (m/rad; see the module docs).
    pub const ROLL_LEVER: f64 = 1.5;

    /// The rule of the sole's pitch: the step-time rule's `C`, `p_theta` and `p_F`
    /// ([`StepTime::default`]), the default gait's period and the humanoid's lever for the
    /// pitch (see the module docs).
    pub fn pitch() -> Self {
        // The LIPM and the pendulum-cart error as the step-time rule reads them.
        let StepTime {
            c, p_theta, p_f, ..
        } = StepTime::default();
        SoleTilt {
            c,
            p_theta,
            p_f,
            step_time: 0.4,
            lever: 1.5,
            scale: 1.0,
        }
    }

    /// The rule of the sole's roll: [`Self::pitch`]'s, with the roll's lever
    /// ([`Self::ROLL_LEVER`]).
    pub fn roll() -> Self {
        SoleTilt {
            lever: Self::ROLL_LEVER,
            ..Self::pitch()
        }
    }

    /// `h / ((e^(C T) - 1) l)`: rad of `G_A` per unit of the pendulum-cart `G` (before
    /// `scale`), `h` the pendulum height ([`pendulum_height`]).
    pub fn factor(&self) -> f64 {
        pendulum_height(self.c) / ((self.c * self.step_time).exp_m1() * self.lever)
    }
}

impl LearningRule for SoleTilt {
    fn gradient(&self, step: &StepOutcome) -> f64 {
        let (p_theta, p_f) = (self.p_theta, self.p_f);
        self.scale * self.factor() * PendulumCart { p_theta, p_f }.gradient(step)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn outcome(theta_e: f64, f_e: f64) -> StepOutcome {
        StepOutcome {
            theta_e,
            theta_e_dot: 0.0,
            f_e,
            f_r: 0.0,
        }
    }

    #[test]
    fn falling_forward_presses_the_toe_and_backward_the_heel() {
        let r = SoleTilt::default();
        assert_eq!(r, SoleTilt::pitch());
        assert!(r.gradient(&outcome(0.2, 0.3)) > 0.0);
        assert!(r.gradient(&outcome(-0.2, -0.3)) < 0.0);
        assert_eq!(r.gradient(&outcome(0.0, 0.0)), 0.0);
    }

    #[test]
    fn the_gradient_is_the_pendulum_carts_times_the_lipm_factor() {
        let r = SoleTilt::pitch();
        let s = outcome(0.1, 0.02);
        let g = PendulumCart::default().gradient(&s);
        // docs/learner.md: G_A is a third of G (0.333) at C = 2.95, T = 0.4 s, l = 1.5 m/rad.
        let ratio = r.gradient(&s) / g;
        assert!((ratio - 0.333).abs() < 1e-3, "G_A / G = {ratio}");
        let factor = (9.81 / (2.95 * 2.95)) / (((2.95f64 * 0.4).exp() - 1.0) * 1.5);
        assert!((r.factor() - factor).abs() < 1e-12);
        assert!((r.gradient(&s) - factor * g).abs() < 1e-12);
        let doubled = SoleTilt { scale: 2.0, ..r };
        assert!((doubled.gradient(&s) - 2.0 * r.gradient(&s)).abs() < 1e-12);
        // A longer step lets the centre of pressure act longer: less pitch does as much.
        let longer = SoleTilt {
            step_time: 0.5,
            ..r
        };
        assert!(longer.factor() < r.factor());
    }
}
