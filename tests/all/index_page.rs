//! `index.html`: one self-contained page per result, and that it renders in a real browser.

use std::path::Path;
use std::process::Command;
use steplearn::experiments::disturbance::DisturbanceSummary;
use steplearn::experiments::index_page::{INDEX_FILE, write_index};
use steplearn::experiments::reproduce::Claims;
use steplearn::experiments::robustness::{NoLearning, RobustnessSummary};
use steplearn::experiments::stability::{ControllerFalls, Controllers, StabilitySummary};
use steplearn::experiments::summary::{ModelLearned, Summary, TypedResult};
use steplearn::experiments::sweep::SUMMARY_FILE;
use steplearn::experiments::tracking::TrackingSummary;

const SVG: &str = "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"200\" height=\"100\"><rect x=\"10\" y=\"10\" width=\"80\" height=\"40\" fill=\"rgb(31,119,180)\"/></svg>\n";

/// A result directory like `reproduce` writes: claims, a top-level figure, two runs.
fn result_dir(dir: &Path) {
    std::fs::write(
        dir.join("claims.md"),
        "# Claims\n\n## 3. Impulse at 50% falls\n\n**not reproduced** (1 of 2 seeds)\n\n| seed | holds | measured |\n|---|---|---|\n| 0 | yes | I50 14.1 |\n| 1 | no | I50 12.0 |\n",
    )
    .unwrap();
    std::fs::write(dir.join("tracking_std_over_seeds.svg"), SVG).unwrap();
    for run in [
        "stability__lwpr__pendulum-cart__s0",
        "robustness__lwpr__pendulum-cart__s0",
    ] {
        std::fs::create_dir_all(dir.join(run)).unwrap();
    }
    std::fs::write(
        dir.join("stability__lwpr__pendulum-cart__s0/fall_probability.svg"),
        SVG,
    )
    .unwrap();
    std::fs::write(
        dir.join("robustness__lwpr__pendulum-cart__s0/df_maps.svg"),
        SVG,
    )
    .unwrap();
}

#[test]
fn the_page_holds_every_figure_the_claims_and_the_command_and_nothing_external() {
    let dir = tempfile::tempdir().unwrap();
    result_dir(dir.path());
    write_index(
        dir.path(),
        "steplearn reproduce",
        &["claims.md", "missing.md"],
        "steplearn reproduce --quick --out x",
        Some("[settings]\nscale = 0.1\n"),
    )
    .unwrap();
    let page = std::fs::read_to_string(dir.path().join(INDEX_FILE)).unwrap();
    assert_eq!(page.matches("<svg").count(), 3, "every figure inlined");
    assert!(page.contains("<td>1</td><td>no</td><td>I50 12.0</td>"));
    assert!(page.contains("<strong>not reproduced</strong>"));
    assert!(page.contains("Experiment C (paper Fig. 6): fall probability against push impulse"));
    assert!(page.contains("Experiment D (paper Fig. 8): the learned offset ΔF over (θ_E, θ̇_E)"));
    assert!(page.contains("<h3>stability__lwpr__pendulum-cart__s0</h3>"));
    assert!(page.contains("steplearn reproduce --quick --out x"));
    assert!(page.contains("scale = 0.1"));
    // self-contained: no script, stylesheet link or fetched resource
    for external in ["<script", "<link", "src=", "href=", "url(", "@import"] {
        assert!(!page.contains(external), "{external} in the page");
    }
    // the top-level figure comes before the runs' figures
    let top = page.find("(tracking_std_over_seeds.svg)").unwrap();
    assert!(top < page.find("<h3>robustness").unwrap());
}

