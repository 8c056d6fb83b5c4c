//! Settings shared by every experiment: the robot, the walker, the learner, and how long to run.

use crate::approx::{AnyApproximator, ApproxError, ApproxKind, InputBox, Lwpr, LwprConfig};
use crate::config::{self, ConfigError};
use crate::control::{FootstepPolicy, WalkerConfig, WalkerMode};
use crate::control::{InputGrid, LearnerConfig, LearnerError};
use crate::experiments::schedule::{Push, PushPlan, ReferenceSchedule};
use crate::experiments::trial::TrialSetup;
use crate::sim::SimConfig;
use serde::{Deserialize, Serialize};

/// Everything an experiment needs besides its own protocol.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Settings {
    /// The robot and physics.
    pub sim: SimConfig,
    /// The walker (its mode is set by each experiment).
    pub walker: WalkerConfig,
    /// The learner. A partial table, at any depth, keeps [`LearnerConfig::default`]'s values
    /// for the keys it leaves out.
    #[serde(deserialize_with = "learner_over_default")]
    pub learner: LearnerConfig,
    /// Scale of every experiment's length in (0, 1]: 1 is the paper's protocol; `--quick`
    /// uses a fraction for a fast look.
    pub scale: f64,
    /// A push counts as absorbed if no fall follows within this time (s).
    pub push_window_s: f64,
    /// Standing time after a reset before walking resumes (s). Default 0: the reset robot is
    /// in its initial pose, so walking resumes exactly as a trial starts; after standing still
    /// for 1 s the Capture Step walker failed to start at 0.2 m steps (a backward first step
    /// and a fall, again after every reset).
    pub recovery_s: f64,
    /// Walking time after a reset before a push that the fall delayed is delivered (s).
    pub resettle_s: f64,
    /// The built-in `lwpr` approximator's settings, `[settings.lwpr]` (absent: its defaults,
    /// and left out of a written config so that a default run's identity is unchanged).
    #[serde(skip_serializing_if = "LwprSettings::is_default")]
    pub lwpr: LwprSettings,
}

/// `[settings.lwpr]`: the settings of the built-in `lwpr` approximator, each key one
/// [`LwprConfig`] field (same name, same meaning and range), read through `LwprConfig`'s own
/// serde over the built-in values ([`ApproxKind::lwpr_config`]); a key left out keeps the
/// built-in value. `n_in`, `n_out` and `norm_in` are not keys: they follow from the learner's
/// input box (`norm_in` is its half-widths); `init_d` is a number, the spherical initial metric
/// `init_d * I`, and `norm_out` one factor for every output.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct LwprSettings(toml::Table);

/// `LwprConfig` fields that follow from the input box.
const DERIVED: [&str; 3] = ["n_in", "n_out", "norm_in"];

impl LwprSettings {
    /// Whether no key is set (the built-in settings).
    pub fn is_default(&self) -> bool {
        self.0.is_empty()
    }

    /// The built-in LWPR's settings over `bounds` ([`ApproxKind::lwpr_config`]) with these
    /// keys applied; the error names the key (`max_rfs: invalid type ...`).
    pub fn config(&self, bounds: &InputBox) -> Result<LwprConfig, ConfigError> {
        let base = ApproxKind::lwpr_config(bounds);
        let internal = |e: &dyn std::fmt::Display| ConfigError::new("", e.to_string());
        let mut table = toml::Table::try_from(&base).map_err(|e| internal(&e))?;
        let mut keys: Vec<String> = table
            .keys()
            .filter(|k| !DERIVED.contains(&k.as_str()))
            .cloned()
            .collect();
        if !keys.iter().any(|k| k == "max_rfs") {
            keys.push("max_rfs".into());
        }
        for (key, value) in &self.0 {
            if !keys.contains(key) {
                return Err(ConfigError::new(
                    key.as_str(),
                    format!("unknown field `{key}`, expected one of {}", keys.join(", ")),
                ));
            }
            let number = || match value {
                toml::Value::Float(v) => Ok(*v),
                toml::Value::Integer(v) => Ok(*v as f64),
                other => Err(ConfigError::new(
                    key.as_str(),
                    format!("must be a number, got {other}"),
                )),
            };
            let value = match key.as_str() {
                "init_d" => toml::Value::try_from(base.clone().init_d(number()?).init_d)
                    .map_err(|e| internal(&e))?,
                "norm_out" => {
                    toml::Value::try_from(vec![number()?; base.n_out]).map_err(|e| internal(&e))?
                }
                _ => value.clone(),
            };
            table.insert(key.clone(), value);
        }
        serde_path_to_error::deserialize(toml::Value::Table(table))
            .map_err(|e| ConfigError::new(e.path().to_string(), e.inner().to_string()))
    }

    /// A fresh, untrained built-in LWPR over `bounds` with these settings (what the built-in
    /// `lwpr` factory builds when the settings are given to it).
    pub fn build(&self, bounds: &InputBox) -> Result<AnyApproximator, ApproxError> {
        let config = self
            .config(bounds)
            .map_err(|e| ApproxError::config("settings.lwpr", e.to_string()))?;
        Lwpr::new(config).map(AnyApproximator::Lwpr)
    }

    /// Checks every key as [`Lwpr::new`] does, over the learner's input box; the error names
    /// the key (`max_rfs: must be at least 1`).
    pub fn validate(&self) -> Result<(), ConfigError> {
        let bounds = InputGrid::default()
            .input_box()
            .map_err(|e| ConfigError::new("", e.to_string()))?;
        Lwpr::new(self.config(&bounds)?)
            .map(drop)
            .map_err(|e| match e {
                ApproxError::InvalidConfig { param, reason } => ConfigError::new(param, reason),
                other => ConfigError::new("", other.to_string()),
            })
    }
}

