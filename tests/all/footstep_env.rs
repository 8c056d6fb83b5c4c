//! The footstep environment: episodes repeat bit for bit, zero actions are the model's walk
//! (checked against `run_trial` on the same pushes), harmful actions fall, the footstep limit
//! truncates, bad actions are refused without changing anything, and a URDF robot works.

use std::path::PathBuf;

use steplearn::control::WalkerMode;
use steplearn::control::{LearnSet, StepParameter};
use steplearn::experiments::footstep_env::{
    EnvError, FootstepEnv, FootstepEnvConfig, PushProtocol, StepResult,
};
use steplearn::experiments::schedule::PushPlan;
use steplearn::experiments::settings::Settings;
use steplearn::experiments::trial::run_trial;

fn quiet(max_footsteps: usize) -> FootstepEnvConfig {
    FootstepEnvConfig {
        pushes: PushProtocol::None,
        max_footsteps,
        ..FootstepEnvConfig::default()
    }
}

/// Runs an episode from `seed` with `policy(footstep, observation values)`; the results.
fn episode(
    env: &mut FootstepEnv,
    seed: u64,
    mut policy: impl FnMut(usize, &[f64]) -> Vec<f64>,
) -> (Vec<f64>, f64, Vec<StepResult>) {
    let first = env.reset(seed).expect("reset").values();
    let t0 = env.time();
    let mut obs = first.clone();
    let mut out = Vec::new();
    for k in 0.. {
        let r = env.step(&policy(k, &obs)).expect("step");
        obs = r.observation.values();
        let end = r.terminated || r.truncated;
        out.push(r);
        if end {
            break;
        }
    }
    (first, t0, out)
}

fn wobble(k: usize, _: &[f64]) -> Vec<f64> {
    vec![0.03 * ((k as f64) * 0.7).sin()]
}

#[test]
fn same_seed_and_actions_repeat_bit_for_bit() {
    let config = FootstepEnvConfig {
        max_footsteps: 40,
        ..FootstepEnvConfig::default()
    };
    let mut a = FootstepEnv::new(config.clone()).unwrap();
    let mut b = FootstepEnv::new(config).unwrap();
    let run_a = episode(&mut a, 7, wobble);
    let run_b = episode(&mut b, 7, wobble);
    assert_eq!(run_a, run_b);
    // The same environment again, after another episode in between.
    episode(&mut a, 8, wobble);
    assert_eq!(episode(&mut a, 7, wobble), run_a);
    // The steps are real: they take time, and other actions change them.
    let (_, _, steps) = &run_a;
    assert!(steps.iter().all(|s| s.info.step_duration_s > 0.1));
    let other = episode(&mut b, 7, |_, _| vec![0.02]);
    assert_ne!(other.2[5].observation, steps[5].observation);
}

#[test]
fn zero_actions_walk_as_the_model_on_experiment_c_pushes() {
    // Gaps longer than the trial's push window, so that the trial never delays a push.
    let gap_s = (3.5, 4.0);
    let impulse = (0.0, 20.0);
    let config = FootstepEnvConfig {
        pushes: PushProtocol::Random {
            impulse,
            gap_s,
            settle_s: 3.0,
            direction: [1.0, 0.0, 0.0],
        },
        max_footsteps: 120,
        ..FootstepEnvConfig::default()
    };
    let mut env = FootstepEnv::new(config).unwrap();
    let seed = 11;
    let (first, t0, steps) = episode(&mut env, seed, |_, _| vec![0.0]);
    let plan = PushPlan {
        count: 40,
        impulse,
        settle: 3.0,
        gap: gap_s,
    };
    let setup =
        Settings::default().push_trial(WalkerMode::CaptureStep, 0.0, &plan, seed, [1.0, 0.0, 0.0]);
    let log = run_trial(&setup, None, &mut []).unwrap();

    // The pushes are the trial's, in order, each delivered within a tick of its time.
    let delivered: Vec<_> = steps.iter().flat_map(|s| s.info.pushes.clone()).collect();
    assert!(delivered.len() >= 5, "{}", delivered.len());
    for (d, (p, t)) in delivered
        .iter()
        .zip(plan.draw(seed).iter().zip(&log.pushes))
    {
        assert_eq!(d.impulse, p.impulse);
        assert_eq!(d.time, t.time);
        assert!(d.time >= p.time && d.time < p.time + 0.0101);
    }

    // Every touch-down of the episode is the trial's, in order.
    let start = log
        .steps
        .iter()
        .position(|s| s.time == t0)
        .expect("the first decision point is a touch-down of the model");
    assert_eq!(first[0], log.steps[start].theta_e);
    for (k, s) in steps.iter().filter(|s| !s.terminated).enumerate() {
        let record = &log.steps[start + 1 + k];
        assert_eq!(s.info.time_s, record.time, "step {k}");
        let o = s.observation.sagittal.unwrap();
        assert_eq!(o.theta_e, record.theta_e);
        assert_eq!(o.theta_e_dot, record.theta_e_dot);
        assert!((o.f_e - record.f_e()).abs() < 1e-12);
        assert_eq!(s.info.applied_offsets, vec![0.0]);
    }
    // It falls where the model falls, or neither does within the episode.
    let last = steps.last().unwrap();
    match log.falls.first() {
        Some(fall) if fall.time <= last.info.time_s => {
            assert!(last.terminated);
            assert_eq!(last.info.fall.unwrap().time, fall.time);
        }
        _ => assert!(last.truncated && !last.terminated),
    }
}

