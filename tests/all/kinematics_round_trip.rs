//! Forward/inverse leg kinematics round trips.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use steplearn::robot::Side;
use steplearn::robot::kinematics::{KinematicsError, LegAngles, LegGeometry};

fn angles() -> impl Strategy<Value = LegAngles> {
    (
        -0.5f64..0.5,
        -0.4f64..0.4,
        -1.2f64..0.5,
        0.05f64..2.0,
        -0.8f64..0.8,
        -0.4f64..0.4,
    )
        .prop_map(|(a, b, c, d, e, f)| [a, b, c, d, e, f])
        // Keep the sole within +-1.2 rad of level (the hip then stays above the ankle in the
        // foot frame, where the closed form picks the physical solution).
        .prop_filter("foot pitch", |q| (q[2] + q[3] + q[4]).abs() < 1.2)
}

fn side() -> impl Strategy<Value = Side> {
    prop::bool::ANY.prop_map(|b| if b { Side::Left } else { Side::Right })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, rng_seed: RngSeed::Fixed(2), ..ProptestConfig::default() })]

    /// Angles -> pose -> angles gives back the angles.
    #[test]
    fn angles_round_trip(q in angles(), side in side()) {
        let g = LegGeometry::default();
        let pose = g.forward(side, &q);
        let back = g.inverse(side, &pose).unwrap();
        for (a, b) in q.iter().zip(back.iter()) {
            prop_assert!((a - b).abs() < 1e-8, "{:?} vs {:?}", q, back);
        }
    }

    /// Reachable pose -> angles -> pose gives back the pose.
    #[test]
    fn pose_round_trip(
        side in side(),
        x in -0.25f64..0.25, dy in -0.1f64..0.1, z in -0.95f64..-0.75,
        roll in -0.3f64..0.3, pitch in -0.4f64..0.4, yaw in -0.4f64..0.4,
    ) {
        let g = LegGeometry::default();
        let y = side.sign() * 0.1 + dy;
        let pose = Isometry3::from_parts(
            Translation3::new(x, y, z),
            UnitQuaternion::from_euler_angles(roll, pitch, yaw),
        );
        let q = g.inverse(side, &pose).unwrap();
        let back = g.forward(side, &q);
        prop_assert!((back.translation.vector - pose.translation.vector).norm() < 1e-9);
        prop_assert!(back.rotation.angle_to(&pose.rotation) < 1e-8);
    }
}

#[test]
fn zero_angles_give_straight_vertical_leg() {
    let g = LegGeometry::default();
    for side in Side::BOTH {
        let p = g.forward(side, &[0.0; 6]);
        let expected = Vector3::new(
            g.sole_offset_x,
            side.sign() * g.hip_offset[1],
            g.hip_offset[2] - g.thigh - g.shank - g.ankle_height,
        );
        assert!((p.translation.vector - expected).norm() < 1e-12);
        assert!(p.rotation.angle() < 1e-12);
    }
}

#[test]
fn sign_conventions() {
    let g = LegGeometry::default();
    let straight = g.forward(Side::Left, &[0.0; 6]).translation.vector;
    // Positive hip pitch swings the foot backwards; positive hip roll moves it left.
    let back = g
        .forward(Side::Left, &[0.0, 0.0, 0.3, 0.0, 0.0, 0.0])
        .translation
        .vector;
    assert!(back.x < straight.x - 0.1);
    let left = g
        .forward(Side::Left, &[0.0, 0.3, 0.0, 0.0, 0.0, 0.0])
        .translation
        .vector;
    assert!(left.y > straight.y + 0.1);
    // Abstract leg space: a = -acos(1 - eta); hip = a, knee = -2a, ankle = a keeps the sole
    // level and below the hip (exactly for equal thigh and shank; here they differ by 2 mm).
    let a = -(1.0f64 - 0.1).acos();
    let bent = g.forward(Side::Right, &[0.0, 0.0, a, -2.0 * a, a, 0.0]);
    assert!(bent.rotation.angle() < 1e-12);
    let slack = (g.shank - g.thigh).abs() * a.sin().abs() + 1e-12;
    assert!((bent.translation.vector.x - g.sole_offset_x).abs() <= slack);
    // Bending the knee shortens the leg.
    assert!(bent.translation.vector.z > straight.z + 0.05);
}

#[test]
fn unreachable_and_non_finite_poses_are_errors() {
    let g = LegGeometry::default();
    let far = Isometry3::translation(0.0, 0.1, -1.2);
    assert!(matches!(
        g.inverse(Side::Left, &far),
        Err(KinematicsError::Unreachable { .. })
    ));
    let nan = Isometry3::translation(f64::NAN, 0.1, -0.9);
    assert!(matches!(
        g.inverse(Side::Left, &nan),
        Err(KinematicsError::NonFinite(_))
    ));
    let bad = LegGeometry {
        thigh: -0.1,
        ..LegGeometry::default()
    };
    assert!(bad.validate().is_err());
    assert!(LegGeometry::default().validate().is_ok());
}
