//! The exact batch kernel ridge fit (faer Cholesky) against the online `KernelRidge`, and its
//! input checks.

use ndarray::{Array2, array};
use steplearn::approx::conformance::stream;
use steplearn::approx::{
    ApproxError, BatchApproximator, ExactKernelRidge, KernelRidge, KernelRidgeConfig,
};

fn data(seed: u64, n: usize, n_out: usize) -> (Array2<f64>, Array2<f64>) {
    let s = stream(seed, n, 2, n_out);
    (
        Array2::from_shape_fn((n, 2), |(i, j)| s[i].0[j]),
        Array2::from_shape_fn((n, n_out), |(i, k)| s[i].1[k]),
    )
}

/// With a budget above the sample count and the smallest novelty threshold, the online model
/// keeps every sample in its dictionary, and KRLS-T's posterior mean is then exactly the kernel
/// ridge solution `k(x, X) (K + lambda I)^-1 Y`. Two differences remain, both small:
/// - the online Gram matrix carries a jitter of 1e-8 on its diagonal, which acts as a
///   regulariser of `lambda + 1e-8`; to first order that moves the coefficients by
///   `1e-8 / lambda = 1e-6` of their size (an upper bound: the eigenvalues of `K + lambda I`
///   are at least `lambda`);
/// - the online model reaches the solution by n rank-one updates instead of one factorisation:
///   rounding of order `cond(K + lambda I) * 1e-16 <= (1 + n / lambda) * 1e-16 = 3e-13`.
///
/// So the predictions must agree to 1e-6 of the largest prediction (measured: about 4e-8).
#[test]
fn online_kernel_ridge_keeping_every_point_agrees_with_the_exact_fit() {
    for n_out in [1, 2] {
        let n = 30;
        let config = KernelRidgeConfig {
            budget: 100,
            novelty_threshold: 1e-6,
            regularisation: 0.01,
            ..KernelRidgeConfig::new(vec![0.3, 0.4], n_out)
        };
        let (x, y) = data(21, n, n_out);
        let mut online = KernelRidge::new(config.clone()).unwrap();
        online.update_batch(x.view(), y.view()).unwrap();
        assert_eq!(
            online.dictionary_size(),
            n,
            "the online model dropped a point"
        );

        let exact = ExactKernelRidge::fit(x.view(), y.view(), &config).unwrap();
        assert_eq!(
            (exact.num_samples(), exact.input_dim(), exact.output_dim()),
            (n, 2, n_out)
        );
        let (q, _) = data(22, 200, n_out);
        let a = online.predict_batch(q.view()).unwrap();
        let b = exact.predict(q.view()).unwrap();
        let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = a
            .iter()
            .zip(&b)
            .fold(0.0f64, |m, (u, v)| m.max((u - v).abs()));
        println!("n_out {n_out}: max |online - exact| = {worst:e} (scale {scale})");
        assert!(
            worst <= 1e-6 * scale,
            "online and exact differ by {worst:e} (scale {scale})"
        );

        // One point at a time agrees with the batch prediction bit for bit.
        let mut yq = vec![0.0; n_out];
        exact
            .predict_point(q.row(3).as_slice().unwrap(), &mut yq)
            .unwrap();
        assert_eq!(yq, b.row(3).to_vec());
    }
}

#[test]
fn exact_fit_interpolates_with_little_regularisation() {
    let (x, y) = data(23, 20, 1);
    let config = KernelRidgeConfig {
        regularisation: 1e-10,
        ..KernelRidgeConfig::new(vec![0.3, 0.3], 1)
    };
    let exact = ExactKernelRidge::fit(x.view(), y.view(), &config).unwrap();
    let p = exact.predict(x.view()).unwrap();
    for (u, v) in p.iter().zip(&y) {
        assert!((u - v).abs() < 1e-5, "{u} vs {v}");
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let config = KernelRidgeConfig::new(vec![0.5, 0.5], 1);
    let (x, y) = data(24, 10, 1);
    let fit = |x: ndarray::ArrayView2<f64>, y: ndarray::ArrayView2<f64>| {
        ExactKernelRidge::fit(x, y, &config)
    };
    // Zero samples.
    let r = fit(Array2::zeros((0, 2)).view(), Array2::zeros((0, 1)).view());
    assert!(matches!(
        r,
        Err(ApproxError::DimensionMismatch { got: 0, .. })
    ));
    // Mismatched shapes.
    assert!(matches!(
        fit(Array2::zeros((10, 3)).view(), y.view()),
        Err(ApproxError::DimensionMismatch {
            expected: 2,
            got: 3,
            ..
        })
    ));
    assert!(matches!(
        fit(x.view(), Array2::zeros((10, 2)).view()),
        Err(ApproxError::DimensionMismatch {
            expected: 1,
            got: 2,
            ..
        })
    ));
    assert!(matches!(
        fit(x.view(), Array2::zeros((9, 1)).view()),
        Err(ApproxError::DimensionMismatch {
            expected: 10,
            got: 9,
            ..
        })
    ));
    // NaN and infinities.
    let mut xn = x.clone();
    xn[[4, 1]] = f64::NAN;
    assert!(matches!(
        fit(xn.view(), y.view()),
        Err(ApproxError::NonFinite { index: 9, .. })
    ));
    let mut yn = y.clone();
    yn[[2, 0]] = f64::NEG_INFINITY;
    assert!(matches!(
        fit(x.view(), yn.view()),
        Err(ApproxError::NonFinite { index: 2, .. })
    ));
    // Parameters out of range.
    for bad in [
        KernelRidgeConfig {
            regularisation: 0.0,
            ..config.clone()
        },
        KernelRidgeConfig::new(vec![0.5, -1.0], 1),
        KernelRidgeConfig::new(vec![], 1),
    ] {
        assert!(matches!(
            ExactKernelRidge::fit(x.view(), y.view(), &bad),
            Err(ApproxError::InvalidConfig { .. })
        ));
    }
    // Queries.
    let exact = fit(x.view(), y.view()).unwrap();
    assert!(matches!(
        exact.predict(array![[0.0, 0.0, 0.0]].view()),
        Err(ApproxError::DimensionMismatch { .. })
    ));
    assert!(matches!(
        exact.predict(array![[0.0, f64::INFINITY]].view()),
        Err(ApproxError::NonFinite { .. })
    ));
    let mut out = [0.0; 2];
    assert!(exact.predict_point(&[0.0, 0.0], &mut out).is_err());
    assert!(
        exact
            .predict_point(&[f64::NAN, 0.0], &mut out[..1])
            .is_err()
    );
}
