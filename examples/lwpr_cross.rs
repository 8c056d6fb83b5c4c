//! Trains LWPR on the cross 2D problem with the reference C demo's settings (init_D 50,
//! init_alpha 250, w_gen 0.2; 100,000 fresh noisy samples) for five seeds, then prints the
//! nMSE on the noiseless 41x41 grid, the number of receptive fields and the time per update
//! and per prediction. Also runs the 3-input step-offset problem with the same settings and
//! `norm_in` = half ranges.
//!
//! Run with `cargo run --release --example lwpr_cross`.

use std::time::Instant;
use steplearn::approx::problems::{Problem, nmse};
use steplearn::approx::{FunctionApproximator, Lwpr, LwprConfig};

fn demo_config(problem: &Problem, norm_in: bool) -> LwprConfig {
    let config = LwprConfig::new(problem.dim(), 1)
        .init_d(50.0)
        .init_alpha(250.0)
        .w_gen(0.2);
    if norm_in {
        config.norm_in(problem.half_ranges())
    } else {
        config
    }
}

struct Run {
    nmse: f64,
    rfs: usize,
    us_update: f64,
    us_predict: f64,
}

fn run(problem: &Problem, config: LwprConfig, seed: u64, n_train: usize) -> Run {
    let train = problem.train_stream(seed, n_train);
    let test = problem.test_set(41);
    let mut model = Lwpr::new(config).expect("valid config");
    let t0 = Instant::now();
    for (x, y) in &train {
        model.update(x, &[*y]).expect("valid sample");
    }
    let us_update = t0.elapsed().as_secs_f64() * 1e6 / n_train as f64;
    let mut pred = vec![0.0; test.len()];
    let mut out = [0.0];
    // Predict the test set a few times for a stable timing.
    let reps = 20;
    let t1 = Instant::now();
    for _ in 0..reps {
        for (p, (x, _)) in pred.iter_mut().zip(&test) {
            model.predict(x, &mut out).expect("valid query");
            *p = out[0];
        }
    }
    let us_predict = t1.elapsed().as_secs_f64() * 1e6 / (reps * test.len()) as f64;
    let truth: Vec<f64> = test.iter().map(|(_, y)| *y).collect();
    Run {
        nmse: nmse(&pred, &truth),
        rfs: model.num_receptive_fields(),
        us_update,
        us_predict,
    }
}

fn report(problem: &Problem, norm_in: bool) {
    println!(
        "{} ({} inputs), C demo settings, 100,000 samples, 41^d test grid:",
        problem.name,
        problem.dim()
    );
    let mut runs = Vec::new();
    for seed in 1..=5 {
        let r = run(problem, demo_config(problem, norm_in), seed, 100_000);
        println!(
            "  seed {seed}: nMSE {:.5}  RFs {:4}  {:.3} us/update  {:.3} us/predict",
            r.nmse, r.rfs, r.us_update, r.us_predict
        );
        runs.push(r);
    }
    let median = |f: &dyn Fn(&Run) -> f64| {
        let mut v: Vec<f64> = runs.iter().map(f).collect();
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    println!(
        "  median: nMSE {:.5}  RFs {}  {:.3} us/update  {:.3} us/predict",
        median(&|r| r.nmse),
        median(&|r| r.rfs as f64),
        median(&|r| r.us_update),
        median(&|r| r.us_predict)
    );
}

fn main() {
    report(&Problem::cross_2d(), false);
    report(&Problem::step_offset_3d(), true);
}
