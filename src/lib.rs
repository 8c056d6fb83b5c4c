//! # steplearn
//!
//! Online learning of foot placement for a balancing biped, after Missura & Behnke, "Online
//! Learning of Foot Placement for Balanced Bipedal Walking".
//!
//! ```
//! use steplearn::prelude::*;
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
//! - [`prelude`]: the names most programs need, in one import.
//! - [`approx`]: online function approximators behind [`approx::FunctionApproximator`].
//! - [`rules`]: learning rules behind [`rules::LearningRule`].
//! - [`robot`]: the robot interface (sensors, joint targets, legs, leg geometry).
//! - [`control`]: state estimation, Capture Step control, step motion generation, the learner.
//! - `sim` (feature `sim`): the humanoid in rapier3d.
//! - `experiments` (feature `experiments`): the trial harness, the paper's protocols, sweeps.
//! - `bench` (feature `experiments`): the registry of approximators, rules and experiments by
//!   name, and the bench that runs any selection into a leaderboard.
//! - `cli` (feature `cli`): the `steplearn` command line over any registry (`main_with`).
//! - `report` (feature `experiments`): CSV, `summary.json` and SVG figures.
//!
//! ## Features
//! The default feature `cli` gives everything, the `steplearn` binary included. With
//! `default-features = false` the crate is the learning layer alone (approximators, rules and
//! the control stack with the learner), without rapier3d, plotters, clap, indicatif or rayon:
//! `sim` adds the humanoid, `experiments` the harness and reports.
#![warn(missing_docs)]

pub mod approx;
pub mod atomic_file;
#[cfg(feature = "experiments")]
pub mod bench;
#[cfg(feature = "cli")]
pub mod cli;
pub mod config;
pub mod control;
#[cfg(feature = "experiments")]
pub mod experiments;
mod names;
pub use names::Named;
pub mod prelude;
#[cfg(feature = "experiments")]
pub mod replay;
#[cfg(feature = "experiments")]
pub mod report;
pub mod robot;
pub mod rules;
#[cfg(feature = "sim")]
pub mod sim;
pub mod stats;
