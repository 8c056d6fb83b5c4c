//! Unit tests of the PLS and distance-metric updates against hand-derived values.

use super::config::LwprConfig;
use super::dim::{Dynamic, Fixed};
use super::kernel::{Activation, Kernel};
use super::metric::distance_derivatives;
use super::receptive_field::ReceptiveField;
use super::workspace::Workspace;
use crate::approx::FunctionApproximator;

fn fresh(config: &LwprConfig, c: &[f64]) -> ReceptiveField {
    let m = config.validate().unwrap();
    ReceptiveField::new(config, &m, None, c, 0.0)
}

#[test]
fn first_pls_step_matches_hand_derivation() {
    // One input, one projection, u = p = 1, SSs2 = 1e-10, lambda = 0.999, all sums zero.
    let config = LwprConfig::new(1, 1);
    let mut rf = fresh(&config, &[0.0]);
    let mut ws = Workspace::default();
    ws.ensure(1);
    let (x, y, w) = (0.4, -0.3, 0.8);
    ws.xmz[0] = x;
    let step = rf.update_regression(Dynamic(rf.n_in()), y, w, &mut ws);
    // s = u x = x; SSs2 = lambda 1e-10 + w s^2; SSYres = w s y; SSXres = w s x.
    let ss_s2 = 0.999 * 1e-10 + x * (w * x);
    assert_eq!(rf.ss_s2[0], ss_s2);
    assert_eq!(rf.ss_yres[0], y * (w * x));
    assert_eq!(rf.beta[0], y * (w * x) / ss_s2);
    assert_eq!(rf.p[0], (w * x) * x / ss_s2);
    // u is the normalised SXresYres = w y x < 0.
    assert_eq!(rf.sxres_yres[0], w * y * x);
    assert_eq!(rf.u[0], -1.0);
    assert_eq!(rf.sum_w[0], 1e-10 * 0.999 + w);
    // SSp = (w s)^2 / SSs2.
    assert_eq!(rf.ssp, (w * x) * (w * x) / ss_s2);
    // The projection is not trusted yet (n_data <= 2 n): prediction is the intercept,
    // errors are the mean-free target.
    assert_eq!(step.yp, rf.beta0);
    assert_eq!((step.e, step.e_cv), (y, y));
    assert!(!rf.trustworthy);
    // Error sums only start once n_data (1 - lambda) > 0.1.
    assert_eq!(rf.sum_e_cv2[0], 0.0);
}

#[test]
fn weighted_means_match_hand_derivation() {
    let config = LwprConfig::new(2, 1);
    let mut rf = fresh(&config, &[0.0, 0.0]);
    rf.sum_w[0] = 3.0;
    rf.lambda[0] = 0.5;
    rf.mean_x = vec![1.0, -1.0];
    rf.var_x = vec![0.5, 0.25];
    rf.beta0 = 2.0;
    let mut xmz = [0.0; 2];
    let ymz = rf.update_means(Dynamic(2), &[2.5, 0.5], 5.0, 0.5, &mut xmz);
    // swl = 1.5, so every mean moves by w / (swl + w) = 1/4 of the way.
    assert_eq!(rf.mean_x, vec![1.375, -0.625]);
    assert_eq!(xmz, [1.125, 1.125]);
    assert_eq!(rf.var_x[0], (1.5 * 0.5 + 0.5 * 1.125 * 1.125) / 2.0);
    assert_eq!(rf.beta0, 2.75);
    assert_eq!(ymz, 2.25);
}

#[test]
fn pls_recovers_a_linear_map() {
    // Noise-free linear data inside one field: the local model becomes the plane.
    let config = LwprConfig::new(2, 1).update_d(false);
    let mut rf = fresh(&config, &[0.0, 0.0]);
    let mut ws = Workspace::default();
    ws.ensure(2);
    let f = |x: &[f64]| 0.7 * x[0] - 1.3 * x[1] + 0.2;
    for k in 0..3000 {
        let x = [
            ((k * 37) % 101) as f64 / 50.0 - 1.0,
            ((k * 53) % 97) as f64 / 48.0 - 1.0,
        ];
        let act = Kernel::Gaussian.activation(0.5);
        rf.train(&config, &x, f(&x), act, &mut ws);
    }
    assert_eq!(rf.n_reg(), 2);
    assert!(rf.trustworthy);
    let mut xu = [0.0; 2];
    for x in [[0.3, -0.2], [-0.9, 0.8], [0.0, 0.0]] {
        let (y, _) = rf.local_prediction(&x, &mut xu);
        // Online PLS keeps a fading trace of the samples seen before its directions settled.
        assert!((y - f(&x)).abs() < 1e-3, "{y} vs {}", f(&x));
    }
}

