//! `steplearn replay`: the replay is true to the run, its page round-trips and is
//! self-contained, bad input is a typed error, and the page plays in a real browser.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;
use steplearn::bench::Registry;
use steplearn::replay::{Replay, ReplayError, embedded_replay, page, record, record_span};

const PUSHES: usize = 3;

/// A short run of `experiment` with `pushes` pushes, made with the real command.
fn make_run(experiment: &str, seed: u64, pushes: usize) -> (tempfile::TempDir, PathBuf) {
    let (seed, pushes) = (seed.to_string(), pushes.to_string());
    run_experiment(&[experiment, "--seed", &seed, "--pushes", &pushes], None)
}

/// `steplearn experiment ARGS [--config FILE] --out DIR` in a fresh temporary directory, the
/// config's text (if any) written to FILE there; the run must succeed.
fn run_experiment(args: &[&str], config: Option<&str>) -> (tempfile::TempDir, PathBuf) {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let mut command = Command::new(env!("CARGO_BIN_EXE_steplearn"));
    command.arg("experiment").args(args);
    if let Some(text) = config {
        let file = tmp.path().join("config.toml");
        std::fs::write(&file, text).unwrap();
        command.arg("--config").arg(file);
    }
    let o = command.arg("--out").arg(&dir).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (tmp, dir)
}

/// A short robustness run (3 pushes), made once.
fn run_dir() -> &'static Path {
    static DIR: OnceLock<(tempfile::TempDir, PathBuf)> = OnceLock::new();
    &DIR.get_or_init(|| make_run("robustness", 1, PUSHES)).1
}

/// A short stability run (4 pushes per controller), made once.
fn stability_dir() -> &'static Path {
    static DIR: OnceLock<(tempfile::TempDir, PathBuf)> = OnceLock::new();
    &DIR.get_or_init(|| make_run("stability", 2, 4)).1
}

/// A short disturbance run (3 pushes), made once.
fn disturbance_dir() -> &'static Path {
    static DIR: OnceLock<(tempfile::TempDir, PathBuf)> = OnceLock::new();
    &DIR.get_or_init(|| make_run("disturbance", 1, 3)).1
}

/// A short tracking run (scale 0.05: 32 s per walker), made once.
fn tracking_dir() -> &'static Path {
    static DIR: OnceLock<(tempfile::TempDir, PathBuf)> = OnceLock::new();
    &DIR.get_or_init(|| {
        run_experiment(
            &["tracking", "--seed", "3"],
            Some("[settings]\nscale = 0.05\n"),
        )
    })
    .1
}

/// One logged push: (time, impulse, fell).
type LoggedPush = (f64, f64, bool);

/// The pushes of `controller` in a pushes table (controller, time_s, impulse_ns, fell, ...).
fn logged_pushes_of(path: &Path, controller: &str) -> Vec<LoggedPush> {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.starts_with("controller,time_s,impulse_ns,fell,"));
    text.lines()
        .skip(1)
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|c| c[0] == controller)
        .map(|c| {
            (
                c[1].parse().unwrap(),
                c[2].parse().unwrap(),
                c[3].parse().unwrap(),
            )
        })
        .collect()
}

/// The touch-down times of `controller` in the steps table `path` within `[from, to]`.
fn logged_step_times(path: &Path, controller: &str, from: f64, to: f64) -> Vec<f64> {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.starts_with("controller,time_s,"));
    text.lines()
        .skip(1)
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|c| c[0] == controller)
        .map(|c| c[1].parse::<f64>().unwrap())
        .filter(|&t| t >= from - 1e-9 && t <= to + 1e-9)
        .collect()
}

/// Every touch-down the walk recorded is one the run logged for its walker in `table`, and
/// every one logged within the walk's frames was recorded.
fn assert_steps_as_logged(walk: &steplearn::replay::Walk, table: &Path) {
    let all = logged_step_times(table, &walk.name, f64::NEG_INFINITY, f64::INFINITY);
    let near = |t: f64, list: &[f64]| list.iter().any(|u| (t - u).abs() < 1e-3);
    let replayed: Vec<f64> = walk.steps.iter().map(|s| s.t).collect();
    assert!(!replayed.is_empty(), "{}", walk.name);
    for &t in &replayed {
        assert!(near(t, &all), "{}: no logged touch-down at {t}", walk.name);
    }
    let (from, to) = (walk.frames[0].t, walk.frames.last().unwrap().t);
    for t in logged_step_times(table, &walk.name, from, to) {
        assert!(
            near(t, &replayed),
            "{}: touch-down at {t} not replayed",
            walk.name
        );
    }
}

