//! The `steplearn` command: a short real run, and bad arguments rejected with a message.

use std::process::Command;

fn steplearn(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_steplearn"))
        .args(args)
        .output()
        .expect("the binary runs")
}

#[test]
fn stability_run_writes_summary_and_figures() {
    let dir = std::env::temp_dir().join(format!("steplearn-cli-{}", std::process::id()));
    let out = dir.to_str().unwrap();
    let o = steplearn(&[
        "experiment",
        "stability",
        "--pushes",
        "3",
        "--seed",
        "4",
        "--out",
        out,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["experiment"], "stability");
    assert_eq!(summary["approx"], "lwpr");
    assert_eq!(summary["rule"], "pendulum-cart");
    assert_eq!(summary["seed"], 4);
    for c in ["open_loop", "model", "learned"] {
        assert_eq!(summary["controllers"][c]["pushes"], 3, "{c}");
        assert!(summary["controllers"][c]["impulse_at_50pct_fall_ns"].is_number());
    }
    assert!(dir.join("fall_probability.svg").exists() && dir.join("pushes.csv").exists());
    // index.html: the figure inlined, the summary, the command and the configuration
    let page = std::fs::read_to_string(dir.join("index.html")).unwrap();
    assert_eq!(page.matches("<svg").count(), 1);
    assert!(page.contains("Experiment C (paper Fig. 6): fall probability against push impulse"));
    assert!(page.contains("&quot;experiment&quot;: &quot;stability&quot;"));
    assert!(page.contains("experiment stability --pushes 3 --seed 4"));
    assert!(page.contains("[protocols.stability]"));

    assert!(dir.join("run-config.toml").exists());

    // The same run again is reused, not run; another run into the directory is refused and
    // leaves every file of the finished run as it was.
    let files = |d: &std::path::Path| {
        let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.is_file())
            .map(|p| {
                (
                    p.file_name().unwrap().to_string_lossy().into_owned(),
                    std::fs::read(&p).unwrap(),
                )
            })
            .collect();
        v.sort();
        v
    };
    let before = files(&dir);
    let same = [
        "experiment",
        "stability",
        "--pushes",
        "3",
        "--seed",
        "4",
        "--out",
        out,
    ];
    let o = steplearn(&same);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("reused"));
    assert_eq!(files(&dir), before);
    for other in [
        vec![
            "experiment",
            "stability",
            "--pushes",
            "3",
            "--seed",
            "5",
            "--out",
            out,
        ],
        vec![
            "experiment",
            "stability",
            "--pushes",
            "2",
            "--seed",
            "4",
            "--out",
            out,
        ],
        vec!["experiment", "disturbance", "--pushes", "1", "--out", out],
    ] {
        let o = steplearn(&other);
        assert!(!o.status.success(), "{other:?} ran over a finished run");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains("--overwrite") && err.contains("another configuration"),
            "{err}"
        );
        assert_eq!(files(&dir), before, "{other:?}");
    }
    // Replacing it takes --overwrite, and leaves no file of the old run behind.
    let o = steplearn(&[
        "experiment",
        "robustness",
        "--pushes",
        "1",
        "--seed",
        "5",
        "--overwrite",
        "--out",
        out,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let now = files(&dir);
    assert!(
        now.iter()
            .all(|(name, _)| !name.contains("fall_probability")),
        "{now:?}"
    );
    let summary = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    assert!(
        summary.contains("\"robustness\"") && summary.contains("\"seed\": 5"),
        "{summary}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_arguments_are_messages_and_failures() {
    let dir = tempfile::tempdir().unwrap();
    let config = |name: &str, text: &str| {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    };
    let malformed = config("malformed.toml", "[settings\nx = 1\n");
    let unknown = config("unknown.toml", "[settings.learner]\nmax_gian = 0.1\n");
    let out_of_range = config("range.toml", "[settings.learner]\nmax_gain = -1.0\n");
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    // Each case and a piece of the message it must give.
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["experiment", "stability", "--approx", "lwrp", "--out", "x"],
            "'lwrp'",
        ),
        (
            vec!["experiment", "stability", "--rule", "nope", "--out", "x"],
            "'nope'",
        ),
        (
            vec![
                "experiment",
                "stability",
                "--impulse-range",
                "5,2",
                "--out",
                "x",
            ],
            "need 0 <= A <= B",
        ),
        (
            vec!["experiment", "stability", "--pushes", "0", "--out", "x"],
            "--pushes must be in [1, 10000], got 0",
        ),
        (
            vec![
                "experiment",
                "stability",
                "--config",
                "/nonexistent.toml",
                "--out",
                "x",
            ],
            "cannot read /nonexistent.toml",
        ),
        (
            vec!["sweep", "--shard", "3/2", "--out", "x"],
            "shard index must be below 2",
        ),
        (
            vec!["merge", "/nonexistent-steplearn-dir"],
            "/nonexistent-steplearn-dir",
        ),
        (vec!["experiment", "walking", "--out", "x"], "'walking'"),
        (
            vec![
                "experiment",
                "disturbance",
                "--impulse-range",
                "5,8",
                "--out",
                "x",
            ],
            "give --impulse-range A,A",
        ),
        (
            vec!["reproduce", "--seeds", "0", "--out", "x"],
            "--seeds must be in [1, 10000], got 0",
        ),
        (
            vec!["reproduce", "--config", "/nonexistent.toml", "--out", "x"],
            "cannot read /nonexistent.toml",
        ),
        (
            vec!["reproduce", "--seeds", "-1"],
            "unexpected argument '-1'",
        ),
        (
            vec![
                "experiment",
                "stability",
                "--pushes",
                "1",
                "--config",
                &malformed,
                "--out",
                out,
            ],
            "unclosed table",
        ),
        (
            vec![
                "experiment",
                "stability",
                "--pushes",
                "1",
                "--config",
                &unknown,
                "--out",
                out,
            ],
            "unknown field `max_gian`",
        ),
        (
            vec![
                "experiment",
                "stability",
                "--pushes",
                "1",
                "--config",
                &out_of_range,
                "--out",
                out,
            ],
            "max_gain must be finite and > 0, got -1",
        ),
    ];
    for (args, message) in cases {
        let o = steplearn(&args);
        assert!(!o.status.success(), "{args:?} succeeded");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("error"), "{args:?}: {err}");
        assert!(
            err.contains(message),
            "{args:?}: expected {message:?} in {err}"
        );
        assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    }
    // None of the failed runs wrote a result.
    assert!(!dir.path().join("out").join("summary.json").exists());
}

