//! The LWPR model: one set of receptive fields per output, creation, pruning and prediction.

use super::config::LwprConfig;
use super::receptive_field::ReceptiveField;
use super::scan::ScanIndex;
use super::workspace::Workspace;
use crate::approx::{ApproxError, FunctionApproximator, check_output, check_vector};
use serde::{Deserialize, Serialize};

/// The largest normalised input (`|x_i / norm_in_i|`) [`Lwpr`] trains on: its fourth power,
/// which the distance metric's curvature accumulates, stays far below what a saved model may
/// hold, so what trains always loads again.
pub const MAX_INPUT: f64 = 1e15;

/// The largest normalised target (`|y_k / norm_out_k|`) [`Lwpr`] trains on: its square times
/// any forgetting-weighted count stays far below what a saved model may hold.
pub const MAX_TARGET: f64 = 1e20;

/// Refuses `v` if an element exceeds `limit` after division by its norm.
fn check_magnitude(
    what: &'static str,
    v: &[f64],
    norm: &[f64],
    limit: f64,
) -> Result<(), ApproxError> {
    match v.iter().zip(norm).position(|(x, n)| (x / n).abs() > limit) {
        Some(index) => Err(ApproxError::OutOfRange {
            what,
            index,
            value: v[index],
            limit: limit * norm[index],
        }),
        None => Ok(()),
    }
}

/// Activations at or below this do not update a receptive field (as in the reference).
pub(crate) const W_UPDATE: f64 = 0.001;

/// The receptive fields that learn one output dimension.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubModel {
    /// The receptive fields.
    pub rfs: Vec<ReceptiveField>,
    /// How many receptive fields were pruned so far.
    pub n_pruned: usize,
    /// With [`LwprConfig::max_rfs`]: for each field, the update count (`n_data`) at which it
    /// was last trained; empty without the cap.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub last_trained: Vec<u64>,
    /// With [`LwprConfig::max_rfs`]: how many fields were replaced at the cap so far.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub n_replaced: usize,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// Locally weighted projection regression (Vijayakumar, D'Souza & Schaal 2005), faithful to
/// the reference library LWPR 1.2.6; see the `steplearn::approx` LWPR module documentation for the
/// algorithm and every deliberate difference.
///
/// ```
/// use steplearn::approx::{FunctionApproximator, Lwpr, LwprConfig};
/// let mut model = Lwpr::new(LwprConfig::new(1, 1).init_d(20.0)).unwrap();
/// for k in 0..2000 {
///     let x = (k % 200) as f64 / 100.0 - 1.0;
///     model.update(&[x], &[2.0 * x + 1.0]).unwrap();
/// }
/// let mut y = [0.0];
/// model.predict(&[0.25], &mut y).unwrap();
/// assert!((y[0] - 1.5).abs() < 0.05);
/// ```
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Lwpr {
    config: LwprConfig,
    /// Cholesky factor of `config.init_d` (derived, kept to avoid recomputation).
    init_m: Vec<f64>,
    /// Number of training samples seen.
    n_data: u64,
    /// Mean of all training inputs (raw units).
    mean_x: Vec<f64>,
    /// Variance of all training inputs (raw units).
    var_x: Vec<f64>,
    /// One submodel per output.
    sub: Vec<SubModel>,
    #[serde(skip)]
    ws: Workspace,
    /// Per output, a column-wise copy of every receptive field's centre and metric (derived,
    /// rebuilt after loading) for the activation scan.
    #[serde(skip)]
    scan: Vec<ScanIndex>,
}

/// Top two activations seen in a scan over receptive fields.
#[derive(Debug, Clone, Copy, Default)]
struct TopTwo {
    w_max: f64,
    ind_max: Option<usize>,
    w_sec: f64,
    ind_sec: Option<usize>,
}

impl TopTwo {
    #[inline]
    fn push(&mut self, w: f64, k: usize) {
        if w > self.w_sec {
            if w > self.w_max {
                self.w_sec = self.w_max;
                self.ind_sec = self.ind_max;
                self.w_max = w;
                self.ind_max = Some(k);
            } else {
                self.w_sec = w;
                self.ind_sec = Some(k);
            }
        }
    }
}

impl Lwpr {
    /// Validates `config` and builds an empty model.
    pub fn new(config: LwprConfig) -> Result<Self, ApproxError> {
        let init_m = config.validate()?;
        let n_out = config.n_out;
        let n_in = config.n_in;
        let mut ws = Workspace::default();
        ws.ensure(n_in);
        Ok(Lwpr {
            init_m,
            n_data: 0,
            mean_x: vec![0.0; n_in],
            var_x: vec![0.0; n_in],
            sub: (0..n_out)
                .map(|_| SubModel {
                    rfs: Vec::new(),
                    n_pruned: 0,
                    last_trained: Vec::new(),
                    n_replaced: 0,
                })
                .collect(),
            scan: vec![ScanIndex::default(); n_out],
            config,
            ws,
        })
    }

