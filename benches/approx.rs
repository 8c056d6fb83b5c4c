//! Criterion benchmarks of every approximator on the seeded problems.
//!
//! One generic function, [`bench_approximator`], measures update and predict time of any
//! [`FunctionApproximator`] on any [`Problem`]; adding an approximator is one line in
//! [`benches`]. Bench ids: `update/<approximator>/<problem>` and
//! `predict/<approximator>/<problem>`; `drift/lwpr/<max_rfs>/<updates>`: one update of LWPR
//! after that many updates of a drifting stream, without a cap (`none`) and with
//! `max_rfs(500)`. Run with `cargo bench --bench approx`.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use steplearn::approx::problems::{Drift, Problem};
use steplearn::approx::{FunctionApproximator, Lwpr, LwprConfig};

/// Samples the model is trained on before timing (the reference's demo length).
const WARMUP_SAMPLES: usize = 100_000;

/// Trains `make()` on `WARMUP_SAMPLES` samples of `problem`, then times one update (on fresh
/// samples, cycling through a pre-drawn stream) and one prediction (cycling through the test
/// set) of the trained model.
fn bench_approximator<A: FunctionApproximator>(
    c: &mut Criterion,
    name: &str,
    problem: &Problem,
    make: impl Fn() -> A,
) {
    let mut model = make();
    for (x, y) in problem.train_stream(1, WARMUP_SAMPLES) {
        model.update(&x, &[y]).expect("valid sample");
    }
    let fresh = problem.train_stream(2, 100_000);
    let test = problem.test_set(41);
    let mut out = vec![0.0; model.output_dim()];

    let mut k = 0;
    c.bench_function(&format!("predict/{name}/{}", problem.name), |b| {
        b.iter(|| {
            let (x, _) = &test[k % test.len()];
            k += 1;
            model.predict(black_box(x), &mut out).expect("valid query");
            black_box(out[0])
        })
    });
    let mut k = 0;
    c.bench_function(&format!("update/{name}/{}", problem.name), |b| {
        b.iter(|| {
            let (x, y) = &fresh[k % fresh.len()];
            k += 1;
            model.update(black_box(x), &[*y]).expect("valid sample");
        })
    });
}

/// LWPR with the reference C demo's settings (init_D 50, init_alpha 250, w_gen 0.2; inputs
/// normalised by the half ranges of the problem's box).
fn lwpr_demo(problem: &Problem) -> impl Fn() -> Lwpr + '_ {
    move || {
        Lwpr::new(
            LwprConfig::new(problem.dim(), 1)
                .init_d(50.0)
                .init_alpha(250.0)
                .w_gen(0.2)
                .norm_in(problem.half_ranges()),
        )
        .expect("valid config")
    }
}

fn benches(c: &mut Criterion) {
    for problem in [Problem::cross_2d(), Problem::step_offset_3d()] {
        bench_approximator(c, "lwpr", &problem, lwpr_demo(&problem));
    }
    bench_drift(c);
}

/// The cost of one LWPR update after 100,000 and 400,000 updates of a drifting stream, without
/// and with a cap on receptive fields: it grows with the stream without the cap, and stays
/// flat with it.
fn bench_drift(c: &mut Criterion) {
    for cap in [None, Some(500)] {
        let config = LwprConfig::new(3, 1);
        let mut model = Lwpr::new(match cap {
            Some(n) => config.max_rfs(n),
            None => config,
        })
        .expect("valid config");
        let mut stream = Drift::new(1, 1e-3, 1.0);
        let mut done = 0;
        for updates in [100_000, 400_000] {
            for (x, y) in stream.by_ref().take(updates - done) {
                model.update(&x, &[y]).expect("valid sample");
            }
            // Time updates on a copy with the stream's next samples (cycled), so that each
            // point measures the model where the drift has taken it.
            let ahead: Vec<([f64; 3], f64)> = stream.by_ref().take(20_000).collect();
            let mut timed = model.clone();
            let mut i = 0;
            let label = cap.map_or("none".to_string(), |n| n.to_string());
            c.bench_function(&format!("drift/lwpr/{label}/{updates}"), |b| {
                b.iter(|| {
                    let (x, y) = &ahead[i % ahead.len()];
                    i += 1;
                    timed.update(black_box(x), &[*y]).expect("valid sample");
                })
            });
            for (x, y) in &ahead {
                model.update(x, &[*y]).expect("valid sample");
            }
            done = updates + ahead.len();
        }
    }
}

criterion_group! {
    name = approx;
    config = Criterion::default().sample_size(30).measurement_time(std::time::Duration::from_secs(3));
    targets = benches
}
criterion_main!(approx);
