//! Online kernel ridge regression with a bounded dictionary (kernel recursive least squares).

use super::square_matrix::SquareMatrix;
use super::{ApproxError, FunctionApproximator, Persist, check_output, check_vector};
use serde::{Deserialize, Serialize};

/// Added to the kernel's diagonal (`k(x, x) = 1 + JITTER`) for numerical stability.
const JITTER: f64 = 1e-8;

/// Settings of a [`KernelRidge`] model.
///
/// Recommended settings (as compared by `probes/src/bin/compare_approximators.rs`; its figures are in
/// docs/approximators.md):
/// - cross 2D on [-1, 1]^2, noise 0.1: `length_scales = [0.25, 0.25]`, `regularisation =
///   0.01` (the noise variance), defaults otherwise (budget 100, novelty threshold 0.02);
/// - the 3-input step-offset map, noise 0.01: `length_scales` = half the input ranges
///   (`[0.5, 3.0, 0.15]`), `regularisation = 1e-4`, defaults otherwise.
///
/// Its update time is measured by `benches/approx_others.rs`.
///
/// Length scales of about the distance over which the target changes noticeably, and a
/// `regularisation` of the observation noise variance, are good starting points. The budget
/// trades accuracy against cost (`O(budget^2)` per update).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct KernelRidgeConfig {
    /// Gaussian kernel length scale per input, `k(a, b) = exp(-sum_i (a_i - b_i)^2 /
    /// (2 length_scales_i^2))` (> 0; one entry per input).
    pub length_scales: Vec<f64>,
    /// Number of outputs (>= 1).
    pub output_dim: usize,
    /// Ridge regulariser (> 0): the noise variance of the targets relative to the kernel's unit
    /// prior variance. Default 0.01.
    pub regularisation: f64,
    /// Most atoms in the dictionary (>= 1). Default 100.
    pub budget: usize,
    /// Approximate-linear-dependence threshold in [1e-6, 1): a sample whose kernel feature has a
    /// squared distance below `novelty_threshold * k(x, x)` from the span of the dictionary
    /// is not added. Larger values keep fewer atoms and update faster. Default 0.02.
    pub novelty_threshold: f64,
    /// Forgetting factor in (0, 1] (1: none, the default). Below 1, each update first moves
    /// the posterior back towards the prior, `Sigma = f Sigma + (1 - f) K`, `mu = sqrt(f) mu`
    /// (KRLS-T's back-to-prior forgetting), so old data fades and the model tracks drift.
    pub forgetting: f64,
}

impl KernelRidgeConfig {
    /// A config with one length scale per input and the defaults (regularisation 0.01,
    /// budget 100, novelty threshold 0.02, no forgetting).
    pub fn new(length_scales: Vec<f64>, output_dim: usize) -> Self {
        KernelRidgeConfig {
            length_scales,
            output_dim,
            regularisation: 0.01,
            budget: 100,
            novelty_threshold: 0.02,
            forgetting: 1.0,
        }
    }

    /// Checks the kernel's parameters (length scales, outputs, regularisation): all that the
    /// exact batch fit ([`super::ExactKernelRidge`]) uses.
    pub(crate) fn validate_kernel(&self) -> Result<(), ApproxError> {
        if self.length_scales.is_empty() {
            return Err(ApproxError::config(
                "length_scales",
                "needs one entry per input (at least one input)",
            ));
        }
        if let Some((i, l)) = self
            .length_scales
            .iter()
            .enumerate()
            .find(|(_, l)| !(l.is_finite() && **l > 0.0 && (1.0 / *l).is_finite()))
        {
            return Err(ApproxError::config(
                "length_scales",
                format!("input {i}: must be finite and > 0, got {l}"),
            ));
        }
        if self.output_dim == 0 {
            return Err(ApproxError::config("output_dim", "must be >= 1"));
        }
        if !(self.regularisation.is_finite() && self.regularisation >= 1e-12) {
            return Err(ApproxError::config(
                "regularisation",
                format!("must be finite and >= 1e-12, got {}", self.regularisation),
            ));
        }
        Ok(())
    }

