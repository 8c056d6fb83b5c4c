//! The paper's experiments (section V), generic over approximator and learning rule, and the
//! harness that runs and sweeps them.

pub mod aligned;
mod error;
pub mod settings;
pub mod stability;
pub mod trial;
mod kind;
pub mod schedule;
pub mod sweep;

pub use error::ExperimentError;
pub use kind::ExperimentKind;
