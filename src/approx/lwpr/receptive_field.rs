//! One receptive field: a local linear model fitted by incremental partial least squares.
//!
//! Matrices are column-major. `n x n` matrices (`d`, `m`, `alpha`, `b`, `h`) follow the
//! reference's convention that `m` is upper triangular with `d = m^T m`. `n x R` matrices
//! (`sxres_yres`, `ssxres`, `u`, `p`) store projection `r` in `[r * n .. (r + 1) * n]`.

use super::config::LwprConfig;
use super::dim::{Dynamic, Fixed, InputDim};
use super::kernel::Activation;
use super::linalg::{axpy, dot};
use super::workspace::Workspace;
use serde::{Deserialize, Serialize};

/// A receptive field: centre, distance metric, and its PLS regression with all sufficient
/// statistics (field names follow the reference library's `LWPR_ReceptiveField`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReceptiveField {
    /// Whether it has seen enough data (`n_data > 2 n_in`) to contribute to predictions.
    pub trustworthy: bool,
    /// Accumulated (non-cross-validated) training error.
    pub sum_e2: f64,
    /// Intercept: the weighted mean of the outputs it was trained on.
    pub beta0: f64,
    /// Sufficient statistic for the confidence bounds.
    pub ssp: f64,
    /// Centre (normalised input units).
    pub c: Vec<f64>,
    /// Distance metric `D = M^T M` (`n x n`).
    pub d: Vec<f64>,
    /// Upper-triangular Cholesky factor `M` of `D` (`n x n`).
    pub m: Vec<f64>,
    /// Learning rates of the elements of `M` (`n x n`).
    pub alpha: Vec<f64>,
    /// Meta learning: log learning rates (`n x n`).
    pub b: Vec<f64>,
    /// Meta learning: memory traces (`n x n`).
    pub h: Vec<f64>,
    /// PLS regression coefficients (`R`).
    pub beta: Vec<f64>,
    /// Sufficient statistics of the projection directions `u` (`n x R`).
    pub sxres_yres: Vec<f64>,
    /// Weighted sums of squared loadings (`R`).
    pub ss_s2: Vec<f64>,
    /// Sufficient statistics of `beta` (`R`).
    pub ss_yres: Vec<f64>,
    /// Sufficient statistics of the input reductions `p` (`n x R`).
    pub ss_xres: Vec<f64>,
    /// PLS projection directions, unit length (`n x R`).
    pub u: Vec<f64>,
    /// PLS input reductions (`n x R`).
    pub p: Vec<f64>,
    /// Distance-metric memory term `H` (`R`).
    pub big_h: Vec<f64>,
    /// Distance-metric memory term `r` (`R`).
    pub r: Vec<f64>,
    /// Accumulated activation per projection (`R`).
    pub sum_w: Vec<f64>,
    /// Accumulated cross-validation error per projection (`R`).
    pub sum_e_cv2: Vec<f64>,
    /// Weighted number of samples per projection (`R`).
    pub n_data: Vec<f64>,
    /// Forgetting factor per projection (`R`).
    pub lambda: Vec<f64>,
    /// Weighted mean of the inputs it was trained on (`n`).
    pub mean_x: Vec<f64>,
    /// Weighted variance of the inputs it was trained on (`n`).
    pub var_x: Vec<f64>,
}

/// What one training step of a receptive field reports back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct RegressionStep {
    /// The field's prediction at the sample (after its update).
    pub yp: f64,
    /// Cross-validation error of the projections used for prediction.
    pub e_cv: f64,
    /// Training error (after the update).
    pub e: f64,
}

