//! The built-in humanoid as a [`Description`]: the links, joints and shapes that
//! [`BodyConfig`] describes with its segments, in the order the simulator builds them.

use super::body::{BodyConfig, Segment, head_neck_length};
use crate::robot::ServoReference;
use crate::robot::{Description, Figure, Geometry, Inertia, Joint, Leg, Link, Servo, Shape, Sole};
use crate::robot::{JOINTS_PER_LEG, LegJoint, Side};

const IDENTITY: [f64; 4] = [1.0, 0.0, 0.0, 0.0];

fn shape(geometry: Geometry, position: [f64; 3]) -> Shape {
    Shape {
        geometry,
        position,
        orientation: IDENTITY,
    }
}

/// A capsule hanging below its joint over `length`, `clearance` short of both ends.
fn capsule_below(length: f64, radius: f64, clearance: f64) -> Shape {
    let half = (length / 2.0 - radius - clearance).max(1e-3);
    shape(
        Geometry::Capsule {
            half_height: half,
            radius,
        },
        [0.0, 0.0, -length / 2.0],
    )
}

/// A limb segment of `mass` (kg) with its capsule.
fn segment_link(name: String, s: &Segment, mass: f64, clearance: f64) -> Link {
    let i_long = mass * (s.gyration_fraction * s.length).powi(2);
    let i_axial = 0.5 * mass * s.radius * s.radius;
    Link {
        name,
        mass,
        com: [0.0, 0.0, -s.com_fraction * s.length],
        inertia: Inertia::diagonal([i_long, i_long, i_axial]),
        shapes: vec![capsule_below(s.length, s.radius, clearance)],
    }
}

impl BodyConfig {
    /// This body's servos, default limits, leg length and mass: what another robot's servos
    /// are scaled from.
    pub fn servo_reference(&self) -> ServoReference {
        let d = self.description();
        ServoReference {
            servos: LegJoint::ALL.map(|j| {
                let s = self.joint(j);
                Servo {
                    stiffness: s.stiffness,
                    damping: s.damping,
                    max_torque: s.max_torque,
                }
            }),
            limits: LegJoint::ALL.map(|j| self.joint(j).limits),
            leg_length: d.leg_length(),
            mass: d.mass(),
            leg_inertia: d.leg_inertia(),
        }
    }

    /// This body as a robot description (unvalidated; [`BodyConfig::validate`] checks it).
    pub fn description(&self) -> Description {
        let t = &self.torso;
        let pelvis_h = 0.12;
        let arm = |s: f64| {
            shape(
                Geometry::Capsule {
                    half_height: t.arm_length / 2.0 - t.arm_radius,
                    radius: t.arm_radius,
                },
                [
                    0.0,
                    s * (t.width / 2.0 + t.arm_radius + 0.01),
                    t.length - t.arm_length / 2.0,
                ],
            )
        };
        let head_z = t.length + head_neck_length(t) - t.head_radius;
        let trunk = Link {
            name: "torso".into(),
            mass: t.mass,
            com: [0.0, 0.0, t.com_height],
            inertia: Inertia::diagonal(t.inertia),
            shapes: vec![
                shape(
                    Geometry::Box {
                        half_extents: [t.depth / 2.0, t.width / 2.0, t.length / 2.0],
                    },
                    [0.0, 0.0, t.length / 2.0 - pelvis_h / 2.0 + 0.02],
                ),
                shape(
                    Geometry::Sphere {
                        radius: t.head_radius,
                    },
                    [0.0, 0.0, head_z],
                ),
                arm(1.0),
                arm(-1.0),
            ],
        };
        Description {
            name: "steplearn-humanoid".into(),
            trunk,
            legs: Side::BOTH.map(|side| self.leg(side)),
            held_joints: Vec::new(),
            remarks: Vec::new(),
            figure: Figure {
                neck: [0.0, 0.0, t.length],
                head: [0.0, 0.0, head_z],
                head_radius: t.head_radius,
            },
        }
    }

    fn leg(&self, side: Side) -> Leg {
        let prefix = match side {
            Side::Left => "left",
            Side::Right => "right",
        };
        let name = |n: &str| format!("{prefix}_{n}");
        let gimbal = |n: &str| Link {
            name: name(n),
            mass: self.gimbal_mass,
            com: [0.0; 3],
            inertia: Inertia::diagonal([1e-4; 3]),
            shapes: Vec::new(),
        };
        let (th, sh, f) = (&self.thigh, &self.shank, &self.foot);
        let fm = f.mass - self.gimbal_mass;
        let (lx, ly, lz) = (f.length, f.width, f.ankle_height);
        let foot = Link {
            name: name("foot"),
            mass: fm,
            com: [f.sole_offset_x, 0.0, -lz / 2.0],
            inertia: Inertia::diagonal([
                fm * (ly * ly + lz * lz) / 12.0,
                fm * (lx * lx + lz * lz) / 12.0,
                fm * (lx * lx + ly * ly) / 12.0,
            ]),
            shapes: vec![shape(
                Geometry::Box {
                    half_extents: [lx / 2.0, ly / 2.0, lz / 2.0],
                },
                [f.sole_offset_x, 0.0, -lz / 2.0],
            )],
        };
        let links = [
            gimbal("hip_yaw_link"),
            gimbal("hip_roll_link"),
            segment_link(name("thigh"), th, th.mass - 2.0 * self.gimbal_mass, 0.0),
            segment_link(name("shank"), sh, sh.mass, 0.01),
            gimbal("ankle_link"),
            foot,
        ];
        let chain = [
            ("hip_yaw", [0.0, side.sign() * self.hip_half_width, 0.0]),
            ("hip_roll", [0.0; 3]),
            ("hip_pitch", [0.0; 3]),
            ("knee", [0.0, 0.0, -th.length]),
            ("ankle_pitch", [0.0, 0.0, -sh.length]),
            ("ankle_roll", [0.0; 3]),
        ];
        let joints: [Joint; JOINTS_PER_LEG] = std::array::from_fn(|k| {
            let j = LegJoint::ALL[k];
            let spec = self.joint(j);
            let [lo, hi] = spec.limits;
            let limits = match (j, side) {
                (LegJoint::HipYaw | LegJoint::HipRoll | LegJoint::AnkleRoll, Side::Right) => {
                    [-hi, -lo]
                }
                _ => [lo, hi],
            };
            Joint {
                name: name(chain[k].0),
                origin: chain[k].1,
                axis: j.axis(),
                sign: 1.0,
                limits,
                servo: Servo {
                    stiffness: spec.stiffness,
                    damping: spec.damping,
                    max_torque: spec.max_torque,
                },
            }
        });
        Leg {
            joints,
            links,
            sole: Sole {
                shape: 0,
                centre: [f.sole_offset_x, 0.0, -f.ankle_height],
                length: lx,
                width: ly,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_description_has_the_bodys_leg_geometry_and_mass() {
        let body = BodyConfig::default();
        let d = body.description();
        d.validate().unwrap();
        assert_eq!(d.leg_geometry(), body.leg_geometry());
        assert!((d.mass() - body.total_mass()).abs() < 1e-12);
    }
}
