//! LWPR configuration: the reference library's parameters, their defaults and validation.

use super::kernel::Kernel;
use super::linalg::cholesky_upper;
use crate::approx::ApproxError;
use serde::{Deserialize, Serialize};

/// Parameters of an [`Lwpr`](super::Lwpr) model, named after the reference library
/// (LWPR 1.2.6, `lwpr_init_model`).
///
/// [`LwprConfig::new`] holds the reference defaults; the consuming setters change one
/// parameter each. Nothing is checked until [`Lwpr::new`](super::Lwpr::new) validates the whole
/// configuration.
///
/// ```
/// use steplearn::approx::{Kernel, LwprConfig};
/// let config = LwprConfig::new(2, 1).init_d(50.0).init_alpha(250.0).w_gen(0.2).kernel(Kernel::Gaussian);
/// assert_eq!(config.w_gen, 0.2);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LwprConfig {
    /// Number of inputs.
    pub n_in: usize,
    /// Number of outputs (each output is learned by its own set of receptive fields).
    pub n_out: usize,
    /// Initial distance metric of new receptive fields, `n_in x n_in`, column-major, symmetric
    /// positive definite (in normalised input units). Default `25 I`.
    pub init_d: Vec<f64>,
    /// Initial learning rate of every distance-metric element. Default 50.
    pub init_alpha: f64,
    /// A new receptive field is created when no activation exceeds this. Default 0.1.
    pub w_gen: f64,
    /// When two activations exceed this, the narrower receptive field is removed. Default 1.0
    /// (which never triggers for the Gaussian kernel: activations are at most 1).
    pub w_prune: f64,
    /// Meta learning (incremental delta-bar-delta) of the metric learning rates. Default off.
    pub meta: bool,
    /// Meta learning rate. Default 250.
    pub meta_rate: f64,
    /// Penalty on large distance metrics (smoothness). Default 1e-6.
    pub penalty: f64,
    /// Keep distance metrics diagonal. Default on.
    pub diag_only: bool,
    /// Adapt the distance metrics. Default on.
    pub update_d: bool,
    /// Initial forgetting factor. Default 0.999.
    pub init_lambda: f64,
    /// Final forgetting factor. Default 0.99999.
    pub final_lambda: f64,
    /// Annealing rate of the forgetting factor. Default 0.9999.
    pub tau_lambda: f64,
    /// Initial variance of new PLS projections. Default 1e-10.
    pub init_s2: f64,
    /// A PLS projection is added when the newest one reduced the CV error below this ratio of
    /// the previous one. Default 0.5.
    pub add_threshold: f64,
    /// Locality kernel. Default Gaussian.
    pub kernel: Kernel,
    /// Input normalisation: input `i` is divided by `norm_in[i]`. Default all 1.
    pub norm_in: Vec<f64>,
    /// Output normalisation: output `k` is divided by `norm_out[k]`. Default all 1.
    pub norm_out: Vec<f64>,
    /// Receptive fields with activation at or below this do not contribute to predictions
    /// (the reference passes it to every `lwpr_predict` call; its demo uses 0.001). Default 0.001.
    pub cutoff: f64,
    /// At most this many receptive fields per output (see [`LwprConfig::max_rfs`]). Default
    /// none: unbounded, as the reference library.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_rfs: Option<usize>,
}

impl LwprConfig {
    /// The reference library's defaults for `n_in` inputs and `n_out` outputs.
    pub fn new(n_in: usize, n_out: usize) -> Self {
        LwprConfig {
            n_in,
            n_out,
            init_d: diagonal(&vec![25.0; n_in]),
            init_alpha: 50.0,
            w_gen: 0.1,
            w_prune: 1.0,
            meta: false,
            meta_rate: 250.0,
            penalty: 1e-6,
            diag_only: true,
            update_d: true,
            init_lambda: 0.999,
            final_lambda: 0.99999,
            tau_lambda: 0.9999,
            init_s2: 1e-10,
            add_threshold: 0.5,
            kernel: Kernel::Gaussian,
            norm_in: vec![1.0; n_in],
            norm_out: vec![1.0; n_out],
            cutoff: 0.001,
            max_rfs: None,
        }
    }

