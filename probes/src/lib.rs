//! What the research probes share: reading a bench directory's run summaries.

use std::path::{Path, PathBuf};

/// The `summary.json` of every run directory in `dir` whose experiment is `experiment`, with
/// its path, in no particular order. Entries without a readable summary are skipped; a summary
/// that is not JSON is an error.
pub fn summaries(
    dir: &Path,
    experiment: &str,
) -> Result<Vec<(PathBuf, serde_json::Value)>, Box<dyn std::error::Error>> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path().join("summary.json");
        let Ok(text) = std::fs::read_to_string(&path) else {
            continue;
        };
        let json: serde_json::Value = serde_json::from_str(&text)?;
        if json["experiment"] == experiment {
            found.push((path, json));
        }
    }
    Ok(found)
}
