//! Saved models from hostile hands: every approximator's and the learner's loader, fed files
//! from the corpus in `tests/corpus/` with numbers (integer fields and sizes included), keys,
//! array elements and bytes mutated, either refuses the file with an error or loads a model that
//! answers with finite numbers or errors; it never panics or aborts. What trains and saves loads
//! again bit for bit, large targets included.
//!
//! The corpus holds one trained model of every built-in approximator, LWPR at its cap of
//! receptive fields, and two learner
//! checkpoints taken mid-step. `STEPLEARN_BLESS=1 cargo test --test all model_files` rewrites it
//! after a deliberate change of the file format.

use proptest::prelude::*;
use serde_json::Value;
use std::path::PathBuf;
use steplearn::approx::conformance::stream;
use steplearn::approx::{
    AnyApproximator, ApproxError, ApproxKind, FunctionApproximator, InputBox, Lwpr, LwprConfig,
    MAX_INPUT, MAX_TARGET, Persist,
};
use steplearn::control::{
    FootstepLearner, InputGrid, LearnerConfig, LearnerError, LearnerInput, SavedLearner,
};
use steplearn::rules::{PendulumCart, StepOutcome};
use strum::VariantArray;

type Learner = FootstepLearner<AnyApproximator, PendulumCart>;

fn corpus_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/corpus")
}

fn bounds() -> InputBox {
    InputGrid::default().input_box().unwrap()
}

/// Inputs spread over the learner's input box.
fn inputs(seed: u64, n: usize) -> Vec<[f64; 3]> {
    let b = bounds();
    stream(seed, n, 3, 0)
        .into_iter()
        .map(|(x, _)| std::array::from_fn(|i| b.lo[i] + 0.5 * (x[i] + 1.0) * (b.hi[i] - b.lo[i])))
        .collect()
}

fn trained(kind: ApproxKind) -> AnyApproximator {
    let mut a = kind.build(&bounds()).unwrap();
    for x in inputs(1, 80) {
        a.update(&x, &[0.3 * x[0] - 0.02 * x[1] + 0.5 * x[2]])
            .unwrap();
    }
    a
}

/// A learner checkpoint in the middle of its third step.
fn learner_mid_step(kind: ApproxKind) -> SavedLearner<AnyApproximator> {
    let config = LearnerConfig {
        max_samples_per_step: 8,
        prior: steplearn::control::Prior {
            samples: 50,
            ..Default::default()
        },
        ..LearnerConfig::default()
    };
    let mut l = Learner::new(
        kind.build(&bounds()).unwrap(),
        PendulumCart::default(),
        config,
    )
    .unwrap();
    for (i, x) in inputs(2, 50).into_iter().enumerate() {
        l.query(LearnerInput::new(x[0], x[1], x[2])).unwrap();
        l.set_reach(-0.2, if i % 2 == 0 { 0.3 } else { f64::INFINITY })
            .unwrap();
        if i % 20 == 19 {
            let step = StepOutcome {
                theta_e: 0.02,
                theta_e_dot: 0.1,
                f_e: -0.01,
                f_r: 0.0,
            };
            l.touch_down(&step).unwrap();
        }
    }
    l.checkpoint()
}

/// The corpus as this version writes it: (file name, JSON).
fn corpus() -> Vec<(String, String)> {
    let mut files: Vec<(String, String)> = ApproxKind::VARIANTS
        .iter()
        .map(|&k| (format!("{k}.json"), trained(k).to_json().unwrap()))
        .collect();
    // LWPR at its receptive-field cap, with training stamps and replacements.
    let mut capped = Lwpr::new(LwprConfig::new(3, 1).init_d(100.0).max_rfs(8)).unwrap();
    for x in inputs(5, 200) {
        capped.update(&x, &[x[0] - x[2]]).unwrap();
    }
    assert!(capped.submodel(0).unwrap().n_replaced > 0);
    let capped = AnyApproximator::Lwpr(capped);
    files.push(("lwpr-capped.json".into(), capped.to_json().unwrap()));
    for kind in [ApproxKind::Lwpr, ApproxKind::Grid] {
        let json = serde_json::to_string(&learner_mid_step(kind)).unwrap();
        files.push((format!("learner-{kind}.json"), json));
    }
    files
}

fn committed_corpus() -> Vec<(String, String)> {
    corpus()
        .into_iter()
        .map(|(name, _)| {
            let text = std::fs::read_to_string(corpus_dir().join(&name)).unwrap_or_else(|e| {
                panic!("corpus file {name}: {e} (STEPLEARN_BLESS=1 writes it)")
            });
            (name, text)
        })
        .collect()
}