/// A config file's push direction holds unless `--push-direction` is given (the flag's
/// absence is not "forward").
#[test]
fn push_direction_comes_from_the_config_unless_the_flag_is_given() {
    let dir = tempfile::tempdir().unwrap();
    let config = dir.path().join("left.toml");
    std::fs::write(
        &config,
        "[protocols.stability]\ndirection = [0.0, 1.0, 0.0]\n",
    )
    .unwrap();
    let config = config.to_str().unwrap();
    for (flag, expected) in [(None, "left push"), (Some("backward"), "backward push")] {
        let out = dir.path().join(expected.replace(' ', "_"));
        let out = out.to_str().unwrap();
        let mut args = vec![
            "experiment",
            "stability",
            "--pushes",
            "1",
            "--config",
            config,
            "--out",
            out,
        ];
        if let Some(f) = flag {
            args.extend(["--push-direction", f]);
        }
        let o = steplearn(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let svg =
            std::fs::read_to_string(dir.path().join(out).join("fall_probability.svg")).unwrap();
        assert!(
            svg.contains(expected),
            "{flag:?}: no {expected:?} in the figure's title"
        );
    }
    // Tracking has no pushes: a direction is an error there, as a push count is.
    let o = steplearn(&[
        "experiment",
        "tracking",
        "--push-direction",
        "left",
        "--out",
        "x",
    ]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("has no pushes"));
}

/// `--push-direction` takes an azimuth in degrees as the omnidirectional experiment's sectors
/// do: 90 is `left` and -90 `right` bit for bit, 45 pushes along the diagonal, and a value that is not a
/// direction is refused before anything is written.
#[test]
fn push_direction_takes_an_azimuth_in_degrees() {
    let dir = tempfile::tempdir().unwrap();
    let run = |flag: &str, name: &str| {
        let out = dir.path().join(name);
        let o = steplearn(&[
            "experiment",
            "stability",
            "--pushes",
            "1",
            "--push-direction",
            flag,
            "--out",
            out.to_str().unwrap(),
        ]);
        (o, out)
    };
    let read = |out: &std::path::Path, f: &str| std::fs::read_to_string(out.join(f)).unwrap();
    let (o, left) = run("left", "left");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (o, ninety) = run("90", "ninety");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (o, right) = run("right", "right");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (o, minus_ninety) = run("-90", "minus_ninety");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in ["summary.json", "run-config.toml"] {
        assert_eq!(read(&left, f), read(&ninety, f), "{f}");
        assert_eq!(read(&right, f), read(&minus_ninety, f), "{f}");
    }
    let (o, diagonal) = run("45", "diagonal");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let config: toml::Table = read(&diagonal, "run-config.toml").parse().unwrap();
    let d: Vec<f64> = config["protocol"]["direction"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_float().unwrap())
        .collect();
    let h = std::f64::consts::FRAC_1_SQRT_2;
    assert!(
        (d[0] - h).abs() < 1e-12 && (d[1] - h).abs() < 1e-12 && d[2] == 0.0,
        "{d:?}"
    );
    for bad in ["400", "-360.5", "north", "NaN", "inf", ""] {
        let (o, out) = run(bad, "bad");
        assert!(!o.status.success(), "{bad:?} was accepted");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("azimuth in degrees"), "{bad:?}: {err}");
        assert!(!out.exists(), "{bad:?} wrote {}", out.display());
    }
}

