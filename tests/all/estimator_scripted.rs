//! The state estimator on synthetic sensors built from the leg kinematics: a scripted step
//! (known trunk motion, known foot placements, a load transfer) with a yawed heading.

use nalgebra::{Isometry3, Rotation3, Translation3, UnitQuaternion, Vector3};
use steplearn::control::estimator::{EstimatorConfig, EstimatorError, StateEstimator};
use steplearn::robot::kinematics::LegGeometry;
use steplearn::robot::{FootContact, Imu, LegJoint, Sensors, Side};

const DT: f64 = 0.002;
const WEIGHT: f64 = 13.5 * 9.81;
const YAW: f64 = 0.2;
/// The right foot lands here (heading frame, left foot at the origin).
const RIGHT_LANDING: [f64; 2] = [0.30, -0.20];
const LAND_TIME: f64 = 0.9;

/// Ground truth of the scripted motion at time t.
struct Truth {
    torso: Isometry3<f64>,
    /// Body angular velocity of the trunk (gyro).
    gyro: [f64; 3],
    pitch: f64,
    pitch_rate: f64,
    soles: [Isometry3<f64>; 2],
    forces: [f64; 2],
}

fn heading_to_world(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Rotation3::from_euler_angles(0.0, 0.0, YAW) * Vector3::new(x, y, z)
}

fn truth(t: f64) -> Truth {
    let w = std::f64::consts::PI / 0.55;
    let pos = heading_to_world(-0.1 + 0.15 * t, 0.05 * (w * t).sin(), 0.90);
    let roll = 0.03 * (1.3 * t).sin();
    let pitch = 0.08 + 0.05 * (2.0 * t).sin();
    let pitch_rate = 0.1 * (2.0 * t).cos();
    let rot = UnitQuaternion::from_euler_angles(roll, pitch, YAW);
    // Body rates of Rz(yaw) Ry(pitch) Rx(roll) with constant yaw.
    let roll_rate = 0.039 * (1.3 * t).cos();
    let gyro = [roll_rate, pitch_rate * roll.cos(), -pitch_rate * roll.sin()];
    let flat = UnitQuaternion::from_euler_angles(0.0, 0.0, YAW);
    let left = Isometry3::from_parts(Translation3::from(heading_to_world(0.0, 0.1, 0.0)), flat);
    // Right foot: lifts at 0.1 s from (-0.15, -0.1), lands at LAND_TIME on RIGHT_LANDING.
    let s = ((t - 0.1) / (LAND_TIME - 0.1)).clamp(0.0, 1.0);
    let rx = -0.15 + s * (RIGHT_LANDING[0] + 0.15);
    let ry = -0.1 + s * (RIGHT_LANDING[1] + 0.1);
    let rz = 0.05 * (std::f64::consts::PI * s).sin();
    let right = Isometry3::from_parts(Translation3::from(heading_to_world(rx, ry, rz)), flat);
    // Loads: double support until 0.1 s, left alone, then a 0.1 s transfer to the right.
    let right_share = if t < 0.1 {
        0.3
    } else if t < LAND_TIME {
        0.0
    } else {
        ((t - LAND_TIME) / 0.1).min(1.0)
    };
    Truth {
        torso: Isometry3::from_parts(Translation3::from(pos), rot),
        gyro,
        pitch,
        pitch_rate,
        soles: [left, right],
        forces: [(1.0 - right_share) * WEIGHT, right_share * WEIGHT],
    }
}

fn sensors(t: f64, g: &LegGeometry) -> Sensors {
    let tr = truth(t);
    let mut s = Sensors {
        time: t,
        ..Sensors::default()
    };
    for side in Side::BOTH {
        let in_torso = tr.torso.inverse() * tr.soles[side.index()];
        let q = g.inverse(side, &in_torso).expect("scripted pose reachable");
        for (j, a) in LegJoint::ALL.iter().zip(q) {
            s.joint_pos[j.index(side)] = a;
        }
        let f = tr.forces[side.index()];
        s.feet[side.index()] = FootContact {
            in_contact: f > 0.0,
            normal_force: f,
            cop: [0.0, 0.0],
        };
    }
    let q = tr.torso.rotation.quaternion();
    s.imu = Imu {
        orientation: [q.w, q.i, q.j, q.k],
        gyro: tr.gyro,
    };
    s
}