/// A `[settings.learner]` table over the learner's defaults.
fn learner_over_default<'de, D: serde::Deserializer<'de>>(d: D) -> Result<LearnerConfig, D::Error> {
    config::patch(&LearnerConfig::default(), d)
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            sim: SimConfig::default(),
            walker: WalkerConfig::new(WalkerMode::CaptureStep),
            learner: LearnerConfig::default(),
            scale: 1.0,
            push_window_s: 3.0,
            recovery_s: 0.0,
            resettle_s: 2.0,
            lwpr: LwprSettings::default(),
        }
    }
}

impl Settings {
    /// Checks every value: the experiment-level numbers and the sim, walker and learner
    /// configs. Errors name the field from the top of the config file (`settings.scale`).
    pub fn validate(&self) -> Result<(), ConfigError> {
        self.validate_inner().map_err(|e| e.within("settings"))
    }

    fn validate_inner(&self) -> Result<(), ConfigError> {
        config::ensure(
            self.scale.is_finite() && self.scale > 0.0 && self.scale <= 1.0,
            "scale",
            || format!("must be in (0, 1], got {}", self.scale),
        )?;
        config::positive("push_window_s", self.push_window_s)?;
        config::non_negative("recovery_s", self.recovery_s)?;
        config::non_negative("resettle_s", self.resettle_s)?;
        self.sim
            .validate()
            .map_err(|e| ConfigError::new("sim", e.to_string()))?;
        self.walker.validate().map_err(|e| e.within("walker"))?;
        self.lwpr.validate().map_err(|e| e.within("lwpr"))?;
        self.learner
            .validate()
            .map_err(|e| ConfigError::new("learner", e.to_string()))
    }

    /// `n` scaled by [`Settings::scale`], at least `min`.
    pub fn scaled(&self, n: usize, min: usize) -> usize {
        ((n as f64 * self.scale).round() as usize).max(min)
    }

    /// A trial of `mode` with these settings.
    pub fn trial(
        &self,
        mode: WalkerMode,
        reference: ReferenceSchedule,
        pushes: Vec<Push>,
        push_direction: [f64; 3],
        duration_s: f64,
    ) -> TrialSetup {
        TrialSetup {
            lateral_reference: None,
            sim: self.sim.clone(),
            walker: WalkerConfig {
                mode,
                ..self.walker
            },
            reference,
            pushes,
            push_direction,
            push_window_s: self.push_window_s,
            recovery_s: self.recovery_s,
            resettle_s: self.resettle_s,
            duration_s,
            stop_after_last_push_s: None,
        }
    }

    /// A trial with pushes drawn from `plan`, long enough to deliver them all even if falls
    /// delay them, ending one push window after the last push.
    pub fn push_trial(
        &self,
        mode: WalkerMode,
        f_r: f64,
        plan: &PushPlan,
        seed: u64,
        push_direction: [f64; 3],
    ) -> TrialSetup {
        let pushes = plan.draw(seed);
        // Falls cost recovery time and delay later pushes: leave room for them.
        let slack = plan.count as f64 * (self.recovery_s + self.resettle_s + self.push_window_s);
        let end = pushes.last().map_or(plan.settle, |p| p.time) + self.push_window_s + slack;
        TrialSetup {
            stop_after_last_push_s: Some(self.push_window_s),
            ..self.trial(
                mode,
                ReferenceSchedule::constant(f_r),
                pushes,
                push_direction,
                end,
            )
        }
    }
}

/// Builds a fresh learner for one run (each controller of an experiment gets its own): a
/// [`FootstepLearner`](crate::control::FootstepLearner), a
/// [`StepLearner`](crate::control::StepLearner) or any other policy.
pub trait LearnerFactory {
    /// The policy it builds.
    type Policy: FootstepPolicy;
    /// A new, untrained learner.
    fn make(&self) -> Result<Self::Policy, LearnerError>;
}

impl<P, F> LearnerFactory for F
where
    P: FootstepPolicy,
    F: Fn() -> Result<P, LearnerError>,
{
    type Policy = P;
    fn make(&self) -> Result<P, LearnerError> {
        self()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every table path of `v` (dotted, from the top).
    fn tables(v: &toml::Value, at: &str, out: &mut Vec<String>) {
        if let toml::Value::Table(t) = v {
            for (k, child) in t {
                if child.is_table() {
                    let path = if at.is_empty() {
                        format!("\"{k}\"")
                    } else {
                        format!("{at}.\"{k}\"")
                    };
                    out.push(path.clone());
                    tables(child, &path, out);
                }
            }
        }
    }

    /// A table that a config file gives but leaves empty changes nothing, at any depth: each
    /// key left out keeps the settings' own default.
    #[test]
    fn an_empty_or_partial_table_keeps_the_settings_defaults() {
        let defaults = Settings::default();
        let value = toml::Value::try_from(&defaults).unwrap();
        let mut paths = Vec::new();
        tables(&value, "", &mut paths);
        assert!(paths.iter().any(|p| p == "\"learner\""), "{paths:?}");
        assert!(paths.len() >= 6, "{paths:?}");
        for path in &paths {
            let parsed: Settings =
                toml::from_str(&format!("[{path}]\n")).unwrap_or_else(|e| panic!("[{path}]: {e}"));
            assert_eq!(parsed, defaults, "an empty [{path}] changed the settings");
        }
        let partial: Settings =
            toml::from_str("[learner]\nlearn = [\"step-x\", \"step-time\"]\n").unwrap();
        assert_eq!(partial.learner.dead_zone, defaults.learner.dead_zone);
        assert_eq!(partial.learner.learn.iter().count(), 2);
    }
}
