//! Runs one experiment for one (approximator, rule, seed) given by name: what the command line
//! and the sweep call.

use super::ExperimentKind;
use super::error::ExperimentError;
use super::settings::Settings;
use super::stability::{self, ControllerPushes, StabilityProtocol};
use super::sweep::RunSpec;
use crate::approx::{AnyApproximator, ApproxKind, InputBox};
use crate::control::learner::{FootstepLearner, InputGrid};
use crate::report::summary::{ControllerFalls, Controllers, ExperimentResult, Summary};
use crate::rules::{LearningRule, RuleConfig};
use std::path::Path;

/// Protocols of every experiment (defaults: the paper's).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Protocols {
    /// Experiment C.
    pub stability: StabilityProtocol,
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
    let grid = InputGrid::default();
    let bounds = InputBox::new(grid.lo.to_array().to_vec(), grid.hi.to_array().to_vec())
        .map_err(|e| ExperimentError::Invalid(e.to_string()))?;
    let prototype = approx
        .build(&bounds)
        .map_err(|e| ExperimentError::Invalid(e.to_string()))?;
    let make = || -> Result<FootstepLearner<AnyApproximator, Box<dyn LearningRule>>, _> {
        // The rule config was validated above, so building it cannot fail.
        let r = rule.build().expect("validated rule config");
        FootstepLearner::new(prototype.clone(), r, settings.learner)
    };
    let result = match spec.experiment {
        ExperimentKind::Stability => {
            let p = &protocols.stability;
            let r = stability::run(settings, p, spec.seed, &make)?;
            r.write(dir, p.impulse)?;
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
            }
        }
        other => {
            return Err(ExperimentError::Invalid(format!(
                "experiment {other:?} is not implemented yet (only stability is)"
            )));
        }
    };
    Ok(Summary {
        approx: spec.approx.clone(),
        rule: spec.rule,
        seed: spec.seed,
        result,
    })
}
