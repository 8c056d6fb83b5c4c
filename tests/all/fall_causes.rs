//! Fall causes (experiment C) and the no-learning baseline (experiment D), short: the observer
//! sees every fall and touch-down of a real trial, the causes account for every fall, and both
//! summaries carry their new fields with consistent sizes.

use steplearn::bench::Registry;
use steplearn::control::Tick;
use steplearn::control::WalkerMode;
use steplearn::experiments::ExperimentKind;
use steplearn::experiments::fall_causes::{
    FallCause, FallCauseObserver, FallEvent, StepLimits, classify,
};
use steplearn::experiments::protocol::ProtocolTables;
use steplearn::experiments::robustness::RobustnessProtocol;
use steplearn::experiments::robustness::RobustnessSummary;
use steplearn::experiments::schedule::PushPlan;
use steplearn::experiments::settings::Settings;
use steplearn::experiments::stability::StabilityProtocol;
use steplearn::experiments::stability::StabilitySummary;
use steplearn::experiments::summary::TypedResult;
use steplearn::experiments::sweep::RunSpec;
use steplearn::experiments::trial::{Observer, run_trial};
use steplearn::robot::Side;

fn temp_dir(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("steplearn-{name}-{}", std::process::id()))
}

fn spec(experiment: ExperimentKind, seed: u64) -> RunSpec {
    RunSpec {
        experiment: experiment.to_string(),
        approx: "lwpr".into(),
        rule: "pendulum-cart".into(),
        seed,
        learn: None,
    }
}

#[test]
fn the_observer_sees_every_fall_and_touch_down_of_a_trial() {
    let settings = Settings::default();
    // Hard pushes: the model falls on some of them.
    let plan = PushPlan {
        count: 4,
        impulse: (14.0, 20.0),
        settle: 3.0,
        gap: (3.0, 4.0),
    };
    let setup = settings.push_trial(WalkerMode::CaptureStep, 0.0, &plan, 5, [1.0, 0.0, 0.0]);
    let mut observer = FallCauseObserver::new();
    let log = run_trial(&setup, None, &mut [&mut observer]).unwrap();
    let events = observer.events();
    let falls = events
        .iter()
        .filter(|e| matches!(e, FallEvent::Fall { .. }))
        .count();
    let touch_downs = events.len() - falls;
    assert_eq!(falls, log.falls.len());
    assert_eq!(touch_downs, log.steps.len());
    assert!(!log.falls.is_empty(), "no fall at 14-20 Ns");
    // The Capture Step walker commands every step it takes.
    assert!(
        events
            .iter()
            .any(|e| matches!(e, FallEvent::TouchDown { step_x: Some(x), .. } if x.is_finite()))
    );

    let c = classify(events, &log.pushes, &StepLimits::of(&setup.walker));
    assert_eq!(c.len(), log.falls.len());
    for (f, r) in c.iter().zip(&log.falls) {
        assert_eq!(f.time, r.time);
        match f.push {
            Some(i) => {
                assert!(log.pushes[i].fell);
                assert!(log.pushes[i].time < f.time);
                assert!(f.time - log.pushes[i].time <= settings.push_window_s + 0.05);
                assert!(f.cause.after_push());
            }
            None => assert!(!f.cause.after_push()),
        }
    }
    // Every push that ended in a fall owns exactly one fall.
    assert_eq!(
        c.iter().filter(|f| f.push.is_some()).count(),
        log.pushes.iter().filter(|p| p.fell).count()
    );
}

/// One tick: its time, the controller's support and command, the estimator's support, and
/// whether the estimator saw a touch-down.
type TickRow = (f64, Option<(Side, f64)>, Side, bool);

/// Every tick of a trial.
#[derive(Default)]
struct Ticks(Vec<TickRow>);

impl Observer for Ticks {
    fn on_tick(&mut self, time: f64, tick: &Tick) {
        self.0.push((
            time,
            tick.decision.map(|d| (d.support, d.step[0])),
            tick.estimate.support,
            tick.step.is_some(),
        ));
    }
}

/// A touch-down's `step_x` is the command of the step that ended: the last one the controller
/// gave standing on that step's support foot, also where the generator exchanged its legs
/// before the estimator saw the touch-down (the controller then decides the next step, from
/// the other foot, and its command is not this step's).
#[test]
fn a_touch_down_records_the_command_of_the_step_that_ended() {
    let settings = Settings::default();
    let plan = PushPlan {
        count: 6,
        impulse: (6.0, 14.0),
        settle: 3.0,
        gap: (3.0, 4.0),
    };
    let setup = settings.push_trial(WalkerMode::CaptureStep, 0.0, &plan, 3, [1.0, 0.0, 0.0]);
    let (mut observer, mut ticks) = (FallCauseObserver::new(), Ticks::default());
    run_trial(&setup, None, &mut [&mut observer, &mut ticks]).unwrap();
    let touch_downs: Vec<(f64, Option<f64>)> = observer
        .events()
        .iter()
        .filter_map(|e| match *e {
            FallEvent::TouchDown { time, step_x, .. } => Some((time, step_x)),
            FallEvent::Fall { .. } => None,
        })
        .collect();
    let ticks = &ticks.0;
    let (mut checked, mut early) = (0, 0);
    for &(time, step_x) in &touch_downs {
        let i = ticks.iter().position(|t| t.0 == time && t.3).unwrap();
        if i == 0 {
            continue;
        }
        // The ending step's support foot: the estimator's, the tick before its touch-down.
        let stance = ticks[i - 1].2;
        // The ticks since the previous touch-down.
        let start = ticks[..i].iter().rposition(|t| t.3).map_or(0, |j| j + 1);
        let own = ticks[start..i]
            .iter()
            .rev()
            .find_map(|t| t.1.filter(|d| d.0 == stance).map(|d| d.1));
        let Some(own) = own else { continue };
        let last = ticks[i - 1].1.map(|d| d.1);
        if ticks[i - 1].1.is_some_and(|d| d.0 != stance) {
            early += 1;
            assert_ne!(
                last,
                Some(own),
                "an early exchange must change the command here"
            );
        }
        assert_eq!(step_x, Some(own), "touch-down at {time} s");
        checked += 1;
    }
    assert!(checked >= 20, "{checked} touch-downs checked");
    // The case that matters happens in this trial: the generator exchanged first.
    assert!(early >= 1, "no early exchange among {checked} touch-downs");
}

