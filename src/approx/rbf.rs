//! A normalised Gaussian radial basis function network with centres on a regular grid.

use super::lattice::{Lattice, TensorWeights};
use super::{ApproxError, FunctionApproximator, InputBox, Persist, check_output, check_vector};
use serde::{Deserialize, Serialize};

/// Most centres per dimension a basis function window may touch (bounds `width / spacing`).
const WINDOW: usize = 32;
/// Most centres for recursive least squares (its covariance has `centres^2` entries).
pub const MAX_RLS_CENTRES: usize = 4096;

/// How an [`Rbf`] network updates its output weights.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum RbfUpdate {
    /// Normalised least mean squares: `w += learning_rate * e * phi / |phi|^2`, so one update
    /// removes the fraction `learning_rate` (in (0, 1]) of the error at `x`. Cost
    /// `O(active * output_dim)`; no memory beyond the weights.
    Nlms {
        /// Fraction of the error removed per update, in (0, 1].
        learning_rate: f64,
    },
    /// Recursive least squares over all output weights (exact least squares with a Gaussian
    /// prior on the weights). Cost `O(centres^2)` per update and `centres^2` floats of memory.
    Rls {
        /// Exponential forgetting factor in (0, 1]; 1 keeps all data. Below 1, forgetting is
        /// bounded-trace: the division by `forgetting` is skipped whenever it would lift the
        /// trace of the covariance above its initial value (`centres * prior_variance`), so
        /// the covariance of rarely visited centres cannot wind up.
        forgetting: f64,
        /// Prior variance of each weight (> 0): the ridge regulariser is `1 / prior_variance`.
        prior_variance: f64,
    },
}

/// Settings of an [`Rbf`] network.
///
/// Recommended settings (as compared by `probes/src/bin/compare_approximators.rs`; its figures are in
/// docs/approximators.md):
/// - cross 2D on [-1, 1]^2, noise 0.1: `centres = [21, 21]`, `widths = [0.07, 0.07]`
///   (0.7 x the spacing), `update = RbfUpdate::Nlms { learning_rate: 0.1 }`, or
///   `RbfUpdate::Rls { forgetting: 1.0, prior_variance: 100.0 }`;
/// - the 3-input step-offset map, noise 0.01: `centres = [9, 5, 5]`, widths 0.7 x the
///   spacing (`[0.0875, 1.05, 0.0525]`), the same NLMS or RLS.
///
/// Widths of 0.5-1 times the centre spacing work well: narrower gives bumpy predictions,
/// wider blurs detail and slows least mean squares.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RbfConfig {
    /// The box the centres span (inputs outside it are allowed; the nearest centres dominate).
    pub bounds: InputBox,
    /// Centres per input dimension (>= 1), evenly spaced including the box faces.
    pub centres: Vec<usize>,
    /// Standard deviation of the Gaussians per input dimension, in input units (> 0).
    pub widths: Vec<f64>,
    /// Number of outputs (>= 1).
    pub output_dim: usize,
    /// The weight update rule.
    pub update: RbfUpdate,
    /// Basis functions further than `cutoff * widths[i]` from `x[i]` along any dimension are
    /// treated as 0 (default 3: they would weigh below exp(-4.5) = 1.1% of the nearest).
    pub cutoff: f64,
    /// Upper limit on the number of centres (default 2^20).
    pub max_centres: usize,
}

impl RbfConfig {
    /// A config with widths equal to the centre spacing, normalised LMS with learning rate
    /// 0.1, cutoff 3 and the default centre limit.
    pub fn new(bounds: InputBox, centres: Vec<usize>, output_dim: usize) -> Self {
        let widths = centres
            .iter()
            .enumerate()
            .map(|(i, &n)| {
                let w = bounds
                    .hi
                    .get(i)
                    .zip(bounds.lo.get(i))
                    .map_or(1.0, |(h, l)| h - l);
                if n > 1 { w / (n - 1) as f64 } else { w }
            })
            .collect();
        RbfConfig {
            bounds,
            centres,
            widths,
            output_dim,
            update: RbfUpdate::Nlms { learning_rate: 0.1 },
            cutoff: 3.0,
            max_centres: 1 << 20,
        }
    }

