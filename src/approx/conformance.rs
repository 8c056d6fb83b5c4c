//! A public check suite every [`FunctionApproximator`] should pass (river's idea: one shared
//! suite, run against every model, including ones written outside this crate).
//!
//! [`check_approximator`] runs the contract checks: bad input rejected with a typed error and the
//! model bit-identical afterwards, no panic on wrong lengths or non-finite numbers,
//! deterministic predictions, predictions that depend on the input after training on
//! input-dependent data, exact save/load, identical learning after a round trip, same data
//! same model, and truncated saved models, wrong sizes and non-finite values refused without
//! a panic (what a changed value that still describes a valid model cannot be told from: see
//! docs/approximators.md). Inputs are drawn
//! from `[-1, 1]^input_dim`. [`check_learns`] adds a quality check on a smooth target.
//!
//! ```
//! use steplearn::approx::conformance::check_approximator;
//! use steplearn::approx::{Grid, GridConfig, InputBox};
//! check_approximator(|| {
//!     Grid::new(GridConfig::new(InputBox::cube(2, -1.0, 1.0).unwrap(), vec![5, 5], 1)).unwrap()
//! })
//! .unwrap();
//! ```

use super::{ApproxError, FunctionApproximator, Persist};
use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;
use thiserror::Error;

/// A failed conformance check: which check, and why.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("conformance check `{check}` failed: {reason}")]
pub struct ConformanceError {
    /// The check's name, one of [`CHECKS`] or `"learns"`.
    pub check: &'static str,
    /// What went wrong.
    pub reason: String,
}

/// The names of the checks [`check_approximator`] runs, in order.
pub const CHECKS: &[&str] = &[
    "dimensions",
    "predict_deterministic",
    "untrained_predictions_finite",
    "predictions_depend_on_input",
    "bad_input_rejected",
    "save_load_exact",
    "learning_after_round_trip",
    "same_data_same_model",
    "corrupt_saved_model_rejected",
    "failed_save_harmless",
];

fn fail(check: &'static str, reason: impl Into<String>) -> ConformanceError {
    ConformanceError {
        check,
        reason: reason.into(),
    }
}

/// Runs `f`, turning a panic into an error of `check`.
fn no_panic<T>(
    check: &'static str,
    what: &str,
    f: impl FnOnce() -> T,
) -> Result<T, ConformanceError> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|_| fail(check, format!("{what} panicked")))
}

/// Runs every contract check on fresh models built by `make` (each call must return an equal,
/// untrained model). Returns the first failure.
pub fn check_approximator<A, F>(make: F) -> Result<(), ConformanceError>
where
    A: FunctionApproximator + Persist + Clone,
    F: Fn() -> A,
{
    let make = || no_panic("dimensions", "make()", &make);
    let (d, n_out) = dimensions(&make()?, &make()?)?;
    let ctx = Ctx { d, n_out };
    predict_deterministic(&ctx, make()?)?;
    untrained_predictions_finite(&ctx, &make()?)?;
    predictions_depend_on_input(&ctx, make()?)?;
    bad_input_rejected(&ctx, make()?)?;
    let (m, loaded) = save_load_exact(&ctx, make()?)?;
    learning_after_round_trip(&ctx, m, loaded)?;
    same_data_same_model(&ctx, make()?, make()?)?;
    corrupt_saved_model_rejected(&ctx, make()?)?;
    failed_save_harmless(&ctx, make()?)
}

/// Checks that a model built by `make` reaches a normalised mean squared error below
/// `max_nmse` on a probe grid over `[-1, 1]^input_dim` after `samples` noisy samples of
/// [`target`] (check name `"learns"`).
pub fn check_learns<A, F>(make: F, samples: usize, max_nmse: f64) -> Result<(), ConformanceError>
where
    A: FunctionApproximator,
    F: Fn() -> A,
{
    const CHECK: &str = "learns";
    let mut m = no_panic(CHECK, "make()", make)?;
    let ctx = Ctx {
        d: m.input_dim(),
        n_out: m.output_dim(),
    };
    train(CHECK, &mut m, &stream(1, samples, ctx.d, ctx.n_out))?;
    let e = nmse(&m).map_err(|e| fail(CHECK, format!("prediction failed: {e}")))?;
    if e.is_nan() || e >= max_nmse {
        return Err(fail(
            CHECK,
            format!("nMSE {e} after {samples} samples, want < {max_nmse}"),
        ));
    }
    Ok(())
}

