//! The protocols of the paper's experiments, one section of the config file.

use super::disturbance::DisturbanceProtocol;
use super::robustness::RobustnessProtocol;
use super::stability::StabilityProtocol;
use super::tracking::TrackingProtocol;
use crate::config::ConfigError;

/// Protocols of every experiment (defaults: the paper's).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Protocols {
    /// Experiment A.
    pub tracking: TrackingProtocol,
    /// Experiment B.
    pub disturbance: DisturbanceProtocol,
    /// Experiment C.
    pub stability: StabilityProtocol,
    /// Experiment D.
    pub robustness: RobustnessProtocol,
}

impl Protocols {
    /// Checks every protocol; errors name the field from the top of the config file
    /// (`protocols.stability.pushes`).
    pub fn validate(&self) -> Result<(), ConfigError> {
        fn within(name: &'static str) -> impl Fn(ConfigError) -> ConfigError {
            move |e| e.within(&format!("protocols.{name}"))
        }
        self.tracking.validate().map_err(within("tracking"))?;
        self.disturbance.validate().map_err(within("disturbance"))?;
        self.stability.validate().map_err(within("stability"))?;
        self.robustness.validate().map_err(within("robustness"))
    }
}
