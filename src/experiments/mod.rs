//! The paper's experiments (section V), generic over approximator and learning rule, and the
//! harness that runs and sweeps them.

pub mod aligned;
pub mod schedule;
