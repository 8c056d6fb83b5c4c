//! The experiments, one file each: the paper's four, A-D in the paper's order, and those
//! beyond the paper. The suite collects them; adding one is a file here, its `mod` line and
//! one line in [`paper()`] or [`beyond`]. [`reproduction`] is the paper's reproduction over its
//! four: their names, the main job's claims and the ablation table.

pub mod disturbance;
pub mod omnidirectional;
pub mod reproduction;
pub mod robustness;
pub mod stability;
pub mod tracking;

use crate::experiments::Experiment;
use disturbance::Disturbance;
use omnidirectional::Omnidirectional;
use robustness::Robustness;
use stability::Stability;
use std::sync::Arc;
use tracking::Tracking;

/// The paper's experiments `tracking`, `disturbance`, `stability`, `robustness`.
pub fn paper() -> Vec<Arc<dyn Experiment>> {
    vec![
        Arc::new(Tracking),
        Arc::new(Disturbance),
        Arc::new(Stability),
        Arc::new(Robustness),
    ]
}

/// The experiments beyond the paper: `omnidirectional`.
pub fn beyond() -> Vec<Arc<dyn Experiment>> {
    vec![Arc::new(Omnidirectional)]
}

/// Every built-in experiment: [`paper`] then [`beyond`] (what `Registry::builtin` registers and
/// what a config file without a registry is checked against).
pub fn builtin() -> Vec<Arc<dyn Experiment>> {
    paper().into_iter().chain(beyond()).collect()
}
