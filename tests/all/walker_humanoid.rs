//! The walker and the trial harness on the simulated humanoid.

use steplearn::control::{LearnSet, PerParameter, StepParameter};
use steplearn::control::{StepReports, Walker, WalkerConfig, WalkerMode};
use steplearn::experiments::schedule::{Push, ReferenceSchedule};
use steplearn::experiments::settings::Settings;
use steplearn::experiments::trial::{TrialError, run_trial};
use steplearn::robot::Side;
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
    // Nominal step time 0.40 s (the controller lengthens some steps): 20-30 touch-downs.
    assert!((20..=30).contains(&steps), "{steps} touch-downs in 10 s");
}

/// Steps after `settle` seconds of a capture-step trial at reference `f_r`: (mean F_hat,
/// mean |F_hat - F_R|, mean theta_E, falls).
fn capture_step_figures(f_r: f64, seconds: f64, settle: f64) -> (f64, f64, f64, usize) {
    let setup = Settings::default().trial(
        WalkerMode::CaptureStep,
        ReferenceSchedule::constant(f_r),
        vec![],
        [1.0, 0.0, 0.0],
        seconds,
    );
    let log = run_trial(&setup, None, &mut []).unwrap();
    let settled: Vec<_> = log.steps.iter().filter(|s| s.time > settle).collect();
    assert!(
        settled.len() >= 10,
        "{} steps after {settle} s",
        settled.len()
    );
    let n = settled.len() as f64;
    let mean = settled.iter().map(|s| s.f_hat).sum::<f64>() / n;
    let mean_abs_err = settled.iter().map(|s| s.f_e().abs()).sum::<f64>() / n;
    let theta_e = settled.iter().map(|s| s.theta_e).sum::<f64>() / n;
    (mean, mean_abs_err, theta_e, log.falls.len())
}

/// Stepping in place (F_R = 0): this 15 s run measures mean F_hat +0.36 cm and mean |F_hat|
/// 1.84 cm after 5 s (60 s: +0.4 cm, 1.9 cm; `probes/src/bin/walk.rs`). Before the walker drove the
/// support leg with the reference instead of the controller's step, the robot walked backward
/// with steps of -11.5 cm.
#[test]
fn capture_step_walker_steps_in_place_on_the_spot() {
    let (mean, mean_abs, _, falls) = capture_step_figures(0.0, 15.0, 5.0);
    println!("F_R 0: mean F_hat {mean:+.4} m, mean |F_hat| {mean_abs:.4} m");
    assert_eq!(falls, 0);
    assert!(mean.abs() < 0.02, "mean step {mean}");
    assert!(mean_abs < 0.02, "mean |step| {mean_abs}");
}

/// Tracks the reference step size: the steady-state mean step error after 5 s of a 15 s run is
/// within 2 cm for F_R in {-0.1, 0.1, 0.2} (measured: see the printed figures and the report).
/// The trunk deviation theta_E is measured from the lean the generator gives the reference
/// gait, so it stays small at every reference (30 s runs, `probes/src/bin/walk.rs`: mean +0.001,
/// -0.004, -0.011, -0.018 rad at F_R = -0.1, 0, 0.1, 0.2; measured from the halt lean alone:
/// -0.019, -0.004, +0.009, +0.022, since the trunk leans about half of what is commanded).
#[test]
fn capture_step_walker_tracks_the_reference_step() {
    for f_r in [-0.1, 0.1, 0.2] {
        let (mean, mean_abs_err, theta_e, falls) = capture_step_figures(f_r, 15.0, 5.0);
        println!(
            "F_R {f_r:+.2}: mean F_hat {mean:+.4} m (error {:+.4}), mean |error| {mean_abs_err:.4} m, mean theta_E {theta_e:+.4} rad",
            mean - f_r
        );
        assert_eq!(falls, 0, "F_R {f_r}");
        assert!((mean - f_r).abs() < 0.02, "F_R {f_r}: mean step {mean}");
        // Single steps scatter around the mean by a few cm at most (measured: mean |error|
        // 2.6, 0.65 and 1.8 cm).
        assert!(
            mean_abs_err < 0.04,
            "F_R {f_r}: mean |error| {mean_abs_err}"
        );
        assert!(theta_e.abs() < 0.03, "F_R {f_r}: mean theta_E {theta_e}");
    }
}

