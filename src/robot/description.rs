//! A robot as data: its trunk, its two legs of six joints, their links' masses, inertias and
//! collision shapes. The simulator builds its multibody from a [`Description`], and control
//! takes the leg geometry, the stance and the scale from it; neither knows where it came from
//! (the built-in humanoid, or a URDF file through [`Description::from_urdf`]).

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::kinematics::LegGeometry;
use super::{JOINTS_PER_LEG, LegJoint, NUM_JOINTS, Side};

/// Why a robot description was refused. Every message names the link or joint at fault.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RobotError {
    /// The file could not be read.
    #[error("cannot read robot file {path}: {reason}")]
    Io {
        /// The file.
        path: String,
        /// The operating system's reason.
        reason: String,
    },
    /// The XML is malformed.
    #[error("malformed robot file: {0}")]
    Xml(String),
    /// An element is missing, malformed or out of range.
    #[error("{element}: {reason}")]
    Invalid {
        /// The link or joint (`link 'foot'`, `joint 'knee'`).
        element: String,
        /// What is wrong.
        reason: String,
    },
}

impl RobotError {
    pub(crate) fn invalid(element: impl Into<String>, reason: impl Into<String>) -> Self {
        RobotError::Invalid {
            element: element.into(),
            reason: reason.into(),
        }
    }
}

/// Principal moments of inertia about the centre of mass and the rotation to their axes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Inertia {
    /// Principal moments (kg m^2).
    pub principal: [f64; 3],
    /// Rotation from the link frame to the principal axes, unit quaternion `[w, x, y, z]`.
    pub axes: [f64; 4],
}

impl Inertia {
    /// Moments about the link's own axes (no rotation).
    pub fn diagonal(principal: [f64; 3]) -> Self {
        Inertia {
            principal,
            axes: [1.0, 0.0, 0.0, 0.0],
        }
    }

    /// Whether the principal axes are the link's own.
    pub fn is_diagonal(&self) -> bool {
        self.axes == [1.0, 0.0, 0.0, 0.0]
    }

    /// The inertia tensor in the link frame.
    pub fn matrix(&self) -> Matrix3<f64> {
        let r = quat(self.axes).to_rotation_matrix();
        let d = Matrix3::from_diagonal(&Vector3::from(self.principal));
        r.matrix() * d * r.matrix().transpose()
    }

    /// From a symmetric tensor in the link frame (diagonal ones kept exactly).
    pub fn from_matrix(m: &Matrix3<f64>) -> Self {
        if m[(0, 1)] == 0.0 && m[(0, 2)] == 0.0 && m[(1, 2)] == 0.0 {
            return Inertia::diagonal([m[(0, 0)], m[(1, 1)], m[(2, 2)]]);
        }
        let eig = m.symmetric_eigen();
        let mut v = eig.eigenvectors;
        if v.determinant() < 0.0 {
            v.column_mut(2).neg_mut();
        }
        let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(v));
        Inertia {
            principal: [eig.eigenvalues[0], eig.eigenvalues[1], eig.eigenvalues[2]],
            axes: [q.w, q.i, q.j, q.k],
        }
    }
}

/// A collision shape's geometry.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Geometry {
    /// A box of these half extents along x, y, z.
    Box {
        /// Half extents (m).
        half_extents: [f64; 3],
    },
    /// A sphere.
    Sphere {
        /// Radius (m).
        radius: f64,
    },
    /// A capsule along z: a cylinder of `2 half_height` with hemispherical caps.
    Capsule {
        /// Half the length of its cylinder (m).
        half_height: f64,
        /// Radius (m).
        radius: f64,
    },
    /// A cylinder along z.
    Cylinder {
        /// Half its length (m).
        half_height: f64,
        /// Radius (m).
        radius: f64,
    },
}

/// A collision shape placed in its link's frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Shape {
    /// What it is.
    pub geometry: Geometry,
    /// Its centre in the link frame (m).
    pub position: [f64; 3],
    /// Its orientation in the link frame, unit quaternion `[w, x, y, z]`.
    pub orientation: [f64; 4],
}

