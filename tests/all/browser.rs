//! The real browser that page tests load their pages in: Debian's Chromium, which `.ci/run`
//! installs.

use std::process::Command;

/// The Chromium command found on this machine. Without one the caller's test is skipped with a
/// message, except under `CI=true`, where a missing browser is a failure, not a skip.
pub fn chromium() -> Option<&'static str> {
    let found = ["chromium", "chromium-browser", "google-chrome"]
        .into_iter()
        .find(|b| {
            Command::new(b)
                .arg("--version")
                .output()
                .is_ok_and(|o| o.status.success())
        });
    if found.is_none() {
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "no chromium found under CI=true (install Debian's `chromium` package)"
        );
        eprintln!(
            "skipped: no chromium found (install Debian's `chromium` package to run this test)"
        );
    }
    found
}
