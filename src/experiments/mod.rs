//! The paper's experiments (section V), generic over approximator and learning rule, and the
//! harness that runs and sweeps them.

pub mod aligned;
pub mod catch_step;
pub mod claim;
pub mod compare;
pub mod config_file;
pub mod disturbance;
mod error;
pub mod experiment;
pub mod fall_causes;
pub mod index_page;
mod kind;
pub mod omnidirectional;
pub mod paired;
pub mod protocol;
pub mod reproduce;
pub mod robustness;
pub mod schedule;
pub mod settings;
pub mod stability;
pub mod suite;
pub mod summary;
pub mod sweep;
pub mod tracking;
pub mod trial;

pub use error::ExperimentError;
pub use kind::ExperimentKind;