/// One rigid link in its frame (aligned with the trunk in the zero pose).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Link {
    /// The name in the robot's file.
    pub name: String,
    /// Mass (kg).
    pub mass: f64,
    /// Centre of mass in the link frame (m).
    pub com: [f64; 3],
    /// Inertia about the centre of mass.
    pub inertia: Inertia,
    /// Collision shapes.
    pub shapes: Vec<Shape>,
}

/// The position servo of one joint.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Servo {
    /// Stiffness (N m / rad).
    pub stiffness: f64,
    /// Damping (N m s / rad).
    pub damping: f64,
    /// Largest torque (N m).
    pub max_torque: f64,
}

/// A revolute leg joint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Joint {
    /// The name in the robot's file.
    pub name: String,
    /// The child link's origin (the joint centre) in the parent link's frame (m).
    pub origin: [f64; 3],
    /// Unit axis (the same in parent and child frames), pointing along steplearn's axis.
    pub axis: [f64; 3],
    /// +1 or -1: the robot's own angle is `sign` times steplearn's.
    pub sign: f64,
    /// Lower and upper limit in steplearn's angle (rad).
    pub limits: [f64; 2],
    /// The position servo.
    pub servo: Servo,
}

/// The sole of a foot: a rectangle on the bottom face of the foot's collision box.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Sole {
    /// Index of the sole's box among the foot link's shapes.
    pub shape: usize,
    /// Centre of the sole (the box's bottom face) in the foot frame (m).
    pub centre: [f64; 3],
    /// Length along x (m).
    pub length: f64,
    /// Width along y (m).
    pub width: f64,
}

/// One leg: six joints from the trunk to the foot, the link each one moves, and the sole.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Leg {
    /// Hip yaw, hip roll, hip pitch, knee, ankle pitch, ankle roll.
    pub joints: [Joint; JOINTS_PER_LEG],
    /// The link each joint moves; the last is the foot.
    pub links: [Link; JOINTS_PER_LEG],
    /// The foot's sole.
    pub sole: Sole,
}

/// Points of the stick figure drawn for the trunk (trunk frame, m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Figure {
    /// Top of the trunk.
    pub neck: [f64; 3],
    /// Centre of the head.
    pub head: [f64; 3],
    /// Head radius.
    pub head_radius: f64,
}

/// A biped: the trunk (the floating base, with every joint outside the legs held) and two
/// legs. Build one with [`Description::from_urdf`] or take the built-in humanoid's; a
/// description is checked on construction ([`Description::validate`]).
///
/// Frames: every link frame is aligned with the trunk frame in the zero pose (all joints at
/// zero), with its origin on its parent joint; a joint's `axis` is the same in both frames.
/// Joint angles are steplearn's ([`crate::robot::LegJoint`]): about +z, +x, +y, +y, +y, +x for
/// hip yaw, roll, pitch, knee, ankle pitch and roll. A robot whose own axis points the other
/// way has `sign = -1`: its angle is `sign` times steplearn's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Description {
    /// The robot's name.
    pub name: String,
    /// The trunk, with every held link merged into it.
    pub trunk: Link,
    /// Left leg, then right.
    pub legs: [Leg; 2],
    /// Joints outside the legs, held fixed (merged into the trunk).
    pub held_joints: Vec<String>,
    /// The trunk's stick figure.
    pub figure: Figure,
    /// What the loader accepted with a remark (a held link whose own inertia is not
    /// physical), one line each.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub remarks: Vec<String>,
}

pub(crate) fn quat(q: [f64; 4]) -> UnitQuaternion<f64> {
    UnitQuaternion::new_normalize(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]))
}

fn finite(element: &str, what: &str, values: &[f64]) -> Result<(), RobotError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(RobotError::invalid(
            element,
            format!("{what} must be finite, got {values:?}"),
        ))
    }
}

