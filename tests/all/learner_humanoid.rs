//! The learner's stability properties on the simulated humanoid, on short runs: the gain
//! applied at every touch-down stays within the guard's limit, the offset stays within the
//! step range's reach (no windup), the literal eq. (6) does neither, and a fall produces an
//! update exactly when learning from falls is on.

use steplearn::approx::{AnyApproximator, ApproxKind};
use steplearn::control::WalkerMode;
use steplearn::control::motion::{MotionConfig, Swing};
use steplearn::control::{FootstepLearner, InputGrid, LearnerConfig};
use steplearn::experiments::schedule::{Push, ReferenceSchedule};
use steplearn::experiments::settings::Settings;
use steplearn::experiments::trial::{TrialLog, run_trial};
use steplearn::rules::PendulumCart;

fn learner(config: LearnerConfig) -> FootstepLearner<AnyApproximator, PendulumCart> {
    let bounds = InputGrid::default().input_box().unwrap();
    FootstepLearner::new(
        ApproxKind::Lwpr.build(&bounds).unwrap(),
        PendulumCart::default(),
        config,
    )
    .unwrap()
}

/// Stepping in place for `seconds` with forward pushes of `impulses`, one every 3 s from 3 s.
/// `paper_start`: the learner acts and learns from the first step (the paper's learner, and
/// `learner_during_fade_in = true`), not only after the generator has faded in.
fn run(config: LearnerConfig, seconds: f64, impulses: &[f64], paper_start: bool) -> TrialLog {
    run_with(
        MotionConfig::default(),
        config,
        seconds,
        impulses,
        paper_start,
    )
}

/// [`run`] with the step motion generator's settings `motion`.
fn run_with(
    motion: MotionConfig,
    config: LearnerConfig,
    seconds: f64,
    impulses: &[f64],
    paper_start: bool,
) -> TrialLog {
    let mut settings = Settings {
        learner: config,
        ..Settings::default()
    };
    settings.walker.motion = motion;
    settings.walker.learner_during_fade_in = paper_start;
    let pushes = impulses
        .iter()
        .enumerate()
        .map(|(i, &impulse)| Push {
            time: 3.0 * (i + 1) as f64,
            impulse,
        })
        .collect();
    let setup = settings.trial(
        WalkerMode::CaptureStep,
        ReferenceSchedule::constant(0.0),
        pushes,
        [1.0, 0.0, 0.0],
        seconds,
    );
    let mut l = learner(config);
    run_trial(&setup, Some(&mut l), &mut []).unwrap()
}

#[test]
fn the_guarded_learner_keeps_its_gain_and_offset_bounded_through_pushes() {
    let config = LearnerConfig::default();
    let limit = config.max_gain.unwrap();
    let log = run(config, 15.0, &[8.0, 12.0, 16.0, 10.0], false);
    assert!(log.steps.len() > 25, "{} steps", log.steps.len());
    let fade_in = Settings::default().walker.motion.fade_in;
    for s in &log.steps {
        // The last start or restart (after a fall) before this touch-down.
        let start = log
            .falls
            .iter()
            .map(|f| f.time)
            .filter(|&t| t <= s.time)
            .fold(0.0, f64::max);
        if s.time - start < fade_in {
            // The model alone starts the walker: nothing learned.
            assert!(s.learning_gain.is_none(), "{s:?}");
            continue;
        }
        if s.time - start < fade_in + 0.1 {
            continue;
        }
        let gain = s
            .learning_gain
            .expect("every touch-down after the fade-in reports its gain");
        assert!(gain.abs() <= limit, "gain {gain} at {}", s.time);
        // The guard only ever scales the step down: the gain is at most eta times the
        // approximator's response to the full step (eta = 1).
        let response = s.learning_response.expect("and its response");
        assert!(
            gain.abs() <= response.abs() + 1e-9,
            "gain {gain} > r {response}"
        );
        // The reach on this walker spans at most the step range plus the analytic step.
        assert!(
            s.learned_offset.abs() < 0.6,
            "dF {} at {}",
            s.learned_offset,
            s.time
        );
    }
    // The prior keeps dF small while stepping in place.
    let before_push: Vec<_> = log.steps.iter().filter(|s| s.time < 3.0).collect();
    assert!(!before_push.is_empty());
    assert!(before_push.iter().all(|s| s.learned_offset.abs() < 0.03));
}

/// The largest |gain| and |dF| over a run's touch-downs.
fn largest_gain_and_offset(log: &TrialLog) -> (f64, f64) {
    let max_gain = log
        .steps
        .iter()
        .filter_map(|s| s.learning_gain)
        .fold(0.0f64, |m, g| m.max(g.abs()));
    let max_offset = log
        .steps
        .iter()
        .fold(0.0f64, |m, s| m.max(s.learned_offset.abs()));
    (max_gain, max_offset)
}

