//! `steplearn replay`: the replay is true to the run, its page round-trips and is
//! self-contained, bad input is a typed error, and the page plays in a real browser.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;
use steplearn::bench::Registry;
use steplearn::replay::{ReplayError, embedded_replay, page, record};

const PUSHES: usize = 3;

/// A short robustness run (3 pushes), made once with the real command.
fn run_dir() -> &'static Path {
    static DIR: OnceLock<(tempfile::TempDir, PathBuf)> = OnceLock::new();
    &DIR.get_or_init(|| {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("run");
        let o = Command::new(env!("CARGO_BIN_EXE_steplearn"))
            .args(["experiment", "robustness", "--seed", "1", "--pushes"])
            .arg(PUSHES.to_string())
            .arg("--out")
            .arg(&dir)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        (tmp, dir)
    })
    .1
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
        text.replace("experiment = \"robustness\"", "experiment = \"tracking\""),
    )
    .unwrap();
    assert!(matches!(
        record(&registry, other.path(), 1),
        Err(ReplayError::Unsupported(e)) if e == "tracking"
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
    // playback moves
    assert!(number("data-last-time") > number("data-first-time"));
}
