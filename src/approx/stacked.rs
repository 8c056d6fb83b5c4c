//! [`Stacked`]: several approximators over the same inputs, read as one with their outputs
//! side by side, so that any single-output approximator serves a learner with more outputs.

use super::{ApproxError, FunctionApproximator, Persist, check_output, check_vector};
use serde::{Deserialize, Serialize};

/// Approximators over the same inputs, their outputs concatenated in order: output `k` of the
/// stack is the outputs of `heads[0]`, then `heads[1]`, and so on.
///
/// ```
/// use steplearn::approx::{FunctionApproximator, Grid, GridConfig, InputBox, Stacked};
/// let bounds = InputBox::new(vec![-1.0, -1.0], vec![1.0, 1.0])?;
/// let head = Grid::new(GridConfig::new(bounds, vec![5, 5], 1))?;
/// let mut both = Stacked::new(vec![head.clone(), head])?;
/// assert_eq!((both.input_dim(), both.output_dim()), (2, 2));
/// both.update(&[0.0, 0.0], &[1.0, -1.0])?;
/// let mut y = [0.0; 2];
/// both.predict(&[0.0, 0.0], &mut y)?;
/// assert!(y[0] > 0.0 && y[1] < 0.0);
/// # Ok::<(), steplearn::approx::ApproxError>(())
/// ```
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Stacked<A> {
    heads: Vec<A>,
    outputs: usize,
}

impl<A: FunctionApproximator> Stacked<A> {
    /// The stack of `heads`: at least one, all with the same number of inputs.
    pub fn new(heads: Vec<A>) -> Result<Self, ApproxError> {
        let outputs = heads.iter().map(|h| h.output_dim()).sum();
        let stack = Stacked { heads, outputs };
        stack.check_shape()?;
        Ok(stack)
    }

    /// Checks that there is a head, that the heads agree on the inputs and that `outputs`
    /// counts theirs.
    fn check_shape(&self) -> Result<(), ApproxError> {
        let heads = &self.heads;
        let Some(first) = heads.first() else {
            return Err(ApproxError::config(
                "heads",
                "needs at least one approximator",
            ));
        };
        let inputs = first.input_dim();
        if let Some((k, h)) = heads
            .iter()
            .enumerate()
            .find(|(_, h)| h.input_dim() != inputs)
        {
            return Err(ApproxError::config(
                "heads",
                format!("head {k} has {} inputs, head 0 has {inputs}", h.input_dim()),
            ));
        }
        let outputs: usize = heads.iter().map(|h| h.output_dim()).sum();
        if outputs != self.outputs {
            return Err(ApproxError::config(
                "outputs",
                format!("is {}, the heads have {outputs}", self.outputs),
            ));
        }
        Ok(())
    }

    /// The approximators, in output order.
    pub fn heads(&self) -> &[A] {
        &self.heads
    }
}

impl<A: FunctionApproximator> FunctionApproximator for Stacked<A> {
    fn input_dim(&self) -> usize {
        self.heads[0].input_dim()
    }
    fn output_dim(&self) -> usize {
        self.outputs
    }
    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        check_vector("x", x, self.input_dim())?;
        check_output("y", y, self.outputs)?;
        let mut at = 0;
        for h in &self.heads {
            let n = h.output_dim();
            h.predict(x, &mut y[at..at + n])?;
            at += n;
        }
        Ok(())
    }
    /// Checks `x` and `y` first, then updates every head in turn. A head that still fails
    /// leaves the heads before it updated (each head's update is all-or-nothing).
    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        check_vector("x", x, self.input_dim())?;
        check_vector("y", y, self.outputs)?;
        let mut at = 0;
        for h in &mut self.heads {
            let n = h.output_dim();
            h.update(x, &y[at..at + n])?;
            at += n;
        }
        Ok(())
    }
}

impl<A: FunctionApproximator + Persist> Persist for Stacked<A> {
    fn check_invariants(&self) -> Result<(), ApproxError> {
        for h in &self.heads {
            h.check_invariants()?;
        }
        self.check_shape()
            .map_err(|e| ApproxError::Corrupt(format!("stacked approximator: {e}")))
    }
}
