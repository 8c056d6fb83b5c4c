//! The check suite every `FunctionApproximator` must pass (river's idea: one shared suite).
//!
//! Call [`check_all`] from a test file per approximator with a factory that builds a fresh model
//! with 2 inputs on [-1, 1]^2 and the requested number of outputs.

#![allow(dead_code)]

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use std::panic::{AssertUnwindSafe, catch_unwind};
use steplearn::approx::{ApproxError, FunctionApproximator, Persist};

/// A smooth 2-input target with `n_out` outputs.
pub fn target(x: &[f64], n_out: usize) -> Vec<f64> {
    (0..n_out)
        .map(|k| 0.5 * x[0] - 0.3 * x[1] + 0.2 * (k as f64) * x[0] * x[1] + 0.1 * k as f64)
        .collect()
}

/// A seeded stream of `n` samples of [`target`] plus uniform noise of +-0.01.
pub fn stream(seed: u64, n: usize, n_out: usize) -> Vec<(Vec<f64>, Vec<f64>)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let x = vec![rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
            let mut y = target(&x, n_out);
            for v in &mut y {
                *v += rng.random_range(-0.01..0.01);
            }
            (x, y)
        })
        .collect()
}

fn train<A: FunctionApproximator>(model: &mut A, data: &[(Vec<f64>, Vec<f64>)]) {
    for (x, y) in data {
        model.update(x, y).expect("valid sample rejected");
    }
}

fn test_points() -> Vec<Vec<f64>> {
    let mut pts = Vec::new();
    for i in 0..11 {
        for j in 0..11 {
            pts.push(vec![-1.0 + 0.2 * i as f64, -1.0 + 0.2 * j as f64]);
        }
    }
    pts
}

fn predictions<A: FunctionApproximator>(model: &A) -> Vec<f64> {
    let mut out = Vec::new();
    let mut y = vec![0.0; model.output_dim()];
    for x in test_points() {
        model.predict(&x, &mut y).expect("valid query rejected");
        out.extend_from_slice(&y);
    }
    out
}

/// Normalised mean squared error of `model` against [`target`] on the 11x11 test grid.
pub fn nmse<A: FunctionApproximator>(model: &A) -> f64 {
    let n_out = model.output_dim();
    let pts = test_points();
    let pred = predictions(model);
    let truth: Vec<f64> = pts.iter().flat_map(|x| target(x, n_out)).collect();
    let mean = truth.iter().sum::<f64>() / truth.len() as f64;
    let var = truth.iter().map(|t| (t - mean).powi(2)).sum::<f64>() / truth.len() as f64;
    let mse = pred
        .iter()
        .zip(&truth)
        .map(|(p, t)| (p - t).powi(2))
        .sum::<f64>()
        / truth.len() as f64;
    mse / var
}

/// Runs every check. `make(n_out)` builds a fresh, untrained model with 2 inputs on [-1, 1]^2.
pub fn check_all<A, F>(make: F)
where
    A: FunctionApproximator + Persist,
    F: Fn(usize) -> A,
{
    for n_out in [1, 2] {
        dims(&make, n_out);
        untrained_predictions_are_finite(&make, n_out);
        inputs_not_mutated(&make, n_out);
        learns_a_smooth_function(&make, n_out);
        save_load_round_trip(&make, n_out);
        same_seed_same_model(&make, n_out);
        bad_input_rejected_and_model_unchanged(&make, n_out);
        corrupt_saved_model_is_an_error(&make, n_out);
    }
}

fn dims<A: FunctionApproximator, F: Fn(usize) -> A>(make: &F, n_out: usize) {
    let m = make(n_out);
    assert_eq!(m.input_dim(), 2);
    assert_eq!(m.output_dim(), n_out);
}

fn untrained_predictions_are_finite<A: FunctionApproximator, F: Fn(usize) -> A>(
    make: &F,
    n_out: usize,
) {
    let m = make(n_out);
    assert!(predictions(&m).iter().all(|v| v.is_finite()));
}

