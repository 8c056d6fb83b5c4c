//! Batch prediction and training over ndarray matrices, for every approximator.
//!
//! Rows are samples: `x` is `n x input_dim`, `y` is `n x output_dim`. The whole batch is checked
//! (shapes, finiteness) before the model is touched, so a rejected batch leaves it unchanged.

use super::{ApproxError, FunctionApproximator};
use ndarray::{Array2, ArrayView1, ArrayView2};

/// Batch methods over [`ndarray`] matrices, implemented for every [`FunctionApproximator`].
///
/// Each method is the per-sample loop over the rows, so its results are bit-identical to calling
/// [`FunctionApproximator::predict`] / [`FunctionApproximator::update`] row by row.
///
/// ```
/// use ndarray::array;
/// use steplearn::approx::{BatchApproximator, Grid, GridConfig, InputBox};
/// let mut g = Grid::new(GridConfig::new(InputBox::cube(1, 0.0, 1.0)?, vec![3], 1))?;
/// g.update_batch(array![[0.0], [1.0]].view(), array![[1.0], [2.0]].view())?;
/// let y = g.predict_batch(array![[0.5]].view())?;
/// assert_eq!(y.dim(), (1, 1));
/// # Ok::<(), steplearn::approx::ApproxError>(())
/// ```
pub trait BatchApproximator: FunctionApproximator {
    /// Predicts every row of `x` (`n x input_dim`), returning an `n x output_dim` matrix.
    ///
    /// A wrong column count is a [`ApproxError::DimensionMismatch`], a non-finite entry a
    /// [`ApproxError::NonFinite`] whose index is the row-major position in `x`.
    fn predict_batch(&self, x: ArrayView2<'_, f64>) -> Result<Array2<f64>, ApproxError> {
        check_matrix("batch x", x, self.input_dim())?;
        let mut out = Array2::zeros((x.nrows(), self.output_dim()));
        let mut xi = Vec::with_capacity(x.ncols());
        let mut yi = vec![0.0; self.output_dim()];
        for (row, mut out_row) in x.rows().into_iter().zip(out.rows_mut()) {
            self.predict(as_slice(row, &mut xi), &mut yi)?;
            out_row.assign(&ArrayView1::from(&yi[..]));
        }
        Ok(out)
    }

    /// Trains on every row pair of `x` (`n x input_dim`) and `y` (`n x output_dim`), in order.
    ///
    /// All rows are validated first (column counts, equal row counts, finiteness); on an error
    /// no update has been made. An error from the model itself on a valid row (which the crate's
    /// approximators never give) stops the loop with the earlier rows applied.
    fn update_batch(
        &mut self,
        x: ArrayView2<'_, f64>,
        y: ArrayView2<'_, f64>,
    ) -> Result<(), ApproxError> {
        check_matrix("batch x", x, self.input_dim())?;
        check_matrix("batch y", y, self.output_dim())?;
        if y.nrows() != x.nrows() {
            return Err(ApproxError::DimensionMismatch {
                what: "rows of batch y (must equal rows of batch x)",
                expected: x.nrows(),
                got: y.nrows(),
            });
        }
        let (mut xi, mut yi) = (Vec::new(), Vec::new());
        for (xr, yr) in x.rows().into_iter().zip(y.rows()) {
            let xs = as_slice(xr, &mut xi);
            let ys = as_slice(yr, &mut yi);
            self.update(xs, ys)?;
        }
        Ok(())
    }
}

impl<A: FunctionApproximator + ?Sized> BatchApproximator for A {}

/// Checks the column count and finiteness of a batch (the index of a non-finite entry is its
/// row-major position).
pub(crate) fn check_matrix(
    what: &'static str,
    m: ArrayView2<'_, f64>,
    cols: usize,
) -> Result<(), ApproxError> {
    if m.ncols() != cols {
        return Err(ApproxError::DimensionMismatch {
            what,
            expected: cols,
            got: m.ncols(),
        });
    }
    // `iter` walks in logical row-major order whatever the memory layout.
    match m.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        Some((index, v)) => Err(ApproxError::NonFinite {
            what,
            index,
            value: *v,
        }),
        None => Ok(()),
    }
}

/// The row as a slice, copied into `buf` only when it is not contiguous.
fn as_slice<'a>(row: ArrayView1<'a, f64>, buf: &'a mut Vec<f64>) -> &'a [f64] {
    match row.to_slice() {
        Some(s) => s,
        None => {
            buf.clear();
            buf.extend(row.iter());
            buf
        }
    }
}
