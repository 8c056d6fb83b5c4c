//! The policy-gradient baseline: the exploration API leaves gradient rules as they were, the
//! perturbations are seeded and reproducible, the REINFORCE estimate is unbiased and drives the
//! learner's mean to the optimum of a toy, bad parameters are typed errors, a saved learner
//! continues bit for bit, and the rule runs through the registry on the humanoid.

use serde::{Deserialize, Serialize};
use steplearn::approx::{ApproxError, FunctionApproximator, Persist};
use steplearn::bench::{Bench, Registry};
use steplearn::control::{
    FootstepLearner, LearnerConfig, LearnerError, LearnerInput, Prior, TouchDownReport,
};
use steplearn::experiments::robustness::RobustnessSummary;
use steplearn::experiments::summary::{Summary, TypedResult};
use steplearn::experiments::sweep::{RunSpec, RunStatus};
use steplearn::rules::{
    LearningRule, PendulumCart, PolicyGradient, PolicyGradientParams, RuleConfig, RuleError,
    RuleKind, StepOutcome,
};
use strum::VariantArray;

/// A one-number approximator: predicts `value` everywhere, an update moves it a tenth of the
/// way to the target (a response of 0.1, below the learner's gain guard).
#[derive(Debug, Clone, Serialize, Deserialize)]
struct Scalar {
    value: f64,
}

impl FunctionApproximator for Scalar {
    fn input_dim(&self) -> usize {
        3
    }
    fn output_dim(&self) -> usize {
        1
    }
    fn predict(&self, _x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        y[0] = self.value;
        Ok(())
    }
    fn update(&mut self, _x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        self.value += 0.1 * (y[0] - self.value);
        Ok(())
    }
}

impl Persist for Scalar {
    fn check_invariants(&self) -> Result<(), ApproxError> {
        if self.value.is_finite() {
            Ok(())
        } else {
            Err(ApproxError::Corrupt("value".into()))
        }
    }
}

/// No prior, no trust region: the policy's mean is the approximator's value.
fn plain() -> LearnerConfig {
    LearnerConfig {
        prior: Prior::none(),
        trust_region: None,
        ..LearnerConfig::default()
    }
}

const INPUT: LearnerInput = LearnerInput {
    theta_e: 0.0,
    theta_e_dot: 0.0,
    f_r: 0.1,
};

/// The toy's step: the step size error is the offset's distance from `optimum`.
fn toy_outcome(offset: f64, optimum: f64) -> StepOutcome {
    StepOutcome {
        theta_e: 0.0,
        theta_e_dot: 0.0,
        f_e: offset - optimum,
        f_r: 0.1,
    }
}

fn samples() -> [StepOutcome; 3] {
    [
        StepOutcome {
            theta_e: 0.1,
            theta_e_dot: -0.4,
            f_e: 0.02,
            f_r: 0.1,
        },
        StepOutcome {
            theta_e: -0.3,
            theta_e_dot: 1.0,
            f_e: -0.05,
            f_r: 0.0,
        },
        StepOutcome::default(),
    ]
}

#[test]
fn gradient_rules_are_unchanged_by_the_exploration_api() {
    for &kind in RuleKind::VARIANTS {
        if kind == RuleKind::PolicyGradient {
            continue;
        }
        let mut rule = RuleConfig::from(kind).build().unwrap();
        rule.reseed(7);
        assert_eq!(rule.explore(), 0.0, "{kind}");
        assert!(rule.state().is_none(), "{kind}");
        assert!(matches!(
            rule.set_state(&serde_json::json!({})),
            Err(RuleError::InvalidState(_))
        ));
        for step in samples() {
            let g = rule.gradient(&step);
            for fell in [false, true] {
                assert_eq!(
                    rule.learn(&step, 0.3, fell).to_bits(),
                    g.to_bits(),
                    "{kind}"
                );
            }
        }
    }
    // The learner with a gradient rule: no perturbation, the offset is the prediction, and a
    // checkpoint writes neither a rule state nor an exploration (the file format is unchanged).
    let mut learner =
        FootstepLearner::new(Scalar { value: -0.0 }, PendulumCart::default(), plain()).unwrap();
    learner.reseed(3);
    let df = learner.query(INPUT).unwrap();
    assert_eq!(df.to_bits(), (-0.0f64).to_bits());
    assert_eq!(learner.exploration(), 0.0);
    let report = learner.touch_down(&samples()[0]).unwrap();
    assert_eq!(
        report.gradient,
        PendulumCart::default().gradient(&samples()[0])
    );
    learner.query(INPUT).unwrap();
    let json = serde_json::to_string(&learner.checkpoint()).unwrap();
    assert!(
        !json.contains("rule_state") && !json.contains("exploration"),
        "{json}"
    );
}

