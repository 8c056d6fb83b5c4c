//! The simulated humanoid in motion: standing, exact pushes, falls and reset, determinism,
//! rejected inputs.

use steplearn::control::motion::{MotionConfig, MotionGenerator};
use steplearn::robot::{JointTargets, Sensors};
use steplearn::sim::{FallTrigger, Humanoid, SimConfig, SimError};

fn stand(sim: &mut Humanoid, seconds: f64) -> Option<steplearn::sim::Fall> {
    let generator = MotionGenerator::new(
        MotionConfig::default().check().unwrap(),
        &sim.body().leg_geometry(),
    );
    let targets = generator.halt_targets();
    while sim.time() < seconds {
        sim.step(&targets).unwrap();
        if let Some(f) = sim.fall() {
            return Some(f);
        }
    }
    None
}

#[test]
fn stands_and_senses_its_weight() {
    let mut sim = Humanoid::new(SimConfig::default()).unwrap();
    assert!(stand(&mut sim, 2.0).is_none());
    let s = sim.sensors();
    let weight = 13.5 * 9.81;
    let total = s.feet[0].normal_force + s.feet[1].normal_force;
    assert!(
        (total - weight).abs() < 0.1 * weight,
        "feet carry {total} N"
    );
    for foot in s.feet {
        assert!(foot.in_contact);
        // Centre of pressure inside the sole.
        assert!(
            foot.cop[0].abs() < 0.2 && foot.cop[1].abs() < 0.06,
            "{:?}",
            foot.cop
        );
    }
    let [roll, pitch, _] = s.imu.roll_pitch_yaw();
    assert!(
        roll.abs() < 0.05 && pitch.abs() < 0.1,
        "trunk {roll} {pitch}"
    );
    assert!(
        s.joint_vel.iter().all(|v| v.abs() < 0.05),
        "{:?}",
        s.joint_vel
    );
}

#[test]
fn a_push_changes_momentum_by_exactly_its_impulse() {
    let config = SimConfig {
        gravity: 0.0,
        initial_clearance: 0.5,
        ..SimConfig::default()
    };
    let mut sim = Humanoid::new(config).unwrap();
    let targets = JointTargets {
        pos: sim.config().initial_joints,
    };
    sim.step(&targets).unwrap();
    let before = sim.ground_truth().momentum;
    let impulse = [2.0, -1.0, 0.5];
    sim.push(impulse).unwrap();
    for _ in 0..4 {
        sim.step(&targets).unwrap();
    }
    assert!(!sim.pushing());
    let after = sim.ground_truth().momentum;
    for k in 0..3 {
        let change = after[k] - before[k];
        assert!(
            (change - impulse[k]).abs() < 1e-3,
            "axis {k}: momentum change {change} vs impulse {}",
            impulse[k]
        );
    }
}

#[test]
fn survives_a_2ns_push_standing() {
    let mut sim = Humanoid::new(SimConfig::default()).unwrap();
    assert!(stand(&mut sim, 0.5).is_none());
    sim.push([2.0, 0.0, 0.0]).unwrap();
    assert_eq!(stand(&mut sim, 3.0), None);
}

#[test]
fn a_hard_push_is_a_fall_and_reset_stands_again() {
    let fresh = Humanoid::new(SimConfig::default()).unwrap();
    let mut sim = Humanoid::new(SimConfig::default()).unwrap();
    assert!(stand(&mut sim, 0.3).is_none());
    sim.push([25.0, 0.0, 0.0]).unwrap();
    let fall = stand(&mut sim, 4.0).expect("a 25 Ns push must topple it");
    assert!(fall.time > 0.3 && fall.time < 4.0);
    match fall.trigger {
        FallTrigger::Tilt { angle } => assert!(angle > sim.config().fall_tilt),
        FallTrigger::Contact { .. } => {}
    }
    sim.reset();
    assert_eq!(sim.time(), 0.0);
    assert!(sim.fall().is_none());
    assert_eq!(sim.ground_truth(), fresh.ground_truth());
    assert_eq!(sim.sensors(), fresh.sensors());
    assert!(stand(&mut sim, 1.0).is_none());
}

