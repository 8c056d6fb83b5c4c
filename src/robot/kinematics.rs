//! Leg geometry shared by the simulator (which builds the body to match it) and by control
//! (state estimation and the step motion generator compute with it).
//!
//! The kinematic chain of one leg, from the torso frame (the rigid trunk and pelvis, which
//! carries the IMU): hip centre at `hip_offset` (left leg; the right leg mirrors y); hip yaw (z),
//! hip roll (x) and hip pitch (y) axes all through the hip centre; the thigh of length `thigh`
//! down to the knee pitch axis (y); the shank of length `shank` down to the ankle centre where the
//! ankle pitch (y) and ankle roll (x) axes cross; the sole `ankle_height` below the ankle centre.
//! With every joint at zero the leg is straight and vertical and the sole is horizontal.
//!
//! Joint angles follow the right-hand rule about the torso-aligned axes for both legs (no
//! mirroring of signs): a positive hip pitch swings the leg backwards, a positive knee bends
//! it (the shank rotates backwards), a positive hip roll moves the foot to the left. The foot
//! orientation is `Rz(hip yaw) Rx(hip roll) Ry(hip pitch + knee + ankle pitch) Rx(ankle roll)`.
//!
//! [`LegGeometry::forward`] maps the six angles of a leg to the pose of the sole centre in the
//! torso frame; [`LegGeometry::inverse`] maps a sole pose back to the angles (closed form, the
//! solution with a non-negative knee and `|hip roll| < pi/2`).

use nalgebra::{Isometry3, Rotation3, Translation3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::{JOINTS_PER_LEG, LegJoint, NUM_JOINTS, Side};

/// Dimensions of one leg and foot (m). The right leg mirrors the left in y.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LegGeometry {
    /// Left hip centre in the torso frame (x forward, y left, z up).
    pub hip_offset: [f64; 3],
    /// Hip centre to knee axis.
    pub thigh: f64,
    /// Knee axis to ankle centre.
    pub shank: f64,
    /// Ankle centre above the sole.
    pub ankle_height: f64,
    /// Sole length (x).
    pub foot_length: f64,
    /// Sole width (y).
    pub foot_width: f64,
    /// Sole centre forward of the point below the ankle centre.
    pub sole_offset_x: f64,
    /// Sole centre to the left of the point below the ankle centre (left leg; mirrored).
    #[serde(default)]
    pub sole_offset_y: f64,
    /// Sagittal angle of the hip-to-knee line from straight down (rad; positive: the knee
    /// lies forward of the hip in the zero pose).
    #[serde(default)]
    pub thigh_angle: f64,
    /// Sagittal angle of the knee-to-ankle line from straight down (rad).
    #[serde(default)]
    pub shank_angle: f64,
    /// Hip centre minus the point where the hip yaw axis passes, in x and y (left leg;
    /// mirrored): zero when the yaw axis runs through the hip centre.
    #[serde(default)]
    pub yaw_offset: [f64; 2],
}

/// What can go wrong with leg kinematics.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum KinematicsError {
    /// A geometry value is not a finite number in its range.
    #[error("invalid leg geometry: {0}")]
    InvalidGeometry(String),
    /// A pose or angle was NaN or infinite.
    #[error("non-finite kinematic input: {0}")]
    NonFinite(String),
    /// The requested sole pose is out of the leg's reach.
    #[error("foot pose out of reach: hip-to-ankle distance {distance} m, reach [{min}, {max}] m")]
    Unreachable {
        /// The required hip-to-ankle distance.
        distance: f64,
        /// Shortest reachable distance `|thigh - shank|`.
        min: f64,
        /// Longest reachable distance `thigh + shank`.
        max: f64,
    },
}

impl Default for LegGeometry {
    /// The 2.0 m humanoid after Winter's segment-length fractions: thigh 0.245 H, shank
    /// 0.246 H, ankle height 0.039 H, foot 0.152 H x 0.055 H (rounded to 0.30 x 0.11 m), sole
    /// centre 0.05 m ahead of the ankle; the torso frame has its origin midway between the hip
    /// centres, which are 0.10 m to each side.
    fn default() -> Self {
        LegGeometry {
            hip_offset: [0.0, 0.10, 0.0],
            thigh: 0.49,
            shank: 0.492,
            ankle_height: 0.078,
            foot_length: 0.30,
            foot_width: 0.11,
            sole_offset_x: 0.05,
            sole_offset_y: 0.0,
            thigh_angle: 0.0,
            shank_angle: 0.0,
            yaw_offset: [0.0, 0.0],
        }
    }
}

