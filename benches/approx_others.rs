//! criterion benches: update and predict of Grid, Rbf (NLMS and RLS) and KernelRidge on cross
//! 2D and the 3-input step-offset map, with the recommended settings of each config's docs,
//! after 20,000 training samples (so the kernel ridge dictionary is at its budget).
//!
//! `cargo bench --bench approx_others`

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Duration;
use steplearn::approx::problems::Problem;
use steplearn::approx::{
    FunctionApproximator, Grid, GridConfig, InputBox, KernelRidge, KernelRidgeConfig, Rbf,
    RbfConfig, RbfUpdate,
};

fn spacing_widths(p: &Problem, centres: &[usize], factor: f64) -> Vec<f64> {
    p.lo.iter()
        .zip(&p.hi)
        .zip(centres)
        .map(|((l, h), &n)| factor * (h - l) / (n - 1) as f64)
        .collect()
}

/// The models under test for a problem, with the recommended settings.
fn models(p: &Problem) -> Vec<(&'static str, Box<dyn FunctionApproximator>)> {
    let bounds = InputBox::new(p.lo.clone(), p.hi.clone()).unwrap();
    let is_3d = p.dim() == 3;
    let (res, lr) = if is_3d {
        (vec![11, 5, 5], 0.05)
    } else {
        (vec![31, 31], 0.1)
    };
    let grid = Grid::new(GridConfig {
        learning_rate: lr,
        ..GridConfig::new(bounds.clone(), res, 1)
    })
    .unwrap();
    let centres = if is_3d { vec![9, 5, 5] } else { vec![21, 21] };
    let rbf = |update| {
        Rbf::new(RbfConfig {
            widths: spacing_widths(p, &centres, 0.7),
            update,
            ..RbfConfig::new(bounds.clone(), centres.clone(), 1)
        })
        .unwrap()
    };
    let (scales, reg) = if is_3d {
        (p.half_ranges(), 1e-4)
    } else {
        (vec![0.25; 2], 0.01)
    };
    let kr = KernelRidge::new(KernelRidgeConfig {
        regularisation: reg,
        ..KernelRidgeConfig::new(scales, 1)
    })
    .unwrap();
    vec![
        ("grid", Box::new(grid)),
        (
            "rbf_nlms",
            Box::new(rbf(RbfUpdate::Nlms { learning_rate: 0.1 })),
        ),
        (
            "rbf_rls",
            Box::new(rbf(RbfUpdate::Rls {
                forgetting: 1.0,
                prior_variance: 100.0,
            })),
        ),
        ("kernel_ridge", Box::new(kr)),
    ]
}

fn bench(c: &mut Criterion) {
    for p in [Problem::cross_2d(), Problem::step_offset_3d()] {
        let warm = p.train_stream(1, 20_000);
        let stream = p.train_stream(2, 10_000);
        let test = p.test_set(21);
        for (name, mut model) in models(&p) {
            for (x, y) in &warm {
                model.update(x, &[*y]).unwrap();
            }
            let mut out = [0.0];
            let mut i = 0;
            c.bench_function(&format!("{}/{name}/predict", p.name), |b| {
                b.iter(|| {
                    let (x, _) = &test[i % test.len()];
                    i += 1;
                    model.predict(black_box(x), &mut out).unwrap();
                    black_box(out[0])
                })
            });
            let mut i = 0;
            c.bench_function(&format!("{}/{name}/update", p.name), |b| {
                b.iter(|| {
                    let (x, y) = &stream[i % stream.len()];
                    i += 1;
                    model.update(black_box(x), &[*y]).unwrap();
                })
            });
        }
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = bench
}
criterion_main!(benches);