    fn validate(&self) -> Result<(), ApproxError> {
        self.validate_kernel()?;
        if !(1..=10_000).contains(&self.budget) {
            return Err(ApproxError::config(
                "budget",
                format!("must be in 1..=10000, got {}", self.budget),
            ));
        }
        if !(self.novelty_threshold >= 1e-6 && self.novelty_threshold < 1.0) {
            return Err(ApproxError::config(
                "novelty_threshold",
                format!("must be in [1e-6, 1), got {}", self.novelty_threshold),
            ));
        }
        if !(self.forgetting > 0.0 && self.forgetting <= 1.0) {
            return Err(ApproxError::config(
                "forgetting",
                format!("must be in (0, 1], got {}", self.forgetting),
            ));
        }
        Ok(())
    }
}

/// Online kernel ridge regression with a Gaussian kernel and a bounded dictionary: the
/// KRLS-T formulation (Van Vaerenbergh, Lázaro-Gredilla and Santamaría, "Kernel recursive
/// least-squares tracker for time-varying regression", IEEE TNNLS 2012), i.e. a sparse online
/// Gaussian process whose posterior mean is the kernel ridge solution on the dictionary.
///
/// State for a dictionary `D` of `m <= budget` atoms: the Gram matrix `K` (plus jitter), its
/// inverse `Q`, the posterior mean `mu` (per output) and covariance `Sigma` of the function
/// values at `D`, and the prediction coefficients `alpha = Q mu`, so that
/// `f(x) = sum_j alpha_j k(d_j, x)`. The dictionary's kernel matrix carries a jitter of 1e-8
/// on its diagonal (`k(x, x) = 1 + 1e-8`), which bounds its inverse by 1e8.
///
/// One update at `(x, y)`:
/// 1. optional forgetting (see [`KernelRidgeConfig::forgetting`]);
/// 2. `k = k(D, x)`, `q = Q k`, novelty `gamma^2 = k(x, x) - k^T q` (approximate linear
///    dependence);
/// 3. if `gamma^2 < novelty_threshold * k(x, x)`, the sample is explained through its projection
///    onto the dictionary: a rank-one Kalman update of `mu` and `Sigma`, dictionary unchanged;
/// 4. otherwise `x` joins the dictionary: `Q` grows by the block-inverse formula, `K`, `mu`,
///    `Sigma` by one row and column, then the Kalman update;
/// 5. **atom replacement**: if the dictionary now exceeds `budget`, the atom whose removal
///    changes the mean prediction least is dropped, i.e. the `r` minimising
///    `|alpha_r| / Q_rr` (summed in quadrature over outputs; KRLS-T's criterion, which may
///    well pick the newcomer). `Q` is downdated by its Schur complement; `mu` and `Sigma`
///    are marginalised;
/// 6. `alpha = Q mu`.
///
/// Cost: update `O(m^2 + m (d + output_dim))` (about 6 passes over `m x m` matrices), predict
/// `O(m (d + output_dim))` with no allocation; memory `3 m^2 + m (d + 2 output_dim)` floats.
///
/// ```
/// use steplearn::approx::{FunctionApproximator, KernelRidge, KernelRidgeConfig};
/// let mut model = KernelRidge::new(KernelRidgeConfig {
///     regularisation: 1e-4,
///     budget: 30,
///     ..KernelRidgeConfig::new(vec![0.3], 1)
/// })?;
/// for i in 0..500 {
///     let x = (i % 100) as f64 / 99.0;
///     model.update(&[x], &[(3.0 * x).sin()])?;
/// }
/// assert!(model.dictionary_size() <= 30);
/// let mut y = [0.0];
/// model.predict(&[0.5], &mut y)?;
/// assert!((y[0] - 1.5f64.sin()).abs() < 1e-2);
/// # Ok::<(), steplearn::approx::ApproxError>(())
/// ```
///
/// Linear algebra: only matrix-vector products and rank-one updates of symmetric matrices
/// (BLAS-2), on compact buffers that grow and shrink by one row and column
/// (`SquareMatrix`, a private helper). Hand-written slice loops auto-vectorise, never allocate and keep the
/// matrices bitwise symmetric, which neither faer's nor nalgebra's general kernels give for
/// free; their strength, blocked factorisations, is only needed when a model is loaded:
/// there nalgebra (the crate's small-matrix library) multiplies `Q K` to check that `Q` is
/// still the inverse of `K`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct KernelRidge {
    config: KernelRidgeConfig,
    /// `1 / length_scales`, precomputed.
    inv_length_scales: Vec<f64>,
    /// Dictionary atoms, `dictionary[j * input_dim + i]`.
    dictionary: Vec<f64>,
    /// Gram matrix of the dictionary, jitter on the diagonal.
    gram: SquareMatrix,
    /// Inverse of `gram`.
    gram_inv: SquareMatrix,
    /// Posterior covariance of the function values at the dictionary.
    covariance: SquareMatrix,
    /// Posterior mean at the dictionary, `mean[j * output_dim + k]`.
    mean: Vec<f64>,
    /// Prediction coefficients `gram_inv * mean`, `alpha[j * output_dim + k]`.
    alpha: Vec<f64>,
    /// Number of accepted updates.
    updates: u64,
    #[serde(skip)]
    scratch: Scratch,
}

