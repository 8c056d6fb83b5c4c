//! Control: everything between the sensors and the joint targets, independent of any simulator.
//!
//! Data flows one way: [`Sensors`](crate::robot::Sensors) -> state estimation -> Capture Step
//! balance control -> footstep learner -> step motion generator ->
//! [`JointTargets`](crate::robot::JointTargets). The learner, the policy and the walker have one
//! path each, here (`control::Walker`, `control::StepLearner`, ...); the robot interface is
//! [`crate::robot`]'s.

pub mod capture_step;
pub mod coupled;
pub mod estimator;
pub mod for_robot;
mod learner;
mod learner_config;
mod learner_error;
pub mod lipm;
pub mod lipm_plant;
pub mod motion;
mod policy;
mod step_learner;
mod step_parameter;
mod step_samples;
mod walker;

// The learner and what it is built from, the policy and the walker: one path each, here.
pub use learner::{
    FootstepLearner, InputGrid, MapSpec, OffsetLearner, OffsetMap, SavedLearner, SavedOffset,
    StepInProgress, TouchDownReport,
};
pub use learner_config::{
    CheckedLearnerConfig, FallSettings, GuardSettings, LEARNER_INPUTS, LearnerConfig, LearnerInput,
    MAX_OFFSET_INPUTS, MAX_PRIOR_SAMPLES, MAX_SAMPLES_PER_STEP, MemorySettings, OffsetSettings,
    ParameterSettings, PartSettings, Prior, TrustFallback, TrustSettings,
};
pub use learner_error::LearnerError;
pub use policy::{FootstepPolicy, StepReports};
pub use step_learner::{SavedStepLearner, StepLearner};
pub use step_parameter::{
    FALL_DIRECTION_BAND, FallDirection, Gate, LearnSet, LearnSetError, PerParameter, Plane, Planes,
    StepParameter,
};
pub use walker::{OffsetTarget, START_RAMP_S, Tick, Walker, WalkerConfig, WalkerError, WalkerMode};