/// Each walk of `r` delivered push K when, with the impulse and outcome, its controller's row
/// of the run's table logged it; its fall (if any) is drawn; it was recorded around the push.
fn assert_push_as_logged(r: &steplearn::replay::Replay, table: &Path, names: &[(&str, &str)]) {
    for &(walk_name, controller) in names {
        let walk = r.walks.iter().find(|w| w.name == walk_name).unwrap();
        let logged = logged_pushes_of(table, controller);
        let (time, impulse, fell) = logged[r.push - 1];
        let at = walk.push_time.expect("the push was delivered");
        assert!(
            (at - time).abs() < 1e-3,
            "{walk_name} push {}: replayed at {at}, logged at {time}",
            r.push
        );
        assert!((r.impulse - impulse).abs() < 1e-3);
        assert_eq!(walk.fell, fell, "{walk_name} push {}", r.push);
        assert_eq!(
            walk.fall_time.is_some(),
            fell,
            "{walk_name} push {}",
            r.push
        );
        let frames = &walk.frames;
        assert!(!frames.is_empty());
        assert!(frames[0].t >= at - 1.0 - 1e-6 && frames[0].t <= at - 0.9);
        assert!(frames.windows(2).all(|w| w[0].t < w[1].t));
    }
}

/// The replay of the second push of C (seed 2, two pushes) with the walker learning `learn`
/// under `config`.
fn second_push_of_a_short_run(learn: &str, config: &str) -> Replay {
    let (_tmp, dir) = run_experiment(
        &[
            "stability",
            "--seed",
            "2",
            "--pushes",
            "2",
            "--learn",
            learn,
        ],
        Some(config),
    );
    record(&Registry::builtin(), &dir, 2).unwrap()
}

/// A replay of a walker that learns the sole's pitch and roll shows their offsets (`d_a`,
/// `d_r`) as the run applied them, and the model's frames leave them out.
#[test]
fn a_replay_of_a_learned_sole_shows_its_pitch_and_roll_offsets() {
    let r = second_push_of_a_short_run(
        "step-x,ankle-pitch,ankle-roll",
        "[settings.learner.ankle-pitch]\ndead_zone = 0.0\n\
         [settings.learner.ankle-roll]\ndead_zone = 0.0\n",
    );
    let learned = r.walks.iter().find(|w| w.name == "learned").unwrap();
    let model = r.walks.iter().find(|w| w.name == "model").unwrap();
    let moved = |f: fn(&steplearn::replay::Frame) -> f64| {
        learned.frames.iter().filter(|fr| f(fr) != 0.0).count()
    };
    assert!(moved(|f| f.d_a) > 10 && moved(|f| f.d_r) > 10);
    let limit = steplearn::control::motion::ANKLE_LIMIT;
    assert!(
        learned
            .frames
            .iter()
            .all(|f| f.d_a.abs() <= limit && f.d_r.abs() <= limit)
    );
    assert!(model.frames.iter().all(|f| f.d_a == 0.0 && f.d_r == 0.0));
    let json = serde_json::to_string(&model.frames[0]).unwrap();
    assert!(!json.contains("d_a") && !json.contains("d_r"), "{json}");
    // The page's timeline draws them.
    let html = page(&r).unwrap();
    assert!(html.contains("sole roll dR"));
}

