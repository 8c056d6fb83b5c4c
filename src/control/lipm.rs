//! The one-dimensional linear inverted pendulum (LIPM) in closed form.
//!
//! A point mass at constant height h above a pivot (the ZMP) `Z` accelerates away from it:
//! `x'' = C^2 (x - Z)` with `C = sqrt(g / h)`. For a constant pivot the motion is
//!
//! ```text
//! x(t) = Z + (x0 - Z) cosh(Ct) + (v0 / C) sinh(Ct)
//! v(t) = (x0 - Z) C sinh(Ct) + v0 cosh(Ct)
//! ```
//!
//! and the orbital energy `E = (v^2 - C^2 (x - Z)^2) / 2` is conserved. Every query here is a
//! closed-form answer to a question about that motion: where the mass is after `t`, when it
//! reaches a location or a velocity, which pivot brings it to a target at a given time, and
//! where to place a new pivot so that the mass passes through a given state.
//!
//! Positions are relative to whatever origin the caller uses (the Capture Step controller uses
//! the support foot's sole centre); the pivot is given in the same coordinates.

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Position and velocity of the pendulum mass along one axis (m, m/s).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct LipmState {
    /// Position (m).
    pub pos: f64,
    /// Velocity (m/s).
    pub vel: f64,
}

impl LipmState {
    /// A state from position and velocity.
    pub fn new(pos: f64, vel: f64) -> Self {
        LipmState { pos, vel }
    }

    /// Whether both numbers are finite.
    pub fn is_finite(&self) -> bool {
        self.pos.is_finite() && self.vel.is_finite()
    }
}

/// A rejected pendulum constant.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum LipmError {
    /// `C` (or the height/gravity it came from) was not a positive finite number.
    #[error("invalid pendulum constant: {0}")]
    InvalidConstant(String),
}

/// A 1-D linear inverted pendulum with constant `C = sqrt(g/h)` (1/s).
///
/// Note: the authors' released code stores `C^2` (their `mgC`) where this type stores `C`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Lipm {
    c: f64,
}

impl Lipm {
    /// A pendulum with constant `c = sqrt(g/h)` (1/s); `c` must be positive and finite.
    pub fn new(c: f64) -> Result<Self, LipmError> {
        if c.is_finite() && c > 0.0 {
            Ok(Lipm { c })
        } else {
            Err(LipmError::InvalidConstant(format!(
                "C must be positive and finite, got {c}"
            )))
        }
    }

    /// A pendulum of height `height` (m) under gravity `gravity` (m/s^2): `C = sqrt(g/h)`.
    pub fn from_height(height: f64, gravity: f64) -> Result<Self, LipmError> {
        if !(height.is_finite() && height > 0.0 && gravity.is_finite() && gravity > 0.0) {
            return Err(LipmError::InvalidConstant(format!(
                "height and gravity must be positive and finite, got h = {height}, g = {gravity}"
            )));
        }
        Lipm::new((gravity / height).sqrt())
    }

    /// The constant `C` (1/s).
    pub fn c(&self) -> f64 {
        self.c
    }

    /// The state after time `t` (may be negative) with the pivot at `zmp`.
    pub fn state_after(&self, s: LipmState, zmp: f64, t: f64) -> LipmState {
        let (sh, ch) = sinh_cosh(self.c * t);
        let x = s.pos - zmp;
        LipmState {
            pos: zmp + x * ch + s.vel / self.c * sh,
            vel: x * self.c * sh + s.vel * ch,
        }
    }

    /// Orbital energy `(v^2 - C^2 (x - zmp)^2) / 2` of `s` about the pivot `zmp`.
    ///
    /// Negative: the mass turns back before passing over the pivot; positive: it passes over.
    pub fn energy(&self, s: LipmState, zmp: f64) -> f64 {
        let x = s.pos - zmp;
        0.5 * (s.vel * s.vel - self.c * self.c * x * x)
    }

    /// The instantaneous capture point: where a pivot would bring the mass to rest on top of it.
    pub fn capture_point(&self, s: LipmState) -> f64 {
        s.pos + s.vel / self.c
    }

    /// Coefficients `(p, m)` of `x(t) - zmp = p e^{Ct} + m e^{-Ct}`.
    fn exp_coefficients(&self, s: LipmState, zmp: f64) -> (f64, f64) {
        let x = s.pos - zmp;
        let w = s.vel / self.c;
        (0.5 * (x + w), 0.5 * (x - w))
    }

    /// The latest time (s, may be negative: in the past) at which the mass passes location
    /// `target` with the pivot at `zmp`, or `None` if it never does.
    ///
    /// A pendulum passes a location zero, one or two times; like the authors' `tLoc`, this
    /// returns the greater of two solutions (e.g. the return through a support-exchange point
    /// after the apex, not the departure from it).
    pub fn time_to_location(&self, s: LipmState, zmp: f64, target: f64) -> Option<f64> {
        // p u^2 - d u + m = 0 with u = e^{Ct} > 0.
        let (p, m) = self.exp_coefficients(s, zmp);
        let d = target - zmp;
        self.latest_positive_root(p, -d, m)
    }

