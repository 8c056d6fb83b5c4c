//! The walker as a footstep environment: episodes under experiment C's random pushes with zero
//! actions (the Capture Step model) and with a proportional policy dF = k theta_E (the
//! pendulum-cart balance law without learning), on the same pushes; prints each policy's mean
//! return, falls and footsteps, and the wall-clock cost per footstep.
//!
//! `cargo run --release --example footstep_env -- --episodes 5 --max-footsteps 100 --gain 1.0`

use clap::Parser;
use std::path::PathBuf;
use std::time::Instant;
use steplearn::experiments::footstep_env::{FootstepEnv, FootstepEnvConfig};

#[derive(Parser)]
struct Args {
    /// Episodes per policy (seeds 0, 1, ...).
    #[arg(long, default_value_t = 5)]
    episodes: u64,
    /// Footsteps per episode before truncation.
    #[arg(long, default_value_t = 100)]
    max_footsteps: usize,
    /// The proportional policy's gain k (m of dF per rad of theta_E).
    #[arg(long, default_value_t = 1.0)]
    gain: f64,
    /// A URDF robot instead of the built-in humanoid.
    #[arg(long)]
    robot: Option<PathBuf>,
}

/// An action from an observation.
type Policy = dyn Fn(&[f64]) -> f64;

/// One policy's episodes: total return, falls, footsteps and stepping time (s).
fn run(
    env: &mut FootstepEnv,
    episodes: u64,
    policy: impl Fn(&[f64]) -> f64,
) -> Result<(f64, usize, usize, f64), Box<dyn std::error::Error>> {
    let [lo, hi] = env.action_bounds()[0];
    let (mut total, mut falls, mut footsteps, mut seconds) = (0.0, 0, 0, 0.0);
    for seed in 0..episodes {
        let mut obs = env.reset(seed)?.values();
        loop {
            let action = policy(&obs).clamp(lo, hi);
            let clock = Instant::now();
            let r = env.step(&[action])?;
            seconds += clock.elapsed().as_secs_f64();
            footsteps += 1;
            total += r.reward;
            obs = r.observation.values();
            if r.terminated {
                falls += 1;
            }
            if r.terminated || r.truncated {
                break;
            }
        }
    }
    Ok((total / episodes as f64, falls, footsteps, seconds))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    if args.episodes == 0 || args.max_footsteps == 0 || !args.gain.is_finite() {
        return Err("--episodes and --max-footsteps must be >= 1, --gain finite".into());
    }
    let config = FootstepEnvConfig {
        robot: args.robot,
        max_footsteps: args.max_footsteps,
        ..FootstepEnvConfig::default()
    };
    let mut env = FootstepEnv::new(config)?;
    println!(
        "observation: {}; action: {} in {:?}",
        env.observation_names().join(", "),
        env.action_names().join(", "),
        env.action_bounds()
    );
    let gain = args.gain;
    let policies: [(&str, Box<Policy>); 2] = [
        ("zero (the model)", Box::new(|_| 0.0)),
        ("dF = k theta_E", Box::new(move |o| gain * o[0])),
    ];
    for (name, policy) in policies {
        let (mean, falls, steps, seconds) = run(&mut env, args.episodes, policy)?;
        println!(
            "{name:>18}: mean return {mean:9.3}, {falls} falls in {} episodes, {steps} footsteps, \
             {:.2} ms per footstep",
            args.episodes,
            1e3 * seconds / steps as f64
        );
    }
    Ok(())
}
