//! The paper's experiments (section V) and the machinery that runs many of them: the sweep
//! over approximator x rule x experiment x seed, sharding for clusters, and merging results.

mod kind;
pub mod sweep;

pub use kind::ExperimentKind;
