//! Ablation: the saturated tracking term alone, G = -p_theta tanh(p_F F_E).

use super::{LearningRule, StepOutcome, saturated_tracking};
use serde::{Deserialize, Serialize};

/// G = -p_theta tanh(p_F F_E): eq. (5) without the balance term.
///
/// Rationale: shows what pure reference tracking learns. It corrects a systematic step size
/// error but ignores the trunk, so it should not help (or should hurt) after pushes: the
/// expected failure mode that motivates the balance term.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TrackingOnly {
    /// Bound of the tracking term (paper: 0.15).
    pub p_theta: f64,
    /// Gain on the step size error inside the saturation (1/m; paper: 30).
    pub p_f: f64,
}

impl Default for TrackingOnly {
    /// The paper's values: p_theta = 0.15, p_F = 30.
    fn default() -> Self {
        TrackingOnly {
            p_theta: 0.15,
            p_f: 30.0,
        }
    }
}

impl LearningRule for TrackingOnly {
    fn gradient(&self, step: &StepOutcome) -> f64 {
        -saturated_tracking(self.p_theta, self.p_f, step.f_e)
    }
}