/// A sole pitch learned on its heel alone (`offset_range = [-0.3, 0]`) is applied on the
/// humanoid, and never presses the toe, pushes included.
#[test]
fn a_sole_pitch_learned_on_its_heel_alone_never_presses_the_toe() {
    let r = second_push_of_a_short_run(
        "step-x,ankle-pitch",
        "[settings.learner.ankle-pitch]\ndead_zone = 0.0\noffset_range = [-0.3, 0.0]\n",
    );
    let learned = r.walks.iter().find(|w| w.name == "learned").unwrap();
    let heel = learned.frames.iter().filter(|f| f.d_a < 0.0).count();
    assert!(heel > 10, "{heel} frames with the heel pressed");
    assert!(learned.frames.iter().all(|f| f.d_a <= 0.0));
}

#[test]
fn a_stability_replay_ends_each_push_as_the_run_logged_it() {
    let dir = stability_dir();
    let registry = Registry::builtin();
    let table = dir.join("pushes.csv");
    let pushes = logged_pushes_of(&table, "learned").len();
    assert_eq!(pushes, 4);
    for k in 1..=pushes {
        let r = record(&registry, dir, k).unwrap();
        let names: Vec<&str> = r.walks.iter().map(|w| w.name.as_str()).collect();
        assert_eq!(names, ["learned", "model", "open-loop"]);
        assert_push_as_logged(
            &r,
            &table,
            &[
                ("learned", "learned"),
                ("model", "model"),
                ("open-loop", "open-loop"),
            ],
        );
    }
    assert!(matches!(
        record(&registry, dir, pushes + 1),
        Err(ReplayError::PushOutOfRange { pushes: 4, .. })
    ));
}

#[test]
fn a_disturbance_replay_ends_each_push_as_the_run_logged_it() {
    let dir = disturbance_dir();
    let registry = Registry::builtin();
    let table = dir.join("disturbance_pushes.csv");
    let pushes = logged_pushes_of(&table, "learned").len();
    assert_eq!(pushes, 3);
    for k in 1..=pushes {
        let r = record(&registry, dir, k).unwrap();
        assert_push_as_logged(&r, &table, &[("learned", "learned"), ("model", "model")]);
        for walk in &r.walks {
            assert_steps_as_logged(walk, &dir.join("disturbance_steps.csv"));
        }
    }
}

/// The rows of `robustness_pushes.csv`: (fell, falls, no_learning_fell, no_learning_falls).
fn logged_pushes(dir: &Path) -> Vec<(bool, usize, bool, usize)> {
    let text = std::fs::read_to_string(dir.join("robustness_pushes.csv")).unwrap();
    text.lines()
        .skip(1)
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            (
                c[2].parse().unwrap(),
                c[3].parse().unwrap(),
                c[5].parse().unwrap(),
                c[6].parse().unwrap(),
            )
        })
        .collect()
}

/// Touch-downs per push in `robustness_steps.csv`.
fn logged_steps(dir: &Path, push: usize) -> usize {
    let text = std::fs::read_to_string(dir.join("robustness_steps.csv")).unwrap();
    text.lines()
        .skip(1)
        .filter(|l| l.split(',').next() == Some(&push.to_string()))
        .count()
}

#[test]
fn the_replay_ends_each_push_as_the_run_logged_it() {
    let dir = run_dir();
    let logged = logged_pushes(dir);
    assert_eq!(logged.len(), PUSHES);
    let registry = Registry::builtin();
    for (k, &(fell, falls, base_fell, base_falls)) in logged.iter().enumerate() {
        let r = record(&registry, dir, k + 1).unwrap();
        let [learned, base] = &r.walks[..] else {
            panic!("two walkers expected")
        };
        assert_eq!(
            (learned.fell, learned.falls),
            (fell, falls),
            "push {}",
            k + 1
        );
        assert_eq!((base.fell, base.falls), (base_fell, base_falls));
        assert_eq!(learned.trial_steps, logged_steps(dir, k + 1));
        // a fall is drawn only where there was one, and the push's fall is drawn
        if falls == 0 {
            assert!(learned.fall_time.is_none());
        }
        if fell && falls == 1 {
            assert!(learned.fall_time.is_some());
        }
        assert!(!learned.frames.is_empty() && !base.frames.is_empty());
        assert!(learned.push_time.is_some());
    }
}

