//! The footstep learner against a test-only nearest-bin table and a toy sagittal plant.

use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicUsize, Ordering};
use steplearn::approx::{ApproxError, FunctionApproximator, Persist, check_output, check_vector};
use steplearn::control::{
    FootstepLearner, InputGrid, LearnerConfig, LearnerError, LearnerInput, MapSpec, TrustFallback,
};
use steplearn::rules::{BalanceOnly, LearningRule, PendulumCart, StepOutcome};

/// A nearest-bin table over a 3-D box: each bin holds one value; an update moves it toward the
/// target by 1 / (number of updates of the bin so far + 1), floored at `min_rate` (a running
/// average with slow forgetting, like an LWPR receptive field's).
///
/// The averaging matters: with the paper's p_theta p_F = 4.5 rad/m slope of G in F_E and
/// eta = 1, an approximator that jumps (nearly) to its target at every touch-down overshoots
/// and oscillates (measured on the toy walker below with `min_rate` 0.05, i.e. ~87% of the way
/// per 40-sample step: mean |F_E| 0.076 m, worse than the model's 0.055 m).
#[derive(Debug, Clone, Serialize, Deserialize)]
struct BinTable {
    lo: [f64; 3],
    hi: [f64; 3],
    bins: [usize; 3],
    min_rate: f64,
    values: Vec<f64>,
    counts: Vec<u32>,
    /// Fault injection: fail every update once this many more have succeeded.
    #[serde(skip)]
    fail_after: Option<usize>,
    #[serde(skip)]
    updates: usize,
}

impl BinTable {
    fn new(bins: [usize; 3], min_rate: f64) -> Self {
        let n = bins.iter().product();
        BinTable {
            lo: [-0.5, -2.0, -0.1],
            hi: [0.5, 2.0, 0.2],
            bins,
            min_rate,
            values: vec![0.0; n],
            counts: vec![0; n],
            fail_after: None,
            updates: 0,
        }
    }

    fn index(&self, x: &[f64]) -> usize {
        let mut idx = 0;
        for (a, &v) in x.iter().enumerate() {
            let u = (v - self.lo[a]) / (self.hi[a] - self.lo[a]);
            let b = ((u * self.bins[a] as f64).floor().max(0.0) as usize).min(self.bins[a] - 1);
            idx = idx * self.bins[a] + b;
        }
        idx
    }
}

impl FunctionApproximator for BinTable {
    fn input_dim(&self) -> usize {
        3
    }
    fn output_dim(&self) -> usize {
        1
    }
    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        check_vector("input x", x, 3)?;
        check_output("output y", y, 1)?;
        y[0] = self.values[self.index(x)];
        Ok(())
    }
    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        check_vector("input x", x, 3)?;
        check_vector("target y", y, 1)?;
        if self.fail_after == Some(self.updates) {
            return Err(ApproxError::Corrupt("injected fault".into()));
        }
        let i = self.index(x);
        let rate = (1.0 / (self.counts[i] as f64 + 1.0)).max(self.min_rate);
        self.values[i] += rate * (y[0] - self.values[i]);
        self.counts[i] = self.counts[i].saturating_add(1);
        self.updates += 1;
        Ok(())
    }
}

impl Persist for BinTable {
    fn check_invariants(&self) -> Result<(), ApproxError> {
        let n: usize = self.bins.iter().product();
        if n == 0 || self.values.len() != n || self.counts.len() != n {
            return Err(ApproxError::Corrupt("table size mismatch".into()));
        }
        if self.values.iter().any(|v| !v.is_finite()) {
            return Err(ApproxError::Corrupt("non-finite value".into()));
        }
        Ok(())
    }
}

/// A 2-input, 1-output model: the wrong shape for the learner.
struct TwoInputs;
impl FunctionApproximator for TwoInputs {
    fn input_dim(&self) -> usize {
        2
    }
    fn output_dim(&self) -> usize {
        1
    }
    fn predict(&self, _: &[f64], _: &mut [f64]) -> Result<(), ApproxError> {
        Ok(())
    }
    fn update(&mut self, _: &[f64], _: &[f64]) -> Result<(), ApproxError> {
        Ok(())
    }
}

/// A rule that counts its calls and returns a fixed gradient.
struct Fixed(f64, AtomicUsize);
impl LearningRule for Fixed {
    fn gradient(&self, _: &StepOutcome) -> f64 {
        self.1.fetch_add(1, Ordering::Relaxed);
        self.0
    }
}

fn input(theta_e: f64, theta_e_dot: f64, f_r: f64) -> LearnerInput {
    LearnerInput::new(theta_e, theta_e_dot, f_r)
}

fn table() -> BinTable {
    BinTable::new([10, 8, 6], 0.001)
}

#[test]
fn touch_down_applies_eq6_at_every_recorded_input() {
    let mut learner = FootstepLearner::new(
        table(),
        PendulumCart::default(),
        LearnerConfig {
            eta: 0.5,
            ..LearnerConfig::literal()
        },
    )
    .unwrap();
    let seen = [
        input(0.0, 0.0, 0.0),
        input(0.3, 1.0, 0.1),
        input(-0.3, -1.5, 0.15),
    ];
    for x in seen {
        assert_eq!(learner.query(x).unwrap(), 0.0);
    }
    let unseen = input(0.45, -1.9, -0.09);
    let step = StepOutcome {
        theta_e: 0.2,
        theta_e_dot: 0.0,
        f_e: 0.01,
        f_r: 0.1,
    };
    let g = 0.2 - 0.15 * (0.3f64).tanh();
    let report = learner.touch_down(&step).unwrap();
    assert_eq!(report.samples, 3);
    assert!((report.gradient - g).abs() < 1e-15);
    // fresh bins move all the way to the target: F(x_i) = 0 + eta G
    for x in seen {
        assert!((learner.predict(x).unwrap() - 0.5 * g).abs() < 1e-15);
    }
    assert_eq!(learner.predict(unseen).unwrap(), 0.0);
    assert_eq!(
        learner.recorded_inputs().len(),
        0,
        "a new step starts empty"
    );
}

#[test]
fn predictions_are_taken_before_updates() {
    // Two recorded inputs in the same bin: both targets are F_old + G, so the bin ends at
    // exactly G. Updating in between would give target 2G for the second sample.
    let mut learner = FootstepLearner::new(
        table(),
        Fixed(0.1, AtomicUsize::new(0)),
        LearnerConfig::literal(),
    )
    .unwrap();
    learner.query(input(0.01, 0.0, 0.0)).unwrap();
    learner.query(input(0.02, 0.0, 0.0)).unwrap();
    learner.touch_down(&StepOutcome::default()).unwrap();
    assert!((learner.predict(input(0.01, 0.0, 0.0)).unwrap() - 0.1).abs() < 1e-15);
    assert_eq!(learner.rule().1.load(Ordering::Relaxed), 1);
}

#[test]
fn recording_is_bounded_and_evenly_spread() {
    let cfg = LearnerConfig {
        max_samples_per_step: 16,
        ..LearnerConfig::literal()
    };
    let mut learner = FootstepLearner::new(table(), BalanceOnly, cfg).unwrap();
    for n in 1..=1000usize {
        learner.query(input(0.0, 0.0, n as f64 * 1e-4)).unwrap();
        let k = learner.recorded_inputs().len();
        assert!(k <= 16);
        if n >= 16 {
            assert!(k >= 8, "after {n} queries only {k} kept");
        } else {
            assert_eq!(k, n);
        }
    }
    // kept samples are every stride-th query from the first: evenly spaced over the step
    let kept: Vec<f64> = learner.recorded_inputs().map(|x| x.f_r).collect();
    let gaps: Vec<f64> = kept.windows(2).map(|w| w[1] - w[0]).collect();
    assert!((kept[0] - 1e-4).abs() < 1e-12);
    assert!(gaps.iter().all(|g| (g - gaps[0]).abs() < 1e-9));
    assert!(*kept.last().unwrap() > 0.1 * 0.5, "covers the whole step");
    learner.discard_step();
    assert_eq!(learner.recorded_inputs().len(), 0);
}

