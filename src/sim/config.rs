//! Physics, solver, contact and control-tick settings of a simulation run.

use serde::{Deserialize, Serialize};

use super::body::BodyConfig;
use super::error::{SimError, in_range, non_negative, positive};
use crate::robot::RobotFile;
use crate::robot::{NUM_JOINTS, STANCE_KNEE, standing_pose};

/// Everything that defines a simulation run besides the control inputs: the body, the physics
/// step, solver settings, ground friction, control tick, push delivery and fall detection.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SimConfig {
    /// The built-in humanoid's body (and the paper's robot that another robot's servos are
    /// scaled from).
    pub body: BodyConfig,
    /// A robot from a URDF file instead of the built-in humanoid (`--robot PATH`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub robot: Option<RobotFile>,
    /// Physics step (s), in [1e-4, 5e-3].
    pub dt: f64,
    /// Physics steps per control tick (>= 1): a control tick lasts `dt * steps_per_tick`.
    pub steps_per_tick: usize,
    /// rapier's solver iterations (substeps) per physics step, in [1, 10].
    pub solver_iterations: usize,
    /// rapier's internal PGS iterations per solver iteration, in [1, 10].
    pub pgs_iterations: usize,
    /// Coulomb friction coefficient between any body and the ground.
    pub friction: f64,
    /// Gravity (m/s^2, pointing down). Zero is allowed (tests of momentum).
    pub gravity: f64,
    /// Physics steps over which a push impulse is spread as a constant force (>= 1).
    pub push_steps: usize,
    /// Trunk tilt from vertical (rad) beyond which the robot has fallen.
    pub fall_tilt: f64,
    /// Joint angles of the initial standing pose (rad), [`crate::robot::LegJoint::index`] order.
    pub initial_joints: [f64; NUM_JOINTS],
    /// Gap between the soles and the ground at the start (m).
    pub initial_clearance: f64,
}

impl Default for SimConfig {
    fn default() -> Self {
        SimConfig {
            body: BodyConfig::default(),
            robot: None,
            dt: 0.002,
            steps_per_tick: 5,
            solver_iterations: 1,
            pgs_iterations: 1,
            friction: 0.8,
            gravity: crate::robot::STANDARD_GRAVITY,
            push_steps: 5,
            fall_tilt: 0.7,
            initial_joints: standing_pose(STANCE_KNEE),
            initial_clearance: 0.0,
        }
    }
}

impl SimConfig {
    /// Duration of one control tick (s).
    pub fn tick(&self) -> f64 {
        self.dt * self.steps_per_tick as f64
    }

    /// Checks every value (and the body).
    pub fn validate(&self) -> Result<(), SimError> {
        self.body.validate()?;
        in_range("dt", self.dt, 1e-4, 5e-3)?;
        in_range("steps_per_tick", self.steps_per_tick as f64, 1.0, 100.0)?;
        in_range(
            "solver_iterations",
            self.solver_iterations as f64,
            1.0,
            10.0,
        )?;
        in_range("pgs_iterations", self.pgs_iterations as f64, 1.0, 10.0)?;
        in_range("friction", self.friction, 0.0, 10.0)?;
        non_negative("gravity", self.gravity)?;
        in_range("push_steps", self.push_steps as f64, 1.0, 1000.0)?;
        positive("fall_tilt", self.fall_tilt)?;
        in_range("initial_clearance", self.initial_clearance, 0.0, 10.0)?;
        for (i, q) in self.initial_joints.iter().enumerate() {
            in_range(&format!("initial_joints[{i}]"), *q, -3.2, 3.2)?;
        }
        Ok(())
    }
}