#[test]
fn compile_time_and_run_time_input_counts_train_bit_identically() {
    // Full metric with meta learning exercises every loop that depends on the input count.
    let config = LwprConfig::new(3, 1)
        .diag_only(false)
        .meta(true)
        .init_d(4.0);
    let mut fixed = fresh(&config, &[0.1, -0.2, 0.3]);
    let mut dynamic = fixed.clone();
    let (mut ws_a, mut ws_b) = (Workspace::default(), Workspace::default());
    ws_a.ensure(3);
    ws_b.ensure(3);
    for k in 0..2000 {
        let x = [
            ((k * 37) % 101) as f64 / 100.0 - 0.4,
            ((k * 53) % 97) as f64 / 96.0 - 0.6,
            ((k * 29) % 89) as f64 / 88.0 - 0.2,
        ];
        let y = 0.5 * x[0] - x[1] + 2.0 * x[2] + 0.1 * (3.0 * x[0]).sin();
        let act = Kernel::Gaussian.activation(0.2 + 0.1 * (k % 7) as f64);
        let a = fixed.train_in(Fixed::<3>, &config, &x, y, act, &mut ws_a);
        let b = dynamic.train_in(Dynamic(3), &config, &x, y, act, &mut ws_b);
        assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
    }
    assert_eq!(fixed, dynamic);
    assert!(fixed.trustworthy);
    assert_ne!(
        fixed.m,
        fresh(&config, &[0.1, -0.2, 0.3]).m,
        "the metric adapted"
    );
}

/// Activation of a field with factor `m` at offset `dx` (Gaussian), and the penalty.
fn w_of(n: usize, m: &[f64], dx: &[f64]) -> f64 {
    let mut q = 0.0;
    for k in 0..n {
        let row: f64 = (k..n).map(|i| m[k + i * n] * dx[i]).sum();
        q += row * row;
    }
    (-0.5 * q).exp()
}

fn penalty_of(n: usize, m: &[f64], gamma: f64) -> f64 {
    let mut d = vec![0.0; n * n];
    super::linalg::metric_from_factor(n, m, &mut d);
    gamma * d.iter().map(|v| v * v).sum::<f64>()
}

#[test]
fn metric_derivatives_match_finite_differences() {
    for diag_only in [true, false] {
        let n = 3;
        let config = LwprConfig::new(n, 1).diag_only(diag_only);
        let mut rf = fresh(&config, &[0.1, -0.2, 0.3]);
        rf.m = vec![2.0, 0.0, 0.0, 0.3, 1.5, 0.0, -0.2, 0.4, 1.2];
        if diag_only {
            rf.m = vec![2.0, 0.0, 0.0, 0.0, 1.5, 0.0, 0.0, 0.0, 1.2];
        }
        super::linalg::metric_from_factor(n, &rf.m.clone(), &mut rf.d);
        let mut ws = Workspace::default();
        ws.ensure(n);
        ws.dx.copy_from_slice(&[0.25, -0.1, 0.15]);
        let dx = ws.dx.clone();
        let w = w_of(n, &rf.m, &dx);
        let act = Activation {
            w,
            dwdq: -0.5 * w,
            ddwdqdq: 0.25 * w,
        };
        let gamma = 0.01;
        distance_derivatives(
            Dynamic(rf.n_in()),
            &rf,
            act,
            gamma,
            diag_only,
            true,
            &mut ws,
        );
        let h = 1e-6;
        for col in 0..n {
            for row in 0..=col {
                if diag_only && row != col {
                    continue;
                }
                let off = row + col * n;
                let bump = |delta: f64| {
                    let mut m = rf.m.clone();
                    m[off] += delta;
                    m
                };
                let (mp, mm) = (bump(h), bump(-h));
                let fd_w = (w_of(n, &mp, &dx) - w_of(n, &mm, &dx)) / (2.0 * h);
                assert!((fd_w - ws.dwdm[off]).abs() < 1e-7, "dw/dM[{row},{col}]");
                let fd_j = (penalty_of(n, &mp, gamma) - penalty_of(n, &mm, gamma)) / (2.0 * h);
                assert!((fd_j - ws.dj2dm[off]).abs() < 1e-6, "dJ2/dM[{row},{col}]");
                let fd_ww = (w_of(n, &mp, &dx) - 2.0 * w + w_of(n, &mm, &dx)) / (h * h);
                assert!(
                    (fd_ww - ws.ddwdmdm[off]).abs() < 1e-3,
                    "d2w/dM2[{row},{col}]"
                );
                let fd_jj = (penalty_of(n, &mp, gamma) - 2.0 * penalty_of(n, &rf.m, gamma)
                    + penalty_of(n, &mm, gamma))
                    / (h * h);
                if diag_only {
                    assert!(
                        (fd_jj - ws.ddj2dmdm[off]).abs() < 1e-3,
                        "d2J2/dM2[{row},{col}]"
                    );
                }
            }
        }
    }
}

