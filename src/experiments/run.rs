//! Runs one experiment for one (approximator, rule, seed) given by name: what the command line
//! and the sweep call.

use super::disturbance::DisturbanceProtocol;
use super::error::ExperimentError;
use super::experiment::{RunContext, RunLearner};
use super::robustness::RobustnessProtocol;
use super::settings::Settings;
use super::stability::StabilityProtocol;
use super::sweep::RunSpec;
use super::tracking::TrackingProtocol;
use crate::approx::ApproxKind;
use crate::config::ConfigError;
use crate::control::learner::{FootstepLearner, InputGrid, LearnerConfig, LearnerError};
use crate::experiments::summary::Summary;
use crate::rules::RuleConfig;
use std::path::Path;

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

/// Runs `spec` with `settings`, writes its figures and CSV into `dir` and returns its summary
/// (the caller writes `summary.json`).
pub fn run_spec(
    spec: &RunSpec,
    dir: &Path,
    settings: &Settings,
    protocols: &Protocols,
) -> Result<Summary, ExperimentError> {
    let approx: ApproxKind = spec.approx.parse().map_err(ExperimentError::Invalid)?;
    let rule = RuleConfig::from(spec.rule);
    rule.validate()
        .map_err(|e| ExperimentError::Invalid(e.to_string()))?;
    let bounds = InputGrid::default()
        .input_box()
        .map_err(|e| ExperimentError::Invalid(e.to_string()))?;
    let prototype = approx
        .build(&bounds)
        .map_err(|e| ExperimentError::Invalid(e.to_string()))?;
    let build = |config: LearnerConfig| -> Result<RunLearner, LearnerError> {
        // The rule config was validated above, so building it cannot fail.
        let r = rule.build().expect("validated rule config");
        FootstepLearner::new(prototype.clone(), r, config)
    };
    let ctx = RunContext {
        settings,
        protocols,
        seed: spec.seed,
        learner: &build,
    };
    let result = spec.experiment.experiment().run(&ctx, dir)?;
    Ok(Summary {
        approx: spec.approx.clone(),
        rule: spec.rule,
        seed: spec.seed,
        result,
    })
}
