//! Distance-metric adaptation: a gradient step on the leave-one-out cost plus penalty,
//! optionally with incremental delta-bar-delta meta learning of the learning rates.

use super::config::LwprConfig;
use super::dim::InputDim;
use super::kernel::Activation;
use super::linalg::metric_from_factor;
use super::receptive_field::ReceptiveField;
use super::workspace::Workspace;

/// Derivatives of the activation and of the penalty with respect to the elements of `M`.
///
/// Writes `dw/dM` into `ws.dwdm` and `dJ2/dM` into `ws.dj2dm` (and the second derivatives into
/// `ws.ddwdmdm`, `ws.ddj2dmdm` when `meta` is on), for the diagonal of `M` if `diag_only`, else
/// for its upper triangle. `penalty` is the per-input penalty `gamma / n`; the cost is
/// `J2 = penalty * sum_ij D_ij^2`.
pub(crate) fn distance_derivatives<D: InputDim>(
    dim: D,
    rf: &ReceptiveField,
    act: Activation,
    penalty: f64,
    diag_only: bool,
    meta: bool,
    ws: &mut Workspace,
) {
    let n = dim.n();
    let dx = &ws.dx;
    let p2 = 2.0 * penalty;
    if diag_only {
        for k in 0..n {
            let kk = k + k * n;
            let two_m = 2.0 * rf.m[kk];
            let dqdm = dx[k] * dx[k] * two_m;
            ws.dwdm[kk] = dqdm * act.dwdq;
            ws.dj2dm[kk] = p2 * rf.d[kk] * two_m;
            if meta {
                ws.ddwdmdm[kk] = act.ddwdqdq * dqdm * dqdm + 2.0 * act.dwdq * dx[k] * dx[k];
                ws.ddj2dmdm[kk] = p2 * (2.0 * rf.d[kk] + two_m * two_m);
            }
        }
        return;
    }
    for col in 0..n {
        for row in 0..=col {
            // q = |M dx|^2, so dq/dM[row, col] = 2 (M dx)[row] dx[col];
            // J2 = penalty |D|_F^2, so dJ2/dM[row, col] = 4 penalty sum_i D[i, col] M[row, i].
            let mut mdx = 0.0;
            let mut dm = 0.0;
            let mut mm = 0.0;
            for i in row..n {
                let m_ri = rf.m[row + i * n];
                mdx += dx[i] * m_ri;
                dm += rf.d[i + col * n] * m_ri;
                mm += if i == col {
                    2.0 * m_ri * m_ri
                } else {
                    m_ri * m_ri
                };
            }
            let dqdm = 2.0 * dx[col] * mdx;
            let off = row + col * n;
            ws.dwdm[off] = dqdm * act.dwdq;
            ws.dj2dm[off] = 2.0 * p2 * dm;
            if meta {
                ws.ddwdmdm[off] = act.ddwdqdq * dqdm * dqdm + 2.0 * act.dwdq * dx[col] * dx[col];
                ws.ddj2dmdm[off] = 2.0 * p2 * (rf.d[col + col * n] + mm);
            }
        }
    }
}

/// Calls `f` with the offset of every element of `M` that adapts: the diagonal with
/// `diag_only`, else the upper triangle.
#[inline(always)]
fn for_each_element(n: usize, diag_only: bool, mut f: impl FnMut(usize)) {
    for col in 0..n {
        if diag_only {
            f(col + col * n);
        } else {
            for row in 0..=col {
                f(row + col * n);
            }
        }
    }
}

