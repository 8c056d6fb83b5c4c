//! Persistence: the invariants a loaded [`Lwpr`] must satisfy.

use super::linalg::{cholesky_upper, metric_from_factor};
use super::model::Lwpr;
use super::receptive_field::ReceptiveField;
use crate::approx::{ApproxError, Persist};

/// Magnitude bound on every stored number: far beyond anything training on sane data
/// produces, and small enough that no product in a prediction can overflow.
const MAX_MAGNITUDE: f64 = 1e100;

fn corrupt(msg: impl Into<String>) -> ApproxError {
    ApproxError::Corrupt(msg.into())
}

fn check_len(what: &str, v: &[f64], expected: usize) -> Result<(), ApproxError> {
    if v.len() != expected {
        return Err(corrupt(format!(
            "{what}: expected {expected} elements, got {}",
            v.len()
        )));
    }
    if let Some(x) = v.iter().find(|x| !x.is_finite() || x.abs() > MAX_MAGNITUDE) {
        return Err(corrupt(format!(
            "{what}: value {x} is not finite or out of range"
        )));
    }
    Ok(())
}

fn check_positive(what: &str, v: &[f64]) -> Result<(), ApproxError> {
    match v.iter().find(|x| **x <= 0.0) {
        Some(x) => Err(corrupt(format!("{what}: must be > 0, got {x}"))),
        None => Ok(()),
    }
}

fn check_rf(rf: &ReceptiveField, lwpr: &Lwpr, label: &str) -> Result<(), ApproxError> {
    let (config, ..) = lwpr.parts();
    let n = config.n_in;
    let nr = rf.beta.len();
    // Training starts a field with min(2, n) projections and only adds more, and adding one
    // compares the newest two: a field with fewer cannot come from a saved model.
    let least = n.min(2);
    if nr < least || nr > n {
        return Err(corrupt(format!(
            "{label}: {nr} projections, need {least}..={n}"
        )));
    }
    for (what, v) in [("c", &rf.c), ("mean_x", &rf.mean_x), ("var_x", &rf.var_x)] {
        check_len(&format!("{label}.{what}"), v, n)?;
    }
    for (what, v) in [
        ("d", &rf.d),
        ("m", &rf.m),
        ("alpha", &rf.alpha),
        ("b", &rf.b),
        ("h", &rf.h),
    ] {
        check_len(&format!("{label}.{what}"), v, n * n)?;
    }
    for (what, v) in [
        ("ss_s2", &rf.ss_s2),
        ("ss_yres", &rf.ss_yres),
        ("big_h", &rf.big_h),
        ("r", &rf.r),
        ("sum_w", &rf.sum_w),
        ("sum_e_cv2", &rf.sum_e_cv2),
        ("n_data", &rf.n_data),
        ("lambda", &rf.lambda),
    ] {
        check_len(&format!("{label}.{what}"), v, nr)?;
    }
    for (what, v) in [
        ("sxres_yres", &rf.sxres_yres),
        ("ss_xres", &rf.ss_xres),
        ("u", &rf.u),
        ("p", &rf.p),
    ] {
        check_len(&format!("{label}.{what}"), v, n * nr)?;
    }
    check_len(
        &format!("{label} scalars"),
        &[rf.sum_e2, rf.beta0, rf.ssp],
        3,
    )?;
    check_positive(&format!("{label}.ss_s2"), &rf.ss_s2)?;
    check_positive(&format!("{label}.sum_w"), &rf.sum_w)?;
    check_positive(&format!("{label}.alpha"), &rf.alpha)?;
    if rf.lambda.iter().any(|l| !(*l > 0.0 && *l <= 1.0)) {
        return Err(corrupt(format!("{label}.lambda must be in (0, 1]")));
    }
    if rf
        .n_data
        .iter()
        .chain(&rf.var_x)
        .chain(&rf.sum_e_cv2)
        .any(|v| *v < 0.0)
        || rf.sum_e2 < 0.0
    {
        return Err(corrupt(format!(
            "{label}: negative count, variance or error sum"
        )));
    }
    for col in 0..n {
        if rf.m[col + col * n] <= 0.0 {
            return Err(corrupt(format!("{label}.m: diagonal must be positive")));
        }
        for row in col + 1..n {
            if rf.m[row + col * n] != 0.0 {
                return Err(corrupt(format!("{label}.m: must be upper triangular")));
            }
            if config.diag_only && rf.m[col + row * n] != 0.0 {
                return Err(corrupt(format!("{label}.m: must be diagonal (diag_only)")));
            }
        }
    }
    // D must be M^T M.
    let mut d = vec![0.0; n * n];
    metric_from_factor(n, &rf.m, &mut d);
    for (a, b) in d.iter().zip(&rf.d) {
        if (a - b).abs() > 1e-9 * a.abs().max(b.abs()).max(1e-300) {
            return Err(corrupt(format!("{label}.d: does not equal m^T m")));
        }
    }
    if cholesky_upper(n, &rf.d).is_none() {
        return Err(corrupt(format!("{label}.d: not positive definite")));
    }
    Ok(())
}

impl Persist for Lwpr {
    fn check_invariants(&self) -> Result<(), ApproxError> {
        let (config, init_m, mean_x, var_x, sub) = self.parts();
        let expected_m = config
            .validate()
            .map_err(|e| corrupt(format!("configuration: {e}")))?;
        if expected_m != init_m {
            return Err(corrupt("init_m is not the Cholesky factor of init_d"));
        }
        check_len("mean_x", mean_x, config.n_in)?;
        check_len("var_x", var_x, config.n_in)?;
        if self.n_data() > crate::stats::MAX_COUNT {
            return Err(corrupt(format!(
                "n_data {} is beyond any run",
                self.n_data()
            )));
        }
        if sub.len() != config.n_out {
            return Err(corrupt(format!(
                "{} submodels for {} outputs",
                sub.len(),
                config.n_out
            )));
        }
        for (k, s) in sub.iter().enumerate() {
            let stamps_fit = match config.max_rfs {
                Some(cap) => {
                    s.rfs.len() <= cap
                        && s.last_trained.len() == s.rfs.len()
                        && s.last_trained.iter().all(|&t| t <= self.n_data())
                }
                None => s.last_trained.is_empty() && s.n_replaced == 0,
            };
            if !stamps_fit {
                return Err(corrupt(format!(
                    "output {k}: {} fields, {} training stamps and {} replacements do not fit \
                     max_rfs {:?}",
                    s.rfs.len(),
                    s.last_trained.len(),
                    s.n_replaced,
                    config.max_rfs
                )));
            }
            for (i, rf) in s.rfs.iter().enumerate() {
                check_rf(rf, self, &format!("output {k} rf {i}"))?;
            }
        }
        Ok(())
    }
}
