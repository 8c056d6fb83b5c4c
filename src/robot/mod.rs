//! The robot interface: what control reads from a robot and writes back, and the leg geometry
//! both sides compute with. Both [`crate::control`] and the simulator use this module; it uses
//! neither.

pub mod description;
pub mod file;
mod io;
pub mod kinematics;
pub mod scale;
pub mod urdf;

/// Standard gravity (m/s^2): the simulator's default and the gravity of the LIPM rules.
pub const STANDARD_GRAVITY: f64 = 9.81;

/// The LIPM constant `C = sqrt(g/h)` (1/s) of the built-in humanoid: the Capture Step
/// controller's default and the default of the rules derived from the LIPM.
pub const HUMANOID_C: f64 = 2.95;

pub use io::{FootContact, Imu, JOINTS_PER_LEG, JointTargets, LegJoint, NUM_JOINTS, Sensors, Side};
