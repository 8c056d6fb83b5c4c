//! The catch step's reach: how much of the step commanded after a push the swing realises.
//!
//! For each push, the step under way when it hits ends at the first touch-down after it; the
//! *catch step* is the step after that, the first step the controller commands wholly after the
//! push. Its reach is the realised step length (foot to foot, measured at its touch-down) over
//! the length commanded at its last tick before touch-down. A push counts only if its catch
//! step touched down before the next push with no fall in between, and was commanded at least
//! [`MIN_CATCH_BEYOND_REFERENCE`] beyond the reference step (a real catch step, not a step in
//! the gait). [`CatchStepObserver::reach`] is the mean over the counted pushes.

use crate::control::walker::Tick;
use crate::experiments::trial::{FallRecord, Observer, PushRecord};
use serde::{Deserialize, Serialize};

/// How far beyond the reference step a catch step must be commanded to count (m).
pub const MIN_CATCH_BEYOND_REFERENCE: f64 = 0.1;

/// One touch-down: when, the commanded and the realised sagittal step, the reference step.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Landing {
    time: f64,
    commanded: Option<f64>,
    realised: f64,
    f_r: f64,
}

/// Records what [`CatchStepObserver::reach`] needs from a trial: every touch-down's commanded
/// and realised step, and every fall. Works with any walker mode (the open-loop walker has no
/// commanded footstep, so none of its pushes counts).
#[derive(Debug, Clone, Default)]
pub struct CatchStepObserver {
    landings: Vec<Landing>,
    falls: Vec<f64>,
    last_command: Option<f64>,
}

/// The catch step's mean reach over the counted pushes of one trial.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CatchStepReach {
    /// Mean realised / commanded length; `None` when no push counted.
    pub reach: Option<f64>,
    /// Pushes that counted.
    pub pushes: usize,
}

impl CatchStepObserver {
    /// A fresh observer.
    pub fn new() -> Self {
        Self::default()
    }

    /// The catch step's reach over the trial's delivered `pushes` (time order).
    pub fn reach(&self, pushes: &[PushRecord]) -> CatchStepReach {
        let mut sum = 0.0;
        let mut n = 0;
        for (k, push) in pushes.iter().enumerate() {
            let next_push = pushes.get(k + 1).map_or(f64::INFINITY, |p| p.time);
            let first = self.landings.partition_point(|l| l.time <= push.time);
            let Some(catch) = self.landings.get(first + 1) else {
                continue;
            };
            let fell = self.falls.iter().any(|&t| t > push.time && t <= catch.time);
            let Some(commanded) = catch.commanded else {
                continue;
            };
            if fell
                || catch.time >= next_push
                || (commanded - catch.f_r).abs() < MIN_CATCH_BEYOND_REFERENCE
                || commanded == 0.0
            {
                continue;
            }
            sum += catch.realised / commanded;
            n += 1;
        }
        CatchStepReach {
            reach: (n > 0).then(|| sum / n as f64),
            pushes: n,
        }
    }
}

impl Observer for CatchStepObserver {
    fn on_tick(&mut self, time: f64, tick: &Tick) {
        // The decision of a touch-down tick is already for the next step.
        if let Some(step) = &tick.step {
            self.landings.push(Landing {
                time,
                commanded: self.last_command,
                realised: step.f_e + step.f_r,
                f_r: step.f_r,
            });
        }
        self.last_command = tick.decision.map(|d| d.step[0]);
    }

    fn on_fall(&mut self, fall: &FallRecord) {
        self.falls.push(fall.time);
        self.last_command = None;
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

    fn observer(landings: &[(f64, f64, f64)], falls: &[f64]) -> CatchStepObserver {
        CatchStepObserver {
            landings: landings
                .iter()
                .map(|&(time, commanded, realised)| Landing {
                    time,
                    commanded: Some(commanded),
                    realised,
                    f_r: 0.0,
                })
                .collect(),
            falls: falls.to_vec(),
            last_command: None,
        }
    }

    #[test]
    fn the_catch_step_is_the_second_landing_after_the_push() {
        // Push at 1.0: the step under way lands at 1.2 (0.3 commanded, 0.3 realised), the
        // catch step at 1.6 (0.4 commanded, 0.2 realised).
        let o = observer(&[(0.8, 0.0, 0.0), (1.2, 0.3, 0.3), (1.6, 0.4, 0.2)], &[]);
        let r = o.reach(&[push(1.0)]);
        assert_eq!(r.pushes, 1);
        assert!((r.reach.unwrap() - 0.5).abs() < 1e-12);
    }

    #[test]
    fn small_commands_falls_and_the_next_push_exclude_a_push() {
        // Commanded only 0.05 beyond the reference: not a catch step.
        let o = observer(&[(1.2, 0.3, 0.3), (1.6, 0.05, 0.05)], &[]);
        assert_eq!(o.reach(&[push(1.0)]).pushes, 0);
        // A fall before the catch step lands.
        let o = observer(&[(1.2, 0.3, 0.3), (1.6, 0.4, 0.4)], &[1.4]);
        assert_eq!(
            o.reach(&[push(1.0)]),
            CatchStepReach {
                reach: None,
                pushes: 0
            }
        );
        // The next push comes before the catch step lands; its own catch step counts.
        let o = observer(&[(1.2, 0.3, 0.3), (1.6, 0.4, 0.4), (2.0, -0.2, -0.1)], &[]);
        let r = o.reach(&[push(1.0), push(1.5)]);
        assert_eq!(r.pushes, 1);
        assert!((r.reach.unwrap() - 0.5).abs() < 1e-12);
    }
}
