//! `index.html`: one self-contained page per result, and that it renders in a real browser.

use std::path::Path;
use std::process::Command;
use steplearn::experiments::index_page::{INDEX_FILE, write_index};

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
    assert!(page.contains("Experiment C: fall probability against push impulse"));
    assert!(page.contains("Experiment D: the learned offset dF"));
    assert!(page.contains("<h3>stability__lwpr__pendulum-cart__s0</h3>"));
    assert!(page.contains("steplearn reproduce --quick --out x"));
    assert!(page.contains("scale = 0.1"));
    // self-contained: no script, stylesheet link or fetched resource
    for external in ["<script", "<link", "src=", "href=", "url(", "@import"] {
        assert!(!page.contains(external), "{external} in the page");
    }
    // the top-level figure comes before the runs' figures
    let top = page.find("Claim 1:").unwrap();
    assert!(top < page.find("<h3>robustness").unwrap());
}

#[test]
fn a_missing_directory_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("nope");
    assert!(write_index(&missing, "t", &[], "c", None).is_err());
    assert!(!missing.exists());
}

/// The first headless browser found, if any.
fn browser() -> Option<&'static str> {
    ["chromium", "chromium-browser", "google-chrome"]
        .into_iter()
        .find(|b| {
            Command::new(b)
                .arg("--version")
                .output()
                .is_ok_and(|o| o.status.success())
        })
}

#[test]
fn the_page_renders_in_a_real_browser() {
    let Some(browser) = browser() else {
        // CI installs Chromium (.ci/run); there a missing browser is a failure, not a skip.
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "no chromium found under CI=true (install Debian's `chromium` package)"
        );
        eprintln!(
            "skipped: no chromium found (install Debian's `chromium` package to run this test)"
        );
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