    /// Spherical initial distance metric `value * I`.
    pub fn init_d(mut self, value: f64) -> Self {
        self.init_d = diagonal(&vec![value; self.n_in]);
        self
    }

    /// Diagonal initial distance metric.
    pub fn init_d_diag(mut self, diag: Vec<f64>) -> Self {
        self.init_d = if diag.len() == self.n_in {
            diagonal(&diag)
        } else {
            diag // keeps the wrong length so that validation reports it
        };
        self
    }

    /// Full initial distance metric (`n_in x n_in`, column-major; needs `diag_only(false)`
    /// unless it is diagonal).
    pub fn init_d_matrix(mut self, d: Vec<f64>) -> Self {
        self.init_d = d;
        self
    }

    /// Initial learning rate of the distance metric.
    pub fn init_alpha(mut self, value: f64) -> Self {
        self.init_alpha = value;
        self
    }

    /// Activation threshold below which a new receptive field is created.
    pub fn w_gen(mut self, value: f64) -> Self {
        self.w_gen = value;
        self
    }

    /// Activation threshold above which one of two overlapping receptive fields is pruned.
    pub fn w_prune(mut self, value: f64) -> Self {
        self.w_prune = value;
        self
    }

    /// Meta learning of the metric learning rates on or off.
    pub fn meta(mut self, on: bool) -> Self {
        self.meta = on;
        self
    }

    /// Meta learning rate.
    pub fn meta_rate(mut self, value: f64) -> Self {
        self.meta_rate = value;
        self
    }

    /// Penalty on large distance metrics.
    pub fn penalty(mut self, value: f64) -> Self {
        self.penalty = value;
        self
    }

    /// Diagonal-only distance metrics on or off.
    pub fn diag_only(mut self, on: bool) -> Self {
        self.diag_only = on;
        self
    }

    /// Distance-metric adaptation on or off.
    pub fn update_d(mut self, on: bool) -> Self {
        self.update_d = on;
        self
    }

    /// Initial forgetting factor.
    pub fn init_lambda(mut self, value: f64) -> Self {
        self.init_lambda = value;
        self
    }

    /// Final forgetting factor.
    pub fn final_lambda(mut self, value: f64) -> Self {
        self.final_lambda = value;
        self
    }

    /// Annealing rate of the forgetting factor.
    pub fn tau_lambda(mut self, value: f64) -> Self {
        self.tau_lambda = value;
        self
    }

    /// Initial variance of new PLS projections.
    pub fn init_s2(mut self, value: f64) -> Self {
        self.init_s2 = value;
        self
    }

    /// CV-error ratio below which a PLS projection is added.
    pub fn add_threshold(mut self, value: f64) -> Self {
        self.add_threshold = value;
        self
    }

    /// Locality kernel.
    pub fn kernel(mut self, kernel: Kernel) -> Self {
        self.kernel = kernel;
        self
    }

    /// Input normalisation factors.
    pub fn norm_in(mut self, norm: Vec<f64>) -> Self {
        self.norm_in = norm;
        self
    }

    /// Output normalisation factors.
    pub fn norm_out(mut self, norm: Vec<f64>) -> Self {
        self.norm_out = norm;
        self
    }

    /// Caps the receptive fields of each output at `n` (at least 1), for learners that run for
    /// days on drifting inputs: when a new field is due and `n` exist, it replaces the field
    /// that was trained least recently (ties: the oldest position), so memory and the cost of
    /// an update stay bounded. Off by default; without it the model is the reference library's.
    pub fn max_rfs(mut self, n: usize) -> Self {
        self.max_rfs = Some(n);
        self
    }

    /// Prediction cutoff activation.
    pub fn cutoff(mut self, value: f64) -> Self {
        self.cutoff = value;
        self
    }

