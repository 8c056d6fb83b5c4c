//! Open-loop walking: the step motion generator commanded with a constant step size, no
//! balance control. Prints drift, steps and whether (and when) the robot fell.
//!
//! `cargo run --release -p steplearn-probes --bin walk_open_loop -- --step-x 0.1 --seconds 30`
//!
//! `--gait open-loop` uses [`MotionConfig::open_loop_gait`], tuned to walk without balance
//! control over the whole step range; the default gait is the one the Capture Step walker uses.

use clap::{Parser, ValueEnum};
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
    /// Print the state every this many seconds (0 = never).
    #[arg(long, default_value_t = 0.0)]
    trace: f64,
    /// Sim config override as JSON (partial configs are not supported: give all fields).
    #[arg(long)]
    sim: Option<String>,
    /// rapier solver iterations.
    #[arg(long)]
    solver: Option<usize>,
    /// rapier internal PGS iterations.
    #[arg(long)]
    pgs: Option<usize>,
    /// Ground friction coefficient.
    #[arg(long)]
    friction: Option<f64>,
    /// Physics step (s) and steps per control tick.
    #[arg(long, num_args = 2)]
    dt: Option<Vec<f64>>,
    /// Time over which the commanded step grows from 0 to `step_x` (s).
    #[arg(long, default_value_t = 4.0)]
    ramp: f64,
    /// Motion preset.
    #[arg(long, value_enum, default_value_t = Gait::Default)]
    gait: Gait,
    /// Motion config override as JSON (fields not given keep their default values).
    #[arg(long, conflicts_with = "gait")]
    motion: Option<String>,
}

/// Motion presets.
#[derive(Clone, Copy, ValueEnum)]
enum Gait {
    /// `MotionConfig::default()`, the closed-loop walker's gait.
    Default,
    /// `MotionConfig::open_loop_gait()`, tuned for walking without balance control.
    OpenLoop,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    let mut sim_config: SimConfig = match &args.sim {
        Some(j) => serde_json::from_str(j)?,
        None => SimConfig::default(),
    };
    if let Some(f) = args.friction {
        sim_config.friction = f;
    }
    if let Some(d) = &args.dt {
        sim_config.dt = d[0];
        sim_config.steps_per_tick = d[1] as usize;
        sim_config.push_steps = d[1] as usize;
    }
    if let Some(n) = args.pgs {
        sim_config.pgs_iterations = n;
    }
    if let Some(n) = args.solver {
        sim_config.solver_iterations = n;
    }
    let mut sim = Humanoid::new(sim_config.clone())?;
    let motion: MotionConfig = match &args.motion {
        Some(j) => serde_json::from_str(j)?,
        None => match args.gait {
            Gait::Default => MotionConfig::default(),
            Gait::OpenLoop => MotionConfig::open_loop_gait(),
        },
    };
    let mut motion_gen = MotionGenerator::new(motion.check()?, &sim.body().leg_geometry());
    let dt = sim_config.tick();
    let start = sim.ground_truth();
    let wall = std::time::Instant::now();
    let mut fell = None;
    while sim.time() < args.seconds {
        let targets = if args.stand {
            motion_gen.halt_targets()
        } else {
            let ramp = if args.ramp > 0.0 {
                (sim.time() / args.ramp).min(1.0)
            } else {
                1.0
            };
            let cmd = motion_gen.open_loop(args.step_x * ramp);
            motion_gen.update(&cmd, dt)
        };
        sim.step(&targets)?;
        if args.trace > 0.0 && (sim.time() / args.trace).fract() < dt / args.trace {
            let t = sim.ground_truth();
            let s = sim.sensors();
            let rpy = s.imu.roll_pitch_yaw();
            println!(
                "t {:6.2} p {:.2} sup {:?} com {:+.3} {:+.3} {:.3} v {:+.2} {:+.2} rpy {:+.3} {:+.3} {:+.3} F {:5.1} {:5.1}",
                sim.time(),
                motion_gen.phase(),
                motion_gen.support(),
                t.com[0],
                t.com[1],
                t.com[2],
                t.com_vel[0],
                t.com_vel[1],
                rpy[0],
                rpy[1],
                rpy[2],
                s.feet[0].normal_force,
                s.feet[1].normal_force
            );
        }
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
