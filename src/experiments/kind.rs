//! The paper's four experiments by name.

use serde::{Deserialize, Serialize};

/// One of the paper's experiments (section V), named as on the command line, in run ids and in
/// `summary.json`.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Hash,
    PartialOrd,
    Ord,
    Serialize,
    Deserialize,
    clap::ValueEnum,
)]
#[serde(rename_all = "lowercase")]
#[value(rename_all = "lowercase")]
pub enum ExperimentKind {
    /// A: reference tracking.
    Tracking,
    /// B: disturbance rejection.
    Disturbance,
    /// C: stability (fall probability vs impulse).
    Stability,
    /// D: robustness (learning without initialisation).
    Robustness,
}

impl ExperimentKind {
    /// All four, in the paper's order.
    pub const ALL: [ExperimentKind; 4] = [
        ExperimentKind::Tracking,
        ExperimentKind::Disturbance,
        ExperimentKind::Stability,
        ExperimentKind::Robustness,
    ];

    /// The lowercase name.
    pub fn name(self) -> &'static str {
        match self {
            ExperimentKind::Tracking => "tracking",
            ExperimentKind::Disturbance => "disturbance",
            ExperimentKind::Stability => "stability",
            ExperimentKind::Robustness => "robustness",
        }
    }
}

impl std::fmt::Display for ExperimentKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
