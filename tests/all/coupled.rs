//! The coupled learner: one approximator with two outputs (dF, dW) over both planes' inputs,
//! each plane's rule teaching its own output, with the sagittal learner's safeguards; on the
//! humanoid and in experiment `omnidirectional` as its `both_planes = "coupled"` setting.

use steplearn::approx::{AnyApproximator, ApproxKind, Stacked};
use steplearn::bench::{Bench, Registry};
use steplearn::control::FootstepPolicy;
use steplearn::control::coupled::{CoupledLearner, coupled_bounds};
use steplearn::control::motion::Swing;
use steplearn::control::{InputGrid, LearnerConfig, LearnerError, LearnerInput, TrustFallback};
use steplearn::control::{PerParameter, StepParameter};
use steplearn::experiments::config_file::ConfigFile;
use steplearn::rules::{PendulumCart, StepOutcome};

use crate::lateral::step_in_place;

fn heads() -> Stacked<AnyApproximator> {
    let bounds = coupled_bounds(&InputGrid::default().input_box().unwrap()).unwrap();
    assert_eq!(bounds.dim(), 6);
    let head = || ApproxKind::Lwpr.build(&bounds).unwrap();
    Stacked::new(vec![head(), head()]).unwrap()
}

fn coupled(config: LearnerConfig) -> CoupledLearner<Stacked<AnyApproximator>, PendulumCart> {
    CoupledLearner::new(heads(), [PendulumCart::default(); 2], config).unwrap()
}

fn outcome(theta_e: f64, f_e: f64) -> StepOutcome {
    StepOutcome {
        theta_e,
        theta_e_dot: 0.0,
        f_e,
        f_r: 0.0,
    }
}

const SAGITTAL: LearnerInput = LearnerInput {
    theta_e: 0.05,
    theta_e_dot: 0.2,
    f_r: 0.0,
};
const LATERAL: LearnerInput = LearnerInput {
    theta_e: 0.02,
    theta_e_dot: -0.1,
    f_r: 0.0,
};

fn at(s: LearnerInput, l: LearnerInput) -> [f64; 6] {
    [
        s.theta_e,
        s.theta_e_dot,
        s.f_r,
        l.theta_e,
        l.theta_e_dot,
        l.f_r,
    ]
}

#[test]
fn each_plane_teaches_its_own_output_within_the_gain_guard() {
    let config = LearnerConfig {
        trust_region: None,
        ..LearnerConfig::default()
    };
    let mut learner = coupled(config);
    let x = at(SAGITTAL, LATERAL);
    let prior = learner.predict(&x).unwrap();
    assert!(prior.iter().all(|v| v.abs() < 1e-3), "{prior:?}");
    // A trunk still pitched forward asks for a longer step (G > 0); a step wider than the
    // reference asks for a narrower one (G < 0).
    for _ in 0..3 {
        learner.query(SAGITTAL, LATERAL).unwrap();
        let [s, l] = learner
            .touch_down([&outcome(0.1, 0.0), &outcome(0.0, 0.05)])
            .unwrap();
        assert!(s.gradient > 0.0 && l.gradient < 0.0);
        for r in [s, l] {
            assert_eq!(r.samples, 1);
            assert!(r.gain.abs() <= 0.2 + 1e-12, "{r:?}");
        }
    }
    let [df, dw] = learner.predict(&x).unwrap();
    assert!(df > prior[0] + 1e-3, "dF {df}");
    assert!(dw < prior[1] - 1e-3, "dW {dw}");
    // One model over both planes: the same sagittal state with another lateral state is
    // another input, where the sagittal output learned less.
    let far = at(
        SAGITTAL,
        LearnerInput {
            theta_e: -0.25,
            theta_e_dot: 1.4,
            f_r: 0.15,
        },
    );
    let [df_far, _] = learner.predict(&far).unwrap();
    assert!(
        df_far.abs() < 0.5 * df.abs(),
        "dF {df} here, {df_far} there"
    );
}

#[test]
fn a_plane_whose_reach_is_exhausted_is_not_wound_up() {
    let mut learner = coupled(LearnerConfig {
        trust_region: None,
        ..LearnerConfig::default()
    });
    let x = at(SAGITTAL, LATERAL);
    let [df_before, dw_before] = learner.predict(&x).unwrap();
    learner.query(SAGITTAL, LATERAL).unwrap();
    // No narrower width can change the step: the lateral target stays where it is.
    learner.set_reach(1, dw_before, 1.0).unwrap();
    learner
        .touch_down([&outcome(0.1, 0.0), &outcome(0.0, 0.05)])
        .unwrap();
    let [df, dw] = learner.predict(&x).unwrap();
    assert!(df > df_before + 1e-4, "{df_before} -> {df}");
    assert!(
        (dw - dw_before).abs() < 0.01 * (df - df_before),
        "{dw_before} -> {dw}"
    );
    assert!(learner.set_reach(2, 0.0, 1.0).is_err());
    assert!(learner.set_reach(1, 1.0, 0.0).is_err());
}

