//! Ablation: eq. (5) without the saturation, G = theta_E - p_theta p_F F_E.

use super::{LearningRule, StepOutcome};
use serde::{Deserialize, Serialize};

/// G = theta_E - p_theta p_F F_E: the first-order expansion of eq. (5) around F_E = 0.
///
/// Rationale: tests the paper's argument for the tanh. For small errors it equals
/// [`super::PendulumCart`]; for a large reference jump the tracking pull grows without bound
/// and can dominate the balance term, which the paper says destabilises learning.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Linear {
    /// Scale of the tracking term (paper's p_theta: 0.15).
    pub p_theta: f64,
    /// Gain on the step size error (1/m; paper's p_F: 30); the slope is p_theta p_F.
    pub p_f: f64,
}

impl Default for Linear {
    /// The paper's values: p_theta = 0.15, p_F = 30 (slope 4.5 rad/m).
    fn default() -> Self {
        Linear {
            p_theta: 0.15,
            p_f: 30.0,
        }
    }
}

impl LearningRule for Linear {
    fn gradient(&self, step: &StepOutcome) -> f64 {
        step.theta_e - self.p_theta * self.p_f * step.f_e
    }
}