#[test]
fn a_tracking_span_has_the_steps_and_reference_the_run_logged() {
    let dir = tracking_dir();
    let registry = Registry::builtin();
    let (from, to) = (12.0, 18.5);
    let r = record_span(&registry, dir, from, to).unwrap();
    assert_eq!(r.span, Some([from, to]));
    assert_eq!(r.push, 0);
    let names: Vec<&str> = r.walks.iter().map(|w| w.name.as_str()).collect();
    assert_eq!(names, ["learned", "model"]);
    let steps = dir.join("tracking_steps.csv");
    for walk in &r.walks {
        assert!(walk.push_time.is_none());
        let frames = &walk.frames;
        assert!((frames[0].t - from).abs() < 0.03, "{}", frames[0].t);
        if walk.fall_time.is_none() {
            assert!(frames.last().unwrap().t > to - 0.03);
        }
        assert_steps_as_logged(walk, &steps);
        assert!(walk.steps.len() >= 5, "{:?}", walk.steps);
        // the learned offset dF at each touch-down is the one the run logged
        if walk.name == "learned" {
            assert!(walk.frames.iter().any(|f| f.d_f != 0.0));
        }
    }
    // the reference F_R over the span, as `tracking_steps.csv` logged it at its steps
    let text = std::fs::read_to_string(&steps).unwrap();
    for l in text.lines().skip(1) {
        let c: Vec<&str> = l.split(',').collect();
        let (t, f_r): (f64, f64) = (c[1].parse().unwrap(), c[2].parse().unwrap());
        if t >= from && t <= to {
            let at = r.changes.iter().rev().find(|ch| ch[0] <= t).unwrap()[1];
            assert!((at - f_r).abs() < 1e-3, "F_R at {t}: {at} vs {f_r}");
        }
    }
    assert_eq!(r.changes[0][0], from);
    // and the page round-trips
    assert_eq!(embedded_replay(&page(&r).unwrap()).unwrap(), r);
}

#[test]
fn bad_spans_are_typed_errors() {
    let registry = Registry::builtin();
    let dir = tracking_dir();
    for (from, to) in [
        (5.0, 5.0),
        (6.0, 5.0),
        (-1.0, 2.0),
        (f64::NAN, 2.0),
        (1.0, f64::INFINITY),
    ] {
        assert!(
            matches!(
                record_span(&registry, dir, from, to),
                Err(ReplayError::BadSpan { .. })
            ),
            "{from}..{to}"
        );
    }
    assert!(matches!(
        record_span(&registry, dir, 10.0, 1000.0),
        Err(ReplayError::SpanOutOfRange { length, .. }) if (length - 32.0).abs() < 1e-9
    ));
    assert!(matches!(
        record(&registry, dir, 1),
        Err(ReplayError::NoPushes(e)) if e == "tracking"
    ));
    assert!(matches!(
        record_span(&registry, run_dir(), 1.0, 2.0),
        Err(ReplayError::NoSpan(e)) if e == "robustness"
    ));
}

