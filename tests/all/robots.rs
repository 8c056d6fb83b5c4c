//! Robots from URDF files: the built-in humanoid exported and loaded back is the same robot,
//! bit for bit; the shipped robots (igus-like, Talos as its makers ship it, a stranger written
//! by someone else) load and walk in place; every hostile file is refused naming its element.

use std::path::{Path, PathBuf};
use std::process::Command;

use steplearn::control::WalkerMode;
use steplearn::experiments::protocol::ProtocolTables;
use steplearn::experiments::robot_setup::{robot_report, use_robot};
use steplearn::experiments::schedule::ReferenceSchedule;
use steplearn::experiments::settings::Settings;
use steplearn::experiments::trial::{TrialLog, run_trial};
use steplearn::robot::Description;
use steplearn::robot::ServoReference;
use steplearn::sim::BodyConfig;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Talos's URDF from the example-robot-data wheel, installed by the project's script.
fn talos() -> PathBuf {
    let out = Command::new("bash")
        .arg(root().join("scripts/install-robots.sh"))
        .output()
        .expect("bash");
    assert!(
        out.status.success(),
        "scripts/install-robots.sh failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let path = String::from_utf8_lossy(&out.stdout)
        .lines()
        .last()
        .expect("a path")
        .to_string();
    PathBuf::from(path)
}

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("steplearn-robots-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn the_exported_humanoid_loads_as_the_same_description() {
    let body = BodyConfig::default();
    let builtin = body.description();
    let text = builtin.to_urdf();
    let loaded =
        Description::from_urdf_str(&text, Path::new("."), &body.servo_reference()).unwrap();
    // Everything but the drawn stick figure, which a URDF does not carry, bit for bit.
    assert_eq!(loaded.trunk, builtin.trunk);
    assert_eq!(loaded.legs, builtin.legs);
    assert_eq!(loaded.name, builtin.name);
    assert!(loaded.held_joints.is_empty());
    // The lean default reference agrees with the body's to within rounding.
    let lean = ServoReference::default();
    let exact = body.servo_reference();
    assert_eq!(lean.servos, exact.servos);
    assert_eq!(lean.limits, exact.limits);
    assert!(
        (lean.mass - exact.mass).abs() < 1e-12
            && (lean.leg_length - exact.leg_length).abs() < 1e-12
    );
}

/// Walks `path` with the Capture Step walker for `seconds`, undisturbed, at the reference step
/// `paper_f_r` of the paper's robot scaled to it; the log and the scaled reference.
fn walk_undisturbed(path: &Path, paper_f_r: f64, seconds: f64) -> (TrialLog, f64) {
    let mut settings = Settings::default();
    let mut protocols = ProtocolTables::new();
    let run = use_robot(path, None, &mut settings, &mut protocols).unwrap();
    let f_r = run.scale.length(paper_f_r);
    let setup = settings.trial(
        WalkerMode::CaptureStep,
        ReferenceSchedule::constant(f_r),
        Vec::new(),
        [1.0, 0.0, 0.0],
        seconds,
    );
    (run_trial(&setup, None, &mut []).unwrap(), f_r)
}

/// Walks `path` in place for 60 s with the Capture Step walker, undisturbed; the falls.
fn falls_in_place(path: &Path) -> usize {
    let (log, _) = walk_undisturbed(path, 0.0, 60.0);
    assert!(log.sim_time_s >= 59.9, "{}", log.sim_time_s);
    assert!(log.steps.len() > 100, "{} steps", log.steps.len());
    log.falls.len()
}

#[test]
fn the_igus_like_robot_walks_in_place_for_60_s() {
    assert_eq!(falls_in_place(&root().join("robots/igus_like.urdf")), 0);
}

/// The model's mean realised step over the last 20 of 30 s walking undisturbed at experiment
/// B's reference step (the paper robot's 0.2 m, scaled), as a share of that reference.
fn realised_share_of_b_reference(path: &Path) -> f64 {
    let (log, f_r) = walk_undisturbed(path, 0.2, 30.0);
    assert!(log.falls.is_empty(), "{} falls", log.falls.len());
    let late: Vec<f64> = log
        .steps
        .iter()
        .filter(|s| s.time > 10.0)
        .map(|s| s.f_hat)
        .collect();
    late.iter().sum::<f64>() / late.len() as f64 / f_r
}

/// The walker's reference point on each sole lies where the stance centre of mass puts it on
/// the paper's robot, scaled (`Scale::sole_shift_x`): on the igus-like robot, whose stance
/// centre of mass lies far behind its soles' centres, the model steps about a third of its
/// reference without it.
#[test]
fn the_igus_like_model_realises_its_reference_step() {
    let share = realised_share_of_b_reference(&root().join("robots/igus_like.urdf"));
    assert!((0.8..1.2).contains(&share), "{share}");
}

#[test]
fn talos_as_shipped_walks_in_place_for_60_s() {
    assert_eq!(falls_in_place(&talos()), 0);
}

#[test]
fn a_strangers_robot_walks_in_place_for_60_s() {
    assert_eq!(
        falls_in_place(&root().join("tests/robots/stranger.urdf")),
        0
    );
}

/// Romeo's full URDF from the same wheel: COLLADA collision meshes (its soles among them),
/// `package://` paths, mimic joints in its hands.
fn romeo() -> PathBuf {
    let robots = talos()
        .ancestors()
        .nth(3)
        .expect("the wheel's robots")
        .to_path_buf();
    robots.join("romeo_description/urdf/romeo.urdf")
}

#[test]
fn romeo_as_shipped_walks_in_place_for_60_s() {
    let r = robot_report(&romeo(), None).unwrap();
    assert_eq!(r.legs.left.joints[3], "LKneePitch");
    assert_eq!(r.legs.right.foot, "r_ankle");
    // The sole from the bounds of the foot's COLLADA mesh.
    let g = &r.leg_geometry;
    assert!(
        g.foot_length > 0.2 && g.foot_length < 0.3,
        "{}",
        g.foot_length
    );
    assert!(
        g.foot_width > 0.1 && g.foot_width < 0.15,
        "{}",
        g.foot_width
    );
    assert_eq!(falls_in_place(&romeo()), 0);
}

#[test]
fn package_paths_resolve_from_a_relative_urdf_path() {
    // Named from its own directory, the URDF's meshes still resolve through the
    // directories above it.
    let urdf = romeo();
    let out = Command::new(env!("CARGO_BIN_EXE_steplearn"))
        .current_dir(urdf.parent().unwrap())
        .args(["robot", "show", "romeo.urdf"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_held_links_unphysical_inertia_is_remarked_and_a_leg_links_refused() {
    let dir = temp("held-inertia");
    let text = std::fs::read_to_string(root().join("tests/robots/stranger.urdf")).unwrap();
    let forearm =
        r#"<inertia ixx="0.0026" ixy="0.0" ixz="0.0" iyy="0.0026" iyz="0.0" izz="0.00036"/>"#;
    assert_eq!(text.matches(forearm).count(), 2, "both forearms");
    let broken =
        r#"<inertia ixx="0.0026" ixy="0.0" ixz="0.0" iyy="0.0002" iyz="0.0" izz="0.00036"/>"#;
    // The left forearm (held in the trunk): loaded, with a remark naming it.
    let held = dir.join("held.urdf");
    std::fs::write(&held, text.replacen(forearm, broken, 1)).unwrap();
    let r = robot_report(&held, None).unwrap();
    assert_eq!(r.remarks.len(), 1, "{:?}", r.remarks);
    assert!(r.remarks[0].contains("link 'LForearm'") && r.remarks[0].contains("triangle"));
    let show = cli(&["robot", "show", held.to_str().unwrap()]);
    assert!(String::from_utf8_lossy(&show.stdout).contains("remark: link 'LForearm'"));
    assert!(
        robot_report(&root().join("tests/robots/stranger.urdf"), None)
            .unwrap()
            .remarks
            .is_empty()
    );
    // The same inertia on a leg link, which is simulated as its own body: refused.
    let shank_start = text.find(r#"<link name="LShank">"#).unwrap();
    let shank_end = shank_start + text[shank_start..].find("</link>").unwrap();
    let shank = &text[shank_start..shank_end];
    let inertia_start = shank.find("<inertia ").unwrap();
    let inertia_end = inertia_start + shank[inertia_start..].find("/>").unwrap() + 2;
    let bad_shank = shank.replace(
        &shank[inertia_start..inertia_end],
        r#"<inertia ixx="0.05" ixy="0.0" ixz="0.0" iyy="0.001" iyz="0.0" izz="0.001"/>"#,
    );
    let leg = dir.join("leg.urdf");
    std::fs::write(&leg, text.replacen(shank, &bad_shank, 1)).unwrap();
    let e = robot_report(&leg, None).unwrap_err().to_string();
    assert!(e.contains("link 'LShank'") && e.contains("triangle"), "{e}");
}

#[test]
fn a_robot_rooted_above_its_waist_holds_the_waist_and_walks() {
    // The stranger with its chest as the root link: the waist joint turned around, so both
    // legs hang from the pelvis below it.
    let text = std::fs::read_to_string(root().join("tests/robots/stranger.urdf")).unwrap();
    let waist = r#"<origin rpy="0 0 0" xyz="0 0 0.08"/>
    <axis xyz="0 0 1"/>
    <parent link="Pelvis"/>
    <child link="Chest"/>"#;
    assert!(text.contains(waist));
    let turned = r#"<origin rpy="0 0 0" xyz="0 0 -0.08"/>
    <axis xyz="0 0 1"/>
    <parent link="Chest"/>
    <child link="Pelvis"/>"#;
    let dir = temp("waist");
    let urdf = dir.join("chest_root.urdf");
    std::fs::write(&urdf, text.replace(waist, turned)).unwrap();
    let r = robot_report(&urdf, None).unwrap();
    let original = robot_report(&root().join("tests/robots/stranger.urdf"), None).unwrap();
    assert_eq!(r.legs.left.joints, original.legs.left.joints);
    assert_eq!(r.legs.right.joints, original.legs.right.joints);
    assert!(
        r.held_joints.iter().any(|j| j == "WaistYaw"),
        "{:?}",
        r.held_joints
    );
    assert_eq!(r.held_joints.len(), original.held_joints.len());
    assert!((r.mass_kg - original.mass_kg).abs() < 1e-9);
    assert!((r.com_height_m - original.com_height_m).abs() < 1e-9);
    assert_eq!(falls_in_place(&urdf), 0);
}

#[test]
fn robot_show_describes_talos_with_its_legs_and_held_joints() {
    let r = robot_report(&talos(), None).unwrap();
    assert_eq!(r.name, "talos");
    assert!((r.mass_kg - 90.27).abs() < 0.01, "{}", r.mass_kg);
    let names: Vec<String> = (1..=6).map(|k| format!("leg_left_{k}_joint")).collect();
    assert_eq!(r.legs.left.joints.to_vec(), names);
    assert_eq!(r.legs.right.joints[3], "leg_right_4_joint");
    assert!(r.held_joints.iter().any(|j| j == "torso_1_joint"));
    assert!(r.held_joints.iter().any(|j| j == "arm_right_7_joint"));
    assert!(!r.held_joints.iter().any(|j| j.starts_with("leg_")));
    // C = sqrt(g/h) of its own centre-of-mass height, calibrated as the paper robot's.
    assert!(
        r.com_height_m > 0.85 && r.com_height_m < 1.0,
        "{}",
        r.com_height_m
    );
    let own = (9.81 / r.com_height_m).sqrt();
    assert!(
        (r.c / own - 1.0).abs() < 0.05,
        "C {} against sqrt(g/h) {own}",
        r.c
    );
}

fn cli(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_steplearn"))
        .args(args)
        .output()
        .expect("steplearn runs")
}

#[test]
fn robot_show_json_has_the_binding_fields() {
    let out = cli(&["robot", "show", "robots/igus_like.urdf", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "name",
        "mass_kg",
        "com_height_m",
        "c",
        "held_joints",
        "leg_geometry",
        "gait",
    ] {
        assert!(v.get(key).is_some(), "{key} missing in {v}");
    }
    let left = v["legs"]["left"]["joints"].as_array().unwrap();
    assert_eq!(left.len(), 6);
    assert_eq!(left[3], "l_knee");
    assert_eq!(v["legs"]["right"]["joints"][0], "r_hip_yaw");
    assert!((v["mass_kg"].as_f64().unwrap() - 6.465).abs() < 0.01);
}

/// Every hostile file, and the element its refusal must name.
const HOSTILE: &[(&str, &str)] = &[
    ("malformed", "79:"),
    ("missing_joint", "l_foot"),
    ("extra_joint", "l_shank_twist"),
    ("knee_about_x", "l_knee"),
    ("locked_knee", "l_knee"),
    ("equal_limits", "r_hip_roll"),
    ("one_leg", "Right"),
    ("negative_mass", "l_shank"),
    ("zero_mass", "r_thigh"),
    ("triangle_inertia", "trunk"),
    ("knee_bends_forward", "l_knee"),
    ("nan", "l_hip_pitch"),
    ("inf", "r_foot"),
    ("mimic_leg", "r_knee"),
    ("missing_mesh", "package://nowhere/foot.stl"),
    ("dangling_parent", "head"),
    ("cycle", "l_shank"),
    ("com_outside_feet", "trunk"),
];

#[test]
fn every_hostile_robot_is_refused_naming_its_element() {
    let dir = root().join("tests/robots/hostile");
    let out_dir = temp("hostile");
    for (file, element) in HOSTILE {
        let path = dir.join(format!("{file}.urdf"));
        let p = path.to_str().unwrap();
        let show = cli(&["robot", "show", p]);
        let err = String::from_utf8_lossy(&show.stderr);
        assert!(!show.status.success(), "{file} was accepted");
        assert!(err.contains(element), "{file}: {err}");
        assert!(!err.contains("panicked"), "{file}: {err}");
        let out = out_dir.join(file);
        let run = cli(&[
            "experiment",
            "stability",
            "--robot",
            p,
            "--pushes",
            "1",
            "--out",
            out.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success(), "{file}: experiment ran");
        assert!(err.contains(element), "{file}: {err}");
        assert!(
            !out.join("summary.json").exists(),
            "{file}: a summary was written"
        );
    }
    // Each defect is a copy of this valid robot, which loads.
    assert!(
        cli(&["robot", "show", "tests/robots/minimal.urdf"])
            .status
            .success()
    );
}

#[test]
fn a_leg_in_another_joint_order_is_refused_with_its_axes_and_the_supported_chain() {
    // The knee of this copy of the minimal robot turns about x: the message names the axis
    // every joint of that leg turns about, so a robot with another hip order (pitch first, as
    // many ship) sees at once what differs from the supported chain.
    let path = root().join("tests/robots/hostile/knee_about_x.urdf");
    let show = cli(&["robot", "show", path.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&show.stderr);
    assert!(!show.status.success());
    assert!(
        err.contains("the leg's joints turn about z, x, y, x, y, x;"),
        "{err}"
    );
    assert!(err.contains("turns about z, x, y, y, y, x"), "{err}");
}

#[test]
fn a_changed_robot_file_is_never_answered_with_old_results() {
    let dir = temp("changed");
    let urdf = dir.join("robot.urdf");
    std::fs::copy(root().join("tests/robots/minimal.urdf"), &urdf).unwrap();
    let out = dir.join("run");
    let args = |u: &Path, o: &Path| {
        vec![
            "experiment".to_string(),
            "stability".into(),
            "--robot".into(),
            u.display().to_string(),
            "--pushes".into(),
            "1".into(),
            "--out".into(),
            o.display().to_string(),
        ]
    };
    let run = |a: Vec<String>| {
        Command::new(env!("CARGO_BIN_EXE_steplearn"))
            .args(a)
            .output()
            .unwrap()
    };
    let first = run(args(&urdf, &out));
    assert!(
        first.status.success(),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("\"sha256\""));
    // The identity names the version of the rules that carry the settings to the robot, so
    // a change of them is never answered with a run made under the old ones.
    let identity = std::fs::read_to_string(out.join("run-config.toml")).unwrap();
    let rules = format!("robot_rules = {}\n", steplearn::bench::ROBOT_RULES);
    assert!(identity.contains(&rules), "{identity}");
    // The same file reuses the run; a changed one is a different run, refused in the same
    // directory without --overwrite.
    let text = std::fs::read_to_string(&urdf)
        .unwrap()
        .replace("mass value=\"4", "mass value=\"4.1");
    std::fs::write(&urdf, text).unwrap();
    let second = run(args(&urdf, &out));
    assert!(
        !second.status.success(),
        "a changed robot reused the old run"
    );
    assert_eq!(
        std::fs::read_to_string(out.join("summary.json")).unwrap(),
        summary
    );
}

#[test]
fn a_robot_inside_the_working_directory_is_named_relative_to_it() {
    // The same file named by its absolute path and by its path relative to the working
    // directory is the same run: the second command reuses the first's.
    let dir = temp("relative");
    std::fs::copy(
        root().join("tests/robots/minimal.urdf"),
        dir.join("robot.urdf"),
    )
    .unwrap();
    let run = |robot: &Path| {
        Command::new(env!("CARGO_BIN_EXE_steplearn"))
            .current_dir(&dir)
            .args([
                "experiment",
                "stability",
                "--pushes",
                "1",
                "--out",
                "run",
                "--robot",
            ])
            .arg(robot)
            .output()
            .unwrap()
    };
    let first = run(&dir.join("robot.urdf"));
    assert!(
        first.status.success(),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    let config = std::fs::read_to_string(dir.join("run/run-config.toml")).unwrap();
    assert!(
        config.contains("path = \"robot.urdf\""),
        "the absolute path was stored: {config}"
    );
    let second = run(Path::new("robot.urdf"));
    let stderr = String::from_utf8_lossy(&second.stderr);
    assert!(second.status.success(), "{stderr}");
    assert_eq!(
        std::fs::read_to_string(dir.join("run/run-config.toml")).unwrap(),
        config
    );
    assert!(stderr.contains("finished earlier: reused"), "{stderr}");
}

#[test]
fn the_shipped_paper_robot_file_is_the_builtin_export() {
    let shipped = std::fs::read_to_string(root().join("robots/steplearn_humanoid.urdf")).unwrap();
    assert_eq!(shipped, BodyConfig::default().description().to_urdf());
}

#[test]
fn a_replay_draws_the_robots_own_links() {
    use steplearn::replay::Recorder;
    let mut settings = Settings::default();
    let mut protocols = ProtocolTables::new();
    use_robot(&talos(), None, &mut settings, &mut protocols).unwrap();
    let setup = settings.trial(
        WalkerMode::CaptureStep,
        ReferenceSchedule::constant(0.0),
        Vec::new(),
        [1.0, 0.0, 0.0],
        1.0,
    );
    let mut recorder = Recorder::new(0.0, 1.0, 0.1).for_sim(&setup.sim);
    run_trial(&setup, None, &mut [&mut recorder]).unwrap();
    let walk = recorder.finish("talos");
    // The trunk and every leg link drawn (Talos's links have meshes: boxes of their inertia).
    assert_eq!(walk.bodies.len(), 13);
    assert!(walk.bodies.iter().all(|b| !b.is_empty()));
    let frame = &walk.frames[3];
    assert_eq!(frame.links.len(), 13);
    // The trunk frame sits about a leg length above the ground.
    assert!(
        frame.links[0][2] > 0.8 && frame.links[0][2] < 1.2,
        "{:?}",
        frame.links[0]
    );
}

#[test]
fn the_exported_humanoid_gives_the_built_in_summaries_bit_for_bit() {
    let dir = temp("exported");
    let urdf = dir.join("humanoid.urdf");
    assert!(
        cli(&["robot", "export", "--out", urdf.to_str().unwrap()])
            .status
            .success()
    );
    let run = |robot: Option<&Path>, out: &Path| {
        let mut args = vec!["experiment", "stability", "--pushes", "3", "--seed", "4"];
        let o = out.to_str().unwrap().to_string();
        args.extend(["--out", &o]);
        let r = robot.map(|p| p.to_str().unwrap().to_string());
        if let Some(r) = &r {
            args.extend(["--robot", r]);
        }
        let res = cli(&args);
        assert!(
            res.status.success(),
            "{}",
            String::from_utf8_lossy(&res.stderr)
        );
        std::fs::read(out.join("summary.json")).unwrap()
    };
    let built_in = run(None, &dir.join("built-in"));
    let exported = run(Some(&urdf), &dir.join("exported"));
    assert!(
        built_in == exported,
        "the exported humanoid's summary differs"
    );
}

#[test]
fn a_bench_over_two_robots_gives_each_its_directory_and_a_column() {
    use steplearn::bench::{Bench, BenchError, Registry};
    use steplearn::experiments::sweep::RunStatus;
    let dir = temp("bench-robots");
    let registry = Registry::builtin();
    let (minimal, igus) = (
        root().join("tests/robots/minimal.urdf"),
        root().join("robots/igus_like.urdf"),
    );
    let bench = |robots: &[&Path], out: &Path| {
        Bench::new(&registry)
            .approximators(["lwpr"])
            .rules(["pendulum-cart"])
            .experiments(["stability"])
            .seeds(2)
            .scale(0.03)
            .robots(robots)
            .out(out)
    };
    let both = bench(&[&minimal, &igus], &dir.join("both")).run().unwrap();
    let robots = both.robots.as_ref().expect("a bench over robots");
    let ids: Vec<&str> = robots.robots.iter().map(|r| r.id.as_str()).collect();
    assert_eq!(ids, ["minimal", "igus_like"]);
    assert_ne!(robots.robots[0].sha256, robots.robots[1].sha256);
    // Each robot's rows are the leaderboard a bench on that robot alone writes.
    let alone = bench(&[&igus], &dir.join("alone")).run().unwrap();
    assert!(alone.robots.is_none());
    let mine: Vec<_> = both
        .leaderboard
        .rows
        .iter()
        .filter(|r| r.robot.as_deref() == Some("igus_like"))
        .cloned()
        .map(|mut r| {
            r.robot = None;
            r
        })
        .collect();
    assert_eq!(mine, alone.leaderboard.rows);
    assert!(!mine.is_empty());
    assert!(dir.join("both/minimal/leaderboard.json").exists());
    assert!(dir.join("both/igus_like/index.html").exists());
    // One column per robot in the Markdown; the JSON names every row's robot.
    let md = std::fs::read_to_string(dir.join("both/leaderboard.md")).unwrap();
    assert!(
        md.contains("| approx | rule | learn | minimal | igus_like |"),
        "{md}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("both/leaderboard.json")).unwrap())
            .unwrap();
    let rows = json["leaderboard"]["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0]["robot"], "minimal");
    assert_eq!(rows[1]["robot"], "igus_like");
    // Run again: every run is reused.
    let again = bench(&[&minimal, &igus], &dir.join("both")).run().unwrap();
    assert!(
        again
            .outcomes
            .iter()
            .all(|o| o.status == RunStatus::Skipped)
    );
    assert_eq!(again.leaderboard, both.leaderboard);
    // The command line takes the robots separated by commas, and reuses the same runs.
    let robots_arg = format!("{},{}", minimal.display(), igus.display());
    let out_arg = dir.join("both").display().to_string();
    let listed = cli(&[
        "bench",
        "--robot",
        &robots_arg,
        "--approx",
        "lwpr",
        "--rule",
        "pendulum-cart",
        "--experiments",
        "stability",
        "--seeds",
        "2",
        "--scale",
        "0.03",
        "--out",
        &out_arg,
    ]);
    let stdout = String::from_utf8_lossy(&listed.stdout);
    assert!(
        listed.status.success(),
        "{}",
        String::from_utf8_lossy(&listed.stderr)
    );
    assert!(
        stdout.contains("| approx | rule | learn | minimal | igus_like |"),
        "{stdout}"
    );
    assert!(stdout.contains("4 runs (4 finished earlier)"), "{stdout}");
    // Two files of one name, and a hostile robot, are refused before any run.
    let copy = dir.join("copy");
    std::fs::create_dir_all(&copy).unwrap();
    std::fs::copy(&igus, copy.join("igus_like.urdf")).unwrap();
    let twice = bench(&[&igus, &copy.join("igus_like.urdf")], &dir.join("twice")).run();
    assert!(matches!(twice, Err(BenchError::Selection(_))), "{twice:?}");
    let hostile = root().join("tests/robots/hostile/one_leg.urdf");
    let refused = bench(&[&igus, &hostile], &dir.join("hostile")).run();
    assert!(
        matches!(refused, Err(BenchError::Robot { .. })),
        "{refused:?}"
    );
    assert!(!dir.join("twice").exists() && !dir.join("hostile").exists());
}

#[test]
fn feet_named_where_a_lower_leaf_is_not_the_foot() {
    // A toe on the left foot, on a joint of its own and lower than the foot's frame: the
    // lowest leaf on that side is the toe, so the leg would have seven joints.
    let dir = temp("feet");
    let toe = r#"  <joint name="l_toe_joint" type="revolute">
    <parent link="l_foot"/>
    <child link="l_toe"/>
    <origin xyz="0.06 0 -0.05" rpy="0 0 0"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="5"/>
  </joint>
  <link name="l_toe">
    <inertial>
      <origin xyz="0 0 0" rpy="0 0 0"/>
      <mass value="0.05"/>
      <inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="1e-5"/>
    </inertial>
  </link>
</robot>"#;
    let text = std::fs::read_to_string(root().join("tests/robots/minimal.urdf"))
        .unwrap()
        .replace("</robot>", toe);
    let urdf = dir.join("toe.urdf");
    std::fs::write(&urdf, text).unwrap();
    let u = urdf.to_str().unwrap();
    let guessed = cli(&["robot", "show", u]);
    assert!(!guessed.status.success());
    let why = String::from_utf8_lossy(&guessed.stderr);
    assert!(why.contains("l_toe"), "{why}");
    let named = cli(&["robot", "show", u, "--feet", "l_foot,r_foot", "--json"]);
    assert!(
        named.status.success(),
        "{}",
        String::from_utf8_lossy(&named.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&named.stdout).unwrap();
    assert_eq!(json["legs"]["left"]["foot"], "l_foot");
    assert_eq!(json["legs"]["left"]["joints"][5], "l_ankle_roll");
    assert!(
        json["held_joints"]
            .as_array()
            .unwrap()
            .iter()
            .any(|j| j == "l_toe_joint"),
        "{json}"
    );
    // A link that is not there, or feet on the wrong sides, are refused naming the link.
    for (feet, names) in [("l_heel,r_foot", "l_heel"), ("r_foot,l_foot", "r_foot")] {
        let refused = cli(&["robot", "show", u, "--feet", feet]);
        assert!(!refused.status.success());
        let why = String::from_utf8_lossy(&refused.stderr);
        assert!(why.contains(names), "{feet}: {why}");
    }
    // An experiment walks on it, with the feet recorded in the run's settings.
    let out = dir.join("run");
    let run = cli(&[
        "experiment",
        "stability",
        "--robot",
        u,
        "--feet",
        "l_foot,r_foot",
        "--pushes",
        "1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let config = std::fs::read_to_string(out.join("run-config.toml")).unwrap();
    assert!(config.contains("left = \"l_foot\""), "{config}");
    let lonely = cli(&["experiment", "stability", "--feet", "l_foot,r_foot"]);
    assert!(!lonely.status.success());
    // A bench over it and another robot: its feet named with it, one column each.
    use steplearn::bench::{Bench, Registry};
    use steplearn::robot::Feet;
    let registry = Registry::builtin();
    let bench = || {
        Bench::new(&registry)
            .approximators(["lwpr"])
            .rules(["pendulum-cart"])
            .experiments(["stability"])
            .seeds(1)
            .scale(0.03)
            .robots([root().join("tests/robots/minimal.urdf")])
            .out(dir.join("bench"))
    };
    let guessed = bench().robot(&urdf, None).run().unwrap_err().to_string();
    assert!(guessed.contains("l_toe"), "{guessed}");
    let feet = Feet {
        left: "l_foot".into(),
        right: "r_foot".into(),
    };
    let report = bench().robot(&urdf, Some(feet)).run().unwrap();
    let ids: Vec<&str> = report
        .robots
        .as_ref()
        .expect("a bench over robots")
        .robots
        .iter()
        .map(|r| r.id.as_str())
        .collect();
    assert_eq!(ids, ["minimal", "toe"]);
    let config = std::fs::read_to_string(
        dir.join("bench/toe/stability__lwpr__pendulum-cart__s0/run-config.toml"),
    )
    .unwrap();
    assert!(config.contains("left = \"l_foot\""), "{config}");
}