/// Work vectors reused across updates (never saved).
#[derive(Debug, Clone, Default)]
struct Scratch {
    k: Vec<f64>,
    q: Vec<f64>,
    h: Vec<f64>,
    e: Vec<f64>,
    col: Vec<f64>,
}

impl KernelRidge {
    /// An empty model (predicts 0), after checking the config.
    pub fn new(config: KernelRidgeConfig) -> Result<Self, ApproxError> {
        config.validate()?;
        let cap = config.budget + 1;
        Ok(KernelRidge {
            inv_length_scales: config.length_scales.iter().map(|l| 1.0 / l).collect(),
            dictionary: Vec::with_capacity(cap * config.length_scales.len()),
            gram: SquareMatrix::with_capacity(cap),
            gram_inv: SquareMatrix::with_capacity(cap),
            covariance: SquareMatrix::with_capacity(cap),
            mean: Vec::with_capacity(cap * config.output_dim),
            alpha: Vec::with_capacity(cap * config.output_dim),
            updates: 0,
            scratch: Scratch::default(),
            config,
        })
    }

    /// The validated settings.
    pub fn config(&self) -> &KernelRidgeConfig {
        &self.config
    }

    /// Current number of dictionary atoms (at most the budget).
    pub fn dictionary_size(&self) -> usize {
        self.gram.n()
    }

    /// Dictionary atom `j`.
    pub fn atom(&self, j: usize) -> &[f64] {
        let d = self.input_dim();
        &self.dictionary[j * d..(j + 1) * d]
    }

    /// Number of accepted updates so far.
    pub fn num_updates(&self) -> u64 {
        self.updates
    }

    /// Posterior variance of the latent function at `x` (without the noise): how unsure the
    /// model is there, between 0 and the prior variance 1.
    pub fn predict_variance(&self, x: &[f64]) -> Result<f64, ApproxError> {
        check_vector("input x", x, self.input_dim())?;
        let m = self.dictionary_size();
        let k: Vec<f64> = (0..m).map(|j| self.kernel(self.atom(j), x)).collect();
        let mut q = vec![0.0; m];
        self.gram_inv.mul_vec(&k, &mut q);
        let mut h = vec![0.0; m];
        self.covariance.mul_vec(&q, &mut h);
        let kq: f64 = k.iter().zip(&q).map(|(a, b)| a * b).sum();
        let qh: f64 = q.iter().zip(&h).map(|(a, b)| a * b).sum();
        Ok((1.0 + JITTER - kq + qh).max(0.0))
    }