impl ReceptiveField {
    /// One distance-metric step after the regression update of the same sample.
    ///
    /// `e_cv` and `e` are the cross-validation and training errors from the regression step,
    /// `ws.s` holds the updated loadings. Returns the transient multiplier that scaled the
    /// step (0 if the field has not seen enough data yet).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn update_distance_metric<D: InputDim>(
        &mut self,
        dim: D,
        config: &LwprConfig,
        act: Activation,
        e_cv: f64,
        e: f64,
        xn: &[f64],
        ws: &mut Workspace,
    ) -> f64 {
        let n = dim.n();
        let nr = self.n_reg();
        let w = act.w;
        let lambda0 = self.lambda[0];
        // A projection takes part in the gradient once it has seen enough data; the first
        // has seen the most, so without it nothing does.
        let warm = self.n_data[0] * (1.0 - lambda0) > 0.1;
        if !warm {
            return 0.0;
        }
        let penalty = config.penalty / n as f64;
        let e2 = e * e;
        let e_cv2 = e_cv * e_cv;
        let big_w = self.sum_w[0];
        let big_e = if nr == 1 || self.n_data[nr - 1] > 2.0 * n as f64 {
            self.sum_e_cv2[nr - 1]
        } else {
            self.sum_e_cv2[nr - 2]
        };
        let transient = (self.sum_e2 / (big_e + 1e-10)).powi(4).min(1.0);

        // The leverage h and dJ1/dw of the leave-one-out cost, in one pass over the
        // projections.
        let (n_data, ss_s2) = (&self.n_data[..nr], &self.ss_s2[..nr]);
        let (big_h, r_mem) = (&self.big_h[..nr], &self.r[..nr]);
        let (s_buf, ps_buf) = (&ws.s[..nr], &mut ws.ps[..nr]);
        let deriv_ok = &mut ws.deriv_ok[..nr];
        let mut h = 0.0;
        let mut dj1dw = -big_e / big_w + e_cv2;
        for r in 0..nr {
            let ok = n_data[r] * (1.0 - lambda0) > 0.1;
            deriv_ok[r] = ok;
            let s = s_buf[r];
            let ps = if ok {
                h += s * s / ss_s2[r];
                s / ss_s2[r]
            } else {
                0.0
            };
            ps_buf[r] = ps;
            let pse = e * ps;
            dj1dw -= 2.0 * pse * big_h[r] + 2.0 * ps * ps * r_mem[r];
        }
        h *= w;
        dj1dw /= big_w;
        let w_over_w = w / big_w;

        for i in 0..n {
            ws.dx[i] = xn[i] - self.c[i];
        }
        let diag_only = config.diag_only;
        distance_derivatives(dim, self, act, penalty, diag_only, config.meta, ws);

        let mut max_m = 0.0f64;
        for_each_element(n, diag_only, |off| {
            max_m = max_m.max(self.m[off].abs());
            // Reuse dj2dm as the whole gradient dJ/dM.
            ws.dj2dm[off] = w_over_w * ws.dj2dm[off] + ws.dwdm[off] * dj1dw;
        });

        if config.meta {
            let mut s_pse = 0.0;
            for r in 0..nr {
                s_pse += ws.s[r] * e * ws.ps[r];
            }
            let mut ddj1dwdw = 2.0 * (e2 * h / w - e_cv2 / big_w) + big_e / (big_w * big_w);
            for r in 0..nr {
                let pse = e * ws.ps[r];
                ddj1dwdw += 4.0 * (pse / big_w + ws.ps[r] * s_pse) * self.big_h[r];
            }
            ddj1dwdw /= big_w;
            let rate = config.meta_rate;
            for_each_element(n, diag_only, |off| {
                let djdm = ws.dj2dm[off];
                let dwdm = ws.dwdm[off];
                let ddjdmdm =
                    w_over_w * ws.ddj2dmdm[off] + ws.ddwdmdm[off] * dj1dw + dwdm * dwdm * ddj1dwdw;
                // Incremental delta-bar-delta with clipped steps and clipped log rates.
                let step = (rate * transient * djdm * self.h[off]).clamp(-0.1, 0.1);
                let b = (self.b[off] - step).clamp(-10.0, 10.0);
                self.b[off] = b;
                let alpha = b.exp();
                self.alpha[off] = alpha;
                let decay = (1.0 - alpha * ddjdmdm * transient).max(0.0);
                self.h[off] = self.h[off] * decay - alpha * transient * djdm;
            });
        }

        for_each_element(n, diag_only, |off| {
            let delta = self.alpha[off] * transient * ws.dj2dm[off];
            if delta > 0.1 * max_m {
                // Too large a step: halve the rate and skip this element.
                self.alpha[off] *= 0.5;
            } else {
                self.m[off] -= delta;
            }
            if diag_only {
                self.d[off] = self.m[off] * self.m[off];
            }
        });
        if !diag_only {
            metric_from_factor(n, &self.m, &mut self.d);
        }

        let h_gain = w / (1.0 - h);
        let r_gain = w * w * e_cv2 / (1.0 - h);
        let (lambda, big_h, r_mem) = (&self.lambda[..nr], &mut self.big_h[..nr], &mut self.r[..nr]);
        let (s_buf, deriv_ok) = (&ws.s[..nr], &ws.deriv_ok[..nr]);
        for r in 0..nr {
            if deriv_ok[r] {
                let s = s_buf[r];
                big_h[r] = lambda[r] * big_h[r] + h_gain * s * e_cv * transient;
                r_mem[r] = lambda[r] * r_mem[r] + r_gain * s * s * transient;
            }
        }
        transient
    }
}
