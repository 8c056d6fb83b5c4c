//! Batch prediction and training over ndarray matrices equal the per-sample loop bit for bit,
//! and reject bad shapes or non-finite numbers with the model unchanged.

use ndarray::{Array2, ArrayView2};
use steplearn::approx::conformance::stream;
use steplearn::approx::{
    ApproxError, BatchApproximator, FunctionApproximator, Grid, GridConfig, InputBox, KernelRidge,
    KernelRidgeConfig, Lwpr, LwprConfig, Persist, Rbf, RbfConfig,
};

const N_OUT: usize = 2;

fn lwpr() -> Lwpr {
    Lwpr::new(LwprConfig::new(2, N_OUT)).unwrap()
}
fn rbf() -> Rbf {
    Rbf::new(RbfConfig::new(
        InputBox::cube(2, -1.0, 1.0).unwrap(),
        vec![7, 7],
        N_OUT,
    ))
    .unwrap()
}
fn grid() -> Grid {
    Grid::new(GridConfig::new(
        InputBox::cube(2, -1.0, 1.0).unwrap(),
        vec![9, 9],
        N_OUT,
    ))
    .unwrap()
}
fn kernel_ridge() -> KernelRidge {
    KernelRidge::new(KernelRidgeConfig {
        budget: 30,
        ..KernelRidgeConfig::new(vec![0.5, 0.5], N_OUT)
    })
    .unwrap()
}

/// `n` samples as `(x, y)` matrices, rows are samples.
fn batch(seed: u64, n: usize) -> (Array2<f64>, Array2<f64>) {
    let data = stream(seed, n, 2, N_OUT);
    let x = Array2::from_shape_fn((n, 2), |(i, j)| data[i].0[j]);
    let y = Array2::from_shape_fn((n, N_OUT), |(i, k)| data[i].1[k]);
    (x, y)
}

fn bits(a: &Array2<f64>) -> Vec<u64> {
    a.iter().map(|v| v.to_bits()).collect()
}

fn batch_equals_loop<A: FunctionApproximator + Persist>(make: impl Fn() -> A) {
    let (x, y) = batch(11, 300);
    let (mut by_batch, mut by_loop) = (make(), make());
    by_batch.update_batch(x.view(), y.view()).unwrap();
    for (xr, yr) in x.rows().into_iter().zip(y.rows()) {
        by_loop
            .update(&xr.to_vec(), yr.as_slice().unwrap())
            .unwrap();
    }
    assert_eq!(by_batch.to_json().unwrap(), by_loop.to_json().unwrap());

    // Predictions, including through a non-contiguous (column-major) view.
    let (q, _) = batch(12, 50);
    let predicted = by_batch.predict_batch(q.view()).unwrap();
    assert_eq!(predicted.dim(), (50, N_OUT));
    let mut looped = Array2::zeros((50, N_OUT));
    let mut out = vec![0.0; N_OUT];
    for (i, row) in q.rows().into_iter().enumerate() {
        by_loop.predict(&row.to_vec(), &mut out).unwrap();
        for k in 0..N_OUT {
            looped[[i, k]] = out[k];
        }
    }
    assert_eq!(bits(&predicted), bits(&looped));
    let q_t = q.t().to_owned();
    let fortran: ArrayView2<f64> = q_t.t();
    assert_eq!(
        bits(&by_batch.predict_batch(fortran).unwrap()),
        bits(&looped)
    );

    // A boxed trait object gets the methods too.
    let boxed: Box<dyn FunctionApproximator> = Box::new(by_loop);
    assert_eq!(bits(&boxed.predict_batch(q.view()).unwrap()), bits(&looped));
}

fn bad_batches_rejected<A: FunctionApproximator + Persist>(make: impl Fn() -> A) {
    let mut m = make();
    let (x, y) = batch(13, 100);
    m.update_batch(x.view(), y.view()).unwrap();
    let before = m.to_json().unwrap();

    let x3 = Array2::<f64>::zeros((10, 3));
    let y1 = Array2::<f64>::zeros((10, 1));
    let (x10, y10) = batch(14, 10);
    let mut x_nan_last = x10.clone();
    x_nan_last[[9, 1]] = f64::NAN;
    let mut y_inf_last = y10.clone();
    y_inf_last[[9, 0]] = f64::INFINITY;

    let cases: Vec<(ArrayView2<f64>, ArrayView2<f64>, &str)> = vec![
        (x3.view(), y10.view(), "dim"),
        (x10.view(), y1.view(), "dim"),
        (x10.view(), y.view(), "dim"),
        (x10.slice(ndarray::s![..9, ..]), y10.view(), "dim"),
        (x_nan_last.view(), y10.view(), "nan"),
        (x10.view(), y_inf_last.view(), "nan"),
    ];
    for (bx, by, kind) in cases {
        let r = m.update_batch(bx, by);
        match (kind, &r) {
            ("dim", Err(ApproxError::DimensionMismatch { .. })) => {}
            ("nan", Err(ApproxError::NonFinite { index, .. })) => assert!(*index > 0),
            _ => panic!(
                "update_batch of shapes {:?}, {:?} gave {r:?}",
                bx.dim(),
                by.dim()
            ),
        }
        // All rows are validated first: the nine good rows before the bad one were not used.
        assert_eq!(
            m.to_json().unwrap(),
            before,
            "a rejected batch changed the model"
        );
    }
    assert!(matches!(
        m.predict_batch(x3.view()),
        Err(ApproxError::DimensionMismatch { .. })
    ));
    assert!(matches!(
        m.predict_batch(x_nan_last.view()),
        Err(ApproxError::NonFinite { index: 19, .. })
    ));
    // An empty batch is fine: nothing to do.
    let empty_x = Array2::<f64>::zeros((0, 2));
    let empty_y = Array2::<f64>::zeros((0, N_OUT));
    m.update_batch(empty_x.view(), empty_y.view()).unwrap();
    assert_eq!(m.predict_batch(empty_x.view()).unwrap().dim(), (0, N_OUT));
    assert_eq!(m.to_json().unwrap(), before);
}

#[test]
fn lwpr_batch_equals_the_loop_and_rejects_bad_batches() {
    batch_equals_loop(lwpr);
    bad_batches_rejected(lwpr);
}

#[test]
fn rbf_batch_equals_the_loop_and_rejects_bad_batches() {
    batch_equals_loop(rbf);
    bad_batches_rejected(rbf);
}

#[test]
fn grid_batch_equals_the_loop_and_rejects_bad_batches() {
    batch_equals_loop(grid);
    bad_batches_rejected(grid);
}

#[test]
fn kernel_ridge_batch_equals_the_loop_and_rejects_bad_batches() {
    batch_equals_loop(kernel_ridge);
    bad_batches_rejected(kernel_ridge);
}
