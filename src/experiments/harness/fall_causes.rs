//! Why a walker fell: every fall of a push trial classified by what came before it.
//!
//! A [`FallCauseObserver`] rides along any trial and keeps a short event list: every
//! touch-down with the sagittal step the balance controller last commanded for the step that
//! ended there (`decision.step[0]`), and every fall with the command of the step in progress.
//! [`classify`] then combines these events with the trial log's pushes (delivery times and
//! outcomes) into one [`FallCause`] per fall:
//!
//! * falls with no push window open (no push delivered within the window before the fall, or
//!   the window already closed by an earlier fall), by the steps taken since the previous fall
//!   (or the trial's start):
//!   [`FallCause::NoPushOnRestart`] none at all (the robot fell starting again after a
//!   reset), [`FallCause::NoPushStepClamped`] at least one commanded at a step length limit,
//!   [`FallCause::NoPush`] otherwise (it fell walking, every step within range);
//! * [`FallCause::BeforeTouchDown`]: pushed, and fell before the next touch-down (the step in
//!   progress could not catch the push, or the catch step came too late);
//! * [`FallCause::CatchStepClamped`]: the catch step (the one that landed first after the
//!   push) was commanded at the limit of the generator's range
//!   ([`crate::control::motion::MotionConfig::step_x_range`]) or of the controller's
//!   `max_step_x`: the controller wanted a longer step than it could take;
//! * [`FallCause::LaterStepClamped`]: the catch step was within range but a later step before
//!   the fall was commanded at a limit;
//! * [`FallCause::TippedAfterCatchStep`]: at least one touch-down after the push, every step
//!   within range, and the robot still fell during a following step.
//!
//! Slips are not told apart: the observer sees the state estimate and the controller's
//! decisions, not the contact forces.

use crate::control::{FootstepPolicy, Tick, WalkerConfig};
use crate::experiments::trial::{
    FallRecord, Observer, PushRecord, StepRecord, TrialError, TrialLog, TrialSetup, run_trial,
};
use crate::report::Fixed;
use crate::robot::Side;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The cause of one fall (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FallCause {
    /// No push window open at the fall; walked at least one step since the previous fall,
    /// every one within the step length limits.
    NoPush,
    /// No push window open, and not one touch-down since the previous fall (or the start).
    NoPushOnRestart,
    /// No push window open, and a step since the previous fall commanded at a limit.
    NoPushStepClamped,
    /// Pushed, fell before the next touch-down.
    BeforeTouchDown,
    /// The catch step was commanded at a step length limit.
    CatchStepClamped,
    /// A step after the catch step was commanded at a step length limit.
    LaterStepClamped,
    /// Touched down after the push within range and still fell.
    TippedAfterCatchStep,
}

impl FallCause {
    /// Every cause, in report order.
    pub const ALL: [FallCause; 7] = [
        FallCause::NoPush,
        FallCause::NoPushOnRestart,
        FallCause::NoPushStepClamped,
        FallCause::BeforeTouchDown,
        FallCause::CatchStepClamped,
        FallCause::LaterStepClamped,
        FallCause::TippedAfterCatchStep,
    ];

    /// The snake_case name used in `summary.json` and the CSV files.
    pub fn name(self) -> &'static str {
        match self {
            FallCause::NoPush => "no_push",
            FallCause::NoPushOnRestart => "no_push_on_restart",
            FallCause::NoPushStepClamped => "no_push_step_clamped",
            FallCause::BeforeTouchDown => "before_touch_down",
            FallCause::CatchStepClamped => "catch_step_clamped",
            FallCause::LaterStepClamped => "later_step_clamped",
            FallCause::TippedAfterCatchStep => "tipped_after_catch_step",
        }
    }

    /// The cause named `name` ([`FallCause::name`]), if any.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|c| c.name() == name)
    }

    /// Whether a fall of this cause ended a push's window (the others came without one).
    pub fn after_push(self) -> bool {
        !matches!(
            self,
            FallCause::NoPush | FallCause::NoPushOnRestart | FallCause::NoPushStepClamped
        )
    }
}

/// The sagittal step limits a commanded step is compared with.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StepLimits {
    /// The motion generator's sagittal range [min, max] (m).
    pub range: [f64; 2],
    /// The controller's symmetric clamp |step_x| <= max_step_x (m).
    pub max_step_x: f64,
    /// A command this close to a limit counts as at the limit (m).
    pub tolerance: f64,
}

impl StepLimits {
    /// The limits of a walker configuration.
    pub fn of(walker: &WalkerConfig) -> Self {
        StepLimits {
            range: walker.motion.step_x_range,
            max_step_x: walker.capture_step.max_step_x,
            tolerance: 1e-6,
        }
    }

