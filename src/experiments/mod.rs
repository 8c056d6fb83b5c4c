//! The paper's experiments (section V), generic over approximator and learning rule, and the
//! harness that runs and sweeps them.

pub mod aligned;
mod kind;
pub mod schedule;
pub mod sweep;

pub use kind::ExperimentKind;