/// A smooth target with `n_out` outputs over any number of inputs (missing inputs count as 0).
pub fn target(x: &[f64], n_out: usize) -> Vec<f64> {
    let x0 = x.first().copied().unwrap_or(0.0);
    let x1 = x.get(1).copied().unwrap_or(0.0);
    let rest: f64 = x.iter().skip(2).map(|v| 0.1 * v).sum();
    (0..n_out)
        .map(|k| 0.5 * x0 - 0.3 * x1 + 0.2 * (k as f64) * x0 * x1 + 0.1 * k as f64 + rest)
        .collect()
}

/// A seeded stream of `n` samples of [`target`] at uniform inputs in `[-1, 1]^d`, plus uniform
/// noise of +-0.01.
pub fn stream(seed: u64, n: usize, d: usize, n_out: usize) -> Vec<(Vec<f64>, Vec<f64>)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let x: Vec<f64> = (0..d).map(|_| rng.random_range(-1.0..1.0)).collect();
            let mut y = target(&x, n_out);
            for v in &mut y {
                *v += rng.random_range(-0.01..0.01);
            }
            (x, y)
        })
        .collect()
}

/// Probe inputs in `[-1, 1]^d`: a regular grid of about 121 points (11 x 11 for `d = 2`), or 128
/// seeded uniform points when `d` is too large for a grid of 2 points per input.
pub fn probe_points(d: usize) -> Vec<Vec<f64>> {
    let per = (121f64.powf(1.0 / d.max(1) as f64) + 1e-9).floor() as usize;
    if per < 2 {
        return stream(99, 128, d, 0).into_iter().map(|(x, _)| x).collect();
    }
    let total = per.pow(d as u32);
    (0..total)
        .map(|mut idx| {
            (0..d)
                .map(|_| {
                    let i = idx % per;
                    idx /= per;
                    -1.0 + 2.0 * i as f64 / (per - 1) as f64
                })
                .collect()
        })
        .collect()
}

/// Normalised mean squared error of `model` against [`target`] on [`probe_points`].
pub fn nmse<A: FunctionApproximator + ?Sized>(model: &A) -> Result<f64, ApproxError> {
    let n_out = model.output_dim();
    let pts = probe_points(model.input_dim());
    let pred = predictions(model, &pts)?;
    let truth: Vec<f64> = pts.iter().flat_map(|x| target(x, n_out)).collect();
    let mean = truth.iter().sum::<f64>() / truth.len() as f64;
    let var = truth.iter().map(|t| (t - mean).powi(2)).sum::<f64>() / truth.len() as f64;
    let mse = pred
        .iter()
        .zip(&truth)
        .map(|(p, t)| (p - t).powi(2))
        .sum::<f64>()
        / truth.len() as f64;
    Ok(mse / var.max(f64::MIN_POSITIVE))
}

struct Ctx {
    d: usize,
    n_out: usize,
}

impl Ctx {
    fn stream(&self, seed: u64, n: usize) -> Vec<(Vec<f64>, Vec<f64>)> {
        stream(seed, n, self.d, self.n_out)
    }
}

fn predictions<A: FunctionApproximator + ?Sized>(
    model: &A,
    pts: &[Vec<f64>],
) -> Result<Vec<f64>, ApproxError> {
    let mut out = Vec::with_capacity(pts.len() * model.output_dim());
    let mut y = vec![0.0; model.output_dim()];
    for x in pts {
        model.predict(x, &mut y)?;
        out.extend_from_slice(&y);
    }
    Ok(out)
}

