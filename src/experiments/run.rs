//! Runs one experiment for one (approximator, rule, seed) given by name: what the command line
//! and the sweep call.

use super::ExperimentKind;
use super::disturbance::{self, DisturbanceProtocol};
use super::error::ExperimentError;
use super::robustness::{self, RobustnessProtocol};
use super::settings::Settings;
use super::stability::{self, ControllerPushes, StabilityProtocol};
use super::sweep::RunSpec;
use super::tracking::{self, TrackingProtocol};
use crate::approx::{AnyApproximator, ApproxKind};
use crate::config::ConfigError;
use crate::control::learner::{FootstepLearner, InputGrid, LearnerConfig, LearnerError, Prior};
use crate::report::summary::{
    ControllerFalls, Controllers, ExperimentResult, ModelLearned, Summary,
};
use crate::rules::{LearningRule, RuleConfig};
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
    let build = |config: LearnerConfig| -> Result<
        FootstepLearner<AnyApproximator, Box<dyn LearningRule>>,
        LearnerError,
    > {
        // The rule config was validated above, so building it cannot fail.
        let r = rule.build().expect("validated rule config");
        FootstepLearner::new(prototype.clone(), r, config)
    };
    let make = || build(settings.learner);
    let result = match spec.experiment {
        ExperimentKind::Stability => {
            let p = &protocols.stability;
            let r = stability::run(settings, p, spec.seed, &make)?;
            r.write(dir, p.impulse, p.direction)?;
            let falls = |c: &ControllerPushes| ControllerFalls {
                pushes: c.pushes.len() as u32,
                falls: c.falls() as u32,
                impulse_at_50pct_fall_ns: c.fall50.impulse_ns,
            };
            ExperimentResult::Stability {
                controllers: Controllers {
                    open_loop: falls(&r.open_loop),
                    model: falls(&r.model),
                    learned: falls(&r.learned),
                },
                fall_causes: r.fall_cause_counts(),
            }
        }
        ExperimentKind::Tracking => {
            let r = tracking::run(settings, &protocols.tracking, spec.seed, &make)?;
            r.write(dir)?;
            let (model, learned) = r.std_per_bin();
            ExperimentResult::Tracking {
                step_error_std_m: ModelLearned { model, learned },
                bin_s: protocols.tracking.bin_s,
            }
        }
        ExperimentKind::Disturbance => {
            let p = &protocols.disturbance;
            let r = disturbance::run(settings, p, spec.seed, &make)?;
            r.write(dir, p.f_r)?;
            ExperimentResult::Disturbance {
                return_time_s: ModelLearned {
                    model: r.model.return_time_s,
                    learned: r.learned.return_time_s,
                },
                max_tda_rad: ModelLearned {
                    model: r.model.max_tda_rad,
                    learned: r.learned.max_tda_rad,
                },
            }
        }
        ExperimentKind::Robustness => {
            // Not initialised: without the dF = 0 prior unless the protocol asks for it.
            let p = &protocols.robustness;
            let config = if p.learner_prior {
                settings.learner
            } else {
                LearnerConfig {
                    prior: Prior::none(),
                    ..settings.learner
                }
            };
            let r = robustness::run(settings, p, spec.seed, &|| build(config))?;
            r.write(dir)?;
            r.summary_result()
        }
    };
    Ok(Summary {
        approx: spec.approx.clone(),
        rule: spec.rule,
        seed: spec.seed,
        result,
    })
}