#[test]
fn metric_step_follows_the_penalty_gradient_when_errors_vanish() {
    // With zero errors and zero memory terms the cost gradient is the penalty's alone:
    // dJ/dM = w/W * 4 gamma/n D M (1-D: 4 gamma D M), and the step is alpha * transient * it.
    let config = LwprConfig::new(1, 1)
        .init_d(4.0)
        .penalty(0.5)
        .init_alpha(0.01);
    let mut rf = fresh(&config, &[0.0]);
    rf.n_data[0] = 500.0; // enough data for the gradient
    rf.sum_w[0] = 2.0;
    rf.sum_e2 = 1.0;
    rf.sum_e_cv2[0] = 1.0; // transient multiplier (1 / (1 + 1e-10))^4
    let mut ws = Workspace::default();
    ws.ensure(1);
    ws.s[0] = 0.0;
    let act = Kernel::Gaussian.activation(0.0);
    let transient = rf.update_distance_metric(Dynamic(1), &config, act, 0.0, 0.0, &[0.0], &mut ws);
    let expected_t = (1.0f64 / (1.0 + 1e-10)).powi(4);
    assert_eq!(transient, expected_t);
    // big E = 1, W = 2: dJ1/dw = -E/W^2 = -0.25, dw/dM = 0 at the centre.
    let grad = (1.0 / 2.0) * (2.0 * 0.5) * 4.0 * (2.0 * 2.0);
    let expected_m = 2.0 - 0.01 * expected_t * grad;
    assert!(
        (rf.m[0] - expected_m).abs() < 1e-15,
        "{} vs {expected_m}",
        rf.m[0]
    );
    assert_eq!(rf.d[0], rf.m[0] * rf.m[0]);
}

#[test]
fn rejected_updates_leave_the_model_bit_identical() {
    let mut model = super::Lwpr::new(LwprConfig::new(2, 1)).unwrap();
    for k in 0..200 {
        let x = [(k % 20) as f64 / 10.0 - 1.0, (k % 7) as f64 / 3.5 - 1.0];
        model.update(&x, &[x[0] * x[1]]).unwrap();
    }
    let before = serde_json::to_string(&model).unwrap();
    assert!(model.update(&[0.1, f64::NAN], &[0.0]).is_err());
    assert!(model.update(&[0.1], &[0.0]).is_err());
    assert!(model.update(&[0.1, 0.2], &[f64::INFINITY]).is_err());
    assert_eq!(before, serde_json::to_string(&model).unwrap());
}

#[test]
fn a_saved_field_with_too_few_projections_is_rejected_on_load() {
    use crate::approx::{ApproxError, Lwpr, Persist};
    let mut model = Lwpr::new(LwprConfig::new(2, 1)).unwrap();
    for k in 0..200 {
        let x = [(k % 20) as f64 / 10.0 - 1.0, (k % 7) as f64 / 3.5 - 1.0];
        model.update(&x, &[x[0] * x[1]]).unwrap();
    }
    let mut json: serde_json::Value = serde_json::from_str(&model.to_json().unwrap()).unwrap();
    let rf = &mut json["sub"][0]["rfs"][0];
    for key in [
        "beta",
        "ss_s2",
        "ss_yres",
        "big_h",
        "r",
        "sum_w",
        "sum_e_cv2",
        "n_data",
        "lambda",
    ] {
        rf[key].as_array_mut().unwrap().truncate(1);
    }
    for key in ["sxres_yres", "ss_xres", "u", "p"] {
        rf[key].as_array_mut().unwrap().truncate(2);
    }
    let err = Lwpr::from_json(&json.to_string()).unwrap_err();
    assert!(
        matches!(err, ApproxError::Corrupt(ref m) if m.contains("1 projections")),
        "{err}"
    );
}
