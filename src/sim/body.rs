//! The body of the simulated humanoid: every size, mass, joint limit and servo gain in one
//! serde struct, so another body can be loaded from a TOML or JSON file.
//!
//! The default body follows Winter's anthropometric tables (D. A. Winter, *Biomechanics and
//! Motor Control of Human Movement*, table 4.1: segment lengths as fractions of the height H,
//! masses as fractions of the body mass M, centres of mass and radii of gyration as fractions
//! of the segment length), scaled to H = 2.0 m and M = 13.5 kg:
//!
//! | segment | length | mass fraction | mass (kg) | CoM from proximal | radius of gyration |
//! |---|---|---|---|---|---|
//! | HAT (head, arms, trunk, pelvis: one rigid torso) | hip to shoulder 0.288 H = 0.576 m | 0.678 | 9.153 | 0.626 | 0.496 |
//! | thigh | 0.245 H = 0.490 m | 0.100 | 1.350 | 0.433 | 0.323 |
//! | shank | 0.246 H = 0.492 m | 0.0465 | 0.628 | 0.433 | 0.302 |
//! | foot | 0.152 H = 0.304 m long, 0.055 H = 0.110 m wide, ankle 0.039 H = 0.078 m high | 0.0145 | 0.196 | 0.5 | 0.475 |
//!
//! Hip height 0.530 H = 1.06 m; hip centres 0.1 H = 0.2 m apart. Each hip is a chain of three
//! 1-DoF revolute joints (yaw, roll, pitch) through one point and each ankle a chain of two
//! (pitch, roll), joined by small "gimbal" links whose mass (`gimbal_mass`) is taken from the
//! thigh (hip gimbals) and the foot (ankle gimbal), so the total stays 13.5 kg.

use serde::{Deserialize, Serialize};

use super::error::{SimError, in_range, non_negative, positive};
use crate::robot::kinematics::LegGeometry;
use crate::robot::{JOINTS_PER_LEG, LegJoint};

/// A limb segment hanging from its proximal joint along -z.
///
/// Every field is required when a segment is given whole; inside a [`BodyConfig`] a partial
/// `thigh` or `shank` keeps that segment's defaults for the fields it leaves out.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Segment {
    /// Proximal to distal joint (m).
    pub length: f64,
    /// Mass (kg), including the gimbal links attached to it.
    pub mass: f64,
    /// Centre of mass from the proximal joint, as a fraction of `length`.
    pub com_fraction: f64,
    /// Radius of gyration about the centre of mass, as a fraction of `length`.
    pub gyration_fraction: f64,
    /// Radius of the collision capsule (m).
    pub radius: f64,
}

/// The rigid torso: trunk, pelvis, head and arms in one body (it carries the IMU).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Torso {
    /// Mass (kg).
    pub mass: f64,
    /// Hip height to shoulder height (m).
    pub length: f64,
    /// Height of the centre of mass above the hip centres (m).
    pub com_height: f64,
    /// Principal moments of inertia about the centre of mass (kg m^2): x, y, z.
    pub inertia: [f64; 3],
    /// Trunk box depth (x) and width (y) (m).
    pub depth: f64,
    /// Trunk box width (y) (m).
    pub width: f64,
    /// Head radius (m); the head sits on top of the trunk.
    pub head_radius: f64,
    /// Arm length (m), arms hanging straight from the shoulders.
    pub arm_length: f64,
    /// Arm capsule radius (m).
    pub arm_radius: f64,
}

/// The box foot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Foot {
    /// Mass (kg), including the ankle gimbal link.
    pub mass: f64,
    /// Sole length (x) (m).
    pub length: f64,
    /// Sole width (y) (m).
    pub width: f64,
    /// Ankle centre above the sole (m).
    pub ankle_height: f64,
    /// Sole centre forward of the point below the ankle (m).
    pub sole_offset_x: f64,
}

/// Limits and position servo of one joint (inside a [`BodyConfig`], a partial entry of
/// `joints` keeps that joint's defaults for the fields it leaves out).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointSpec {
    /// Lower and upper angle limit (rad).
    pub limits: [f64; 2],
    /// Servo stiffness (N m / rad).
    pub stiffness: f64,
    /// Servo damping (N m s / rad).
    pub damping: f64,
    /// Largest servo torque (N m).
    pub max_torque: f64,
}

