//! # steplearn
//!
//! Online learning of foot placement for a balancing biped, after Missura & Behnke, "Online
//! Learning of Foot Placement for Balanced Bipedal Walking".
//!
//! ```
//! use steplearn::control::{LegJoint, Side};
//! assert_eq!(LegJoint::Knee.index(Side::Right), 9);
//! ```
//!
//! - [`approx`]: online function approximators behind [`approx::FunctionApproximator`].
//! - [`rules`]: learning rules behind [`rules::LearningRule`].
//! - [`control`]: state estimation, Capture Step control, step motion generation, the learner.
//! - [`sim`]: the humanoid in rapier3d.
#![warn(missing_docs)]

pub mod approx;
pub mod control;
pub mod experiments;
pub mod report;
pub mod rules;
pub mod sim;