#[test]
fn the_command_refuses_bad_moments() {
    let dir = tracking_dir();
    let out = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_steplearn"))
            .arg("replay")
            .arg(dir)
            .args(args)
            .arg("--out")
            .arg(out.path().join("x.html"))
            .output()
            .unwrap();
        (
            o.status.success(),
            String::from_utf8_lossy(&o.stderr).into_owned(),
        )
    };
    for (args, says) in [
        (
            &["--push", "1", "--time", "1..2"][..],
            "cannot be used with",
        ),
        (&[][..], "--push"),
        (&["--time", "5..3"][..], "the start must be before the end"),
        (&["--time=-1..3"][..], "the start must be >= 0"),
        (&["--time", "NaN..3"][..], "finite"),
        (&["--time", "3-5"][..], "expected A..B"),
        (&["--time", "1..1000"][..], "after the run's trial"),
        (&["--push", "1"][..], "has no pushes"),
    ] {
        let (ok, err) = run(args);
        assert!(!ok, "{args:?}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
    assert!(!out.path().join("x.html").exists());
    let (ok, err) = run(&["--time", "2..3.5"]);
    assert!(ok, "{err}");
    let html = std::fs::read_to_string(out.path().join("x.html")).unwrap();
    assert_eq!(embedded_replay(&html).unwrap().span, Some([2.0, 3.5]));
}

/// The `href="..."` values of a page.
fn hrefs(html: &str) -> Vec<String> {
    html.split("href=\"")
        .skip(1)
        .map(|s| s[..s.find('"').unwrap()].to_string())
        .collect()
}

#[test]
fn the_reproduce_page_links_a_replay_of_each_experiment_beside_it() {
    let tmp = tempfile::tempdir().unwrap();
    let config = tmp.path().join("tiny.toml");
    std::fs::write(
        &config,
        "[settings]\nscale = 0.02\n[protocols.stability]\npushes = 10\n\
         [protocols.robustness]\npushes = 10\n",
    )
    .unwrap();
    let out = tmp.path().join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_steplearn"))
        .args(["reproduce", "--seeds", "1", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let index = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(index.len() < 2_000_000, "{} bytes", index.len());
    let links: Vec<String> = hrefs(&index)
        .into_iter()
        .filter(|h| h.starts_with("replay-"))
        .collect();
    let experiments = ["tracking", "disturbance", "stability", "robustness"];
    assert_eq!(
        links,
        experiments.map(|e| format!("replay-{e}.html")),
        "in the paper's order"
    );
    for (link, experiment) in links.iter().zip(experiments) {
        let file = out.join(link);
        assert!(file.is_file(), "{link}");
        let r = embedded_replay(&std::fs::read_to_string(&file).unwrap()).unwrap();
        assert_eq!(r.experiment, experiment);
        assert!(r.walks.len() >= 2 && r.walks.iter().all(|w| !w.frames.is_empty()));
        assert_eq!(r.span.is_some(), experiment == "tracking");
    }
    // each link sits after its experiment's figures across seeds, before the next one's
    let at = |s: &str| index.find(s).unwrap_or_else(|| panic!("{s}"));
    assert!(at("replay-tracking.html") < at("disturbance_by_step_over_seeds.svg"));
    assert!(at("replay-disturbance.html") > at("disturbance_by_step_over_seeds.svg"));
    assert!(at("replay-stability.html") > at("stability_fall_probability_over_seeds.svg"));
    assert!(at("replay-robustness.html") > at("robustness_absorbed_over_seeds.svg"));
}

#[test]
fn the_bench_page_links_a_replay_of_its_best_and_its_worst_row_beside_it() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("bench");
    let o = Command::new(env!("CARGO_BIN_EXE_steplearn"))
        .args([
            "bench",
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
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let index = std::fs::read_to_string(out.join("index.html")).unwrap();
    let links: Vec<String> = hrefs(&index)
        .into_iter()
        .filter(|h| h.starts_with("replay-"))
        .collect();
    assert_eq!(links, ["replay-best.html", "replay-worst.html"]);
    // one row: the best row's first seed and the worst row's last seed
    for (link, seed) in links.iter().zip([0, 1]) {
        let file = out.join(link);
        assert!(file.is_file(), "{link}");
        let r = embedded_replay(&std::fs::read_to_string(&file).unwrap()).unwrap();
        assert_eq!(r.experiment, "stability");
        assert_eq!(r.seed, seed);
        assert!(r.walks.len() >= 2 && r.walks.iter().all(|w| !w.frames.is_empty()));
    }
}

#[test]
fn the_page_holds_exactly_the_recorded_frames_and_nothing_external() {
    let dir = run_dir();
    let r = record(&Registry::builtin(), dir, 2).unwrap();
    let html = page(&r).unwrap();
    assert_eq!(embedded_replay(&html).unwrap(), r);
    assert!(html.len() < 3_000_000, "{} bytes", html.len());
    // No fetched resource. three.js names the XHTML namespace (a name, never fetched).
    let scrubbed = html.replace("\"http://www.w3.org/1999/xhtml\"", "");
    for external in [
        "http://", "https://", "<link", " src=", "href=", "url(", "@import",
    ] {
        assert!(!scrubbed.contains(external), "{external} in the page");
    }
    assert!(html.contains("three.js 0.170.0"));
    assert!(html.contains("The MIT License"));
}

#[test]
fn bad_input_is_a_typed_error() {
    let registry = Registry::builtin();
    let dir = run_dir();
    let missing = tempfile::tempdir().unwrap();
    assert!(matches!(
        record(&registry, &missing.path().join("nope"), 1),
        Err(ReplayError::MissingRun(_))
    ));
    for push in [0, PUSHES + 1] {
        assert!(matches!(
            record(&registry, dir, push),
            Err(ReplayError::PushOutOfRange { pushes: PUSHES, .. })
        ));
    }
    // corrupt and foreign run configurations
    let other = tempfile::tempdir().unwrap();
    let config = other.path().join("run-config.toml");
    std::fs::write(&config, "format = [").unwrap();
    assert!(matches!(
        record(&registry, other.path(), 1),
        Err(ReplayError::Corrupt { .. })
    ));
    let text = std::fs::read_to_string(dir.join("run-config.toml")).unwrap();
    std::fs::write(
        &config,
        text.replace(
            "experiment = \"robustness\"",
            "experiment = \"omnidirectional\"",
        ),
    )
    .unwrap();
    assert!(matches!(
        record(&registry, other.path(), 1),
        Err(ReplayError::Unsupported(e)) if e == "omnidirectional"
    ));
    // a run of another results format is not reproduced by this binary
    assert!(text.contains("format = 1\n"));
    std::fs::write(&config, text.replace("format = 1\n", "format = 0\n")).unwrap();
    assert!(matches!(
        record(&registry, other.path(), 1),
        Err(ReplayError::NotReproducible(_))
    ));
}

#[test]
fn the_command_writes_the_page() {
    let dir = run_dir();
    let out = tempfile::tempdir().unwrap();
    let file = out.path().join("replay.html");
    let o = Command::new(env!("CARGO_BIN_EXE_steplearn"))
        .arg("replay")
        .arg(dir)
        .args(["--push", "2", "--out"])
        .arg(&file)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let html = std::fs::read_to_string(&file).unwrap();
    assert_eq!(embedded_replay(&html).unwrap().push, 2);
    let o = Command::new(env!("CARGO_BIN_EXE_steplearn"))
        .arg("replay")
        .arg(dir)
        .args(["--push", "99", "--out"])
        .arg(out.path().join("x.html"))
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("out of range"));
}

/// The value of `name="..."` in the DOM's `<body ...>` tag.
fn body_attr(dom: &str, name: &str) -> Option<String> {
    let body = &dom[dom.find("<body")?..];
    let body = &body[..body.find('>')?];
    let key = format!("{name}=\"");
    let start = body.find(&key)? + key.len();
    Some(body[start..start + body[start..].find('"')?].to_string())
}

#[test]
fn the_page_draws_and_plays_in_a_real_browser() {
    let Some(browser) = crate::browser::chromium() else {
        return;
    };
    let r = record(&Registry::builtin(), run_dir(), 2).unwrap();
    let out = tempfile::tempdir().unwrap();
    let file = out.path().join("replay.html");
    std::fs::write(&file, page(&r).unwrap()).unwrap();
    let o = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--use-gl=swiftshader",
            "--enable-unsafe-swiftshader",
            "--disable-background-networking",
            "--enable-logging=stderr",
            "--window-size=1200,900",
            "--virtual-time-budget=3000",
            "--dump-dom",
        ])
        .arg(format!("file://{}", file.display()))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let dom = String::from_utf8_lossy(&o.stdout);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!stderr.contains("Uncaught"), "console errors:\n{stderr}");
    assert!(
        dom.contains("<pre id=\"errors\"></pre>"),
        "the page reported errors: {dom}"
    );
    let number = |name: &str| -> f64 {
        body_attr(&dom, name)
            .unwrap_or_else(|| panic!("no {name} on body"))
            .parse()
            .unwrap()
    };
    assert!(number("data-frames-drawn") >= 2.0, "not animating");
    // coloured pixels (bodies, markers) in the first picture: the walkers were drawn
    assert!(number("data-nonblank") > 1000.0, "blank scene");
    // playback moves: a drawn moment differs from the first (the last one alone may have
    // looped back to the start under a slow browser)
    assert!(number("data-moved") > 0.0, "playback did not move");
}
