//! Control: everything between the sensors and the joint targets, independent of any simulator.
//!
//! Data flows one way: [`Sensors`] -> state estimation -> Capture Step balance control ->
//! footstep learner -> step motion generator -> [`JointTargets`].

pub mod capture_step;
pub mod estimator;
mod io;
pub mod kinematics;
pub mod learner;
pub mod lipm;
pub mod lipm_plant;
pub mod motion;
pub mod walker;

pub use io::{FootContact, Imu, JOINTS_PER_LEG, JointTargets, LegJoint, NUM_JOINTS, Sensors, Side};

impl Default for walker::WalkerConfig {
    /// A Capture Step walker with the default controller, estimator and generator (what a
    /// config file's `[settings.walker]` starts from; each experiment sets its own mode).
    fn default() -> Self {
        walker::WalkerConfig::new(walker::WalkerMode::CaptureStep)
    }
}