/// The model's predictions over the probe set, as bit patterns (a panic or error is a failure
/// of `check`).
fn fingerprint<A: FunctionApproximator>(
    check: &'static str,
    model: &A,
) -> Result<Vec<u64>, ConformanceError> {
    let pts = probe_points(model.input_dim());
    no_panic(check, "predict", || predictions(model, &pts))?
        .map(|p| p.iter().map(|v| v.to_bits()).collect())
        .map_err(|e| fail(check, format!("valid query rejected: {e}")))
}

/// Saved bytes plus predictions: equal snapshots mean bit-identical models.
fn snapshot<A: FunctionApproximator + Persist>(
    check: &'static str,
    model: &A,
) -> Result<(String, Vec<u64>), ConformanceError> {
    let json = no_panic(check, "to_json", || model.to_json())?
        .map_err(|e| fail(check, format!("to_json failed: {e}")))?;
    Ok((json, fingerprint(check, model)?))
}

fn train<A: FunctionApproximator>(
    check: &'static str,
    model: &mut A,
    data: &[(Vec<f64>, Vec<f64>)],
) -> Result<(), ConformanceError> {
    for (i, (x, y)) in data.iter().enumerate() {
        no_panic(check, "update", || model.update(x, y))?
            .map_err(|e| fail(check, format!("valid sample {i} rejected: {e}")))?;
    }
    Ok(())
}

fn dimensions<A: FunctionApproximator>(a: &A, b: &A) -> Result<(usize, usize), ConformanceError> {
    const CHECK: &str = "dimensions";
    let (d, n_out) = (a.input_dim(), a.output_dim());
    if d == 0 || n_out == 0 {
        return Err(fail(
            CHECK,
            format!("input_dim {d}, output_dim {n_out}: both must be >= 1"),
        ));
    }
    if (b.input_dim(), b.output_dim()) != (d, n_out) {
        return Err(fail(
            CHECK,
            "two models from make() differ in their dimensions",
        ));
    }
    Ok((d, n_out))
}

fn predict_deterministic<A: FunctionApproximator>(
    ctx: &Ctx,
    mut m: A,
) -> Result<(), ConformanceError> {
    const CHECK: &str = "predict_deterministic";
    train(CHECK, &mut m, &ctx.stream(6, 200))?;
    if fingerprint(CHECK, &m)? != fingerprint(CHECK, &m)? {
        return Err(fail(CHECK, "two predictions at the same inputs differ"));
    }
    Ok(())
}

fn untrained_predictions_finite<A: FunctionApproximator>(
    _ctx: &Ctx,
    m: &A,
) -> Result<(), ConformanceError> {
    const CHECK: &str = "untrained_predictions_finite";
    if fingerprint(CHECK, m)?
        .iter()
        .any(|b| !f64::from_bits(*b).is_finite())
    {
        return Err(fail(
            CHECK,
            "an untrained model predicts a non-finite value",
        ));
    }
    Ok(())
}

/// The smallest spread of a trained model's predictions over the probe points, as a share of
/// the spread of [`target`] there, that counts as depending on the input.
const MIN_INPUT_DEPENDENCE: f64 = 0.01;