#[test]
fn dead_zone_shrinks_the_gradient_and_leakage_pulls_back_to_zero() {
    let x = input(0.0, 0.0, 0.0);
    // G = 0.3 with a dead zone of 0.1: the target moves by 0.2; a G inside the zone teaches
    // nothing, and the report keeps the rule's raw G.
    let cfg = LearnerConfig {
        dead_zone: 0.1,
        ..LearnerConfig::literal()
    };
    let mut learner = FootstepLearner::new(
        BinTable::new([10, 8, 6], 1.0),
        Fixed(0.3, AtomicUsize::new(0)),
        cfg,
    )
    .unwrap();
    learner.query(x).unwrap();
    let report = learner.touch_down(&StepOutcome::default()).unwrap();
    assert_eq!(report.gradient, 0.3);
    assert!((learner.predict(x).unwrap() - 0.2).abs() < 1e-12);
    let mut inside = FootstepLearner::new(
        BinTable::new([10, 8, 6], 1.0),
        Fixed(-0.05, AtomicUsize::new(0)),
        cfg,
    )
    .unwrap();
    inside.query(x).unwrap();
    inside.touch_down(&StepOutcome::default()).unwrap();
    assert_eq!(inside.predict(x).unwrap(), 0.0);
    // Leakage 0.5 with G = 0: each touch-down halves the prediction (a table that moves all
    // the way to its targets).
    let mut leaky = FootstepLearner::new(
        BinTable::new([10, 8, 6], 1.0),
        Fixed(0.4, AtomicUsize::new(0)),
        LearnerConfig::literal(),
    )
    .unwrap();
    leaky.query(x).unwrap();
    leaky.touch_down(&StepOutcome::default()).unwrap();
    let (approx, _) = leaky.into_parts();
    let mut leaky = FootstepLearner::new(
        approx,
        Fixed(0.0, AtomicUsize::new(0)),
        LearnerConfig {
            leakage: 0.5,
            prior: steplearn::control::Prior::none(),
            ..LearnerConfig::literal()
        },
    )
    .unwrap();
    for want in [0.2, 0.1] {
        leaky.query(x).unwrap();
        leaky.touch_down(&StepOutcome::default()).unwrap();
        assert!((leaky.predict(x).unwrap() - want).abs() < 1e-12);
    }
}

#[test]
fn max_step_error_skips_steps_the_model_missed_but_not_the_learners_own_errors() {
    let cfg = LearnerConfig {
        max_step_error: Some(0.05),
        ..LearnerConfig::literal()
    };
    let x = input(0.0, 0.0, 0.0);
    let step = |f_e: f64| StepOutcome {
        f_e,
        ..StepOutcome::default()
    };
    let mut learner = FootstepLearner::new(
        BinTable::new([10, 8, 6], 1.0),
        Fixed(0.3, AtomicUsize::new(0)),
        cfg,
    )
    .unwrap();
    // dF was 0 and the step missed by 0.2 m: a disturbed step, nothing learned.
    assert_eq!(learner.query(x).unwrap(), 0.0);
    let report = learner.touch_down(&step(0.2)).unwrap();
    assert_eq!((report.samples, report.scale), (0, 0.0));
    assert_eq!(learner.predict(x).unwrap(), 0.0);
    // Within the bound: learned.
    learner.query(x).unwrap();
    learner.touch_down(&step(0.04)).unwrap();
    assert_eq!(learner.predict(x).unwrap(), 0.3);
    // Now dF = 0.3 and the step misses by 0.32: without the learner's part only 0.02, so the
    // learner's own error still teaches.
    assert_eq!(learner.query(x).unwrap(), 0.3);
    let report = learner.touch_down(&step(0.32)).unwrap();
    assert_eq!(report.samples, 1);
    assert_eq!(learner.predict(x).unwrap(), 0.6);
}

#[test]
fn max_step_error_in_metres_gates_only_the_footstep_offsets() {
    use steplearn::control::StepParameter;
    let cfg = LearnerConfig {
        max_step_error: Some(0.05),
        ..LearnerConfig::literal()
    };
    let x = input(0.0, 0.0, 0.0);
    // The same number, 0.2, is a 0.2 m miss of a footstep but 0.2 s of step time or 0.2 rad
    // of sole: only the metres are held against the metre threshold.
    let samples = |parameter: StepParameter| {
        let mut learner = FootstepLearner::for_parameters(
            BinTable::new([10, 8, 6], 1.0),
            [Fixed(0.3, AtomicUsize::new(0))],
            [parameter],
            cfg,
        )
        .unwrap();
        learner.query(x).unwrap();
        let outcome = StepOutcome {
            f_e: 0.2,
            ..StepOutcome::default()
        };
        learner.touch_down(&outcome).unwrap().samples
    };
    assert_eq!(samples(StepParameter::StepX), 0);
    assert_eq!(samples(StepParameter::StepY), 0);
    assert_eq!(samples(StepParameter::StepTime), 1);
    assert_eq!(samples(StepParameter::AnklePitch), 1);
    assert_eq!(samples(StepParameter::AnkleRoll), 1);
    assert!(StepParameter::StepX.is_length() && !StepParameter::StepTime.is_length());
}

#[test]
fn train_share_trains_only_the_latest_inputs_of_a_step() {
    let cfg = LearnerConfig {
        train_share: 0.5,
        ..LearnerConfig::literal()
    };
    let mut learner = FootstepLearner::new(
        BinTable::new([10, 8, 6], 1.0),
        Fixed(0.3, AtomicUsize::new(0)),
        cfg,
    )
    .unwrap();
    let xs = [-0.35, -0.15, 0.05, 0.25].map(|t| input(t, 0.0, 0.0));
    for x in xs {
        learner.query(x).unwrap();
    }
    let report = learner.touch_down(&StepOutcome::default()).unwrap();
    assert_eq!(report.samples, 2);
    let learned: Vec<f64> = xs.iter().map(|x| learner.predict(*x).unwrap()).collect();
    assert_eq!(learned, vec![0.0, 0.0, 0.3, 0.3]);
}

/// Eq. (6) with a trust region of 2 std and `fallback`, over a bin table and a rule that always
/// asks for 0.3.
fn trust_learner(fallback: TrustFallback) -> FootstepLearner<BinTable, Fixed> {
    let cfg = LearnerConfig {
        trust_region: Some(2.0),
        trust_fallback: fallback,
        ..LearnerConfig::literal()
    };
    FootstepLearner::new(
        BinTable::new([10, 8, 6], 1.0),
        Fixed(0.3, AtomicUsize::new(0)),
        cfg,
    )
    .unwrap()
}

#[test]
fn trust_region_applies_the_offset_only_near_trained_inputs() {
    let mut learner = trust_learner(TrustFallback::Zero);
    // Nothing trained yet: no offset, whatever the approximator says.
    for k in 0..20 {
        assert_eq!(
            learner
                .query(input(0.01 * (k % 5) as f64, 0.0, 0.1))
                .unwrap(),
            0.0
        );
    }
    learner.touch_down(&StepOutcome::default()).unwrap();
    // Trained at theta_E in [0, 0.04] (mean 0.02, std 0.0141), theta_E_dot 0 (std floored at
    // 2% of the prior's 3 rad/s): all the points below share the trained bin, which predicts
    // 0.3. Inside, the full prediction; 2.5 std away, half; 5 std away, none.
    let std = 0.02f64.sqrt() / 10.0;
    let inside = input(0.02, 0.0, 0.1);
    let half = input(0.02 + 2.5 * std, 0.0, 0.1);
    let far = input(0.02 + 5.0 * std, 0.0, 0.1);
    let far_rate = input(0.02, 0.4, 0.1);
    for x in [inside, half, far, far_rate] {
        assert_eq!(learner.predict(x).unwrap(), 0.3);
    }
    assert_eq!(learner.query(inside).unwrap(), 0.3);
    assert!((learner.query(half).unwrap() - 0.15).abs() < 1e-9);
    assert_eq!(learner.query(far).unwrap(), 0.0);
    assert_eq!(learner.query(far_rate).unwrap(), 0.0);
    // The region survives a save / load round trip.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("learner.json");
    learner.save(&path).unwrap();
    let mut loaded: FootstepLearner<BinTable, _> =
        FootstepLearner::load(&path, Fixed(0.3, AtomicUsize::new(0))).unwrap();
    assert_eq!(loaded.query(inside).unwrap(), 0.3);
    assert_eq!(loaded.query(far_rate).unwrap(), 0.0);
    // Tampered statistics are a corrupt file, not a silently wrong region.
    let mut json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    json["trained"][0]["m2"] = serde_json::json!(-1.0);
    std::fs::write(&path, json.to_string()).unwrap();
    let err = FootstepLearner::<BinTable, _>::load(&path, Fixed(0.3, AtomicUsize::new(0)))
        .err()
        .unwrap();
    assert!(
        err.to_string().contains("trained-input statistics"),
        "{err}"
    );
}