#[test]
fn bad_input_is_refused_and_changes_nothing() {
    // Wrong shape: a one-output, three-input approximator.
    let bounds = InputGrid::default().input_box().unwrap();
    let small = Stacked::new(vec![ApproxKind::Lwpr.build(&bounds).unwrap()]).unwrap();
    let err = CoupledLearner::new(
        small,
        [PendulumCart::default(); 2],
        LearnerConfig::default(),
    )
    .unwrap_err();
    assert!(
        matches!(
            err,
            LearnerError::WrongApproximatorShape {
                expected: (6, 2),
                inputs: 3,
                outputs: 1
            }
        ),
        "{err}"
    );
    let r = CoupledLearner::new(
        heads(),
        [PendulumCart::default(); 2],
        LearnerConfig {
            eta: f64::NAN,
            ..LearnerConfig::default()
        },
    );
    assert!(matches!(
        r,
        Err(LearnerError::InvalidConfig { param: "eta", .. })
    ));
    let mut learner = coupled(LearnerConfig::default());
    let nan = LearnerInput {
        theta_e: f64::NAN,
        ..LATERAL
    };
    assert!(matches!(
        learner.query(SAGITTAL, nan),
        Err(LearnerError::NonFinite {
            what: "lateral lean",
            ..
        })
    ));
    // Nothing was recorded: the next step teaches from its one query only.
    learner.query(SAGITTAL, LATERAL).unwrap();
    let bad = outcome(f64::INFINITY, 0.0);
    assert!(learner.touch_down([&outcome(0.1, 0.0), &bad]).is_err());
    let [s, _] = learner
        .touch_down([&outcome(0.1, 0.0), &outcome(0.0, 0.0)])
        .unwrap();
    assert_eq!(s.samples, 1);
}

#[test]
fn as_a_policy_it_learns_both_planes_and_not_the_step_time() {
    let mut learner = coupled(LearnerConfig {
        trust_region: None,
        ..LearnerConfig::default()
    });
    assert_eq!(learner.learns().to_string(), "step-x,step-y");
    let inputs = PerParameter::from_planes(SAGITTAL, LATERAL);
    let offsets = learner.offsets(&inputs).unwrap();
    let both = learner.predict(&at(SAGITTAL, LATERAL)).unwrap();
    assert_eq!(offsets.0, [both[0], both[1], 0.0, 0.0, 0.0]);
    let reports = FootstepPolicy::touch_down(
        &mut learner,
        &PerParameter::from_planes(outcome(0.1, 0.0), outcome(0.0, 0.0)),
    )
    .unwrap();
    let s = reports[StepParameter::StepX].unwrap();
    assert!(s.gradient > 0.0 && s.samples == 1);
    assert!(reports[StepParameter::StepY].is_some());
    assert!(reports[StepParameter::StepTime].is_none());
    learner.offsets(&inputs).unwrap();
    let reports = FootstepPolicy::fall(
        &mut learner,
        &PerParameter::from_planes(outcome(2.0, 0.0), outcome(-2.0, 0.0)),
    )
    .unwrap();
    // Learning from falls clamps theta_E to the fall limit before the rule sees it.
    let lim = LearnerConfig::default().fall_theta_limit;
    assert_eq!(reports[StepParameter::StepX].unwrap().gradient, lim);
    assert_eq!(reports[StepParameter::StepY].unwrap().gradient, -lim);
}

#[test]
fn on_the_humanoid_the_coupled_learner_learns_the_width_after_a_side_push() {
    let mut learner = coupled(LearnerConfig::default());
    // The paper's swing, as for the uncoupled lateral learner's test.
    let learned = step_in_place(14.0, [0.0, 5.0, 0.0], Swing::Paper, Some(&mut learner));
    let model = step_in_place(14.0, [0.0, 5.0, 0.0], Swing::Paper, None);
    assert_eq!(learned.falls + model.falls, 0);
    assert!(learned.offsets.iter().any(|o| *o != 0.0));
    let err = |r: &crate::lateral::Run| r.mean_width_error_after(8.0);
    eprintln!(
        "mean |width error| from 8 to 14 s: coupled {:.5} m, model {:.5} m",
        err(&learned),
        err(&model)
    );
    assert!(
        err(&learned) < 0.5 * err(&model),
        "mean |width error| after 8 s: coupled {:.4} m, model {:.4} m",
        err(&learned),
        err(&model)
    );
}

