//! Control: everything between the sensors and the joint targets, independent of any simulator.
//!
//! Data flows one way: [`Sensors`] -> state estimation -> Capture Step balance control ->
//! footstep learner -> step motion generator -> [`JointTargets`].

pub mod capture_step;
pub mod coupled;
pub mod estimator;
pub mod for_robot;
pub mod learner;
pub mod learner_config;
pub mod learner_error;
pub mod lipm;
pub mod lipm_plant;
pub mod motion;
pub mod policy;
pub mod step_learner;
pub mod step_parameter;
mod step_samples;
pub mod walker;

// The robot interface, re-exported where control's users look for it.
pub use crate::robot::kinematics;
pub use crate::robot::{
    FootContact, Imu, JOINTS_PER_LEG, JointTargets, LegJoint, NUM_JOINTS, Sensors, Side,
};

// The learner and what it is built from, where users look for them.
pub use learner::{FootstepLearner, OffsetLearner, SavedLearner, TouchDownReport};
pub use learner_config::{LearnerConfig, LearnerInput, ParameterSettings, PartSettings, Prior};
pub use learner_error::LearnerError;
pub use policy::FootstepPolicy;
pub use step_learner::StepLearner;
pub use step_parameter::{LearnSet, Plane, Planes, StepParameter};
pub use walker::{Walker, WalkerConfig, WalkerMode};