/// Every size, mass, joint limit and servo gain of the humanoid. See the module docs for the
/// anthropometric sources of [`BodyConfig::default`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BodyConfig {
    /// The torso (trunk, pelvis, head, arms).
    pub torso: Torso,
    /// Lateral distance of each hip centre from the torso's mid-plane (m).
    pub hip_half_width: f64,
    /// The thigh (hip centre to knee).
    #[serde(deserialize_with = "thigh_patch")]
    pub thigh: Segment,
    /// The shank (knee to ankle centre).
    #[serde(deserialize_with = "shank_patch")]
    pub shank: Segment,
    /// The foot.
    pub foot: Foot,
    /// Mass of each small gimbal link of the hip and ankle joint chains (kg).
    pub gimbal_mass: f64,
    /// Joints of one leg in [`LegJoint::ALL`] order (both legs alike; limits are for the left
    /// leg, the right leg mirrors roll and yaw limits).
    #[serde(deserialize_with = "joints_patch")]
    pub joints: [JointSpec; JOINTS_PER_LEG],
}

fn thigh_patch<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Segment, D::Error> {
    crate::config::patch(&BodyConfig::default().thigh, d)
}

fn shank_patch<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Segment, D::Error> {
    crate::config::patch(&BodyConfig::default().shank, d)
}

fn joints_patch<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> Result<[JointSpec; JOINTS_PER_LEG], D::Error> {
    crate::config::patch(&BodyConfig::default().joints, d)
}

impl Default for Torso {
    /// The torso of [`BodyConfig::default`].
    fn default() -> Self {
        BodyConfig::default().torso
    }
}

impl Default for Foot {
    /// The foot of [`BodyConfig::default`].
    fn default() -> Self {
        BodyConfig::default().foot
    }
}

const H: f64 = 2.0;
const M: f64 = 13.5;

impl Default for BodyConfig {
    fn default() -> Self {
        let hat_length = 0.288 * H;
        let hat_mass = 0.678 * M;
        let rg = 0.496 * hat_length;
        let servo = |limits: [f64; 2], stiffness: f64, damping: f64, max_torque: f64| JointSpec {
            limits,
            stiffness,
            damping,
            max_torque,
        };
        BodyConfig {
            torso: Torso {
                mass: hat_mass,
                length: hat_length,
                com_height: 0.626 * hat_length,
                inertia: [hat_mass * rg * rg, hat_mass * rg * rg, 0.15],
                depth: 0.2,
                width: 0.34,
                head_radius: 0.132,
                arm_length: 0.44 * H * 0.8,
                arm_radius: 0.04,
            },
            hip_half_width: 0.05 * H,
            thigh: Segment {
                length: 0.245 * H,
                mass: 0.100 * M,
                com_fraction: 0.433,
                gyration_fraction: 0.323,
                radius: 0.06,
            },
            shank: Segment {
                length: 0.246 * H,
                mass: 0.0465 * M,
                com_fraction: 0.433,
                gyration_fraction: 0.302,
                radius: 0.045,
            },
            foot: Foot {
                mass: 0.0145 * M,
                length: 0.152 * H,
                width: 0.055 * H,
                ankle_height: 0.039 * H,
                sole_offset_x: 0.05,
            },
            gimbal_mass: 0.02,
            joints: [
                servo([-0.6, 0.6], 300.0, 6.0, 60.0),
                servo([-0.6, 0.6], 800.0, 15.0, 150.0),
                servo([-1.8, 0.8], 800.0, 15.0, 150.0),
                servo([0.0, 2.4], 800.0, 15.0, 150.0),
                servo([-0.9, 0.9], 500.0, 8.0, 80.0),
                servo([-0.6, 0.6], 500.0, 8.0, 80.0),
            ],
        }
    }
}

impl BodyConfig {
    /// Loads a body from TOML text (unvalidated; [`BodyConfig::validate`] it or build a
    /// [`super::Humanoid`], which validates).
    pub fn from_toml(text: &str) -> Result<Self, SimError> {
        toml::from_str(text).map_err(|e| SimError::Parse(e.to_string()))
    }

