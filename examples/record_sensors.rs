//! Records a rapier trial on a robot from a URDF file: every control tick's sensors, the
//! reference step and the joint targets the walker (with the paper's learner) sent back. The
//! lean outside crate `outside/lean-walker` replays the sensors into its own walker, built
//! without the simulator, and must send the same targets bit for bit.
//!
//! `cargo run --release --example record_sensors -- ROBOT.urdf OUT.json [SECONDS]`

use std::path::PathBuf;

use steplearn::approx::{Lwpr, LwprConfig};
use steplearn::control::for_robot::ScaledPolicy;
use steplearn::control::{FootstepLearner, LearnerConfig};
use steplearn::control::{Walker, WalkerConfig, WalkerMode};
use steplearn::robot::RobotFile;
use steplearn::robot::{JointTargets, Sensors};
use steplearn::rules::PendulumCart;
use steplearn::sim::{BodyConfig, Humanoid, SimConfig};

#[derive(serde::Serialize)]
struct Recording {
    robot: PathBuf,
    ticks: Vec<(Sensors, f64, JointTargets)>,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let (Some(robot), Some(out)) = (args.next(), args.next()) else {
        return Err("usage: record_sensors ROBOT.urdf OUT.json [SECONDS]".into());
    };
    let seconds: f64 = args.next().map_or(Ok(10.0), |s| s.parse())?;
    let body = BodyConfig::default();
    let stance = SimConfig::default().initial_joints;
    let (file, _) = RobotFile::open(robot.as_ref(), None, &body.servo_reference(), &stance)?;
    let mut sim = Humanoid::new(SimConfig {
        robot: Some(file),
        ..SimConfig::default()
    })?;
    let scale = sim.scale();
    let config = WalkerConfig::new(WalkerMode::CaptureStep).for_robot(&scale);
    let mut walker = Walker::new(config, sim.robot().leg_geometry())?;
    let lwpr = Lwpr::new(LwprConfig::new(3, 1).norm_in(vec![0.5, 3.0, 0.15]))?;
    let mut learner =
        FootstepLearner::new(lwpr, PendulumCart::default(), LearnerConfig::default())?;
    let mut policy = ScaledPolicy::new(&mut learner, scale);
    let mut ticks = Vec::new();
    while sim.time() < seconds {
        let sensors = sim.sensors();
        // Step in place, then forward at a tenth of the leg length per step.
        let f_r = if sensors.time < seconds / 2.0 {
            0.0
        } else {
            0.1 * sim.robot().leg_length()
        };
        let tick = walker.tick(&sensors, f_r, Some(&mut policy))?;
        ticks.push((sensors, f_r, tick.targets));
        sim.step(&tick.targets)?;
        if let Some(fall) = sim.fall() {
            return Err(format!("the robot fell at {:.2} s", fall.time).into());
        }
    }
    let recording = Recording {
        robot: PathBuf::from(robot),
        ticks,
    };
    std::fs::write(&out, serde_json::to_string(&recording)?)?;
    println!(
        "{} ticks of {} written to {out}",
        recording.ticks.len(),
        recording.robot.display()
    );
    Ok(())
}