#[test]
fn the_committed_corpus_is_what_this_version_writes_and_loads() {
    let fresh = corpus();
    if std::env::var_os("STEPLEARN_BLESS").is_some() {
        std::fs::create_dir_all(corpus_dir()).unwrap();
        for (name, json) in &fresh {
            std::fs::write(corpus_dir().join(name), json).unwrap();
        }
    }
    for ((name, committed), (_, json)) in committed_corpus().iter().zip(&fresh) {
        assert_eq!(
            committed, json,
            "{name}: the file format or training changed (STEPLEARN_BLESS=1 rewrites the corpus)"
        );
        load(name, committed).unwrap_or_else(|e| panic!("{name}: {e:?}"));
    }
}

/// Why a corpus file (mutated or not) was refused: the loader's typed error.
#[derive(Debug)]
enum Refused {
    /// The approximator's or checkpoint's loader ([`Persist::from_json`]).
    File(ApproxError),
    /// The learner refused a checkpoint that parsed ([`Learner::from_checkpoint`]).
    Learner(LearnerError),
}

impl Refused {
    /// Whether this is a refusal of the file itself: a parse or invariant error
    /// ([`ApproxError::Corrupt`]), or the learner refusing the checkpoint's contents (its
    /// approximator's or rule's state, or its shape); never an i/o error or a panic.
    fn is_a_refusal_of_the_file(&self) -> bool {
        match self {
            Refused::File(e) => matches!(e, ApproxError::Corrupt(_)),
            Refused::Learner(e) => matches!(
                e,
                LearnerError::Approx {
                    source: ApproxError::Corrupt(_),
                    ..
                } | LearnerError::Rule(_)
                    | LearnerError::InvalidConfig { .. }
                    | LearnerError::WrongApproximatorShape { .. }
            ),
        }
    }
}

/// Asserts that what loaded is a valid model: it passes its own invariants and saves a file
/// that loads back to the same bytes (a corrupted file that loads is another valid model, not
/// a damaged one).
fn assert_valid<M: Persist>(name: &str, m: &M) {
    m.check_invariants()
        .unwrap_or_else(|e| panic!("{name}: loaded a model that breaks its invariants: {e}"));
    let saved = m.to_json().unwrap();
    let again = M::from_json(&saved)
        .unwrap_or_else(|e| panic!("{name}: what loaded saves a file that is refused: {e}"));
    assert_eq!(again.to_json().unwrap(), saved, "{name}: not a fixed point");
}

/// Loads a corpus file (mutated or not) by its kind and exercises what loaded: it must be a
/// valid model ([`assert_valid`]), its predictions finite or errors; a learner must also take
/// queries and a touch-down without a panic. A refusal is the loader's typed error.
fn load(name: &str, text: &str) -> Result<(), Refused> {
    if name.starts_with("learner-") {
        let saved = SavedLearner::<AnyApproximator>::from_json(text).map_err(Refused::File)?;
        assert_valid(name, &saved);
        let mut l =
            Learner::from_checkpoint(saved, PendulumCart::default()).map_err(Refused::Learner)?;
        for x in inputs(3, 20) {
            if let Ok(df) = l.query(LearnerInput::new(x[0], x[1], x[2])) {
                assert!(df.is_finite(), "{name}: offset {df}");
            }
        }
        let step = StepOutcome {
            theta_e: -0.01,
            theta_e_dot: 0.05,
            f_e: 0.02,
            f_r: 0.0,
        };
        let _ = l.touch_down(&step);
        Ok(())
    } else {
        let a = AnyApproximator::from_json(text).map_err(Refused::File)?;
        assert_valid(name, &a);
        let mut y = vec![0.0; a.output_dim()];
        for x in inputs(3, 20) {
            let x = &x[..a.input_dim().min(3)];
            if a.predict(x, &mut y).is_ok() {
                assert!(y.iter().all(|v| v.is_finite()), "{name}: predicts {y:?}");
            }
        }
        Ok(())
    }
}

/// Values that break loaders: sizes that overflow or exhaust memory, signs, extremes.
const HOSTILE: &[&str] = &[
    "0",
    "1",
    "2",
    "3",
    "-1",
    "0.5",
    "1e6",
    "1e9",
    "2147483648",
    "4294967296",
    "4294967297",
    "9007199254740993",
    "18446744073709551615",
    "-9223372036854775808",
    "1e300",
    "-1e300",
    "1e-320",
    "null",
    "true",
    "\"x\"",
    "[]",
    "{}",
];