#[test]
fn the_nominal_trust_fallback_keeps_the_offset_learned_at_the_nominal_state() {
    let learner_with = |fallback| {
        let mut learner = trust_learner(fallback);
        for k in 0..20 {
            learner
                .query(input(0.01 * (k % 5) as f64, 0.0, 0.1))
                .unwrap();
        }
        learner.touch_down(&StepOutcome::default()).unwrap();
        learner
    };
    // Trained in one bin (theta_E 0-0.04, theta_E_dot 0, F_R 0.1), which predicts 0.3. Far in
    // theta_E_dot (another, untrained bin) and far in F_R (0.2: another bin too).
    let (inside, far_rate, far_ref) = (
        input(0.02, 0.0, 0.1),
        input(0.02, 1.5, 0.1),
        input(0.02, 0.0, 0.2),
    );
    let mut zero = learner_with(TrustFallback::Zero);
    let mut nominal = learner_with(TrustFallback::Nominal);
    for x in [far_rate, far_ref] {
        assert_eq!(zero.predict(x).unwrap(), 0.0, "an untrained bin");
        assert_eq!(zero.query(x).unwrap(), 0.0);
        // The nominal state (mean theta_E and rate, F_R clamped into the region) is trained.
        assert_eq!(nominal.query(x).unwrap(), 0.3);
    }
    assert_eq!(zero.query(inside).unwrap(), 0.3);
    assert_eq!(nominal.query(inside).unwrap(), 0.3);
    // Before any training the fallback is the prior's belief, not a guess.
    let mut fresh = trust_learner(TrustFallback::Nominal);
    assert_eq!(fresh.query(far_rate).unwrap(), 0.0);
    // The setting is part of the saved learner.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("learner.json");
    nominal.save(&path).unwrap();
    let mut loaded: FootstepLearner<BinTable, _> =
        FootstepLearner::load(&path, Fixed(0.3, AtomicUsize::new(0))).unwrap();
    assert_eq!(loaded.query(far_rate).unwrap(), 0.3);
}

#[test]
fn output_clamp_limits_the_query_not_the_model() {
    let cfg = LearnerConfig {
        max_offset: Some(0.05),
        ..LearnerConfig::literal()
    };
    let mut learner = FootstepLearner::new(table(), Fixed(0.3, AtomicUsize::new(0)), cfg).unwrap();
    let x = input(0.0, 0.0, 0.0);
    learner.query(x).unwrap();
    learner.touch_down(&StepOutcome::default()).unwrap();
    assert_eq!(learner.query(x).unwrap(), 0.05);
    assert!((learner.predict(x).unwrap() - 0.3).abs() < 1e-15);
}

#[test]
fn a_one_sided_offset_range_clamps_the_query_and_stops_the_targets_at_its_ends() {
    let x = input(0.0, 0.0, 0.0);
    // One touch-down with G = g (eta 1): the query after it and the model's prediction.
    let taught = |g: f64, range: [f64; 2], anti_windup: bool| {
        let cfg = LearnerConfig {
            offset_range: Some(range),
            anti_windup,
            ..LearnerConfig::literal()
        };
        let mut learner =
            FootstepLearner::new(table(), Fixed(g, AtomicUsize::new(0)), cfg).unwrap();
        learner.query(x).unwrap();
        learner.touch_down(&StepOutcome::default()).unwrap();
        (learner.query(x).unwrap(), learner.predict(x).unwrap())
    };
    // Asked past the closed end, the learner stays at it and learns nothing beyond it.
    assert_eq!(taught(0.3, [-0.1, 0.0], true), (0.0, 0.0));
    // Within the range it learns up to the end.
    let (q, p) = taught(-0.3, [-0.1, 0.0], true);
    assert!(
        (q + 0.1).abs() < 1e-12 && (p + 0.1).abs() < 1e-12,
        "{q} {p}"
    );
    let (q, p) = taught(0.3, [-0.1, 0.05], true);
    assert!(
        (q - 0.05).abs() < 1e-12 && (p - 0.05).abs() < 1e-12,
        "{q} {p}"
    );
    // Without anti-windup the range clamps the query only.
    let (q, p) = taught(0.3, [-0.1, 0.0], false);
    assert_eq!(q, 0.0);
    assert!((p - 0.3).abs() < 1e-12, "{p}");
    // With max_offset too, the query is clamped to both.
    let cfg = LearnerConfig {
        max_offset: Some(0.02),
        offset_range: Some([-0.1, 0.0]),
        ..LearnerConfig::literal()
    };
    let mut learner = FootstepLearner::new(table(), Fixed(-0.3, AtomicUsize::new(0)), cfg).unwrap();
    learner.query(x).unwrap();
    learner.touch_down(&StepOutcome::default()).unwrap();
    assert_eq!(learner.query(x).unwrap(), -0.02);
}

#[test]
fn bad_configs_shapes_and_inputs_are_typed_errors() {
    for cfg in [
        LearnerConfig {
            eta: 0.0,
            ..LearnerConfig::literal()
        },
        LearnerConfig {
            eta: f64::NAN,
            ..LearnerConfig::literal()
        },
        LearnerConfig {
            max_samples_per_step: 1,
            ..LearnerConfig::literal()
        },
        LearnerConfig {
            max_offset: Some(-1.0),
            ..LearnerConfig::literal()
        },
    ] {
        assert!(matches!(
            FootstepLearner::new(table(), BalanceOnly, cfg),
            Err(LearnerError::InvalidConfig { .. })
        ));
    }
    assert!(matches!(
        FootstepLearner::new(TwoInputs, BalanceOnly, LearnerConfig::literal()),
        Err(LearnerError::WrongApproximatorShape {
            expected: (3, 1),
            inputs: 2,
            outputs: 1
        })
    ));
    let mut learner = FootstepLearner::new(table(), BalanceOnly, LearnerConfig::literal()).unwrap();
    learner.query(input(0.1, 0.0, 0.0)).unwrap();
    assert!(matches!(
        learner.query(input(f64::NAN, 0.0, 0.0)),
        Err(LearnerError::NonFinite {
            what: "theta_e",
            ..
        })
    ));
    assert_eq!(
        learner.recorded_inputs().len(),
        1,
        "rejected query not recorded"
    );
    // a bad outcome is rejected before any change: the step's inputs are kept
    let bad = StepOutcome {
        theta_e: f64::INFINITY,
        ..Default::default()
    };
    assert!(matches!(
        learner.touch_down(&bad),
        Err(LearnerError::NonFinite { .. })
    ));
    assert_eq!(learner.recorded_inputs().len(), 1);
    assert_eq!(learner.predict(input(0.1, 0.0, 0.0)).unwrap(), 0.0);
    // and the learner is still usable
    let ok = StepOutcome {
        theta_e: 0.1,
        ..Default::default()
    };
    learner.touch_down(&ok).unwrap();
    assert!((learner.predict(input(0.1, 0.0, 0.0)).unwrap() - 0.1).abs() < 1e-15);
    let grid = InputGrid {
        points: [0, 1, 1],
        ..Default::default()
    };
    assert!(matches!(
        learner.learning_metric(&grid),
        Err(LearnerError::InvalidConfig { .. })
    ));
}

#[test]
fn approximator_failure_propagates_and_leaves_the_learner_usable() {
    let mut model = table();
    model.fail_after = Some(1);
    let mut learner = FootstepLearner::new(
        model,
        Fixed(0.2, AtomicUsize::new(0)),
        LearnerConfig::literal(),
    )
    .unwrap();
    let (a, b) = (input(-0.4, 0.0, 0.0), input(0.4, 0.0, 0.0));
    learner.query(a).unwrap();
    learner.query(b).unwrap();
    let err = learner.touch_down(&StepOutcome::default()).unwrap_err();
    assert!(
        matches!(err, LearnerError::Approx { applied: 1, .. }),
        "{err}"
    );
    // the first update stayed, the second was rejected without effect
    assert!((learner.predict(a).unwrap() - 0.2).abs() < 1e-15);
    assert_eq!(learner.predict(b).unwrap(), 0.0);
    // the failed step was discarded; the learner keeps working
    assert_eq!(learner.recorded_inputs().len(), 0);
    assert_eq!(learner.query(b).unwrap(), 0.0);
    assert!(learner.learning_metric(&InputGrid::default()).unwrap() > 0.0);
}

