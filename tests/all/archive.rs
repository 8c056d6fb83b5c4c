//! The stored main jobs are today's code's: every run of `results-archive/paper` (the
//! defaults) and `results-archive/improved` (`--config configs/improved.toml`) has the
//! identity today's code gives it, their claims recomputed from the stored summaries with
//! today's code are the stored claims, and the README's claims table is the one built from
//! them. docs/configuration.md's key table is what `steplearn config --table` prints.

use std::path::{Path, PathBuf};
use steplearn::bench::Registry;
use steplearn::experiments::claims_table::{claims_table, robots_table};
use steplearn::experiments::config_file::ConfigFile;
use steplearn::experiments::config_keys::key_table;
use steplearn::experiments::reproduce::Claims;
use steplearn::experiments::summary::Summary;
use steplearn::experiments::sweep::RunSpec;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The run directories of a stored main job.
fn runs(job: &Path) -> Vec<PathBuf> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(job)
        .unwrap_or_else(|e| panic!("{}: {e}", job.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("run-config.toml").is_file())
        .collect();
    dirs.sort();
    dirs
}

/// Checks a stored main job made with `config` (none: the defaults) against today's code and
/// returns its claims.
fn check_job(job: &str, config: Option<&str>) -> Claims {
    let job = root().join(job);
    let config = match config {
        None => ConfigFile::default(),
        Some(path) => ConfigFile::load(&root().join(path)).unwrap(),
    };
    let registry = Registry::builtin();
    let dirs = runs(&job);
    assert_eq!(
        dirs.len(),
        40,
        "{}: the main job's 4 experiments x 10 seeds",
        job.display()
    );
    let mut summaries = Vec::new();
    for dir in &dirs {
        let stored = std::fs::read_to_string(dir.join("run-config.toml")).unwrap();
        let value: toml::Value = toml::from_str(&stored).unwrap();
        let spec = RunSpec {
            experiment: value["experiment"].as_str().unwrap().to_string(),
            approx: value["approx"].as_str().unwrap().to_string(),
            rule: value["rule"].as_str().unwrap().to_string(),
            seed: value["seed"].as_integer().unwrap() as u64,
            learn: None,
        };
        let today = registry
            .run_identity(&spec, &config.settings, &config.protocols)
            .unwrap();
        assert!(
            stored == today,
            "{} was made with another config or code than today's: rerun the main job \
             (the job's README in results-archive says how)",
            dir.display()
        );
        summaries.push(Summary::read(&dir.join("summary.json")).unwrap());
    }
    judged_as_stored(&job, &summaries)
}

/// The job's stored `claims.json`, after checking that today's code judges `summaries` so.
fn judged_as_stored(job: &Path, summaries: &[Summary]) -> Claims {
    let stored: Claims =
        serde_json::from_str(&std::fs::read_to_string(job.join("claims.json")).unwrap()).unwrap();
    let today = Claims::from_summaries(summaries, 0.15);
    assert_eq!(
        serde_json::to_value(&today).unwrap(),
        serde_json::to_value(&stored).unwrap(),
        "{}: today's code judges the stored summaries otherwise",
        job.display()
    );
    stored
}

#[test]
fn the_readme_claims_table_is_the_stored_main_jobs_of_todays_code() {
    let paper = check_job("results-archive/paper", None);
    let improved = check_job("results-archive/improved", Some("configs/improved.toml"));
    let table = claims_table(&paper, &improved);
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    assert!(
        readme.contains(&table),
        "README.md's claims table differs from the stored main jobs; it should read:\n{table}"
    );
}

/// The stored main job of a robot: today's code judges its summaries as stored.
fn robot_job(dir: &str) -> Claims {
    let job = root().join(dir);
    let mut summaries = Vec::new();
    for entry in std::fs::read_dir(&job).unwrap() {
        let path = entry.unwrap().path().join("summary.json");
        if path.exists() {
            summaries.push(Summary::read(&path).unwrap());
        }
    }
    assert_eq!(summaries.len(), 20, "{dir}: four experiments x five seeds");
    judged_as_stored(&job, &summaries)
}

#[test]
fn the_readme_robot_table_is_the_stored_robot_jobs() {
    let paper = check_job("results-archive/paper", None);
    let igus = robot_job("results-archive/robots/igus_like");
    let talos = robot_job("results-archive/robots/talos");
    let table = robots_table(&[
        ("the paper's humanoid (built in)", &paper, "89 x"),
        ("igus-like (6.5 kg)", &igus, "84 x"),
        ("Talos (90 kg, as shipped)", &talos, "86 x"),
    ]);
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    assert!(
        readme.contains(&table),
        "README.md's robot table differs from the stored robot jobs; it should read:\n{table}"
    );
}

#[test]
fn the_configuration_chapter_holds_the_key_table_of_todays_code() {
    let doc = std::fs::read_to_string(root().join("docs/configuration.md")).unwrap();
    let table = key_table();
    assert!(
        doc.contains(&table),
        "docs/configuration.md's key table differs from `steplearn config --table`:\n{table}"
    );
}
