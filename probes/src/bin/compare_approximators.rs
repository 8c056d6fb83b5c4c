//! Trains every approximator on the same seeded streams and prints one Markdown table.
//!
//! `cargo run --release -p steplearn-probes --bin compare_approximators [-- --samples N]`
//!
//! Problems (from `steplearn::approx::problems`): cross 2D (noiseless 41x41 test grid), the
//! 3-input step-offset map (21^3 test grid) and cross 2D embedded in 10 inputs with 8
//! irrelevant ones (1681 random test points). Each model sees the same training stream
//! (seed 1, 100,000 samples by default); us/update is the mean over the whole stream,
//! us/predict the mean over the test set; size is the saved model's JSON length.

use std::time::Instant;
use steplearn::approx::problems::{Problem, nmse};
use steplearn::approx::{
    ApproxError, FunctionApproximator, Grid, GridConfig, InputBox, KernelRidge, KernelRidgeConfig,
    Lwpr, LwprConfig, Persist, Rbf, RbfConfig, RbfUpdate,
};

/// What the comparison needs from a model: the trait, plus its saved size.
trait Compared: FunctionApproximator {
    fn json_bytes(&self) -> Result<usize, ApproxError>;
}

impl<T: FunctionApproximator + Persist> Compared for T {
    fn json_bytes(&self) -> Result<usize, ApproxError> {
        Ok(self.to_json()?.len())
    }
}

/// A model built for a problem, with a short description of its settings.
struct Built {
    model: Box<dyn Compared>,
    settings: String,
}

type Factory = fn(&Problem) -> Result<Built, ApproxError>;

fn bounds(p: &Problem) -> Result<InputBox, ApproxError> {
    InputBox::new(p.lo.clone(), p.hi.clone())
}

/// Per-dimension spacing of `n` centres over the problem's box, times `factor`.
fn spacing_widths(p: &Problem, n: &[usize], factor: f64) -> Vec<f64> {
    p.lo.iter()
        .zip(&p.hi)
        .zip(n)
        .map(|((l, h), &n)| factor * (h - l) / (n.max(2) - 1) as f64)
        .collect()
}

fn grid(p: &Problem) -> Result<Built, ApproxError> {
    // The recommended settings from `GridConfig`'s docs; on 10 inputs the 2-D resolution per
    // input, which needs 31^10 nodes and is rejected.
    let (res, lr) = match p.name {
        "step-offset-3d" => (vec![11, 5, 5], 0.05),
        _ => (vec![31; p.dim()], 0.1),
    };
    let settings = format!("resolution {res:?}, learning_rate {lr}");
    let config = GridConfig {
        learning_rate: lr,
        ..GridConfig::new(bounds(p)?, res, 1)
    };
    Ok(Built {
        model: Box::new(Grid::new(config)?),
        settings,
    })
}

fn grid_coarse(p: &Problem) -> Result<Built, ApproxError> {
    // 3 nodes per input: the most a 10-input table can afford (59,049 nodes).
    let res = vec![3; p.dim()];
    let settings = "resolution 3 per input, learning_rate 0.1".to_string();
    let config = GridConfig {
        learning_rate: 0.1,
        ..GridConfig::new(bounds(p)?, res, 1)
    };
    Ok(Built {
        model: Box::new(Grid::new(config)?),
        settings,
    })
}

fn rbf(p: &Problem, update: RbfUpdate, label: &str) -> Result<Built, ApproxError> {
    let (centres, factor) = match p.name {
        "step-offset-3d" => (vec![9, 5, 5], 0.7),
        _ => (vec![21; p.dim()], 0.7),
    };
    let widths = spacing_widths(p, &centres, factor);
    let settings = format!("{label}, centres {centres:?}, widths {factor} x spacing");
    let config = RbfConfig {
        widths,
        update,
        ..RbfConfig::new(bounds(p)?, centres, 1)
    };
    Ok(Built {
        model: Box::new(Rbf::new(config)?),
        settings,
    })
}

fn rbf_nlms(p: &Problem) -> Result<Built, ApproxError> {
    rbf(p, RbfUpdate::Nlms { learning_rate: 0.1 }, "NLMS rate 0.1")
}

fn rbf_rls(p: &Problem) -> Result<Built, ApproxError> {
    rbf(
        p,
        RbfUpdate::Rls {
            forgetting: 1.0,
            prior_variance: 100.0,
        },
        "RLS",
    )
}

