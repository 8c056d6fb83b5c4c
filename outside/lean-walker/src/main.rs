//! Your robot outside rapier: the Capture Step walker and the paper's learner, built from a
//! URDF with the lean crate, fed one control tick of sensors at a time, answering joint
//! targets. Here the sensors are a recorded rapier trial's (`examples/record_sensors.rs`), so
//! every target must equal the recorded one, bit for bit.
//!
//! `cargo run --manifest-path outside/lean-walker/Cargo.toml -- RECORDING.json`

use std::path::{Path, PathBuf};

use steplearn::approx::{Lwpr, LwprConfig};
use steplearn::control::for_robot::ScaledPolicy;
use steplearn::control::{FootstepLearner, LearnerConfig};
use steplearn::control::{Walker, WalkerConfig, WalkerMode};
use steplearn::robot::Description;
use steplearn::robot::Scale;
use steplearn::robot::ServoReference;
use steplearn::robot::{JointTargets, STANCE_KNEE, Sensors, standing_pose};
use steplearn::rules::PendulumCart;

#[derive(serde::Deserialize)]
struct Recording {
    robot: PathBuf,
    ticks: Vec<(Sensors, f64, JointTargets)>,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .ok_or("usage: steplearn-lean-walker RECORDING.json")?;
    let recording: Recording = serde_json::from_str(&std::fs::read_to_string(&path)?)?;
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");

    // The robot and the paper's, both as files; the walker scaled from the paper's settings.
    let reference = ServoReference::default();
    let robot = Description::from_urdf(&root.join(&recording.robot), &reference)?;
    let paper = Description::from_urdf(&root.join("robots/steplearn_humanoid.urdf"), &reference)?;
    let scale = Scale::between(&robot, &paper, &standing_pose(STANCE_KNEE));
    let config = WalkerConfig::new(WalkerMode::CaptureStep).for_robot(&scale);
    let mut walker = Walker::new(config, robot.leg_geometry())?;
    let lwpr = Lwpr::new(LwprConfig::new(3, 1).norm_in(vec![0.5, 3.0, 0.15]))?;
    let mut learner =
        FootstepLearner::new(lwpr, PendulumCart::default(), LearnerConfig::default())?;
    let mut policy = ScaledPolicy::new(&mut learner, scale);

    // The loop a robot runs: sensors in, joint targets out, every control tick.
    for (k, (sensors, f_r, recorded)) in recording.ticks.iter().enumerate() {
        let tick = walker.tick(sensors, *f_r, Some(&mut policy))?;
        let bits = |t: &JointTargets| t.pos.map(f64::to_bits);
        if bits(&tick.targets) != bits(recorded) {
            return Err(format!(
                "tick {k}: {:?} != recorded {:?}",
                tick.targets.pos, recorded.pos
            )
            .into());
        }
        // In the robot's own joint order and signs, for its servos:
        let _servo_angles = robot.to_robot_angles(&tick.targets.pos);
    }
    println!(
        "{} ticks of {}: every joint target equals the rapier trial's, bit for bit",
        recording.ticks.len(),
        robot.name
    );
    Ok(())
}