#[test]
fn metric_and_map_sample_the_model() {
    let mut learner = FootstepLearner::new(
        table(),
        Fixed(0.1, AtomicUsize::new(0)),
        LearnerConfig::literal(),
    )
    .unwrap();
    let grid = InputGrid {
        points: [10, 8, 6],
        ..Default::default()
    };
    assert_eq!(learner.learning_metric(&grid).unwrap(), 0.0);
    learner.query(input(0.02, 0.1, 0.0)).unwrap();
    learner.touch_down(&StepOutcome::default()).unwrap();
    // a 10x8x6 grid over the table's box hits every bin once (default box has wider theta_dot)
    let inside = InputGrid {
        hi: input(0.45, 1.75, 0.175),
        lo: input(-0.45, -1.75, -0.075),
        points: [10, 8, 6],
    };
    assert!((learner.learning_metric(&inside).unwrap() - 0.1).abs() < 1e-12);
    let spec = MapSpec {
        resolution: (5, 3),
        f_r: 0.0,
        ..Default::default()
    };
    let map = learner.offset_map(&spec).unwrap();
    assert_eq!(map.theta_e, vec![-0.5, -0.25, 0.0, 0.25, 0.5]);
    assert_eq!(map.theta_e_dot, vec![-3.0, 0.0, 3.0]);
    assert_eq!(map.values.len(), 15);
    // row 1 (rate 0), column 2 (angle 0) is the trained bin
    assert!((map.values[5 + 2] - 0.1).abs() < 1e-15);
    assert_eq!(map.values.iter().filter(|v| **v != 0.0).count(), 1);
    let bad = MapSpec {
        theta_e: (1.0, -1.0),
        ..spec
    };
    assert!(learner.offset_map(&bad).is_err());
}

