//! The sweep machinery with a fake runner: determinism across thread counts (and with real
//! experiments, every file byte for byte), resumption,
//! failures, sharding into one directory, and merging into the ablation table.

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use steplearn::experiments::ablation::{AblationCsvRow, merge};
use steplearn::experiments::disturbance::DisturbanceSummary;
use steplearn::experiments::robustness::{NoLearning, RobustnessSummary};
use steplearn::experiments::stability::{ControllerFalls, Controllers, StabilitySummary};
use steplearn::experiments::summary::{ModelLearned, Summary, TypedResult};
use steplearn::experiments::sweep::{
    RunError, RunSpec, RunStatus, Shard, SweepGrid, SweepOptions, run_sweep,
};
use steplearn::experiments::tracking::TrackingSummary;
use steplearn::report::Shortest;

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("steplearn-sweep-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// FNV-1a: a hash that is the same on every platform and version.
fn fnv(s: &str) -> u64 {
    s.bytes().fold(0xcbf29ce484222325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x100000001b3)
    })
}

/// A fake experiment: pseudo-random results seeded from the run id, plus a CSV file.
fn fake(spec: &RunSpec, dir: &Path) -> Result<Summary, RunError> {
    let mut rng = ChaCha8Rng::seed_from_u64(fnv(&spec.id()));
    std::fs::write(dir.join("steps.csv"), format!("id\n{}\n", spec.id()))?;
    let mut controller = |pushes: u32| ControllerFalls {
        pushes,
        falls: rng.random_range(0..=pushes),
        impulse_at_50pct_fall_ns: rng.random_range(2.0..15.0),
    };
    let result = match spec.experiment.as_str() {
        "stability" => StabilitySummary {
            controllers: Controllers {
                open_loop: controller(40),
                model: controller(40),
                learned: controller(40),
            },
            fall_causes: Default::default(),
            catch_step_reach: None,
        }
        .into_result()?,
        "robustness" => {
            let first = rng.random_range(1..=6u32);
            RobustnessSummary {
                pushes_until_first_absorbed: (first < 6).then_some(first),
                falls: first - 1,
                impulse_ns: Some(6.0),
                // 5 pushes, absorbed from the first absorbed one on
                absorbed_by_push: (1..=5).map(|p| p >= first).collect(),
                no_learning: Some(NoLearning {
                    absorbed_by_push: (1..=5).map(|p| p == 5).collect(),
                    falls: 4,
                }),
            }
            .into_result()?
        }
        "tracking" => TrackingSummary {
            step_error_std_m: ModelLearned {
                model: vec![Some(rng.random_range(0.0..0.1)); 4],
                learned: vec![Some(rng.random_range(0.0..0.1)); 4],
            },
            bin_s: 0.5,
        }
        .into_result()?,
        "disturbance" => DisturbanceSummary {
            return_time_s: ModelLearned {
                model: rng.random_range(0.0..5.0),
                learned: rng.random_range(0.0..5.0),
            },
            return_time_by_step_s: None,
            settle_time_s: None,
            step_error_after_push_m: None,
            max_tda_rad: ModelLearned {
                model: 0.1,
                learned: 0.15,
            },
            falls: None,
        }
        .into_result()?,
        other => return Err(format!("no fake {other}").into()),
    };
    Ok(Summary {
        approx: spec.approx.clone(),
        rule: spec.rule.clone(),
        seed: spec.seed,
        learn: Default::default(),
        robot: None,
        result,
    })
}

fn grid() -> Vec<RunSpec> {
    SweepGrid::new(
        &["tracking", "disturbance", "stability", "robustness"],
        &["lwpr", "grid"],
        &["pendulum-cart", "balance-only"],
        3,
    )
    .runs()
    .unwrap()
}

/// Every `summary.json` under `dir`, by run id.
fn summaries(dir: &Path) -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .map(|p| {
            let id = p.file_name().unwrap().to_string_lossy().into_owned();
            (id, std::fs::read_to_string(p.join("summary.json")).unwrap())
        })
        .collect();
    out.sort();
    out
}