#[derive(Debug, Clone)]
enum Mutation {
    /// Replace the `i`-th leaf (number, bool, null, string) by a hostile value.
    Leaf(usize, usize),
    /// Replace the `i`-th integer (counts, sizes, dimensions) by a hostile value.
    Integer(usize, usize),
    /// Remove the last element of the `i`-th array.
    Pop(usize),
    /// Append a copy of the first element to the `i`-th array.
    Push(usize),
    /// Remove a key of the `i`-th object.
    DropKey(usize, usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        3 => (any::<usize>(), 0..HOSTILE.len()).prop_map(|(i, h)| Mutation::Leaf(i, h)),
        3 => (any::<usize>(), 0..HOSTILE.len()).prop_map(|(i, h)| Mutation::Integer(i, h)),
        1 => any::<usize>().prop_map(Mutation::Pop),
        1 => any::<usize>().prop_map(Mutation::Push),
        1 => (any::<usize>(), any::<usize>()).prop_map(|(i, k)| Mutation::DropKey(i, k)),
    ]
}

/// JSON pointers to the nodes of a document by kind, in a fixed order.
#[derive(Default)]
struct Nodes {
    leaves: Vec<String>,
    integers: Vec<String>,
    arrays: Vec<String>,
    objects: Vec<String>,
}

/// Collects the nodes of `v` (at JSON pointer `at`) into `nodes_of`.
fn nodes(v: &Value, at: &str, nodes_of: &mut Nodes) {
    match v {
        Value::Array(items) => {
            nodes_of.arrays.push(at.to_string());
            for (i, item) in items.iter().enumerate() {
                nodes(item, &format!("{at}/{i}"), nodes_of);
            }
        }
        Value::Object(map) => {
            nodes_of.objects.push(at.to_string());
            for (k, item) in map {
                let key = k.replace('~', "~0").replace('/', "~1");
                nodes(item, &format!("{at}/{key}"), nodes_of);
            }
        }
        _ => {
            if v.is_u64() || v.is_i64() {
                nodes_of.integers.push(at.to_string());
            }
            nodes_of.leaves.push(at.to_string())
        }
    }
}