#[test]
fn same_seed_same_perturbations_different_seed_different() {
    let draws = |seed: u64| -> Vec<u64> {
        let mut pg = PolicyGradient::default();
        pg.reseed(seed);
        (0..50).map(|_| pg.explore().to_bits()).collect()
    };
    assert_eq!(draws(11), draws(11));
    assert_ne!(draws(11), draws(12));
    // reseeding restarts the sequence
    let mut pg = PolicyGradient::default();
    pg.reseed(11);
    pg.explore();
    pg.reseed(11);
    assert_eq!(pg.explore().to_bits(), draws(11)[0]);
    // the draws have the configured spread
    let mut pg = PolicyGradient::default();
    pg.reseed(1);
    let n = 20_000;
    let (mut sum, mut sq) = (0.0, 0.0);
    for _ in 0..n {
        let e = pg.explore();
        sum += e;
        sq += e * e;
    }
    let mean = sum / n as f64;
    let std = (sq / n as f64 - mean * mean).sqrt();
    let sigma = PolicyGradientParams::default().sigma;
    assert!(mean.abs() < 0.05 * sigma, "{mean}");
    assert!((std - sigma).abs() < 0.05 * sigma, "{std}");

    // Through the learner: one perturbation held for a whole step, a new one the next step,
    // the same offsets for the same seed.
    let offsets = |seed: u64| -> Vec<u64> {
        let mut l = FootstepLearner::new(Scalar { value: 0.0 }, PolicyGradient::default(), plain())
            .unwrap();
        l.reseed(seed);
        let mut out = Vec::new();
        for _ in 0..5 {
            let first = l.query(INPUT).unwrap();
            assert_ne!(first, 0.0);
            assert_eq!(l.exploration(), first);
            for _ in 0..3 {
                assert_eq!(l.query(INPUT).unwrap().to_bits(), first.to_bits());
            }
            out.push(first.to_bits());
            l.discard_step();
            assert_eq!(l.exploration(), 0.0);
        }
        out
    };
    let a = offsets(5);
    assert_eq!(a, offsets(5));
    assert_ne!(a, offsets(6));
    assert!(a.windows(2).all(|w| w[0] != w[1]));
}

#[test]
fn the_reinforce_estimate_is_unbiased_on_a_quadratic() {
    // r(a) = -((a - opt) / s_F)^2 with a = mu + eps: dE[r]/dmu = -2 (mu - opt) / s_F^2 exactly,
    // and E[G] = scale * dE[r]/dmu for any baseline that does not see the step's eps. The
    // fall penalty, which caps the cost, is set out of reach so that r is the quadratic.
    let params = PolicyGradientParams {
        fall_penalty: 1e9,
        ..PolicyGradientParams::default()
    };
    let (mu, opt) = (0.0, 0.05);
    let exact = params.scale * -2.0 * (mu - opt) / (params.s_f * params.s_f);
    let mut pg = PolicyGradient::new(params).unwrap();
    pg.reseed(2024);
    let n = 200_000;
    let mut sum = 0.0;
    for _ in 0..n {
        let eps = pg.explore();
        sum += pg.learn(&toy_outcome(mu + eps, opt), eps, false);
    }
    let mean = sum / n as f64;
    // a relative standard error of ~0.3% at the defaults
    assert!(
        (mean - exact).abs() < 0.03 * exact.abs(),
        "{mean} vs {exact}"
    );
    // without a perturbation there is nothing to learn
    assert_eq!(pg.learn(&toy_outcome(mu, opt), 0.0, false), 0.0);
}

