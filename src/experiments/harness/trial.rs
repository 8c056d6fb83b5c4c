//! One trial: the simulated humanoid, a walker and an optional learner, driven by a reference
//! schedule and a sequence of pushes. Every experiment is a configuration of [`run_trial`] plus
//! an analysis of its [`TrialLog`]; observers receive the same records as they happen (for
//! progress bars, CSV logs, checkpoints).
//!
//! Data flows one way each tick: `Humanoid::sensors` -> `Walker::tick` (estimator, controller,
//! learner, generator) -> `Humanoid::step`. After a fall the robot and the walker are reset and
//! the learner keeps what it learned (its unfinished step is discarded).

use crate::control::StepParameter;
use crate::control::for_robot::ScaledPolicy;
use crate::control::{FootstepPolicy, Tick, Walker, WalkerConfig, WalkerError};
use crate::experiments::schedule::{Push, ReferenceSchedule};
use crate::report::Fixed;
use crate::sim::{Fall, GroundTruth, Humanoid, SimConfig, SimError};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// What can stop a trial.
#[derive(Debug, Error)]
pub enum TrialError {
    /// The simulator failed (bad configuration, or the physics blew up).
    #[error("simulation: {0}")]
    Sim(#[from] SimError),
    /// The controller or learner failed.
    #[error("walker: {0}")]
    Walker(#[from] WalkerError),
    /// The trial's own settings are invalid.
    #[error("invalid trial: {0}")]
    Invalid(String),
}

/// How a trial runs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrialSetup {
    /// The robot and physics.
    pub sim: SimConfig,
    /// The walker.
    pub walker: WalkerConfig,
    /// The reference step size over trial time (falls do not rewind it).
    pub reference: ReferenceSchedule,
    /// The lateral reference F_R,y over trial time (m per step, positive to the left; see
    /// [`Walker::tick_2d`]); none: stepping in place laterally.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lateral_reference: Option<ReferenceSchedule>,
    /// Pushes in time order (trial time). A push due while the robot is getting up after a
    /// fall, or has not walked `resettle_s` since, is delayed until it has.
    pub pushes: Vec<Push>,
    /// Unit direction of every push in the world frame (x forward).
    pub push_direction: [f64; 3],
    /// A push counts as absorbed if the robot does not fall within this time after it (s).
    pub push_window_s: f64,
    /// Time to stand and start stepping after a reset before anything else happens (s).
    pub recovery_s: f64,
    /// Walking time after `recovery_s` before a delayed push is delivered (s): without it the
    /// pushes that falls delayed would hit the robot in its first step, and one fall would
    /// cause the next.
    #[serde(default)]
    pub resettle_s: f64,
    /// Length of the trial (s): its end at the latest.
    pub duration_s: f64,
    /// If set, the trial ends this long after the last push was delivered (and not before that
    /// push's window closed), even if `duration_s` leaves more time: push trials reserve time
    /// for the delays that falls cause and need not walk through what was not needed.
    #[serde(default)]
    pub stop_after_last_push_s: Option<f64>,
}

impl TrialSetup {
    fn validate(&self) -> Result<(), TrialError> {
        let positive = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(TrialError::Invalid(format!(
                    "{name} must be positive and finite, got {v}"
                )))
            }
        };
        positive("duration_s", self.duration_s)?;
        if let Some(tail) = self.stop_after_last_push_s
            && !(tail.is_finite() && tail >= 0.0)
        {
            return Err(TrialError::Invalid(format!(
                "stop_after_last_push_s must be >= 0 and finite, got {tail}"
            )));
        }
        positive("push_window_s", self.push_window_s)?;
        if !(self.resettle_s.is_finite() && self.resettle_s >= 0.0) {
            return Err(TrialError::Invalid(format!(
                "resettle_s must be >= 0, got {}",
                self.resettle_s
            )));
        }
        if !(self.recovery_s.is_finite() && self.recovery_s >= 0.0) {
            return Err(TrialError::Invalid(format!(
                "recovery_s must be >= 0, got {}",
                self.recovery_s
            )));
        }
        if !crate::experiments::schedule::is_unit_direction(&self.push_direction) {
            return Err(TrialError::Invalid(format!(
                "push_direction must be a unit vector, got {:?}",
                self.push_direction
            )));
        }
        for reference in std::iter::once(&self.reference).chain(&self.lateral_reference) {
            if reference.segments.is_empty()
                || reference
                    .segments
                    .iter()
                    .any(|(t, f)| !t.is_finite() || !f.is_finite())
            {
                return Err(TrialError::Invalid(
                    "a reference schedule needs at least one finite segment".into(),
                ));
            }
        }
        if self
            .pushes
            .iter()
            .any(|p| !(p.time.is_finite() && p.impulse.is_finite() && p.impulse >= 0.0))
            || self.pushes.windows(2).any(|w| w[0].time > w[1].time)
        {
            return Err(TrialError::Invalid(
                "pushes must be finite, non-negative and in time order".into(),
            ));
        }
        Ok(())
    }
}

