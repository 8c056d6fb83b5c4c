//! The robot interface: what control reads from a robot and writes back, and the leg geometry
//! both sides compute with. Both [`crate::control`] and the simulator use this module; it uses
//! neither.

mod description;
mod file;
mod io;
pub mod kinematics;
mod mesh;
mod scale;
mod urdf;

/// Standard gravity (m/s^2): the simulator's default and the gravity of the LIPM rules.
pub const STANDARD_GRAVITY: f64 = 9.81;

/// The LIPM constant `C = sqrt(g/h)` (1/s) of the built-in humanoid: the Capture Step
/// controller's default and the default of the rules derived from the LIPM.
pub const HUMANOID_C: f64 = 2.95;

pub use description::{
    Description, Figure, Geometry, Inertia, Joint, Leg, Link, RobotError, Servo, Shape, Sole,
};
pub use file::{RobotFile, sha256_hex};
pub use io::{FootContact, Imu, JOINTS_PER_LEG, JointTargets, LegJoint, NUM_JOINTS, Sensors, Side};
pub use scale::Scale;
pub use urdf::{Feet, ServoReference};

/// Knee bend of the initial standing pose (rad): the simulator starts every robot in
/// `standing_pose(STANCE_KNEE)`, and a robot's stance quantities (centre-of-mass height, C) are
/// taken there.
pub const STANCE_KNEE: f64 = 0.25;

/// Joint angles of a symmetric stance with knees bent by `knee` (rad): hips and ankles each
/// take half the bend so the trunk and soles stay level.
pub fn standing_pose(knee: f64) -> [f64; NUM_JOINTS] {
    let mut q = [0.0; NUM_JOINTS];
    for side in Side::BOTH {
        q[LegJoint::HipPitch.index(side)] = -knee / 2.0;
        q[LegJoint::Knee.index(side)] = knee;
        q[LegJoint::AnklePitch.index(side)] = -knee / 2.0;
    }
    q
}