#[test]
fn stability_summary_counts_every_fall_by_cause() {
    let settings = Settings::default();
    let mut protocols = ProtocolTables::new();
    protocols
        .set(
            "stability",
            &StabilityProtocol {
                pushes: 5,
                impulse: (6.0, 20.0),
                ..StabilityProtocol::default()
            },
        )
        .unwrap();
    let dir = temp_dir("fall-causes-c");
    let s = Registry::builtin()
        .run_spec(
            &spec(ExperimentKind::Stability, 4),
            &dir,
            &settings,
            &protocols,
        )
        .unwrap();
    s.validate().unwrap();
    let StabilitySummary {
        controllers,
        fall_causes,
        catch_step_reach,
    } = &StabilitySummary::from_result(&s.result).unwrap();
    // The stability summary reports the catch step's reach of both Capture Step walkers.
    let reach = catch_step_reach.expect("catch_step_reach in a new summary");
    for r in [reach.model, reach.learned].into_iter().flatten() {
        assert!(r.is_finite() && r > 0.0, "reach {r}");
    }
    let mut any_fall = false;
    for (c, causes) in [
        (&controllers.open_loop, &fall_causes.open_loop),
        (&controllers.model, &fall_causes.model),
        (&controllers.learned, &fall_causes.learned),
    ] {
        assert_eq!(causes.len(), FallCause::ALL.len());
        let pushed: u32 = causes
            .iter()
            .filter(|(k, _)| FallCause::from_name(k).unwrap().after_push())
            .map(|(_, n)| n)
            .sum();
        assert_eq!(pushed, c.falls);
        any_fall |= c.falls > 0;
    }
    assert!(any_fall, "no controller fell at 6-20 Ns");
    let json: serde_json::Value = serde_json::from_str(&s.to_json().unwrap()).unwrap();
    assert!(json["fall_causes"]["learned"]["catch_step_clamped"].is_u64());

    // pushes.csv: a cause exactly for the pushes that ended in a fall.
    let csv = std::fs::read_to_string(dir.join("pushes.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "controller,time_s,impulse_ns,fell,fall_cause"
    );
    let mut rows = 0;
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells.len(), 5, "{line}");
        assert_eq!(cells[3] == "true", !cells[4].is_empty(), "{line}");
        if !cells[4].is_empty() {
            assert!(
                FallCause::ALL
                    .iter()
                    .any(|c| c.name() == cells[4] && c.after_push())
            );
        }
        rows += 1;
    }
    assert_eq!(rows, 3 * 5);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn robustness_summary_carries_the_baseline_on_the_same_pushes() {
    let settings = Settings {
        scale: 0.2, // 3 of the protocol's 15 pushes
        ..Settings::default()
    };
    let protocols = ProtocolTables::new();
    let dir = temp_dir("fall-causes-d");
    let s = Registry::builtin()
        .run_spec(
            &spec(ExperimentKind::Robustness, 1),
            &dir,
            &settings,
            &protocols,
        )
        .unwrap();
    s.validate().unwrap();
    let RobustnessSummary {
        pushes_until_first_absorbed,
        falls,
        impulse_ns,
        absorbed_by_push,
        no_learning,
    } = RobustnessSummary::from_result(&s.result).unwrap();
    assert_eq!(impulse_ns, Some(RobustnessProtocol::default().impulse));
    assert_eq!(absorbed_by_push.len(), 3);
    let b = no_learning.as_ref().expect("baseline");
    assert_eq!(b.absorbed_by_push.len(), absorbed_by_push.len());
    assert_eq!(
        pushes_until_first_absorbed,
        absorbed_by_push
            .iter()
            .position(|&a| a)
            .map(|i| i as u32 + 1)
    );
    assert!(falls as usize >= absorbed_by_push.iter().filter(|&&a| !a).count());
    assert!(b.falls as usize >= b.absorbed_by_push.iter().filter(|&&a| !a).count());
    let json: serde_json::Value = serde_json::from_str(&s.to_json().unwrap()).unwrap();
    assert_eq!(json["absorbed_by_push"].as_array().unwrap().len(), 3);
    assert_eq!(
        json["no_learning"]["absorbed_by_push"]
            .as_array()
            .unwrap()
            .len(),
        3
    );
    assert!(json["impulse_ns"].is_f64());

    // The per-push CSV has both walkers' outcomes, matching the summary.
    let csv = std::fs::read_to_string(dir.join("robustness_pushes.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len(), 3);
    for (i, r) in rows.iter().enumerate() {
        assert_eq!(r[2] == "true", !absorbed_by_push[i]);
        assert_eq!(r[5] == "true", !b.absorbed_by_push[i]);
    }
    std::fs::remove_dir_all(&dir).ok();
}
