//! What the research probes share: reading a bench directory's run summaries, and running the
//! model beside a learner on the same trial.

use std::path::{Path, PathBuf};
use steplearn::bench::Registry;
use steplearn::control::{FootstepPolicy, StepReports};
use steplearn::control::{LearnSet, PerParameter};
use steplearn::control::{LearnerError, LearnerInput};
use steplearn::experiments::RunContext;
use steplearn::experiments::RunStepLearner;
use steplearn::experiments::config_file::{ConfigFile, ConfigFileError};
use steplearn::experiments::settings::Settings;
use steplearn::experiments::trial::{Observer, TrialSetup, run_trial};
use steplearn::rules::StepOutcome;

/// The config of `--config FILE` (`steplearn config` format), or the defaults without one.
pub fn config_file(config: Option<&Path>) -> Result<ConfigFile, ConfigFileError> {
    Ok(match config {
        Some(path) => ConfigFile::load(path)?,
        None => ConfigFile::default(),
    })
}

/// The settings of `--config FILE` ([`config_file`]).
pub fn settings(config: Option<&Path>) -> Result<Settings, ProbeError> {
    Ok(config_file(config)?.settings)
}

/// The learner of `set` as `steplearn experiment` builds it for `config` and `seed`: the
/// registry's `lwpr` with the config's LWPR settings and `pendulum-cart`.
pub fn builtin_learner(
    config: &ConfigFile,
    seed: u64,
    set: LearnSet,
) -> Result<RunStepLearner, Box<dyn std::error::Error>> {
    let settings = &config.settings;
    let components = Registry::builtin().components("lwpr", "pendulum-cart", &settings.lwpr)?;
    let ctx = RunContext {
        settings,
        protocols: &config.protocols,
        seed,
        approx: "lwpr",
        rule: "pendulum-cart",
        components: &components,
    };
    Ok(ctx.make_learner_of(set)?)
}

/// The error a probe's parallel part returns.
pub type ProbeError = Box<dyn std::error::Error + Send + Sync>;

/// Runs `setup` for the model (no policy) and for the policy `make` builds, in parallel, each
/// watched by a fresh `O`; returns the two observers (model, learned).
pub fn model_and_learned<O: Observer + Default + Send>(
    setup: &TrialSetup,
    make: impl FnOnce() -> Result<Box<dyn FootstepPolicy>, ProbeError> + Send,
) -> Result<(O, O), String> {
    let watch = |policy: Option<&mut dyn FootstepPolicy>| -> Result<O, ProbeError> {
        let mut o = O::default();
        run_trial(setup, policy, &mut [&mut o])?;
        Ok(o)
    };
    let (model, learned) = rayon::join(
        || watch(None),
        || {
            let mut policy = make()?;
            watch(Some(policy.as_mut()))
        },
    );
    Ok((
        model.map_err(|e| e.to_string())?,
        learned.map_err(|e| e.to_string())?,
    ))
}

/// The `summary.json` of every run directory in `dir` whose experiment is `experiment`, with
/// its path, in no particular order. Entries without a readable summary are skipped; a summary
/// that is not JSON is an error.
pub fn summaries(
    dir: &Path,
    experiment: &str,
) -> Result<Vec<(PathBuf, serde_json::Value)>, Box<dyn std::error::Error>> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path().join("summary.json");
        let Ok(text) = std::fs::read_to_string(&path) else {
            continue;
        };
        let json: serde_json::Value = serde_json::from_str(&text)?;
        if json["experiment"] == experiment {
            found.push((path, json));
        }
    }
    Ok(found)
}

/// A policy that does not learn: `offsets` maps the learner's inputs to the offsets of the
/// parameters in `learns`, and touch-downs and falls teach it nothing.
pub struct FixedPolicy<F> {
    /// The parameters it sets.
    pub learns: LearnSet,
    /// The offsets, from the inputs of every parameter.
    pub offsets: F,
}

impl<F> FootstepPolicy for FixedPolicy<F>
where
    F: FnMut(&PerParameter<LearnerInput>) -> PerParameter<f64>,
{
    fn learns(&self) -> LearnSet {
        self.learns
    }
    fn offsets(
        &mut self,
        inputs: &PerParameter<LearnerInput>,
    ) -> Result<PerParameter<f64>, LearnerError> {
        Ok((self.offsets)(inputs))
    }
    fn set_reach(&mut self, _reach: &PerParameter<[f64; 2]>) -> Result<(), LearnerError> {
        Ok(())
    }
    fn touch_down(
        &mut self,
        _outcomes: &PerParameter<StepOutcome>,
    ) -> Result<StepReports, LearnerError> {
        Ok(StepReports::default())
    }
    fn fall(&mut self, _outcomes: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError> {
        Ok(StepReports::default())
    }
    fn discard_step(&mut self) {}
}