impl Link {
    /// Checks mass, centre of mass, inertia and shapes.
    pub fn validate(&self) -> Result<(), RobotError> {
        let el = format!("link '{}'", self.name);
        if !(self.mass.is_finite() && self.mass > 0.0) {
            return Err(RobotError::invalid(
                el,
                format!("mass must be positive and finite, got {}", self.mass),
            ));
        }
        finite(&el, "centre of mass", &self.com)?;
        finite(&el, "inertia", &self.inertia.principal)?;
        finite(&el, "inertia axes", &self.inertia.axes)?;
        let [a, b, c] = self.inertia.principal;
        if a <= 0.0 || b <= 0.0 || c <= 0.0 {
            return Err(RobotError::invalid(
                el,
                format!("principal moments of inertia must be positive, got {a}, {b}, {c}"),
            ));
        }
        let tol = 1e-9 * (a + b + c);
        if a + b < c - tol || a + c < b - tol || b + c < a - tol {
            return Err(RobotError::invalid(
                el,
                format!("principal moments of inertia {a}, {b}, {c} break the triangle inequality"),
            ));
        }
        for s in &self.shapes {
            finite(&el, "shape position", &s.position)?;
            finite(&el, "shape orientation", &s.orientation)?;
            let dims: Vec<f64> = match s.geometry {
                Geometry::Box { half_extents } => half_extents.to_vec(),
                Geometry::Sphere { radius } => vec![radius],
                Geometry::Capsule {
                    half_height,
                    radius,
                }
                | Geometry::Cylinder {
                    half_height,
                    radius,
                } => vec![half_height + radius, radius],
            };
            if dims.iter().any(|d| !(d.is_finite() && *d > 0.0)) {
                return Err(RobotError::invalid(
                    el,
                    format!("shape sizes must be positive and finite: {:?}", s.geometry),
                ));
            }
        }
        Ok(())
    }
}

fn rot(axis: [f64; 3], angle: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(Vector3::from(axis)), angle)
}

impl Description {
    /// Checks every link, joint and sole, and that the robot stands: its centre of mass in the
    /// knee-bent stance `stance` lies over the support polygon of its soles.
    pub fn validate_standing(&self, stance: &[f64; NUM_JOINTS]) -> Result<(), RobotError> {
        self.validate()?;
        // The stance lies within every leg joint's limits (steplearn's sense: a knee bends the
        // shank back with a positive angle).
        for side in Side::BOTH {
            for (joint, j) in self.legs[side.index()].joints.iter().zip(LegJoint::ALL) {
                let q = stance[j.index(side)];
                let [lo, hi] = joint.limits;
                if q < lo - 1e-9 || q > hi + 1e-9 {
                    return Err(RobotError::invalid(
                        format!("joint '{}'", joint.name),
                        format!(
                            "its limits [{lo:.3}, {hi:.3}] rad (in steplearn's sense, where a knee \
                             bends back with a positive angle) exclude the stance's {q:.3} rad: \
                             the robot cannot stand (a knee that bends forward, or a robot whose \
                             front is not its +x?)"
                        ),
                    ));
                }
            }
        }
        let com = self.com_in_trunk(stance);
        let soles: Vec<Vector3<f64>> = Side::BOTH
            .iter()
            .flat_map(|s| self.sole_corners_in_trunk(*s, stance))
            .collect();
        let (xs, ys): (Vec<f64>, Vec<f64>) = soles.iter().map(|p| (p.x, p.y)).unzip();
        let min = |v: &[f64]| v.iter().cloned().fold(f64::INFINITY, f64::min);
        let max = |v: &[f64]| v.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        // Both soles are level in the stance: the support polygon is their bounding box.
        if com.x < min(&xs) || com.x > max(&xs) || com.y < min(&ys) || com.y > max(&ys) {
            return Err(RobotError::invalid(
                format!("link '{}'", self.trunk.name),
                format!(
                    "the centre of mass ({:.3}, {:.3}) m in the trunk frame lies outside the \
                     feet (x in [{:.3}, {:.3}], y in [{:.3}, {:.3}]): the robot cannot stand",
                    com.x,
                    com.y,
                    min(&xs),
                    max(&xs),
                    min(&ys),
                    max(&ys)
                ),
            ));
        }
        Ok(())
    }