    #[inline]
    fn kernel(&self, a: &[f64], b: &[f64]) -> f64 {
        gaussian_kernel(&self.inv_length_scales, a.iter(), b.iter())
    }

    /// `alpha = Q mu`, one output at a time (column-wise matrix-vector products vectorise).
    fn recompute_alpha(&mut self) {
        let (m, n_out) = (self.dictionary_size(), self.config.output_dim);
        self.alpha.resize(m * n_out, 0.0);
        let s = &mut self.scratch;
        for k in 0..n_out {
            s.col.clear();
            s.col.extend(self.mean.iter().skip(k).step_by(n_out));
            s.q.resize(m, 0.0);
            self.gram_inv.mul_vec(&s.col, &mut s.q);
            for (a, v) in self.alpha.iter_mut().skip(k).step_by(n_out).zip(&s.q) {
                *a = *v;
            }
        }
    }

    /// Drops atom `r` (see step 5 of the type's docs).
    fn remove_atom(&mut self, r: usize) {
        let (d, n_out) = (self.input_dim(), self.config.output_dim);
        let m = self.dictionary_size();
        let s = &mut self.scratch;
        s.col.clear();
        s.col.extend_from_slice(self.gram_inv.column(r));
        s.e.clear();
        s.e.extend_from_slice(&self.alpha[r * n_out..(r + 1) * n_out]);
        let qrr = s.col[r];
        self.gram_inv.add_outer(-1.0 / qrr, &s.col);
        // alpha' = Q' mu' = alpha - Q[:, r] alpha_r / Q_rr (then drop entry r).
        for (row, c) in self.alpha.chunks_exact_mut(n_out).zip(&s.col) {
            let f = c / qrr;
            for (a, ar) in row.iter_mut().zip(&s.e[..n_out]) {
                *a -= f * ar;
            }
        }
        self.gram_inv.swap_remove(r);
        self.gram.swap_remove(r);
        self.covariance.swap_remove(r);
        let last = m - 1;
        self.dictionary.copy_within(last * d..m * d, r * d);
        self.dictionary.truncate(last * d);
        for v in [&mut self.mean, &mut self.alpha] {
            v.copy_within(last * n_out..m * n_out, r * n_out);
            v.truncate(last * n_out);
        }
    }

    /// The atom whose removal changes the predictions least: `argmin_r |alpha_r| / Q_rr`.
    fn least_useful_atom(&self) -> usize {
        let n_out = self.config.output_dim;
        let mut best = (0, f64::INFINITY);
        for r in 0..self.dictionary_size() {
            let a2: f64 = self.alpha[r * n_out..(r + 1) * n_out]
                .iter()
                .map(|a| a * a)
                .sum();
            let score = a2.sqrt() / self.gram_inv.get(r, r);
            if score < best.1 {
                best = (r, score);
            }
        }
        best.0
    }
}

impl FunctionApproximator for KernelRidge {
    fn input_dim(&self) -> usize {
        self.config.length_scales.len()
    }