fn stepping_run(seconds: f64) -> Vec<Sensors> {
    let mut sim = Humanoid::new(SimConfig::default()).unwrap();
    let mut generator = MotionGenerator::new(
        MotionConfig::default().check().unwrap(),
        &sim.body().leg_geometry(),
    );
    let dt = sim.config().tick();
    let mut out = Vec::new();
    while sim.time() < seconds {
        let cmd = generator.open_loop(0.0);
        sim.step(&generator.update(&cmd, dt)).unwrap();
        if sim.time() > 1.0 && out.is_empty() {
            sim.push([1.0, 0.0, 0.0]).unwrap();
        }
        out.push(sim.sensors());
    }
    out
}

#[test]
fn same_inputs_give_bit_identical_runs() {
    let a = stepping_run(1.5);
    let b = stepping_run(1.5);
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(x, y);
    }
    // The run actually moved.
    assert!(a.iter().any(|s| s.joint_vel.iter().any(|v| v.abs() > 0.1)));
}

#[test]
fn non_finite_targets_are_rejected_and_change_nothing() {
    let mut sim = Humanoid::new(SimConfig::default()).unwrap();
    let before = sim.ground_truth();
    let mut t = JointTargets::default();
    t.pos[4] = f64::NAN;
    assert!(matches!(
        sim.step(&t),
        Err(SimError::BadTarget { index: 4, .. })
    ));
    assert_eq!(sim.ground_truth(), before);
    assert_eq!(sim.time(), 0.0);
}

/// Walks open-loop with `motion` at a constant commanded step (reached over a 4 s ramp) for
/// `seconds`; returns the fall time, if any, and the CoM's sagittal travel.
fn walk_open_loop(motion: MotionConfig, step_x: f64, seconds: f64) -> (Option<f64>, f64) {
    let mut sim = Humanoid::new(SimConfig::default()).unwrap();
    let mut generator = MotionGenerator::new(motion.check().unwrap(), &sim.body().leg_geometry());
    let dt = sim.config().tick();
    let start = sim.ground_truth().com[0];
    while sim.time() < seconds {
        let cmd = generator.open_loop(step_x * (sim.time() / 4.0).min(1.0));
        sim.step(&generator.update(&cmd, dt)).unwrap();
        if let Some(f) = sim.fall() {
            return (Some(f.time), sim.ground_truth().com[0] - start);
        }
    }
    (None, sim.ground_truth().com[0] - start)
}

#[test]
fn open_loop_gait_walks_the_whole_step_range() {
    for step_x in [-0.1, 0.2] {
        // The open-loop gait walks 30 s at both ends of the range and travels close to the
        // commanded distance.
        let (fall, travel) = walk_open_loop(MotionConfig::open_loop_gait(), step_x, 30.0);
        assert_eq!(fall, None, "open-loop gait at {step_x} m fell");
        let commanded = step_x * (30.0 - 2.0) / 0.4;
        assert!(
            travel * commanded.signum() > 0.8 * commanded.abs(),
            "travel {travel} m for {commanded} m commanded"
        );
    }
}

#[test]
fn a_non_finite_push_is_rejected_and_changes_nothing() {
    let mut sim = Humanoid::new(SimConfig::default()).unwrap();
    assert!(matches!(
        sim.push([f64::NAN, 0.0, 0.0]),
        Err(SimError::BadImpulse { .. })
    ));
    assert!(!sim.pushing());
    sim.push([1.0, 0.0, 0.0]).unwrap();
    assert!(matches!(
        sim.push([0.0, f64::INFINITY, 0.0]),
        Err(SimError::BadImpulse { .. })
    ));
    // The earlier push is still under way.
    assert!(sim.pushing());
}

#[test]
fn an_exploding_simulation_is_an_error_not_a_nan_state() {
    let mut sim = Humanoid::new(SimConfig::default()).unwrap();
    let targets = MotionGenerator::new(
        MotionConfig::default().check().unwrap(),
        &sim.body().leg_geometry(),
    )
    .halt_targets();
    // 1e7 N s on 13.5 kg: far beyond any velocity the check accepts.
    sim.push([1e7, 0.0, 0.0]).unwrap();
    let mut error = None;
    for _ in 0..50 {
        match sim.step(&targets) {
            Ok(()) => assert!(sim.ground_truth().com.iter().all(|v| v.is_finite())),
            Err(e) => {
                error = Some(e);
                break;
            }
        }
    }
    match error {
        Some(SimError::BlowUp { time, what }) => {
            assert!(time > 0.0);
            assert!(!what.is_empty());
        }
        other => panic!("expected BlowUp, got {other:?}"),
    }
}