#[test]
fn results_do_not_depend_on_the_number_of_threads() {
    let runs = grid();
    let mut results = Vec::new();
    for threads in [1, 4] {
        let dir = temp_dir(&format!("threads{threads}"));
        let outcomes = run_sweep(
            &runs,
            &dir,
            &fake,
            &SweepOptions {
                threads: Some(threads),
            },
            &|_| {},
        )
        .unwrap();
        assert_eq!(outcomes.len(), runs.len());
        assert!(outcomes.iter().zip(&runs).all(|(o, r)| &o.spec == r));
        assert!(
            outcomes
                .iter()
                .all(|o| matches!(o.status, RunStatus::Done { .. }))
        );
        let merged = merge(&dir).unwrap();
        // The tables differ only in run time: compare every other column.
        let rows: Vec<String> = merged
            .csv_rows()
            .into_iter()
            .map(|r| {
                format!(
                    "{:?}",
                    AblationCsvRow {
                        run_time_s_mean: Shortest(0.0),
                        run_time_s_std: Shortest(0.0),
                        ..r
                    }
                )
            })
            .collect();
        results.push((summaries(&dir), merged.to_markdown(), rows));
        std::fs::remove_dir_all(&dir).unwrap();
    }
    assert_eq!(results[0].0.len(), runs.len());
    assert_eq!(
        results[0].0, results[1].0,
        "summaries differ between 1 and 4 threads"
    );
    assert!(!results[0].2.is_empty());
    assert_eq!(results[0].2, results[1].2);
}