/// A reproduction's output directory for seeds `0..seeds` without running physics: each run's
/// `summary.json` and the CSV files the figures across seeds read, plus large per-run figures
/// like the real ones (a 1.3 MB `df_maps.svg`, 250 kB others).
fn reproduction(dir: &Path, seeds: u64) {
    fn run(
        dir: &Path,
        experiment: &str,
        seed: u64,
        result: impl TypedResult,
    ) -> std::path::PathBuf {
        let d = dir.join(format!("{experiment}__lwpr__pendulum-cart__s{seed}"));
        std::fs::create_dir_all(&d).unwrap();
        Summary {
            approx: "lwpr".into(),
            rule: "pendulum-cart".into(),
            seed,
            learn: Default::default(),
            robot: None,
            result: result.into_result().unwrap(),
        }
        .write(&d.join(SUMMARY_FILE))
        .unwrap();
        d
    }
    let big = |bytes: usize| format!("{}<!--{}-->", SVG, "x".repeat(bytes));
    for seed in 0..seeds {
        let s = seed as f64;
        let d = run(
            dir,
            "tracking",
            seed,
            TrackingSummary {
                step_error_std_m: ModelLearned {
                    model: vec![Some(0.05), Some(0.03), Some(0.02)],
                    learned: vec![Some(0.04 + 0.001 * s), Some(0.02), Some(0.01)],
                },
                bin_s: 0.5,
            },
        );
        std::fs::write(d.join("tracking_std.svg"), big(250_000)).unwrap();
        let d = run(
            dir,
            "disturbance",
            seed,
            DisturbanceSummary {
                return_time_s: ModelLearned {
                    model: 3.0 + 0.1 * s,
                    learned: 2.0,
                },
                return_time_by_step_s: None,
                settle_time_s: None,
                step_error_after_push_m: None,
                max_tda_rad: ModelLearned {
                    model: 0.1,
                    learned: 0.12,
                },
                falls: None,
            },
        );
        let mut csv = String::from(
            "controller,touch_down_after_push,mean_step_m,std_step_m,mean_tda_rad,std_tda_rad,steps\n",
        );
        for (c, base) in [("model", 0.30), ("learned", 0.26)] {
            for k in 1..=6 {
                let step = 0.2 + (base - 0.2) / k as f64 + 0.002 * s;
                csv.push_str(&format!("{c},{k},{step:.4},0.01,0.05,0.01,10\n"));
            }
        }
        std::fs::write(d.join("disturbance_by_step.csv"), csv).unwrap();
        std::fs::write(d.join("disturbance_step.svg"), big(250_000)).unwrap();
        let falls = |i50: f64| ControllerFalls {
            pushes: 40,
            falls: 10,
            impulse_at_50pct_fall_ns: i50,
        };
        let d = run(
            dir,
            "stability",
            seed,
            StabilitySummary {
                controllers: Controllers {
                    open_loop: falls(4.0),
                    model: falls(12.0 + s),
                    learned: falls(13.0 + s),
                },
                fall_causes: Default::default(),
                catch_step_reach: None,
            },
        );
        let mut csv = String::from("controller,time_s,impulse_ns,fell,fall_cause\n");
        for (c, i50) in [
            ("open-loop", 4.0),
            ("model", 12.0 + s),
            ("learned", 13.0 + s),
        ] {
            for p in 0..40 {
                let impulse = p as f64 * 0.5;
                csv.push_str(&format!("{c},{p},{impulse:.4},{},\n", impulse > i50));
            }
        }
        std::fs::write(d.join("pushes.csv"), csv).unwrap();
        std::fs::write(d.join("fall_probability.svg"), big(250_000)).unwrap();
        let absorbed: Vec<bool> = (0..6).map(|p| p + (seed as usize % 2) >= 2).collect();
        let d = run(
            dir,
            "robustness",
            seed,
            RobustnessSummary {
                pushes_until_first_absorbed: absorbed.iter().position(|&a| a).map(|i| i as u32 + 1),
                falls: absorbed.iter().filter(|&&a| !a).count() as u32,
                impulse_ns: Some(8.0),
                absorbed_by_push: absorbed.clone(),
                no_learning: Some(NoLearning {
                    absorbed_by_push: vec![false; 6],
                    falls: 6,
                }),
            },
        );
        std::fs::write(d.join("df_maps.svg"), big(1_300_000)).unwrap();
    }
}

/// The page `reproduce` writes for [`reproduction`]: the claims and their figures across
/// seeds, then the index.
fn reproduce_page(dir: &Path, seeds: u64) -> String {
    reproduction(dir, seeds);
    let summaries: Vec<Summary> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path().join(SUMMARY_FILE))
        .filter(|p| p.is_file())
        .map(|p| Summary::read(&p).unwrap())
        .collect();
    let claims = Claims::from_summaries(&summaries, 0.15);
    claims.write(dir, "lwpr", "pendulum-cart").unwrap();
    write_index(
        dir,
        "steplearn reproduce: the paper's claims (lwpr + pendulum-cart)",
        &["claims.md"],
        "steplearn reproduce --quick",
        None,
    )
    .unwrap();
    std::fs::read_to_string(dir.join(INDEX_FILE)).unwrap()
}

/// The text of every `<text>` element of `svg`, trimmed.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let body = &t[t.find('>')? + 1..];
            Some(body[..body.find('<')?].trim().to_string())
        })
        .collect()
}

const OVER_SEEDS: [&str; 4] = [
    "tracking_std_over_seeds.svg",
    "disturbance_by_step_over_seeds.svg",
    "stability_fall_probability_over_seeds.svg",
    "robustness_absorbed_over_seeds.svg",
];

