//! The catch step's reach: how much of the step commanded after a push the swing realises.
//!
//! For each push, the step under way when it hits ends at the first touch-down after it; the
//! *catch step* is the step after that, the first step the controller commands wholly after the
//! push. Its reach is the realised step length (foot to foot, measured at its touch-down) over
//! the length commanded for it ([`FallEvent::TouchDown`]'s `step_x`: at its last tick before
//! touch-down, or before the generator exchanged its legs where it did so ahead of the
//! estimator's touch-down). A push counts only if its catch
//! step touched down before the next push with no fall in between, and was commanded at least
//! [`MIN_CATCH_BEYOND_REFERENCE`] beyond the reference step (a real catch step, not a step in
//! the gait). [`catch_step_reach`] is the mean over the counted pushes.

use crate::experiments::fall_causes::FallEvent;
use crate::experiments::trial::PushRecord;
use serde::{Deserialize, Serialize};

/// How far beyond the reference step a catch step must be commanded to count (m).
pub const MIN_CATCH_BEYOND_REFERENCE: f64 = 0.1;

/// The catch step's mean reach over the counted pushes of one trial.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CatchStepReach {
    /// Mean realised / commanded length; `None` when no push counted.
    pub reach: Option<f64>,
    /// Pushes that counted.
    pub pushes: usize,
}

/// One push's catch step, as [`catch_step_reach`] takes it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CatchStep {
    /// Its touch-down time (s).
    pub time: f64,
    /// The length commanded for it (m).
    pub commanded: f64,
    /// The realised length, foot to foot (m).
    pub realised: f64,
    /// The reference step at its touch-down (m).
    pub f_r: f64,
    /// Time since the touch-down before it, which ended the step under way at the push (s).
    pub duration: f64,
    /// Whether the push counts for the reach.
    pub counted: bool,
}

/// Each push's catch step (in the order of `pushes`): `None` where no second touch-down
/// followed the push or it had no commanded footstep. Inputs as [`catch_step_reach`].
pub fn catch_steps(events: &[FallEvent], pushes: &[PushRecord]) -> Vec<Option<CatchStep>> {
    let landings: Vec<(f64, Option<f64>, f64, f64)> = events
        .iter()
        .filter_map(|e| match *e {
            FallEvent::TouchDown {
                time,
                step_x,
                realised,
                f_r,
            } => Some((time, step_x, realised, f_r)),
            FallEvent::Fall { .. } => None,
        })
        .collect();
    let falls: Vec<f64> = events
        .iter()
        .filter_map(|e| match *e {
            FallEvent::Fall { time, .. } => Some(time),
            FallEvent::TouchDown { .. } => None,
        })
        .collect();
    pushes
        .iter()
        .enumerate()
        .map(|(k, push)| {
            let next_push = pushes.get(k + 1).map_or(f64::INFINITY, |p| p.time);
            let first = landings.partition_point(|l| l.0 <= push.time);
            let &(time, commanded, realised, f_r) = landings.get(first + 1)?;
            let commanded = commanded?;
            let fell = falls.iter().any(|&t| t > push.time && t <= time);
            let counted = !fell
                && time < next_push
                && (commanded - f_r).abs() >= MIN_CATCH_BEYOND_REFERENCE
                && commanded != 0.0;
            Some(CatchStep {
                time,
                commanded,
                realised,
                f_r,
                duration: time - landings[first].0,
                counted,
            })
        })
        .collect()
}

/// The catch step's reach over a trial's delivered `pushes` (time order), from the touch-downs
/// and falls a [`crate::experiments::fall_causes::FallCauseObserver`] recorded (`events`, time
/// order). Works with any walker mode: the open-loop walker has no commanded footstep, so none
/// of its pushes counts.
pub fn catch_step_reach(events: &[FallEvent], pushes: &[PushRecord]) -> CatchStepReach {
    let mut sum = 0.0;
    let mut n = 0;
    for c in catch_steps(events, pushes).into_iter().flatten() {
        if c.counted {
            sum += c.realised / c.commanded;
            n += 1;
        }
    }
    CatchStepReach {
        reach: (n > 0).then(|| sum / n as f64),
        pushes: n,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn push(time: f64) -> PushRecord {
        PushRecord {
            time,
            impulse: 10.0,
            fell: false,
        }
    }

    /// Touch-downs `(time, commanded, realised)` at F_R = 0 and falls, in time order.
    fn events(landings: &[(f64, f64, f64)], falls: &[f64]) -> Vec<FallEvent> {
        let mut events: Vec<FallEvent> = landings
            .iter()
            .map(|&(time, commanded, realised)| FallEvent::TouchDown {
                time,
                step_x: Some(commanded),
                realised,
                f_r: 0.0,
            })
            .chain(
                falls
                    .iter()
                    .map(|&time| FallEvent::Fall { time, step_x: None }),
            )
            .collect();
        let time = |e: &FallEvent| match *e {
            FallEvent::TouchDown { time, .. } | FallEvent::Fall { time, .. } => time,
        };
        events.sort_by(|a, b| time(a).total_cmp(&time(b)));
        events
    }

    #[test]
    fn the_catch_step_is_the_second_landing_after_the_push() {
        // Push at 1.0: the step under way lands at 1.2 (0.3 commanded, 0.3 realised), the
        // catch step at 1.6 (0.4 commanded, 0.2 realised).
        let o = events(&[(0.8, 0.0, 0.0), (1.2, 0.3, 0.3), (1.6, 0.4, 0.2)], &[]);
        let r = catch_step_reach(&o, &[push(1.0)]);
        assert_eq!(r.pushes, 1);
        assert!((r.reach.unwrap() - 0.5).abs() < 1e-12);
    }

    #[test]
    fn small_commands_falls_and_the_next_push_exclude_a_push() {
        // Commanded only 0.05 beyond the reference: not a catch step.
        let o = events(&[(1.2, 0.3, 0.3), (1.6, 0.05, 0.05)], &[]);
        assert_eq!(catch_step_reach(&o, &[push(1.0)]).pushes, 0);
        // A fall before the catch step lands.
        let o = events(&[(1.2, 0.3, 0.3), (1.6, 0.4, 0.4)], &[1.4]);
        assert_eq!(
            catch_step_reach(&o, &[push(1.0)]),
            CatchStepReach {
                reach: None,
                pushes: 0
            }
        );
        // The next push comes before the catch step lands; its own catch step counts.
        let o = events(&[(1.2, 0.3, 0.3), (1.6, 0.4, 0.4), (2.0, -0.2, -0.1)], &[]);
        let r = catch_step_reach(&o, &[push(1.0), push(1.5)]);
        assert_eq!(r.pushes, 1);
        assert!((r.reach.unwrap() - 0.5).abs() < 1e-12);
    }
}