    /// Whether `step_x` reached a limit.
    pub fn at_limit(&self, step_x: f64) -> bool {
        let lo = self.range[0].max(-self.max_step_x);
        let hi = self.range[1].min(self.max_step_x);
        step_x >= hi - self.tolerance || step_x <= lo + self.tolerance
    }
}

/// What the observer saw, in time order.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum FallEvent {
    /// A touch-down at `time`; `step_x` is the last sagittal step commanded for the step that
    /// ended (none in open-loop mode, or right after a reset).
    TouchDown {
        /// Trial time (s).
        time: f64,
        /// The step's command `decision.step[0]` (m): of its last tick, or of the tick before
        /// the generator exchanged its legs where it did so ahead of the estimator's
        /// touch-down (then the controller already decided the next step).
        step_x: Option<f64>,
        /// The realised sagittal step, foot to foot, as the estimator measured it (m).
        realised: f64,
        /// The reference step F_R at the touch-down (m).
        f_r: f64,
    },
    /// A fall at `time`; `step_x` is the command of the step in progress (as for a
    /// touch-down).
    Fall {
        /// Trial time (s).
        time: f64,
        /// `decision.step[0]` of the last tick before the fall (m).
        step_x: Option<f64>,
    },
}

/// An [`Observer`] that records the events [`classify`] needs. Works with any walker mode.
#[derive(Debug, Clone, Default)]
pub struct FallCauseObserver {
    events: Vec<FallEvent>,
    last_step_x: Option<f64>,
    /// The controller's support foot at the last tick with a decision.
    support: Option<Side>,
    /// The command the swing foot was let go at, when the generator exchanged its legs before
    /// the estimator saw the touch-down (from then on the controller decides the next step).
    released: Option<Option<f64>>,
}

impl FallCauseObserver {
    /// A fresh observer.
    pub fn new() -> Self {
        Self::default()
    }

    /// The events so far.
    pub fn events(&self) -> &[FallEvent] {
        &self.events
    }
}

impl Observer for FallCauseObserver {
    fn on_tick(&mut self, time: f64, tick: &Tick) {
        // The decision of a touch-down tick is already for the next step; so is every
        // decision after the generator exchanged its legs ahead of the estimator's touch-down
        // (a step whose time ran out first): the step's command is the one its swing foot was
        // let go at.
        if let Some(step) = &tick.step {
            self.events.push(FallEvent::TouchDown {
                time,
                step_x: self.released.take().unwrap_or(self.last_step_x),
                realised: step.f_e + step.f_r,
                f_r: step.f_r,
            });
        }
        if let Some(d) = tick.decision {
            // The controller changed feet while the estimator still stands on the old one.
            let ahead = self
                .support
                .is_some_and(|s| s != d.support && tick.estimate.support == s);
            if ahead && tick.step.is_none() && self.released.is_none() {
                self.released = Some(self.last_step_x);
            }
            self.support = Some(d.support);
        }
        self.last_step_x = tick.decision.map(|d| d.step[0]);
    }

    fn on_step(&mut self, _step: &StepRecord) {}

    fn on_fall(&mut self, fall: &FallRecord) {
        self.events.push(FallEvent::Fall {
            time: fall.time,
            step_x: self.released.take().unwrap_or(self.last_step_x),
        });
        self.last_step_x = None;
        self.support = None;
    }
}

/// One classified fall.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ClassifiedFall {
    /// When it was detected (s).
    pub time: f64,
    /// Index in the trial's pushes of the push whose window it ended, if any.
    pub push: Option<usize>,
    /// Why.
    pub cause: FallCause,
}