/// After training on [`target`] (which depends on the first input with slope 0.5), the
/// predictions over the probe points must spread by at least [`MIN_INPUT_DEPENDENCE`] of the
/// target's own spread in some output: a `predict` that ignores its input (a running mean,
/// a constant, a model that reads the wrong slice) fails here.
fn predictions_depend_on_input<A: FunctionApproximator>(
    ctx: &Ctx,
    mut m: A,
) -> Result<(), ConformanceError> {
    const CHECK: &str = "predictions_depend_on_input";
    train(CHECK, &mut m, &ctx.stream(7, 500))?;
    let pts = probe_points(ctx.d);
    let pred: Vec<f64> = fingerprint(CHECK, &m)?
        .into_iter()
        .map(f64::from_bits)
        .collect();
    let truth: Vec<f64> = pts.iter().flat_map(|x| target(x, ctx.n_out)).collect();
    let spread = |v: &[f64], k: usize| {
        let (lo, hi) = v
            .iter()
            .skip(k)
            .step_by(ctx.n_out)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &y| {
                (lo.min(y), hi.max(y))
            });
        hi - lo
    };
    let depends = (0..ctx.n_out).any(|k| {
        let (got, want) = (spread(&pred, k), spread(&truth, k));
        got.is_finite() && got >= MIN_INPUT_DEPENDENCE * want
    });
    if !depends {
        return Err(fail(
            CHECK,
            format!(
                "after 500 samples of an input-dependent target, the predictions over {} probe \
                 points do not depend on the input (spread below {MIN_INPUT_DEPENDENCE} of the \
                 target's in every output)",
                pts.len()
            ),
        ));
    }
    Ok(())
}

fn bad_input_rejected<A: FunctionApproximator + Persist>(
    ctx: &Ctx,
    mut m: A,
) -> Result<(), ConformanceError> {
    const CHECK: &str = "bad_input_rejected";
    let (d, n_out) = (ctx.d, ctx.n_out);
    train(CHECK, &mut m, &ctx.stream(4, 300))?;
    let before = snapshot(CHECK, &m)?;
    let good_x = vec![0.1; d];
    let good_y = vec![0.1; n_out];
    let with = |v: &[f64], i: usize, value: f64| {
        let mut v = v.to_vec();
        v[i] = value;
        v
    };
    // (x, y, is a length error)
    let mut bad: Vec<(Vec<f64>, Vec<f64>, bool)> = vec![
        (vec![0.1; d - 1], good_y.clone(), true),
        (vec![0.1; d + 1], good_y.clone(), true),
        (vec![], good_y.clone(), true),
        (good_x.clone(), vec![0.1; n_out + 1], true),
        (good_x.clone(), vec![0.1; n_out - 1], true),
    ];
    for value in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        bad.push((with(&good_x, 0, value), good_y.clone(), false));
        bad.push((with(&good_x, d - 1, value), good_y.clone(), false));
        bad.push((good_x.clone(), with(&good_y, 0, value), false));
        bad.push((good_x.clone(), with(&good_y, n_out - 1, value), false));
    }
    for (x, y, length_error) in &bad {
        let r = no_panic(CHECK, &format!("update({x:?}, {y:?})"), || m.update(x, y))?;
        let typed = match r {
            Err(ApproxError::DimensionMismatch { .. }) => *length_error,
            Err(ApproxError::NonFinite { .. }) => !*length_error,
            _ => false,
        };
        if !typed {
            let want = if *length_error {
                "DimensionMismatch"
            } else {
                "NonFinite"
            };
            return Err(fail(
                CHECK,
                format!("update({x:?}, {y:?}) gave {r:?}, want {want}"),
            ));
        }
        if snapshot(CHECK, &m)? != before {
            return Err(fail(
                CHECK,
                format!("rejected update({x:?}, {y:?}) changed the model"),
            ));
        }
    }
    let mut out = vec![0.0; n_out];
    let bad_queries: Vec<(Vec<f64>, usize)> = vec![
        (vec![0.1; d - 1], n_out),
        (vec![0.1; d + 1], n_out),
        (with(&good_x, 0, f64::NAN), n_out),
        (with(&good_x, d - 1, f64::INFINITY), n_out),
        (good_x.clone(), n_out + 1),
        (good_x.clone(), n_out - 1),
    ];
    for (x, len) in &bad_queries {
        out.resize(*len, 0.0);
        let r = no_panic(CHECK, &format!("predict({x:?}) into {len} outputs"), || {
            m.predict(x, &mut out)
        })?;
        if !matches!(
            r,
            Err(ApproxError::DimensionMismatch { .. } | ApproxError::NonFinite { .. })
        ) {
            return Err(fail(
                CHECK,
                format!("predict({x:?}) into {len} outputs gave {r:?}"),
            ));
        }
    }
    if snapshot(CHECK, &m)? != before {
        return Err(fail(CHECK, "a rejected query changed the model"));
    }
    Ok(())
}

