//! Learning rules: from what happened in a step to the gradient G that trains the learner.
//!
//! The paper's rule is [`PendulumCart`] (eq. 5). Every rule sees the same [`StepOutcome`],
//! measured at touch-down, and returns one number: how much larger (G > 0) the step taken
//! under the conditions seen during that step should have been.

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
pub trait LearningRule: Send + Sync {
    /// The gradient G for the step that just ended.
    fn gradient(&self, step: &StepOutcome) -> f64;
}

impl<R: LearningRule + ?Sized> LearningRule for Box<R> {
    fn gradient(&self, step: &StepOutcome) -> f64 {
        (**self).gradient(step)
    }
}
