//! Falls: what counts as one and how it is reported.

use serde::{Deserialize, Serialize};

use crate::robot::Side;

/// A part of the robot that can touch the ground.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum BodyPart {
    /// The torso (trunk, pelvis, head or arms).
    Torso,
    /// A thigh.
    Thigh(Side),
    /// A shank.
    Shank(Side),
    /// A foot (touching the ground with it is not a fall).
    Foot(Side),
}

/// What made the simulator declare a fall: the trunk's tilt or a body other than a foot on
/// the ground. (Why it fell, relative to a push and the catch step, is the experiments'
/// `FallCause`.)
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum FallTrigger {
    /// The trunk tilted beyond the threshold.
    Tilt {
        /// Trunk tilt from vertical (rad).
        angle: f64,
    },
    /// A body other than a foot touched the ground.
    Contact {
        /// Which one.
        part: BodyPart,
    },
}

/// A detected fall.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Fall {
    /// Simulation time of detection (s).
    pub time: f64,
    /// What triggered it.
    pub trigger: FallTrigger,
}