/// True CoM relative to the support sole, in the heading frame, and its velocity.
fn true_com(t: f64, support: Side, com_offset: [f64; 3]) -> (Vector3<f64>, Vector3<f64>) {
    let at = |t: f64| {
        let tr = truth(t);
        let com = tr.torso * nalgebra::Point3::from(Vector3::from(com_offset));
        let rel = com.coords - tr.soles[support.index()].translation.vector;
        Rotation3::from_euler_angles(0.0, 0.0, -YAW) * rel
    };
    let h = 1e-6;
    (at(t), (at(t + h) - at(t - h)) / (2.0 * h))
}

/// Runs the script through an estimator; returns (max position error, max velocity error
/// after the first 0.1 s, touch-downs).
fn run_script(cfg: EstimatorConfig) -> (f64, f64, Vec<steplearn::control::estimator::TouchDown>) {
    let g = LegGeometry::default();
    let mut est = StateEstimator::new(g, cfg).unwrap();
    let (mut max_p, mut max_v) = (0.0f64, 0.0f64);
    let mut tds = Vec::new();
    let theta_ref = 0.05;
    for k in 0..1000 {
        let t = k as f64 * DT;
        let e = est.update(&sensors(t, &g), theta_ref).unwrap();
        let tr = truth(t);
        assert!((e.pitch - tr.pitch).abs() < 1e-9);
        assert!((e.theta_e - (tr.pitch - theta_ref)).abs() < 1e-9);
        assert!((e.theta_e_rate - tr.pitch_rate).abs() < 1e-9);
        // Support: left until the transfer passes 60 %, right after.
        let expected = if t < LAND_TIME + 0.06 + 0.5 * DT {
            Side::Left
        } else {
            Side::Right
        };
        assert_eq!(e.support, expected, "t = {t}");
        let (p, v) = true_com(t, e.support, cfg.com_offset);
        max_p = max_p.max((e.com[0].pos - p.x).abs().max((e.com[1].pos - p.y).abs()));
        max_p = max_p.max((e.com_height - p.z).abs());
        if t > 0.1 {
            max_v = max_v.max((e.com[0].vel - v.x).abs().max((e.com[1].vel - v.y).abs()));
        }
        if let Some(td) = e.touch_down {
            tds.push(td);
        }
    }
    (max_p, max_v, tds)
}

#[test]
fn scripted_step_is_estimated() {
    let (max_p, max_v, tds) = run_script(EstimatorConfig::default());
    println!(
        "default filter (tau 0.02 s): max CoM position error {max_p:.2e} m, max velocity error {max_v:.4} m/s"
    );
    assert!(max_p < 1e-9, "{max_p}");
    // Lag of a first-order filter: about tau times the peak acceleration (~1.7 m/s^2 here).
    assert!(max_v < 0.05, "{max_v}");
    assert_eq!(tds.len(), 1, "{tds:?}");
    let td = tds[0];
    assert_eq!(td.support, Side::Right);
    assert!((td.time - (LAND_TIME + 0.06)).abs() < 1.5 * DT, "{td:?}");
    assert!((td.step[0] - RIGHT_LANDING[0]).abs() < 1e-9, "F_hat {td:?}");
    assert!(
        (td.step[1] - (RIGHT_LANDING[1] - 0.1)).abs() < 1e-9,
        "{td:?}"
    );
}

