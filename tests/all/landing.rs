//! Steps that end at the landing (`landing_wait_s`, `early_landing_phase`) on the pushed
//! humanoid: the controller then changes its support foot only once the estimator stands on it.

use steplearn::control::walker::{Tick, WalkerMode};
use steplearn::experiments::schedule::PushPlan;
use steplearn::experiments::settings::Settings;
use steplearn::experiments::trial::{FallRecord, Observer, run_trial};
use steplearn::robot::Side;

/// Per tick: the controller's support foot (if it decided) and the estimator's; a fall ends a
/// segment.
#[derive(Default)]
struct Supports(Vec<Vec<(Option<Side>, Side)>>);

impl Observer for Supports {
    fn on_tick(&mut self, _time: f64, tick: &Tick) {
        if self.0.is_empty() {
            self.0.push(Vec::new());
        }
        let row = (tick.decision.map(|d| d.support), tick.estimate.support);
        self.0.last_mut().unwrap().push(row);
    }
    fn on_fall(&mut self, _fall: &FallRecord) {
        self.0.push(Vec::new());
    }
}

/// (exchanges of the controller's support foot, of which before the estimator stood on the
/// new foot) over a pushed trial with these settings.
fn exchanges(settings: &Settings) -> (usize, usize) {
    let plan = PushPlan {
        count: 6,
        impulse: (6.0, 14.0),
        settle: 3.0,
        gap: (3.0, 4.0),
    };
    let setup = settings.push_trial(WalkerMode::CaptureStep, 0.0, &plan, 3, [-1.0, 0.0, 0.0]);
    let mut supports = Supports::default();
    run_trial(&setup, None, &mut [&mut supports]).unwrap();
    let (mut all, mut ahead) = (0, 0);
    for segment in &supports.0 {
        for pair in segment.windows(2) {
            let [(Some(before), _), (Some(after), _)] = pair else {
                continue;
            };
            if before != after {
                all += 1;
                // The tick before the controller's change: did the estimator stand on it?
                if pair[0].1 != *after {
                    ahead += 1;
                }
            }
        }
    }
    (all, ahead)
}

#[test]
fn with_steps_ending_at_the_landing_the_controller_changes_feet_only_on_the_new_foot() {
    let mut on_time = Settings::default();
    on_time.walker.motion.early_landing_phase = 1.0;
    let (all, ahead) = exchanges(&on_time);
    assert!(all >= 40, "{all} exchanges");
    // On time, the generator lets some swing feet go before they land.
    assert!(ahead >= 1, "none of {all} exchanges ahead of the landing");

    let mut landing = Settings::default();
    landing.walker.motion.early_landing_phase = 0.5;
    landing.walker.motion.landing_wait_s = 1.0;
    let (all, ahead) = exchanges(&landing);
    assert!(all >= 40, "{all} exchanges");
    assert_eq!(ahead, 0, "{ahead} of {all} exchanges ahead of the landing");
}