/// Applies one mutation (picking nodes by index modulo their count).
fn mutate(v: &mut Value, m: &Mutation) {
    let mut all = Nodes::default();
    nodes(v, "", &mut all);
    let Nodes {
        leaves,
        integers,
        arrays,
        objects,
    } = all;
    let pick = |list: &[String], i: usize| (!list.is_empty()).then(|| list[i % list.len()].clone());
    match *m {
        Mutation::Leaf(i, h) => {
            if let Some(node) = pick(&leaves, i).and_then(|p| v.pointer_mut(&p)) {
                *node = serde_json::from_str(HOSTILE[h]).unwrap();
            }
        }
        Mutation::Integer(i, h) => {
            if let Some(node) = pick(&integers, i).and_then(|p| v.pointer_mut(&p)) {
                *node = serde_json::from_str(HOSTILE[h]).unwrap();
            }
        }
        Mutation::Pop(i) => {
            if let Some(Value::Array(items)) = pick(&arrays, i).and_then(|p| v.pointer_mut(&p)) {
                items.pop();
            }
        }
        Mutation::Push(i) => {
            if let Some(Value::Array(items)) = pick(&arrays, i).and_then(|p| v.pointer_mut(&p))
                && let Some(first) = items.first().cloned()
            {
                items.push(first);
            }
        }
        Mutation::DropKey(i, k) => {
            if let Some(Value::Object(map)) = pick(&objects, i).and_then(|p| v.pointer_mut(&p))
                && !map.is_empty()
            {
                let key = map.keys().nth(k % map.len()).cloned().unwrap_or_default();
                map.remove(&key);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn mutated_model_files_load_or_are_refused(
        file in 0..7usize,
        mutations in prop::collection::vec(mutation(), 1..4),
    ) {
        let corpus = committed_corpus();
        let (name, text) = &corpus[file % corpus.len()];
        let mut v: Value = serde_json::from_str(text).unwrap();
        for m in &mutations {
            mutate(&mut v, m);
        }
        // Either refused with the loader's typed error, or loaded as a valid model (checked
        // inside `load`): a changed number can describe another valid model.
        if let Err(refused) = load(name, &v.to_string()) {
            prop_assert!(refused.is_a_refusal_of_the_file(), "{name}: {refused:?}");
        }
    }

    #[test]
    fn files_with_bytes_changed_or_cut_load_or_are_refused(
        file in 0..7usize,
        at in any::<usize>(),
        byte in prop::sample::select(b"0123456789-.e,]}\"x ".to_vec()),
        cut in any::<bool>(),
    ) {
        let corpus = committed_corpus();
        let (name, text) = &corpus[file % corpus.len()];
        let mut bytes = text.clone().into_bytes();
        let i = at % bytes.len();
        if cut {
            bytes.truncate(i);
        } else {
            bytes[i] = byte;
        }
        match load(name, &String::from_utf8_lossy(&bytes)) {
            // A changed byte may still be another valid model (checked inside `load`).
            Ok(()) => prop_assert!(!cut, "{name}: a file cut at byte {i} loaded"),
            // A file cut short is never valid JSON: always refused, as a corrupt file.
            Err(Refused::File(ApproxError::Corrupt(_))) => {}
            Err(refused) => {
                prop_assert!(!cut, "{name} cut at {i}: {refused:?}");
                prop_assert!(refused.is_a_refusal_of_the_file(), "{name}: {refused:?}");
            }
        }
    }
}

/// The hostile files, by hand: sizes that would overflow `n * n` or allocate terabytes.
#[test]
fn files_with_impossible_sizes_are_refused() {
    let lwpr: Value = serde_json::from_str(&trained(ApproxKind::Lwpr).to_json().unwrap()).unwrap();
    for n_in in ["4294967296", "18446744073709551615", "0"] {
        let mut v = lwpr.clone();
        v["config"]["n_in"] = serde_json::from_str(n_in).unwrap();
        let err = AnyApproximator::from_json(&v.to_string()).unwrap_err();
        assert!(err.to_string().contains("n_in"), "n_in = {n_in}: {err}");
    }
    let learner: Value = serde_json::to_value(learner_mid_step(ApproxKind::Grid)).unwrap();
    for samples in ["1099511627776", "18446744073709551615", "1"] {
        let mut v = learner.clone();
        v["config"]["max_samples_per_step"] = serde_json::from_str(samples).unwrap();
        let err = SavedLearner::<AnyApproximator>::from_json(&v.to_string()).unwrap_err();
        assert!(
            err.to_string().contains("max_samples_per_step"),
            "max_samples_per_step = {samples}: {err}"
        );
    }
}

/// Trains a 2-input LWPR with inputs scaled by `sx` (and `norm_in`) and targets by `sy` until
/// the end of the stream or the first refused sample; returns it and the refusal.
fn train_scaled(sx: f64, norm_in: f64, sy: f64) -> (Lwpr, Option<ApproxError>) {
    let mut m = Lwpr::new(LwprConfig::new(2, 1).norm_in(vec![norm_in; 2])).unwrap();
    for (x, y) in stream(4, 300, 2, 1) {
        if let Err(e) = m.update(&[x[0] * sx, x[1] * sx], &[y[0] * sy]) {
            return (m, Some(e));
        }
    }
    (m, None)
}

/// LWPR trained on inputs and targets of growing magnitude either keeps its model within what
/// loading accepts (and then loads again bit for bit) or refuses the sample with `OutOfRange`
/// exactly when a normalised value is beyond its documented range; it never saves a file its
/// own load refuses. With inputs normalised, it learns huge targets as it learns small ones
/// (no silent 0).
#[test]
fn lwpr_trained_on_huge_values_saves_what_loads_or_refuses_the_sample() {
    for (x_exp, normalised) in [
        (0, false),
        (10, false),
        (15, false),
        (16, false),
        (30, false),
        (30, true),
    ] {
        for y_exp in [0, 10, 20, 21, 30, 60, 100, 160, 300] {
            let (sx, sy) = (10f64.powi(x_exp), 10f64.powi(y_exp));
            let norm_in = if normalised { sx } else { 1.0 };
            let what = format!("inputs 1e{x_exp} (norm {norm_in:e}), targets 1e{y_exp}");
            let (m, refused) = train_scaled(sx, norm_in, sy);
            let json = m
                .to_json()
                .unwrap_or_else(|e| panic!("{what}: save failed: {e}"));
            let back = Lwpr::from_json(&json).unwrap_or_else(|e| panic!("{what}: reload: {e}"));
            assert_eq!(back.to_json().unwrap(), json, "{what}: not bit for bit");
            let beyond =
                (sx / norm_in).log10() > MAX_INPUT.log10() || y_exp as f64 > MAX_TARGET.log10();
            match &refused {
                Some(e) => {
                    assert!(beyond, "{what}: refused within range: {e}");
                    assert!(matches!(e, ApproxError::OutOfRange { .. }), "{what}: {e}");
                }
                None => assert!(!beyond, "{what}: accepted beyond the range"),
            }
            if normalised && refused.is_none() {
                // The same problem as at scale 1 (up to the parts of LWPR that are not scale
                // invariant, such as its penalty): about the same prediction, scaled.
                let (unit, _) = train_scaled(1.0, 1.0, 1.0);
                let (mut y, mut y1) = ([0.0], [0.0]);
                m.predict(&[0.3 * sx, -0.2 * sx], &mut y).unwrap();
                unit.predict(&[0.3, -0.2], &mut y1).unwrap();
                let ratio = y[0] / (y1[0] * sy);
                assert!(
                    ratio > 0.5 && ratio < 2.0,
                    "{what}: predicts {} where scale 1 predicts {}",
                    y[0],
                    y1[0]
                );
            }
        }
    }
}