#[test]
fn unfiltered_velocity_is_the_exact_difference() {
    let cfg = EstimatorConfig {
        velocity_time_constant: 0.0,
        ..EstimatorConfig::default()
    };
    let (_, max_v, _) = run_script(cfg);
    println!("unfiltered: max velocity error {max_v:.5} m/s");
    // A backward difference lags half a tick: dt/2 times the peak acceleration.
    assert!(max_v < 0.005, "{max_v}");
}

fn loaded(t: f64, forces: [f64; 2]) -> Sensors {
    let mut s = sensors(0.05, &LegGeometry::default());
    s.time = t;
    for (f, c) in forces.iter().zip(s.feet.iter_mut()) {
        c.normal_force = *f;
        c.in_contact = *f > 0.0;
    }
    s
}

#[test]
fn support_has_hysteresis_and_dwell_time() {
    let mut est = StateEstimator::new(LegGeometry::default(), EstimatorConfig::default()).unwrap();
    assert_eq!(
        est.update(&loaded(0.0, [80.0, 50.0]), 0.0).unwrap().support,
        Side::Left
    );
    // Loads chattering around 50/50 (within +-8 %) never exchange the support.
    for k in 1..200 {
        let share = 0.5 + 0.08 * (k as f64 * 1.7).sin();
        let e = est
            .update(
                &loaded(k as f64 * DT, [(1.0 - share) * WEIGHT, share * WEIGHT]),
                0.0,
            )
            .unwrap();
        assert_eq!(e.support, Side::Left);
        assert!(e.touch_down.is_none());
    }
    // A clear transfer does.
    let t0 = 200.0 * DT;
    let e = est
        .update(&loaded(t0, [0.2 * WEIGHT, 0.8 * WEIGHT]), 0.0)
        .unwrap();
    assert_eq!(e.support, Side::Right);
    assert!(e.touch_down.is_some());
    // Switching straight back is refused within the dwell time, allowed after it.
    let e = est.update(&loaded(t0 + 0.05, [WEIGHT, 0.0]), 0.0).unwrap();
    assert_eq!(e.support, Side::Right);
    let e = est.update(&loaded(t0 + 0.11, [WEIGHT, 0.0]), 0.0).unwrap();
    assert_eq!(e.support, Side::Left);
    // Both feet in the air: the support is kept.
    let e = est.update(&loaded(t0 + 0.3, [0.0, 1.0]), 0.0).unwrap();
    assert_eq!(e.support, Side::Left);
}

#[test]
fn bad_inputs_and_configs_are_rejected_without_state_change() {
    let g = LegGeometry::default();
    let mut est = StateEstimator::new(g, EstimatorConfig::default()).unwrap();
    est.update(&sensors(0.0, &g), 0.0).unwrap();
    let before = est.clone();
    let mut s = sensors(0.002, &g);
    s.joint_pos[3] = f64::NAN;
    assert!(matches!(
        est.update(&s, 0.0),
        Err(EstimatorError::InvalidInput(_))
    ));
    let mut s = sensors(0.002, &g);
    s.imu.orientation = [0.0; 4];
    assert!(est.update(&s, 0.0).is_err());
    assert!(
        est.update(&sensors(0.0, &g), 0.0).is_err(),
        "time must advance"
    );
    assert!(est.update(&sensors(0.002, &g), f64::INFINITY).is_err());
    assert_eq!(est, before);

    for cfg in [
        EstimatorConfig {
            switch_fraction: 0.5,
            ..EstimatorConfig::default()
        },
        EstimatorConfig {
            min_support_time: -1.0,
            ..EstimatorConfig::default()
        },
        EstimatorConfig {
            com_offset: [0.0, f64::NAN, 0.0],
            ..EstimatorConfig::default()
        },
    ] {
        assert!(StateEstimator::new(g, cfg).is_err());
    }
    let bad_geometry = LegGeometry { shank: 0.0, ..g };
    assert!(matches!(
        StateEstimator::new(bad_geometry, EstimatorConfig::default()),
        Err(EstimatorError::Geometry(_))
    ));
}