    /// Checks every link, joint and sole.
    pub fn validate(&self) -> Result<(), RobotError> {
        self.trunk.validate()?;
        for leg in &self.legs {
            for (j, (joint, link)) in LegJoint::ALL.iter().zip(leg.joints.iter().zip(&leg.links)) {
                link.validate()?;
                let el = format!("joint '{}'", joint.name);
                finite(&el, "origin", &joint.origin)?;
                finite(&el, "axis", &joint.axis)?;
                finite(&el, "limits", &joint.limits)?;
                let n = Vector3::from(joint.axis).norm();
                if (n - 1.0).abs() > 1e-6 {
                    return Err(RobotError::invalid(el, "axis must be a unit vector"));
                }
                if joint.sign != 1.0 && joint.sign != -1.0 {
                    return Err(RobotError::invalid(el, "sign must be +1 or -1"));
                }
                let [lo, hi] = joint.limits;
                if lo >= hi {
                    return Err(RobotError::invalid(
                        el,
                        format!(
                            "is locked (limits [{lo}, {hi}]): the gait needs the {j:?} joint to move"
                        ),
                    ));
                }
                let s = joint.servo;
                finite(&el, "servo", &[s.stiffness, s.damping, s.max_torque])?;
                if s.stiffness <= 0.0 || s.damping < 0.0 || s.max_torque <= 0.0 {
                    return Err(RobotError::invalid(
                        el,
                        format!("servo out of range: {s:?}"),
                    ));
                }
            }
            let foot = &leg.links[JOINTS_PER_LEG - 1];
            let el = format!("link '{}'", foot.name);
            let sole = &leg.sole;
            finite(&el, "sole", &[sole.length, sole.width])?;
            finite(&el, "sole centre", &sole.centre)?;
            if !matches!(
                foot.shapes.get(sole.shape).map(|s| s.geometry),
                Some(Geometry::Box { .. })
            ) || sole.length <= 0.0
                || sole.width <= 0.0
            {
                return Err(RobotError::invalid(
                    el,
                    "the sole must be a box of the foot",
                ));
            }
        }
        finite("figure", "points", &[self.figure.head_radius])?;
        Ok(())
    }

    /// Total mass (kg).
    pub fn mass(&self) -> f64 {
        self.trunk.mass
            + self
                .legs
                .iter()
                .flat_map(|l| l.links.iter())
                .map(|l| l.mass)
                .sum::<f64>()
    }

    /// The pose in the trunk frame of every link of leg `side` at joint angles `q` (12, in
    /// [`LegJoint::index`] order): origin and rotation.
    pub fn link_poses(
        &self,
        side: Side,
        q: &[f64; NUM_JOINTS],
    ) -> [(Vector3<f64>, Rotation3<f64>); JOINTS_PER_LEG] {
        let leg = &self.legs[side.index()];
        let mut p = Vector3::zeros();
        let mut r = Rotation3::identity();
        let mut out = [(p, r); JOINTS_PER_LEG];
        for (k, j) in LegJoint::ALL.iter().enumerate() {
            let joint = &leg.joints[k];
            p += r * Vector3::from(joint.origin);
            r *= rot(joint.axis, q[j.index(side)]);
            out[k] = (p, r);
        }
        out
    }

    /// The whole robot's centre of mass in the trunk frame at joint angles `q`.
    pub fn com_in_trunk(&self, q: &[f64; NUM_JOINTS]) -> Vector3<f64> {
        let mut sum = Vector3::from(self.trunk.com) * self.trunk.mass;
        let mut m = self.trunk.mass;
        for side in Side::BOTH {
            let poses = self.link_poses(side, q);
            for (link, (p, r)) in self.legs[side.index()].links.iter().zip(poses) {
                sum += (p + r * Vector3::from(link.com)) * link.mass;
                m += link.mass;
            }
        }
        sum / m
    }

