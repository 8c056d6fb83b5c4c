//! Sets of learned step parameters as a dimension of the bench: each run learns its own set,
//! each leaderboard row names its set, comparisons with the baseline pair runs of the same set,
//! the paper's set keeps today's directory ids and identities byte for byte; and a factory
//! that cannot build is refused before anything is written.

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use steplearn::approx::{ApproxError, Grid, GridConfig, InputBox};
use steplearn::bench::{Bench, BenchError, Registry};
use steplearn::control::LearnSet;
use steplearn::control::LearnerInput;
use steplearn::experiments::ExperimentError;
use steplearn::experiments::paired::{Direction, Paired};
use steplearn::experiments::summary::{CustomResult, ExperimentResult, Summary};
use steplearn::experiments::sweep::{RunSpec, RunStatus};
use steplearn::experiments::{Experiment, Headline, RunContext};
use steplearn::rules::StepOutcome;

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("steplearn-sets-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// An experiment without the simulator that reports the set its learner was given: its value
/// is the learner's offset at one input plus the number of parameters learned, so that a
/// comparison paired across sets would be off by whole units.
struct SetProbe;

#[derive(Serialize, Deserialize)]
struct SetProbeResult {
    set: String,
    value: f64,
}

impl Experiment for SetProbe {
    fn name(&self) -> &str {
        "set-probe"
    }
    fn run(&self, ctx: &RunContext<'_>, _dir: &Path) -> Result<ExperimentResult, ExperimentError> {
        let mut learner = ctx.make_learner()?;
        let input = LearnerInput::new(0.02, 0.1, 0.1);
        for k in 0..3 {
            learner.query(input)?;
            learner.touch_down(&StepOutcome {
                theta_e: 0.01 * ((ctx.seed + k) % 4) as f64,
                theta_e_dot: 0.0,
                f_e: 0.0,
                f_r: 0.1,
            })?;
        }
        let set = ctx.settings.learner.learn;
        let result = SetProbeResult {
            set: set.to_string(),
            value: learner.predict(input)? + set.iter().count() as f64,
        };
        Ok(ExperimentResult::Custom(CustomResult::new(
            self.name(),
            &result,
        )?))
    }
    fn versus_model(&self, runs: &[&Summary]) -> Vec<Paired> {
        let v: Vec<f64> = runs.iter().map(|s| value(s).value).collect();
        vec![Paired::new("value (1)", &v, 0.0, Direction::HigherIsBetter)]
    }
    fn headline(&self, runs: &[&Summary]) -> Vec<Headline> {
        vec![Headline::mean_of("runs", [runs.len() as f64])]
    }
}

fn value(s: &Summary) -> SetProbeResult {
    match &s.result {
        ExperimentResult::Custom(c) => c.parse::<SetProbeResult>().unwrap(),
        other => panic!("not a set-probe result: {other:?}"),
    }
}

fn coarse_grid(bounds: &InputBox) -> Result<Grid, ApproxError> {
    Grid::new(GridConfig::new(bounds.clone(), vec![3, 3, 3], 1))
}

fn finer_grid(bounds: &InputBox) -> Result<Grid, ApproxError> {
    Grid::new(GridConfig::new(bounds.clone(), vec![4, 4, 4], 1))
}

fn registry() -> Registry {
    Registry::builtin()
        .approximator("coarse-grid", coarse_grid)
        .approximator("finer-grid", finer_grid)
        .experiment(SetProbe)
}

fn xt() -> LearnSet {
    "step-x,step-time".parse().unwrap()
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn names(set: LearnSet) -> serde_json::Value {
    serde_json::Value::from(set.names())
}

#[test]
fn two_sets_give_a_row_each_naming_its_set_and_default_ids_stay() {
    let r = registry();
    fn select(b: Bench<'_>) -> Bench<'_> {
        b.approximators(["coarse-grid"])
            .rules(["pendulum-cart"])
            .experiments(["stability"])
            .seeds(1)
            .scale(0.02)
            .threads(2)
    }
    // Today's bench (no set given: the paper's), and the same with two sets.
    let plain = temp_dir("plain");
    select(Bench::new(&r)).out(&plain).run().unwrap();
    let both = temp_dir("both");
    let report = select(Bench::new(&r))
        .learn_sets([LearnSet::default(), xt()])
        .out(&both)
        .run()
        .unwrap();
    assert_eq!(report.outcomes.len(), 2);

    let paper_id = "stability__coarse-grid__pendulum-cart__s0";
    let xt_id = "stability__coarse-grid__pendulum-cart__s0__step-x+step-time";
    let ids: Vec<String> = report.outcomes.iter().map(|o| o.spec.id()).collect();
    assert_eq!(ids, [paper_id, xt_id]);
    // The paper's run: today's id, identity and summary, byte for byte.
    for file in ["run-config.toml", "summary.json", "pushes.csv"] {
        assert_eq!(
            std::fs::read(both.join(paper_id).join(file)).unwrap(),
            std::fs::read(plain.join(paper_id).join(file)).unwrap(),
            "{file}"
        );
    }
    assert_eq!(
        std::fs::read(both.join("bench-config.toml")).unwrap(),
        std::fs::read(plain.join("bench-config.toml")).unwrap()
    );
    let identity = std::fs::read_to_string(both.join(paper_id).join("run-config.toml")).unwrap();
    assert!(!identity.contains("step-time"), "{identity}");
    // The other set's run learned its set and says so.
    let other = std::fs::read_to_string(both.join(xt_id).join("run-config.toml")).unwrap();
    assert!(other.contains("\"step-time\""), "{other}");
    assert_eq!(
        json(&both.join(xt_id).join("summary.json"))["learn"],
        names(xt())
    );
    assert_eq!(
        json(&both.join(paper_id).join("summary.json"))["learn"],
        names(LearnSet::default())
    );

    // Every row names its set: JSON, Markdown and CSV.
    let board = json(&both.join("leaderboard.json"));
    let rows = board["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0]["learn"], names(LearnSet::default()));
    assert_eq!(rows[1]["learn"], names(xt()));
    for row in rows {
        assert_eq!(row["seeds"], serde_json::json!([0]), "{row}");
    }
    let plain_board = json(&plain.join("leaderboard.json"));
    assert_eq!(plain_board["rows"][0]["learn"], names(LearnSet::default()));
    assert_eq!(plain_board["rows"][0]["vs_model"], rows[0]["vs_model"]);
    let md = std::fs::read_to_string(both.join("leaderboard.md")).unwrap();
    assert!(
        md.contains("| coarse-grid | pendulum-cart | step-x | 1 |"),
        "{md}"
    );
    assert!(
        md.contains("| coarse-grid | pendulum-cart | step-x,step-time | 1 |"),
        "{md}"
    );
    let csv = std::fs::read_to_string(both.join("leaderboard.csv")).unwrap();
    assert!(csv.starts_with("approx,rule,experiment,"), "{csv}");
    assert!(
        csv.lines().next().unwrap().ends_with(",seeds,learn"),
        "{csv}"
    );
    assert!(csv.contains("\"step-x,step-time\""), "{csv}");
    for d in [plain, both] {
        std::fs::remove_dir_all(d).unwrap();
    }
}

#[test]
fn the_command_line_takes_several_sets_and_pairs_the_baseline_by_set() {
    let dir = temp_dir("cli");
    let code = steplearn::cli::main_from(
        registry(),
        [
            "steplearn",
            "bench",
            "--approx",
            "coarse-grid,finer-grid",
            "--rule",
            "pendulum-cart",
            "--experiments",
            "set-probe",
            "--learn",
            "step-x",
            "--learn",
            "step-time,step-x",
            "--seeds",
            "3",
            "--baseline",
            "coarse-grid+pendulum-cart",
            "--out",
            dir.to_str().unwrap(),
        ],
    );
    assert_eq!(code, std::process::ExitCode::SUCCESS);
    let board = json(&dir.join("leaderboard.json"));
    let rows = board["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 4, "2 approximators x 2 sets");
    for (row, (approx, set)) in rows.iter().zip([
        ("coarse-grid", LearnSet::default()),
        ("coarse-grid", xt()),
        ("finer-grid", LearnSet::default()),
        ("finer-grid", xt()),
    ]) {
        assert_eq!(
            (row["approx"].as_str(), &row["learn"]),
            (Some(approx), &names(set))
        );
        // Every run learned its row's set.
        let read = |approx: &str, seed: u64| {
            let spec = RunSpec {
                experiment: "set-probe".into(),
                approx: approx.into(),
                rule: "pendulum-cart".into(),
                seed,
                learn: Some(set),
            };
            let s = Summary::read(&dir.join(spec.id()).join("summary.json")).unwrap();
            assert_eq!(s.learn, set);
            let v = value(&s);
            assert_eq!(v.set, set.to_string());
            v.value
        };
        // Against the baseline: the mean of this minus the baseline of the same set and seed.
        if approx == "finer-grid" {
            let diffs: Vec<f64> = (0..3)
                .map(|seed| read("finer-grid", seed) - read("coarse-grid", seed))
                .collect();
            let mean = diffs.iter().sum::<f64>() / 3.0;
            let got = row["vs_baseline"][0]["mean"].as_f64().unwrap();
            assert!((got - mean).abs() < 1e-12, "{got} vs {mean}");
            assert!(got.abs() < 0.5, "paired within one set: {got}");
        } else {
            assert!(row["vs_baseline"].as_array().unwrap().is_empty());
        }
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_set_selected_twice_or_none_is_refused() {
    let r = registry();
    let base = || {
        Bench::new(&r)
            .experiments(["set-probe"])
            .out(temp_dir("never"))
    };
    let twice = base().learn_sets([xt(), xt()]).grid().unwrap_err();
    assert!(
        matches!(&twice, BenchError::Selection(m) if m.contains("twice")),
        "{twice}"
    );
    let none = base().learn_sets([]).grid().unwrap_err();
    assert!(matches!(none, BenchError::Selection(_)), "{none}");
    assert!(!temp_dir("never").exists());
}

#[test]
fn a_factory_that_cannot_build_is_refused_before_anything_is_written() {
    let r = registry().approximator("broken", |_: &InputBox| -> Result<Grid, ApproxError> {
        Err(ApproxError::config("cells", "no cells"))
    });
    let dir = temp_dir("broken");
    let err = Bench::new(&r)
        .approximators(["coarse-grid", "broken"])
        .rules(["pendulum-cart"])
        .experiments(["set-probe"])
        .seeds(1)
        .out(&dir)
        .run()
        .unwrap_err();
    match &err {
        BenchError::CannotBuild { approx, rule, .. } => {
            assert_eq!(
                (approx.as_str(), rule.as_str()),
                ("broken", "pendulum-cart")
            );
        }
        other => panic!("expected CannotBuild, got {other:?}"),
    }
    assert!(err.to_string().contains("no cells"), "{err}");
    assert!(!dir.exists(), "no directory, no run, no leaderboard");
    let code = steplearn::cli::main_from(
        r.clone(),
        [
            "steplearn",
            "bench",
            "--approx",
            "broken",
            "--rule",
            "pendulum-cart",
            "--experiments",
            "set-probe",
            "--seeds",
            "1",
            "--out",
            dir.to_str().unwrap(),
        ],
    );
    assert_eq!(code, std::process::ExitCode::FAILURE);
    assert!(!dir.exists());
}

/// A user's rule with a parameter.
struct Scaled(f64);
impl steplearn::rules::LearningRule for Scaled {
    fn gradient(&self, step: &StepOutcome) -> f64 {
        self.0 * step.theta_e
    }
}

#[test]
fn a_users_changed_parameter_is_never_handed_back_as_a_finished_run() {
    let dir = temp_dir("changed");
    let bench = |cells: usize, k: f64| {
        let r = registry()
            .approximator("mine", move |b: &InputBox| {
                Grid::new(GridConfig::new(b.clone(), vec![cells, 3, 3], 1))
            })
            .rule("scaled", move || Scaled(k));
        Bench::new(&r)
            .approximators(["mine"])
            .rules(["scaled"])
            .experiments(["set-probe"])
            .seeds(1)
            .out(&dir)
            .run()
            .map(|report| report.outcomes[0].status.clone())
    };
    let id = dir.join("set-probe__mine__scaled__s0");
    assert!(matches!(bench(3, 1.0), Ok(RunStatus::Done { .. })));
    let identity = std::fs::read_to_string(id.join("run-config.toml")).unwrap();
    assert!(
        identity.contains("approx_model = \"fnv1a-64:"),
        "{identity}"
    );
    assert!(identity.contains("rule_model = \"fnv1a-64:"), "{identity}");
    let record = json(&id.join("run.json"));
    assert_eq!(record["steplearn_version"], env!("CARGO_PKG_VERSION"));
    // The same registrations: reused.
    assert_eq!(bench(3, 1.0).unwrap(), RunStatus::Skipped);
    // Another approximator parameter, then another rule parameter: refused, saying why,
    // and the old result is not in the leaderboard.
    for (cells, k, field) in [(4, 1.0, "approx_model"), (3, 2.0, "rule_model")] {
        match bench(cells, k) {
            Err(BenchError::RunsFailed(failed)) => {
                assert!(failed[0].1.contains(field), "{failed:?}")
            }
            other => panic!("expected a refusal, got {other:?}"),
        }
        let board = json(&dir.join("leaderboard.json"));
        assert_eq!(board["rows"][0]["seeds"], serde_json::json!([]), "{board}");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn built_in_components_keep_identities_without_fingerprints() {
    let r = registry();
    let spec = RunSpec {
        experiment: "stability".into(),
        approx: "lwpr".into(),
        rule: "pendulum-cart".into(),
        seed: 0,
        learn: None,
    };
    let settings = steplearn::experiments::settings::Settings::default();
    let protocols = steplearn::experiments::protocol::ProtocolTables::new();
    let identity = r.run_identity(&spec, &settings, &protocols).unwrap();
    assert!(!identity.contains("_model"), "{identity}");
    let user = RunSpec {
        approx: "coarse-grid".into(),
        ..spec
    };
    let identity = r.run_identity(&user, &settings, &protocols).unwrap();
    assert!(identity.contains("approx_model"), "{identity}");
    assert!(!identity.contains("rule_model"), "{identity}");
}
