//! The trial harness every experiment shares: the trial loop and its observers, the settings,
//! protocols and schedules, push options, and the analyses of a trial's log (fall causes, the
//! catch step's reach, aligned recoveries, paired controllers), and what a replay needs.

pub mod aligned;
pub mod catch_step;
pub mod compare;
pub mod fall_causes;
pub mod footstep_env;
pub mod protocol;
pub(crate) mod push_options;
pub mod replay_plan;
pub mod robot_setup;
pub mod schedule;
pub mod settings;
pub mod trial;
