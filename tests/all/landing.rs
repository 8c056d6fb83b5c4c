//! Steps that end at the landing (`early_landing_phase`, the improved setup's) on the pushed
//! humanoid: the controller then changes its support foot ahead of the estimator less often
//! than with every step on time.

use steplearn::control::motion::Swing;
use steplearn::control::{Tick, WalkerMode};
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
fn with_steps_ending_at_the_landing_the_controller_changes_feet_ahead_of_the_landing_less_often() {
    let mut on_time = Settings::default();
    on_time.walker.motion.swing = Swing::Tracking;
    on_time.walker.motion.early_landing_phase = 1.0;
    let (all_on_time, ahead_on_time) = exchanges(&on_time);
    assert!(all_on_time >= 40, "{all_on_time} exchanges");
    // On time, the generator lets some swing feet go before they land.
    assert!(
        ahead_on_time >= 1,
        "none of {all_on_time} exchanges ahead of the landing"
    );

    let mut landing = on_time.clone();
    landing.walker.motion.early_landing_phase = 0.5;
    let (all, ahead) = exchanges(&landing);
    assert!(all >= 40, "{all} exchanges");
    // As shares of all exchanges: a foot that lands past half the step ends it at once.
    assert!(
        (ahead as f64 / all as f64) < (ahead_on_time as f64 / all_on_time as f64),
        "{ahead} of {all} exchanges ahead of the landing, on time {ahead_on_time} of {all_on_time}"
    );
}