/// Classifies every fall in `events` (time order) given the trial's delivered `pushes` (time
/// order, with their outcomes). A fall belongs to a push if that push is the last one
/// delivered before the fall, its outcome is `fell`, and no other fall came between them (the
/// trial closes a push's window at the first fall after it).
pub fn classify(
    events: &[FallEvent],
    pushes: &[PushRecord],
    limits: &StepLimits,
) -> Vec<ClassifiedFall> {
    let mut out = Vec::new();
    let mut previous_fall = f64::NEG_INFINITY;
    // Index in `events` just after the previous fall.
    let mut since = 0;
    let clamped = |s: &Option<f64>| s.is_some_and(|x| limits.at_limit(x));
    for (k, e) in events.iter().enumerate() {
        let FallEvent::Fall { time, step_x: _ } = *e else {
            continue;
        };
        let last_push = pushes.partition_point(|p| p.time <= time);
        let push = last_push
            .checked_sub(1)
            .filter(|&i| pushes[i].fell && pushes[i].time > previous_fall);
        // The commanded steps that touched down after `t0` and before this fall.
        let steps_after = |t0: f64| -> Vec<Option<f64>> {
            events[since..k]
                .iter()
                .filter_map(|e| match *e {
                    FallEvent::TouchDown {
                        time: t, step_x, ..
                    } if t > t0 => Some(step_x),
                    _ => None,
                })
                .collect()
        };
        let cause = match push {
            None => {
                let steps = steps_after(f64::NEG_INFINITY);
                if steps.is_empty() {
                    FallCause::NoPushOnRestart
                } else if steps.iter().any(clamped) {
                    FallCause::NoPushStepClamped
                } else {
                    FallCause::NoPush
                }
            }
            Some(i) => {
                let steps = steps_after(pushes[i].time);
                match steps.split_first() {
                    None => FallCause::BeforeTouchDown,
                    Some((catch, _)) if clamped(catch) => FallCause::CatchStepClamped,
                    Some((_, later)) if later.iter().any(clamped) => FallCause::LaterStepClamped,
                    Some(_) => FallCause::TippedAfterCatchStep,
                }
            }
        };
        out.push(ClassifiedFall { time, push, cause });
        previous_fall = time;
        since = k + 1;
    }
    out
}

/// Falls per cause, every cause present (zero where none), keyed by [`FallCause::name`].
pub fn count(falls: &[ClassifiedFall]) -> BTreeMap<String, u32> {
    let mut counts: BTreeMap<String, u32> = FallCause::ALL
        .iter()
        .map(|c| (c.name().to_string(), 0))
        .collect();
    for f in falls {
        *counts.entry(f.cause.name().to_string()).or_default() += 1;
    }
    counts
}

/// The cause of the fall that ended each push's window (`None` for absorbed pushes), in push
/// order.
pub fn cause_by_push(falls: &[ClassifiedFall], pushes: usize) -> Vec<Option<FallCause>> {
    let mut by_push = vec![None; pushes];
    for f in falls {
        if let Some(i) = f.push
            && i < pushes
        {
            by_push[i] = Some(f.cause);
        }
    }
    by_push
}