fn save_load_exact<A: FunctionApproximator + Persist + Clone>(
    ctx: &Ctx,
    mut m: A,
) -> Result<(A, A), ConformanceError> {
    const CHECK: &str = "save_load_exact";
    train(CHECK, &mut m, &ctx.stream(2, 500))?;
    let original = snapshot(CHECK, &m)?;
    let loaded = no_panic(CHECK, "from_json", || A::from_json(&original.0))?
        .map_err(|e| fail(CHECK, format!("from_json of a saved model failed: {e}")))?;
    if snapshot(CHECK, &loaded)? != original {
        return Err(fail(
            CHECK,
            "the model loaded from JSON differs from the saved one",
        ));
    }
    if snapshot(CHECK, &m.clone())? != original {
        return Err(fail(CHECK, "a clone differs from the original"));
    }
    let tmp = tempdir(CHECK)?;
    let path = tmp.path().join("model.json");
    no_panic(CHECK, "save", || m.save(&path))?
        .map_err(|e| fail(CHECK, format!("save failed: {e}")))?;
    let from_file = no_panic(CHECK, "load", || A::load(&path))?
        .map_err(|e| fail(CHECK, format!("load of a saved file failed: {e}")))?;
    if snapshot(CHECK, &from_file)? != original {
        return Err(fail(
            CHECK,
            "the model loaded from a file differs from the saved one",
        ));
    }
    Ok((m, loaded))
}

fn learning_after_round_trip<A: FunctionApproximator + Persist + Clone>(
    ctx: &Ctx,
    mut m: A,
    mut loaded: A,
) -> Result<(), ConformanceError> {
    const CHECK: &str = "learning_after_round_trip";
    let mut cloned = m.clone();
    let data = ctx.stream(2, 600);
    train(CHECK, &mut m, &data[500..])?;
    train(CHECK, &mut loaded, &data[500..])?;
    train(CHECK, &mut cloned, &data[500..])?;
    let want = snapshot(CHECK, &m)?;
    if snapshot(CHECK, &loaded)? != want {
        return Err(fail(
            CHECK,
            "a loaded copy learns differently from the original",
        ));
    }
    if snapshot(CHECK, &cloned)? != want {
        return Err(fail(CHECK, "a clone learns differently from the original"));
    }
    Ok(())
}

fn same_data_same_model<A: FunctionApproximator + Persist>(
    ctx: &Ctx,
    mut a: A,
    mut b: A,
) -> Result<(), ConformanceError> {
    const CHECK: &str = "same_data_same_model";
    let data = ctx.stream(3, 800);
    train(CHECK, &mut a, &data)?;
    train(CHECK, &mut b, &data)?;
    if snapshot(CHECK, &a)? != snapshot(CHECK, &b)? {
        return Err(fail(CHECK, "two fresh models fed the same stream differ"));
    }
    Ok(())
}

