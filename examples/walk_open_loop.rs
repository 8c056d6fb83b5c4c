//! Open-loop walking: the step motion generator commanded with a constant step size, no
//! balance control. Prints drift, steps and whether (and when) the robot fell.
//!
//! `cargo run --release --example walk_open_loop -- --step-x 0.1 --seconds 30`

use clap::Parser;
use steplearn::control::motion::{MotionConfig, MotionGenerator};
use steplearn::sim::{Humanoid, SimConfig};

#[derive(Parser)]
struct Args {
    /// Commanded sagittal step size (m).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    step_x: f64,
    /// Simulated seconds.
    #[arg(long, default_value_t = 30.0)]
    seconds: f64,
    /// Stand still instead of stepping.
    #[arg(long)]
    stand: bool,
    /// Motion config override as JSON.
    #[arg(long)]
    motion: Option<String>,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let sim_config = SimConfig::default();
    let mut sim = Humanoid::new(sim_config.clone())?;
    let motion: MotionConfig = match &args.motion {
        Some(j) => serde_json::from_str(j)?,
        None => MotionConfig::default(),
    };
    let mut motion_gen = MotionGenerator::new(motion, &sim.body().leg_geometry());
    let dt = sim_config.tick();
    let start = sim.ground_truth();
    let wall = std::time::Instant::now();
    let mut fell = None;
    while sim.time() < args.seconds {
        let targets = if args.stand {
            motion_gen.halt_targets()
        } else {
            let cmd = motion_gen.open_loop(args.step_x);
            motion_gen.update(&cmd, dt)
        };
        sim.step(&targets)?;
        if let Some(f) = sim.fall() {
            fell = Some(f);
            break;
        }
    }
    let end = sim.ground_truth();
    let wall = wall.elapsed().as_secs_f64();
    println!(
        "step_x {:+.3}: t = {:.2} s, steps {}, fell {:?}, CoM start {:.3?} end {:.3?}, drift x {:+.3} y {:+.3} m, {:.1}x real time",
        args.step_x,
        sim.time(),
        motion_gen.steps(),
        fell,
        start.com,
        end.com,
        end.com[0] - start.com[0],
        end.com[1] - start.com[1],
        sim.time() / wall
    );
    Ok(())
}