fn rbf_coarse(p: &Problem) -> Result<Built, ApproxError> {
    // 2 centres per input (1,024 in 10-D), widths = spacing, NLMS.
    let centres = vec![2; p.dim()];
    let config = RbfConfig {
        widths: spacing_widths(p, &centres, 1.0),
        ..RbfConfig::new(bounds(p)?, centres, 1)
    };
    Ok(Built {
        model: Box::new(Rbf::new(config)?),
        settings: "NLMS rate 0.1, 2 centres per input, widths = spacing".into(),
    })
}

fn kernel_ridge(p: &Problem) -> Result<Built, ApproxError> {
    // The recommended settings from `KernelRidgeConfig`'s docs (defaults: budget 100, novelty
    // threshold 0.02); on 10 inputs one isotropic length scale, as a user who does not know
    // which inputs matter would choose.
    let (scales, reg) = match p.name {
        "step-offset-3d" => (p.half_ranges(), 1e-4),
        "cross-2d" => (vec![0.25; 2], 0.01),
        _ => (vec![0.7; p.dim()], 0.01),
    };
    let settings = format!(
        "length_scales {:?}, regularisation {reg}, budget 100, novelty_threshold 0.02",
        scales
            .iter()
            .map(|s| (s * 1e3).round() / 1e3)
            .collect::<Vec<_>>()
    );
    let config = KernelRidgeConfig {
        regularisation: reg,
        ..KernelRidgeConfig::new(scales, 1)
    };
    Ok(Built {
        model: Box::new(KernelRidge::new(config)?),
        settings,
    })
}

fn lwpr(p: &Problem) -> Result<Built, ApproxError> {
    // The reference C demo's settings, with inputs scaled by the box's half-widths.
    let config = LwprConfig::new(p.dim(), 1)
        .init_d(50.0)
        .init_alpha(250.0)
        .w_gen(0.2)
        .norm_in(p.half_ranges());
    Ok(Built {
        model: Box::new(Lwpr::new(config)?),
        settings: "init_D 50, init_alpha 250, w_gen 0.2, norm_in = half ranges".into(),
    })
}

fn main() {
    let mut samples = 100_000;
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--samples") {
        samples = args
            .get(i + 1)
            .and_then(|s| s.parse().ok())
            .expect("--samples needs a number");
    }
    let factories: Vec<(&str, Factory)> = vec![
        ("LWPR", lwpr),
        ("Grid", grid),
        ("Grid, coarse", grid_coarse),
        ("RBF (NLMS)", rbf_nlms),
        ("RBF (RLS)", rbf_rls),
        ("RBF, coarse", rbf_coarse),
        ("KernelRidge", kernel_ridge),
    ];
    let problems = [
        (Problem::cross_2d(), 41),
        (Problem::step_offset_3d(), 21),
        (Problem::cross_10d(), 41),
    ];
    println!("| problem | approximator | nMSE | us/update | us/predict | JSON bytes |");
    println!("|---|---|---|---|---|---|");
    let mut legend = Vec::new();
    for (problem, per_dim) in &problems {
        let train = problem.train_stream(1, samples);
        let test = problem.test_set(*per_dim);
        let truth: Vec<f64> = test.iter().map(|(_, y)| *y).collect();
        for (name, make) in &factories {
            // Coarse variants only where the regular ones cannot run.
            if name.ends_with("coarse") && problem.dim() <= 3 {
                continue;
            }
            let built = match make(problem) {
                Ok(b) => b,
                Err(e) => {
                    println!("| {} | {name} | config error: {e} | | | |", problem.name);
                    continue;
                }
            };
            let Built {
                mut model,
                settings,
            } = built;
            legend.push(format!("{} / {name}: {settings}", problem.name));
            let start = Instant::now();
            for (x, y) in &train {
                model.update(x, &[*y]).expect("valid sample");
            }
            let us_update = start.elapsed().as_secs_f64() * 1e6 / train.len() as f64;
            let mut pred = vec![0.0; test.len()];
            let mut out = [0.0];
            let start = Instant::now();
            for ((x, _), p) in test.iter().zip(&mut pred) {
                model.predict(x, &mut out).expect("valid query");
                *p = out[0];
            }
            let us_predict = start.elapsed().as_secs_f64() * 1e6 / test.len() as f64;
            let bytes = model
                .json_bytes()
                .map_or_else(|e| format!("error: {e}"), |b| b.to_string());
            println!(
                "| {} | {name} | {:.4} | {us_update:.2} | {us_predict:.2} | {bytes} |",
                problem.name,
                nmse(&pred, &truth)
            );
        }
    }
    println!("\nSettings ({samples} training samples, seed 1):\n");
    for l in legend {
        println!("- {l}");
    }
}