#[test]
fn save_load_round_trip_keeps_learning() {
    let dir = std::env::temp_dir().join(format!("steplearn-learner-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("learner.json");
    let cfg = LearnerConfig {
        eta: 0.7,
        max_samples_per_step: 8,
        max_offset: Some(0.3),
        ..LearnerConfig::literal()
    };
    let mut learner = FootstepLearner::new(table(), PendulumCart::default(), cfg).unwrap();
    let step = StepOutcome {
        theta_e: 0.1,
        theta_e_dot: 0.3,
        f_e: -0.02,
        f_r: 0.1,
    };
    for i in 0..5 {
        learner.query(input(0.01 * i as f64, 0.2, 0.1)).unwrap();
        learner.touch_down(&step).unwrap();
    }
    learner.save(&path).unwrap();
    let mut loaded: FootstepLearner<BinTable, PendulumCart> =
        FootstepLearner::load(&path, PendulumCart::default()).unwrap();
    assert_eq!(loaded.config(), learner.config());
    let grid = InputGrid::default();
    assert_eq!(
        loaded.learning_metric(&grid).unwrap().to_bits(),
        learner.learning_metric(&grid).unwrap().to_bits()
    );
    // both keep learning identically
    for l in [&mut learner, &mut loaded] {
        l.query(input(0.3, -1.0, 0.0)).unwrap();
        l.touch_down(&step).unwrap();
    }
    assert_eq!(
        loaded.learning_metric(&grid).unwrap().to_bits(),
        learner.learning_metric(&grid).unwrap().to_bits()
    );
    assert!(loaded.predict(input(0.3, -1.0, 0.0)).unwrap() != 0.0);
    // a corrupt file is an error and does not touch the good one
    std::fs::write(dir.join("bad.json"), "{\"config\": 1}").unwrap();
    assert!(matches!(
        FootstepLearner::<BinTable, _>::load(dir.join("bad.json"), BalanceOnly),
        Err(LearnerError::Approx { .. })
    ));
    let good = std::fs::read_to_string(&path).unwrap();
    let broken = good.replacen("\"eta\":0.7", "\"eta\":-0.7", 1);
    assert_ne!(broken, good);
    std::fs::write(dir.join("neg.json"), broken).unwrap();
    assert!(FootstepLearner::<BinTable, _>::load(dir.join("neg.json"), BalanceOnly).is_err());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A toy sagittal walker, pendulum-cart-like: stepping too short leaves the trunk leaning
/// forward at the next touch-down, stepping too far tips it back. The "analytic model" steps
/// `model_bias(F_R)` away from the reference and ignores the trunk; the learner adds dF.
struct ToyWalker {
    theta: f64,
    theta_dot: f64,
}

const TICKS: usize = 40;
const STEP_T: f64 = 0.4;

fn model_bias(f_r: f64) -> f64 {
    -0.03 - 0.2 * f_r
}

/// Steady-state step size that keeps the trunk where it is: F* = F_R + 0.2 theta.
fn balancing_step(f_r: f64, theta: f64) -> f64 {
    f_r + 0.2 * theta
}

impl ToyWalker {
    /// Walks one step with `df(theta, theta_dot)` queried every tick; returns the outcome.
    fn step(
        &mut self,
        f_r: f64,
        push: f64,
        mut df: impl FnMut(LearnerInput) -> f64,
    ) -> StepOutcome {
        self.theta_dot += push;
        let mut last_df = 0.0;
        let dt = STEP_T / TICKS as f64;
        for _ in 0..TICKS {
            last_df = df(input(self.theta, self.theta_dot, f_r));
            self.theta += self.theta_dot * dt;
            self.theta_dot *= 0.97;
        }
        let f_hat = f_r + model_bias(f_r) + last_df;
        let shortfall = balancing_step(f_r, self.theta) - f_hat;
        let theta_next = 0.6 * self.theta + 0.8 * shortfall;
        self.theta_dot = 0.5 * (theta_next - self.theta) / STEP_T;
        self.theta = theta_next;
        StepOutcome {
            theta_e: self.theta,
            theta_e_dot: self.theta_dot,
            f_e: f_hat - f_r,
            f_r,
        }
    }
}

/// Mean |theta_E| and |F_E| over windows of steps, with or without learning.
fn walk(learn: bool, steps: usize) -> Vec<StepOutcome> {
    let mut learner =
        FootstepLearner::new(table(), PendulumCart::default(), LearnerConfig::default()).unwrap();
    let mut walker = ToyWalker {
        theta: 0.0,
        theta_dot: 0.0,
    };
    let refs = [0.0, 0.1, 0.2, 0.05, 0.15];
    (0..steps)
        .map(|k| {
            let f_r = refs[(k / 25) % refs.len()];
            // a push every 50 steps
            let push = if k % 50 == 10 { 0.6 } else { 0.0 };
            if learn {
                let out = walker.step(f_r, push, |x| learner.query(x).unwrap());
                learner.touch_down(&out).unwrap();
                out
            } else {
                walker.step(f_r, push, |_| 0.0)
            }
        })
        .collect()
}

fn mean_abs(outs: &[StepOutcome]) -> (f64, f64) {
    let n = outs.len() as f64;
    (
        outs.iter().map(|o| o.theta_e.abs()).sum::<f64>() / n,
        outs.iter().map(|o| o.f_e.abs()).sum::<f64>() / n,
    )
}

#[test]
fn learning_reduces_trunk_and_step_errors_on_a_toy_walker() {
    let steps = 1000;
    let learned = walk(true, steps);
    let fixed = walk(false, steps);
    let (th_first, fe_first) = mean_abs(&learned[..100]);
    let (th_last, fe_last) = mean_abs(&learned[steps - 100..]);
    let (th_model, fe_model) = mean_abs(&fixed[steps - 100..]);
    println!(
        "|theta_E| first {th_first:.4} last {th_last:.4} model {th_model:.4}; \
         |F_E| first {fe_first:.4} last {fe_last:.4} model {fe_model:.4}"
    );
    assert!(
        learned
            .iter()
            .all(|o| o.theta_e.is_finite() && o.f_e.is_finite())
    );
    // measured: |theta_E| 0.038 -> 0.0059 (model 0.188), |F_E| 0.043 -> 0.0017 (model 0.055)
    assert!(th_last < 0.5 * th_first && fe_last < 0.5 * fe_first);
    assert!(th_last < 0.25 * th_model && fe_last < 0.25 * fe_model);
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { rng_seed: proptest::test_runner::RngSeed::Fixed(13), failure_persistence: None, ..proptest::prelude::ProptestConfig::default() })]
    /// On a fresh table (first update of a bin moves it all the way), one touch-down leaves
    /// exactly F_old + eta G = eta G at every recorded input, nothing elsewhere, whatever the
    /// inputs, their number (subsampling included), eta and G.
    #[test]
    fn eq6_holds_for_any_step(
        points in proptest::collection::vec((-0.5..0.5f64, -2.0..2.0f64, -0.1..0.2f64), 1..300),
        eta in 0.01..3.0f64,
        g in -1.0..1.0f64,
    ) {
        let cfg = LearnerConfig { eta, max_samples_per_step: 32, ..LearnerConfig::literal() };
        let mut learner = FootstepLearner::new(table(), Fixed(g, AtomicUsize::new(0)), cfg).unwrap();
        for &(a, b, c) in &points {
            learner.query(input(a, b, c)).unwrap();
        }
        let kept: Vec<LearnerInput> = learner.recorded_inputs().collect();
        proptest::prop_assert!(kept.len() <= 32 && kept.len() >= points.len().min(16));
        let report = learner.touch_down(&StepOutcome::default()).unwrap();
        proptest::prop_assert_eq!(report.samples, kept.len());
        for x in &kept {
            proptest::prop_assert_eq!(learner.predict(*x).unwrap(), eta * g);
        }
        let trained = learner.approximator().values.iter().filter(|v| **v != 0.0).count();
        proptest::prop_assert!(trained <= kept.len());
    }
}

#[test]
fn works_with_a_rule_chosen_at_run_time() {
    use steplearn::rules::{RuleConfig, RuleKind};
    let rule = RuleConfig::from(RuleKind::BalanceOnly).build().unwrap();
    let mut learner = FootstepLearner::new(table(), rule, LearnerConfig::literal()).unwrap();
    learner.query(input(0.1, 0.0, 0.0)).unwrap();
    let report = learner
        .touch_down(&StepOutcome {
            theta_e: 0.1,
            ..Default::default()
        })
        .unwrap();
    assert_eq!(report.gradient, 0.1);
    assert!((learner.predict(input(0.1, 0.0, 0.0)).unwrap() - 0.1).abs() < 1e-15);
}

#[test]
fn input_grid_box_matches_its_corners_and_rejects_flat_axes() {
    let grid = InputGrid::default();
    let b = grid.input_box().unwrap();
    assert_eq!(b.lo, grid.lo.to_array().to_vec());
    assert_eq!(b.hi, grid.hi.to_array().to_vec());
    let flat = InputGrid {
        hi: input(0.5, 3.0, -0.1),
        ..grid
    };
    // a single F_R value is a valid grid to sample but not a box to size an approximator by
    assert!(flat.validate().is_ok());
    assert!(flat.input_box().is_err());
}

/// A table that jumps all the way to its targets (the least stable approximator there is).
fn jumpy() -> BinTable {
    BinTable::new([10, 8, 6], 1.0)
}

fn one_step(learner: &mut FootstepLearner<BinTable, Fixed>, x: LearnerInput, reach: (f64, f64)) {
    learner.query(x).unwrap();
    learner.set_reach(reach.0, reach.1).unwrap();
}

#[test]
fn gain_guard_keeps_the_applied_gain_at_its_limit_for_a_jumpy_approximator() {
    let cfg = LearnerConfig {
        prior: steplearn::control::Prior::none(),
        ..LearnerConfig::default()
    };
    let limit = cfg.max_gain.unwrap();
    let mut learner = FootstepLearner::new(jumpy(), Fixed(0.3, AtomicUsize::new(0)), cfg).unwrap();
    let x = input(0.05, 0.1, 0.0);
    one_step(&mut learner, x, (f64::NEG_INFINITY, f64::INFINITY));
    let report = learner.touch_down(&StepOutcome::default()).unwrap();
    // The table moves all the way (response 1); the guard scales eta G = 0.3 to 0.2 * 0.3.
    assert!((report.response - 1.0).abs() < 1e-12, "{report:?}");
    assert!(
        report.gain <= limit && report.gain > 0.9 * limit,
        "{report:?}"
    );
    assert!((report.scale - 0.95 * limit).abs() < 1e-9, "{report:?}");
    assert!((learner.predict(x).unwrap() - 0.3 * report.gain).abs() < 1e-12);
    // Without the guard the same table applies the whole step.
    let mut literal = FootstepLearner::new(
        jumpy(),
        Fixed(0.3, AtomicUsize::new(0)),
        LearnerConfig::literal(),
    )
    .unwrap();
    one_step(&mut literal, x, (f64::NEG_INFINITY, f64::INFINITY));
    let report = literal.touch_down(&StepOutcome::default()).unwrap();
    assert_eq!((report.gain, report.scale), (1.0, 1.0));
    assert_eq!(literal.predict(x).unwrap(), 0.3);
}

#[test]
fn anti_windup_bounds_the_offset_by_the_reach_and_unwinds_it() {
    let cfg = LearnerConfig {
        max_gain: None,
        prior: steplearn::control::Prior::none(),
        ..LearnerConfig::default()
    };
    let mut learner = FootstepLearner::new(jumpy(), Fixed(0.5, AtomicUsize::new(0)), cfg).unwrap();
    let x = input(0.1, 0.0, 0.1);
    // G keeps asking for more; only 0.12 more can change the step.
    for _ in 0..50 {
        one_step(&mut learner, x, (-0.3, 0.12));
        learner.touch_down(&StepOutcome::default()).unwrap();
        assert!(learner.predict(x).unwrap() <= 0.12 + 1e-12);
    }
    assert!((learner.predict(x).unwrap() - 0.12).abs() < 1e-12);
    // Past a smaller reach the offset stops where it is (it is not pulled into the reach)...
    one_step(&mut learner, x, (-0.3, 0.05));
    learner.touch_down(&StepOutcome::default()).unwrap();
    assert!((learner.predict(x).unwrap() - 0.12).abs() < 1e-12);
    // ... and moves on, up to the end of a larger reach.
    one_step(&mut learner, x, (0.4, 0.6));
    learner.touch_down(&StepOutcome::default()).unwrap();
    assert!((learner.predict(x).unwrap() - 0.6).abs() < 1e-12);
    // The literal eq. (6) integrates without bound.
    let mut literal = FootstepLearner::new(
        jumpy(),
        Fixed(0.5, AtomicUsize::new(0)),
        LearnerConfig::literal(),
    )
    .unwrap();
    for _ in 0..50 {
        one_step(&mut literal, x, (-0.3, 0.12));
        literal.touch_down(&StepOutcome::default()).unwrap();
    }
    assert!((literal.predict(x).unwrap() - 25.0).abs() < 1e-9);
}

#[test]
fn set_reach_rejects_nan_and_reversed_bounds_without_changing_the_step() {
    let mut learner = FootstepLearner::new(
        jumpy(),
        Fixed(0.5, AtomicUsize::new(0)),
        LearnerConfig::literal(),
    )
    .unwrap();
    learner.query(input(0.0, 0.0, 0.0)).unwrap();
    assert!(learner.set_reach(0.2, 0.1).is_err());
    assert!(learner.set_reach(f64::NAN, 0.1).is_err());
    assert_eq!(learner.recorded_inputs().len(), 1);
}

#[test]
fn the_prior_is_held_and_lowers_lwprs_response() {
    use steplearn::approx::ApproxKind;
    let make = |prior| {
        let lwpr = ApproxKind::Lwpr
            .build(&InputGrid::default().input_box().unwrap())
            .unwrap();
        let cfg = LearnerConfig {
            max_gain: None,
            prior,
            ..LearnerConfig::default()
        };
        FootstepLearner::new(lwpr, PendulumCart::default(), cfg).unwrap()
    };
    let mut with = make(steplearn::control::Prior::default());
    let mut without = make(steplearn::control::Prior::none());
    let x = input(0.05, 0.2, 0.1);
    assert_eq!(with.predict(x).unwrap(), 0.0);
    let step = StepOutcome {
        theta_e: 0.05,
        ..StepOutcome::default()
    };
    for l in [&mut with, &mut without] {
        for i in 0..20 {
            l.query(input(0.05 + 0.001 * i as f64, 0.2, 0.1)).unwrap();
        }
    }
    let r_with = with.touch_down(&step).unwrap().response;
    let r_without = without.touch_down(&step).unwrap().response;
    eprintln!("response with the prior {r_with}, without {r_without}");
    assert!(r_without > 0.9, "{r_without}");
    // measured: 0.32 with the prior, 1.00 without
    assert!(r_with < 0.5, "{r_with}");
}

#[test]
fn a_fall_is_learned_from_only_when_that_setting_is_on() {
    let fall = StepOutcome {
        theta_e: 0.9,
        theta_e_dot: 8.0,
        f_e: 0.02,
        f_r: 0.0,
    };
    let x = input(0.2, 1.0, 0.0);
    for on in [false, true] {
        let cfg = LearnerConfig {
            learn_from_falls: on,
            ..LearnerConfig::literal()
        };
        let mut learner = FootstepLearner::new(jumpy(), BalanceOnly, cfg).unwrap();
        learner.query(x).unwrap();
        let report = learner.fall(&fall).unwrap();
        assert_eq!(learner.recorded_inputs().len(), 0);
        if on {
            // theta_E clamped to the fall limit (0.3) before the rule sees it
            assert_eq!(report.unwrap().gradient, 0.3);
            assert_eq!(learner.predict(x).unwrap(), 0.3);
        } else {
            assert!(report.is_none());
            assert_eq!(learner.predict(x).unwrap(), 0.0);
        }
    }
}

#[test]
fn new_learner_settings_are_validated() {
    for bad in [
        LearnerConfig {
            max_gain: Some(0.0),
            ..LearnerConfig::default()
        },
        LearnerConfig {
            max_gain: Some(f64::NAN),
            ..LearnerConfig::default()
        },
        LearnerConfig {
            fall_theta_limit: -1.0,
            ..LearnerConfig::default()
        },
        LearnerConfig {
            dead_zone: -0.01,
            ..LearnerConfig::default()
        },
        LearnerConfig {
            dead_zone: f64::INFINITY,
            ..LearnerConfig::default()
        },
        LearnerConfig {
            leakage: 1.0,
            ..LearnerConfig::default()
        },
        LearnerConfig {
            leakage: f64::NAN,
            ..LearnerConfig::default()
        },
        LearnerConfig {
            train_share: 0.0,
            ..LearnerConfig::default()
        },
        LearnerConfig {
            train_share: 1.5,
            ..LearnerConfig::default()
        },
        LearnerConfig {
            train_share: f64::NAN,
            ..LearnerConfig::default()
        },
        LearnerConfig {
            prior: steplearn::control::Prior {
                lo: input(0.3, 0.0, 0.0),
                hi: input(-0.3, 1.0, 1.0),
                samples: 10,
            },
            ..LearnerConfig::default()
        },
    ] {
        let err = FootstepLearner::new(table(), BalanceOnly, bad)
            .err()
            .unwrap();
        assert!(matches!(err, LearnerError::InvalidConfig { .. }), "{err}");
    }
}

#[test]
fn a_parameter_table_sets_its_offset_apart_from_the_shared_settings() {
    use steplearn::control::ParameterSettings;
    use steplearn::control::StepParameter;
    let x = input(0.0, 0.0, 0.0);
    // Shared: dead zone 0.1, eta 1. The step-x table: no dead zone, eta 0.5.
    let cfg = LearnerConfig {
        dead_zone: 0.1,
        step_x: ParameterSettings {
            dead_zone: Some(0.0),
            eta: Some(0.5),
            ..ParameterSettings::default()
        },
        ..LearnerConfig::literal()
    };
    let learned = |parameter: StepParameter| {
        let mut learner = FootstepLearner::for_parameters(
            BinTable::new([10, 8, 6], 1.0),
            [Fixed(0.3, AtomicUsize::new(0))],
            [parameter],
            cfg,
        )
        .unwrap();
        assert_eq!(learner.parameter(), parameter);
        learner.query(x).unwrap();
        learner.touch_down(&StepOutcome::default()).unwrap();
        learner.predict(x).unwrap()
    };
    // step-x: 0.5 * 0.3; step-time and step-y (no table): 1 * (0.3 - 0.1).
    assert!((learned(StepParameter::StepX) - 0.15).abs() < 1e-12);
    assert!((learned(StepParameter::StepTime) - 0.2).abs() < 1e-12);
    assert!((learned(StepParameter::StepY) - 0.2).abs() < 1e-12);
    // `new` is the paper's step-x; `as_parameter` switches to another parameter's settings.
    let mut switched = FootstepLearner::new(
        BinTable::new([10, 8, 6], 1.0),
        Fixed(0.3, AtomicUsize::new(0)),
        cfg,
    )
    .unwrap()
    .as_parameter(StepParameter::StepTime)
    .unwrap();
    switched.query(x).unwrap();
    switched.touch_down(&StepOutcome::default()).unwrap();
    assert!((switched.predict(x).unwrap() - 0.2).abs() < 1e-12);
}

#[test]
fn a_bad_value_in_a_parameter_table_is_refused_by_its_key() {
    use steplearn::control::ParameterSettings;
    use steplearn::control::StepParameter;
    let cases = [
        (
            "step-time.eta",
            LearnerConfig {
                step_time: ParameterSettings {
                    eta: Some(-1.0),
                    ..ParameterSettings::default()
                },
                ..LearnerConfig::default()
            },
        ),
        (
            "step-y.leakage",
            LearnerConfig {
                step_y: ParameterSettings {
                    leakage: Some(1.0),
                    ..ParameterSettings::default()
                },
                ..LearnerConfig::default()
            },
        ),
        (
            "step-x.dead_zone",
            LearnerConfig {
                step_x: ParameterSettings {
                    dead_zone: Some(f64::NAN),
                    ..ParameterSettings::default()
                },
                ..LearnerConfig::default()
            },
        ),
        (
            "offset_range",
            LearnerConfig {
                offset_range: Some([-0.1, f64::INFINITY]),
                ..LearnerConfig::default()
            },
        ),
        (
            "step-x.max_offset",
            LearnerConfig {
                step_x: ParameterSettings {
                    max_offset: Some(0.0),
                    ..ParameterSettings::default()
                },
                ..LearnerConfig::default()
            },
        ),
        // A footstep offset is learned in its own plane only; the step time in either or both.
        (
            "step-x.plane",
            LearnerConfig {
                step_x: ParameterSettings {
                    plane: Some(steplearn::control::Planes::Frontal),
                    ..ParameterSettings::default()
                },
                ..LearnerConfig::default()
            },
        ),
        (
            "step-y.plane",
            LearnerConfig {
                step_y: ParameterSettings {
                    plane: Some(steplearn::control::Planes::Sagittal),
                    ..ParameterSettings::default()
                },
                ..LearnerConfig::default()
            },
        ),
        (
            "step-x.plane",
            LearnerConfig {
                step_x: ParameterSettings {
                    plane: Some(steplearn::control::Planes::Both),
                    ..ParameterSettings::default()
                },
                ..LearnerConfig::default()
            },
        ),
    ];
    // The sole's pitch is learned in the sagittal plane only, its roll in the frontal plane
    // only, each with its own table.
    use steplearn::control::Planes;
    let table_of = |sole: StepParameter, own: ParameterSettings| {
        let mut cfg = LearnerConfig::default();
        match sole {
            StepParameter::AnkleRoll => cfg.ankle_roll = own,
            _ => cfg.ankle_pitch = own,
        }
        cfg
    };
    let plane = |plane| ParameterSettings {
        plane: Some(plane),
        ..ParameterSettings::default()
    };
    let range = |r| ParameterSettings {
        offset_range: Some(r),
        ..ParameterSettings::default()
    };
    let (pitch, roll) = (StepParameter::AnklePitch, StepParameter::AnkleRoll);
    let ankle_cases = [
        ("ankle-pitch.plane", pitch, plane(Planes::Frontal)),
        ("ankle-roll.plane", roll, plane(Planes::Sagittal)),
        ("ankle-roll.plane", roll, plane(Planes::Both)),
        (
            "ankle-pitch.max_offset",
            pitch,
            ParameterSettings {
                max_offset: Some(f64::INFINITY),
                ..ParameterSettings::default()
            },
        ),
        // A range holds the prior's 0 and is not empty.
        ("ankle-pitch.offset_range", pitch, range([0.05, 0.1])),
        ("ankle-roll.offset_range", roll, range([0.0, 0.0])),
        ("ankle-pitch.offset_range", pitch, range([f64::NAN, 0.0])),
        (
            "ankle-roll.eta",
            roll,
            ParameterSettings {
                eta: Some(f64::NAN),
                ..ParameterSettings::default()
            },
        ),
    ]
    .map(|(key, sole, own)| (key, table_of(sole, own)));
    for (key, cfg) in cases.into_iter().chain(ankle_cases) {
        match cfg.check() {
            Err(LearnerError::InvalidConfig { param, .. }) => assert_eq!(param, key),
            other => panic!("{key}: expected a refusal, got {other:?}"),
        }
        assert!(
            FootstepLearner::new(table(), PendulumCart::default(), cfg).is_err(),
            "{key}: a learner was built"
        );
    }
}

#[test]
fn parameter_tables_read_from_toml_and_a_default_config_writes_none() {
    use steplearn::control::StepParameter;
    let written = toml::to_string(&LearnerConfig::default()).unwrap();
    assert!(!written.contains("step-"), "{written}");
    let cfg: LearnerConfig =
        toml::from_str("dead_zone = 0.06\n[step-time]\neta = 0.5\nleakage = 0.1\n").unwrap();
    let time = cfg.offset(StepParameter::StepTime);
    assert_eq!((time.eta, time.dead_zone, time.leakage), (0.5, 0.06, 0.1));
    assert_eq!(cfg.offset(StepParameter::StepX).dead_zone, 0.06);
    assert_eq!(cfg.offset(StepParameter::StepY).dead_zone, 0.06);
    let back: LearnerConfig = toml::from_str(&toml::to_string(&cfg).unwrap()).unwrap();
    assert_eq!(back, cfg);
    let unknown = toml::from_str::<LearnerConfig>("[step-time]\nmax_gain = 0.1\n");
    assert!(
        unknown.unwrap_err().to_string().contains("max_gain"),
        "a learner-wide key in a parameter's table is refused"
    );
}

#[test]
fn the_step_time_may_be_learned_in_the_frontal_plane() {
    use steplearn::control::Planes;
    use steplearn::control::StepParameter;
    let cfg: LearnerConfig = toml::from_str("[step-time]\nplane = \"frontal\"\n").unwrap();
    let checked = cfg.check().unwrap();
    assert_eq!(checked.planes(StepParameter::StepTime), Planes::Frontal);
    assert_eq!(checked.planes(StepParameter::StepX), Planes::Sagittal);
    assert_eq!(checked.planes(StepParameter::StepY), Planes::Frontal);
    let back: LearnerConfig = toml::from_str(&toml::to_string(&cfg).unwrap()).unwrap();
    assert_eq!(back, cfg);
    // The default plane is left out of written configs, and an unknown plane is refused.
    let default = LearnerConfig::default().check().unwrap();
    assert_eq!(default.planes(StepParameter::StepTime), Planes::Sagittal);
    let bad = toml::from_str::<LearnerConfig>("[step-time]\nplane = \"diagonal\"\n");
    assert!(bad.unwrap_err().to_string().contains("diagonal"));
}

/// `plane = "both"` is a setting of the step time only, and a learner of one plane refuses it
/// for its own parameter (naming the key) but not for another's.
#[test]
fn the_step_time_may_be_learned_in_both_planes_by_a_step_learner_only() {
    use steplearn::control::Planes;
    use steplearn::control::StepParameter;
    let cfg: LearnerConfig = toml::from_str("[step-time]\nplane = \"both\"\n").unwrap();
    let checked = cfg.check().unwrap();
    assert_eq!(checked.planes(StepParameter::StepTime), Planes::Both);
    let back: LearnerConfig = toml::from_str(&toml::to_string(&cfg).unwrap()).unwrap();
    assert_eq!(back, cfg);
    let one = |p: StepParameter| {
        FootstepLearner::for_parameters(
            BinTable::new([4, 4, 4], 1.0),
            [PendulumCart::default()],
            [p],
            cfg,
        )
    };
    match one(StepParameter::StepTime) {
        Err(LearnerError::InvalidConfig { param, reason }) => {
            assert_eq!(param, "step-time.plane");
            assert!(reason.contains("StepLearner"), "{reason}");
        }
        other => panic!("expected a refusal, got {other:?}"),
    }
    let step_x = one(StepParameter::StepX).unwrap();
    assert!(matches!(
        step_x.as_parameter(StepParameter::StepTime),
        Err(LearnerError::InvalidConfig {
            param: "step-time.plane",
            ..
        })
    ));
    let sagittal = cfg.in_planes(StepParameter::StepTime, Planes::Sagittal);
    assert!(
        FootstepLearner::for_parameters(
            BinTable::new([4, 4, 4], 1.0),
            [PendulumCart::default()],
            [StepParameter::StepTime],
            sagittal,
        )
        .is_ok()
    );
}

/// In both planes the frontal part may have its own dead zone (`[step-time.frontal]`): its learner gets them, the sagittal part keeps the step time's, and
/// the table is refused (naming it) without `plane = "both"` or with a bad value.
#[test]
fn the_frontal_part_of_a_step_time_in_both_planes_has_its_own_settings() {
    use steplearn::control::StepParameter;
    use steplearn::control::{Plane, Planes};
    let text = "dead_zone = 0.06\n[step-time]\nplane = \"both\"\neta = 0.5\n[step-time.frontal]\ndead_zone = 0.0\n";
    let cfg: LearnerConfig = toml::from_str(text).unwrap();
    cfg.check().unwrap();
    let back: LearnerConfig = toml::from_str(&toml::to_string(&cfg).unwrap()).unwrap();
    assert_eq!(back, cfg);
    let t = StepParameter::StepTime;
    let (sagittal, frontal) = (cfg.part(t, Plane::Sagittal), cfg.part(t, Plane::Frontal));
    for (part, plane, dead_zone) in [
        (sagittal, Planes::Sagittal, 0.06),
        (frontal, Planes::Frontal, 0.0),
    ] {
        let checked = part.check().unwrap();
        assert_eq!(checked.planes(t), plane);
        assert_eq!(checked.offset(t).dead_zone, dead_zone);
        assert_eq!(checked.offset(t).eta, 0.5);
        assert!(part.step_time.frontal.is_none());
        // The other parameters are untouched.
        assert_eq!(part.step_x, cfg.step_x);
        assert_eq!(
            part.offset(StepParameter::StepX),
            cfg.offset(StepParameter::StepX)
        );
    }
    let refused = |text: &str, key: &str| {
        let cfg: LearnerConfig = toml::from_str(text).unwrap();
        match cfg.check() {
            Err(LearnerError::InvalidConfig { param, .. }) => assert_eq!(param, key, "{text}"),
            other => panic!("{text}: expected a refusal, got {other:?}"),
        }
    };
    refused(
        "[step-time.frontal]\ndead_zone = 0.0\n",
        "step-time.frontal",
    );
    refused(
        "[step-time]\nplane = \"frontal\"\n[step-time.frontal]\ndead_zone = 0.1\n",
        "step-time.frontal",
    );
    refused("[step-x.frontal]\ndead_zone = 0.1\n", "step-x.frontal");
    // Only the dead zone is set apart.
    assert!(toml::from_str::<LearnerConfig>("[step-time.frontal]\neta = 1.0\n").is_err());
    refused(
        "[step-time]\nplane = \"both\"\n[step-time.frontal]\ndead_zone = -1.0\n",
        "step-time.frontal.dead_zone",
    );
    assert!(toml::from_str::<LearnerConfig>("[step-time.frontal]\nplane = \"frontal\"\n").is_err());
}

/// The run's step learner (LWPR, pendulum-cart, seed 0) that `config` describes.
fn lwpr_step_learner_of(
    config: &steplearn::experiments::config_file::ConfigFile,
) -> steplearn::experiments::RunStepLearner {
    let components = steplearn::bench::Registry::builtin()
        .components("lwpr", "pendulum-cart", &config.settings.lwpr)
        .unwrap();
    let ctx = steplearn::experiments::RunContext {
        settings: &config.settings,
        protocols: &config.protocols,
        seed: 0,
        approx: "lwpr",
        rule: "pendulum-cart",
        components: &components,
    };
    ctx.make_step_learner().unwrap()
}

/// `gate = "rate-share"` in a parameter's table weights its offset by its plane's share of the
/// trunk's deviation rate: checked once (an unknown gate refused), kept by each part of a step
/// time in both planes, and acting in the run's learner: a gated `step-y` learner gives nothing
/// while the trunk falls only forward, its whole offset while it falls only sideways.
#[test]
fn a_gated_offset_acts_by_its_planes_share_of_the_trunks_rate() {
    use steplearn::control::FootstepPolicy;
    use steplearn::control::LearnerInput;
    use steplearn::control::{Gate, LearnSet, PerParameter, StepParameter};
    use steplearn::control::{Plane, Planes};
    use steplearn::experiments::config_file::ConfigFile;
    use steplearn::rules::StepOutcome;
    let t = StepParameter::StepTime;
    let text = "[step-time]\nplane = \"both\"\ngate = \"rate-share\"\n";
    let cfg: LearnerConfig = toml::from_str(text).unwrap();
    assert_eq!(cfg.check().unwrap().gate(t), Gate::RateShare);
    assert_eq!(LearnerConfig::default().check().unwrap().gate(t), Gate::Off);
    let back: LearnerConfig = toml::from_str(&toml::to_string(&cfg).unwrap()).unwrap();
    assert_eq!(back, cfg);
    for plane in [Plane::Sagittal, Plane::Frontal] {
        let part = cfg.part(t, plane).check().unwrap();
        assert_eq!(part.planes(t), Planes::from(plane));
        assert_eq!(part.gate(t), Gate::RateShare);
    }
    assert!(toml::from_str::<LearnerConfig>("[step-y]\ngate = \"max\"\n").is_err());
    // The run's learner of `step-x,step-y` with a gated `step-y`.
    let mut config = ConfigFile::default();
    let y = StepParameter::StepY;
    config.settings.learner.learn = LearnSet::of(&[StepParameter::StepX, y]).unwrap();
    config.settings.learner.step_y.gate = Some(Gate::RateShare);
    config.settings.learner.step_y.dead_zone = Some(0.0);
    let mut learner = lwpr_step_learner_of(&config);
    let input = |sagittal_rate: f64, frontal_rate: f64| {
        let x = LearnerInput::new(0.0, sagittal_rate, 0.0);
        PerParameter::from_planes(x, LearnerInput::new(0.05, frontal_rate, 0.0))
    };
    // Teach the lateral offset at a lean towards the swing leg, sideways rate only.
    let outcome = StepOutcome {
        theta_e: 0.1,
        theta_e_dot: 0.0,
        f_e: 0.0,
        f_r: 0.0,
    };
    for _ in 0..20 {
        learner.offsets(&input(0.0, 0.2)).unwrap();
        learner.touch_down(&PerParameter::splat(outcome)).unwrap();
    }
    let sideways = learner.offsets(&input(0.0, 0.2)).unwrap()[y];
    assert!(sideways.abs() > 1e-4, "{sideways}");
    assert_eq!(learner.offsets(&input(0.2, 0.0)).unwrap()[y], 0.0);
    let half = learner.offsets(&input(0.2, 0.2)).unwrap()[y];
    let whole = learner.learner(y).unwrap().last_offset();
    assert!((half - 0.5 * whole).abs() < 1e-12, "{half} {whole}");
}

/// `gate = "with-the-fall"` withholds an offset while it points against the trunk's fall in
/// its plane: a learned heel (negative sole pitch) acts while the trunk falls backward and not
/// while it falls forward. The step time, with no direction in space, refuses the gate naming
/// its key.
#[test]
fn a_with_the_fall_gate_withholds_an_offset_that_points_against_the_fall() {
    use steplearn::control::FootstepPolicy;
    use steplearn::control::LearnerInput;
    use steplearn::control::{Gate, LearnSet, PerParameter, StepParameter};
    use steplearn::experiments::config_file::ConfigFile;
    use steplearn::rules::StepOutcome;
    let text = "[ankle-pitch]\ngate = \"with-the-fall\"\n";
    let cfg: LearnerConfig = toml::from_str(text).unwrap();
    let a = StepParameter::AnklePitch;
    assert_eq!(cfg.check().unwrap().gate(a), Gate::WithTheFall);
    let back: LearnerConfig = toml::from_str(&toml::to_string(&cfg).unwrap()).unwrap();
    assert_eq!(back, cfg);
    let refused: LearnerConfig = toml::from_str("[step-time]\ngate = \"with-the-fall\"\n").unwrap();
    let err = refused.check().unwrap_err().to_string();
    assert!(err.contains("step-time.gate"), "{err}");
    // The run's learner of `step-x,ankle-pitch` with the gated pitch.
    let mut config = ConfigFile::default();
    config.settings.learner.learn = LearnSet::of(&[StepParameter::StepX, a]).unwrap();
    config.settings.learner.ankle_pitch.gate = Some(Gate::WithTheFall);
    config.settings.learner.ankle_pitch.dead_zone = Some(0.0);
    let mut learner = lwpr_step_learner_of(&config);
    let input = |rate: f64| {
        let x = LearnerInput::new(0.0, rate, 0.0);
        PerParameter::from_planes(x, LearnerInput::new(0.05, 0.0, 0.0))
    };
    // Steps that end leaning back teach a heel at both falling rates.
    let outcome = StepOutcome {
        theta_e: -0.1,
        theta_e_dot: 0.0,
        f_e: 0.0,
        f_r: 0.0,
    };
    for k in 0..40 {
        let rate = if k % 2 == 0 { -0.3 } else { 0.3 };
        learner.offsets(&input(rate)).unwrap();
        learner.touch_down(&PerParameter::splat(outcome)).unwrap();
    }
    // A rate of 0 lies within the gate's hysteresis band: it keeps the direction the rate
    // before it gave (backward after -0.1, forward after 0.3).
    let (mut passed, mut withheld) = (0, 0);
    for (rate, backward) in [
        (-0.3, true),
        (-0.1, true),
        (0.0, true),
        (0.1, false),
        (0.3, false),
        (0.0, false),
    ] {
        let got = learner.offsets(&input(rate)).unwrap()[a];
        let raw = learner.learner(a).unwrap().last_offset();
        assert!(raw < -1e-4, "a heel was taught at rate {rate}: {raw}");
        if backward {
            assert_eq!(got, raw, "falling backward the heel acts");
            passed += 1;
        } else {
            assert_eq!(got, 0.0, "falling forward the heel is withheld");
            withheld += 1;
        }
    }
    assert_eq!((passed, withheld), (3, 3));
}

#[test]
fn checked_settings_hold_every_value_in_its_group() {
    use steplearn::control::StepParameter;
    let cfg = LearnerConfig {
        max_gain: Some(0.3),
        anti_windup: false,
        learn_from_falls: false,
        fall_theta_limit: 0.2,
        trust_region: Some(1.5),
        trust_fallback: TrustFallback::Nominal,
        max_step_error: Some(0.04),
        max_samples_per_step: 64,
        train_share: 0.5,
        eta: 0.7,
        ..LearnerConfig::default()
    };
    let c = cfg.check().unwrap();
    assert_eq!(
        (c.guard().max_gain, c.guard().anti_windup),
        (Some(0.3), false)
    );
    assert_eq!((c.falls().learn, c.falls().theta_limit), (false, 0.2));
    assert_eq!(
        (
            c.trust().region,
            c.trust().fallback,
            c.trust().max_step_error
        ),
        (Some(1.5), TrustFallback::Nominal, Some(0.04))
    );
    assert_eq!(
        (c.memory().max_samples_per_step, c.memory().train_share),
        (64, 0.5)
    );
    assert_eq!(c.offset(StepParameter::StepTime).eta, 0.7);
    assert_eq!(c.prior(), cfg.prior);
    let learner = FootstepLearner::new(table(), PendulumCart::default(), cfg).unwrap();
    assert_eq!(learner.settings(), &c);
}
