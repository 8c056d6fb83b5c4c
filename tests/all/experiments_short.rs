//! Experiments A, B and D, short: the protocols run on the humanoid, the statistics are
//! consistent with the logs, and the files are written. Whether learning helps is measured by
//! `steplearn reproduce`, not asserted here.

use std::sync::atomic::{AtomicUsize, Ordering};
use steplearn::approx::{AnyApproximator, ApproxKind};
use steplearn::control::{FootstepLearner, InputGrid, LearnerConfig, LearnerError};
use steplearn::experiments::ExperimentError;
use steplearn::experiments::disturbance::{self, DisturbanceProtocol};
use steplearn::experiments::fall_causes::FallCause;
use steplearn::experiments::robustness::{self, RobustnessProtocol};
use steplearn::experiments::settings::Settings;
use steplearn::experiments::tracking::{self, TrackingProtocol};
use steplearn::rules::PendulumCart;

fn learner() -> Result<FootstepLearner<AnyApproximator, PendulumCart>, LearnerError> {
    let bounds = InputGrid::default().input_box().unwrap();
    FootstepLearner::new(
        ApproxKind::Lwpr.build(&bounds).unwrap(),
        PendulumCart::default(),
        LearnerConfig::default(),
    )
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("steplearn-{name}-{}", std::process::id()))
}

#[test]
fn tracking_bins_every_step_after_a_change_and_the_model_settles() {
    let settings = Settings {
        scale: 0.01, // the protocol's floor: four of the longest holds
        ..Settings::default()
    };
    let p = TrackingProtocol::default();
    let r = tracking::run(&settings, &p, 3, &learner).unwrap();
    let changes = r.reference.change_times();
    assert!(changes.len() >= 3, "{changes:?}");
    // Both controllers followed the same reference, recorded at every step: the schedule's,
    // ramped in over the walker's start ramp after the start and after every reset.
    let ramp = settings.walker.start_ramp_s;
    for log in [&r.runs.model, &r.runs.learned] {
        for s in &log.steps {
            let want = r.reference.at(s.time);
            let restarted = log.falls.iter().any(|f| f.time < s.time);
            if s.time > ramp && !restarted {
                assert_eq!(s.f_r, want);
            } else {
                assert!(s.f_r * want >= 0.0 && s.f_r.abs() <= want.abs(), "{s:?}");
            }
        }
    }
    // Every step within the horizon after a change is in exactly one bin.
    let in_horizon = r
        .runs
        .model
        .steps
        .iter()
        .filter(|s| {
            let i = changes.partition_point(|&c| c <= s.time);
            i > 0 && s.time - changes[i - 1] < p.horizon_s
        })
        .count();
    assert_eq!(r.model.count.iter().sum::<usize>(), in_horizon);
    assert_eq!(r.model.mean.len(), (p.horizon_s / p.bin_s) as usize);
    // The model has not caught up right after a change and has at the end of the horizon.
    let (model_std, _) = r.std_per_bin();
    let first = model_std[0].unwrap();
    let last = model_std.last().unwrap().unwrap();
    assert!(
        first > last,
        "std right after a change {first} vs later {last}"
    );
    assert!(r.runs.model.falls.is_empty());

    let dir = temp_dir("tracking");
    r.write(&dir).unwrap();
    for f in [
        "tracking_steps.csv",
        "tracking_aligned.csv",
        "tracking_std.svg",
        "tracking_series.svg",
    ] {
        assert!(dir.join(f).exists(), "{f}");
    }
    std::fs::remove_dir_all(&dir).ok();
    assert!(
        tracking::run(
            &settings,
            &TrackingProtocol {
                horizon_s: 9.0,
                ..p
            },
            3,
            &learner
        )
        .is_err(),
        "a horizon beyond the shortest hold is rejected"
    );
}

