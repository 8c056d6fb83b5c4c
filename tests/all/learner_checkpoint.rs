//! A learner checkpoint continues bit for bit: on the humanoid, mid-experiment, a learner saved
//! to a file and loaded again in the middle of a step (recorded inputs, reaches, counters and
//! trust region included) walks on exactly as the learner that was never saved, for every
//! built-in approximator.

use steplearn::approx::{AnyApproximator, ApproxKind};
use steplearn::control::PerParameter;
use steplearn::control::{
    FootstepLearner, InputGrid, LearnerConfig, LearnerError, LearnerInput, SavedLearner,
    StepInProgress,
};
use steplearn::control::{FootstepPolicy, StepReports, WalkerMode};
use steplearn::experiments::schedule::{Push, ReferenceSchedule};
use steplearn::experiments::settings::Settings;
use steplearn::experiments::trial::{TrialLog, run_trial};
use steplearn::rules::PendulumCart;
use steplearn::rules::StepOutcome;
use strum::VariantArray;

type Learner = FootstepLearner<AnyApproximator, PendulumCart>;

/// A deliberate corruption of a saved step.
type Corruption = fn(&mut StepInProgress);

/// A policy that, every `every` queries, saves its learner to a file and continues with the
/// learner loaded from it.
struct Reloading {
    learner: Learner,
    every: Option<usize>,
    queries: usize,
    /// How many reloads happened mid-step (with inputs recorded) and how many of those after
    /// the per-step bound made the learner thin its records.
    mid_step: usize,
    thinned: usize,
    dir: tempfile::TempDir,
}

impl Reloading {
    fn new(learner: Learner, every: Option<usize>) -> Self {
        Reloading {
            learner,
            every,
            queries: 0,
            mid_step: 0,
            thinned: 0,
            dir: tempfile::tempdir().unwrap(),
        }
    }

    fn reload(&mut self) {
        let path = self.dir.path().join("learner.json");
        self.learner.save(&path).unwrap();
        let loaded = Learner::load(&path, PendulumCart::default()).unwrap();
        let step = &loaded.checkpoint().step;
        assert_eq!(step, &self.learner.checkpoint().step);
        if !step.recorded.is_empty() {
            self.mid_step += 1;
        }
        if step.stride > 1 {
            self.thinned += 1;
        }
        self.learner = loaded;
    }
}

impl FootstepPolicy for Reloading {
    fn offsets(
        &mut self,
        inputs: &PerParameter<LearnerInput>,
    ) -> Result<PerParameter<f64>, LearnerError> {
        self.queries += 1;
        if self.every.is_some_and(|k| self.queries.is_multiple_of(k)) {
            self.reload();
        }
        self.learner.offsets(inputs)
    }
    fn set_reach(&mut self, reach: &PerParameter<[f64; 2]>) -> Result<(), LearnerError> {
        FootstepPolicy::set_reach(&mut self.learner, reach)
    }
    fn touch_down(
        &mut self,
        outcomes: &PerParameter<StepOutcome>,
    ) -> Result<StepReports, LearnerError> {
        FootstepPolicy::touch_down(&mut self.learner, outcomes)
    }
    fn fall(&mut self, outcomes: &PerParameter<StepOutcome>) -> Result<StepReports, LearnerError> {
        FootstepPolicy::fall(&mut self.learner, outcomes)
    }
    fn discard_step(&mut self) {
        self.learner.discard_step()
    }
}

/// Stepping in place for 6 s with two forward pushes, the learner acting and
/// learning from the first step.
fn walk(kind: ApproxKind, config: LearnerConfig, every: Option<usize>) -> (TrialLog, Reloading) {
    let mut settings = Settings {
        learner: config,
        ..Settings::default()
    };
    settings.walker.learner_during_fade_in = true;
    let pushes = vec![
        Push {
            time: 2.0,
            impulse: 9.0,
        },
        Push {
            time: 4.0,
            impulse: 7.0,
        },
    ];
    let setup = settings.trial(
        WalkerMode::CaptureStep,
        ReferenceSchedule::constant(0.0),
        pushes,
        [1.0, 0.0, 0.0],
        6.0,
    );
    let bounds = InputGrid::default().input_box().unwrap();
    let learner = FootstepLearner::new(
        kind.build(&bounds).unwrap(),
        PendulumCart::default(),
        config,
    )
    .unwrap();
    let mut policy = Reloading::new(learner, every);
    let log = run_trial(&setup, Some(&mut policy), &mut []).unwrap();
    (log, policy)
}

fn json(saved: &SavedLearner<AnyApproximator>) -> String {
    serde_json::to_string(saved).unwrap()
}

