//! A user's own approximator, checked with `steplearn::approx::conformance`, and the paper's
//! learner (LWPR + pendulum-cart) used from the lean build.

use serde::{Deserialize, Serialize};
use steplearn::approx::conformance::check_approximator;
use steplearn::approx::{
    ApproxError, FunctionApproximator, Lwpr, LwprConfig, Persist, check_output, check_vector,
};
use steplearn::control::{FootstepLearner, LearnerConfig, LearnerInput};
use steplearn::rules::{PendulumCart, StepOutcome};

/// Predicts the running mean of the targets seen on the same side of 0 in the first input:
/// two constants, the simplest model whose predictions depend on the input.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct RunningMean {
    input_dim: usize,
    /// Samples seen with the first input below 0, and at or above it.
    count: [u64; 2],
    /// The mean target of each side, one value per output.
    mean: [Vec<f64>; 2],
}

impl RunningMean {
    fn new(input_dim: usize, output_dim: usize) -> Self {
        RunningMean {
            input_dim,
            count: [0, 0],
            mean: [vec![0.0; output_dim], vec![0.0; output_dim]],
        }
    }

    /// The side of `x`: 0 below 0 in the first input, 1 otherwise.
    fn side(x: &[f64]) -> usize {
        usize::from(x[0] >= 0.0)
    }
}

impl FunctionApproximator for RunningMean {
    fn input_dim(&self) -> usize {
        self.input_dim
    }
    fn output_dim(&self) -> usize {
        self.mean[0].len()
    }
    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        check_vector("x", x, self.input_dim)?;
        check_output("y", y, self.output_dim())?;
        y.copy_from_slice(&self.mean[Self::side(x)]);
        Ok(())
    }
    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        // Validate everything before changing anything.
        check_vector("x", x, self.input_dim)?;
        check_vector("y", y, self.output_dim())?;
        let side = Self::side(x);
        self.count[side] += 1;
        let n = self.count[side] as f64;
        for (m, v) in self.mean[side].iter_mut().zip(y) {
            *m += (v - *m) / n;
        }
        Ok(())
    }
}

impl Persist for RunningMean {
    fn check_invariants(&self) -> Result<(), ApproxError> {
        if self.input_dim == 0
            || self.mean[0].is_empty()
            || self.mean[1].len() != self.mean[0].len()
        {
            return Err(ApproxError::Corrupt("empty or unequal dimensions".into()));
        }
        if self.mean.iter().flatten().any(|m| !m.is_finite()) {
            return Err(ApproxError::Corrupt("non-finite mean".into()));
        }
        Ok(())
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    check_approximator(|| RunningMean::new(2, 1))?;
    check_approximator(|| RunningMean::new(3, 2))?;
    println!("conformance: RunningMean passes every check");

    let lwpr = Lwpr::new(LwprConfig::new(3, 1).norm_in(vec![0.5, 3.0, 0.15]))?;
    let mut learner =
        FootstepLearner::new(lwpr, PendulumCart::default(), LearnerConfig::default())?;
    let input = LearnerInput::new(0.02, 0.1, 0.1);
    let before = learner.query(input)?;
    learner.touch_down(&StepOutcome {
        theta_e: 0.05,
        theta_e_dot: 0.1,
        f_e: -0.02,
        f_r: 0.1,
    })?;
    let after = learner.query(input)?;
    if after.is_nan() || after <= before {
        return Err(format!("the learner did not step longer: {before} -> {after}").into());
    }
    println!("lean learner: dF {before:+.5} -> {after:+.5} m after one touch-down");
    Ok(())
}