fn corrupt_saved_model_rejected<A: FunctionApproximator + Persist>(
    ctx: &Ctx,
    mut m: A,
) -> Result<(), ConformanceError> {
    const CHECK: &str = "corrupt_saved_model_rejected";
    train(CHECK, &mut m, &ctx.stream(5, 300))?;
    let (json, _) = snapshot(CHECK, &m)?;
    let from_json =
        |text: &str| no_panic(CHECK, "from_json of a corrupt model", || A::from_json(text));
    // Truncated text, in memory and on disk, is a `Corrupt` error.
    let tmp = tempdir(CHECK)?;
    let path = tmp.path().join("truncated.json");
    for cut in [
        0,
        1,
        json.len() / 4,
        json.len() / 2,
        json.len().saturating_sub(1),
    ] {
        let Some(text) = json.get(..cut) else {
            continue;
        };
        match from_json(text)? {
            Err(ApproxError::Corrupt(_)) => {}
            r => {
                return Err(fail(
                    CHECK,
                    format!(
                        "JSON truncated to {cut} of {} bytes gave {:?}",
                        json.len(),
                        r.err()
                    ),
                ));
            }
        }
        std::fs::write(&path, text).map_err(|e| fail(CHECK, format!("cannot write: {e}")))?;
        if no_panic(CHECK, "load of a truncated file", || A::load(&path))?.is_ok() {
            return Err(fail(
                CHECK,
                format!("a file truncated to {cut} bytes loaded"),
            ));
        }
    }
    for foreign in ["{\"hello\": 1}", "[1, 2, 3]", "null"] {
        if from_json(foreign)?.is_ok() {
            return Err(fail(CHECK, format!("foreign JSON {foreign} loaded")));
        }
    }
    if no_panic(CHECK, "load of a missing file", || {
        A::load(tmp.path().join("missing.json"))
    })?
    .is_ok()
    {
        return Err(fail(CHECK, "a missing file loaded"));
    }

    // Tampering with any numeric array must never panic: either an error, or a model that
    // still answers with finite numbers.
    let value: serde_json::Value = serde_json::from_str(&json)
        .map_err(|e| fail(CHECK, format!("saved JSON unparsable: {e}")))?;
    let mut paths = Vec::new();
    numeric_arrays(&value, &mut Vec::new(), &mut paths);
    let mut integers = Vec::new();
    integer_fields(&value, &mut Vec::new(), &mut integers);
    let arrays = paths
        .iter()
        .take(40)
        .flat_map(|p| [(p, Tamper::DropLast), (p, Tamper::Huge)]);
    // Sizes, counts and dimensions: zero, beyond 32 bits, and the largest integer.
    let fields = integers.iter().take(40).flat_map(|p| {
        [0, 1 << 32, u64::MAX]
            .into_iter()
            .map(move |n| (p, Tamper::Integer(n)))
    });
    for (path, tamper) in arrays.chain(fields) {
        let mut v = value.clone();
        apply(&mut v, path, tamper);
        let text = v.to_string();
        let what = format!("a model tampered with ({tamper:?} at {path:?})");
        if let Ok(loaded) = from_json(&text)? {
            let pts = probe_points(ctx.d);
            let mut y = vec![0.0; ctx.n_out];
            for x in &pts {
                let r = no_panic(CHECK, &format!("predict on {what}"), || {
                    loaded.predict(x, &mut y)
                })?;
                if r.is_ok() && y.iter().any(|v| !v.is_finite()) {
                    return Err(fail(
                        CHECK,
                        format!("{what} loaded and predicts non-finite values"),
                    ));
                }
            }
        }
    }
    Ok(())
}

fn failed_save_harmless<A: FunctionApproximator + Persist>(
    ctx: &Ctx,
    mut m: A,
) -> Result<(), ConformanceError> {
    const CHECK: &str = "failed_save_harmless";
    let tmp = tempdir(CHECK)?;
    let dir = tmp.path();
    // A save into a missing directory fails and creates nothing.
    let missing = dir.join("missing-dir");
    if no_panic(CHECK, "save", || m.save(missing.join("m.json")))?.is_ok() {
        return Err(fail(CHECK, "a save into a missing directory succeeded"));
    }
    if missing.exists() {
        return Err(fail(CHECK, "a failed save created its directory"));
    }
    // A save whose final step fails (here the name is taken by a non-empty directory, so the
    // written model cannot be renamed over it) leaves what was there intact and no temporary
    // file behind.
    let path = dir.join("model.json");
    std::fs::create_dir(&path)
        .and_then(|()| std::fs::write(path.join("keep"), b"kept"))
        .map_err(|e| fail(CHECK, format!("cannot create a directory: {e}")))?;
    let before = entries(dir)?;
    if no_panic(CHECK, "save", || m.save(&path))?.is_ok() {
        return Err(fail(CHECK, "a save over a non-empty directory succeeded"));
    }
    if read(&path.join("keep"))? != b"kept" || entries(dir)? != before {
        return Err(fail(
            CHECK,
            "a failed save changed what was there or left a temporary file",
        ));
    }
    // A save over an existing model replaces it whole.
    let path = dir.join("model2.json");
    no_panic(CHECK, "save", || m.save(&path))?
        .map_err(|e| fail(CHECK, format!("save failed: {e}")))?;
    train(CHECK, &mut m, &ctx.stream(7, 50))?;
    no_panic(CHECK, "save", || m.save(&path))?
        .map_err(|e| fail(CHECK, format!("save over a model failed: {e}")))?;
    if no_panic(CHECK, "load", || A::load(&path))?.is_err() {
        return Err(fail(
            CHECK,
            "after a save over an existing file, the file does not load",
        ));
    }
    Ok(())
}