#[test]
fn resumption_skips_finished_runs_and_retries_failed_ones() {
    let runs = grid();
    let dir = temp_dir("resume");
    let calls = AtomicUsize::new(0);
    // first attempt: robustness runs fail, one stability run panics
    let flaky = |spec: &RunSpec, d: &Path| -> Result<Summary, RunError> {
        calls.fetch_add(1, Ordering::Relaxed);
        if spec.experiment == "robustness" {
            return Err("simulator exploded".into());
        }
        if spec.id() == "stability__grid__balance-only__s1" {
            panic!("boom");
        }
        fake(spec, d)
    };
    let seen = Mutex::new(Vec::new());
    let first = run_sweep(&runs, &dir, &flaky, &SweepOptions::default(), &|o| {
        seen.lock().unwrap().push(o.spec.id())
    })
    .unwrap();
    assert_eq!(seen.lock().unwrap().len(), runs.len());
    let failed: Vec<_> = first
        .iter()
        .filter(|o| matches!(o.status, RunStatus::Failed(_)))
        .collect();
    assert_eq!(failed.len(), 12 + 1);
    assert!(failed.iter().any(|o| matches!(&o.status,
        RunStatus::Failed(m) if m.contains("panicked: boom"))));
    assert!(failed.iter().any(|o| matches!(&o.status,
        RunStatus::Failed(m) if m.contains("simulator exploded"))));
    assert_eq!(calls.load(Ordering::Relaxed), runs.len());
    let finished_ids: Vec<String> = first
        .iter()
        .filter(|o| matches!(o.status, RunStatus::Done { .. }))
        .map(|o| o.spec.id())
        .collect();
    let done_summary =
        std::fs::read_to_string(dir.join(&finished_ids[0]).join("summary.json")).unwrap();

    // second attempt with a working runner: only the failed runs run again
    calls.store(0, Ordering::Relaxed);
    let counting = |spec: &RunSpec, d: &Path| -> Result<Summary, RunError> {
        calls.fetch_add(1, Ordering::Relaxed);
        fake(spec, d)
    };
    let second = run_sweep(&runs, &dir, &counting, &SweepOptions::default(), &|_| {}).unwrap();
    assert_eq!(calls.load(Ordering::Relaxed), 13);
    let skipped = second
        .iter()
        .filter(|o| o.status == RunStatus::Skipped)
        .count();
    assert_eq!(skipped, runs.len() - 13);
    assert_eq!(
        std::fs::read_to_string(dir.join(&finished_ids[0]).join("summary.json")).unwrap(),
        done_summary
    );
    // a third attempt does nothing
    calls.store(0, Ordering::Relaxed);
    run_sweep(&runs, &dir, &counting, &SweepOptions::default(), &|_| {}).unwrap();
    assert_eq!(calls.load(Ordering::Relaxed), 0);

    // a corrupted result is reported, never overwritten
    let victim = dir.join(&finished_ids[1]).join("summary.json");
    std::fs::write(&victim, "{not json").unwrap();
    let third = run_sweep(&runs, &dir, &counting, &SweepOptions::default(), &|_| {}).unwrap();
    assert_eq!(calls.load(Ordering::Relaxed), 0);
    assert_eq!(
        third
            .iter()
            .filter(|o| matches!(&o.status, RunStatus::Failed(m) if m.contains("left untouched")))
            .count(),
        1
    );
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "{not json");
    // merge lists it with its path and still builds the table from the rest
    let merged = merge(&dir).unwrap();
    assert_eq!(merged.problems.len(), 1);
    assert_eq!(merged.problems[0].path, victim);
    assert_eq!(merged.runs_read, runs.len() - 1);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_runner_returning_the_wrong_summary_fails_the_run() {
    let dir = temp_dir("mismatch");
    let runs = grid();
    let wrong = |spec: &RunSpec, d: &Path| -> Result<Summary, RunError> {
        let mut s = fake(spec, d)?;
        s.seed += 1;
        Ok(s)
    };
    let out = run_sweep(&runs[..2], &dir, &wrong, &SweepOptions::default(), &|_| {}).unwrap();
    assert!(
        out.iter()
            .all(|o| matches!(&o.status, RunStatus::Failed(m) if m.contains("another run")))
    );
    assert!(!dir.join(runs[0].id()).join("summary.json").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn shards_fill_one_directory_and_merge_builds_the_table() {
    let runs = grid();
    let dir = temp_dir("shards");
    for i in 0..3 {
        let shard = Shard::new(i, 3).unwrap();
        let mine = shard.select(&runs);
        run_sweep(
            &mine,
            &dir,
            &fake,
            &SweepOptions { threads: Some(2) },
            &|_| {},
        )
        .unwrap();
    }
    // an unfinished run directory and a stray malformed run record
    std::fs::create_dir_all(dir.join("stability__rbf__linear__s9")).unwrap();
    let record = dir.join(runs[0].id()).join("run.json");
    std::fs::write(&record, "[]").unwrap();

    let merged = merge(&dir).unwrap();
    assert_eq!(merged.runs_read, runs.len());
    assert_eq!(merged.unfinished.len(), 1);
    assert_eq!(merged.problems.len(), 1);
    assert_eq!(merged.problems[0].path, record);
    assert_eq!(merged.rows.len(), 4);
    let names: Vec<(String, String)> = merged
        .rows
        .iter()
        .map(|r| (r.approx.clone(), r.rule.clone()))
        .collect();
    assert_eq!(
        names,
        [
            ("grid".into(), "pendulum-cart".into()),
            ("grid".into(), "balance-only".into()),
            ("lwpr".into(), "pendulum-cart".into()),
            ("lwpr".into(), "balance-only".into()),
        ]
    );
    // the lwpr / pendulum-cart row recomputed by hand from the summaries
    let row = &merged.rows[2];
    let mut learned = Vec::new();
    let mut absorbed_within_3 = 0;
    let mut absorbed = (0, 0);
    for seed in 0..3 {
        let spec = |experiment: &str| RunSpec {
            experiment: experiment.into(),
            approx: "lwpr".into(),
            rule: "pendulum-cart".into(),
            seed,
            learn: None,
        };
        let s = fake(&spec("stability"), &dir.join(spec("stability").id())).unwrap();
        if let Some(StabilitySummary { controllers, .. }) = StabilitySummary::of(&s) {
            learned.push(controllers.learned.impulse_at_50pct_fall_ns);
        }
        let s = fake(&spec("robustness"), &dir.join(spec("robustness").id())).unwrap();
        if let Some(RobustnessSummary {
            pushes_until_first_absorbed,
            absorbed_by_push,
            no_learning: Some(b),
            ..
        }) = RobustnessSummary::of(&s)
        {
            if let Some(n) = pushes_until_first_absorbed {
                absorbed_within_3 += usize::from(n <= 3);
            }
            absorbed.0 += absorbed_by_push.iter().filter(|&&a| a).count() as u64;
            absorbed.1 += b.absorbed_by_push.iter().filter(|&&a| a).count() as u64;
        }
    }
    let mean = learned.iter().sum::<f64>() / 3.0;
    assert!((row.i50_learned.mean - mean).abs() < 1e-12);
    assert_eq!(row.i50_learned.n, 3);
    assert_eq!(row.robustness_seeds, 3);
    assert_eq!(row.absorbed_within_3, absorbed_within_3);
    assert_eq!(row.absorbed_vs_no_learning, absorbed);
    assert_eq!(absorbed.1, 3);
    // every experiment's run is timed, except runs[0] (this row) whose run.json was broken
    assert_eq!(runs[0].id(), "tracking__lwpr__pendulum-cart__s0");
    assert_eq!(row.run_time_s.n, 4 * 3 - 1);

    merged.write(&dir).unwrap();
    let md = std::fs::read_to_string(dir.join("ablation.md")).unwrap();
    assert!(md.starts_with("| approx | rule |"));
    assert_eq!(md.lines().count(), 2 + 4);
    assert!(md.contains("| lwpr | pendulum-cart |"));
    let mut csv = csv::Reader::from_path(dir.join("ablation.csv")).unwrap();
    assert_eq!(csv.headers().unwrap().len(), 22);
    assert_eq!(csv.records().count(), 4);
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(merge(&dir).is_err(), "a missing directory is an error");
}

/// Every file under `dir` except the runs' `run.json` (wall times), by relative path.
fn all_files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.file_name().unwrap() != steplearn::experiments::sweep::RECORD_FILE {
                let rel = p.strip_prefix(dir).unwrap().to_string_lossy().into_owned();
                out.push((rel, std::fs::read(&p).unwrap()));
            }
        }
    }
    out.sort();
    out
}