impl ReceptiveField {
    /// A new receptive field centred at `xc`, a copy of `template`'s metric and projection
    /// count if given, else the configured initial metric.
    pub(crate) fn new(
        config: &LwprConfig,
        init_m: &[f64],
        template: Option<&ReceptiveField>,
        xc: &[f64],
        y: f64,
    ) -> Self {
        let n = config.n_in;
        let (n_reg, d, m, alpha, beta0) = match template {
            Some(t) => (
                t.n_reg(),
                t.d.clone(),
                t.m.clone(),
                t.alpha.clone(),
                t.beta0,
            ),
            None => (
                if n > 1 { 2 } else { 1 },
                config.init_d.clone(),
                init_m.to_vec(),
                vec![config.init_alpha; n * n],
                y,
            ),
        };
        let mut b = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..=j {
                b[i + j * n] = (alpha[i + j * n] + 1e-10).ln();
            }
        }
        // Reserve room for all n projections so that adding one never reallocates.
        let per_reg = |v: f64| {
            let mut x = Vec::with_capacity(n);
            x.resize(n_reg, v);
            x
        };
        let per_reg_vec = || {
            let mut x = Vec::with_capacity(n * n);
            x.resize(n * n_reg, 0.0);
            x
        };
        let mut u = per_reg_vec();
        let mut p = per_reg_vec();
        for r in 0..n_reg {
            u[r + r * n] = 1.0;
            p[r + r * n] = 1.0;
        }
        ReceptiveField {
            trustworthy: false,
            sum_e2: 0.0,
            beta0,
            ssp: 0.0,
            c: xc.to_vec(),
            d,
            m,
            alpha,
            b,
            h: vec![0.0; n * n],
            beta: per_reg(0.0),
            sxres_yres: per_reg_vec(),
            ss_s2: per_reg(config.init_s2),
            ss_yres: per_reg(0.0),
            ss_xres: per_reg_vec(),
            u,
            p,
            big_h: per_reg(0.0),
            r: per_reg(0.0),
            sum_w: per_reg(1e-10),
            sum_e_cv2: per_reg(0.0),
            n_data: per_reg(1e-10),
            lambda: per_reg(config.init_lambda),
            mean_x: vec![0.0; n],
            var_x: vec![0.0; n],
        }
    }

    /// Number of PLS projections `R`.
    pub fn n_reg(&self) -> usize {
        self.beta.len()
    }

    /// Number of inputs.
    pub fn n_in(&self) -> usize {
        self.c.len()
    }

    /// `q = (x - c)^T D (x - c)`, or `None` as soon as a partial sum proves `q > limit`.
    #[inline]
    pub(crate) fn squared_distance(&self, xn: &[f64], limit: f64, diag_only: bool) -> Option<f64> {
        let n = self.c.len();
        let mut q = 0.0;
        if diag_only {
            for i in 0..n {
                let dx = xn[i] - self.c[i];
                q += self.d[i + i * n] * dx * dx;
                if q > limit {
                    return None;
                }
            }
        } else {
            // q = |M dx|^2 with M upper triangular: the partial sums only grow.
            for k in 0..n {
                let mut row = 0.0;
                for i in k..n {
                    row += self.m[k + i * n] * (xn[i] - self.c[i]);
                }
                q += row * row;
                if q > limit {
                    return None;
                }
            }
        }
        Some(q)
    }

    /// Number of projections trusted for prediction: the newest one only once it has seen
    /// more than `2 n` samples.
    #[inline]
    pub(crate) fn n_reg_trusted(&self) -> usize {
        let nr = self.n_reg();
        if self.n_data[nr - 1] > 2.0 * self.n_in() as f64 {
            nr
        } else {
            nr - 1
        }
    }

    /// The local model's output at normalised input `xn` and `sum_r s_r^2 / SSs2_r`
    /// (for the confidence bound), using `xu` (length `n`) as scratch.
    #[inline]
    pub(crate) fn local_prediction(&self, xn: &[f64], xu: &mut [f64]) -> (f64, f64) {
        let n = self.n_in();
        for ((u, x), m) in xu.iter_mut().zip(xn).zip(&self.mean_x) {
            *u = x - m;
        }
        let nr = self.n_reg_trusted();
        let mut y = self.beta0;
        let mut s2 = 0.0;
        for r in 0..nr {
            let s = dot(&self.u[r * n..(r + 1) * n], xu);
            y += s * self.beta[r];
            s2 += s * s / self.ss_s2[r];
            if r + 1 < nr {
                axpy(xu, -s, &self.p[r * n..(r + 1) * n]);
            }
        }
        (y, s2)
    }

    /// Confidence-bound variance of this field's prediction given `s2` from
    /// [`Self::local_prediction`] and activation `w`.
    pub(crate) fn predictive_variance(&self, w: f64, s2: f64) -> f64 {
        let r = self.n_reg_trusted().max(1) - 1;
        self.sum_e_cv2[r] / (self.sum_w[r] - self.ssp) * (1.0 + w * s2)
    }

    /// Updates the weighted input mean and variance and the intercept; writes `x - mean_x`
    /// into `xmz` and returns `y - beta0`.
    pub(crate) fn update_means<D: InputDim>(
        &mut self,
        dim: D,
        x: &[f64],
        y: f64,
        w: f64,
        xmz: &mut [f64],
    ) -> f64 {
        let swl = self.sum_w[0] * self.lambda[0];
        let inv = 1.0 / (swl + w);
        for i in 0..dim.n() {
            let mean = (swl * self.mean_x[i] + w * x[i]) * inv;
            self.mean_x[i] = mean;
            let dx = x[i] - mean;
            xmz[i] = dx;
            self.var_x[i] = (swl * self.var_x[i] + w * dx * dx) * inv;
        }
        self.beta0 = (swl * self.beta0 + w * y) * inv;
        y - self.beta0
    }

    /// One weighted incremental PLS step on the mean-free sample (`ws.xmz`, `y`).
    ///
    /// Leaves the loadings of the updated projections at the sample in `ws.s`.
    pub(crate) fn update_regression<D: InputDim>(
        &mut self,
        dim: D,
        y: f64,
        w: f64,
        ws: &mut Workspace,
    ) -> RegressionStep {
        let n = dim.n();
        let nr = self.n_reg();
        let used = self.n_reg_trusted();
        // Every array cut to its length up front, so that the loops below need no bounds
        // checks and keep the data pointers in registers.
        let ReceptiveField {
            beta,
            sum_w,
            lambda,
            sxres_yres,
            u,
            ss_s2,
            ss_yres,
            ss_xres,
            p,
            ..
        } = self;
        let (beta, sum_w, lambda) = (&mut beta[..nr], &mut sum_w[..nr], &lambda[..nr]);
        let (ss_s2, ss_yres) = (&mut ss_s2[..nr], &mut ss_yres[..nr]);
        let (sxres_yres, u) = (&mut sxres_yres[..n * nr], &mut u[..n * nr]);
        let (ss_xres, p) = (&mut ss_xres[..n * nr], &mut p[..n * nr]);
        let xmz = &ws.xmz[..n];
        let xres = &mut ws.xres[..n * nr];
        let (s_buf, e_cv, ytarget) = (&mut ws.s[..nr], &mut ws.e_cv[..nr], &mut ws.ytarget[..nr]);
        // Loadings and input residuals with the current projections. The residual before
        // projection 0 is the mean-free input itself: it is read from `ws.xmz`, and
        // `ws.xres[..n]` is not used (copying a few numbers costs a library call).
        for r in 0..nr {
            let (done, rest) = xres.split_at_mut((r + 1) * n);
            let xr = if r == 0 { xmz } else { &done[r * n..] };
            let s = dot(&u[r * n..(r + 1) * n], xr);
            s_buf[r] = s;
            if r + 1 < nr {
                let pr = &p[r * n..(r + 1) * n];
                for ((next, x), pi) in rest[..n].iter_mut().zip(xr).zip(pr) {
                    *next = x - pi * s;
                }
            }
        }
        let mut yres = 0.0;
        for r in 0..nr {
            yres += beta[r] * s_buf[r];
            sum_w[r] = sum_w[r] * lambda[r] + w;
            e_cv[r] = y - yres;
            // Projection r + 1 regresses what the first r + 1 left unexplained.
            if r + 1 < nr {
                ytarget[r + 1] = e_cv[r];
            }
        }
        ytarget[0] = y;
        let mut ws2_ss_s2 = 0.0;
        for r in 0..nr {
            let col = r * n..(r + 1) * n;
            let lambda_r = lambda[r];
            let lambda_slow = 0.9 + 0.1 * lambda_r;
            let wyt = w * ytarget[r];
            let xr = if r == 0 { xmz } else { &xres[col.clone()] };
            let sxy_r = &mut sxres_yres[col.clone()];
            let mut norm2 = 0.0;
            for (sxy, x) in sxy_r.iter_mut().zip(xr) {
                *sxy = *sxy * lambda_slow + wyt * x;
                norm2 += *sxy * *sxy;
            }
            if norm2 > 1e-24 {
                let inv = 1.0 / norm2.sqrt();
                for (u, sxy) in u[col.clone()].iter_mut().zip(sxy_r.iter()) {
                    *u = inv * sxy;
                }
            }
            let s = s_buf[r];
            let ws_r = w * s;
            ss_s2[r] = lambda_r * ss_s2[r] + s * ws_r;
            ss_yres[r] = lambda_r * ss_yres[r] + ytarget[r] * ws_r;
            let inv_ss_s2 = 1.0 / ss_s2[r];
            for ((sx, p), x) in ss_xres[col.clone()]
                .iter_mut()
                .zip(&mut p[col.clone()])
                .zip(xr)
            {
                *sx = lambda_r * *sx + ws_r * x;
                *p = *sx * inv_ss_s2;
            }
            beta[r] = ss_yres[r] * inv_ss_s2;
            ws2_ss_s2 += ws_r * ws_r * inv_ss_s2;
        }
        self.ssp = self.lambda[nr - 1] * self.ssp + ws2_ss_s2;

        // Loadings with the updated projections (the residuals go to `ws.dx` as scratch).
        let (u, p, beta) = (&self.u[..n * nr], &self.p[..n * nr], &self.beta[..nr]);
        let (xu, _) = ws.dx.split_at_mut(n);
        let s_buf = &mut ws.s[..nr];
        let s = dot(&u[..n], xmz);
        s_buf[0] = s;
        if nr > 1 {
            for ((v, x), p) in xu.iter_mut().zip(xmz).zip(&p[..n]) {
                *v = x + -s * p;
            }
        }
        for r in 1..nr {
            let s = dot(&u[r * n..(r + 1) * n], xu);
            s_buf[r] = s;
            if r + 1 < nr {
                axpy(xu, -s, &p[r * n..(r + 1) * n]);
            }
        }
        let ypred: f64 = (0..used).map(|r| beta[r] * s_buf[r]).sum();
        // With no trusted projection the prediction is the intercept alone, so the
        // cross-validation error is the mean-free target itself (the reference reads the
        // element before `e_cv` here).
        let e_cv = &ws.e_cv[..nr];
        let e_cv_used = if used == 0 { y } else { e_cv[used - 1] };
        let e = y - ypred;
        let lambda = &self.lambda[..nr];
        if self.n_data[0] * (1.0 - lambda[0]) > 0.1 {
            self.sum_e2 = self.sum_e2 * lambda[nr - 1] + w * e * e;
            for ((sum, e), l) in self.sum_e_cv2[..nr].iter_mut().zip(e_cv).zip(lambda) {
                *sum = *sum * l + w * e * e;
            }
        }
        if self.n_data[0] > 2.0 * n as f64 {
            self.trustworthy = true;
        }
        RegressionStep {
            yp: ypred + self.beta0,
            e_cv: e_cv_used,
            e,
        }
    }

    /// Adds a PLS projection when the newest one lowered the cross-validation error enough
    /// and has seen enough data. Returns whether one was added.
    pub(crate) fn check_add_projection<D: InputDim>(
        &mut self,
        dim: D,
        config: &LwprConfig,
    ) -> bool {
        let n = dim.n();
        let nr = self.n_reg();
        if nr >= n {
            return false;
        }
        let mse = self.sum_e_cv2[nr - 1] / self.sum_w[nr - 1] + 1e-10;
        let mse_prev = self.sum_e_cv2[nr - 2] / self.sum_w[nr - 2] + 1e-10;
        if mse < config.add_threshold * mse_prev
            && self.n_data[nr - 1] > 0.99 * self.n_data[0]
            && self.n_data[nr - 1] * (1.0 - self.lambda[nr - 1]) > 0.5
        {
            for v in [
                &mut self.sxres_yres,
                &mut self.ss_xres,
                &mut self.u,
                &mut self.p,
            ] {
                v.resize(n * (nr + 1), 0.0);
            }
            self.u[nr + nr * n] = 1.0;
            self.p[nr + nr * n] = 1.0;
            self.beta.push(0.0);
            self.ss_s2.push(config.init_s2);
            self.ss_yres.push(0.0);
            self.big_h.push(0.0);
            self.r.push(0.0);
            self.sum_w.push(1e-10);
            self.sum_e_cv2.push(0.0);
            self.n_data.push(0.0);
            self.lambda.push(config.init_lambda);
            self.ssp = 0.0;
            true
        } else {
            false
        }
    }

    /// One full training step at normalised input `xn` with activation `act`: means, PLS,
    /// distance metric, projection growth, data counts and forgetting factors. Returns the
    /// field's prediction at `xn` if it is trustworthy.
    pub(crate) fn train(
        &mut self,
        config: &LwprConfig,
        xn: &[f64],
        y: f64,
        act: Activation,
        ws: &mut Workspace,
    ) -> Option<f64> {
        match xn.len() {
            1 => self.train_in(Fixed::<1>, config, xn, y, act, ws),
            2 => self.train_in(Fixed::<2>, config, xn, y, act, ws),
            3 => self.train_in(Fixed::<3>, config, xn, y, act, ws),
            4 => self.train_in(Fixed::<4>, config, xn, y, act, ws),
            n => self.train_in(Dynamic(n), config, xn, y, act, ws),
        }
    }

    /// [`Self::train`] for `dim` inputs.
    pub(crate) fn train_in<D: InputDim>(
        &mut self,
        dim: D,
        config: &LwprConfig,
        xn: &[f64],
        y: f64,
        act: Activation,
        ws: &mut Workspace,
    ) -> Option<f64> {
        let ymz = {
            let (xmz, _) = ws.xmz.split_at_mut(dim.n());
            self.update_means(dim, xn, y, act.w, xmz)
        };
        let step = self.update_regression(dim, ymz, act.w, ws);
        let yp = self.trustworthy.then_some(step.yp);
        if config.update_d {
            self.update_distance_metric(dim, config, act, step.e_cv, step.e, xn, ws);
        }
        self.check_add_projection(dim, config);
        let tau = config.tau_lambda;
        for r in 0..self.n_reg() {
            self.n_data[r] = self.n_data[r] * self.lambda[r] + 1.0;
            self.lambda[r] = tau * self.lambda[r] + config.final_lambda * (1.0 - tau);
        }
        yp
    }

    /// Trace of the distance metric (the width measure used for pruning).
    pub(crate) fn trace_d(&self) -> f64 {
        let n = self.n_in();
        (0..n).map(|i| self.d[i + i * n]).sum()
    }
}
