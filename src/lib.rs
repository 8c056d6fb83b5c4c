//! # steplearn
//!
//! Online learning of foot placement for a balancing biped, after Missura & Behnke, "Online
//! Learning of Foot Placement for Balanced Bipedal Walking".
//!
//! ```
//! use steplearn::approx::{FunctionApproximator, Lwpr, LwprConfig};
//! use steplearn::control::learner::{FootstepLearner, LearnerConfig, LearnerInput};
//! use steplearn::rules::{PendulumCart, StepOutcome};
//!
//! // The paper's learner: LWPR over (theta_E, theta_E_dot, F_R), trained with eq. (5)-(6).
//! let lwpr = Lwpr::new(LwprConfig::new(3, 1).norm_in(vec![0.5, 3.0, 0.15]))?;
//! let mut learner = FootstepLearner::new(lwpr, PendulumCart::default(), LearnerConfig::default())?;
//!
//! // Every control tick of a step: the offset dF added to the Capture Step footstep.
//! for tick in 0..50 {
//!     let theta_e = 0.001 * tick as f64;
//!     let df = learner.query(LearnerInput::new(theta_e, 0.1, 0.1))?;
//!     assert_eq!(df, 0.0); // nothing learned yet
//! }
//! // At touch-down the robot leaned forward and stepped 2 cm short: G > 0, step longer.
//! learner.touch_down(&StepOutcome { theta_e: 0.05, theta_e_dot: 0.1, f_e: -0.02, f_r: 0.1 })?;
//! assert!(learner.query(LearnerInput::new(0.025, 0.1, 0.1))? > 0.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! - [`approx`]: online function approximators behind [`approx::FunctionApproximator`].
//! - [`rules`]: learning rules behind [`rules::LearningRule`].
//! - [`control`]: state estimation, Capture Step control, step motion generation, the learner.
//! - [`sim`]: the humanoid in rapier3d.
//! - [`experiments`]: the trial harness, the paper's protocols, sweeps.
//! - [`report`]: CSV, `summary.json` and SVG figures.
#![warn(missing_docs)]

pub mod approx;
pub mod config;
pub mod control;
pub mod experiments;
mod names;
pub mod report;
pub mod rules;
pub mod sim;
