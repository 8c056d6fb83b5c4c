//! Control: everything between the sensors and the joint targets, independent of any simulator.
//!
//! Data flows one way: [`Sensors`] -> state estimation -> Capture Step balance control ->
//! footstep learner -> step motion generator -> [`JointTargets`].

mod io;
pub mod kinematics;
pub mod motion;

pub use io::{FootContact, Imu, JOINTS_PER_LEG, JointTargets, LegJoint, NUM_JOINTS, Sensors, Side};