#[test]
fn a_learner_reloaded_mid_step_walks_on_bit_for_bit_for_every_approximator() {
    // 128 samples per step (the default) and 4, so that records are thinned within a step.
    for max_samples_per_step in [128, 4] {
        let config = LearnerConfig {
            max_samples_per_step,
            ..LearnerConfig::default()
        };
        for &kind in ApproxKind::VARIANTS {
            let (log, plain) = walk(kind, config, None);
            // Reload every 37 queries: mid-step at different phases of the step.
            let (log_reloaded, reloaded) = walk(kind, config, Some(37));
            let what = format!("{kind}, {max_samples_per_step} samples per step");
            assert!(log.steps.len() > 8, "{what}: {} steps", log.steps.len());
            assert!(
                reloaded.mid_step > 10,
                "{what}: only {} reloads mid-step",
                reloaded.mid_step
            );
            if max_samples_per_step == 4 {
                assert!(reloaded.thinned > 5, "{what}: {} thinned", reloaded.thinned);
            }
            assert_eq!(
                serde_json::to_string(&log).unwrap(),
                serde_json::to_string(&log_reloaded).unwrap(),
                "{what}: the walk differs after reloading"
            );
            assert_eq!(
                json(&plain.learner.checkpoint()),
                json(&reloaded.learner.checkpoint()),
                "{what}: the learners differ after reloading"
            );
        }
    }
}

#[test]
fn a_checkpoint_whose_step_does_not_fit_its_learner_is_refused() {
    let bounds = InputGrid::default().input_box().unwrap();
    let config = LearnerConfig {
        max_samples_per_step: 4,
        ..LearnerConfig::default()
    };
    let mut learner: Learner = FootstepLearner::new(
        ApproxKind::Grid.build(&bounds).unwrap(),
        PendulumCart::default(),
        config,
    )
    .unwrap();
    for i in 0..6 {
        learner
            .query(LearnerInput::new(0.01 * i as f64, 0.0, 0.0))
            .unwrap();
        learner.set_reach(-0.1, f64::INFINITY).unwrap();
    }
    let good = learner.checkpoint();
    assert_eq!(good.step.stride, 2);
    assert!(Learner::from_checkpoint(good.clone(), PendulumCart::default()).is_ok());
    let broken: [(&str, Corruption); 9] = [
        ("too many records", |s| {
            s.recorded.extend(vec![vec![0.0; 3]; 4])
        }),
        ("reach count", |s| {
            s.reach.pop();
        }),
        ("stride not a power of two", |s| s.stride = 3),
        ("stride zero", |s| s.stride = 0),
        ("fewer queries than records", |s| s.queries = 1),
        ("non-finite input", |s| s.recorded[0][1] = f64::NAN),
        ("non-finite offset", |s| s.last_offset = f64::INFINITY),
        ("empty reach", |s| s.reach[0] = [Some(1.0), Some(0.0)]),
        ("recorded flag", |s| {
            s.recorded.clear();
            s.reach.clear();
            s.last_recorded = true;
        }),
    ];
    for (what, corrupt) in broken {
        let mut saved = good.clone();
        corrupt(&mut saved.step);
        let err = Learner::from_checkpoint(saved, PendulumCart::default())
            .err()
            .unwrap_or_else(|| panic!("{what}: accepted"));
        assert!(
            err.to_string().contains("step in progress"),
            "{what}: {err}"
        );
    }
    // And through a file: the same refusal, the file left as it was.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("l.json");
    let mut saved = good;
    saved.step.stride = 3;
    let text = serde_json::to_string(&saved).unwrap();
    std::fs::write(&path, &text).unwrap();
    assert!(Learner::load(&path, PendulumCart::default()).is_err());
    assert_eq!(std::fs::read_to_string(&path).unwrap(), text);
}

#[test]
fn a_checkpoint_keeps_the_parameter_its_learner_learns() {
    use steplearn::control::StepParameter;
    let approx = || {
        ApproxKind::Lwpr
            .build(&InputGrid::default().input_box().unwrap())
            .unwrap()
    };
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("learner.json");
    for p in [
        StepParameter::StepTime,
        StepParameter::AnklePitch,
        StepParameter::AnkleRoll,
    ] {
        let learner =
            FootstepLearner::new(approx(), PendulumCart::default(), LearnerConfig::default())
                .unwrap()
                .as_parameter(p)
                .unwrap();
        learner.save(&path).unwrap();
        assert!(
            std::fs::read_to_string(&path)
                .unwrap()
                .contains(&format!("\"{p}\""))
        );
        let loaded: FootstepLearner<AnyApproximator, PendulumCart> =
            FootstepLearner::load(&path, PendulumCart::default()).unwrap();
        assert_eq!(loaded.parameter(), p);
        assert_eq!(loaded.settings().offset(p), learner.settings().offset(p));
    }
    // The paper's step-x is left out of the file, so files from before read as step-x.
    let paper =
        FootstepLearner::new(approx(), PendulumCart::default(), LearnerConfig::default()).unwrap();
    assert!(!json(&paper.checkpoint()).contains("\"parameter\""));
}
