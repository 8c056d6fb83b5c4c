//! The paper's suite: its four experiments by name ([`ExperimentKind`]), the main job that runs
//! them and checks the paper's claims ([`reproduce`]), and the ablation table of a sweep over
//! approximators and rules ([`ablation`]). Everything here is about the paper's four; the
//! harness, the records and the other experiments know none of them by name.

pub mod ablation;
pub(crate) mod kind;
pub mod reproduce;

pub use kind::ExperimentKind;
