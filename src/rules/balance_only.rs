//! Ablation: the pendulum-cart balance law alone, G = theta_E.

use super::{LearningRule, StepOutcome};
use serde::{Deserialize, Serialize};

/// G = theta_E: eq. (5) with the tracking term removed (p_theta = 0).
///
/// Rationale: isolates what the balance law (eq. 4) learns by itself. The paper expects it to
/// keep the trunk upright but not to track a reference step size: nothing in G depends on F_E.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BalanceOnly;

impl LearningRule for BalanceOnly {
    fn gradient(&self, step: &StepOutcome) -> f64 {
        step.theta_e
    }
}