#[test]
fn real_experiments_are_byte_identical_under_1_and_4_threads() {
    use steplearn::bench::Registry;
    use steplearn::experiments::protocol::ProtocolTables;
    use steplearn::experiments::settings::Settings;
    let settings = Settings {
        scale: 0.02,
        ..Settings::default()
    };
    let protocols = ProtocolTables::new();
    let mut runs = SweepGrid::new(
        &["tracking", "disturbance", "stability", "robustness"],
        &["lwpr"],
        &["pendulum-cart"],
        1,
    )
    .runs()
    .unwrap();
    runs.extend(
        SweepGrid::new(
            &["stability", "robustness"],
            &["grid"],
            &["balance-only"],
            1,
        )
        .runs()
        .unwrap(),
    );
    let registry = Registry::builtin();
    let runner = |spec: &RunSpec, dir: &Path| -> Result<Summary, RunError> {
        registry
            .run_spec(spec, dir, &settings, &protocols)
            .map_err(|e| e.into())
    };
    let mut results = Vec::new();
    for threads in [1, 4] {
        let dir = temp_dir(&format!("real-threads{threads}"));
        let outcomes = run_sweep(
            &runs,
            &dir,
            &runner,
            &SweepOptions {
                threads: Some(threads),
            },
            &|_| {},
        )
        .unwrap();
        assert!(
            outcomes
                .iter()
                .all(|o| matches!(o.status, RunStatus::Done { .. })),
            "{outcomes:?}"
        );
        results.push(all_files(&dir));
        std::fs::remove_dir_all(&dir).unwrap();
    }
    // every run wrote its summary and its pushes
    for run in &runs {
        let pushes = match run.experiment.as_str() {
            "stability" => "pushes.csv",
            "robustness" => "robustness_pushes.csv",
            "tracking" => "tracking_steps.csv",
            _ => "disturbance_pushes.csv",
        };
        for file in ["summary.json", pushes] {
            let want = format!("{}/{file}", run.id());
            assert!(results[0].iter().any(|(p, _)| *p == want), "{want} missing");
        }
    }
    assert_eq!(
        results[0].iter().map(|f| &f.0).collect::<Vec<_>>(),
        results[1].iter().map(|f| &f.0).collect::<Vec<_>>()
    );
    for (a, b) in results[0].iter().zip(&results[1]) {
        assert!(a.1 == b.1, "{} differs between 1 and 4 threads", a.0);
    }
}