    fn output_dim(&self) -> usize {
        self.config.output_dim
    }

    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        check_vector("input x", x, self.input_dim())?;
        check_output("output y", y, self.output_dim())?;
        let n_out = self.config.output_dim;
        y.fill(0.0);
        for (atom, alpha) in self
            .dictionary
            .chunks_exact(self.input_dim())
            .zip(self.alpha.chunks_exact(n_out))
        {
            let kj = self.kernel(atom, x);
            for (yk, a) in y.iter_mut().zip(alpha) {
                *yk += kj * a;
            }
        }
        Ok(())
    }

    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        check_vector("input x", x, self.input_dim())?;
        check_vector("target y", y, self.output_dim())?;
        // Everything below is infallible: a rejected call never gets here.
        let (d, n_out) = (self.input_dim(), self.config.output_dim);
        let m = self.dictionary_size();
        let f = self.config.forgetting;
        if f < 1.0 {
            self.covariance.scale_add(f, 1.0 - f, &self.gram);
            let sf = f.sqrt();
            self.mean.iter_mut().for_each(|v| *v *= sf);
        }
        let mut s = std::mem::take(&mut self.scratch);
        s.k.clear();
        s.k.extend(self.dictionary.chunks_exact(d).map(|a| self.kernel(a, x)));
        s.q.resize(m, 0.0);
        self.gram_inv.mul_vec(&s.k, &mut s.q);
        s.h.resize(m, 0.0);
        self.covariance.mul_vec(&s.q, &mut s.h);
        let kxx = 1.0 + JITTER;
        let gamma2 = kxx - dot(&s.k, &s.q);
        let qh = dot(&s.q, &s.h);
        // Residuals e = y - q^T mu.
        s.e.clear();
        s.e.extend_from_slice(y);
        for (j, qj) in s.q.iter().enumerate() {
            for (e, mu) in s.e.iter_mut().zip(&self.mean[j * n_out..(j + 1) * n_out]) {
                *e -= qj * mu;
            }
        }
        let noise = self.config.regularisation;
        if gamma2 < self.config.novelty_threshold * kxx {
            // Projected (reduced) update: dictionary unchanged.
            let inv_sy2 = 1.0 / (noise + qh);
            kalman_update(&mut self.mean, &s.h, &s.e, inv_sy2, n_out);
            self.covariance.add_outer(-inv_sy2, &s.h);
        } else {
            // Add x to the dictionary.
            let sf2 = gamma2 + qh;
            let inv_sy2 = 1.0 / (noise + sf2);
            let inv_g2 = 1.0 / gamma2;
            self.gram_inv.add_outer(inv_g2, &s.q);
            s.col.clear();
            s.col.extend(s.q.iter().map(|v| -v * inv_g2));
            self.gram_inv.push(&s.col, inv_g2);
            self.gram.push(&s.k, kxx);
            self.covariance.push(&s.h, sf2);
            s.h.push(sf2);
            self.covariance.add_outer(-inv_sy2, &s.h);
            // The prior mean of f(x) given the dictionary values is q^T mu = y - e.
            for (yk, ek) in y.iter().zip(&s.e) {
                self.mean.push(yk - ek);
            }
            kalman_update(&mut self.mean, &s.h, &s.e, inv_sy2, n_out);
            self.dictionary.extend_from_slice(x);
        }
        self.scratch = s;
        self.recompute_alpha();
        if self.dictionary_size() > self.config.budget {
            let r = self.least_useful_atom();
            self.remove_atom(r);
        }
        self.updates += 1;
        Ok(())
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// `mean[j, k] += p[j] * e[k] * inv_var`.
fn kalman_update(mean: &mut [f64], p: &[f64], e: &[f64], inv_var: f64, n_out: usize) {
    for (row, pj) in mean.chunks_exact_mut(n_out).zip(p) {
        for (mu, ek) in row.iter_mut().zip(e) {
            *mu += pj * ek * inv_var;
        }
    }
}