    /// The four corners of the sole of leg `side` in the trunk frame at joint angles `q`.
    pub fn sole_corners_in_trunk(&self, side: Side, q: &[f64; NUM_JOINTS]) -> [Vector3<f64>; 4] {
        let (p, r) = self.link_poses(side, q)[JOINTS_PER_LEG - 1];
        let s = &self.legs[side.index()].sole;
        let c = Vector3::from(s.centre);
        [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)]
            .map(|(a, b)| p + r * (c + Vector3::new(a * s.length / 2.0, b * s.width / 2.0, 0.0)))
    }

    /// Height of the centre of mass above the soles at joint angles `q` (both soles level).
    pub fn com_height(&self, q: &[f64; NUM_JOINTS]) -> f64 {
        let sole_z = Side::BOTH
            .iter()
            .flat_map(|s| self.sole_corners_in_trunk(*s, q))
            .map(|c| c.z)
            .fold(f64::INFINITY, f64::min);
        self.com_in_trunk(q).z - sole_z
    }

    /// Hip centre of leg `side` in the trunk frame: where the hip pitch axis crosses the
    /// sagittal plane of the leg, in the zero pose.
    pub fn hip_centre(&self, side: Side) -> Vector3<f64> {
        self.legs[side.index()].joints[..3]
            .iter()
            .map(|j| Vector3::from(j.origin))
            .sum()
    }

    /// The left leg's moment of inertia about its hip pitch axis in the zero pose (kg m^2).
    pub fn leg_inertia(&self) -> f64 {
        let hip = self.hip_centre(Side::Left);
        let poses = self.link_poses(Side::Left, &[0.0; NUM_JOINTS]);
        self.legs[Side::Left.index()]
            .links
            .iter()
            .zip(poses)
            .map(|(link, (p, r))| {
                let c = p + r * Vector3::from(link.com) - hip;
                link.mass * (c.x * c.x + c.z * c.z) + link.inertia.matrix()[(1, 1)]
            })
            .sum()
    }

    /// Leg length: hip centre to sole, straight (m).
    pub fn leg_length(&self) -> f64 {
        let g = self.leg_geometry();
        g.thigh + g.shank + g.ankle_height
    }

    /// The leg geometry control computes with (the left leg's; the right leg mirrors it).
    pub fn leg_geometry(&self) -> LegGeometry {
        let leg = &self.legs[Side::Left.index()];
        let yaw = Vector3::from(leg.joints[0].origin);
        let hip = self.hip_centre(Side::Left);
        let knee = Vector3::from(leg.joints[3].origin);
        let ankle = Vector3::from(leg.joints[4].origin) + Vector3::from(leg.joints[5].origin);
        // The length of a segment along -z, and its sagittal angle (0 when straight).
        let segment = |v: Vector3<f64>| {
            if v.x == 0.0 && v.y == 0.0 {
                (-v.z, 0.0)
            } else {
                (v.norm(), v.x.atan2(-v.z))
            }
        };
        let (thigh, thigh_angle) = segment(knee);
        let (shank, shank_angle) = segment(ankle);
        let sole = &leg.sole;
        LegGeometry {
            hip_offset: [hip.x, hip.y, hip.z],
            thigh,
            shank,
            ankle_height: -sole.centre[2],
            foot_length: sole.length,
            foot_width: sole.width,
            sole_offset_x: sole.centre[0],
            sole_offset_y: sole.centre[1],
            thigh_angle,
            shank_angle,
            yaw_offset: [hip.x - yaw.x, hip.y - yaw.y],
        }
    }

    /// The six joint names of leg `side`, in [`LegJoint::ALL`] order.
    pub fn joint_names(&self, side: Side) -> [&str; JOINTS_PER_LEG] {
        let leg = &self.legs[side.index()];
        std::array::from_fn(|k| leg.joints[k].name.as_str())
    }

    /// Joint angles in the robot's own convention and order (left leg, then right, each
    /// in [`LegJoint::ALL`] order), from steplearn's.
    pub fn to_robot_angles(&self, q: &[f64; NUM_JOINTS]) -> [f64; NUM_JOINTS] {
        std::array::from_fn(|i| {
            q[i] * self.legs[i / JOINTS_PER_LEG].joints[i % JOINTS_PER_LEG].sign
        })
    }

    /// Joint angles in steplearn's convention, from the robot's own.
    pub fn from_robot_angles(&self, q: &[f64; NUM_JOINTS]) -> [f64; NUM_JOINTS] {
        self.to_robot_angles(q)
    }
}