    fn validate(&self) -> Result<Lattice, ApproxError> {
        if self.output_dim == 0 {
            return Err(ApproxError::config("output_dim", "must be >= 1"));
        }
        let lattice = Lattice::new(
            self.bounds.clone(),
            self.centres.clone(),
            self.max_centres,
            "centres",
        )?;
        if self.widths.len() != lattice.dim() {
            return Err(ApproxError::config(
                "widths",
                format!(
                    "has {} entries for {} inputs",
                    self.widths.len(),
                    lattice.dim()
                ),
            ));
        }
        if !(self.cutoff.is_finite() && self.cutoff >= 1.0) {
            return Err(ApproxError::config(
                "cutoff",
                format!("must be finite and >= 1, got {}", self.cutoff),
            ));
        }
        for (i, &w) in self.widths.iter().enumerate() {
            if !(w.is_finite() && w > 0.0) {
                return Err(ApproxError::config(
                    "widths",
                    format!("dimension {i}: must be finite and > 0, got {w}"),
                ));
            }
            let window = lattice.gaussian_window(i, w, self.cutoff);
            if window > WINDOW as f64 {
                return Err(ApproxError::config(
                    "widths",
                    format!(
                        "dimension {i}: width {w} spans {window} centres within the cutoff; \
                         at most {WINDOW} are supported (use a width near the spacing {})",
                        lattice.spacing(i)
                    ),
                ));
            }
        }
        match self.update {
            RbfUpdate::Nlms { learning_rate } => {
                if !(learning_rate > 0.0 && learning_rate <= 1.0) {
                    return Err(ApproxError::config(
                        "learning_rate",
                        format!("must be in (0, 1], got {learning_rate}"),
                    ));
                }
            }
            RbfUpdate::Rls {
                forgetting,
                prior_variance,
            } => {
                if !(forgetting > 0.0 && forgetting <= 1.0) {
                    return Err(ApproxError::config(
                        "forgetting",
                        format!("must be in (0, 1], got {forgetting}"),
                    ));
                }
                if !(prior_variance.is_finite() && prior_variance > 0.0) {
                    return Err(ApproxError::config(
                        "prior_variance",
                        format!("must be finite and > 0, got {prior_variance}"),
                    ));
                }
                if lattice.len() > MAX_RLS_CENTRES {
                    return Err(ApproxError::config(
                        "centres",
                        format!(
                            "{} centres: recursive least squares supports at most \
                             {MAX_RLS_CENTRES} (its covariance is centres^2); use Nlms",
                            lattice.len()
                        ),
                    ));
                }
            }
        }
        if lattice.len().checked_mul(self.output_dim).is_none() {
            return Err(ApproxError::config(
                "output_dim",
                "weight table size overflows",
            ));
        }
        Ok(lattice)
    }
}

/// A normalised Gaussian RBF network: `f(x) = sum_j phi_j(x) w_j` with
/// `phi_j(x) = g_j(x) / sum_l g_l(x)` and `g_j(x) = exp(-sum_i (x_i - c_ji)^2 / (2 widths_i^2))`,
/// centres `c_j` on a regular grid. Only the output weights `w` are learned (online, by
/// [`RbfUpdate`]); untrained weights are 0.
///
/// Because the Gaussians are separable and the centres form a tensor grid, the normalised
/// basis is a product of per-dimension normalised 1-D bases; each is evaluated over the centres
/// within `cutoff * widths[i]` of `x[i]` (the *active* window, at most 32 per dimension).
///
/// Cost, with `active` = product of the window lengths (about `(2 cutoff widths / spacing)^d`):
/// predict `O(active (d + output_dim))` with no allocation; update the same for
/// [`RbfUpdate::Nlms`], `O(centres^2 + centres * output_dim)` for [`RbfUpdate::Rls`].
///
/// ```
/// use steplearn::approx::{FunctionApproximator, InputBox, Rbf, RbfConfig, RbfUpdate};
/// let bounds = InputBox::cube(1, 0.0, 1.0)?;
/// let update = RbfUpdate::Rls { forgetting: 1.0, prior_variance: 100.0 };
/// let mut net = Rbf::new(RbfConfig { update, ..RbfConfig::new(bounds, vec![11], 1) })?;
/// for i in 0..200 {
///     let x = i as f64 / 199.0;
///     net.update(&[x], &[x * x])?;
/// }
/// let mut y = [0.0];
/// net.predict(&[0.5], &mut y)?;
/// assert!((y[0] - 0.25).abs() < 0.01);
/// # Ok::<(), steplearn::approx::ApproxError>(())
/// ```
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Rbf {
    config: RbfConfig,
    lattice: Lattice,
    /// Output weights, `weights[centre * output_dim + k]`.
    weights: Vec<f64>,
    /// RLS covariance of the weights (column-major, centres x centres; empty for NLMS).
    covariance: Vec<f64>,
    /// Scratch space for the RLS gain (not saved).
    #[serde(skip)]
    scratch: Vec<f64>,
}