#[test]
fn the_learner_mean_converges_to_the_optimum_of_a_scalar_toy() {
    let optimum = 0.05;
    let mut learner =
        FootstepLearner::new(Scalar { value: 0.0 }, PolicyGradient::default(), plain()).unwrap();
    learner.reseed(4);
    let mut late = Vec::new();
    for step in 0..3000 {
        let offset = learner.query(INPUT).unwrap();
        learner.touch_down(&toy_outcome(offset, optimum)).unwrap();
        if step >= 1500 {
            late.push(learner.predict(INPUT).unwrap());
        }
    }
    let mean = late.iter().sum::<f64>() / late.len() as f64;
    assert!((mean - optimum).abs() < 0.01, "{mean}");
    // a fall is worse than any step: with a positive perturbation it asks for a smaller offset
    let mut pg = PolicyGradient::default();
    pg.learn(&toy_outcome(0.1, 0.1), 0.0, false);
    assert!(pg.learn(&toy_outcome(0.1, 0.1), 0.02, true) < 0.0);
}

#[test]
fn invalid_parameters_are_typed_errors() {
    let base = PolicyGradientParams::default();
    let bad = [
        (
            "sigma",
            PolicyGradientParams {
                sigma: -0.1,
                ..base
            },
        ),
        ("sigma", PolicyGradientParams { sigma: 0.0, ..base }),
        (
            "sigma",
            PolicyGradientParams {
                sigma: f64::NAN,
                ..base
            },
        ),
        (
            "s_theta",
            PolicyGradientParams {
                s_theta: f64::INFINITY,
                ..base
            },
        ),
        ("s_f", PolicyGradientParams { s_f: 0.0, ..base }),
        (
            "fall_penalty",
            PolicyGradientParams {
                fall_penalty: -1.0,
                ..base
            },
        ),
        (
            "fall_penalty",
            PolicyGradientParams {
                fall_penalty: 0.0,
                ..base
            },
        ),
        (
            "baseline_rate",
            PolicyGradientParams {
                baseline_rate: 0.0,
                ..base
            },
        ),
        (
            "baseline_rate",
            PolicyGradientParams {
                baseline_rate: 1.5,
                ..base
            },
        ),
        (
            "scale",
            PolicyGradientParams {
                scale: f64::NAN,
                ..base
            },
        ),
    ];
    for (name, params) in bad {
        for err in [
            PolicyGradient::new(params).err(),
            RuleConfig::PolicyGradient(params).build().err(),
        ] {
            match err {
                Some(RuleError::InvalidParameter { param, .. }) => assert_eq!(param, name),
                other => panic!("{name}: {other:?}"),
            }
        }
    }
    assert!(RuleConfig::PolicyGradient(base).build().is_ok());
    // the serde form: tagged, defaults filled in, unknown fields refused
    let cfg: RuleConfig =
        serde_json::from_str(r#"{"rule":"policy-gradient","sigma":0.05}"#).unwrap();
    assert_eq!(
        cfg,
        RuleConfig::PolicyGradient(PolicyGradientParams {
            sigma: 0.05,
            ..base
        })
    );
    assert_eq!(cfg.kind(), RuleKind::PolicyGradient);
    assert!(
        serde_json::from_str::<RuleConfig>(r#"{"rule":"policy-gradient","sigmaa":1}"#).is_err()
    );
    assert_eq!(
        "policy-gradient".parse::<RuleKind>(),
        Ok(RuleKind::PolicyGradient)
    );
}

type PgLearner = FootstepLearner<Scalar, PolicyGradient>;

/// Runs `steps` steps of 3 queries on the toy from `learner`, starting `skip` queries into
/// the first step; the offsets and touch-down reports, as bits.
fn continue_toy(learner: &mut PgLearner, skip: usize, steps: usize) -> Vec<u64> {
    let mut out = Vec::new();
    for s in 0..steps {
        for _ in if s == 0 { skip } else { 0 }..3 {
            out.push(learner.query(INPUT).unwrap().to_bits());
        }
        let offset = learner.exploration() + learner.predict(INPUT).unwrap();
        let r: TouchDownReport = learner.touch_down(&toy_outcome(offset, 0.05)).unwrap();
        out.extend([r.gradient.to_bits(), r.gain.to_bits(), r.scale.to_bits()]);
    }
    out
}

#[test]
fn a_saved_learner_continues_bit_for_bit_mid_step() {
    let mut learner =
        PgLearner::new(Scalar { value: 0.0 }, PolicyGradient::default(), plain()).unwrap();
    learner.reseed(8);
    continue_toy(&mut learner, 0, 20);
    // two queries into a step: the perturbation is drawn and held
    learner.query(INPUT).unwrap();
    learner.query(INPUT).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("learner.json");
    learner.save(&path).unwrap();
    let json = std::fs::read_to_string(&path).unwrap();
    assert!(json.contains("rule_state") && json.contains("exploration"));
    // loaded with a fresh, unseeded rule: the saved state wins
    let mut loaded = PgLearner::load(&path, PolicyGradient::default()).unwrap();
    assert_eq!(loaded.exploration(), learner.exploration());
    assert_eq!(loaded.rule().snapshot(), learner.rule().snapshot());
    let want = continue_toy(&mut learner, 2, 30);
    assert_eq!(continue_toy(&mut loaded, 2, 30), want);
    // the same checkpoint in memory
    let mut again =
        PgLearner::new(Scalar { value: 0.0 }, PolicyGradient::default(), plain()).unwrap();
    again.reseed(8);
    continue_toy(&mut again, 0, 20);
    again.query(INPUT).unwrap();
    again.query(INPUT).unwrap();
    let mut restored =
        PgLearner::from_checkpoint(again.checkpoint(), PolicyGradient::default()).unwrap();
    assert_eq!(continue_toy(&mut restored, 2, 30), want);
    // a perturbation before any query, or a non-finite one, is a corrupt checkpoint
    let mut early = PgLearner::new(Scalar { value: 0.0 }, PolicyGradient::default(), plain())
        .unwrap()
        .checkpoint();
    early.step.exploration = 0.01;
    let mut nan = again.checkpoint();
    nan.step.exploration = f64::NAN;
    for bad in [early, nan] {
        assert!(matches!(
            PgLearner::from_checkpoint(bad, PolicyGradient::default()),
            Err(LearnerError::Approx { .. })
        ));
    }
    // a gradient rule cannot take the policy gradient's state
    assert!(matches!(
        FootstepLearner::<Scalar, PendulumCart>::load(&path, PendulumCart::default()),
        Err(LearnerError::Rule(RuleError::InvalidState(_)))
    ));
}

#[test]
fn policy_gradient_runs_experiment_d_on_the_humanoid_through_the_bench() {
    let registry = Registry::builtin();
    assert!(registry.rule_names().contains(&"policy-gradient"));
    let dir = tempfile::tempdir().unwrap();
    let report = Bench::new(&registry)
        .approximators(["lwpr"])
        .rules(["policy-gradient"])
        .experiments(["robustness"])
        .seeds(1)
        .scale(0.03)
        .threads(1)
        .out(dir.path())
        .run()
        .unwrap();
    assert_eq!(report.outcomes.len(), 1);
    let outcome = &report.outcomes[0];
    assert!(
        matches!(outcome.status, RunStatus::Done { .. }),
        "{:?}",
        outcome.status
    );
    let spec: &RunSpec = &outcome.spec;
    assert_eq!(spec.rule, "policy-gradient");
    let summary = Summary::read(&dir.path().join(spec.id()).join("summary.json")).unwrap();
    assert_eq!(summary.rule, "policy-gradient");
    let pushes = RobustnessSummary::from_result(&summary.result)
        .unwrap()
        .absorbed_by_push
        .len();
    assert!(pushes >= 1);
    // The rule learns on the humanoid: experiment D's learner starts untrained (the learning
    // metric, the norm of the mean dF over the input grid, is exactly 0 before the first
    // push), and after every push the approximator holds what the rule taught it. Exploration
    // alone does not count here: the metric is the approximator's mean, without perturbation.
    let csv =
        std::fs::read_to_string(dir.path().join(spec.id()).join("robustness_pushes.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = header.iter().position(|h| *h == "learning_metric").unwrap();
    let metrics: Vec<f64> = lines
        .map(|l| l.split(',').nth(col).unwrap().parse().unwrap())
        .collect();
    assert_eq!(metrics.len(), pushes);
    assert!(
        metrics.iter().all(|m| m.is_finite() && *m > 0.0),
        "learning metric after each push: {metrics:?}"
    );
}

/// The tuning probe of docs/policy-gradient.md (ignored: minutes of simulation): experiment D
/// (learning from scratch) with LWPR on seeds 0-4 at half length, for the paper's rule and a
/// 4 x 4 grid of sigma and scale; prints each run's first absorbed push and falls.
/// `cargo test --test all rules_policy_gradient::tuning_probe -- --ignored --nocapture`
#[test]
#[ignore]
fn tuning_probe() {
    let mut registry = Registry::builtin();
    let mut rules = vec!["pendulum-cart".to_string(), "policy-gradient".to_string()];
    for sigma_mm in [10u32, 20, 40, 80] {
        for k in [3u32, 10, 30, 100] {
            if (sigma_mm, k) == (20, 10) {
                continue; // the defaults: "policy-gradient"
            }
            let params = PolicyGradientParams {
                sigma: f64::from(sigma_mm) / 1000.0,
                scale: f64::from(k) * 1e-4,
                ..PolicyGradientParams::default()
            };
            let name = format!("pg-s{sigma_mm}mm-k{k}e-4");
            registry = registry.rule(&name, move || {
                PolicyGradient::new(params).expect("valid parameters")
            });
            rules.push(name);
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let report = Bench::new(&registry)
        .approximators(["lwpr"])
        .rules(&rules)
        .experiments(["robustness"])
        .seeds(5)
        .scale(0.5)
        .threads(2)
        .out(dir.path())
        .run()
        .unwrap();
    println!("rule | seed | first absorbed push | falls");
    // Every rule on every seed ran and printed its row.
    assert_eq!(report.outcomes.len(), rules.len() * 5);
    let mut printed = std::collections::BTreeMap::<&str, usize>::new();
    for outcome in &report.outcomes {
        assert!(
            matches!(outcome.status, RunStatus::Done { .. }),
            "{:?}",
            outcome.status
        );
        let spec = &outcome.spec;
        let summary = Summary::read(&dir.path().join(spec.id()).join("summary.json")).unwrap();
        let RobustnessSummary {
            pushes_until_first_absorbed,
            falls,
            ..
        } = RobustnessSummary::of(&summary).expect("a robustness summary");
        println!(
            "{} | {} | {:?} | {falls}",
            spec.rule, spec.seed, pushes_until_first_absorbed
        );
        *printed.entry(spec.rule.as_str()).or_default() += 1;
    }
    assert_eq!(printed.len(), rules.len(), "{printed:?}");
    assert!(printed.values().all(|&n| n == 5), "{printed:?}");
    println!("{}", report.leaderboard.to_markdown());
}
