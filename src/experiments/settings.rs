//! Settings shared by every experiment: the robot, the walker, the learner, and how long to run.

use super::schedule::{Push, PushPlan, ReferenceSchedule};
use super::trial::TrialSetup;
use crate::config::{self, ConfigError};
use crate::control::learner::{LearnerConfig, LearnerError};
use crate::control::walker::{FootstepPolicy, WalkerConfig, WalkerMode};
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
    /// The learner.
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
/// [`FootstepLearner`](crate::control::learner::FootstepLearner), a
/// [`StepLearner`](crate::control::step_learner::StepLearner) or any other policy.
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