/// A step that ended in a touch-down.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StepRecord {
    /// Time of the touch-down (s).
    pub time: f64,
    /// Reference step size F_R (m).
    pub f_r: f64,
    /// Measured step size F_hat (m).
    pub f_hat: f64,
    /// Trunk deviation angle theta_E at touch-down (rad).
    pub theta_e: f64,
    /// Its rate (rad/s).
    pub theta_e_dot: f64,
    /// The learned offset dF in force at touch-down (m).
    pub learned_offset: f64,
    /// The learning gain the learner applied at this touch-down (m of dF per unit of G; see
    /// [`crate::control::TouchDownReport::gain`]); `None` without a learner.
    #[serde(default)]
    pub learning_gain: Option<f64>,
    /// The approximator's response r at this touch-down: the share of the requested change
    /// its predictions moved under the full step, before the gain guard scaled it
    /// ([`crate::control::TouchDownReport::response`]); `None` without a learner.
    #[serde(default)]
    pub learning_response: Option<f64>,
}

impl StepRecord {
    /// Step size error F_E = F_hat - F_R (m).
    pub fn f_e(&self) -> f64 {
        self.f_hat - self.f_r
    }

    /// The step as the cells of a steps table (after its label column).
    pub fn cells(&self) -> StepCells {
        StepCells {
            time_s: Fixed(self.time),
            f_r_m: Fixed(self.f_r),
            f_hat_m: Fixed(self.f_hat),
            f_e_m: Fixed(self.f_e()),
            theta_e_rad: Fixed(self.theta_e),
            theta_e_dot_rad_s: Fixed(self.theta_e_dot),
            learned_offset_m: Fixed(self.learned_offset),
            learning_gain: self.learning_gain.map(Fixed),
            learning_response: self.learning_response.map(Fixed),
        }
    }
}

/// A [`StepRecord`] as CSV cells: the field names are the column names.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct StepCells {
    /// Touch-down time (s).
    pub time_s: Fixed<4>,
    /// Reference step F_R (m).
    pub f_r_m: Fixed<4>,
    /// Measured step F_hat (m).
    pub f_hat_m: Fixed<5>,
    /// Step error F_E (m).
    pub f_e_m: Fixed<5>,
    /// theta_E (rad).
    pub theta_e_rad: Fixed<5>,
    /// theta_E_dot (rad/s).
    pub theta_e_dot_rad_s: Fixed<5>,
    /// dF (m).
    pub learned_offset_m: Fixed<5>,
    /// The learning gain; empty without a learner.
    pub learning_gain: Option<Fixed<5>>,
    /// The approximator's response r; empty without a learner.
    pub learning_response: Option<Fixed<5>>,
}

/// The label column of a steps table: which controller took the step.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct ControllerCell<'a> {
    /// `model`, `learned`, `open_loop`, ...
    pub controller: &'a str,
}

/// A delivered push and whether the robot absorbed it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PushRecord {
    /// When it was delivered (s).
    pub time: f64,
    /// Its impulse (Ns).
    pub impulse: f64,
    /// Whether the robot fell within the push window.
    pub fell: bool,
}

/// A fall.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FallRecord {
    /// When it was detected (s).
    pub time: f64,
    /// What the simulator reported.
    pub fall: Fall,
    /// The learning gain of the update the learner made from the fall, if it learns from
    /// falls.
    #[serde(default)]
    pub learning_gain: Option<f64>,
}

/// Everything a trial recorded.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct TrialLog {
    /// Every touch-down.
    pub steps: Vec<StepRecord>,
    /// Every delivered push.
    pub pushes: Vec<PushRecord>,
    /// Every fall.
    pub falls: Vec<FallRecord>,
    /// Simulated time (s).
    pub sim_time_s: f64,
}

/// Receives a trial's records as they happen. Every method has an empty default.
pub trait Observer {
    /// After every control tick.
    fn on_tick(&mut self, _time: f64, _tick: &Tick) {}
    /// At every touch-down.
    fn on_step(&mut self, _step: &StepRecord) {}
    /// When a push's outcome is known.
    fn on_push(&mut self, _push: &PushRecord) {}
    /// At every fall (before the reset).
    fn on_fall(&mut self, _fall: &FallRecord) {}
    /// Whether this observer wants the simulator's ground truth every tick (for figures only:
    /// it costs a pass over the bodies, and control never sees it).
    fn wants_truth(&self) -> bool {
        false
    }
    /// The ground truth after [`Observer::on_tick`] of the same tick (trial time `time`), if
    /// [`Observer::wants_truth`].
    fn on_truth(&mut self, _time: f64, _truth: &GroundTruth) {}
}

