//! The simulated body: sizes and masses, joint sign conventions, config validation.

use steplearn::control::motion::{LegPose, LegSpace};
use steplearn::robot::{LegJoint, NUM_JOINTS, Side};
use steplearn::sim::{BodyConfig, Humanoid, SimConfig, SimError};

fn floating(joints: [f64; NUM_JOINTS]) -> Humanoid {
    let config = SimConfig {
        gravity: 0.0,
        initial_joints: joints,
        initial_clearance: 0.5,
        ..SimConfig::default()
    };
    Humanoid::new(config).unwrap()
}

#[test]
fn mass_and_height_match_the_paper_robot() {
    let body = BodyConfig::default();
    assert!(
        (body.total_mass() - 13.5).abs() < 1e-9,
        "{}",
        body.total_mass()
    );
    assert!((body.height() - 2.0).abs() < 1e-9, "{}", body.height());
    let sim = Humanoid::new(SimConfig::default()).unwrap();
    let truth = sim.ground_truth();
    assert!((truth.mass - 13.5).abs() < 1e-9, "sim mass {}", truth.mass);
    // Human-like mass distribution: CoM a little above half the height.
    assert!(
        truth.com[2] > 1.0 && truth.com[2] < 1.25,
        "CoM {:?}",
        truth.com
    );
    // Soles on the ground.
    for sole in truth.soles {
        assert!(sole.position[2].abs() < 1e-9, "{:?}", sole.position);
    }
    let g = body.leg_geometry();
    assert_eq!(g.thigh + g.shank + g.ankle_height, 1.06);
}

#[test]
fn joint_signs_follow_the_right_hand_rule() {
    let hip_to_ankle = |q: [f64; NUM_JOINTS], side: Side| {
        let t = floating(q).ground_truth();
        let leg = t.skeleton.legs[side.index()];
        [
            leg[2][0] - leg[0][0],
            leg[2][1] - leg[0][1],
            leg[2][2] - leg[0][2],
        ]
    };
    let mut q = [0.0; NUM_JOINTS];
    q[LegJoint::HipPitch.index(Side::Left)] = 0.3;
    let d = hip_to_ankle(q, Side::Left);
    assert!(
        d[0] < -0.2,
        "positive hip pitch swings the foot back: {d:?}"
    );
    let mut q = [0.0; NUM_JOINTS];
    q[LegJoint::HipRoll.index(Side::Right)] = 0.2;
    let d = hip_to_ankle(q, Side::Right);
    assert!(d[1] > 0.15, "positive hip roll swings the foot left: {d:?}");
    // Full leg-space check: the ankle lands where the leg angle says.
    let body = BodyConfig::default();
    let space = LegSpace::new(&body.leg_geometry());
    let pose = LegPose {
        extension: 0.1,
        angle: [0.1, -0.2, 0.0],
        foot: [0.0, 0.0],
    };
    let joints = space.to_joints(&pose);
    let mut q = [0.0; NUM_JOINTS];
    for j in LegJoint::ALL {
        q[j.index(Side::Left)] = joints[j as usize];
    }
    let sim = floating(q);
    let d = hip_to_ankle(q, Side::Left);
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    assert!((len - 0.9 * space.leg_length()).abs() < 1e-9, "{len}");
    // Leg pitch -0.2 with roll 0.1 puts the ankle forward and to the left.
    assert!(d[0] > 0.15 && d[1] > 0.05, "{d:?}");
    // Sole level: its orientation is the torso's.
    let sole = sim.ground_truth().soles[0].orientation;
    assert!((sole[0].abs() - 1.0).abs() < 1e-9, "{sole:?}");
}

#[test]
fn bad_configs_are_rejected() {
    let bad = |f: &dyn Fn(&mut SimConfig)| {
        let mut c = SimConfig::default();
        f(&mut c);
        matches!(Humanoid::new(c), Err(SimError::InvalidConfig { .. }))
    };
    assert!(bad(&|c| c.body.thigh.mass = 0.0));
    assert!(bad(&|c| c.body.torso.mass = -1.0));
    assert!(bad(&|c| c.body.shank.length = 0.0));
    assert!(bad(&|c| c.body.foot.length = -0.1));
    assert!(bad(&|c| c.dt = 0.0));
    assert!(bad(&|c| c.dt = 0.02));
    assert!(bad(&|c| c.dt = f64::NAN));
    assert!(bad(&|c| c.body.joints[2].stiffness = f64::NAN));
    assert!(bad(&|c| c.body.joints[3].damping = f64::NAN));
    assert!(bad(&|c| c.body.joints[0].max_torque = 0.0));
    assert!(bad(&|c| c.body.joints[3].limits = [0.5, -0.5]));
    assert!(bad(&|c| c.steps_per_tick = 0));
    assert!(!bad(&|_| ()));
}

#[test]
fn body_loads_from_toml_and_json() {
    let body = BodyConfig::default();
    let text = toml::to_string(&body).unwrap();
    assert_eq!(BodyConfig::from_toml(&text).unwrap(), body);
    let json = serde_json::to_string(&body).unwrap();
    assert_eq!(BodyConfig::from_json(&json).unwrap(), body);
    assert!(matches!(
        BodyConfig::from_toml("torso = 3"),
        Err(SimError::Parse(_))
    ));
}
