//! The step motion generator: leg space round trip, timing, support exchange, smoothness.

use proptest::prelude::*;
use steplearn::control::motion::{
    LegPose, LegSpace, MotionConfig, MotionGenerator, StepCommand, Swing,
};
use steplearn::robot::LegJoint;
use steplearn::sim::BodyConfig;

fn space() -> LegSpace {
    LegSpace::new(&BodyConfig::default().leg_geometry())
}

proptest! {
    #[test]
    fn leg_pose_joint_round_trip(
        ext in 0.0..0.6f64,
        roll in -0.4..0.4f64, pitch in -0.8..0.8f64, yaw in -0.4..0.4f64,
        froll in -0.3..0.3f64, fpitch in -0.5..0.5f64,
    ) {
        let pose = LegPose { extension: ext, angle: [roll, pitch, yaw], foot: [froll, fpitch] };
        let q = space().to_joints(&pose);
        let back = space().from_joints(&q);
        prop_assert!((back.extension - ext).abs() < 1e-9);
        for k in 0..3 { prop_assert!((back.angle[k] - pose.angle[k]).abs() < 1e-9); }
        for k in 0..2 { prop_assert!((back.foot[k] - pose.foot[k]).abs() < 1e-9); }
        // Bent knee never hyperextends; the sole angle is the sum of the pitch joints.
        prop_assert!(q[LegJoint::Knee as usize] >= 0.0);
        let sole = q[LegJoint::HipPitch as usize] + q[LegJoint::Knee as usize]
            + q[LegJoint::AnklePitch as usize];
        prop_assert!((sole - fpitch).abs() < 1e-9);
    }
}

#[test]
fn straight_leg_is_zero() {
    let q = space().to_joints(&LegPose::default());
    assert!(q.iter().all(|v| v.abs() < 1e-7), "{q:?}");
}

fn generator() -> MotionGenerator {
    generator_with(MotionConfig::default())
}

#[test]
fn steps_take_the_commanded_time_and_alternate() {
    let mut g = generator();
    let dt = 0.01;
    let mut exchanges = Vec::new();
    let mut t = 0.0;
    let mut support = g.support();
    while t < 3.0 {
        // Remaining time of a 0.5 s step.
        let cmd = StepCommand {
            step_x: 0.0,
            step_y: g.swing().sign() * g.nominal_width(),
            turn: 0.0,
            step_time: (1.0 - g.phase()) * 0.5,
            gait_x: 0.0,
            tilt: None,
            swing_landed: None,
            ankle_pitch: 0.0,
            ankle_roll: 0.0,
        };
        g.update(&cmd, dt);
        t += dt;
        if g.support() != support {
            exchanges.push(t);
            assert_eq!(g.support(), support.other());
            support = g.support();
        }
    }
    assert_eq!(exchanges.len(), 6, "{exchanges:?}");
    for w in exchanges.windows(2) {
        assert!((w[1] - w[0] - 0.5).abs() < 0.011, "{exchanges:?}");
    }
}

/// The swing foot lands `step_x` ahead of the support foot, and the support leg has swept the
/// hips `gait_x / 2` ahead of its foot whatever `step_x` is.
#[test]
fn swing_foot_lands_where_commanded() {
    for (step_x, gait_x) in [(0.15, 0.15), (-0.1, 0.0), (0.15, 0.0), (0.0, 0.2)] {
        let mut g = generator();
        let dt = 0.005;
        // Run long enough for the fade-in and filter to settle, stop just before touch-down.
        for _ in 0..4000 {
            let cmd = StepCommand {
                gait_x,
                ..g.open_loop(step_x)
            };
            g.update(&cmd, dt);
            if g.steps() >= 8 && g.phase() > 0.995 - dt / 0.4 {
                break;
            }
        }
        let d = space().leg_length() * (1.0 - g.config().gait().halt_extension);
        let lean = g.config().gait().lean_per_step * gait_x;
        let swing = g.legs()[g.swing().index()].angle[1] + lean;
        let support = g.legs()[g.support().index()].angle[1] + lean;
        // Foot x relative to the hip is -d sin(pitch).
        let gap = -d * swing.sin() + d * support.sin();
        assert!((gap - step_x).abs() < 0.01, "{step_x} {gait_x}: gap {gap}");
        let hips = d * support.sin();
        assert!(
            (hips - gait_x / 2.0).abs() < 0.01,
            "{step_x} {gait_x}: hips {hips} ahead of the support foot"
        );
    }
}

