//! The walker and the trial harness on the simulated humanoid.

use steplearn::control::walker::{Walker, WalkerConfig, WalkerMode};
use steplearn::experiments::schedule::{Push, ReferenceSchedule};
use steplearn::experiments::settings::Settings;
use steplearn::experiments::trial::{TrialError, run_trial};
use steplearn::sim::{Humanoid, SimConfig};

#[test]
fn capture_step_walker_steps_in_place_without_falling() {
    let mut robot = Humanoid::new(SimConfig::default()).unwrap();
    let mut walker = Walker::new(
        WalkerConfig::new(WalkerMode::CaptureStep),
        robot.body().leg_geometry(),
    )
    .unwrap();
    let mut steps = 0;
    while robot.time() < 10.0 {
        let tick = walker.tick(&robot.sensors(), 0.0, None).unwrap();
        let d = tick.decision.expect("capture step decides every tick");
        assert!(d.time_to_step.is_finite() && d.step.iter().all(|v| v.is_finite()));
        if let Some(s) = tick.step {
            steps += 1;
            assert!(s.f_e.is_finite() && s.theta_e.abs() < 0.5);
        }
        robot.step(&tick.targets).unwrap();
        assert!(robot.fall().is_none(), "fell at {:.2} s", robot.time());
    }
    // Nominal step time 0.55 s: about 18 touch-downs in 10 s.
    assert!((14..=24).contains(&steps), "{steps} touch-downs in 10 s");
}

fn pushed_trial(impulse: f64) -> steplearn::experiments::trial::TrialSetup {
    Settings::default().trial(
        WalkerMode::OpenLoop,
        ReferenceSchedule::constant(0.0),
        vec![Push { time: 2.0, impulse }],
        [1.0, 0.0, 0.0],
        8.0,
    )
}

#[test]
fn a_large_push_is_a_recorded_fall_and_the_trial_goes_on_after_a_reset() {
    let log = run_trial(&pushed_trial(40.0), None, &mut []).unwrap();
    assert_eq!(log.pushes.len(), 1);
    assert!(log.pushes[0].fell, "a 40 Ns push was absorbed");
    assert_eq!(log.falls.len(), 1);
    assert!(log.falls[0].time > 2.0 && log.falls[0].time < 5.0);
    assert!(log.sim_time_s >= 8.0 - 1e-9);
    let after = log
        .steps
        .iter()
        .filter(|s| s.time > log.falls[0].time)
        .count();
    assert!(after >= 3, "only {after} steps after the reset");
}

#[test]
fn a_small_push_is_absorbed_and_trials_are_deterministic() {
    let a = run_trial(&pushed_trial(0.5), None, &mut []).unwrap();
    assert_eq!(a.pushes.len(), 1);
    assert!(!a.pushes[0].fell);
    assert!(a.falls.is_empty());
    let b = run_trial(&pushed_trial(0.5), None, &mut []).unwrap();
    assert_eq!(a, b);
}

#[test]
fn invalid_trials_are_errors() {
    let mut t = pushed_trial(1.0);
    t.push_direction = [1.0, 1.0, 0.0];
    assert!(matches!(
        run_trial(&t, None, &mut []),
        Err(TrialError::Invalid(_))
    ));
    let mut t = pushed_trial(1.0);
    t.duration_s = f64::NAN;
    assert!(matches!(
        run_trial(&t, None, &mut []),
        Err(TrialError::Invalid(_))
    ));
    let mut t = pushed_trial(1.0);
    t.pushes[0].impulse = -1.0;
    assert!(matches!(
        run_trial(&t, None, &mut []),
        Err(TrialError::Invalid(_))
    ));
}