fn inputs_not_mutated<A: FunctionApproximator, F: Fn(usize) -> A>(make: &F, n_out: usize) {
    let mut m = make(n_out);
    let x = vec![0.3, -0.4];
    let y = target(&x, n_out);
    let (x0, y0) = (x.clone(), y.clone());
    m.update(&x, &y).unwrap();
    let mut out = vec![0.0; n_out];
    m.predict(&x, &mut out).unwrap();
    assert_eq!(x, x0);
    assert_eq!(y, y0);
}

fn learns_a_smooth_function<A: FunctionApproximator, F: Fn(usize) -> A>(make: &F, n_out: usize) {
    let mut m = make(n_out);
    train(&mut m, &stream(1, 5000, n_out));
    let e = nmse(&m);
    assert!(
        e < 0.05,
        "nMSE {e} after 5000 samples of a smooth function (n_out {n_out})"
    );
    assert!(predictions(&m).iter().all(|v| v.is_finite()));
}

fn save_load_round_trip<A: FunctionApproximator + Persist, F: Fn(usize) -> A>(
    make: &F,
    n_out: usize,
) {
    let mut m = make(n_out);
    let data = stream(2, 600, n_out);
    train(&mut m, &data[..500]);
    let json = m.to_json().unwrap();
    let mut loaded = A::from_json(&json).unwrap();
    assert_eq!(
        predictions(&m)
            .iter()
            .map(|v| v.to_bits())
            .collect::<Vec<_>>(),
        predictions(&loaded)
            .iter()
            .map(|v| v.to_bits())
            .collect::<Vec<_>>(),
        "loaded model predicts differently"
    );
    // Both keep learning identically.
    train(&mut m, &data[500..]);
    train(&mut loaded, &data[500..]);
    assert_eq!(m.to_json().unwrap(), loaded.to_json().unwrap());

    // Through a file too, and a failed save (into a missing directory) leaves nothing behind.
    // A directory of its own: tests of the same approximator type run in parallel.
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let path = dir.join(format!("model-{n_out}.json"));
    m.save(&path).unwrap();
    let from_file = A::load(&path).unwrap();
    assert_eq!(m.to_json().unwrap(), from_file.to_json().unwrap());
    assert!(m.save(dir.join("missing-dir").join("m.json")).is_err());
    assert!(!dir.join("missing-dir").exists());
}

fn same_seed_same_model<A: FunctionApproximator + Persist, F: Fn(usize) -> A>(
    make: &F,
    n_out: usize,
) {
    let (mut a, mut b) = (make(n_out), make(n_out));
    train(&mut a, &stream(3, 800, n_out));
    train(&mut b, &stream(3, 800, n_out));
    assert_eq!(a.to_json().unwrap(), b.to_json().unwrap());
}

fn bad_input_rejected_and_model_unchanged<A: FunctionApproximator + Persist, F: Fn(usize) -> A>(
    make: &F,
    n_out: usize,
) {
    let mut m = make(n_out);
    train(&mut m, &stream(4, 300, n_out));
    let before = m.to_json().unwrap();
    let good_y = vec![0.1; n_out];
    let mut out = vec![0.0; n_out];

    let bad_updates: Vec<(Vec<f64>, Vec<f64>)> = vec![
        (vec![0.1], good_y.clone()),
        (vec![0.1, 0.2, 0.3], good_y.clone()),
        (vec![0.1, 0.2], vec![0.1; n_out + 1]),
        (vec![0.1, 0.2], vec![]),
        (vec![f64::NAN, 0.2], good_y.clone()),
        (vec![0.1, f64::INFINITY], good_y.clone()),
        (vec![0.1, 0.2], vec![f64::NAN; n_out]),
        (vec![0.1, 0.2], vec![f64::NEG_INFINITY; n_out]),
    ];
    for (x, y) in &bad_updates {
        let r = m.update(x, y);
        assert!(
            matches!(
                r,
                Err(ApproxError::DimensionMismatch { .. } | ApproxError::NonFinite { .. })
            ),
            "update({x:?}, {y:?}) gave {r:?}"
        );
        assert_eq!(
            before,
            m.to_json().unwrap(),
            "rejected update changed the model"
        );
    }
    assert!(m.predict(&[0.1], &mut out).is_err());
    assert!(m.predict(&[f64::NAN, 0.0], &mut out).is_err());
    assert!(m.predict(&[0.0, 0.0], &mut vec![0.0; n_out + 1]).is_err());
    assert_eq!(before, m.to_json().unwrap());
}

