//! The paper's reproduction, part of the suite: its four experiments by name
//! ([`ExperimentKind`]), the main job that runs them and checks the paper's claims
//! ([`reproduce`]), and the ablation table of a sweep over approximators and rules
//! ([`ablation`]). Only the suite knows the paper's four by name; the harness, the records, the
//! replay, the bench and the command line reach them through the `Experiment` trait.

pub mod ablation;
pub mod claims_table;
pub(crate) mod kind;
pub mod reproduce;

pub use kind::ExperimentKind;