    /// The latest time (s, may be negative) at which the mass has velocity `target` with the
    /// pivot at `zmp`, or `None` if it never does.
    pub fn time_to_velocity(&self, s: LipmState, zmp: f64, target: f64) -> Option<f64> {
        // v(t) = C (p u - m / u): C p u^2 - target u - C m = 0.
        let (p, m) = self.exp_coefficients(s, zmp);
        self.latest_positive_root(self.c * p, -target, -self.c * m)
    }

    /// `ln(u)/C` for the greatest positive root `u` of `a u^2 + b u + c = 0`.
    fn latest_positive_root(&self, a: f64, b: f64, c: f64) -> Option<f64> {
        let scale = a.abs().max(b.abs()).max(c.abs());
        if scale == 0.0 || !scale.is_finite() {
            return None;
        }
        let (a, b, c) = (a / scale, b / scale, c / scale);
        let roots: [Option<f64>; 2] = if a.abs() < 1e-14 {
            // Linear: b u + c = 0.
            if b == 0.0 {
                [None, None]
            } else {
                [Some(-c / b), None]
            }
        } else {
            let disc = b * b - 4.0 * a * c;
            if disc < 0.0 {
                [None, None]
            } else {
                // Numerically stable quadratic roots.
                let q = -0.5 * (b + b.signum() * disc.sqrt());
                if q == 0.0 {
                    [Some(0.0), None]
                } else {
                    [Some(q / a), Some(c / q)]
                }
            }
        };
        roots
            .into_iter()
            .flatten()
            .filter(|u| *u > 0.0 && u.is_finite())
            .map(|u| u.ln() / self.c)
            .fold(None, |best: Option<f64>, t| {
                Some(best.map_or(t, |b| b.max(t)))
            })
    }

    /// The pivot that brings the mass from `s` to location `target` at time `t`:
    /// `Z = (x0 cosh(Ct) + (v0/C) sinh(Ct) - target) / (cosh(Ct) - 1)`.
    ///
    /// `None` when `t` is too short (or not finite) for the pivot to be determined
    /// (`cosh(Ct) - 1` vanishes). The result is unclamped: the caller keeps it inside the foot.
    pub fn zmp_to_reach(&self, s: LipmState, target: f64, t: f64) -> Option<f64> {
        if !t.is_finite() {
            return None;
        }
        let (sh, ch) = sinh_cosh(self.c * t);
        let denom = ch - 1.0;
        if denom < 1e-9 {
            return None;
        }
        let z = (s.pos * ch + s.vel / self.c * sh - target) / denom;
        z.is_finite().then_some(z)
    }

    /// Pivot placement: where, relative to the mass's current position, to put a new pivot so
    /// that the mass later passes through position `target` (relative to the new pivot) with
    /// velocity `target_vel`.
    ///
    /// Orbital energy about the new pivot is conserved, so the offset has magnitude
    /// `sqrt((v0^2 - target_vel^2)/C^2 + target^2)`; the returned offset is that of the new
    /// pivot seen from the mass, signed opposite to `target` (the mass sits on the `target`
    /// side of the new pivot); with `target = 0` it lies ahead of the motion. `None` when no
    /// pivot exists (negative radicand, or a target velocity the orbit cannot reach).
    pub fn pivot_for(&self, s: LipmState, target: f64, target_vel: f64) -> Option<f64> {
        let c2 = self.c * self.c;
        let r = (s.vel * s.vel - target_vel * target_vel) / c2 + target * target;
        if r < 0.0 || !r.is_finite() {
            return None;
        }
        // A target with positive energy lies on an orbit that never turns: the velocity sign
        // cannot change along it.
        if target_vel * target_vel - c2 * target * target > 0.0 && s.vel * target_vel < 0.0 {
            return None;
        }
        let mag = r.sqrt();
        let sign = if target != 0.0 {
            -target.signum()
        } else if s.vel != 0.0 {
            s.vel.signum()
        } else {
            1.0
        };
        Some(sign * mag)
    }
}

/// `(sinh, cosh)` of `x`.
fn sinh_cosh(x: f64) -> (f64, f64) {
    (x.sinh(), x.cosh())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_constants() {
        assert!(Lipm::new(0.0).is_err());
        assert!(Lipm::new(-1.0).is_err());
        assert!(Lipm::new(f64::NAN).is_err());
        assert!(Lipm::from_height(0.0, 9.81).is_err());
        assert!((Lipm::from_height(9.81 / 9.0, 9.81).unwrap().c() - 3.0).abs() < 1e-12);
    }

    #[test]
    fn symmetric_lateral_swing_returns_after_two_tau() {
        // Start at xi moving inward on the apex orbit through alpha: back at xi after 2 tau.
        let lipm = Lipm::new(3.0).unwrap();
        let (alpha, xi) = (0.09_f64, 0.12_f64);
        let tau = (xi / alpha).acosh() / 3.0;
        let s = LipmState::new(xi, -3.0 * (xi * xi - alpha * alpha).sqrt());
        let t = lipm.time_to_location(s, 0.0, xi).unwrap();
        assert!((t - 2.0 * tau).abs() < 1e-9, "{t} vs {}", 2.0 * tau);
        let apex = lipm.time_to_velocity(s, 0.0, 0.0).unwrap();
        assert!((apex - tau).abs() < 1e-9);
        assert!((lipm.state_after(s, 0.0, apex).pos - alpha).abs() < 1e-9);
    }
}
