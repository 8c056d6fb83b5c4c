//! The paper's four experiments, A-D in the paper's order, and those beyond the paper: the
//! suite only collects; each experiment lives in its own file.

use super::disturbance::Disturbance;
use super::experiment::Experiment;
use super::omnidirectional::Omnidirectional;
use super::robustness::Robustness;
use super::stability::Stability;
use super::tracking::Tracking;
use std::sync::Arc;

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