    /// Loads a body from JSON text (unvalidated).
    pub fn from_json(text: &str) -> Result<Self, SimError> {
        serde_json::from_str(text).map_err(|e| SimError::Parse(e.to_string()))
    }

    /// The leg geometry control computes with; the simulated legs are built to match it.
    pub fn leg_geometry(&self) -> LegGeometry {
        LegGeometry {
            hip_offset: [0.0, self.hip_half_width, 0.0],
            thigh: self.thigh.length,
            shank: self.shank.length,
            ankle_height: self.foot.ankle_height,
            foot_length: self.foot.length,
            foot_width: self.foot.width,
            sole_offset_x: self.foot.sole_offset_x,
            ..LegGeometry::default()
        }
    }

    /// Total mass (kg).
    pub fn total_mass(&self) -> f64 {
        self.torso.mass + 2.0 * (self.thigh.mass + self.shank.mass + self.foot.mass)
    }

    /// Standing height with straight legs: sole to top of the head (m).
    pub fn height(&self) -> f64 {
        self.foot.ankle_height
            + self.shank.length
            + self.thigh.length
            + self.torso.length
            + head_neck_length(&self.torso)
    }

    /// The spec of joint `j` (same for both legs).
    pub fn joint(&self, j: LegJoint) -> &JointSpec {
        &self.joints[j as usize]
    }

    /// Checks every value: masses, lengths and gains positive and finite, limits ordered and
    /// containing zero, gimbals lighter than what they are taken from.
    pub fn validate(&self) -> Result<(), SimError> {
        let t = &self.torso;
        positive("torso.mass", t.mass)?;
        positive("torso.length", t.length)?;
        non_negative("torso.com_height", t.com_height)?;
        for (i, v) in t.inertia.iter().enumerate() {
            positive(&format!("torso.inertia[{i}]"), *v)?;
        }
        positive("torso.depth", t.depth)?;
        positive("torso.width", t.width)?;
        positive("torso.head_radius", t.head_radius)?;
        positive("torso.arm_length", t.arm_length)?;
        positive("torso.arm_radius", t.arm_radius)?;
        positive("hip_half_width", self.hip_half_width)?;
        for (name, s) in [("thigh", &self.thigh), ("shank", &self.shank)] {
            positive(&format!("{name}.length"), s.length)?;
            positive(&format!("{name}.mass"), s.mass)?;
            in_range(&format!("{name}.com_fraction"), s.com_fraction, 0.0, 1.0)?;
            positive(&format!("{name}.gyration_fraction"), s.gyration_fraction)?;
            positive(&format!("{name}.radius"), s.radius)?;
        }
        let f = &self.foot;
        positive("foot.mass", f.mass)?;
        positive("foot.length", f.length)?;
        positive("foot.width", f.width)?;
        positive("foot.ankle_height", f.ankle_height)?;
        in_range(
            "foot.sole_offset_x",
            f.sole_offset_x,
            -f.length / 2.0,
            f.length / 2.0,
        )?;
        positive("gimbal_mass", self.gimbal_mass)?;
        in_range(
            "gimbal_mass",
            self.gimbal_mass,
            0.0,
            0.25 * self.thigh.mass.min(self.foot.mass),
        )?;
        for (j, spec) in LegJoint::ALL.iter().zip(&self.joints) {
            let name = format!("joints.{j:?}");
            in_range(&format!("{name}.limits[0]"), spec.limits[0], -3.2, 0.0)?;
            in_range(&format!("{name}.limits[1]"), spec.limits[1], 0.0, 3.2)?;
            positive(&format!("{name}.stiffness"), spec.stiffness)?;
            non_negative(&format!("{name}.damping"), spec.damping)?;
            positive(&format!("{name}.max_torque"), spec.max_torque)?;
        }
        Ok(())
    }
}

/// Shoulder to top of head (m): the neck plus the head ball.
pub(crate) fn head_neck_length(t: &Torso) -> f64 {
    0.1 + 2.0 * t.head_radius
}