/// The six joint angles of one leg in chain order ([`LegJoint::ALL`]).
pub type LegAngles = [f64; JOINTS_PER_LEG];

impl LegGeometry {
    /// Checks that lengths are positive and every value finite.
    pub fn validate(&self) -> Result<(), KinematicsError> {
        let all = [
            self.hip_offset[0],
            self.hip_offset[1],
            self.hip_offset[2],
            self.sole_offset_x,
            self.sole_offset_y,
            self.thigh_angle,
            self.shank_angle,
            self.yaw_offset[0],
            self.yaw_offset[1],
        ];
        if all.iter().any(|v| !v.is_finite()) {
            return Err(KinematicsError::InvalidGeometry(format!(
                "offsets must be finite: {self:?}"
            )));
        }
        for (name, v) in [
            ("thigh", self.thigh),
            ("shank", self.shank),
            ("ankle_height", self.ankle_height),
            ("foot_length", self.foot_length),
            ("foot_width", self.foot_width),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(KinematicsError::InvalidGeometry(format!(
                    "{name} must be positive and finite, got {v}"
                )));
            }
        }
        Ok(())
    }

    /// Hip centre of leg `side` in the torso frame.
    pub fn hip_centre(&self, side: Side) -> Vector3<f64> {
        let [x, y, z] = self.hip_offset;
        Vector3::new(x, side.sign() * y, z)
    }

    /// The angles of leg `side` taken from a 12-joint array (e.g. `Sensors::joint_pos`).
    pub fn leg_angles(joints: &[f64; NUM_JOINTS], side: Side) -> LegAngles {
        LegJoint::ALL.map(|j| joints[j.index(side)])
    }

    /// Forward kinematics: the pose of the sole centre of leg `side` in the torso frame.
    pub fn forward(&self, side: Side, q: &LegAngles) -> Isometry3<f64> {
        let hip = self.hip_at_yaw(side, q[0]);
        self.forward_from(hip, side, &self.straight_angles(q))
    }

    /// Whether the leg is straight in the zero pose and its yaw axis runs through the hip.
    fn is_plain(&self) -> bool {
        self.thigh_angle == 0.0 && self.shank_angle == 0.0 && self.yaw_offset == [0.0, 0.0]
    }

    /// The angles of the equivalent straight leg (thigh and shank along -z in the zero pose).
    fn straight_angles(&self, q: &LegAngles) -> LegAngles {
        if self.thigh_angle == 0.0 && self.shank_angle == 0.0 {
            return *q;
        }
        let (a, b) = (self.thigh_angle, self.shank_angle);
        let mut s = *q;
        s[2] -= a;
        s[3] += a - b;
        s[4] += b;
        s
    }

    /// The robot's angles from those of the equivalent straight leg.
    fn robot_angles(&self, s: &LegAngles) -> LegAngles {
        if self.thigh_angle == 0.0 && self.shank_angle == 0.0 {
            return *s;
        }
        let (a, b) = (self.thigh_angle, self.shank_angle);
        let mut q = *s;
        q[2] += a;
        q[3] -= a - b;
        q[4] -= b;
        q
    }

    /// Hip centre of leg `side` with the hip yawed by `yaw`.
    fn hip_at_yaw(&self, side: Side, yaw: f64) -> Vector3<f64> {
        let hip = self.hip_centre(side);
        if self.yaw_offset == [0.0, 0.0] {
            return hip;
        }
        let off = Vector3::new(self.yaw_offset[0], side.sign() * self.yaw_offset[1], 0.0);
        hip - off + rot_z(yaw) * off
    }

    fn forward_from(&self, hip: Vector3<f64>, side: Side, q: &LegAngles) -> Isometry3<f64> {
        let [yaw, roll, pitch, knee, ankle_pitch, ankle_roll] = *q;
        let hip_rot = rot_z(yaw) * rot_x(roll) * rot_y(pitch);
        let knee_pos = hip + hip_rot * Vector3::new(0.0, 0.0, -self.thigh);
        let shank_rot = hip_rot * rot_y(knee);
        let ankle_pos = knee_pos + shank_rot * Vector3::new(0.0, 0.0, -self.shank);
        let foot_rot = shank_rot * rot_y(ankle_pitch) * rot_x(ankle_roll);
        let sole = ankle_pos + foot_rot * self.ankle_to_sole(side);
        Isometry3::from_parts(
            Translation3::from(sole),
            UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(foot_rot)),
        )
    }

    /// Inverse kinematics: the angles of leg `side` that put the sole centre at `foot` (torso
    /// frame). Closed form; the solution with the knee bent forward (knee >= 0).
    /// With a yaw axis off the hip centre, the hip's place follows from the yaw, which
    /// follows from the hip's place: a few fixed-point rounds settle it.
    pub fn inverse(&self, side: Side, foot: &Isometry3<f64>) -> Result<LegAngles, KinematicsError> {
        let t = foot.translation.vector;
        let qv = foot.rotation.coords;
        if t.iter().chain(qv.iter()).any(|v| !v.is_finite()) {
            return Err(KinematicsError::NonFinite(format!("foot pose {foot:?}")));
        }
        if self.is_plain() {
            return self.inverse_from(self.hip_centre(side), side, foot);
        }
        let mut q = self.inverse_from(self.hip_at_yaw(side, 0.0), side, foot)?;
        for _ in 0..4 {
            q = self.inverse_from(self.hip_at_yaw(side, q[0]), side, foot)?;
        }
        Ok(self.robot_angles(&q))
    }

    fn inverse_from(
        &self,
        hip: Vector3<f64>,
        side: Side,
        foot: &Isometry3<f64>,
    ) -> Result<LegAngles, KinematicsError> {
        let t = foot.translation.vector;
        let foot_rot = foot.rotation.to_rotation_matrix();
        let ankle = t - foot_rot * self.ankle_to_sole(side);
        // Hip seen from the ankle, in the foot frame.
        let r = foot_rot.inverse() * (hip - ankle);
        let (l1, l2) = (self.thigh, self.shank);
        let dist = r.norm();
        let (min, max) = ((l1 - l2).abs(), l1 + l2);
        let tol = 1e-9 * max;
        if dist > max + tol || dist < min - tol {
            return Err(KinematicsError::Unreachable {
                distance: dist,
                min,
                max,
            });
        }
        let cos_knee = ((dist * dist - l1 * l1 - l2 * l2) / (2.0 * l1 * l2)).clamp(-1.0, 1.0);
        let knee = cos_knee.acos();
        let ankle_roll = r.y.atan2(r.z);
        let wz = r.y.hypot(r.z);
        let ankle_pitch = (-l1 * knee.sin()).atan2(l1 * knee.cos() + l2) - r.x.atan2(wz);
        // Hip rotation Rz(yaw) Rx(roll) Ry(pitch).
        let hip = foot_rot.matrix() * rot_x(-ankle_roll) * rot_y(-(knee + ankle_pitch));
        let roll = hip[(2, 1)].clamp(-1.0, 1.0).asin();
        let yaw = (-hip[(0, 1)]).atan2(hip[(1, 1)]);
        let pitch = (-hip[(2, 0)]).atan2(hip[(2, 2)]);
        Ok([yaw, roll, pitch, knee, ankle_pitch, ankle_roll])
    }

    /// Sole centre relative to the ankle centre, in the foot frame.
    fn ankle_to_sole(&self, side: Side) -> Vector3<f64> {
        if self.sole_offset_y == 0.0 {
            return Vector3::new(self.sole_offset_x, 0.0, -self.ankle_height);
        }
        Vector3::new(
            self.sole_offset_x,
            side.sign() * self.sole_offset_y,
            -self.ankle_height,
        )
    }
}

fn rot_x(a: f64) -> nalgebra::Matrix3<f64> {
    Rotation3::from_axis_angle(&Vector3::x_axis(), a).into_inner()
}

fn rot_y(a: f64) -> nalgebra::Matrix3<f64> {
    Rotation3::from_axis_angle(&Vector3::y_axis(), a).into_inner()
}

fn rot_z(a: f64) -> nalgebra::Matrix3<f64> {
    Rotation3::from_axis_angle(&Vector3::z_axis(), a).into_inner()
}
