//! Exact batch kernel ridge regression: a dense Cholesky solve with faer.

use super::batch::check_matrix;
use super::kernel_ridge::gaussian_kernel;
use super::{ApproxError, KernelRidgeConfig, check_output, check_vector};
use faer::Mat;
use faer::linalg::solvers::Solve;
use ndarray::{Array2, ArrayView2};

/// Exact kernel ridge regression (the Gaussian process posterior mean) fitted in one batch.
///
/// With the Gaussian kernel `k(a, b) = exp(-sum_i (a_i - b_i)^2 / (2 l_i^2))` of a
/// [`KernelRidgeConfig`] (its `length_scales`, `regularisation` `lambda` and `output_dim`; the
/// online settings `budget`, `novelty_threshold` and `forgetting` play no part), the fit solves
/// `(K + lambda I) alpha = Y` on the `n x n` Gram matrix `K` of all samples by a Cholesky
/// factorisation (faer's `llt`), and predicts `f(x) = sum_j alpha_j k(x_j, x)`.
///
/// Cost: `O(n^2 d)` to build `K`, `O(n^3)` to factor it, `n^2` floats of memory during the
/// fit; prediction `O(n (d + output_dim))`. It is the reference the online
/// [`KernelRidge`](super::KernelRidge) converges to when its dictionary keeps every sample, and
/// the better choice when all data are at hand and `n` is a few thousand at most.
///
/// ```
/// use ndarray::array;
/// use steplearn::approx::{ExactKernelRidge, KernelRidgeConfig};
/// let x = array![[0.0], [0.5], [1.0]];
/// let y = array![[0.0], [0.25], [1.0]];
/// let config = KernelRidgeConfig { regularisation: 1e-6, ..KernelRidgeConfig::new(vec![0.5], 1) };
/// let model = ExactKernelRidge::fit(x.view(), y.view(), &config)?;
/// let p = model.predict(array![[0.5]].view())?;
/// assert!((p[[0, 0]] - 0.25).abs() < 1e-3);
/// # Ok::<(), steplearn::approx::ApproxError>(())
/// ```
#[derive(Debug, Clone)]
pub struct ExactKernelRidge {
    /// `1 / length_scales`.
    inv_length_scales: Vec<f64>,
    /// Training inputs, `n x input_dim`.
    x: Array2<f64>,
    /// Coefficients, `n x output_dim`.
    alpha: Array2<f64>,
}

impl ExactKernelRidge {
    /// Fits the model to the rows of `x` (`n x input_dim`, `input_dim = length_scales.len()`)
    /// and `y` (`n x output_dim`).
    ///
    /// Errors: a parameter out of range ([`ApproxError::InvalidConfig`]); zero samples, a wrong
    /// column count or unequal row counts ([`ApproxError::DimensionMismatch`]); NaN or an infinity
    /// ([`ApproxError::NonFinite`], index row-major).
    pub fn fit(
        x: ArrayView2<'_, f64>,
        y: ArrayView2<'_, f64>,
        config: &KernelRidgeConfig,
    ) -> Result<Self, ApproxError> {
        config.validate_kernel()?;
        let (d, n_out) = (config.length_scales.len(), config.output_dim);
        let n = x.nrows();
        if n == 0 {
            return Err(ApproxError::DimensionMismatch {
                what: "rows of x (at least one sample needed)",
                expected: 1,
                got: 0,
            });
        }
        check_matrix("x", x, d)?;
        check_matrix("y", y, n_out)?;
        if y.nrows() != n {
            return Err(ApproxError::DimensionMismatch {
                what: "rows of y (must equal rows of x)",
                expected: n,
                got: y.nrows(),
            });
        }
        let inv_length_scales: Vec<f64> = config.length_scales.iter().map(|l| 1.0 / l).collect();
        let x = x.to_owned();
        let lambda = config.regularisation;
        let gram = Mat::from_fn(n, n, |i, j| {
            let k = gaussian_kernel(&inv_length_scales, x.row(i).iter(), x.row(j).iter());
            if i == j { k + lambda } else { k }
        });
        let llt = gram.llt(faer::Side::Lower).map_err(|e| {
            ApproxError::config(
                "regularisation",
                format!(
                    "the regularised Gram matrix is not positive definite ({e:?}); increase it"
                ),
            )
        })?;
        let mut rhs = Mat::from_fn(n, n_out, |i, k| y[[i, k]]);
        llt.solve_in_place(rhs.as_mut());
        let alpha = Array2::from_shape_fn((n, n_out), |(i, k)| rhs[(i, k)]);
        if let Some(v) = alpha.iter().find(|v| !v.is_finite()) {
            return Err(ApproxError::config(
                "regularisation",
                format!("the solve gave a non-finite coefficient ({v}); increase it"),
            ));
        }
        Ok(ExactKernelRidge {
            inv_length_scales,
            x,
            alpha,
        })
    }

    /// Number of inputs.
    pub fn input_dim(&self) -> usize {
        self.inv_length_scales.len()
    }

    /// Number of outputs.
    pub fn output_dim(&self) -> usize {
        self.alpha.ncols()
    }

    /// Number of training samples.
    pub fn num_samples(&self) -> usize {
        self.x.nrows()
    }

    /// The coefficients `alpha` (`n x output_dim`).
    pub fn alpha(&self) -> ArrayView2<'_, f64> {
        self.alpha.view()
    }

    /// Writes the prediction at one point `x` into `y` (len == output_dim).
    pub fn predict_point(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        check_vector("input x", x, self.input_dim())?;
        check_output("output y", y, self.output_dim())?;
        y.fill(0.0);
        for (xj, aj) in self.x.rows().into_iter().zip(self.alpha.rows()) {
            let k = gaussian_kernel(&self.inv_length_scales, xj.iter(), x.iter());
            for (yk, a) in y.iter_mut().zip(aj) {
                *yk += a * k;
            }
        }
        Ok(())
    }

    /// Predicts every row of `x` (`n x input_dim`), returning an `n x output_dim` matrix.
    pub fn predict(&self, x: ArrayView2<'_, f64>) -> Result<Array2<f64>, ApproxError> {
        check_matrix("x", x, self.input_dim())?;
        let mut out = Array2::zeros((x.nrows(), self.output_dim()));
        let mut y = vec![0.0; self.output_dim()];
        for (i, row) in x.rows().into_iter().enumerate() {
            let xi: Vec<f64> = row.to_vec();
            self.predict_point(&xi, &mut y)?;
            for (k, v) in y.iter().enumerate() {
                out[[i, k]] = *v;
            }
        }
        Ok(out)
    }
}