/// Runs one trial. `policy` is the learner (none for the open-loop walker and the model).
pub fn run_trial(
    setup: &TrialSetup,
    policy: Option<&mut (dyn FootstepPolicy + '_)>,
    observers: &mut [&mut dyn Observer],
) -> Result<TrialLog, TrialError> {
    setup.validate()?;
    let mut robot = Humanoid::new(setup.sim.clone())?;
    // Another robot than the paper's: its gait scaled from the settings, and the learner kept
    // in the paper robot's units.
    let scale = robot.scale();
    let walker_config = if scale.is_one() {
        setup.walker
    } else {
        setup.walker.for_robot(&scale)
    };
    let mut walker = Walker::new(walker_config, robot.robot().leg_geometry())?;
    let mut scaled;
    let mut policy = match policy {
        Some(p) if !scale.is_one() => {
            scaled = ScaledPolicy::new(p, scale);
            Some(&mut scaled as &mut dyn FootstepPolicy)
        }
        other => other.map(|p| p as &mut dyn FootstepPolicy),
    };
    let mut log = TrialLog::default();
    let mut next_push = 0;
    // The push being watched: (record index in log.pushes, deadline).
    let mut watching: Option<(usize, f64)> = None;
    // Trial time = offset + robot time: a reset restarts the robot's clock at zero.
    let mut offset = 0.0;
    let mut ready_at = 0.0;
    let mut push_ready_at = 0.0;
    // The estimate and reference of the last walker tick: the step in progress that a fall
    // interrupts.
    let mut last_tick = None;

    while offset + robot.time() < setup.duration_s {
        let sensors = robot.sensors();
        let t = offset + sensors.time;
        if let (Some(tail), Some(last)) = (setup.stop_after_last_push_s, log.pushes.last())
            && next_push == setup.pushes.len()
            && watching.is_none()
            && t >= last.time + tail
        {
            break;
        }
        let f_r = setup.reference.at(t);
        let f_r_y = setup.lateral_reference.as_ref().map_or(0.0, |r| r.at(t));
        let tick = if t < ready_at && !log.falls.is_empty() {
            // Getting up after a fall: hold the standing pose.
            None
        } else {
            Some(walker.tick_2d(&sensors, [f_r, f_r_y], policy.as_deref_mut())?)
        };
        if let Some(tick) = &tick {
            last_tick = Some((tick.estimate, tick.f_r));
        }
        let targets = match &tick {
            Some(tick) => {
                for o in observers.iter_mut() {
                    o.on_tick(t, tick);
                }
                if let Some(s) = tick.step {
                    let record = StepRecord {
                        time: t,
                        f_r: s.f_r,
                        f_hat: s.f_e + s.f_r,
                        theta_e: s.theta_e,
                        theta_e_dot: s.theta_e_dot,
                        learned_offset: tick.learned_offset,
                        learning_gain: tick.learning.map(|r| r.gain),
                        learning_response: tick.learning.map(|r| r.response),
                    };
                    for o in observers.iter_mut() {
                        o.on_step(&record);
                    }
                    log.steps.push(record);
                }
                tick.targets
            }
            None => walker.halt_targets(),
        };
        if observers.iter().any(|o| o.wants_truth()) {
            let truth = robot.ground_truth();
            for o in observers.iter_mut().filter(|o| o.wants_truth()) {
                o.on_truth(t, &truth);
            }
        }

        if next_push < setup.pushes.len()
            && watching.is_none()
            && t >= setup.pushes[next_push].time
            && t >= push_ready_at
        {
            let p = setup.pushes[next_push];
            robot.push(setup.push_direction.map(|d| d * p.impulse))?;
            log.pushes.push(PushRecord {
                time: t,
                impulse: p.impulse,
                fell: false,
            });
            watching = Some((log.pushes.len() - 1, t + setup.push_window_s));
            next_push += 1;
        }

        robot.step(&targets)?;

        if let Some(fall) = robot.fall() {
            // The learner learns from the step in progress or forgets it (its setting).
            let mut learning_gain = None;
            if let Some(p) = policy.as_deref_mut() {
                match last_tick.take() {
                    Some((estimate, f_r)) => {
                        // The walker is as it was at that tick: it is reset below.
                        let outcomes = walker.outcomes_at(&estimate, f_r);
                        let reports = p.fall(&outcomes).map_err(WalkerError::from)?;
                        learning_gain = reports[StepParameter::StepX].map(|r| r.gain);
                    }
                    None => p.discard_step(),
                }
            }
            let record = FallRecord {
                time: offset + robot.time(),
                fall,
                learning_gain,
            };
            for o in observers.iter_mut() {
                o.on_fall(&record);
            }
            log.falls.push(record);
            if let Some((i, _)) = watching.take() {
                log.pushes[i].fell = true;
                for o in observers.iter_mut() {
                    o.on_push(&log.pushes[i]);
                }
            }
            offset += robot.time();
            robot.reset();
            walker.reset();
            ready_at = offset + setup.recovery_s;
            push_ready_at = ready_at + setup.resettle_s;
        } else if let Some((i, deadline)) = watching
            && offset + robot.time() >= deadline
        {
            watching = None;
            for o in observers.iter_mut() {
                o.on_push(&log.pushes[i]);
            }
        }
    }
    // A push still watched when the trial ends was not followed by a fall.
    if let Some((i, _)) = watching {
        for o in observers.iter_mut() {
            o.on_push(&log.pushes[i]);
        }
    }
    log.sim_time_s = offset + robot.time();
    Ok(log)
}
