//! Variant: eq. (5) plus the trunk rate, G = theta_E + k theta_E_dot - p_theta tanh(p_F F_E).

use super::{LearningRule, StepOutcome, saturated_tracking};
use serde::{Deserialize, Serialize};

/// G = theta_E + k theta_E_dot - p_theta tanh(p_F F_E).
///
/// Rationale: a trunk that is upright at touch-down but still rotating forward will lean
/// forward next step; eq. (5) only sees the angle. Adding k theta_E_dot makes the balance term
/// a capture-point-like quantity of the trunk (angle plus rate times a time constant). The
/// default k = 0.3 s is about 1/C of the LIPM of this 2 m robot (C ~ 3.1 1/s). With k = 0 it
/// is exactly [`super::PendulumCart`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RateDamped {
    /// Bound of the tracking term (paper: 0.15).
    pub p_theta: f64,
    /// Gain on the step size error inside the saturation (1/m; paper: 30).
    pub p_f: f64,
    /// Weight of the trunk rate (s); default 0.3.
    pub k: f64,
}

impl Default for RateDamped {
    /// p_theta = 0.15, p_F = 30 (the paper's), k = 0.3 s.
    fn default() -> Self {
        RateDamped {
            p_theta: 0.15,
            p_f: 30.0,
            k: 0.3,
        }
    }
}

impl LearningRule for RateDamped {
    fn gradient(&self, step: &StepOutcome) -> f64 {
        step.theta_e + self.k * step.theta_e_dot
            - saturated_tracking(self.p_theta, self.p_f, step.f_e)
    }
}
