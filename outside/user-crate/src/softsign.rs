//! The pendulum-cart rule with a softsign saturation: a user's own learning rule.

use steplearn::rules::{LearningRule, StepOutcome};

/// G = theta_E - p_theta * s(p_F F_E) with s(u) = u / (1 + |u|): the same slope at 0 as eq. (5),
/// a slower approach to the bound p_theta.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoftsignCart {
    /// Tracking weight (rad).
    pub p_theta: f64,
    /// Saturation gain (1/m).
    pub p_f: f64,
}

impl Default for SoftsignCart {
    fn default() -> Self {
        SoftsignCart {
            p_theta: 0.15,
            p_f: 30.0,
        }
    }
}

impl LearningRule for SoftsignCart {
    fn gradient(&self, step: &StepOutcome) -> f64 {
        let u = self.p_f * step.f_e;
        step.theta_e - self.p_theta * u / (1.0 + u.abs())
    }
}