/// `merge` on a directory without finished runs fails and writes no (empty) table; a malformed
/// run is named in plain words.
#[test]
fn merge_without_finished_runs_fails_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let run = dir.path().join("stability__lwpr__pendulum-cart__s0");
    std::fs::create_dir_all(&run).unwrap();
    std::fs::write(run.join("summary.json"), "{bad").unwrap();
    std::fs::create_dir_all(dir.path().join("stability__lwpr__pendulum-cart__s1")).unwrap();
    let o = steplearn(&["merge", dir.path().to_str().unwrap()]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("no finished runs to merge") && err.contains("1 unfinished, 1 unreadable"),
        "{err}"
    );
    assert!(
        err.contains("skipped ") && err.contains("summary.json: malformed"),
        "{err}"
    );
    assert!(!err.contains("MergeProblem"), "{err}");
    assert!(!dir.path().join("ablation.md").exists());
    assert!(!dir.path().join("index.html").exists());
}

/// The main job, shrunk by a config file: every experiment runs once, the claims report is
/// written, and a second call reuses the finished runs and writes the same report.
#[test]
fn reproduce_writes_runs_and_the_claims_report_and_reuses_runs() {
    let dir = std::env::temp_dir().join(format!("steplearn-reproduce-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let config = dir.join("tiny.toml");
    std::fs::write(
        &config,
        "[settings]\nscale = 0.02\n[protocols.stability]\npushes = 10\n\
         [protocols.robustness]\npushes = 10\n",
    )
    .unwrap();
    let out = dir.join("out");
    let args = [
        "reproduce",
        "--seeds",
        "1",
        "--config",
        config.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    let o = steplearn(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    // One lead line per claim, each with both verdicts, in the paper's order.
    let leads: Vec<&str> = stdout.lines().filter(|l| l.starts_with("Claim ")).collect();
    assert_eq!(leads.len(), 4, "{stdout}");
    for (i, l) in leads.iter().enumerate() {
        assert!(l.starts_with(&format!("Claim {}", i + 1)), "{l}");
        assert!(l.contains("strict per seed"), "{l}");
    }
    assert!(stdout.contains("index.html"), "{stdout}");
    // Off a terminal: one progress line per run, with its count, the time elapsed and, until
    // the last, an estimate of the time left.
    let stderr = String::from_utf8_lossy(&o.stderr);
    let lines: Vec<&str> = stderr.lines().filter(|l| l.starts_with('[')).collect();
    assert_eq!(lines.len(), 4, "{stderr}");
    for (k, l) in lines.iter().enumerate() {
        assert!(l.starts_with(&format!("[{}/4] ", k + 1)), "{l}");
        assert!(l.contains("elapsed"), "{l}");
        assert_eq!(l.contains("left)"), k < 3, "{l}");
    }
    for kind in ["tracking", "disturbance", "stability", "robustness"] {
        let summary = out.join(format!("{kind}__lwpr__pendulum-cart__s0/summary.json"));
        assert!(summary.exists(), "{kind}");
    }
    let claims: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("claims.json")).unwrap()).unwrap();
    for c in ["tracking", "disturbance", "stability", "robustness"] {
        assert_eq!(claims[c]["seeds"].as_array().unwrap().len(), 1, "{c}");
        assert!(
            !claims[c]["over_seeds"].as_array().unwrap().is_empty(),
            "{c}"
        );
    }
    // One seed: the comparison over seeds has its value but no interval.
    let i50 = &claims["stability"]["over_seeds"][0];
    assert_eq!(i50["quantity"], "I50 learned / model");
    assert_eq!(i50["values"].as_array().unwrap().len(), 1);
    assert!(i50["verdict"].is_null());
    assert!(
        stdout.contains("over seeds: I50 learned / model: ") && stdout.contains("too few seeds"),
        "{stdout}"
    );
    let report = std::fs::read(out.join("claims.md")).unwrap();
    let summaries: Vec<_> = ["tracking", "disturbance", "stability", "robustness"]
        .iter()
        .map(|k| out.join(format!("{k}__lwpr__pendulum-cart__s0/summary.json")))
        .collect();
    let modified = |p: &std::path::Path| std::fs::metadata(p).unwrap().modified().unwrap();
    let before: Vec<_> = summaries.iter().map(|p| modified(p)).collect();
    let o = steplearn(&args);
    assert!(o.status.success());
    assert_eq!(report, std::fs::read(out.join("claims.md")).unwrap());
    // The finished runs were reused, not run again: their files were not rewritten.
    let after: Vec<_> = summaries.iter().map(|p| modified(p)).collect();
    assert_eq!(before, after);
    // A changed config never yields the old results: the run it changes is refused (its
    // files kept), and the report is not rewritten.
    std::fs::write(
        &config,
        "[settings]\nscale = 0.02\n[protocols.stability]\npushes = 11\n\
         [protocols.robustness]\npushes = 10\n",
    )
    .unwrap();
    let stability = std::fs::read(&summaries[2]).unwrap();
    let o = steplearn(&args);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("stability__lwpr__pendulum-cart__s0"), "{err}");
    assert!(
        err.contains("another configuration") && err.contains("pushes"),
        "{err}"
    );
    assert_eq!(stability, std::fs::read(&summaries[2]).unwrap());
    assert_eq!(report, std::fs::read(out.join("claims.md")).unwrap());
    std::fs::remove_dir_all(&dir).ok();
}

/// `experiment stability` with two pushes on seed 1 into `out`, with `args` besides.
fn two_pushes(out: &std::path::Path, args: &[&str]) -> std::process::Output {
    let out = out.to_str().unwrap();
    let fixed = ["experiment", "stability", "--pushes", "2", "--seed", "1"];
    steplearn(&[&fixed[..], args, &["--out", out]].concat())
}

/// `--learn` sets the learned step parameters: the summary names the set, the run identity
/// records it (another set into the same directory is refused), and a malformed set is refused
/// before anything runs, naming what is wrong.
#[test]
fn learn_names_the_step_parameters_of_a_run() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("xt");
    let run = |learn: &str| two_pushes(&out, &["--learn", learn]);
    let o = run("step-time,step-x");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["learn"], serde_json::json!(["step-x", "step-time"]));
    let identity = std::fs::read_to_string(out.join("run-config.toml")).unwrap();
    assert!(
        identity.contains("learn = [") && identity.contains("\"step-time\""),
        "{identity}"
    );
    // The paper's set is another run: refused in the finished run's directory.
    let o = run("step-x");
    assert!(!o.status.success());
    // Each refusal names what is wrong: the unknown name (an empty one too), or the name
    // given twice.
    for (bad, why) in [
        ("step-z", "unknown step parameter \"step-z\""),
        ("step-x,step-x", "step parameter step-x named twice"),
        ("", "unknown step parameter \"\""),
    ] {
        let o = run(bad);
        assert!(!o.status.success(), "{bad:?} accepted");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(why), "{bad:?}: {err}");
    }
}

