//! Every fall of experiment B's trial, one line each: when, its cause
//! (`steplearn::experiments::fall_causes`), the time since the previous fall and since the last
//! push (falls more than `push_window_s` after a push are the ones B's fall rate leaves out and
//! `falls.before_next_push` counts), the touch-downs since the previous fall, and the last four
//! steps before it (F_hat / dF, m).
//!
//! `cargo run --release -p steplearn-probes --bin fall_list -- --seed 0 [--learned] [--config configs/mismatch.toml]`

use clap::Parser;
use std::path::PathBuf;
use steplearn::approx::ApproxKind;
use steplearn::control::{FootstepLearner, InputGrid};
use steplearn::experiments::config_file::ConfigFile;
use steplearn::experiments::disturbance;
use steplearn::experiments::fall_causes::run_classified;
use steplearn::rules::PendulumCart;

#[derive(Parser)]
struct Args {
    /// Seed of the push sequence (as `steplearn experiment disturbance --seed`).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// The learned walker (LWPR + pendulum-cart, the settings' learner); else the model.
    #[arg(long)]
    learned: bool,
    /// Settings and protocols as TOML or JSON (as the `steplearn` command's `--config`).
    #[arg(long)]
    config: Option<PathBuf>,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let config = match &args.config {
        Some(path) => ConfigFile::load(path)?,
        None => ConfigFile::default(),
    };
    let protocol = config.protocols.get("disturbance")?;
    let setup = disturbance::trial_setup(&config.settings, &protocol, args.seed);
    let (log, falls) = if args.learned {
        let bounds = InputGrid::default().input_box()?;
        let mut learner = FootstepLearner::new(
            ApproxKind::Lwpr.build(&bounds)?,
            PendulumCart::default(),
            config.settings.learner,
        )?;
        run_classified(&setup, Some(&mut learner))?
    } else {
        run_classified(&setup, None)?
    };
    println!("time_s cause since_previous_fall_s since_push_s touch_downs last_steps(F_hat/dF)");
    let mut previous = 0.0;
    for f in &falls {
        let last_push = log
            .pushes
            .iter()
            .filter(|p| p.time < f.time)
            .map(|p| p.time)
            .fold(f64::NAN, f64::max);
        let steps: Vec<_> = log
            .steps
            .iter()
            .filter(|s| s.time > previous && s.time < f.time)
            .collect();
        let last: Vec<String> = steps
            .iter()
            .rev()
            .take(4)
            .rev()
            .map(|s| format!("{:+.3}/{:+.3}", s.f_hat, s.learned_offset))
            .collect();
        println!(
            "{:8.2} {:24} {:6.2} {:6.2} {:4} {}",
            f.time,
            f.cause.name(),
            f.time - previous,
            f.time - last_push,
            steps.len(),
            last.join(" ")
        );
        previous = f.time;
    }
    let late = falls.iter().filter(|f| !f.cause.after_push()).count();
    println!(
        "{} falls, {} after pushes within the window, {late} without a window open",
        falls.len(),
        falls.len() - late
    );
    Ok(())
}
