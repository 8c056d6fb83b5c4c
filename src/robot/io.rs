//! What control reads from a robot and what it writes back.
//!
//! These plain structs are the whole boundary between control and any simulator or real robot:
//! the simulator fills [`Sensors`] every control tick and applies [`JointTargets`]. Nothing in
//! `control` knows about rapier.
//!
//! Conventions (everywhere in the crate): world frame x forward, y left, z up; gravity along -z.
//! Angles follow the right-hand rule about the parent frame's axis: roll about x, pitch about y,
//! yaw about z. A positive trunk pitch is a forward lean. Units are SI (m, s, rad, N, Ns).

use serde::{Deserialize, Serialize};

/// Number of actuated joints: six per leg.
pub const NUM_JOINTS: usize = 12;
/// Number of joints in one leg.
pub const JOINTS_PER_LEG: usize = 6;

/// A leg.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Side {
    /// The left leg (positive y).
    Left,
    /// The right leg (negative y).
    Right,
}

impl Side {
    /// Both sides, left first (the order of joints and feet in every array).
    pub const BOTH: [Side; 2] = [Side::Left, Side::Right];

    /// Index of this side in per-side arrays (left 0, right 1).
    pub fn index(self) -> usize {
        match self {
            Side::Left => 0,
            Side::Right => 1,
        }
    }

    /// The other leg.
    pub fn other(self) -> Side {
        match self {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
        }
    }

    /// +1 for left, -1 for right: the sign of this side's lateral offset.
    pub fn sign(self) -> f64 {
        match self {
            Side::Left => 1.0,
            Side::Right => -1.0,
        }
    }
}

/// A joint within one leg, in chain order from the pelvis to the foot.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum LegJoint {
    /// Rotation about z at the hip.
    HipYaw,
    /// Rotation about x at the hip.
    HipRoll,
    /// Rotation about y at the hip.
    HipPitch,
    /// Rotation about y at the knee.
    Knee,
    /// Rotation about y at the ankle.
    AnklePitch,
    /// Rotation about x at the ankle.
    AnkleRoll,
}

impl LegJoint {
    /// All joints of a leg in chain order.
    pub const ALL: [LegJoint; JOINTS_PER_LEG] = [
        LegJoint::HipYaw,
        LegJoint::HipRoll,
        LegJoint::HipPitch,
        LegJoint::Knee,
        LegJoint::AnklePitch,
        LegJoint::AnkleRoll,
    ];

    /// The axis this joint turns about, in the trunk frame of the zero pose.
    pub fn axis(self) -> [f64; 3] {
        match self {
            LegJoint::HipYaw => [0.0, 0.0, 1.0],
            LegJoint::HipRoll | LegJoint::AnkleRoll => [1.0, 0.0, 0.0],
            LegJoint::HipPitch | LegJoint::Knee | LegJoint::AnklePitch => [0.0, 1.0, 0.0],
        }
    }

    /// Index of this joint of leg `side` in the 12-element joint arrays.
    pub fn index(self, side: Side) -> usize {
        side.index() * JOINTS_PER_LEG + self as usize
    }
}

/// Inertial measurement of the trunk.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Imu {
    /// Trunk orientation in the world frame as a unit quaternion `[w, x, y, z]`.
    pub orientation: [f64; 4],
    /// Trunk angular velocity in the trunk frame (rad/s), as a gyroscope reads it.
    pub gyro: [f64; 3],
}

impl Imu {
    /// Roll, pitch and yaw (rad) of the trunk: intrinsic z-y-x Euler angles of `orientation`
    /// (nalgebra's [`nalgebra::UnitQuaternion::euler_angles`], as the estimator uses).
    pub fn roll_pitch_yaw(&self) -> [f64; 3] {
        let [w, x, y, z] = self.orientation;
        let q = nalgebra::UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(w, x, y, z));
        let (roll, pitch, yaw) = q.euler_angles();
        [roll, pitch, yaw]
    }
}

/// Contact sensing of one foot sole.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct FootContact {
    /// Whether the sole touches the ground.
    pub in_contact: bool,
    /// Total normal force on the sole (N).
    pub normal_force: f64,
    /// Centre of pressure in the foot frame (x forward, y left, m); zero without contact.
    pub cop: [f64; 2],
}

/// Everything control may read in one tick.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Sensors {
    /// Time since the start of the run (s).
    pub time: f64,
    /// Joint angles (rad), indexed by [`LegJoint::index`].
    pub joint_pos: [f64; NUM_JOINTS],
    /// Joint rates (rad/s), same order.
    pub joint_vel: [f64; NUM_JOINTS],
    /// The trunk IMU.
    pub imu: Imu,
    /// Foot contacts, left then right.
    pub feet: [FootContact; 2],
}

impl Default for Sensors {
    fn default() -> Self {
        Sensors {
            time: 0.0,
            joint_pos: [0.0; NUM_JOINTS],
            joint_vel: [0.0; NUM_JOINTS],
            imu: Imu {
                orientation: [1.0, 0.0, 0.0, 0.0],
                gyro: [0.0; 3],
            },
            feet: [FootContact::default(); 2],
        }
    }
}

/// Position targets for the joint servos (rad), indexed by [`LegJoint::index`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct JointTargets {
    /// Target angle of every joint.
    pub pos: [f64; NUM_JOINTS],
}

impl Default for JointTargets {
    fn default() -> Self {
        JointTargets {
            pos: [0.0; NUM_JOINTS],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joint_indices_cover_all_twelve_once() {
        let mut seen = [false; NUM_JOINTS];
        for side in Side::BOTH {
            for j in LegJoint::ALL {
                assert!(!seen[j.index(side)]);
                seen[j.index(side)] = true;
            }
        }
        assert!(seen.iter().all(|&s| s));
    }

    #[test]
    fn pitch_of_forward_lean_is_positive() {
        // Rotation of 0.2 rad about +y.
        let a: f64 = 0.2;
        let imu = Imu {
            orientation: [(a / 2.0).cos(), 0.0, (a / 2.0).sin(), 0.0],
            gyro: [0.0; 3],
        };
        let [r, p, y] = imu.roll_pitch_yaw();
        assert!(r.abs() < 1e-12 && y.abs() < 1e-12);
        assert!((p - a).abs() < 1e-12);
        // All three at once round-trip through a quaternion built from them.
        let q = nalgebra::UnitQuaternion::from_euler_angles(0.1, -0.2, 0.3);
        let imu = Imu {
            orientation: [q.w, q.i, q.j, q.k],
            gyro: [0.0; 3],
        };
        let [r, p, y] = imu.roll_pitch_yaw();
        assert!((r - 0.1).abs() < 1e-12 && (p + 0.2).abs() < 1e-12 && (y - 0.3).abs() < 1e-12);
    }
}