impl Persist for KernelRidge {
    fn check_invariants(&self) -> Result<(), ApproxError> {
        let corrupt = |m: String| Err(ApproxError::Corrupt(format!("kernel ridge: {m}")));
        if let Err(e) = self.config.validate() {
            return corrupt(format!("invalid config: {e}"));
        }
        let (d, n_out) = (self.input_dim(), self.config.output_dim);
        if self.updates > crate::stats::MAX_COUNT {
            return corrupt(format!("{} updates is beyond any run", self.updates));
        }
        if self.inv_length_scales.len() != d
            || self
                .inv_length_scales
                .iter()
                .zip(&self.config.length_scales)
                .any(|(il, l)| *il != 1.0 / l)
        {
            return corrupt("inverse length scales do not match the config".into());
        }
        let m = self.gram.n();
        if m > self.config.budget {
            return corrupt(format!("{m} atoms exceed the budget"));
        }
        if self.dictionary.len() != m * d
            || self.gram_inv.n() != m
            || self.covariance.n() != m
            || Some(self.mean.len()) != m.checked_mul(n_out)
            || Some(self.alpha.len()) != m.checked_mul(n_out)
        {
            return corrupt("dictionary, matrices and coefficients disagree in size".into());
        }
        if !(self.gram.is_valid() && self.gram_inv.is_valid() && self.covariance.is_valid()) {
            return corrupt("a matrix is malformed, not finite or not symmetric".into());
        }
        if let Some(v) = self
            .dictionary
            .iter()
            .chain(&self.mean)
            .chain(&self.alpha)
            .find(|v| !v.is_finite())
        {
            return corrupt(format!("non-finite entry {v}"));
        }
        for i in 0..m {
            for j in 0..=i {
                let expected =
                    self.kernel(self.atom(i), self.atom(j)) + if i == j { JITTER } else { 0.0 };
                if (self.gram.get(i, j) - expected).abs() > 1e-12 {
                    return corrupt(format!("Gram entry ({i}, {j}) does not match the atoms"));
                }
            }
            let var = self.covariance.get(i, i);
            if !(-1e-9..=1.0 + JITTER + 1e-9).contains(&var) {
                return corrupt(format!(
                    "posterior variance {var} at atom {i} is out of [0, 1]"
                ));
            }
        }
        let k = nalgebra::DMatrix::from_column_slice(m, m, &self.gram.to_compact());
        let q = nalgebra::DMatrix::from_column_slice(m, m, &self.gram_inv.to_compact());
        // K + jitter I has eigenvalues >= JITTER, so no entry of its inverse exceeds
        // 1 / JITTER, and the inverse of a positive definite matrix has a diagonal >= 1 / K_ii.
        let qmax = q.amax();
        if qmax > 2.0 / JITTER || (0..m).any(|i| q[(i, i)] < 0.5) {
            return corrupt(format!(
                "the stored inverse is out of range (largest entry {qmax:e})"
            ));
        }
        // Rank-one updates accumulate rounding in proportion to the conditioning, which a
        // small novelty threshold lets grow to about 1 / JITTER: measure the residual
        // relative to |Q| (measured: below 2e-7 |Q| after 30,000 updates at threshold 1e-6).
        let residual = (&q * &k - nalgebra::DMatrix::identity(m, m)).amax();
        let tolerance = INVERSE_TOLERANCE * (m as f64) * qmax.max(1.0);
        if residual > tolerance {
            return corrupt(format!(
                "the stored inverse is off by {residual:e} (tolerance {tolerance:e})"
            ));
        }
        let mu = nalgebra::DMatrix::from_row_slice(m, n_out, &self.mean);
        let alpha = nalgebra::DMatrix::from_row_slice(m, n_out, &self.alpha);
        let scale = 1.0 + qmax * mu.amax() * m as f64;
        if (&q * &mu - &alpha).amax() > 1e-9 * scale {
            return corrupt(
                "coefficients do not equal the inverse Gram matrix times the mean".into(),
            );
        }
        Ok(())
    }
}

/// Largest `|Q K - I|` entry accepted when a model is loaded, per atom and relative to the
/// largest entry of `Q`.
const INVERSE_TOLERANCE: f64 = 1e-6;

impl PartialEq for KernelRidge {
    fn eq(&self, other: &Self) -> bool {
        self.config == other.config
            && self.dictionary == other.dictionary
            && self.gram_inv == other.gram_inv
            && self.covariance == other.covariance
            && self.mean == other.mean
    }
}

/// The Gaussian kernel exp(-|(a - b) / l|^2 / 2) with `inv_length_scales` = 1 / l, shared by
/// the online model and the exact batch fit so that both compute it identically.
#[inline]
pub(crate) fn gaussian_kernel<'a>(
    inv_length_scales: &[f64],
    a: impl Iterator<Item = &'a f64>,
    b: impl Iterator<Item = &'a f64>,
) -> f64 {
    let mut s = 0.0;
    for ((ai, bi), il) in a.zip(b).zip(inv_length_scales) {
        let t = (ai - bi) * il;
        s += t * t;
    }
    (-0.5 * s).exp()
}