    /// The configuration the model was built with.
    pub fn config(&self) -> &LwprConfig {
        &self.config
    }

    /// Number of receptive fields over all outputs.
    pub fn num_receptive_fields(&self) -> usize {
        self.sub.iter().map(|s| s.rfs.len()).sum()
    }

    /// The receptive fields learning output `k` (read-only, for inspection).
    pub fn submodel(&self, k: usize) -> Option<&SubModel> {
        self.sub.get(k)
    }

    /// Number of training samples seen.
    pub fn n_data(&self) -> u64 {
        self.n_data
    }

    /// Mean and variance of all training inputs seen (raw units).
    pub fn input_stats(&self) -> (&[f64], &[f64]) {
        (&self.mean_x, &self.var_x)
    }

    /// Prediction at `x` into `y` and, per output, a confidence bound into `conf` (the
    /// reference's `lwpr_predict` with `conf`): the square root of the activation-weighted
    /// predictive variance of the contributing receptive fields plus the weighted spread of
    /// their predictions, divided by the summed activation. Where no trustworthy receptive
    /// field is active, `y` is 0 and `conf` is infinite.
    pub fn predict_with_confidence(
        &self,
        x: &[f64],
        y: &mut [f64],
        conf: &mut [f64],
    ) -> Result<(), ApproxError> {
        check_output("confidence conf", conf, self.config.n_out)?;
        self.predict_impl(x, y, Some(conf))
    }

    fn predict_impl(
        &self,
        x: &[f64],
        y: &mut [f64],
        mut conf: Option<&mut [f64]>,
    ) -> Result<(), ApproxError> {
        let n = self.config.n_in;
        check_vector("input x", x, n)?;
        check_output("output y", y, self.config.n_out)?;
        with_scratch(2 * n, |buf| {
            let (xn, xu) = buf.split_at_mut(n);
            for ((v, xi), ni) in xn.iter_mut().zip(x).zip(&self.config.norm_in) {
                *v = xi / ni;
            }
            let cutoff = self.config.cutoff;
            let limit = self.config.kernel.q_limit(cutoff);
            for (k, sub) in self.sub.iter().enumerate() {
                let (mut sum_w, mut sum_wy, mut sum_wyy, mut sum_conf) = (0.0, 0.0, 0.0, 0.0);
                let diag_only = self.config.diag_only;
                let index = self
                    .scan
                    .get(k)
                    .filter(|v| v.matches(n, diag_only, sub.rfs.len()));
                for (idx, rf) in sub.rfs.iter().enumerate() {
                    if !rf.trustworthy {
                        continue;
                    }
                    let q = match index {
                        Some(v) => v.distance(idx, xn, limit),
                        None => rf.squared_distance(xn, limit, diag_only),
                    };
                    let Some(q) = q else {
                        continue;
                    };
                    let w = self.config.kernel.weight(q);
                    if w <= cutoff {
                        continue;
                    }
                    let (yk, s2) = rf.local_prediction(xn, xu);
                    sum_w += w;
                    sum_wy += w * yk;
                    if conf.is_some() {
                        sum_wyy += w * yk * yk;
                        sum_conf += w * rf.predictive_variance(w, s2);
                    }
                }
                let norm = self.config.norm_out[k];
                let mean = if sum_w > 0.0 { sum_wy / sum_w } else { 0.0 };
                y[k] = mean * norm;
                if let Some(c) = conf.as_deref_mut() {
                    c[k] = if sum_w > 0.0 {
                        norm * (sum_conf + sum_wyy - sum_wy * mean).abs().sqrt() / sum_w
                    } else {
                        f64::INFINITY
                    };
                }
            }
        });
        // Only reachable with a tampered model whose numbers are finite but absurd.
        if let Some(index) = y.iter().position(|v| !v.is_finite()) {
            return Err(ApproxError::NonFinite {
                what: "prediction (model state out of range)",
                index,
                value: y[index],
            });
        }
        Ok(())
    }