#[test]
fn changing_the_command_mid_step_is_smooth() {
    let mut g = generator();
    let dt = 0.01;
    let mut last = g.update(&g.open_loop(0.0), dt);
    let mut biggest: f64 = 0.0;
    for i in 0..300 {
        let mut cmd = g.open_loop(if i < 150 { 0.0 } else { 0.2 });
        if i == 170 {
            cmd.step_time *= 0.5;
        }
        let t = g.update(&cmd, dt);
        for k in 0..12 {
            biggest = biggest.max((t.pos[k] - last.pos[k]).abs());
        }
        last = t;
    }
    // No joint target moves more than ~0.1 rad in one 10 ms tick (10 rad/s).
    assert!(biggest < 0.1, "largest jump {biggest}");
}

#[test]
fn bad_command_values_are_ignored() {
    let mut g = generator();
    let cmd = StepCommand {
        step_x: f64::NAN,
        step_y: f64::INFINITY,
        turn: f64::NAN,
        step_time: f64::NAN,
        gait_x: f64::NAN,
        tilt: Some([[f64::NAN, 0.0], [0.0, f64::INFINITY]]),
        swing_landed: None,
        ankle_pitch: 0.0,
        ankle_roll: 0.0,
    };
    for _ in 0..100 {
        let t = g.update(&cmd, 0.01);
        assert!(t.pos.iter().all(|v| v.is_finite()));
    }
    assert!(g.steps() >= 1);
}

/// The improved setup's tracking swing with the generator's other defaults.
fn tracking() -> MotionConfig {
    MotionConfig {
        swing: Swing::Tracking,
        ..MotionConfig::default()
    }
}

fn generator_with(config: MotionConfig) -> MotionGenerator {
    MotionGenerator::new(
        config.check().unwrap(),
        &BodyConfig::default().leg_geometry(),
    )
}

/// Runs `g` with steps of `step_time` left at every tick, the swing foot reported landed from
/// `landed_at` on (s after the last exchange; `None`: unknown), and returns the time of the
/// first exchange.
fn first_exchange(g: &mut MotionGenerator, step_time: f64, landed_at: Option<f64>) -> f64 {
    let dt = 0.01;
    let mut t = 0.0;
    let start = g.steps();
    while g.steps() == start {
        let cmd = StepCommand {
            step_x: 0.2,
            step_y: g.swing().sign() * g.nominal_width(),
            turn: 0.0,
            step_time: (step_time - t).max(0.0),
            gait_x: 0.0,
            tilt: None,
            swing_landed: landed_at.map(|at| t >= at - 1e-9),
            ankle_pitch: 0.0,
            ankle_roll: 0.0,
        };
        g.update(&cmd, dt);
        t += dt;
        assert!(t < 5.0, "no exchange");
    }
    t
}

#[test]
fn an_early_landing_ends_the_step_only_past_the_set_phase() {
    let early = MotionConfig {
        early_landing_phase: 0.5,
        ..tracking()
    };
    // Off (1): the landing at 0.3 s of a 0.4 s step changes nothing.
    let off = MotionConfig {
        early_landing_phase: 1.0,
        ..tracking()
    };
    let on_time = first_exchange(&mut generator_with(off), 0.4, Some(0.3));
    assert!((on_time - 0.4).abs() < 0.015, "{on_time}");
    // With it, the step ends at the landing; before half the step a landing waits for it.
    let ended = first_exchange(&mut generator_with(early), 0.4, Some(0.3));
    assert!((ended - 0.31).abs() < 0.015, "{ended}");
    let at_half = first_exchange(&mut generator_with(early), 0.4, Some(0.05));
    assert!(at_half > 0.15 && at_half < 0.25, "{at_half}");
}

#[test]
fn landing_settings_out_of_range_are_refused_naming_the_key() {
    for (config, key) in [
        (
            MotionConfig {
                early_landing_phase: 1.2,
                ..tracking()
            },
            "early_landing_phase",
        ),
        (
            MotionConfig {
                early_landing_phase: f64::NAN,
                ..tracking()
            },
            "early_landing_phase",
        ),
        (
            MotionConfig {
                tilt_lift: -0.1,
                ..tracking()
            },
            "tilt_lift",
        ),
        (
            MotionConfig {
                tilt_lift: 1.5,
                ..tracking()
            },
            "tilt_lift",
        ),
    ] {
        let err = config.check().unwrap_err().to_string();
        assert!(err.starts_with(key), "{key}: {err}");
    }
}

