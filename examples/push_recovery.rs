//! The push-recovery curve (the paper's experiment C, Fig. 6): fall probability against forward
//! push impulse for the open-loop walker, the Capture Step model and the learned walker (LWPR +
//! pendulum-cart), walking in place, pushed at random gait phases. Writes `pushes.csv` and
//! `fall_probability.svg` and prints the impulse at 50% falls per controller.
//!
//! `cargo run --release --example push_recovery -- --pushes 100 --seed 1 --out results/push_recovery`

use clap::Parser;
use std::path::PathBuf;
use steplearn::approx::ApproxKind;
use steplearn::control::{FootstepLearner, InputGrid, LearnerConfig};
use steplearn::experiments::settings::Settings;
use steplearn::experiments::stability::{self, StabilityProtocol};
use steplearn::rules::PendulumCart;

#[derive(Parser)]
struct Args {
    /// Pushes per controller.
    #[arg(long, default_value_t = 100)]
    pushes: usize,
    /// Seed of the push sequence.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Largest impulse (Ns); impulses are uniform in [0, max].
    #[arg(long, default_value_t = 20.0)]
    max_impulse: f64,
    /// The learner's rate eta (the paper: 1).
    #[arg(long, default_value_t = 1.0)]
    eta: f64,
    /// Output directory.
    #[arg(long, default_value = "results/push_recovery")]
    out: PathBuf,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    if !(args.max_impulse.is_finite() && args.max_impulse > 0.0) || args.pushes == 0 {
        return Err("--pushes must be >= 1 and --max-impulse positive".into());
    }
    let protocol = StabilityProtocol {
        pushes: args.pushes,
        impulse: (0.0, args.max_impulse),
        ..StabilityProtocol::default()
    };
    let grid = InputGrid::default();
    let bounds = grid.input_box()?;
    let make = || {
        let approx = ApproxKind::Lwpr
            .build(&bounds)
            .expect("the default LWPR config is valid");
        FootstepLearner::new(
            approx,
            PendulumCart::default(),
            LearnerConfig {
                eta: args.eta,
                ..LearnerConfig::default()
            },
        )
    };
    let wall = std::time::Instant::now();
    let result = stability::run(&Settings::default(), &protocol, args.seed, &make)?;
    result.write(&args.out, protocol.impulse, protocol.direction)?;
    println!("| controller | pushes | falls | impulse at 50% falls (Ns) | method |");
    println!("|---|---|---|---|---|");
    for (name, c) in result.controllers() {
        println!(
            "| {name} | {} | {} | {:.2} | {:?} |",
            c.pushes.len(),
            c.falls(),
            c.fall50.impulse_ns,
            c.fall50.method
        );
    }
    println!(
        "wrote {} and {} ({:.0} s wall)",
        args.out.join("pushes.csv").display(),
        args.out.join("fall_probability.svg").display(),
        wall.elapsed().as_secs_f64()
    );
    Ok(())
}