fn corrupt_saved_model_is_an_error<A: FunctionApproximator + Persist, F: Fn(usize) -> A>(
    make: &F,
    n_out: usize,
) {
    let mut m = make(n_out);
    train(&mut m, &stream(5, 300, n_out));
    let json = m.to_json().unwrap();
    // Truncated, empty and foreign files are errors.
    assert!(matches!(
        A::from_json(&json[..json.len() / 2]),
        Err(ApproxError::Corrupt(_))
    ));
    assert!(A::from_json("").is_err());
    assert!(A::from_json("{\"hello\": 1}").is_err());
    assert!(A::from_json("[1, 2, 3]").is_err());

    // Tampering with any numeric array must never panic: either an error, or a model that
    // still answers with finite numbers.
    let value: serde_json::Value = serde_json::from_str(&json).unwrap();
    let mut paths = Vec::new();
    numeric_arrays(&value, &mut Vec::new(), &mut paths);
    for path in paths.iter().take(40) {
        for tamper in [Tamper::DropLast, Tamper::Huge] {
            let mut v = value.clone();
            apply(&mut v, path, tamper);
            let text = v.to_string();
            let outcome = catch_unwind(AssertUnwindSafe(|| match A::from_json(&text) {
                Ok(loaded) => answers_finite_or_errs(&loaded),
                Err(_) => true,
            }));
            assert!(
                matches!(outcome, Ok(true)),
                "tampered model ({tamper:?} at {path:?}) panicked or predicted non-finite values"
            );
        }
    }
}

/// True if every query on the test grid either fails with an error or gives finite values.
fn answers_finite_or_errs<A: FunctionApproximator>(model: &A) -> bool {
    let mut y = vec![0.0; model.output_dim()];
    test_points()
        .iter()
        .all(|x| match model.predict(x, &mut y) {
            Ok(()) => y.iter().all(|v| v.is_finite()),
            Err(_) => true,
        })
}

#[derive(Debug, Clone, Copy)]
enum Tamper {
    DropLast,
    Huge,
}

fn numeric_arrays(v: &serde_json::Value, at: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    match v {
        serde_json::Value::Array(items) => {
            if !items.is_empty() && items.iter().all(|i| i.is_number()) {
                out.push(at.clone());
            } else {
                for (i, item) in items.iter().enumerate() {
                    at.push(i.to_string());
                    numeric_arrays(item, at, out);
                    at.pop();
                }
            }
        }
        serde_json::Value::Object(map) => {
            for (k, item) in map {
                at.push(k.clone());
                numeric_arrays(item, at, out);
                at.pop();
            }
        }
        _ => {}
    }
}

fn apply(v: &mut serde_json::Value, path: &[String], tamper: Tamper) {
    let mut cur = v;
    for key in path {
        cur = match cur {
            serde_json::Value::Array(items) => &mut items[key.parse::<usize>().unwrap()],
            serde_json::Value::Object(map) => map.get_mut(key).unwrap(),
            _ => unreachable!(),
        };
    }
    if let serde_json::Value::Array(items) = cur {
        match tamper {
            Tamper::DropLast => {
                items.pop();
            }
            Tamper::Huge => {
                if let Some(first) = items.first_mut() {
                    *first = serde_json::json!(1e308);
                }
            }
        }
    }
}
