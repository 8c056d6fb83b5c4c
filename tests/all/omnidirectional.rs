//! Experiment `omnidirectional` through the bench, as a user's experiment would run: its
//! summary's binding fields, its figure, its leaderboard rows, and the same bytes run twice.

use steplearn::bench::{Bench, Registry};
use steplearn::experiments::config_file::ConfigFile;
use steplearn::experiments::omnidirectional::{
    OmnidirectionalResult, SECTORS, WALK_WALKERS, WALKERS, direction, sector_of,
};

#[test]
fn the_summary_holds_i50_per_sector_for_every_walker_and_runs_repeat_bit_for_bit() {
    let dir = std::env::temp_dir().join(format!("steplearn-omni-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let registry = Registry::builtin();
    assert!(registry.experiment_names().contains(&"omnidirectional"));
    // A short walk: 4 references of 2-3 s.
    let config = ConfigFile::from_toml(
        "[protocols.omnidirectional]\nwalk_s = 8.0\nwalk_hold_s = [2.0, 3.0]\n",
    )
    .unwrap();
    let run = |out: &std::path::Path| {
        Bench::new(&registry)
            .config(config.clone())
            .approximators(["lwpr"])
            .rules(["pendulum-cart"])
            .experiments(["omnidirectional"])
            .seeds(1)
            .scale(0.03)
            .out(out)
            .run()
            .unwrap()
    };
    run(&dir.join("a"));
    let run_dir = dir
        .join("a")
        .join("omnidirectional__lwpr__pendulum-cart__s0");
    let summary = std::fs::read_to_string(run_dir.join("summary.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&summary).unwrap();
    let sectors: Vec<f64> = serde_json::from_value(json["sectors_deg"].clone()).unwrap();
    assert_eq!(
        sectors,
        [0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0]
    );
    let i50 = |walker: &str| -> Vec<f64> {
        serde_json::from_value(json["i50_ns"][walker].clone()).unwrap()
    };
    for walker in ["open_loop", "model", "sagittal", "both"] {
        let i50 = i50(walker);
        assert_eq!(i50.len(), SECTORS, "{walker}");
        // Every walker withstands some push in every direction.
        assert!(
            i50.iter().all(|v| v.is_finite() && *v > 0.0),
            "{walker}: {i50:?}"
        );
    }
    // What the experiment is for: the Capture Step model recovers from pushes by stepping,
    // the open-loop walker cannot, so the model's I50 is higher, here in the sectors' mean
    // (measured on this seed: 9.18 against 7.14 Ns; the full protocol gives about twice the
    // open-loop walker's I50, docs/research/robot-variants.md), and no sector is lower (at this length the two
    // are tied in five of eight).
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let (model, open_loop) = (i50("model"), i50("open_loop"));
    assert!(
        mean(&model) > mean(&open_loop),
        "model {model:?}, open loop {open_loop:?}"
    );
    assert!(
        model.iter().zip(&open_loop).all(|(m, o)| m >= o),
        "model {model:?}, open loop {open_loop:?}"
    );
    let result: OmnidirectionalResult = serde_json::from_value(json.clone()).unwrap();
    assert_eq!(result.pushes.len(), SECTORS);
    assert!(result.pushes.iter().all(|n| *n >= 2));
    for w in WALKERS {
        // Every pushed fall has a cause; the counts add up to at least the falls.
        for (k, causes) in result.fall_causes[w].iter().enumerate() {
            let total: u32 = causes.values().sum();
            assert!(total as usize >= result.falls[w][k], "{w} sector {k}");
        }
    }
    // The walk: per walker a list over the sectors, null where no reference pointed.
    for w in WALK_WALKERS {
        let errors = &result.walk_error_m[w];
        assert_eq!(errors.len(), SECTORS);
        assert!(errors.iter().flatten().count() >= 1, "{w}: {errors:?}");
        assert!(errors.iter().flatten().all(|e| e.is_finite() && *e >= 0.0));
        let steps = &result.walk_steps[w];
        for (k, e) in errors.iter().enumerate() {
            assert_eq!(e.is_some(), steps[k] > 0, "{w} sector {k}");
            // The norm of (F_E, W_E) is at least either part.
            if let (Some(e), Some(f), Some(wd)) = (
                e,
                result.walk_step_error_m[w][k],
                result.walk_width_error_m[w][k],
            ) {
                assert!(*e >= f.max(wd) - 1e-12 && *e <= f + wd + 1e-12);
            }
        }
        assert!(result.walk_falls.contains_key(w));
    }
    assert!(run_dir.join("omnidirectional_walk.csv").is_file());
    assert!(run_dir.join("omnidirectional_i50.svg").is_file());
    assert!(run_dir.join("omnidirectional_pushes.csv").is_file());
    // The leaderboard compares both learners and the sagittal one with the model.
    let board = std::fs::read_to_string(dir.join("a").join("leaderboard.json")).unwrap();
    let board: serde_json::Value = serde_json::from_str(&board).unwrap();
    let row = &board["rows"].as_array().unwrap()[0];
    assert_eq!(row["experiment"], "omnidirectional");
    let quantities: Vec<&str> = row["vs_model"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["quantity"].as_str().unwrap())
        .collect();
    assert!(quantities.len() >= 5, "{quantities:?}");
    assert!(quantities.contains(&"walk error both / model, sectors' mean"));
    // The same seed gives the same bytes in another directory.
    run(&dir.join("b"));
    let again = std::fs::read_to_string(
        dir.join("b")
            .join("omnidirectional__lwpr__pendulum-cart__s0")
            .join("summary.json"),
    )
    .unwrap();
    assert_eq!(summary, again);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// With a set of step parameters other than the paper's, a fifth walker, `learned`, learns that
/// set: it has an I50 in every sector, and its I50 differs from the sagittal walker's
/// somewhere (it learns the step time as well); the paper's set adds no such walker. Without a
/// dead zone, so that the learners learn from the few steps of this short run.
#[test]
fn a_learned_set_adds_the_walker_that_learns_it() {
    let dir = tempfile::tempdir().unwrap();
    let registry = Registry::builtin();
    let run = |learn: &str, out: &str| {
        let config = ConfigFile::from_toml(&format!(
            "[settings.learner]\nlearn = {learn}\ndead_zone = 0.0\n[protocols.omnidirectional]\nwalk_s = 8.0\nwalk_hold_s = [2.0, 3.0]\n"
        ))
        .unwrap();
        Bench::new(&registry)
            .config(config)
            .approximators(["lwpr"])
            .rules(["pendulum-cart"])
            .experiments(["omnidirectional"])
            .seeds(1)
            .scale(0.03)
            .out(dir.path().join(out))
            .run()
            .unwrap();
        // A run of another set than the paper's is named by its set.
        let id = match learn {
            "[\"step-x\"]" => "omnidirectional__lwpr__pendulum-cart__s0".to_string(),
            _ => "omnidirectional__lwpr__pendulum-cart__s0__step-x+step-time".to_string(),
        };
        let summary =
            std::fs::read_to_string(dir.path().join(out).join(id).join("summary.json")).unwrap();
        serde_json::from_str::<OmnidirectionalResult>(&summary).unwrap()
    };
    let with = run("[\"step-x\", \"step-time\"]", "xt");
    let learned = &with.i50_ns["learned"];
    assert_eq!(learned.len(), SECTORS);
    assert!(learned.iter().all(|v| v.is_finite() && *v >= 0.0));
    assert_ne!(learned, &with.i50_ns["sagittal"]);
    let paper = run("[\"step-x\"]", "x");
    assert!(!paper.i50_ns.contains_key("learned"));
}

#[test]
fn sector_directions_are_unit_vectors_counter_clockwise_from_forward() {
    assert_eq!(direction(0.0), [1.0, 0.0, 0.0]);
    assert_eq!(direction(90.0), [0.0, 1.0, 0.0]);
    assert_eq!(direction(180.0), [-1.0, 0.0, 0.0]);
    assert_eq!(direction(270.0), [0.0, -1.0, 0.0]);
    let d = direction(45.0);
    assert!((d[0] - d[1]).abs() < 1e-15 && (d[0] * d[0] + d[1] * d[1] - 1.0).abs() < 1e-15);
}

#[test]
fn reference_directions_fall_in_the_sector_of_the_nearest_azimuth() {
    assert_eq!(sector_of(0.1, 0.0), 0);
    assert_eq!(sector_of(0.1, 0.1), 1);
    assert_eq!(sector_of(0.0, 0.05), 2);
    assert_eq!(sector_of(-0.1, 0.001), 4);
    assert_eq!(sector_of(-0.1, -0.001), 4);
    assert_eq!(sector_of(0.0, -0.05), 6);
    assert_eq!(sector_of(0.1, -0.03), 0);
    assert_eq!(sector_of(0.1, -0.06), 7);
}
