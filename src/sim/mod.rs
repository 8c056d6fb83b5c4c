//! The simulated humanoid in rapier3d: a 2 m, 13.5 kg biped with 12 position-controlled joints,
//! pushes, fall detection and resets. It fills [`crate::robot::Sensors`] and applies
//! [`crate::robot::JointTargets`]; control never sees rapier.

mod body;
mod builtin;
mod config;
mod error;
mod fall;
mod humanoid;
pub mod picture;
mod sensors;
mod truth;

pub use body::{BodyConfig, Foot, JointSpec, Segment, Torso};
pub use config::SimConfig;
pub use error::SimError;
pub use fall::{BodyPart, Fall, FallTrigger};
pub use humanoid::Humanoid;
pub use truth::{GroundTruth, Skeleton, WorldPose};