/// The sole's pitch and roll are learned like any step parameter: from `--learn`, each with
/// its own table in a config (recorded in the run's identity), and each refused outside its
/// plane by its key.
#[test]
fn the_soles_pitch_and_roll_are_learned_from_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ankle");
    let config = dir.path().join("ankle.toml");
    std::fs::write(
        &config,
        "[settings.learner.ankle-pitch]\nmax_offset = 0.05\n\
         [settings.learner.ankle-roll]\ndead_zone = 0.01\n",
    )
    .unwrap();
    let run = |config: &std::path::Path| {
        two_pushes(
            &out,
            &[
                "--learn",
                "ankle-roll,ankle-pitch,step-x",
                "--config",
                config.to_str().unwrap(),
            ],
        )
    };
    let o = run(&config);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(
        summary["learn"],
        serde_json::json!(["step-x", "ankle-pitch", "ankle-roll"])
    );
    let identity = std::fs::read_to_string(out.join("run-config.toml")).unwrap();
    assert!(
        identity.contains("[settings.learner.ankle-pitch]")
            && identity.contains("max_offset = 0.05")
            && identity.contains("[settings.learner.ankle-roll]")
            && identity.contains("dead_zone = 0.01"),
        "{identity}"
    );
    for (table, plane) in [("ankle-pitch", "frontal"), ("ankle-roll", "sagittal")] {
        std::fs::write(
            &config,
            format!("[settings.learner.{table}]\nplane = \"{plane}\"\n"),
        )
        .unwrap();
        let o = run(&config);
        assert!(!o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(&format!("{table}.plane")), "{err}");
    }
}

/// The step time learned in both planes runs from the shipped config: the run's identity
/// records the planes, and a footstep offset in both planes is refused before anything runs,
/// naming the key.
#[test]
fn the_step_time_in_both_planes_runs_from_its_config() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("both");
    let config = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/configs/both_planes_step_time.toml"
    );
    let run = |config: &str| {
        two_pushes(
            &out,
            &["--learn", "step-x,step-y,step-time", "--config", config],
        )
    };
    let o = run(config);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let identity = std::fs::read_to_string(out.join("run-config.toml")).unwrap();
    assert!(identity.contains("plane = \"both\""), "{identity}");
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "[settings.learner.step-x]\nplane = \"both\"\n").unwrap();
    let o = run(bad.to_str().unwrap());
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("step-x.plane"), "{err}");
}