/// A 6 Ns forward push while stepping in place, at four phases over one step: the open-loop
/// walker falls every time, the capture-step walker never (measured over ten phases from 3.00
/// to 3.36 s: open loop falls 8/10 at 4 Ns and 10/10 at 6, 8 and 10 Ns; capture step 0/10 at
/// each of 4, 6, 8 and 10 Ns).
#[test]
fn capture_step_walker_survives_a_push_the_open_loop_walker_does_not() {
    let pushed = |mode, time| {
        let setup = Settings::default().trial(
            mode,
            ReferenceSchedule::constant(0.0),
            vec![Push { time, impulse: 6.0 }],
            [1.0, 0.0, 0.0],
            time + 3.0,
        );
        run_trial(&setup, None, &mut []).unwrap().pushes[0].fell
    };
    for time in [3.0, 3.1, 3.2, 3.3] {
        assert!(
            pushed(WalkerMode::OpenLoop, time),
            "open loop absorbed 6 Ns at {time} s"
        );
        assert!(
            !pushed(WalkerMode::CaptureStep, time),
            "capture step fell after 6 Ns at {time} s"
        );
    }
}

/// The estimator's CoM model (`com_offset`, a fixed point of the torso frame) matches the
/// simulated body: the true CoM in the torso frame, averaged while stepping in place, is
/// within 5 mm of it in x and z.
#[test]
fn estimator_com_offset_matches_the_body() {
    let mut robot = Humanoid::new(SimConfig::default()).unwrap();
    let config = WalkerConfig::new(WalkerMode::CaptureStep);
    let mut walker = Walker::new(config, robot.body().leg_geometry()).unwrap();
    let (mut sum, mut n) = (nalgebra::Vector3::zeros(), 0.0);
    while robot.time() < 6.0 {
        let tick = walker.tick(&robot.sensors(), 0.0, None).unwrap();
        robot.step(&tick.targets).unwrap();
        if robot.time() > 2.0 {
            let gt = robot.ground_truth();
            let [w, x, y, z] = gt.torso.orientation;
            let q =
                nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
            let torso = nalgebra::Vector3::from(gt.torso.position);
            sum += q.inverse() * (nalgebra::Vector3::from(gt.com) - torso);
            n += 1.0;
        }
    }
    let mean = sum / n;
    let model = config.estimator.com_offset;
    println!("true CoM in the torso frame {mean:?}, model {model:?}");
    assert!((mean.x - model[0]).abs() < 0.005, "{mean:?} vs {model:?}");
    assert!((mean.z - model[2]).abs() < 0.005, "{mean:?} vs {model:?}");
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

/// A push due while the robot is down waits until it has stood up and walked `resettle_s`;
/// the trial then ends one push window after its last push.
#[test]
fn pushes_delayed_by_a_fall_wait_for_the_gait_and_trials_end_after_the_last_push() {
    let settings = Settings::default();
    let setup = steplearn::experiments::trial::TrialSetup {
        stop_after_last_push_s: Some(settings.push_window_s),
        ..settings.trial(
            WalkerMode::CaptureStep,
            ReferenceSchedule::constant(0.0),
            vec![
                Push {
                    time: 2.0,
                    impulse: 40.0,
                },
                Push {
                    time: 2.5,
                    impulse: 0.5,
                },
            ],
            [1.0, 0.0, 0.0],
            60.0,
        )
    };
    let log = run_trial(&setup, None, &mut []).unwrap();
    assert_eq!(log.pushes.len(), 2);
    assert!(log.pushes[0].fell && !log.pushes[1].fell);
    let fall = log.falls[0].time;
    let earliest = fall + settings.recovery_s + settings.resettle_s;
    assert!(
        log.pushes[1].time >= earliest - 0.011 && log.pushes[1].time < earliest + 0.1,
        "second push at {} s, fall at {fall} s",
        log.pushes[1].time
    );
    let end = log.pushes[1].time + settings.push_window_s;
    assert!(
        (log.sim_time_s - end).abs() < 0.05,
        "trial ended at {} s, expected about {end} s",
        log.sim_time_s
    );
}

/// A policy with one fixed sagittal offset and, if given, one fixed lateral width offset, one
/// fixed step-time offset and one fixed sole pitch or roll, all held from its `from_query`-th
/// query on (0 before); it records the sagittal, the step-time and the sole's reach the walker
/// reports (the pitch's, or the roll's if it holds a roll) and learns nothing.
pub(crate) struct FixedOffset {
    pub(crate) offset: f64,
    pub(crate) lateral: Option<f64>,
    pub(crate) time: Option<f64>,
    pub(crate) ankle: Option<f64>,
    pub(crate) roll: Option<f64>,
    pub(crate) from_query: usize,
    pub(crate) queries: usize,
    pub(crate) reach: Vec<[f64; 2]>,
    pub(crate) time_reach: Vec<[f64; 2]>,
    pub(crate) ankle_reach: Vec<[f64; 2]>,
}

impl FixedOffset {
    pub(crate) fn sagittal(offset: f64) -> Self {
        FixedOffset {
            offset,
            lateral: None,
            time: None,
            ankle: None,
            roll: None,
            from_query: 0,
            queries: 0,
            reach: vec![],
            time_reach: vec![],
            ankle_reach: vec![],
        }
    }
}

impl steplearn::control::FootstepPolicy for FixedOffset {
    fn learns(&self) -> LearnSet {
        let mut set = vec![StepParameter::StepX];
        set.extend(self.lateral.map(|_| StepParameter::StepY));
        set.extend(self.time.map(|_| StepParameter::StepTime));
        set.extend(self.ankle.map(|_| StepParameter::AnklePitch));
        set.extend(self.roll.map(|_| StepParameter::AnkleRoll));
        LearnSet::of(&set).unwrap()
    }
    fn offsets(
        &mut self,
        _: &PerParameter<steplearn::control::LearnerInput>,
    ) -> Result<PerParameter<f64>, steplearn::control::LearnerError> {
        self.queries += 1;
        let mut out = PerParameter::splat(0.0);
        if self.queries > self.from_query {
            out[StepParameter::StepX] = self.offset;
            out[StepParameter::StepY] = self.lateral.unwrap_or(0.0);
            out[StepParameter::StepTime] = self.time.unwrap_or(0.0);
            out[StepParameter::AnklePitch] = self.ankle.unwrap_or(0.0);
            out[StepParameter::AnkleRoll] = self.roll.unwrap_or(0.0);
        }
        Ok(out)
    }
    fn set_reach(
        &mut self,
        reach: &PerParameter<[f64; 2]>,
    ) -> Result<(), steplearn::control::LearnerError> {
        self.reach.push(reach[StepParameter::StepX]);
        self.time_reach.push(reach[StepParameter::StepTime]);
        let sole = if self.roll.is_some() {
            StepParameter::AnkleRoll
        } else {
            StepParameter::AnklePitch
        };
        self.ankle_reach.push(reach[sole]);
        Ok(())
    }
    fn touch_down(
        &mut self,
        _: &PerParameter<steplearn::rules::StepOutcome>,
    ) -> Result<StepReports, steplearn::control::LearnerError> {
        let mut out = StepReports::default();
        out[StepParameter::StepX] = Some(steplearn::control::TouchDownReport {
            gradient: 0.0,
            samples: 0,
            response: 0.0,
            gain: 0.0,
            scale: 1.0,
        });
        Ok(out)
    }
    fn fall(
        &mut self,
        _: &PerParameter<steplearn::rules::StepOutcome>,
    ) -> Result<StepReports, steplearn::control::LearnerError> {
        Ok(StepReports::default())
    }
    fn discard_step(&mut self) {}
}

/// The learned offset enters the footstep (the paper) or the controller's reference: with
/// the offset in the reference the controller plans the whole step for F_R + dF (its target
/// state moves, the footstep carries no separate offset), the sweep still gets F_R + dF, and
/// the reach the learner is told is the same offset range as in footstep mode.
#[test]
fn the_learned_offset_enters_the_footstep_or_the_reference() {
    use steplearn::control::OffsetTarget;
    let (f_r, d_f) = (0.2, 0.03);
    for target in [OffsetTarget::Footstep, OffsetTarget::Reference] {
        let mut config = WalkerConfig::new(WalkerMode::CaptureStep);
        config.offset_target = target;
        let range = config.motion.step_x_range;
        let mut robot = Humanoid::new(SimConfig::default()).unwrap();
        let mut walker = Walker::new(config, robot.body().leg_geometry()).unwrap();
        let mut policy = FixedOffset::sagittal(d_f);
        let mut checked = 0;
        while robot.time() < 4.0 {
            let tick = walker
                .tick(&robot.sensors(), f_r, Some(&mut policy))
                .unwrap();
            let d = tick.decision.unwrap();
            // Fully engaged once the generator and then the offset have faded in (2 x 1 s).
            if robot.time() > 2.1 {
                checked += 1;
                assert_eq!(tick.learned_offset, d_f);
                assert!((tick.command.gait_x - (f_r + d_f)).abs() < 1e-12);
                let [lo, hi] = *policy.reach.last().unwrap();
                let (planned, footstep_offset) = match target {
                    OffsetTarget::Footstep => (f_r, d_f),
                    OffsetTarget::Reference => (f_r + d_f, 0.0),
                };
                assert!(
                    (d.target[0].pos - 0.5 * planned).abs() < 1e-12,
                    "{target:?}"
                );
                assert_eq!(d.learned_offset, footstep_offset, "{target:?}");
                // The reach is measured from the step without the offset.
                let base = match target {
                    OffsetTarget::Footstep => d.analytic_step_x,
                    OffsetTarget::Reference => d.analytic_step_x - d_f,
                };
                assert!((lo - (range[0] - base)).abs() < 1e-12, "{target:?}");
                assert!((hi - (range[1] - base)).abs() < 1e-12, "{target:?}");
            }
            robot.step(&tick.targets).unwrap();
            assert!(
                robot.fall().is_none(),
                "{target:?}: fell at {:.2} s",
                robot.time()
            );
        }
        assert!(checked > 100, "{checked}");
    }
    // In learner-only mode the offset is the whole step whatever the target.
    let mut config = WalkerConfig::new(WalkerMode::LearnerOnly);
    config.offset_target = OffsetTarget::Reference;
    let robot = Humanoid::new(SimConfig::default()).unwrap();
    let mut walker = Walker::new(config, robot.body().leg_geometry()).unwrap();
    let mut policy = FixedOffset::sagittal(d_f);
    let tick = walker
        .tick(&robot.sensors(), 0.0, Some(&mut policy))
        .unwrap();
    let d = tick.decision.unwrap();
    assert_eq!(d.learned_offset, d_f);
    assert_eq!(d.target[0].pos, 0.0);
}

/// With the default start ramp the Capture Step walker starts from standing at references
/// where it fell at once without one (0.19 m, 0.25 m) and at the controller's largest (0.30 m).
#[test]
fn the_walker_starts_from_standing_at_brisk_references() {
    for f_r in [0.19, 0.25, 0.30] {
        let setup = Settings::default().trial(
            WalkerMode::CaptureStep,
            ReferenceSchedule::constant(f_r),
            vec![],
            [1.0, 0.0, 0.0],
            6.0,
        );
        let log = run_trial(&setup, None, &mut []).unwrap();
        assert!(log.falls.is_empty(), "F_R {f_r}: fell at {:?}", log.falls);
        // Walking at the reference by the end (the model steps a little short).
        let last: Vec<_> = log.steps.iter().filter(|s| s.time > 4.0).collect();
        assert!(last.len() >= 4);
        let mean = last.iter().map(|s| s.f_hat).sum::<f64>() / last.len() as f64;
        assert!((mean - f_r).abs() < 0.08, "F_R {f_r}: mean step {mean}");
        // The ramp shows in the logged reference of the first steps.
        assert!(log.steps[0].f_r < 0.5 * f_r, "{:?}", log.steps[0]);
    }
}

#[test]
fn a_negative_start_ramp_is_refused() {
    let mut config = WalkerConfig::new(WalkerMode::CaptureStep);
    config.start_ramp_s = -1.0;
    let robot = Humanoid::new(SimConfig::default()).unwrap();
    let err = Walker::new(config, robot.body().leg_geometry()).unwrap_err();
    assert!(err.to_string().contains("start_ramp_s"), "{err}");
    config.start_ramp_s = f64::NAN;
    assert!(Walker::new(config, robot.body().leg_geometry()).is_err());
}

/// A step-time offset reaches the controller: stepping in place with dT = -0.05 s the steps are
/// shorter in time than the model's (measured: 0.356 s against 0.368 s; the controller's step
/// time is recomputed every tick, so a constant dT does not shorten a step by all of it), and the reach the walker reports for dT always contains
/// the offsets that leave the step time within its limits (lo <= 0 <= hi where the limits do
/// not bind).
#[test]
fn a_step_time_offset_shortens_the_steps_and_its_reach_is_reported() {
    let setup = Settings::default().trial(
        WalkerMode::CaptureStep,
        ReferenceSchedule::constant(0.0),
        vec![],
        [1.0, 0.0, 0.0],
        10.0,
    );
    let durations = |log: &steplearn::experiments::trial::TrialLog| {
        let t: Vec<f64> = log
            .steps
            .iter()
            .filter(|s| s.time > 4.0)
            .map(|s| s.time)
            .collect();
        (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64
    };
    let model = run_trial(&setup, None, &mut []).unwrap();
    let mut policy = FixedOffset {
        time: Some(-0.05),
        ..FixedOffset::sagittal(0.0)
    };
    let sooner = run_trial(&setup, Some(&mut policy), &mut []).unwrap();
    assert_eq!(model.falls.len() + sooner.falls.len(), 0);
    let (m, s) = (durations(&model), durations(&sooner));
    assert!(
        s < m - 0.005,
        "mean step duration: dT -0.05 {s:.3} s, model {m:.3} s"
    );
    assert!(!policy.time_reach.is_empty());
    assert!(policy.time_reach.iter().all(|[lo, hi]| lo <= hi));
    let open = policy
        .time_reach
        .iter()
        .filter(|[lo, hi]| *lo < 0.0 && *hi > 0.0)
        .count();
    assert!(
        open * 2 > policy.time_reach.len(),
        "{open} of {}",
        policy.time_reach.len()
    );
}

/// What happened after a sole tilt offset was switched on stepping in place.
struct AnkleSwitch {
    /// The support foot's mean centre of pressure over the single-support ticks of the first
    /// 0.25 s (m forward of the foot's frame) for the pitch, of the first 0.6 s (two steps, m
    /// towards the swing leg's side) for the roll.
    cop: f64,
    /// The trunk's estimated pitch 0.05 s after the centre of pressure's window (rad).
    pitch: f64,
    /// The offset of the switched parameter the walker applied, every tick.
    applied: Vec<f64>,
    /// The reach reported for it, every tick.
    reach: Vec<[f64; 2]>,
}

/// Stepping in place, the sole's pitch (`ankle-pitch`) or roll (`ankle-roll`) offset `value`
/// switched on at the first tick after 3 s (the learner's engagement has ramped in by then).
fn after_an_ankle_switch(sole: StepParameter, value: f64) -> AnkleSwitch {
    let mut robot = Humanoid::new(SimConfig::default()).unwrap();
    let mut walker = Walker::new(
        WalkerConfig::new(WalkerMode::CaptureStep),
        robot.body().leg_geometry(),
    )
    .unwrap();
    let mut policy = FixedOffset {
        ankle: (sole == StepParameter::AnklePitch).then_some(value),
        roll: (sole == StepParameter::AnkleRoll).then_some(value),
        from_query: usize::MAX,
        ..FixedOffset::sagittal(0.0)
    };
    let window = if sole == StepParameter::AnkleRoll {
        0.6
    } else {
        0.25
    };
    let (mut cops, mut pitch, mut applied) = (vec![], f64::NAN, vec![]);
    while robot.time() < 3.05 + window {
        let sensors = robot.sensors();
        if sensors.time >= 3.0 && policy.from_query == usize::MAX {
            policy.from_query = policy.queries;
        }
        let tick = walker.tick(&sensors, 0.0, Some(&mut policy)).unwrap();
        applied.push(tick.offsets[sole]);
        let since = sensors.time - 3.0;
        let [a, b] = sensors.feet;
        if (0.0..window).contains(&since) && a.in_contact != b.in_contact {
            let (support, foot) = if a.in_contact {
                (Side::Left, a)
            } else {
                (Side::Right, b)
            };
            cops.push(match sole {
                StepParameter::AnkleRoll => support.other().sign() * foot.cop[1],
                _ => foot.cop[0],
            });
        }
        pitch = tick.estimate.pitch;
        robot.step(&tick.targets).unwrap();
        assert!(robot.fall().is_none(), "fell at {:.2} s", robot.time());
    }
    assert!(cops.len() > 10, "{} single-support ticks", cops.len());
    AnkleSwitch {
        cop: cops.iter().sum::<f64>() / cops.len() as f64,
        pitch,
        applied,
        reach: policy.ankle_reach,
    }
}

/// The switches of `sole` to +0.02, 0 and -0.02 rad; each moves the centre of pressure by at
/// least `margin` (m) beyond the next.
fn ankle_switches(sole: StepParameter, margin: f64) -> [AnkleSwitch; 3] {
    let out = [0.02, 0.0, -0.02].map(|v| after_an_ankle_switch(sole, v));
    let [plus, flat, minus] = [out[0].cop, out[1].cop, out[2].cop];
    assert!(
        plus > flat + margin && flat > minus + margin,
        "{sole}: centre of pressure at +0.02 rad {plus:.4} m, flat {flat:.4} m, -0.02 rad {minus:.4} m"
    );
    out
}

/// The reach the walker reported for the switched sole was the ankle's limit, every tick.
fn assert_reach_is_the_ankles_limit(switch: &AnkleSwitch) {
    let limit = steplearn::control::motion::ANKLE_LIMIT;
    assert!(!switch.reach.is_empty());
    assert!(switch.reach.iter().all(|r| *r == [-limit, limit]));
}

/// The learned sole pitch reaches the support foot: switched on stepping in place, +0.02 rad
/// (toe down) moves the support foot's centre of pressure forward at once and turns the trunk
/// back, -0.02 rad (heel down) the other way round (measured: about 0.04 m either way in the
/// first 0.25 s, the lever `SoleTilt::lever` stands for); the walker applies exactly the
/// policy's offset and reports the ankle's limit as its reach.
#[test]
fn an_ankle_pitch_offset_moves_the_support_soles_centre_of_pressure() {
    let [toe, flat, heel] = ankle_switches(StepParameter::AnklePitch, 0.015);
    assert!(
        toe.pitch < flat.pitch && flat.pitch < heel.pitch,
        "trunk pitch: toe down {:.4}, flat {:.4}, heel down {:.4}",
        toe.pitch,
        flat.pitch,
        heel.pitch
    );
    let switched = toe.applied.iter().filter(|&&a| a == 0.02).count();
    assert!(switched > 20 && toe.applied[..10].iter().all(|&a| a == 0.0));
    assert_reach_is_the_ankles_limit(&toe);
}

/// The learned sole roll reaches the support foot: switched on stepping in place, +0.02 rad
/// (the edge on the swing leg's side down) moves the support foot's centre of pressure towards
/// the swing leg's side, -0.02 rad away from it, on whichever foot the walker stands
/// (measured over two steps: about 0.03 m towards it, 0.05 m away; the sole's inner edge is
/// nearer the centre of pressure of a flat sole); the
/// walker applies the policy's offset, mirrored to the side of each step's swing leg
/// (`Tick::offsets` holds the sole's roll, positive pressing its right edge), and reports the
/// ankle's limit as its reach.
#[test]
fn an_ankle_roll_offset_moves_the_support_soles_centre_of_pressure_sideways() {
    let [inner, ..] = ankle_switches(StepParameter::AnkleRoll, 0.005);
    let switched: Vec<f64> = inner
        .applied
        .iter()
        .copied()
        .filter(|a| *a != 0.0)
        .collect();
    assert!(switched.len() > 20 && inner.applied[..10].iter().all(|&a| a == 0.0));
    assert!(switched.iter().all(|a| a.abs() == 0.02));
    assert!(switched.contains(&0.02) && switched.contains(&-0.02));
    assert_reach_is_the_ankles_limit(&inner);
}
