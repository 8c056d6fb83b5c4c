//! Ground truth of the simulation, for tests and figures only (control never reads it).

use rapier3d_f64::prelude::*;
use serde::{Deserialize, Serialize};

/// A position and orientation in the world frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WorldPose {
    /// Position (m).
    pub position: [f64; 3],
    /// Orientation as a unit quaternion `[w, x, y, z]`.
    pub orientation: [f64; 4],
}

pub(crate) fn pose_of(p: Vector, r: Rotation) -> WorldPose {
    WorldPose {
        position: [p.x, p.y, p.z],
        orientation: [r.w, r.x, r.y, r.z],
    }
}

/// Points of a stick figure of the robot (world frame, m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Skeleton {
    /// Torso origin, midway between the hip centres.
    pub pelvis: [f64; 3],
    /// Top of the trunk (between the shoulders).
    pub neck: [f64; 3],
    /// Centre of the head.
    pub head: [f64; 3],
    /// Head radius (m).
    pub head_radius: f64,
    /// Per leg (left, right): hip centre, knee, ankle centre, heel and toe on the sole.
    pub legs: [[[f64; 3]; 5]; 2],
}

/// The true state of the simulated robot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GroundTruth {
    /// Simulation time (s).
    pub time: f64,
    /// Total mass (kg).
    pub mass: f64,
    /// Centre of mass (m).
    pub com: [f64; 3],
    /// Centre-of-mass velocity (m/s).
    pub com_vel: [f64; 3],
    /// Linear momentum (N s).
    pub momentum: [f64; 3],
    /// The torso frame (midway between the hip centres).
    pub torso: WorldPose,
    /// Sole centres, left then right.
    pub soles: [WorldPose; 2],
    /// Stick-figure points.
    pub skeleton: Skeleton,
    /// Every link's frame: the trunk, then the left leg's six links and the right leg's, in
    /// [`crate::robot::LegJoint::ALL`] order (the robot description's order).
    pub links: [WorldPose; 1 + crate::robot::NUM_JOINTS],
}