#[test]
fn experiment_omnidirectional_runs_both_planes_coupled_as_a_setting() {
    let dir = std::env::temp_dir().join(format!("steplearn-coupled-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let summary = |both_planes: &str, out: &str| -> serde_json::Value {
        // The improved setup, where the walker `both` learns within this short protocol.
        let improved = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/configs/improved.toml"
        ))
        .unwrap();
        let config = ConfigFile::from_toml(&format!(
            "{improved}\n[protocols.omnidirectional]\n{both_planes}walk_s = 8.0\nwalk_hold_s = [2.0, 3.0]\n"
        ))
        .unwrap();
        Bench::new(&Registry::builtin())
            .config(config)
            .approximators(["lwpr"])
            .rules(["pendulum-cart"])
            .experiments(["omnidirectional"])
            .seeds(1)
            .scale(0.02)
            .out(dir.join(out))
            .run()
            .unwrap();
        let run = dir
            .join(out)
            .join("omnidirectional__lwpr__pendulum-cart__s0");
        serde_json::from_str(&std::fs::read_to_string(run.join("summary.json")).unwrap()).unwrap()
    };
    let coupled = summary("both_planes = \"coupled\"\n", "coupled");
    let uncoupled = summary("", "uncoupled");
    assert_eq!(coupled["both_planes"], "coupled");
    assert!(uncoupled.get("both_planes").is_none(), "{uncoupled}");
    let i50 = |s: &serde_json::Value, walker: &str| -> Vec<f64> {
        serde_json::from_value(s["i50_ns"][walker].clone()).unwrap()
    };
    assert_eq!(i50(&coupled, "both").len(), 8);
    assert!(i50(&coupled, "both").iter().all(|v| v.is_finite()));
    // The setting changes the walker `both` and nothing else: the same seed gives the other
    // walkers the same pushes and the same I50s, and `both` learns with another model (one
    // approximator over both planes instead of two), which shows in its I50s and in its walk.
    for walker in ["open_loop", "model", "sagittal"] {
        assert_eq!(i50(&coupled, walker), i50(&uncoupled, walker), "{walker}");
    }
    assert_ne!(
        i50(&coupled, "both"),
        i50(&uncoupled, "both"),
        "the coupled walker's I50s are the uncoupled pair's"
    );
    assert_ne!(
        coupled["walk_error_m"]["both"], uncoupled["walk_error_m"]["both"],
        "the coupled walker walked exactly as the uncoupled pair"
    );
    // A typo in the setting is an error naming the key and the value, never a silent default.
    let err = Bench::new(&Registry::builtin())
        .config(
            ConfigFile::from_toml("[protocols.omnidirectional]\nboth_planes = \"couple\"\n")
                .unwrap(),
        )
        .approximators(["lwpr"])
        .rules(["pendulum-cart"])
        .experiments(["omnidirectional"])
        .seeds(1)
        .scale(0.02)
        .out(dir.join("bad"))
        .run()
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("both_planes") && err.contains("unknown variant `couple`"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn max_step_error_and_the_nominal_fallback_act_on_the_coupled_learner_too() {
    // max_step_error: a step either plane's model missed by more teaches nothing.
    let mut learner = coupled(LearnerConfig {
        max_step_error: Some(0.05),
        trust_region: None,
        ..LearnerConfig::default()
    });
    let x = at(SAGITTAL, LATERAL);
    let before = learner.predict(&x).unwrap();
    learner.query(SAGITTAL, LATERAL).unwrap();
    let missed = StepOutcome {
        f_e: 0.2,
        ..outcome(0.1, 0.0)
    };
    let [s, l] = learner.touch_down([&outcome(0.1, 0.0), &missed]).unwrap();
    assert_eq!((s.samples, l.samples), (0, 0));
    assert_eq!(learner.predict(&x).unwrap(), before);
    // Within it, the same step teaches.
    learner.query(SAGITTAL, LATERAL).unwrap();
    let [s, _] = learner
        .touch_down([&outcome(0.1, 0.0), &outcome(0.0, 0.0)])
        .unwrap();
    assert_eq!(s.samples, 1);
    assert!(learner.predict(&x).unwrap()[0] > before[0]);

    // The nominal fallback: far outside the trust region the offsets fade to those learned at
    // the nominal state, not to zero.
    let mut learner = coupled(LearnerConfig {
        trust_fallback: TrustFallback::Nominal,
        ..LearnerConfig::default()
    });
    for _ in 0..20 {
        learner.query(SAGITTAL, LATERAL).unwrap();
        learner
            .touch_down([&outcome(0.1, 0.0), &outcome(0.0, 0.0)])
            .unwrap();
    }
    let far = LearnerInput {
        theta_e_dot: 1.4,
        ..SAGITTAL
    };
    let [df_far, _] = learner.query(far, LATERAL).unwrap();
    let [df_nominal, _] = learner.predict(&x).unwrap();
    assert!(df_nominal > 0.01, "learned {df_nominal}");
    // Every query was at one state, so the nominal state is that state; far from it the trust
    // share is 0 and the offset is the nominal one exactly (with the zero fallback: 0).
    assert_eq!(df_far, df_nominal);
}

#[test]
fn each_offset_takes_its_own_parameters_dead_zone() {
    // The shared dead zone 0.15 covers both planes' G of 0.1; the step-y table (no dead
    // zone, as in configs/improved.toml) lets the lateral one through, so only the width
    // learns.
    let mut learner = coupled(LearnerConfig {
        trust_region: None,
        dead_zone: 0.15,
        step_y: steplearn::control::ParameterSettings {
            dead_zone: Some(0.0),
            ..Default::default()
        },
        ..LearnerConfig::default()
    });
    assert_eq!(
        learner.parameters(),
        [StepParameter::StepX, StepParameter::StepY]
    );
    let x = at(SAGITTAL, LATERAL);
    let [df_before, dw_before] = learner.predict(&x).unwrap();
    learner.query(SAGITTAL, LATERAL).unwrap();
    let [s, l] = learner
        .touch_down([&outcome(0.1, 0.0), &outcome(0.1, 0.0)])
        .unwrap();
    assert!(s.gradient > 0.1 - 1e-9 && l.gradient > 0.1 - 1e-9);
    let [df, dw] = learner.predict(&x).unwrap();
    assert!(dw > dw_before + 1e-4, "dW {dw_before} -> {dw}");
    assert!(
        (df - df_before).abs() < 0.01 * (dw - dw_before),
        "dF {df_before} -> {df}"
    );
}

/// Drives `learner` through `steps` steps of queries with reaches, touching down after each,
/// calling `between(learner, query)` before every query; returns every offset it answered.
fn drive(
    learner: &mut CoupledLearner<Stacked<AnyApproximator>, PendulumCart>,
    steps: usize,
    mut between: impl FnMut(&mut CoupledLearner<Stacked<AnyApproximator>, PendulumCart>, usize),
) -> Vec<[f64; 2]> {
    let mut answers = Vec::new();
    let mut query = 0;
    for step in 0..steps {
        let lean = 0.01 * (step as f64 - 3.0);
        for tick in 0..23 {
            between(learner, query);
            query += 1;
            let s = LearnerInput::new(lean + 0.002 * tick as f64, 0.1 - 0.01 * tick as f64, 0.05);
            let l = LearnerInput::new(-0.5 * lean, 0.02 * tick as f64, -0.02);
            answers.push(learner.query(s, l).unwrap());
            learner
                .set_reach(0, -0.05 - 0.001 * tick as f64, f64::INFINITY)
                .unwrap();
            learner.set_reach(1, f64::NEG_INFINITY, 0.04).unwrap();
        }
        let sagittal = outcome(lean + 0.04, 0.01 * (step % 3) as f64 - 0.01);
        let lateral = outcome(-0.5 * lean, -0.005 * (step % 2) as f64);
        learner.touch_down([&sagittal, &lateral]).unwrap();
    }
    answers
}

#[test]
fn a_coupled_learner_saved_and_loaded_mid_step_continues_bit_for_bit() {
    let config = LearnerConfig {
        max_samples_per_step: 8,
        ..LearnerConfig::default()
    };
    let mut plain = coupled(config);
    let answers = drive(&mut plain, 9, |_, _| {});
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("coupled.json");
    let mut reloaded = coupled(config);
    let mut mid_step = 0;
    let answers_reloaded = drive(&mut reloaded, 9, |learner, query| {
        // Every 17 queries: at varying phases of the 23-query steps, after thinning too.
        if query % 17 == 16 {
            learner.save(&path).unwrap();
            let loaded = CoupledLearner::load_with(&path, [PendulumCart::default(); 2]).unwrap();
            assert_eq!(
                serde_json::to_string(&loaded.checkpoint()).unwrap(),
                serde_json::to_string(&learner.checkpoint()).unwrap()
            );
            mid_step += usize::from(!learner.checkpoint().step.recorded.is_empty());
            *learner = loaded;
        }
    });
    assert!(mid_step >= 10, "{mid_step} reloads mid-step");
    assert!(
        answers.iter().flatten().any(|v| *v != 0.0),
        "nothing learned"
    );
    assert_eq!(answers, answers_reloaded);
    let saved = plain.checkpoint();
    assert_eq!(saved.more_offsets.len(), 1);
    assert_eq!(saved.more_offsets[0].parameter, StepParameter::StepY);
    assert_eq!(
        serde_json::to_string(&saved).unwrap(),
        serde_json::to_string(&reloaded.checkpoint()).unwrap()
    );
}

#[test]
fn a_coupled_checkpoint_of_another_shape_or_with_a_broken_offset_is_refused() {
    let mut learner = coupled(LearnerConfig::default());
    drive(&mut learner, 2, |_, _| {});
    learner.query(SAGITTAL, LATERAL).unwrap();
    let good = learner.checkpoint();
    assert!(
        CoupledLearner::from_checkpoint_with(good.clone(), [PendulumCart::default(); 2]).is_ok()
    );
    // Without the second offset's record the two-output approximator has one offset too few.
    let mut one = good.clone();
    one.more_offsets.clear();
    let err = CoupledLearner::from_checkpoint_with(one, [PendulumCart::default(); 2]).unwrap_err();
    assert!(err.to_string().contains("output"), "{err}");
    type Corruption = fn(&mut steplearn::control::SavedOffset);
    let broken: [(&str, Corruption); 3] = [
        ("reach count", |o| {
            o.reach.pop();
        }),
        ("empty reach", |o| o.reach[0] = [Some(1.0), Some(0.0)]),
        ("non-finite offset", |o| o.last_offset = f64::NAN),
    ];
    for (what, corrupt) in broken {
        let mut saved = good.clone();
        corrupt(&mut saved.more_offsets[0]);
        let err = CoupledLearner::from_checkpoint_with(saved, [PendulumCart::default(); 2])
            .err()
            .unwrap_or_else(|| panic!("{what}: accepted"));
        assert!(err.to_string().contains("step-y"), "{what}: {err}");
    }
    // A one-offset learner cannot take a coupled checkpoint.
    let err = steplearn::control::FootstepLearner::<Stacked<AnyApproximator>, _>::from_checkpoint(
        good,
        PendulumCart::default(),
    )
    .unwrap_err();
    assert!(
        matches!(err, LearnerError::WrongApproximatorShape { .. }),
        "{err}"
    );
}

/// A gate on either offset (`gate = "rate-share"`) weights the coupled learner's offsets as it
/// weights the uncoupled ones: each by its plane's share of the trunk's squared deviation rate.
#[test]
fn a_gate_weights_each_coupled_offset_by_its_planes_share() {
    use steplearn::control::Gate;
    let mut config = LearnerConfig {
        trust_region: None,
        ..LearnerConfig::default()
    };
    config.step_x.gate = Some(Gate::RateShare);
    config.step_y.gate = Some(Gate::RateShare);
    let mut learner = coupled(config);
    // Teach both outputs something other than zero.
    for _ in 0..5 {
        learner
            .offsets(&PerParameter::from_planes(SAGITTAL, LATERAL))
            .unwrap();
        FootstepPolicy::touch_down(&mut learner, &PerParameter::splat(outcome(0.1, 0.0))).unwrap();
    }
    let both = learner.predict(&at(SAGITTAL, LATERAL)).unwrap();
    assert!(both[0].abs() > 1e-6 && both[1].abs() > 1e-6, "{both:?}");
    let offsets = learner
        .offsets(&PerParameter::from_planes(SAGITTAL, LATERAL))
        .unwrap();
    // Rates 0.2 (sagittal) and -0.1 rad/s (frontal): squared 0.04 and 0.01, shares 0.8 and
    // 0.2 of their sum 0.05.
    assert_eq!((SAGITTAL.theta_e_dot, LATERAL.theta_e_dot), (0.2, -0.1));
    let want = [0.8 * both[0], 0.2 * both[1]];
    assert!((offsets.0[0] - want[0]).abs() < 1e-15 && (offsets.0[1] - want[1]).abs() < 1e-15);
    assert!(offsets.0[0].abs() < both[0].abs() && offsets.0[1].abs() < both[1].abs());
}
