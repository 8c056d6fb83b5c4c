//! The robot interface: what control reads from a robot and writes back, and the leg geometry
//! both sides compute with. Both [`crate::control`] and the simulator use this module; it uses
//! neither.

mod io;
pub mod kinematics;

pub use io::{FootContact, Imu, JOINTS_PER_LEG, JointTargets, LegJoint, NUM_JOINTS, Sensors, Side};