/// Runs `setup` with a [`FallCauseObserver`] and classifies every fall of the trial: the log
/// and its falls with their causes.
pub fn run_classified(
    setup: &TrialSetup,
    policy: Option<&mut (dyn FootstepPolicy + '_)>,
) -> Result<(TrialLog, Vec<ClassifiedFall>), TrialError> {
    run_classified_with(setup, policy).map(|(log, falls, _)| (log, falls))
}

/// [`run_classified`] that also returns the observer's events (for
/// [`crate::experiments::catch_step::catch_step_reach`]).
pub fn run_classified_with(
    setup: &TrialSetup,
    policy: Option<&mut (dyn FootstepPolicy + '_)>,
) -> Result<(TrialLog, Vec<ClassifiedFall>, Vec<FallEvent>), TrialError> {
    let mut observer = FallCauseObserver::new();
    let log = run_trial(setup, policy, &mut [&mut observer])?;
    let falls = classify(
        observer.events(),
        &log.pushes,
        &StepLimits::of(&setup.walker),
    );
    Ok((log, falls, observer.events))
}

/// One CSV row per push: controller, time (s), impulse (Ns), whether a fall followed and its
/// cause (empty where absorbed).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct PushRow<'a> {
    controller: &'a str,
    time_s: Fixed<4>,
    impulse_ns: Fixed<4>,
    fell: bool,
    fall_cause: &'a str,
}

/// The rows of one controller's `pushes` with the causes of its classified `falls`.
pub fn push_rows<'a>(
    controller: &'a str,
    pushes: &[PushRecord],
    falls: &[ClassifiedFall],
) -> Vec<PushRow<'a>> {
    pushes
        .iter()
        .zip(cause_by_push(falls, pushes.len()))
        .map(|(p, cause)| PushRow {
            controller,
            time_s: Fixed(p.time),
            impulse_ns: Fixed(p.impulse),
            fell: p.fell,
            fall_cause: cause.map_or("", FallCause::name),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIMITS: StepLimits = StepLimits {
        range: [-0.15, 0.45],
        max_step_x: 0.5,
        tolerance: 1e-6,
    };

    fn td(time: f64, x: f64) -> FallEvent {
        FallEvent::TouchDown {
            time,
            step_x: Some(x),
            realised: x,
            f_r: 0.0,
        }
    }

    fn fall(time: f64) -> FallEvent {
        FallEvent::Fall {
            time,
            step_x: Some(0.1),
        }
    }

    fn push(time: f64, fell: bool) -> PushRecord {
        PushRecord {
            time,
            impulse: 10.0,
            fell,
        }
    }

    #[test]
    fn limits_use_the_tighter_of_range_and_clamp() {
        assert!(LIMITS.at_limit(0.45));
        assert!(LIMITS.at_limit(0.6));
        assert!(!LIMITS.at_limit(0.44));
        assert!(LIMITS.at_limit(-0.15));
        assert!(!LIMITS.at_limit(-0.14));
        let tight = StepLimits {
            max_step_x: 0.3,
            ..LIMITS
        };
        assert!(tight.at_limit(0.3) && !tight.at_limit(0.29));
    }

    #[test]
    fn each_cause_from_a_synthetic_sequence() {
        let events = vec![
            // 1: a fall with no push at all.
            td(0.5, 0.0),
            fall(1.0),
            // 2: pushed at 2.0, fell before any touch-down.
            td(1.9, 0.0),
            fall(2.2),
            // 3: pushed at 4.0, catch step at the generator's maximum.
            td(4.3, 0.45),
            fall(4.6),
            // 4: pushed at 6.0, catch step in range, a later step at the minimum.
            td(6.3, 0.3),
            td(6.6, -0.15),
            fall(6.8),
            // 5: pushed at 8.0, every step in range.
            td(8.3, 0.3),
            td(8.6, 0.1),
            fall(8.9),
            // 6: pushed at 10.0 and absorbed; fell 5 s later: no push window open.
            td(10.3, 0.2),
            fall(15.0),
            // 7: fell again before a single step.
            fall(15.5),
            // 8: fell walking, a step at the limit, no push.
            td(15.8, 0.0),
            td(16.1, 0.45),
            fall(16.3),
        ];
        let pushes = vec![
            push(2.0, true),
            push(4.0, true),
            push(6.0, true),
            push(8.0, true),
            push(10.0, false),
        ];
        let c = classify(&events, &pushes, &LIMITS);
        let causes: Vec<FallCause> = c.iter().map(|f| f.cause).collect();
        assert_eq!(
            causes,
            [
                FallCause::NoPush,
                FallCause::BeforeTouchDown,
                FallCause::CatchStepClamped,
                FallCause::LaterStepClamped,
                FallCause::TippedAfterCatchStep,
                FallCause::NoPush,
                FallCause::NoPushOnRestart,
                FallCause::NoPushStepClamped,
            ]
        );
        assert_eq!(
            c.iter().map(|f| f.push).collect::<Vec<_>>(),
            [None, Some(0), Some(1), Some(2), Some(3), None, None, None]
        );
        for f in &c {
            assert_eq!(f.push.is_some(), f.cause.after_push());
            assert_eq!(FallCause::from_name(f.cause.name()), Some(f.cause));
        }
        // Counts cover every cause and sum to the falls.
        let n = count(&c);
        assert_eq!(n.len(), FallCause::ALL.len());
        assert_eq!(n.values().sum::<u32>() as usize, c.len());
        assert_eq!(n["no_push"], 2);
        assert_eq!(n["no_push_on_restart"], 1);
        assert_eq!(n["tipped_after_catch_step"], 1);
        // Each fell push has the cause of its fall, the absorbed one none.
        let by_push = cause_by_push(&c, pushes.len());
        assert_eq!(by_push[1], Some(FallCause::CatchStepClamped));
        assert_eq!(by_push[4], None);
        assert_eq!(
            by_push.iter().flatten().count(),
            pushes.iter().filter(|p| p.fell).count()
        );
    }

    #[test]
    fn a_second_fall_after_a_push_is_not_the_push_s() {
        // The push's window closed at the first fall; the next fall (after the reset) is not
        // caused by it, and a touch-down before the push is not a catch step.
        let events = vec![td(0.9, 0.45), fall(1.2), td(1.5, 0.0), fall(1.8)];
        let c = classify(&events, &[push(1.0, true)], &LIMITS);
        assert_eq!(c[0].cause, FallCause::BeforeTouchDown);
        // The clamped step before the first fall does not count for the second.
        assert_eq!(c[1].cause, FallCause::NoPush);
    }

    #[test]
    fn open_loop_steps_are_never_clamped() {
        let events = vec![
            FallEvent::TouchDown {
                time: 1.2,
                step_x: None,
                realised: 0.1,
                f_r: 0.0,
            },
            FallEvent::Fall {
                time: 1.5,
                step_x: None,
            },
        ];
        let c = classify(&events, &[push(1.0, true)], &LIMITS);
        assert_eq!(c[0].cause, FallCause::TippedAfterCatchStep);
    }
}
