//! An axis-aligned box of inputs, shared by the approximators that tile their input space.

use super::ApproxError;
use serde::{Deserialize, Serialize};

/// The axis-aligned box `[lo[i], hi[i]]` per input dimension.
///
/// [`Grid`](super::Grid) and [`Rbf`](super::Rbf) place their nodes or centres on a regular
/// lattice over such a box. Construct it with [`InputBox::new`], which checks the corners.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InputBox {
    /// Lower corner, one value per input.
    pub lo: Vec<f64>,
    /// Upper corner, one value per input; `hi[i] > lo[i]`.
    pub hi: Vec<f64>,
}

impl InputBox {
    /// A checked box: same non-zero length, finite corners, `lo[i] < hi[i]`.
    pub fn new(lo: Vec<f64>, hi: Vec<f64>) -> Result<Self, ApproxError> {
        let b = InputBox { lo, hi };
        b.validate()?;
        Ok(b)
    }

    /// The cube `[lo, hi]^dim`.
    pub fn cube(dim: usize, lo: f64, hi: f64) -> Result<Self, ApproxError> {
        Self::new(vec![lo; dim], vec![hi; dim])
    }

    /// Number of input dimensions.
    pub fn dim(&self) -> usize {
        self.lo.len()
    }

    /// Width `hi[i] - lo[i]` of dimension `i`.
    pub fn width(&self, i: usize) -> f64 {
        self.hi[i] - self.lo[i]
    }

    /// Checks the box (used again when a config or saved model is validated).
    pub fn validate(&self) -> Result<(), ApproxError> {
        if self.lo.is_empty() {
            return Err(ApproxError::config("bounds", "needs at least one input"));
        }
        if self.lo.len() != self.hi.len() {
            return Err(ApproxError::config(
                "bounds",
                format!(
                    "lo has {} entries but hi has {}",
                    self.lo.len(),
                    self.hi.len()
                ),
            ));
        }
        for (i, (l, h)) in self.lo.iter().zip(&self.hi).enumerate() {
            // `h - l` must be finite too, or spacing computations overflow.
            if !(l.is_finite() && h.is_finite() && (h - l).is_finite() && l < h) {
                return Err(ApproxError::config(
                    "bounds",
                    format!("dimension {i}: need finite lo < hi, got [{l}, {h}]"),
                ));
            }
        }
        Ok(())
    }
}