#[test]
fn the_literal_eq6_learner_exceeds_the_gain_limit_and_winds_up_with_steps_on_time() {
    // The tracking swing with every step on time, named in full so that the test keeps its
    // meaning when the defaults change.
    let on_time = MotionConfig {
        swing: Swing::Tracking,
        early_landing_phase: 1.0,
        tilt_gain: 1.0,
        tilt_lift: 0.0,
        ..MotionConfig::default()
    };
    let log = run_with(on_time, LearnerConfig::literal(), 6.0, &[], true);
    let (max_gain, max_offset) = largest_gain_and_offset(&log);
    // measured: ~1 at the first touch-downs (a fresh LWPR moves all the way)
    assert!(max_gain > 0.5, "max gain {max_gain}");
    // Winding up: dF grows past 0.1 m, over three times the 0.03 m the prior keeps it under
    // stepping in place (measured: +-0.2-0.44 m within 3 s, and a fall at 19 s of 20); a fall
    // alone does not count.
    let falls = log.falls.len();
    assert!(max_offset > 0.1, "max dF {max_offset}, {falls} falls");
}

/// The paper's system (the defaults) needs the gain guard: there the literal eq. (6) takes
/// gains far above the stability limit, and stepping in place its offset swings several times
/// as far as the guarded learner's on the same walk.
#[test]
fn on_the_papers_system_the_literal_eq6_learner_exceeds_the_gain_limit_and_winds_up() {
    let literal = run(LearnerConfig::literal(), 20.0, &[], true);
    let guarded = run(LearnerConfig::default(), 20.0, &[], true);
    let (max_gain, max_offset) = largest_gain_and_offset(&literal);
    let (guarded_gain, guarded_offset) = largest_gain_and_offset(&guarded);
    eprintln!(
        "literal: gain {max_gain}, dF {max_offset}; guarded: gain {guarded_gain}, dF {guarded_offset}"
    );
    assert!(max_gain > 0.5, "max gain {max_gain}");
    assert!(guarded_gain <= 0.2 + 1e-9, "guarded gain {guarded_gain}");
    assert!(
        max_offset > 3.0 * guarded_offset,
        "max dF {max_offset}, guarded {guarded_offset}"
    );
}

/// With the improved setup's swing (tracking, steps that end at their landing) the literal
/// eq. (6) still takes gains far above the guard's limit, but stepping in place its offset
/// stays bounded: the swing lands the steps the offsets ask for, so G answers them.
#[test]
fn with_the_improved_swing_the_literal_eq6_learner_exceeds_the_gain_limit_without_winding_up() {
    let improved = MotionConfig {
        swing: Swing::Tracking,
        early_landing_phase: 0.5,
        step_x_range: [-0.45, 0.45],
        ..MotionConfig::default()
    };
    let log = run_with(improved, LearnerConfig::literal(), 20.0, &[], true);
    let (max_gain, max_offset) = largest_gain_and_offset(&log);
    assert!(max_gain > 0.5, "max gain {max_gain}");
    assert!(log.falls.is_empty(), "{:?}", log.falls);
    // A third of the step range (0.45 m), and of the swing the on-time walker's dF takes.
    assert!(max_offset < 0.15, "max dF {max_offset}");
}

#[test]
fn a_fall_updates_the_learner_only_when_learning_from_falls() {
    for on in [false, true] {
        let config = LearnerConfig {
            learn_from_falls: on,
            ..LearnerConfig::default()
        };
        // 25 Ns is far beyond what the walker can absorb.
        let log = run(config, 5.0, &[25.0], false);
        assert!(!log.falls.is_empty(), "no fall");
        for f in &log.falls {
            assert_eq!(f.learning_gain.is_some(), on, "{f:?}");
        }
    }
}

#[test]
fn with_learner_during_fade_in_off_the_model_alone_starts_the_walker() {
    for on in [true, false] {
        let mut settings = Settings::default();
        settings.walker.learner_during_fade_in = on;
        let setup = settings.trial(
            WalkerMode::CaptureStep,
            ReferenceSchedule::constant(0.2),
            Vec::new(),
            [1.0, 0.0, 0.0],
            3.0,
        );
        let mut l = learner(LearnerConfig::default());
        let log = run_trial(&setup, Some(&mut l), &mut []).unwrap();
        let fade_in = settings.walker.motion.fade_in;
        let early: Vec<_> = log.steps.iter().filter(|s| s.time < fade_in).collect();
        let late: Vec<_> = log.steps.iter().filter(|s| s.time > fade_in).collect();
        assert!(
            early.len() >= 2 && late.len() >= 2,
            "{} steps",
            log.steps.len()
        );
        // measured: the first steps from standing miss F_R = 0.2 m by ~0.2 m, so the default
        // learner learns from them and offsets the next ones.
        for s in &early {
            assert_eq!(s.learning_gain.is_some(), on, "{s:?}");
            if !on {
                assert_eq!(s.learned_offset, 0.0, "{s:?}");
            }
        }
        assert!(late.iter().all(|s| s.learning_gain.is_some()));
    }
}