    /// Checks every parameter and returns the Cholesky factor `M` (upper triangular,
    /// `init_d = M^T M`, column-major) of the initial distance metric.
    pub(crate) fn validate(&self) -> Result<Vec<f64>, ApproxError> {
        let n = self.n_in;
        if n == 0 {
            return Err(ApproxError::config("n_in", "must be at least 1"));
        }
        if self.n_out == 0 {
            return Err(ApproxError::config("n_out", "must be at least 1"));
        }
        let Some(nn) = n.checked_mul(n) else {
            return Err(ApproxError::config("n_in", format!("{n} is too large")));
        };
        if self.init_d.len() != nn {
            return Err(ApproxError::config(
                "init_d",
                format!("needs {n} x {n} = {nn} elements, got {}", self.init_d.len()),
            ));
        }
        if let Some(v) = self.init_d.iter().find(|v| !v.is_finite()) {
            return Err(ApproxError::config(
                "init_d",
                format!("must be finite, got {v}"),
            ));
        }
        for i in 0..n {
            let d = self.init_d[i + i * n];
            if d <= 0.0 {
                return Err(ApproxError::config(
                    "init_d",
                    format!("diagonal must be positive, got {d} at ({i}, {i})"),
                ));
            }
            for j in 0..n {
                let (a, b) = (self.init_d[i + j * n], self.init_d[j + i * n]);
                if a != b {
                    return Err(ApproxError::config("init_d", "must be symmetric"));
                }
                if i != j && a != 0.0 && self.diag_only {
                    return Err(ApproxError::config(
                        "init_d",
                        "must be diagonal when diag_only is on",
                    ));
                }
            }
        }
        let init_m = cholesky_upper(n, &self.init_d)
            .ok_or_else(|| ApproxError::config("init_d", "must be positive definite"))?;
        positive("init_alpha", self.init_alpha)?;
        open_unit("w_gen", self.w_gen)?;
        if !(self.w_prune > self.w_gen && self.w_prune <= 1.0) {
            return Err(ApproxError::config(
                "w_prune",
                format!(
                    "must be in (w_gen, 1] = ({}, 1], got {}",
                    self.w_gen, self.w_prune
                ),
            ));
        }
        positive("meta_rate", self.meta_rate)?;
        if !(self.penalty >= 0.0 && self.penalty.is_finite()) {
            return Err(ApproxError::config(
                "penalty",
                format!("must be finite and >= 0, got {}", self.penalty),
            ));
        }
        half_open_unit("init_lambda", self.init_lambda)?;
        half_open_unit("final_lambda", self.final_lambda)?;
        half_open_unit("tau_lambda", self.tau_lambda)?;
        positive("init_s2", self.init_s2)?;
        positive("add_threshold", self.add_threshold)?;
        norms("norm_in", &self.norm_in, n)?;
        norms("norm_out", &self.norm_out, self.n_out)?;
        if self.max_rfs == Some(0) {
            return Err(ApproxError::config("max_rfs", "must be at least 1"));
        }
        if !(0.0..1.0).contains(&self.cutoff) {
            return Err(ApproxError::config(
                "cutoff",
                format!("must be in [0, 1), got {}", self.cutoff),
            ));
        }
        Ok(init_m)
    }
}

fn diagonal(diag: &[f64]) -> Vec<f64> {
    let n = diag.len();
    let mut d = vec![0.0; n * n];
    for (i, v) in diag.iter().enumerate() {
        d[i + i * n] = *v;
    }
    d
}

fn positive(param: &'static str, v: f64) -> Result<(), ApproxError> {
    if v > 0.0 && v.is_finite() {
        Ok(())
    } else {
        Err(ApproxError::config(
            param,
            format!("must be finite and > 0, got {v}"),
        ))
    }
}

fn open_unit(param: &'static str, v: f64) -> Result<(), ApproxError> {
    if v > 0.0 && v < 1.0 {
        Ok(())
    } else {
        Err(ApproxError::config(
            param,
            format!("must be in (0, 1), got {v}"),
        ))
    }
}