#[test]
fn disturbance_aligns_steps_at_absorbed_pushes() {
    let settings = Settings {
        scale: 0.05,
        ..Settings::default()
    };
    let p = DisturbanceProtocol::default();
    let r = disturbance::run(&settings, &p, 5, &learner).unwrap();
    assert_eq!(r.model.pushes, 3);
    assert!(r.runs.model.pushes.iter().all(|x| x.impulse == 8.0));
    let absorbed = r.model.pushes - r.model.falls;
    assert!(absorbed >= 1, "the model absorbs 8 Ns at 0.2 m steps");
    // The first step after an absorbed push is longer than the reference (the push throws the
    // robot forward), and the model's figures are finite and within the horizon.
    assert!(r.model.step.mean[0] > p.f_r, "{:?}", r.model.step.mean);
    assert!((0.0..=p.horizon_s).contains(&r.model.return_time_s));
    assert!(r.model.max_tda_rad.is_finite() && r.model.max_tda_rad > 0.0);
    assert!(r.learned.return_time_s.is_finite() && r.learned.max_tda_rad.is_finite());
    // The settle time (to its own undisturbed step) and the return time (to F_R) are the same
    // bins against different targets; by touch-down, the catch steps come first: the first or
    // second touch-down after a push is longer than the reference.
    assert!((0.0..=p.horizon_s).contains(&r.model.settle_time_s));
    let by_step = &r.model.step_by_index;
    assert_eq!(
        by_step.count[0], absorbed,
        "one first touch-down per absorbed push"
    );
    assert!(
        by_step.mean[0].max(by_step.mean[1]) > p.f_r,
        "{:?}",
        by_step.mean
    );
    assert!(r.model.step_error_after_push_m > 0.0 && r.model.step_error_after_push_m < 0.3);

    let dir = temp_dir("disturbance");
    r.write(&dir, p.f_r).unwrap();
    for f in [
        "disturbance_steps.csv",
        "disturbance_pushes.csv",
        "disturbance_aligned.csv",
        "disturbance_by_step.csv",
        "disturbance_by_step.svg",
        "disturbance_step.svg",
        "disturbance_tda.svg",
    ] {
        assert!(dir.join(f).exists(), "{f}");
    }
    // Falls after the push window count towards the falls before the next push.
    for r in [&r.model, &r.learned] {
        assert!(
            (r.falls..=r.pushes).contains(&r.falls_before_next_push),
            "{r:?}"
        );
    }
    // Every fall after a push has one cause, in the summary counts and the pushes CSV.
    let causes = r.runs.fall_causes();
    for (counts, falls) in [
        (&causes.model, r.model.falls),
        (&causes.learned, r.learned.falls),
    ] {
        let after_push: u32 = counts
            .iter()
            .filter(|(k, _)| FallCause::from_name(k).unwrap().after_push())
            .map(|(_, n)| n)
            .sum();
        assert_eq!(after_push as usize, falls, "{counts:?}");
    }
    let pushes_csv = std::fs::read_to_string(dir.join("disturbance_pushes.csv")).unwrap();
    assert!(pushes_csv.starts_with("controller,time_s,impulse_ns,fell,fall_cause\n"));
    std::fs::remove_dir_all(&dir).ok();
    let bad = DisturbanceProtocol {
        gap_s: (3.0, 6.0),
        ..p
    };
    assert!(disturbance::run(&settings, &bad, 5, &learner).is_err());
    // Pushes nobody survives leave nothing to align: a clear error, not a figure error.
    let hopeless = DisturbanceProtocol { impulse: 60.0, ..p };
    match disturbance::run(&settings, &hopeless, 5, &learner) {
        Err(ExperimentError::NothingToMeasure(m)) => assert!(m.contains("every push"), "{m}"),
        other => panic!("{:?}", other.map(|r| (r.model.falls, r.learned.falls))),
    }
}

#[test]
fn robustness_learns_from_scratch_and_keeps_what_it_learned() {
    let settings = Settings {
        scale: 0.2,
        ..Settings::default()
    };
    let p = RobustnessProtocol {
        map: steplearn::control::MapSpec {
            resolution: (9, 7),
            ..Default::default()
        },
        ..RobustnessProtocol::default()
    };
    // The run gives the learner its config (without the dF = 0 prior: not initialised).
    let learner_with = |config: LearnerConfig| {
        assert_eq!(config.prior.samples, 0, "experiment D strips the prior");
        let bounds = InputGrid::default().input_box().unwrap();
        FootstepLearner::new(
            ApproxKind::Lwpr.build(&bounds).unwrap(),
            PendulumCart::default(),
            config,
        )
    };
    let built = AtomicUsize::new(0);
    let counted = |config: LearnerConfig| {
        built.fetch_add(1, Ordering::Relaxed);
        learner_with(config)
    };
    let r = robustness::run(&settings, &p, 2, &counted).unwrap();
    assert_eq!(r.initial_metric, 0.0, "an untrained learner outputs zero");
    assert_eq!(r.episodes.len(), 3);
    // One learner for every episode: the experiment builds it once and keeps it.
    assert_eq!(built.load(Ordering::Relaxed), 1, "a learner per episode");
    for (i, e) in r.episodes.iter().enumerate() {
        assert_eq!(e.push, i + 1);
        assert!(e.learning_metric.is_finite() && e.learning_metric > 0.0);
        assert_eq!(e.map.values.len(), 9 * 7);
        // An episode that fell had a fall (a fall in the push window, or falls before the
        // push that kept it from being delivered), with or without learning.
        assert!(!e.fell || e.falls >= 1, "push {}: {e:?}", e.push);
        let base = &r.no_learning[i];
        assert_eq!(base.push, e.push);
        assert!(!base.fell || base.falls >= 1, "push {}: {base:?}", e.push);
    }
    // Touch-downs happened, so the learner changed.
    assert!(r.episodes[0].steps.len() > 3);
    // It keeps what it learned: the first touch-down of every later episode has an offset
    // learned in the episodes before (nothing has trained the learner in this episode yet),
    // where a fresh learner's is exactly 0 (measured with the experiments' dead zone: 0.49 mm
    // and more; without it -12.7 and -12.2 mm).
    for e in &r.episodes[1..] {
        let first = e.steps[0].learned_offset;
        assert!(first.abs() > 1e-4, "push {}: first offset {first}", e.push);
    }
    match r.pushes_until_first_absorbed() {
        Some(n) => assert!(!r.episodes[n - 1].fell && r.episodes[..n - 1].iter().all(|e| e.fell)),
        None => assert!(r.episodes.iter().all(|e| e.fell)),
    }

    let dir = temp_dir("robustness");
    r.write(&dir).unwrap();
    for f in [
        "robustness_pushes.csv",
        "robustness_steps.csv",
        "learning_metric.svg",
        "df_maps.svg",
    ] {
        assert!(dir.join(f).exists(), "{f}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