#[test]
fn harmful_actions_fall_and_cost_the_rest_of_the_episode() {
    let mut env = FootstepEnv::new(quiet(60)).unwrap();
    let [lo, hi] = env.action_bounds()[0];
    let (_, _, steps) = episode(&mut env, 1, |k, _| vec![if k % 2 == 0 { hi } else { lo }]);
    let last = steps.last().unwrap();
    assert!(last.terminated, "{} steps without a fall", steps.len());
    assert!(last.info.fall.is_some());
    let left = 60 - steps.len();
    assert_eq!(last.reward, -(1.0 + left as f64));
    // The walker applied the action as given.
    assert_eq!(steps[0].info.applied_offsets, vec![hi]);
    assert!(steps[..steps.len() - 1].iter().all(|s| s.reward >= -1.0));
    assert!(matches!(env.step(&[0.0]), Err(EnvError::EpisodeOver)));
}

#[test]
fn the_footstep_limit_truncates() {
    let mut env = FootstepEnv::new(quiet(5)).unwrap();
    let (_, _, steps) = episode(&mut env, 3, |_, _| vec![0.0]);
    assert_eq!(steps.len(), 5);
    assert!(steps[..4].iter().all(|s| !s.truncated && !s.terminated));
    let last = &steps[4];
    assert!(last.truncated && !last.terminated && !last.info.stalled);
    assert_eq!(last.info.footsteps, 5);
    // Walking in place without pushes: small errors, rewards near 0.
    assert!(steps.iter().all(|s| s.reward <= 0.0 && s.reward > -0.05));
    assert!(matches!(env.step(&[0.0]), Err(EnvError::EpisodeOver)));
}

#[test]
fn bad_actions_are_refused_and_change_nothing() {
    let mut env = FootstepEnv::new(quiet(10)).unwrap();
    assert!(matches!(env.step(&[0.0]), Err(EnvError::NotReset)));
    let mut reference = FootstepEnv::new(quiet(10)).unwrap();
    env.reset(4).unwrap();
    reference.reset(4).unwrap();
    let [lo, hi] = env.action_bounds()[0];
    for bad in [
        vec![],
        vec![0.0, 0.0],
        vec![f64::NAN],
        vec![f64::INFINITY],
        vec![f64::NEG_INFINITY],
        vec![hi + 1e-9],
        vec![lo - 1e-9],
    ] {
        let e = env.step(&bad).unwrap_err();
        assert!(
            matches!(
                e,
                EnvError::ActionLength { .. }
                    | EnvError::ActionNotFinite { .. }
                    | EnvError::ActionOutOfRange { .. }
            ),
            "{bad:?}: {e}"
        );
        assert!(!e.to_string().is_empty());
    }
    for _ in 0..3 {
        assert_eq!(env.step(&[0.01]).unwrap(), reference.step(&[0.01]).unwrap());
    }
    let bad = FootstepEnvConfig {
        max_footsteps: 0,
        ..FootstepEnvConfig::default()
    };
    assert!(matches!(FootstepEnv::new(bad), Err(EnvError::Config(_))));
    let bad = FootstepEnvConfig {
        pushes: PushProtocol::Random {
            impulse: (5.0, 1.0),
            gap_s: (3.0, 4.0),
            settle_s: 3.0,
            direction: [1.0, 0.0, 0.0],
        },
        ..FootstepEnvConfig::default()
    };
    assert!(matches!(FootstepEnv::new(bad), Err(EnvError::Config(_))));
}

#[test]
fn two_planes_give_two_action_entries_and_eight_observations() {
    let config = FootstepEnvConfig {
        learn: LearnSet::of(&[StepParameter::StepX, StepParameter::StepY]).unwrap(),
        ..quiet(4)
    };
    let mut env = FootstepEnv::new(config).unwrap();
    assert_eq!(env.action_names(), vec!["step-x", "step-y"]);
    assert_eq!(env.observation_len(), 8);
    assert_eq!(env.observation_names()[4], "frontal.theta_e");
    let obs = env.reset(2).unwrap();
    assert_eq!(obs.values().len(), 8);
    let r = env.step(&[0.0, 0.02]).unwrap();
    assert_eq!(r.info.g.len(), 2);
    assert_eq!(r.info.applied_offsets.len(), 2);
    // The lateral offset is applied towards the swing leg: its magnitude is the action's.
    assert_eq!(r.info.applied_offsets[1].abs(), 0.02);
}

#[test]
fn a_urdf_robot_walks_in_the_environment_with_scaled_bounds() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("robots/igus_like.urdf");
    let paper = FootstepEnv::new(quiet(8)).unwrap();
    let config = FootstepEnvConfig {
        robot: Some(path),
        ..quiet(8)
    };
    let mut env = FootstepEnv::new(config).unwrap();
    let s = env.scale();
    assert!(!s.is_one());
    let [_, hi] = env.action_bounds()[0];
    let [_, paper_hi] = paper.action_bounds()[0];
    assert!((hi - s.length(paper_hi)).abs() < 1e-12, "{hi} {paper_hi}");
    let (_, _, steps) = episode(&mut env, 5, |_, _| vec![0.0]);
    assert_eq!(steps.len(), 8);
    assert!(steps.last().unwrap().truncated);
    assert!(steps.iter().all(|s| !s.terminated));
}