impl Rbf {
    /// A network with zero weights, after checking the config.
    pub fn new(config: RbfConfig) -> Result<Self, ApproxError> {
        let lattice = config.validate()?;
        let m = lattice.len();
        let weights = vec![0.0; m * config.output_dim];
        let covariance = match config.update {
            RbfUpdate::Nlms { .. } => Vec::new(),
            RbfUpdate::Rls { prior_variance, .. } => {
                let mut p = vec![0.0; m * m];
                for j in 0..m {
                    p[j * m + j] = prior_variance;
                }
                p
            }
        };
        Ok(Rbf {
            config,
            lattice,
            weights,
            covariance,
            scratch: Vec::new(),
        })
    }

    /// The validated settings.
    pub fn config(&self) -> &RbfConfig {
        &self.config
    }

    /// Number of centres (basis functions).
    pub fn num_centres(&self) -> usize {
        self.lattice.len()
    }

    /// Output weights, `weights()[centre * output_dim + k]`, dimension 0 varying fastest.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The normalised basis at `x` as `(centre index, phi)` pairs over the active window.
    pub fn basis(&self, x: &[f64]) -> Result<Vec<(usize, f64)>, ApproxError> {
        check_vector("input x", x, self.input_dim())?;
        let w = self.features(x);
        let mut out = Vec::with_capacity(w.support());
        self.lattice.for_each(&w, |j, p| out.push((j, p)));
        Ok(out)
    }

    fn features(&self, x: &[f64]) -> TensorWeights<WINDOW> {
        let mut w = TensorWeights::default();
        self.lattice
            .normalised_gaussian(x, &self.config.widths, self.config.cutoff, &mut w);
        w
    }

    fn combine(&self, phi: &TensorWeights<WINDOW>, y: &mut [f64]) {
        let n_out = self.config.output_dim;
        y.fill(0.0);
        self.lattice.for_each(phi, |j, p| {
            for (yk, w) in y.iter_mut().zip(&self.weights[j * n_out..(j + 1) * n_out]) {
                *yk += p * w;
            }
        });
    }

    fn rls_update(
        &mut self,
        phi: &TensorWeights<WINDOW>,
        err: &[f64],
        forgetting: f64,
        prior_variance: f64,
    ) {
        let m = self.lattice.len();
        let n_out = self.config.output_dim;
        let p = &mut self.covariance;
        let u = &mut self.scratch;
        u.clear();
        u.resize(m, 0.0);
        // u = P phi (P is symmetric, so its columns are its rows).
        let mut phi_u = 0.0;
        self.lattice.for_each(phi, |j, pj| {
            for (ui, pij) in u.iter_mut().zip(&p[j * m..(j + 1) * m]) {
                *ui += pj * pij;
            }
        });
        self.lattice.for_each(phi, |j, pj| phi_u += pj * u[j]);
        let inv_denom = 1.0 / (forgetting + phi_u);
        for (i, ui) in u.iter().enumerate() {
            let gain = ui * inv_denom;
            for (w, e) in self.weights[i * n_out..(i + 1) * n_out].iter_mut().zip(err) {
                *w += gain * e;
            }
        }
        // P = (P - u u^T / denom) / forgetting, computed so that P stays exactly symmetric;
        // forgetting only while the trace stays within its initial value.
        let trace: f64 = (0..m).map(|i| p[i * m + i] - u[i] * u[i] * inv_denom).sum();
        let inv_forget = if trace <= forgetting * m as f64 * prior_variance {
            1.0 / forgetting
        } else {
            1.0
        };
        for (j, col) in p.chunks_exact_mut(m).enumerate() {
            let uj = u[j];
            for (pij, ui) in col.iter_mut().zip(u.iter()) {
                *pij = (*pij - ui * uj * inv_denom) * inv_forget;
            }
        }
    }
}