#[test]
fn the_reproduce_page_leads_with_both_verdicts_then_a_to_d_across_seeds_then_per_seed() {
    let dir = tempfile::tempdir().unwrap();
    let page = reproduce_page(dir.path(), 3);
    // One lead line per claim with both verdicts, before anything else.
    let first_section = page.find("<h3>").unwrap();
    for n in 1..=4 {
        let at = page
            .find(&format!("<li>Claim {n}, experiment "))
            .unwrap_or_else(|| panic!("no lead line for claim {n}"));
        assert!(at < first_section);
        let line = &page[at..at + page[at..].find("</li>").unwrap()];
        assert!(line.contains("over seeds"), "{line}");
        assert!(line.contains("95% ["), "{line}");
        assert!(line.contains("strict per seed:"), "{line}");
        assert!(line.contains(" of 3 seeds"), "{line}");
        assert!(line.contains("(paper Fig"), "{line}");
    }
    assert!(!page.contains("*level*"));
    // The figures across seeds, A-D, each with its 95% band and its caption citing the paper.
    let mut last = 0;
    for (name, fig) in OVER_SEEDS
        .iter()
        .zip(["Fig. 4", "Fig. 5", "Fig. 6", "Fig. 7"])
    {
        let svg = std::fs::read_to_string(dir.path().join(name)).unwrap();
        assert!(svg.contains("95% band"), "{name}: no band in the title");
        assert!(svg.contains("<polygon"), "{name}: no band drawn");
        let labels = texts(&svg);
        assert!(
            !labels.iter().any(|l| l == "-0" || l == "-0.0"),
            "{name}: {labels:?}"
        );
        let at = page.find(&format!("({name})")).unwrap();
        assert!(at > last, "{name} out of the paper's order");
        assert!(
            page[..at]
                .rfind("<figcaption>")
                .is_some_and(|c| page[c..at].contains(fig))
        );
        last = at;
    }
    // Counts on the x axis are labelled at integers only.
    let pushes = std::fs::read_to_string(dir.path().join(OVER_SEEDS[3])).unwrap();
    let labels = texts(&pushes);
    assert!(labels.contains(&"2".to_string()), "{labels:?}");
    assert!(!labels.iter().any(|l| l.contains('.')), "{labels:?}");
    // Then the runs, A-D, after every figure across seeds.
    let runs: Vec<usize> = ["tracking", "disturbance", "stability", "robustness"]
        .iter()
        .map(|e| {
            page.find(&format!("<h3>{e}__lwpr__pendulum-cart__s0</h3>"))
                .unwrap()
        })
        .collect();
    assert!(
        runs[0] > last && runs.windows(2).all(|w| w[0] < w[1]),
        "{runs:?}"
    );
}

#[test]
fn the_reproduce_page_stays_under_2_mb_linking_what_does_not_fit() {
    let dir = tempfile::tempdir().unwrap();
    let page = reproduce_page(dir.path(), 5);
    assert!(page.len() < 2_000_000, "{} bytes", page.len());
    // The large maps are linked by relative path, the figures across seeds inlined.
    assert!(page.contains("href=\"robustness__lwpr__pendulum-cart__s0/df_maps.svg\""));
    for name in OVER_SEEDS {
        let at = page.find(&format!("({name})")).unwrap();
        assert!(
            page[..at].rfind("<figure>") > page[..at].rfind("</figure>"),
            "{name} not inlined"
        );
    }
    for href in page.split("href=\"").skip(1) {
        assert!(!href.starts_with('/') && !href[..href.find('"').unwrap()].contains(':'));
    }
}

#[test]
fn a_missing_directory_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("nope");
    assert!(write_index(&missing, "t", &[], "c", None).is_err());
    assert!(!missing.exists());
}

#[test]
fn the_page_renders_in_a_real_browser() {
    let Some(browser) = crate::browser::chromium() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    result_dir(dir.path());
    write_index(
        dir.path(),
        "steplearn reproduce",
        &["claims.md"],
        "steplearn reproduce",
        None,
    )
    .unwrap();
    let shot = dir.path().join("shot.png");
    let o = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--window-size=1000,1400",
        ])
        .arg(format!("--screenshot={}", shot.display()))
        .arg(format!("file://{}", dir.path().join(INDEX_FILE).display()))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let png = std::fs::read(&shot).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
    // width and height from the IHDR chunk
    let w = u32::from_be_bytes(png[16..20].try_into().unwrap());
    let h = u32::from_be_bytes(png[20..24].try_into().unwrap());
    assert_eq!((w, h), (1000, 1400));
    // a rendered page with text, tables and figures compresses to far more than a blank one
    assert!(png.len() > 20_000, "{} bytes: blank page?", png.len());
}
