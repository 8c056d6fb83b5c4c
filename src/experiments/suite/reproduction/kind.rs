//! The paper's four experiments by name.

/// One of the paper's experiments (section V), named as on the command line, in run ids and
/// in `summary.json`, in the paper's order.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Hash,
    PartialOrd,
    Ord,
    serde::Serialize,
    serde::Deserialize,
    strum::Display,
    strum::IntoStaticStr,
    strum::VariantArray,
)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
#[strum(serialize_all = "kebab-case")]
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