impl PartialEq for Rbf {
    fn eq(&self, other: &Self) -> bool {
        self.config == other.config
            && self.weights == other.weights
            && self.covariance == other.covariance
    }
}

impl FunctionApproximator for Rbf {
    fn input_dim(&self) -> usize {
        self.lattice.dim()
    }

    fn output_dim(&self) -> usize {
        self.config.output_dim
    }

    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        check_vector("input x", x, self.input_dim())?;
        check_output("output y", y, self.output_dim())?;
        let phi = self.features(x);
        self.combine(&phi, y);
        Ok(())
    }

    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        check_vector("input x", x, self.input_dim())?;
        check_vector("target y", y, self.output_dim())?;
        const MAX_OUT_ON_STACK: usize = 8;
        let n_out = self.config.output_dim;
        let phi = self.features(x);
        let mut stack = [0.0; MAX_OUT_ON_STACK];
        let mut heap = Vec::new();
        let err: &mut [f64] = if n_out <= MAX_OUT_ON_STACK {
            &mut stack[..n_out]
        } else {
            heap.resize(n_out, 0.0);
            &mut heap
        };
        self.combine(&phi, err);
        for (e, target) in err.iter_mut().zip(y) {
            *e = target - *e;
        }
        match self.config.update {
            RbfUpdate::Nlms { learning_rate } => {
                let scale = learning_rate / phi.squared_norm();
                let weights = &mut self.weights;
                self.lattice.for_each(&phi, |j, p| {
                    for (w, e) in weights[j * n_out..(j + 1) * n_out]
                        .iter_mut()
                        .zip(err.iter())
                    {
                        *w += scale * p * e;
                    }
                });
            }
            RbfUpdate::Rls {
                forgetting,
                prior_variance,
            } => self.rls_update(&phi, err, forgetting, prior_variance),
        }
        Ok(())
    }
}

impl Persist for Rbf {
    fn check_invariants(&self) -> Result<(), ApproxError> {
        let corrupt = |m: String| Err(ApproxError::Corrupt(format!("rbf: {m}")));
        if let Err(m) = self.lattice.check_table(
            self.config.validate(),
            &self.weights,
            self.config.output_dim,
            "weight",
        ) {
            return corrupt(m);
        }
        let m = self.lattice.len();
        match self.config.update {
            RbfUpdate::Nlms { .. } => {
                if !self.covariance.is_empty() {
                    return corrupt("least mean squares model carries a covariance".into());
                }
            }
            RbfUpdate::Rls { prior_variance, .. } => {
                let p = &self.covariance;
                if p.len() != m * m {
                    return corrupt(format!("covariance has {} entries, not {m}^2", p.len()));
                }
                // Updates never raise the trace above its initial value.
                let trace: f64 = (0..m).map(|i| p[i * m + i]).sum();
                if trace.is_nan() || trace > m as f64 * prior_variance * (1.0 + 1e-9) {
                    return corrupt(format!(
                        "covariance trace {trace} exceeds its initial value"
                    ));
                }
                for i in 0..m {
                    let pii = p[i * m + i];
                    if !(pii.is_finite() && pii > 0.0) {
                        return corrupt(format!("covariance diagonal {i} is {pii}"));
                    }
                    for j in 0..i {
                        let (pij, pji) = (p[j * m + i], p[i * m + j]);
                        if pij != pji || !pij.is_finite() {
                            return corrupt(format!("covariance ({i}, {j}) is not symmetric"));
                        }
                        // A covariance matrix has |P_ij| <= sqrt(P_ii P_jj).
                        if pij * pij > pii * p[j * m + j] * (1.0 + 1e-6) + 1e-300 {
                            return corrupt(format!("covariance ({i}, {j}) is not positive"));
                        }
                    }
                }
            }
        }
        Ok(())
    }
}
