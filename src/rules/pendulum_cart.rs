//! The paper's rule, eq. (5): balance first, reference tracking within a bounded margin.

use super::{LearningRule, StepOutcome, saturated_tracking};
use serde::{Deserialize, Serialize};

/// G = theta_E - p_theta tanh(p_F F_E) (Missura & Behnke, eq. 5).
///
/// Rationale: the theta_E term is the pendulum-cart balance law (a forward lean at
/// touch-down asks for a larger step next time in the same situation); the tanh term pulls
/// the step toward the reference, saturated at p_theta so that an abrupt reference change
/// cannot destabilise learning and a large tilt (|theta_E| >> p_theta) always wins.
/// At equilibrium (G = 0) the learner accepts a trunk deviation of up to p_theta in exchange
/// for stepping onto the reference.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PendulumCart {
    /// Largest trunk angle (rad) the tracking term may trade for step accuracy (paper: 0.15).
    pub p_theta: f64,
    /// Gain on the step size error (1/m) inside the saturation (paper: 30).
    pub p_f: f64,
}

impl Default for PendulumCart {
    /// The paper's values: p_theta = 0.15, p_F = 30.
    fn default() -> Self {
        PendulumCart {
            p_theta: 0.15,
            p_f: 30.0,
        }
    }
}

impl LearningRule for PendulumCart {
    fn gradient(&self, step: &StepOutcome) -> f64 {
        step.theta_e - saturated_tracking(self.p_theta, self.p_f, step.f_e)
    }
}