fn half_open_unit(param: &'static str, v: f64) -> Result<(), ApproxError> {
    if v > 0.0 && v <= 1.0 {
        Ok(())
    } else {
        Err(ApproxError::config(
            param,
            format!("must be in (0, 1], got {v}"),
        ))
    }
}

fn norms(param: &'static str, v: &[f64], expected: usize) -> Result<(), ApproxError> {
    if v.len() != expected {
        return Err(ApproxError::config(
            param,
            format!("needs {expected} elements, got {}", v.len()),
        ));
    }
    match v.iter().find(|x| !(**x > 0.0 && x.is_finite())) {
        Some(x) => Err(ApproxError::config(
            param,
            format!("must be finite and > 0, got {x}"),
        )),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rejects(config: LwprConfig, param: &str) {
        match config.validate() {
            Err(ApproxError::InvalidConfig { param: p, .. }) => assert_eq!(p, param),
            other => panic!("expected invalid {param}, got {other:?}"),
        }
    }

    #[test]
    fn defaults_are_the_reference_defaults_and_valid() {
        let c = LwprConfig::new(2, 1);
        assert_eq!(c.init_d, vec![25.0, 0.0, 0.0, 25.0]);
        assert_eq!((c.init_alpha, c.w_gen, c.w_prune), (50.0, 0.1, 1.0));
        assert_eq!(
            (c.init_lambda, c.final_lambda, c.tau_lambda),
            (0.999, 0.99999, 0.9999)
        );
        assert_eq!(
            (c.init_s2, c.add_threshold, c.penalty, c.meta_rate),
            (1e-10, 0.5, 1e-6, 250.0)
        );
        assert!(c.diag_only && c.update_d && !c.meta);
        let m = c.validate().unwrap();
        assert_eq!(m, vec![5.0, 0.0, 0.0, 5.0]);
    }

    #[test]
    fn invalid_parameters_are_named() {
        let c = || LwprConfig::new(2, 1);
        rejects(LwprConfig::new(0, 1), "n_in");
        rejects(LwprConfig::new(2, 0), "n_out");
        rejects(c().init_d(0.0), "init_d");
        rejects(c().init_d(-1.0), "init_d");
        rejects(c().init_d(f64::NAN), "init_d");
        rejects(c().init_d_diag(vec![1.0]), "init_d");
        rejects(c().init_d_matrix(vec![1.0, 0.5, 0.5, 1.0]), "init_d");
        rejects(
            c().diag_only(false).init_d_matrix(vec![1.0, 2.0, 2.0, 1.0]),
            "init_d",
        );
        rejects(
            c().diag_only(false).init_d_matrix(vec![1.0, 0.2, 0.3, 1.0]),
            "init_d",
        );
        rejects(c().init_alpha(0.0), "init_alpha");
        rejects(c().w_gen(0.0), "w_gen");
        rejects(c().w_gen(1.0), "w_gen");
        rejects(c().w_prune(0.05), "w_prune");
        rejects(c().w_prune(1.5), "w_prune");
        rejects(c().meta_rate(-1.0), "meta_rate");
        rejects(c().penalty(-1.0), "penalty");
        rejects(c().init_lambda(0.0), "init_lambda");
        rejects(c().final_lambda(1.01), "final_lambda");
        rejects(c().tau_lambda(f64::NAN), "tau_lambda");
        rejects(c().init_s2(0.0), "init_s2");
        rejects(c().add_threshold(0.0), "add_threshold");
        rejects(c().norm_in(vec![1.0, 0.0]), "norm_in");
        rejects(c().norm_in(vec![1.0]), "norm_in");
        rejects(c().norm_out(vec![f64::INFINITY]), "norm_out");
        rejects(c().cutoff(1.0), "cutoff");
        assert!(
            c().diag_only(false)
                .init_d_matrix(vec![2.0, 0.5, 0.5, 1.0])
                .validate()
                .is_ok()
        );
    }
}
