//! The open bench: a user's approximator, rule and experiment registered beside the built-ins,
//! every bad name or setting a typed error before anything runs, the leaderboard's contract, and
//! the same bytes for a run alone, in a bench, through the command line and sharded.

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use steplearn::approx::{ApproxError, Grid, GridConfig, InputBox};
use steplearn::bench::{Bench, BenchError, Registry};
use steplearn::control::LearnerInput;
use steplearn::experiments::ExperimentError;
use steplearn::experiments::paired::{Direction, Paired};
use steplearn::experiments::protocol::ProtocolTables;
use steplearn::experiments::settings::Settings;
use steplearn::experiments::summary::TypedResult;
use steplearn::experiments::summary::{CustomResult, ExperimentResult, Summary};
use steplearn::experiments::sweep::{RunSpec, Shard};
use steplearn::experiments::tracking::TrackingSummary;
use steplearn::experiments::{Experiment, Headline, RunContext};
use steplearn::rules::{LearningRule, StepOutcome};

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("steplearn-bench-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// A rule of the test's own: twice the trunk deviation.
struct Doubled;
impl LearningRule for Doubled {
    fn gradient(&self, step: &StepOutcome) -> f64 {
        2.0 * step.theta_e
    }
}

/// An experiment of the test's own, without the simulator: trains a fresh learner on a few
/// seeded outcomes and reports its offset at one input ("learned") against 0 ("model").
struct Probe;

#[derive(Serialize, Deserialize)]
struct ProbeResult {
    offset_m: f64,
}

impl Experiment for Probe {
    fn name(&self) -> &str {
        "probe"
    }
    fn run(&self, ctx: &RunContext<'_>, dir: &Path) -> Result<ExperimentResult, ExperimentError> {
        let mut learner = ctx.make_learner()?;
        let input = LearnerInput::new(0.02, 0.1, 0.1);
        for k in 0..3 {
            learner.query(input)?;
            let theta_e = 0.01 * ((ctx.seed + k) % 4) as f64;
            learner.touch_down(&StepOutcome {
                theta_e,
                theta_e_dot: 0.0,
                f_e: 0.0,
                f_r: 0.1,
            })?;
        }
        std::fs::write(dir.join("probe.txt"), ctx.approx)
            .map_err(|e| ExperimentError::Invalid(e.to_string()))?;
        let result = ProbeResult {
            offset_m: learner.predict(input)?,
        };
        Ok(ExperimentResult::Custom(CustomResult::new(
            self.name(),
            &result,
        )?))
    }
    fn versus_model(&self, runs: &[&Summary]) -> Vec<Paired> {
        let v: Vec<f64> = runs
            .iter()
            .map(|s| match &s.result {
                ExperimentResult::Custom(c) => c.parse::<ProbeResult>().unwrap().offset_m,
                _ => f64::NAN,
            })
            .collect();
        vec![Paired::new(
            "offset, learned - model (m)",
            &v,
            0.0,
            Direction::HigherIsBetter,
        )]
    }
    fn headline(&self, runs: &[&Summary]) -> Vec<Headline> {
        vec![Headline::mean_of("runs", [runs.len() as f64])]
    }
}

fn coarse_grid(bounds: &InputBox) -> Result<Grid, ApproxError> {
    Grid::new(GridConfig::new(bounds.clone(), vec![3, 3, 3], 1))
}

fn registry() -> Registry {
    Registry::builtin()
        .approximator("coarse-grid", coarse_grid)
        .rule("doubled", || Doubled)
        .experiment(Probe)
}

#[test]
fn bad_registrations_and_selections_are_typed_errors_before_anything_runs() {
    let dir = temp_dir("bad");
    let dup = Registry::builtin().approximator("lwpr", coarse_grid);
    assert!(matches!(dup.check(), Err(BenchError::Registry(m)) if m.contains("twice")));
    let bench = Bench::new(&dup).out(&dir).run();
    assert!(matches!(bench, Err(BenchError::Registry(_))), "{bench:?}");
    let malformed = Registry::builtin().rule("Bad Name", || Doubled);
    assert!(malformed.check().is_err());
    let twice = Registry::builtin().experiment(Probe).experiment(Probe);
    assert!(twice.check().is_err());

    let r = registry();
    let base = || {
        Bench::new(&r)
            .approximators(["coarse-grid"])
            .rules(["doubled"])
            .experiments(["probe"])
            .out(&dir)
    };
    let unknown = base().rules(["doubled", "nope"]).run().unwrap_err();
    assert!(
        matches!(&unknown, BenchError::Unknown { what, name, .. } if what == "rule" && name == "nope"),
        "{unknown}"
    );
    assert!(
        unknown.to_string().contains("doubled"),
        "lists the known names"
    );
    for (bad, what) in [
        (base().approximators(["lwpr", "lwpr"]), "twice"),
        (base().experiments(Vec::<String>::new()), "no experiment"),
        (base().seeds(0), "seeds"),
        (base().first_seed(u64::MAX).seeds(2), "overflows"),
        (base().scale(0.0), "scale"),
        (base().scale(f64::NAN), "scale"),
        (base().baseline("lwpr", "doubled"), "baseline"),
    ] {
        let e = bad.run().unwrap_err();
        assert!(e.to_string().contains(what), "{what}: {e}");
    }
    assert!(!dir.exists(), "nothing was written");
    // Seeds from a first seed on.
    let grid = base().first_seed(5).seeds(3).grid().unwrap();
    assert_eq!(grid.seeds, [5, 6, 7]);
    assert_eq!(base().seeds(2).grid().unwrap().seeds, [0, 1]);
}

#[test]
fn a_users_names_run_into_a_leaderboard_with_a_verdict_per_row() {
    let dir = temp_dir("leaderboard");
    let r = registry();
    // The probe teaches one small step; the experiments' dead zone (for the walker's step
    // noise) would swallow its G, so this bench learns from every step.
    let config = steplearn::experiments::config_file::ConfigFile::from_toml(
        "[settings.learner]\ndead_zone = 0.0\n",
    )
    .unwrap();
    let bench = || {
        Bench::new(&r)
            .config(config.clone())
            .approximators(["coarse-grid", "lwpr"])
            .rules(["doubled", "pendulum-cart"])
            .experiments(["probe"])
            .seeds(3)
            .out(&dir)
            .run()
            .unwrap()
    };
    let report = bench();
    assert_eq!(report.outcomes.len(), 2 * 2 * 3);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("leaderboard.json")).unwrap())
            .unwrap();
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 4);
    assert_eq!(json["baseline"]["approx"], "lwpr");
    for row in rows {
        for key in ["approx", "rule", "experiment"] {
            assert!(row[key].is_string(), "{row}");
        }
        let c = &row["vs_model"][0];
        assert_eq!(c["quantity"], "offset, learned - model (m)");
        assert!(c["mean"].is_f64() && c["ci95"][0].is_f64() && c["ci95"][1].is_f64());
        assert!(["better", "level", "worse"].contains(&c["verdict"].as_str().unwrap()));
        let is_base = row["approx"] == "lwpr" && row["rule"] == "pendulum-cart";
        assert_eq!(row["vs_baseline"].as_array().unwrap().is_empty(), is_base);
    }
    // The comparison is the mean of the per-seed values, recomputed here from the summaries.
    let mut offsets = Vec::new();
    for seed in 0..3 {
        let spec = RunSpec {
            experiment: "probe".into(),
            approx: "coarse-grid".into(),
            rule: "doubled".into(),
            seed,
            learn: None,
        };
        let s = Summary::read(&dir.join(spec.id()).join("summary.json")).unwrap();
        assert_eq!(
            (s.approx.as_str(), s.rule.as_str()),
            ("coarse-grid", "doubled")
        );
        let ExperimentResult::Custom(c) = &s.result else {
            panic!("{s:?}")
        };
        offsets.push(c.parse::<ProbeResult>().unwrap().offset_m);
    }
    let mean = offsets.iter().sum::<f64>() / 3.0;
    // Every row's interval and verdict, recomputed from its runs' offsets: the mean, the
    // sample standard deviation, the two-sided 95% Student-t half width with 2 degrees of
    // freedom (t = 4.302653), and the verdict of a learned offset that is better when higher.
    for row in rows {
        let (approx, rule) = (
            row["approx"].as_str().unwrap(),
            row["rule"].as_str().unwrap(),
        );
        let values: Vec<f64> = (0..3)
            .map(|seed| {
                let spec = RunSpec {
                    experiment: "probe".into(),
                    approx: approx.into(),
                    rule: rule.into(),
                    seed,
                    learn: None,
                };
                let s = Summary::read(&dir.join(spec.id()).join("summary.json")).unwrap();
                let ExperimentResult::Custom(c) = &s.result else {
                    panic!("{s:?}")
                };
                c.parse::<ProbeResult>().unwrap().offset_m
            })
            .collect();
        let m = values.iter().sum::<f64>() / 3.0;
        let sd = (values.iter().map(|v| (v - m).powi(2)).sum::<f64>() / 2.0).sqrt();
        let half = 4.302_652_729_911_275 * sd / 3f64.sqrt();
        let (lo, hi) = (m - half, m + half);
        let c = &row["vs_model"][0];
        let got = |v: &serde_json::Value| v.as_f64().unwrap();
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + b.abs());
        assert!(
            close(got(&c["mean"]), m),
            "{approx}/{rule}: {c} vs mean {m}"
        );
        assert!(
            close(got(&c["ci95"][0]), lo) && close(got(&c["ci95"][1]), hi),
            "{approx}/{rule}: {c} vs [{lo}, {hi}]"
        );
        let verdict = if lo > 0.0 {
            "better"
        } else if hi < 0.0 {
            "worse"
        } else {
            "level"
        };
        assert_eq!(
            c["verdict"], verdict,
            "{approx}/{rule}: {c} vs [{lo}, {hi}]"
        );
    }
    let row = rows
        .iter()
        .find(|r| r["approx"] == "coarse-grid" && r["rule"] == "doubled")
        .unwrap();
    assert!((row["vs_model"][0]["mean"].as_f64().unwrap() - mean).abs() < 1e-12);
    assert!(mean > 0.0, "a learner that leaned forward steps longer");
    for f in [
        "leaderboard.md",
        "leaderboard.csv",
        "forest.svg",
        "index.html",
    ] {
        assert!(dir.join(f).is_file(), "{f}");
    }
    let csv = std::fs::read_to_string(dir.join("leaderboard.csv")).unwrap();
    assert!(
        csv.lines()
            .any(|l| l.starts_with("coarse-grid,doubled,probe,model,"))
    );
    // A run reused: a second call runs nothing and writes the same leaderboard.
    let before = std::fs::read(dir.join("leaderboard.json")).unwrap();
    let again = bench();
    assert!(
        again
            .outcomes
            .iter()
            .all(|o| o.status == steplearn::experiments::sweep::RunStatus::Skipped)
    );
    assert_eq!(std::fs::read(dir.join("leaderboard.json")).unwrap(), before);
    // Another configuration into the same directory is refused, naming the record.
    let changed = Bench::new(&r)
        .approximators(["coarse-grid"])
        .rules(["doubled"])
        .experiments(["probe"])
        .scale(0.5)
        .out(&dir)
        .run()
        .unwrap_err();
    assert!(matches!(changed, BenchError::ConfigChanged(_)), "{changed}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_run_gives_the_same_bytes_alone_in_a_bench_sharded_and_through_the_command_line() {
    let r = registry();
    let settings = Settings {
        scale: 0.02,
        ..Settings::default()
    };
    let spec = RunSpec {
        experiment: "stability".into(),
        approx: "coarse-grid".into(),
        rule: "doubled".into(),
        seed: 1,
        learn: None,
    };
    let alone = temp_dir("alone");
    std::fs::create_dir_all(&alone).unwrap();
    let summary = r
        .run_spec(&spec, &alone, &settings, &ProtocolTables::new())
        .unwrap();
    let want = summary.to_json().unwrap();

    let bench = temp_dir("bench");
    fn select(b: Bench<'_>) -> Bench<'_> {
        b.approximators(["coarse-grid"])
            .rules(["doubled"])
            .experiments(["stability"])
            .seeds(2)
            .scale(0.02)
    }
    select(Bench::new(&r)).threads(1).out(&bench).run().unwrap();
    let sharded = temp_dir("sharded");
    for i in 0..2 {
        let b = select(Bench::new(&r)).threads(2).out(&sharded);
        b.shard(Shard::new(i, 2).unwrap()).run().unwrap();
    }
    let cli = temp_dir("cli");
    let code = steplearn::cli::main_from(
        registry(),
        [
            "steplearn",
            "bench",
            "--approx",
            "coarse-grid",
            "--rule",
            "doubled",
            "--experiments",
            "stability",
            "--seeds",
            "2",
            "--scale",
            "0.02",
            "--out",
            cli.to_str().unwrap(),
        ],
    );
    assert_eq!(code, std::process::ExitCode::SUCCESS);
    for dir in [&bench, &sharded, &cli] {
        let got = std::fs::read_to_string(dir.join(spec.id()).join("summary.json")).unwrap();
        assert_eq!(got, want, "{}", dir.display());
        assert_eq!(
            std::fs::read(dir.join(spec.id()).join("pushes.csv")).unwrap(),
            std::fs::read(alone.join("pushes.csv")).unwrap()
        );
    }
    for d in [alone, bench, sharded, cli] {
        std::fs::remove_dir_all(d).unwrap();
    }
}

#[test]
fn custom_results_round_trip_and_cannot_pose_as_built_ins() {
    let c = CustomResult::new("probe", &ProbeResult { offset_m: 0.25 }).unwrap();
    let s = Summary {
        approx: "knn".into(),
        rule: "doubled".into(),
        seed: 7,
        learn: Default::default(),
        robot: None,
        result: ExperimentResult::Custom(c),
    };
    let json = s.to_json().unwrap();
    assert!(json.contains("\"experiment\": \"probe\""), "{json}");
    assert_eq!(Summary::from_json(&json).unwrap(), s);
    let posing = Summary {
        result: ExperimentResult::Custom(
            CustomResult::new("tracking", &ProbeResult { offset_m: 0.0 }).unwrap(),
        ),
        ..s.clone()
    };
    // A result posing as a built-in experiment's is refused by that experiment's check (the
    // registry refuses a second experiment of the same name).
    assert!(TrackingSummary::from_result(&posing.result).is_err());
    let registry = Registry::builtin();
    let tracking = registry.find_experiment("tracking").unwrap();
    assert!(tracking.check_result(&posing.result).is_err());
    let clash = Summary {
        result: ExperimentResult::Custom(
            CustomResult::new("probe", &serde_json::json!({"seed": 3})).unwrap(),
        ),
        ..s
    };
    assert!(clash.to_json().is_err());
    assert!(CustomResult::new("probe", &3.0).is_err(), "not an object");
}

#[test]
fn the_registrys_built_in_rules_are_the_rule_kinds_with_their_defaults() {
    use steplearn::Named;
    use steplearn::rules::{RuleConfig, RuleKind, StepOutcome};
    use strum::VariantArray;
    let registry = Registry::builtin();
    let kinds: Vec<&str> = RuleKind::VARIANTS.iter().map(|k| k.name()).collect();
    assert_eq!(registry.rule_names(), kinds);
    // Each builds the kind's default rule: the same gradient on a step.
    let step = StepOutcome {
        theta_e: 0.07,
        theta_e_dot: -0.3,
        f_e: 0.02,
        f_r: 0.1,
    };
    let settings = steplearn::experiments::settings::LwprSettings::default();
    for kind in RuleKind::VARIANTS {
        let learner = registry
            .learner_builder("lwpr", kind.name(), &settings)
            .unwrap()(steplearn::control::LearnerConfig::default())
        .unwrap();
        let expected = RuleConfig::from(*kind).build().unwrap().gradient(&step);
        assert_eq!(learner.rule().gradient(&step), expected, "{kind}");
    }
}