    /// One training step for output `k` at normalised input `xn` with normalised target `yn`.
    fn update_output(&mut self, k: usize, yn: f64) {
        let config = &self.config;
        let sub = &mut self.sub[k];
        let ws = &mut self.ws;
        let n = config.n_in;
        // Receptive fields whose activation is at or below this cannot matter: they are not
        // updated and cannot be the template of a new one.
        let w_skip = W_UPDATE.min(0.1 * config.w_gen);
        let limit = config.kernel.q_limit(w_skip);
        let mut top = TopTwo::default();
        let xn = std::mem::take(&mut ws.xn);
        let diag_only = config.diag_only;
        // With a cap on the fields, the update count stamps every field trained.
        let (cap, stamp) = (config.max_rfs, self.n_data);
        if self.scan.len() != config.n_out {
            self.scan.resize(config.n_out, ScanIndex::default());
        }
        let scan = &mut self.scan[k];
        if !scan.matches(n, diag_only, sub.rfs.len()) {
            // After loading (the index is not saved): rebuild it once.
            *scan = ScanIndex::build(n, diag_only, &sub.rfs);
        }
        // All distances first (vectorised over the fields), then the fields within reach:
        // the same fields, activations and training as a scan that trains as it goes,
        // since a field's training changes only its own entry.
        scan.distances(&xn, &mut ws.q, &mut ws.row);
        for idx in 0..scan.len() {
            let q = ws.q[idx];
            if q > limit {
                continue;
            }
            let act = config.kernel.activation(q);
            top.push(act.w, idx);
            if act.w > W_UPDATE {
                let rf = &mut sub.rfs[idx];
                rf.train(config, &xn, yn, act, ws);
                if cap.is_some() {
                    sub.last_trained[idx] = stamp;
                }
                if config.update_d {
                    scan.write_metric(idx, rf);
                }
            }
        }
        if top.w_max <= config.w_gen {
            let template = match top.ind_max {
                Some(i) if top.w_max > 0.1 * config.w_gen && sub.rfs[i].trustworthy => {
                    Some(&sub.rfs[i])
                }
                _ => None,
            };
            let rf = ReceptiveField::new(config, &self.init_m, template, &xn[..n], yn);
            match cap {
                Some(cap) if sub.rfs.len() >= cap => {
                    // Replace the field trained least recently (the first of equals).
                    let victim = (0..sub.rfs.len())
                        .min_by_key(|&i| (sub.last_trained[i], i))
                        .unwrap_or(0);
                    scan.write(victim, &rf);
                    sub.rfs[victim] = rf;
                    sub.last_trained[victim] = stamp;
                    sub.n_replaced += 1;
                }
                _ => {
                    scan.push(&rf);
                    sub.rfs.push(rf);
                    if cap.is_some() {
                        sub.last_trained.push(stamp);
                    }
                }
            }
        } else if let (true, Some(a), Some(b)) =
            (top.w_sec > config.w_prune, top.ind_max, top.ind_sec)
        {
            // Remove the narrower of the two (larger trace of D), as the documentation
            // and the MATLAB code do.
            let prune = if sub.rfs[a].trace_d() > sub.rfs[b].trace_d() {
                a
            } else {
                b
            };
            sub.rfs.swap_remove(prune);
            scan.swap_remove(prune);
            if cap.is_some() {
                sub.last_trained.swap_remove(prune);
            }
            sub.n_pruned += 1;
        }
        ws.xn = xn;
    }
}

/// Runs `f` on a zeroed scratch slice of length `len`: on the stack for small inputs, on the
/// heap only for inputs with more than 32 dimensions.
fn with_scratch<R>(len: usize, f: impl FnOnce(&mut [f64]) -> R) -> R {
    const STACK: usize = 64;
    if len <= STACK {
        let mut buf = [0.0; STACK];
        f(&mut buf[..len])
    } else {
        let mut buf = vec![0.0; len];
        f(&mut buf)
    }
}

impl FunctionApproximator for Lwpr {
    fn input_dim(&self) -> usize {
        self.config.n_in
    }

    fn output_dim(&self) -> usize {
        self.config.n_out
    }

    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        self.predict_impl(x, y, None)
    }

    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        let n = self.config.n_in;
        check_vector("input x", x, n)?;
        check_vector("target y", y, self.config.n_out)?;
        check_magnitude("input x", x, &self.config.norm_in, MAX_INPUT)?;
        check_magnitude("target y", y, &self.config.norm_out, MAX_TARGET)?;
        // Nothing below can fail: a rejected sample never reaches this point.
        self.ws.ensure(n);
        self.n_data += 1;
        let count = self.n_data as f64;
        for i in 0..n {
            let mean = (self.mean_x[i] * (count - 1.0) + x[i]) / count;
            self.mean_x[i] = mean;
            let d = x[i] - mean;
            self.var_x[i] = (self.var_x[i] * (count - 1.0) + d * d) / count;
            self.ws.xn[i] = x[i] / self.config.norm_in[i];
        }
        for (k, yk) in y.iter().enumerate() {
            self.update_output(k, yk / self.config.norm_out[k]);
        }
        Ok(())
    }
}

impl Lwpr {
    pub(crate) fn parts(&self) -> (&LwprConfig, &[f64], &[f64], &[f64], &[SubModel]) {
        (
            &self.config,
            &self.init_m,
            &self.mean_x,
            &self.var_x,
            &self.sub,
        )
    }
}
