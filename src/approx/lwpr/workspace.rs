//! Preallocated scratch buffers for one update, so that training allocates nothing.

/// Scratch space sized for `n` inputs (at most `n` PLS projections).
///
/// Not part of the model's state: it is skipped by serde and resized on first use.
#[derive(Debug, Clone, Default)]
pub(crate) struct Workspace {
    /// Normalised input.
    pub xn: Vec<f64>,
    /// Input minus the receptive field's running mean.
    pub xmz: Vec<f64>,
    /// Input residuals before each projection (`n x R`, projection-major; the residual before
    /// projection 0 is `xmz` itself, so the first `n` entries are unused).
    pub xres: Vec<f64>,
    /// Current PLS loadings.
    pub s: Vec<f64>,
    /// Cumulative output predictions with 1..=R projections.
    pub yres: Vec<f64>,
    /// Cross-validation errors with 1..=R projections.
    pub e_cv: Vec<f64>,
    /// Regression target of each projection.
    pub ytarget: Vec<f64>,
    /// Input minus the receptive field's centre.
    pub dx: Vec<f64>,
    /// Derivative of the activation with respect to `M`.
    pub dwdm: Vec<f64>,
    /// Derivative of the penalty (later: of the whole cost) with respect to `M`.
    pub dj2dm: Vec<f64>,
    /// Second derivative of the activation with respect to `M` (meta learning).
    pub ddwdmdm: Vec<f64>,
    /// Second derivative of the penalty with respect to `M` (meta learning).
    pub ddj2dmdm: Vec<f64>,
    /// `s_r / SSs2_r` for projections with enough data, else 0.
    pub ps: Vec<f64>,
    /// Whether projection `r` has enough data for the metric gradient.
    pub deriv_ok: Vec<bool>,
    /// Squared distance of every receptive field to the sample (grows with the field count).
    pub q: Vec<f64>,
    /// Scratch of the same length as `q`.
    pub row: Vec<f64>,
}

impl Workspace {
    /// Makes every buffer large enough for `n` inputs (allocates only the first time).
    pub fn ensure(&mut self, n: usize) {
        if self.xn.len() == n {
            return;
        }
        for v in [
            &mut self.xn,
            &mut self.xmz,
            &mut self.s,
            &mut self.yres,
            &mut self.e_cv,
            &mut self.ytarget,
            &mut self.dx,
            &mut self.ps,
        ] {
            *v = vec![0.0; n];
        }
        for v in [
            &mut self.xres,
            &mut self.dwdm,
            &mut self.dj2dm,
            &mut self.ddwdmdm,
            &mut self.ddj2dmdm,
        ] {
            *v = vec![0.0; n * n];
        }
        self.deriv_ok = vec![false; n];
    }
}
