//! Property tests of LWPR convergence: random linear and smooth functions in 1-3 inputs are
//! learned to a tight error, predictions stay finite, and the number of receptive fields is
//! bounded by the input volume.

use proptest::prelude::*;
use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use steplearn::approx::{FunctionApproximator, Lwpr, LwprConfig};

/// A random target: `b + a . x + c * sin(2 x_0)` (linear when `c == 0`).
#[derive(Debug, Clone)]
struct Target {
    a: Vec<f64>,
    b: f64,
    c: f64,
}

impl Target {
    fn eval(&self, x: &[f64]) -> f64 {
        self.b + self.a.iter().zip(x).map(|(a, x)| a * x).sum::<f64>() + self.c * (2.0 * x[0]).sin()
    }
}

fn target(dim: usize, smooth: bool) -> impl Strategy<Value = Target> {
    (
        prop::collection::vec(-1.0..1.0f64, dim),
        -1.0..1.0f64,
        if smooth {
            (0.2..0.6f64).boxed()
        } else {
            Just(0.0).boxed()
        },
    )
        .prop_map(|(a, b, c)| Target { a, b, c })
}

/// Trains on `n` uniform samples in [-1, 1]^d; returns the model and its RMS error on a
/// seeded test sample relative to the target's standard deviation.
fn learn(t: &Target, seed: u64, n: usize) -> (Lwpr, f64) {
    let d = t.a.len();
    let mut model = Lwpr::new(LwprConfig::new(d, 1)).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut x = vec![0.0; d];
    for _ in 0..n {
        for v in &mut x {
            *v = rng.random_range(-1.0..1.0);
        }
        model.update(&x, &[t.eval(&x)]).unwrap();
    }
    let (mut se, mut ys) = (0.0, Vec::new());
    let mut out = [0.0];
    for _ in 0..400 {
        for v in &mut x {
            *v = rng.random_range(-0.9..0.9);
        }
        model.predict(&x, &mut out).unwrap();
        assert!(out[0].is_finite());
        let y = t.eval(&x);
        se += (out[0] - y).powi(2);
        ys.push(y);
    }
    let mean = ys.iter().sum::<f64>() / ys.len() as f64;
    let var = ys.iter().map(|y| (y - mean).powi(2)).sum::<f64>() / ys.len() as f64;
    (model, (se / ys.len() as f64 / var.max(1e-12)).sqrt())
}

/// Standard deviation of the target over an even grid on [-0.9, 0.9]^d.
fn spread(t: &Target) -> f64 {
    let d = t.a.len();
    let n = 9usize;
    let ys: Vec<f64> = (0..n.pow(d as u32))
        .map(|mut k| {
            let x: Vec<f64> = (0..d)
                .map(|_| {
                    let v = -0.9 + 1.8 * (k % n) as f64 / (n - 1) as f64;
                    k /= n;
                    v
                })
                .collect();
            t.eval(&x)
        })
        .collect();
    let mean = ys.iter().sum::<f64>() / ys.len() as f64;
    (ys.iter().map(|y| (y - mean).powi(2)).sum::<f64>() / ys.len() as f64).sqrt()
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 12,
        rng_seed: proptest::test_runner::RngSeed::Fixed(14),
        ..ProptestConfig::default()
    })]

    #[test]
    fn linear_functions_are_learned_tightly(t in (1usize..=3).prop_flat_map(|d| target(d, false)), seed in 0u64..1000) {
        let dim = t.a.len();
        prop_assume!(t.a.iter().map(|a| a * a).sum::<f64>() > 0.01);
        let (_, rel) = learn(&t, seed, 3000 * dim);
        prop_assert!(rel < 0.02, "relative RMS error {rel} for {t:?}");
    }

    #[test]
    fn smooth_functions_are_learned(t in (1usize..=3).prop_flat_map(|d| target(d, true)), seed in 0u64..1000) {
        let d = t.a.len();
        // The error is relative to the target's spread, so a target whose linear part nearly
        // cancels the sine (spread well below its amplitude) inflates it: e.g. y = -0.79 x +
        // 0.445 sin(2x) plateaus at 0.098 relative (absolute RMS about 0.015) even after 100k
        // samples with the library defaults. Every target is kept: one with a spread of at
        // least 0.3 must be learned to 10% of it, any other to an absolute RMS error of 0.03.
        let (model, rel) = learn(&t, seed, 5000 * d);
        let spread = spread(&t);
        if spread >= 0.3 {
            prop_assert!(rel < 0.1, "relative RMS error {rel} for {t:?}");
        } else {
            prop_assert!(rel * spread < 0.03, "absolute RMS error {} for {t:?}", rel * spread);
        }
        // Receptive fields are bounded by the input volume: with the initial metric 25 I and
        // w_gen 0.1 a new field is only created farther than sqrt(2 ln 10 / 25) = 0.43 from
        // every centre, so the centres pack balls of radius 0.21 into [-1.21, 1.21]^d. The
        // metrics adapt (a field can narrow), so this is a checked property, not a theorem.
        let r = 0.5 * (2.0 * 10f64.ln() / 25.0).sqrt();
        let ball = match d { 1 => 2.0 * r, 2 => std::f64::consts::PI * r * r, _ => 4.0 / 3.0 * std::f64::consts::PI * r.powi(3) };
        let bound = (2.0 * (1.0 + r)).powi(d as i32) / ball;
        prop_assert!((model.num_receptive_fields() as f64) <= bound,
            "{} RFs > volume bound {bound}", model.num_receptive_fields());
    }

    #[test]
    fn predictions_are_always_finite(
        samples in prop::collection::vec((prop::collection::vec(-1e3..1e3f64, 2), -1e3..1e3f64), 1..200),
        queries in prop::collection::vec(prop::collection::vec(-1e6..1e6f64, 2), 1..20),
    ) {
        let mut model = Lwpr::new(LwprConfig::new(2, 1).meta(true)).unwrap();
        for (x, y) in &samples {
            model.update(x, &[*y]).unwrap();
        }
        let (mut out, mut conf) = ([0.0], [0.0]);
        for x in &queries {
            model.predict_with_confidence(x, &mut out, &mut conf).unwrap();
            prop_assert!(out[0].is_finite());
            prop_assert!(conf[0] >= 0.0);
        }
    }
}