#[test]
fn workers_sharing_a_directory_compute_each_run_once() {
    let runs = grid();
    // One undisturbed worker, for the bytes.
    let alone = temp_dir("workers-alone");
    run_sweep(&runs, &alone, &fake, &SweepOptions::default(), &|_| {}).unwrap();
    // Three workers at once on one directory, each with its own two threads.
    let shared = temp_dir("workers-shared");
    let calls = AtomicUsize::new(0);
    let counting = |spec: &RunSpec, d: &Path| -> Result<Summary, RunError> {
        calls.fetch_add(1, Ordering::Relaxed);
        std::thread::sleep(std::time::Duration::from_millis(5));
        fake(spec, d)
    };
    let outcomes: Vec<Vec<_>> = std::thread::scope(|s| {
        let workers: Vec<_> = (0..3)
            .map(|_| {
                s.spawn(|| {
                    run_sweep(
                        &runs,
                        &shared,
                        &counting,
                        &SweepOptions { threads: Some(2) },
                        &|_| {},
                    )
                    .unwrap()
                })
            })
            .collect();
        workers.into_iter().map(|w| w.join().unwrap()).collect()
    });
    assert_eq!(
        calls.load(Ordering::Relaxed),
        runs.len(),
        "each run computed once"
    );
    for worker in &outcomes {
        // Every worker returns with the whole selection finished.
        assert!(
            worker
                .iter()
                .all(|o| matches!(o.status, RunStatus::Done { .. } | RunStatus::Skipped))
        );
    }
    let done: usize = outcomes
        .iter()
        .flatten()
        .filter(|o| matches!(o.status, RunStatus::Done { .. }))
        .count();
    assert_eq!(done, runs.len());
    assert_eq!(summaries(&shared), summaries(&alone));
}

#[test]
fn a_run_whose_worker_died_is_taken_over() {
    let runs = grid()[..2].to_vec();
    let dir = temp_dir("workers-died");
    // A worker that claimed the first run and then died: its lock goes when its file closes.
    let held = dir.join(runs[0].id());
    std::fs::create_dir_all(&held).unwrap();
    let lock = std::fs::File::create(held.join(steplearn::experiments::sweep::CLAIM_FILE)).unwrap();
    lock.lock().unwrap();
    let calls = AtomicUsize::new(0);
    let counting = |spec: &RunSpec, d: &Path| -> Result<Summary, RunError> {
        calls.fetch_add(1, Ordering::Relaxed);
        fake(spec, d)
    };
    let outcomes = std::thread::scope(|s| {
        let worker =
            s.spawn(|| run_sweep(&runs, &dir, &counting, &SweepOptions::default(), &|_| {}));
        // The other run is computed while the first waits for its claim.
        while !dir.join(runs[1].id()).join("summary.json").exists() {
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        assert_eq!(calls.load(Ordering::Relaxed), 1);
        drop(lock);
        worker.join().unwrap().unwrap()
    });
    assert_eq!(calls.load(Ordering::Relaxed), 2);
    assert!(
        outcomes
            .iter()
            .all(|o| matches!(o.status, RunStatus::Done { .. }))
    );
}
