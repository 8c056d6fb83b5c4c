//! The paper's four experiments, A-D in the paper's order: the suite only collects; each
//! experiment lives in its own file.

use super::disturbance::Disturbance;
use super::experiment::Experiment;
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