/// The names in `dir`, sorted.
fn entries(dir: &Path) -> Result<Vec<String>, ConformanceError> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .map_err(|e| fail("failed_save_harmless", format!("cannot list {dir:?}: {e}")))?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    Ok(names)
}

fn read(path: &Path) -> Result<Vec<u8>, ConformanceError> {
    std::fs::read(path)
        .map_err(|e| fail("failed_save_harmless", format!("cannot read {path:?}: {e}")))
}

fn tempdir(check: &'static str) -> Result<tempfile::TempDir, ConformanceError> {
    tempfile::Builder::new()
        .prefix("steplearn-conformance-")
        .tempdir()
        .map_err(|e| fail(check, format!("cannot create a temporary directory: {e}")))
}

#[derive(Debug, Clone, Copy)]
enum Tamper {
    DropLast,
    Huge,
    Integer(u64),
}

/// The paths of the integer fields (not array elements) of `v`.
fn integer_fields(v: &serde_json::Value, at: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    match v {
        serde_json::Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                if !item.is_number() {
                    at.push(i.to_string());
                    integer_fields(item, at, out);
                    at.pop();
                }
            }
        }
        serde_json::Value::Object(map) => {
            for (k, item) in map {
                at.push(k.clone());
                if item.is_u64() {
                    out.push(at.clone());
                } else {
                    integer_fields(item, at, out);
                }
                at.pop();
            }
        }
        _ => {}
    }
}

fn numeric_arrays(v: &serde_json::Value, at: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    match v {
        serde_json::Value::Array(items) => {
            if !items.is_empty() && items.iter().all(|i| i.is_number()) {
                out.push(at.clone());
            } else {
                for (i, item) in items.iter().enumerate() {
                    at.push(i.to_string());
                    numeric_arrays(item, at, out);
                    at.pop();
                }
            }
        }
        serde_json::Value::Object(map) => {
            for (k, item) in map {
                at.push(k.clone());
                numeric_arrays(item, at, out);
                at.pop();
            }
        }
        _ => {}
    }
}

fn apply(v: &mut serde_json::Value, path: &[String], tamper: Tamper) {
    let mut cur = Some(v);
    for key in path {
        cur = match cur {
            Some(serde_json::Value::Array(items)) => {
                key.parse::<usize>().ok().and_then(|i| items.get_mut(i))
            }
            Some(serde_json::Value::Object(map)) => map.get_mut(key),
            _ => None,
        };
    }
    if let (Some(field), Tamper::Integer(n)) = (&mut cur, tamper) {
        **field = serde_json::json!(n);
        return;
    }
    if let Some(serde_json::Value::Array(items)) = cur {
        match tamper {
            Tamper::DropLast => {
                items.pop();
            }
            Tamper::Huge => {
                if let Some(first) = items.first_mut() {
                    *first = serde_json::json!(1e308);
                }
            }
            Tamper::Integer(_) => {}
        }
    }
}
