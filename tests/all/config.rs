//! Strict, checked config files and `steplearn config`: unknown keys and sections are errors
//! naming the key, partial sections keep the defaults at every level, out-of-range protocol
//! values are errors naming the field, and the printed defaults round-trip.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use steplearn::experiments::config_file::ConfigFile;
use steplearn::experiments::disturbance::DisturbanceProtocol;
use steplearn::experiments::protocol::ProtocolTables;
use steplearn::experiments::robustness::RobustnessProtocol;
use steplearn::experiments::settings::Settings;
use steplearn::experiments::stability::StabilityProtocol;
use steplearn::experiments::tracking::TrackingProtocol;
use steplearn::sim::BodyConfig;

fn steplearn(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_steplearn"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// `experiment stability --config CONFIG --out OUT`.
fn stability_with(config: &Path, out: &Path) -> Output {
    steplearn(&[
        "experiment",
        "stability",
        "--config",
        config.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ])
}

/// `config --check` on `text`: (success, stdout, stderr).
fn check(text: &str) -> (bool, String, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "c.toml", text);
    let o = steplearn(&["config", "--check", path.to_str().unwrap()]);
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn unknown_sections_and_keys_are_errors_that_name_them_and_list_the_allowed() {
    for (text, key, allowed) in [
        ("[settings.robot]\ndt = 0.5\n", "`robot`", "`sim`"),
        (
            "[settings]\nunknown_key = 3\n",
            "`unknown_key`",
            "`push_window_s`",
        ),
        ("[settings.sim]\nd_t = 0.001\n", "`d_t`", "`steps_per_tick`"),
        (
            "[settings.sim.body.thigh]\nmass = 2.0\nmas = 1\n",
            "`mas`",
            "`gyration_fraction`",
        ),
        (
            "[settings.walker.motion]\nswing_step_scal = 0.9\n",
            "`swing_step_scal`",
            "`swing_step_scale`",
        ),
        (
            "[protocols.stabilty]\npushes = 3\n",
            "`stabilty`",
            "`stability`",
        ),
        (
            "[protocols.robustness]\nimpuls = 3\n",
            "`impuls`",
            "`impulse`",
        ),
    ] {
        let (ok, _, err) = check(text);
        assert!(!ok, "{text:?} accepted");
        assert!(
            err.contains(&format!("unknown field {key}")),
            "{text:?}: {err}"
        );
        assert!(err.contains("expected one of"), "{text:?}: {err}");
        assert!(err.contains(allowed), "{text:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
    // With its path in the file.
    let (_, _, err) = check("[settings.robot]\ndt = 0.5\n");
    assert!(err.contains("settings.robot"), "{err}");
    let e = ConfigFile::from_toml("[settings]\nunknown_key = 3\n").unwrap_err();
    assert_eq!(e.field, "settings.unknown_key");
}

#[test]
fn out_of_range_protocol_values_are_errors_naming_the_field() {
    for (text, field) in [
        (
            "[protocols.stability]\npushes = 0\n",
            "protocols.stability.pushes",
        ),
        (
            "[protocols.stability]\ndirection = [0.0, 0.0, 0.0]\n",
            "protocols.stability.direction",
        ),
        (
            "[protocols.stability]\ndirection = [nan, 0.0, 0.0]\n",
            "protocols.stability.direction",
        ),
        (
            "[protocols.stability]\nimpulse = [10.0, 5.0]\n",
            "protocols.stability.impulse",
        ),
        (
            "[protocols.stability]\nimpulse = [-1.0, 5.0]\n",
            "protocols.stability.impulse",
        ),
        (
            "[protocols.stability]\ngap_s = [4.0, 3.0]\n",
            "protocols.stability.gap_s",
        ),
        (
            "[protocols.disturbance]\npushes = 0\n",
            "protocols.disturbance.pushes",
        ),
        (
            "[protocols.disturbance]\nimpulse = -8.0\n",
            "protocols.disturbance.impulse",
        ),
        (
            "[protocols.robustness]\npushes = 0\n",
            "protocols.robustness.pushes",
        ),
        (
            "[protocols.robustness]\nsettle_s = [0.0, 4.0]\n",
            "protocols.robustness.settle_s",
        ),
        (
            "[protocols.tracking]\nduration_s = 0.0\n",
            "protocols.tracking.duration_s",
        ),
        (
            "[protocols.tracking]\nhold_s = [8.0, 4.0]\n",
            "protocols.tracking.hold_s",
        ),
        ("[settings]\nscale = 0.0\n", "settings.scale"),
        ("[settings.sim]\ndt = 0.5\n", "settings.sim"),
        (
            "[settings.walker.motion]\nearly_landing_phase = 1.5\n",
            "settings.walker.motion.early_landing_phase",
        ),
    ] {
        let (ok, _, err) = check(text);
        assert!(!ok, "{text:?} accepted");
        assert!(err.contains(field), "{text:?}: expected {field} in {err}");
        let parsed = ConfigFile::from_toml(text).unwrap();
        let e = parsed.validate().unwrap_err();
        assert!(e.field.starts_with(field), "{text:?}: {e:?}");
        assert!(!e.reason.is_empty());
    }
}

#[test]
fn an_out_of_range_protocol_stops_the_experiment_before_it_runs() {
    let dir = tempfile::tempdir().unwrap();
    let config = write(dir.path(), "c.toml", "[protocols.stability]\npushes = 0\n");
    let out = dir.path().join("out");
    let o = stability_with(&config, &out);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("protocols.stability.pushes"), "{err}");
    assert!(!out.join("summary.json").exists());
    // The sweep's --pushes 0 is an error too, not silently one push.
    let o = steplearn(&["sweep", "--pushes", "0", "--out", out.to_str().unwrap()]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("pushes"));
}

#[test]
fn partial_nested_sections_keep_the_other_defaults() {
    let config = ConfigFile::parse_toml("[settings.sim.body.torso]\nmass = 11.5\n").unwrap();
    let default = BodyConfig::default();
    assert_eq!(config.settings.sim.body.torso.mass, 11.5);
    assert_eq!(config.settings.sim.body.torso.length, default.torso.length);
    let mut expected = Settings::default();
    expected.sim.body.torso.mass = 11.5;
    assert_eq!(config.settings, expected);
    assert_eq!(config.protocols, ProtocolTables::new());

    // Thigh and shank share a type but not their defaults: each keeps its own.
    let config = ConfigFile::parse_toml("[settings.sim.body.shank]\nmass = 0.7\n").unwrap();
    let shank = config.settings.sim.body.shank;
    assert_eq!(shank.mass, 0.7);
    assert_eq!(shank.length, default.shank.length);
    assert_eq!(shank.radius, default.shank.radius);
    assert_eq!(config.settings.sim.body.thigh, default.thigh);

    // The robustness map is the figure's resolution, 31 x 31, not a key.
    let config = ConfigFile::parse_toml("[protocols.robustness]\npushes = 3\n").unwrap();
    let robustness: RobustnessProtocol = config.protocols.get("robustness").unwrap();
    assert_eq!(robustness.map.resolution, (31, 31));
    let e = ConfigFile::parse_toml("[protocols.robustness.map]\nf_r = 0.1\n").unwrap_err();
    assert!(e.to_string().contains("unknown field `map`"), "{e}");

    // The CLI accepts it.
    let (ok, out, err) = check("[settings.sim.body.torso]\nmass = 11.5\n");
    assert!(ok, "{err}");
    assert_eq!(out.trim(), "ok");
}

#[test]
fn a_walker_section_without_mode_takes_the_defaults() {
    let config =
        ConfigFile::parse_toml("[settings.walker.motion]\nswing_step_scale = 0.9\n").unwrap();
    assert_eq!(config.settings.walker.motion.swing_step_scale, 0.9);
    let config = ConfigFile::parse_toml("[settings.walker]\noffset_in_gait = false\n").unwrap();
    let mut expected = Settings::default().walker;
    expected.offset_in_gait = false;
    assert_eq!(config.settings.walker, expected);
    let (ok, out, err) = check("[settings.walker]\noffset_in_gait = false\n");
    assert!(ok, "{err}");
    assert_eq!(out.trim(), "ok");
    let config =
        ConfigFile::parse_toml("[settings.walker]\noffset_target = \"reference\"\n").unwrap();
    assert_eq!(
        config.settings.walker.offset_target,
        steplearn::control::OffsetTarget::Reference
    );
    let (ok, _, err) = check("[settings.walker]\noffset_target = \"elsewhere\"\n");
    assert!(!ok);
    assert!(
        err.contains("offset_target") || err.contains("elsewhere"),
        "{err}"
    );
}

#[test]
fn printed_defaults_round_trip_through_check_and_parse_to_the_defaults() {
    let o = steplearn(&["config"]);
    assert!(o.status.success());
    let text = String::from_utf8(o.stdout).unwrap();
    for section in [
        "[settings]",
        "[settings.sim]",
        "[settings.sim.body.torso]",
        "[[settings.sim.body.joints]]",
        "[settings.walker.capture_step]",
        "[settings.walker.estimator]",
        "[settings.walker.motion]",
        "[settings.learner.prior]",
        "[protocols.tracking]",
        "[protocols.disturbance]",
        "[protocols.stability]",
        "[protocols.robustness]",
        "[protocols.omnidirectional]",
    ] {
        assert!(text.lines().any(|l| l == section), "{section} missing");
    }
    let parsed = ConfigFile::parse_toml(&text).unwrap();
    assert_eq!(parsed.settings, Settings::default());
    let p = &parsed.protocols;
    assert_eq!(
        p.get::<TrackingProtocol>("tracking"),
        Ok(TrackingProtocol::default())
    );
    assert_eq!(
        p.get::<DisturbanceProtocol>("disturbance"),
        Ok(DisturbanceProtocol::default())
    );
    assert_eq!(
        p.get::<StabilityProtocol>("stability"),
        Ok(StabilityProtocol::default())
    );
    assert_eq!(
        p.get::<RobustnessProtocol>("robustness"),
        Ok(RobustnessProtocol::default())
    );
    let defaults = ConfigFile::default().resolved_for(&steplearn::experiments::builtin());
    assert_eq!(Ok(parsed), defaults);
    let (ok, out, err) = check(&text);
    assert!(ok, "{err}");
    assert_eq!(out.trim(), "ok");
    // An empty file is the defaults as well.
    assert_eq!(ConfigFile::parse_toml("").unwrap(), ConfigFile::default());
}

#[test]
fn the_shipped_configs_pass_the_check() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/configs/mismatch.toml");
    let o = steplearn(&["config", "--check", path]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(String::from_utf8_lossy(&o.stdout).trim(), "ok");
    let config = ConfigFile::load(Path::new(path)).unwrap();
    assert_eq!(config.settings.walker.motion.swing_step_scale, 0.85);

    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/configs/compliant_hip.toml");
    let o = steplearn(&["config", "--check", path]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let config = ConfigFile::load(Path::new(path)).unwrap();
    // only the hip pitch stiffness differs from the default robot
    let default = steplearn::sim::SimConfig::default();
    let mut joints = default.body.joints;
    joints[2].stiffness = 400.0;
    assert_eq!(config.settings.sim.body.joints, joints);
    assert_eq!(
        steplearn::sim::SimConfig {
            body: steplearn::sim::BodyConfig {
                joints: default.body.joints,
                ..config.settings.sim.body.clone()
            },
            ..config.settings.sim.clone()
        },
        default
    );

    // The compensated mismatch: the default robot with the step range cut to 85%.
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/configs/mismatch_compensated.toml"
    );
    let o = steplearn(&["config", "--check", path]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let config = ConfigFile::load(Path::new(path)).unwrap();
    let mismatch = ConfigFile::load(Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/configs/mismatch.toml"
    )))
    .unwrap();
    let motion = config.settings.walker.motion;
    let scale = mismatch.settings.walker.motion.swing_step_scale;
    let range = steplearn::control::motion::MotionConfig::default().step_x_range;
    for (cut, full) in motion.step_x_range.iter().zip(range) {
        assert!((cut - scale * full).abs() < 1e-12);
    }
    assert_eq!(motion.swing_step_scale, 1.0);

    // The offset in the reference: the defaults but for where dF enters; with the mismatch,
    // the mismatch robot but for the same.
    use steplearn::control::OffsetTarget;
    for (file, base) in [
        ("offset_in_reference.toml", ConfigFile::default()),
        ("mismatch_offset_in_reference.toml", mismatch),
    ] {
        let path = format!("{}/configs/{file}", env!("CARGO_MANIFEST_DIR"));
        let o = steplearn(&["config", "--check", &path]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let mut config = ConfigFile::load(Path::new(&path)).unwrap();
        assert_eq!(
            config.settings.walker.offset_target,
            OffsetTarget::Reference
        );
        config.settings.walker.offset_target = OffsetTarget::Footstep;
        assert_eq!(config, base, "{file}");
    }

    // The improved setup: the defaults but for the swing, the landing, the step range and
    // the dead zone (the lateral learner's kept at 0).
    use steplearn::control::motion::Swing;
    let path = format!("{}/configs/improved.toml", env!("CARGO_MANIFEST_DIR"));
    let o = steplearn(&["config", "--check", &path]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut config = ConfigFile::load(Path::new(&path)).unwrap();
    let default = ConfigFile::default();
    let motion = &mut config.settings.walker.motion;
    assert_eq!(
        (
            motion.swing,
            motion.early_landing_phase,
            motion.step_x_range
        ),
        (Swing::Tracking, 0.5, [-0.45, 0.45])
    );
    let m = default.settings.walker.motion;
    (
        motion.swing,
        motion.early_landing_phase,
        motion.step_x_range,
    ) = (m.swing, m.early_landing_phase, m.step_x_range);
    let learner = &mut config.settings.learner;
    assert_eq!(
        (learner.dead_zone, learner.step_y.dead_zone),
        (0.06, Some(0.0))
    );
    learner.dead_zone = default.settings.learner.dead_zone;
    learner.step_y = default.settings.learner.step_y;
    assert_eq!(config, default, "improved.toml");

    // The step time learned sideways, and in both planes: the defaults but for the step time's
    // plane and dead zone.
    use steplearn::control::Planes;
    for (file, planes) in [
        ("frontal_step_time", Planes::Frontal),
        ("both_planes_step_time", Planes::Both),
    ] {
        let path = format!("{}/configs/{file}.toml", env!("CARGO_MANIFEST_DIR"));
        let o = steplearn(&["config", "--check", &path]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let mut config = ConfigFile::load(Path::new(&path)).unwrap();
        let time = &mut config.settings.learner.step_time;
        assert_eq!((time.plane, time.dead_zone), (Some(planes), Some(0.0)));
        *time = Default::default();
        assert_eq!(config, ConfigFile::default(), "{file}");
    }

    // The sole's pitch on its heel alone: the defaults but for the learned set and the pitch's
    // range and dead zone.
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/configs/heel_pitch.toml");
    let o = steplearn(&["config", "--check", path]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut config = ConfigFile::load(Path::new(path)).unwrap();
    let learner = &mut config.settings.learner;
    assert_eq!(learner.learn.to_string(), "step-x,step-time,ankle-pitch");
    let pitch = learner.offset(steplearn::control::StepParameter::AnklePitch);
    assert_eq!(pitch.bounds(), [-0.3, 0.0]);
    assert_eq!(pitch.dead_zone, 0.02);
    learner.learn = Default::default();
    learner.ankle_pitch = Default::default();
    assert_eq!(config, ConfigFile::default());
}

#[test]
fn json_configs_are_as_strict() {
    let dir = tempfile::tempdir().unwrap();
    let bad = write(
        dir.path(),
        "c.json",
        r#"{"settings": {"robot": {"dt": 0.5}}}"#,
    );
    let o = steplearn(&["config", "--check", bad.to_str().unwrap()]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown field `robot`"));
    let good = write(
        dir.path(),
        "d.json",
        r#"{"settings": {"sim": {"body": {"torso": {"mass": 11.5}}}}}"#,
    );
    let config = ConfigFile::load(&good).unwrap();
    assert_eq!(config.settings.sim.body.torso.mass, 11.5);
    assert_eq!(
        config.settings.sim.body.torso.length,
        BodyConfig::default().torso.length
    );
}

#[test]
fn malformed_files_and_missing_files_are_errors() {
    let (ok, _, err) = check("[settings\nx = 1\n");
    assert!(!ok);
    assert!(err.contains("unclosed table"), "{err}");
    let o = steplearn(&["config", "--check", "/nonexistent-steplearn.toml"]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("cannot read"));
}

/// Values beyond what a run can do in bounded memory and time: each is refused by
/// `config --check` and by the run itself, with a message naming the key, before anything
/// runs (never a panic, an abort or a hang).
#[test]
fn hostile_values_are_refused_before_anything_runs() {
    let huge = u64::MAX;
    let cases = [
        (
            format!("[protocols.stability]\npushes = {}\n", i64::MAX),
            "protocols.stability.pushes",
        ),
        (
            "[protocols.tracking]\nbin_s = 1e-300\n".to_string(),
            "protocols.tracking.bin_s",
        ),
        (
            "[protocols.tracking]\nduration_s = 1e300\n".to_string(),
            "protocols.tracking.duration_s",
        ),
        (
            "[protocols.stability]\ngap_s = [1e300, 1e300]\n".to_string(),
            "protocols.stability.gap_s",
        ),
        (
            "[protocols.stability]\nimpulse = [0.0, 1e300]\n".to_string(),
            "protocols.stability.impulse",
        ),
        (
            "[protocols.disturbance]\nimpulse = 1e300\n".to_string(),
            "protocols.disturbance.impulse",
        ),
        (
            "[protocols.robustness]\nimpulse = 1e300\n".to_string(),
            "protocols.robustness.impulse",
        ),
        (
            "[protocols.robustness.map]\nresolution = [100000000, 100000000]\n".to_string(),
            "unknown field `map`",
        ),
        (
            "[protocols.robustness.metric_grid]\npoints = [100000000, 1, 1]\n".to_string(),
            "unknown field `metric_grid`",
        ),
        (
            format!(
                "[settings.learner]\nmax_samples_per_step = {}\n",
                1u64 << 40
            ),
            "max_samples_per_step",
        ),
        (
            "[settings.learner.prior]\nsamples = 1000000000000000\n".to_string(),
            "prior.samples",
        ),
    ];
    let dir = tempfile::tempdir().unwrap();
    for (text, key) in &cases {
        let (ok, _, err) = check(text);
        assert!(!ok, "{text:?} accepted by config --check");
        assert!(err.contains(key), "{text:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        let e = ConfigFile::parse_toml(text).unwrap_err();
        assert!(e.to_string().contains(key), "{text:?}: {e}");
        // The run agrees with the check and leaves nothing behind.
        let config = write(dir.path(), "hostile.toml", text);
        let out = dir.path().join("out");
        let o = stability_with(&config, &out);
        assert!(!o.status.success(), "{text:?} ran");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains(key) && !err.contains("panicked"),
            "{text:?}: {err}"
        );
        assert!(!out.exists(), "{text:?} wrote {}", out.display());
    }
    // Command-line counts beyond the limits.
    for args in [
        vec!["reproduce", "--seeds", &huge.to_string()],
        vec!["sweep", "--seeds", &huge.to_string()],
        vec!["bench", "--seeds", &huge.to_string()],
        vec!["experiment", "stability", "--pushes", &huge.to_string()],
    ] {
        let mut args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        args.extend(["--out".into(), dir.path().join("cli").display().to_string()]);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = steplearn(&args);
        assert!(!o.status.success(), "{args:?} ran");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(
            err.contains("seeds") || err.contains("pushes"),
            "{args:?}: {err}"
        );
        assert!(!dir.path().join("cli").join("summary.json").exists());
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]

    /// Any value of any numeric protocol key: refused with a message naming the key, or
    /// accepted only within the documented limits (so that a run is bounded); never a panic.
    #[test]
    fn extreme_protocol_values_are_refused_or_bounded(
        key in proptest::sample::select(vec![
            ("stability", "pushes"), ("disturbance", "pushes"), ("robustness", "pushes"),
            ("tracking", "bin_s"), ("tracking", "duration_s"), ("tracking", "horizon_s"),
            ("disturbance", "impulse"), ("robustness", "impulse"), ("disturbance", "bin_s"),
            ("disturbance", "horizon_s"), ("disturbance", "tolerance_m"), ("disturbance", "f_r"),
            ("disturbance", "touch_down_share"),
        ]),
        value in proptest::sample::select(vec![
            "0", "1", "-1", "1e-300", "1e300", "nan", "inf", "-inf", "9223372036854775807",
            "0.5", "4.0", "10001", "1e-3", "600.5",
        ]),
    ) {
        let (section, name) = key;
        let text = format!("[protocols.{section}]\n{name} = {value}\n");
        let result = std::panic::catch_unwind(|| ConfigFile::parse_toml(&text));
        let parsed = result.expect("validation never panics");
        match parsed {
            Err(e) => proptest::prop_assert!(e.field.starts_with(&format!("protocols.{section}")), "{text}: {e}"),
            Ok(c) => {
                let t = c.protocols.table(section).unwrap();
                let v = t[name].as_float().or(t[name].as_integer().map(|i| i as f64)).unwrap();
                proptest::prop_assert!(v.is_finite() && v.abs() <= 86_400.0, "{text} accepted");
            }
        }
    }
}