/// The swing leg's extension over a 0.4 s step with the trunk tilted by `tilt` (rad of pitch,
/// beyond the dead band from the first tick on: the settled tilt starts upright).
fn swing_extensions(config: MotionConfig, tilt: f64) -> Vec<f64> {
    swing_poses(config, tilt, 0.0)
        .iter()
        .map(|pose| pose.extension)
        .collect()
}

/// The swing leg's pose at every tick of a 0.4 s step of `step_x` with the trunk tilted by
/// `tilt`, as [`swing_extensions`].
fn swing_poses(config: MotionConfig, tilt: f64, step_x: f64) -> Vec<LegPose> {
    let mut g = generator_with(config);
    // Fade in first, stepping in place upright.
    let dt = 0.01;
    let upright = |g: &MotionGenerator, left: f64| StepCommand {
        step_x,
        step_y: g.swing().sign() * g.nominal_width(),
        turn: 0.0,
        step_time: left,
        gait_x: 0.0,
        tilt: Some([[0.0, 0.0], [0.0, 0.0]]),
        swing_landed: None,
        ankle_pitch: 0.0,
        ankle_roll: 0.0,
    };
    while g.time_since_start() < 2.0 || g.phase() > 0.0 {
        let left = (1.0 - g.phase()) * 0.4;
        g.update(&upright(&g, left), dt);
    }
    let swing = g.swing();
    let mut out = Vec::new();
    for k in 0..40 {
        let mut cmd = upright(&g, 0.4 - k as f64 * dt);
        cmd.tilt = Some([[0.0, tilt], [0.0, 0.0]]);
        g.update(&cmd, dt);
        if g.swing() != swing {
            break;
        }
        out.push(g.legs()[swing.index()]);
    }
    out
}

#[test]
fn the_tilt_gain_acts_only_beyond_its_band() {
    let once = MotionConfig {
        tilt_gain: 1.0,
        tilt_gain_band: 0.0,
        ..tracking()
    };
    let gained = MotionConfig {
        tilt_gain: 1.3,
        tilt_gain_band: 0.0,
        ..tracking()
    };
    let banded = MotionConfig {
        tilt_gain: 1.3,
        tilt_gain_band: 0.05,
        ..tracking()
    };
    let pitch = |config: MotionConfig, tilt: f64| -> Vec<f64> {
        // Stepping in place the tracked swing leg stays parallel to the support leg whatever
        // the gain: a step forward shows it.
        swing_poses(config, tilt, 0.2)
            .iter()
            .map(|pose| pose.angle[1])
            .collect()
    };
    // A tilt within the band (0.03 rad beyond the dead band, settling towards it) is
    // compensated once: tick for tick the swing of the gain 1 generator.
    assert_eq!(pitch(banded, -0.04), pitch(once, -0.04));
    assert_ne!(pitch(gained, -0.04), pitch(once, -0.04));
    // A push's tilt: beyond the band the gain adds to the compensation, less than without a
    // band by about the gain's share of the band.
    let (a, b, c) = (pitch(once, -0.2), pitch(banded, -0.2), pitch(gained, -0.2));
    let end = a.len() * 3 / 4;
    let (a, b, c) = (a[end], b[end], c[end]);
    assert!((a - b) * (b - c) > 0.0, "once {a}, banded {b}, gained {c}");
    let share = (b - a) / (c - a);
    assert!((0.6..0.85).contains(&share), "share {share}");
}

#[test]
fn tilt_lift_lifts_a_tilted_swing_higher_and_lands_it_as_before() {
    let plain = MotionConfig {
        tilt_lift: 0.0,
        ..tracking()
    };
    let lifted = MotionConfig {
        tilt_lift: 0.5,
        ..tracking()
    };
    let upright = swing_extensions(lifted, 0.0);
    let without = swing_extensions(plain, -0.11);
    let with = swing_extensions(lifted, -0.11);
    // Upright it changes nothing.
    assert_eq!(upright, swing_extensions(plain, 0.0));
    // Mid-swing 0.5 x 0.1 rad of tilt beyond the band lifts by up to 0.05 leg lengths.
    let mid = with.len() / 2;
    let extra = with[mid] - without[mid];
    assert!((extra - 0.05).abs() < 0.01, "{extra}");
    // At the end of the lift both are back at the halt extension.
    let (a, b) = (with.last().unwrap(), without.last().unwrap());
    assert!((a - b).abs() < 1e-6, "{a} {b}");
}
