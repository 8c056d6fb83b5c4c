//! The open bench: any registered approximator x rule x experiment x seed, run through one
//! runner (resumable, sharded, bit-identical at any thread count), reported as a leaderboard
//! with paired verdicts against the model and against a baseline combination.
//!
//! ```no_run
//! use steplearn::bench::{Bench, Registry};
//! use steplearn::approx::{Grid, GridConfig, InputBox};
//! use steplearn::rules::BalanceOnly;
//!
//! let registry = Registry::builtin()
//!     .approximator("coarse-grid", |bounds: &InputBox| {
//!         Grid::new(GridConfig::new(bounds.clone(), vec![3, 3, 3], 1))
//!     })
//!     .rule("my-balance", || BalanceOnly);
//! let report = Bench::new(&registry)
//!     .approximators(["coarse-grid", "lwpr"])
//!     .rules(["my-balance", "pendulum-cart"])
//!     .experiments(["robustness", "stability"])
//!     .seeds(2)
//!     .scale(0.1)
//!     .out("results/mine")
//!     .run()?;
//! println!("{}", report.leaderboard.to_markdown());
//! # Ok::<(), steplearn::bench::BenchError>(())
//! ```

mod error;
mod leaderboard;
mod registry;
mod robots;
mod runner;

pub use error::BenchError;
pub use leaderboard::{Combination, Comparison, LEADERBOARD_FILES, Leaderboard, LeaderboardRow};
pub use registry::{RESULTS_FORMAT, ROBOT_RULES, Registry, RegistryRunner};
pub use robots::{RobotColumn, RobotLeaderboard};
pub use runner::{Bench, Report};
