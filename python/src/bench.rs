//! The bench from Python: a [`Registry`] that takes Python factories, and the Rust [`Bench`]
//! run with the GIL released.
//!
//! A Python approximator is wrapped as [`BenchApprox::Python`] and a Python rule as
//! [`PyRule`]; both call the Python object under the GIL from the bench's worker threads. A
//! factory that returns one of the package's own classes (`steplearn.Lwpr`, ...) gives the
//! Rust model itself ([`BenchApprox::Native`]), so that it runs with no Python call per tick.
//! Every exception of a Python callback becomes an error of the run (an
//! [`ApproxError::External`] naming the exception's type and message, or a
//! NaN gradient that the learner refuses) and is recorded, so that [`PyBench::run`] raises it
//! with the Python message: nothing is swallowed, nothing panics.

use crate::arrays;
use crate::model::{self, py_err};
use numpy::PyArray1;
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use serde::de::Error as _;
use serde::ser::{Error as _, SerializeStruct};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use steplearn::approx::{
    self as rs, AnyApproximator, ApproxError, FunctionApproximator, InputBox, Persist,
    check_output, check_vector,
};
use steplearn::bench::{Bench, BenchError, Registry};
use steplearn::control::LearnSet;
use steplearn::experiments::config_file::ConfigFile;
use steplearn::experiments::sweep::{RunOutcome, RunStatus, Shard, SweepError};
use steplearn::rules::{LearningRule, StepOutcome};

/// The most Python errors a registry keeps for one run (the first ones, without repeats).
const MAX_RECORDED: usize = 8;

/// The exceptions raised by a registry's Python callbacks during a run, shared by its
/// factories and the objects they build.
#[derive(Clone, Default)]
struct Errors(Arc<Mutex<Vec<String>>>);

impl Errors {
    fn record(&self, message: String) {
        let mut v = self.0.lock().unwrap_or_else(|p| p.into_inner());
        if v.len() < MAX_RECORDED && !v.contains(&message) {
            v.push(message);
        }
    }

    fn take(&self) -> Vec<String> {
        std::mem::take(&mut *self.0.lock().unwrap_or_else(|p| p.into_inner()))
    }
}

/// An exception of a Python approximator's `what` as an [`ApproxError::External`] that names
/// the exception's type and message (recorded too).
fn approx_error(errors: &Errors, name: &str, what: &str, e: impl std::fmt::Display) -> ApproxError {
    let reason = format!("{name:?}: {what} raised {e}");
    errors.record(format!("approximator {reason}"));
    ApproxError::External(reason)
}

/// The input box an approximator factory receives: the learner's inputs (theta_E,
/// theta_E_dot, F_R), each within `[lo[i], hi[i]]`.
#[pyclass(module = "steplearn", name = "InputBox", frozen)]
pub(crate) struct PyInputBox {
    inner: InputBox,
}

#[pymethods]
impl PyInputBox {
    /// A checked box (`lo[i] < hi[i]`, finite).
    #[new]
    fn new(lo: &Bound<'_, PyAny>, hi: &Bound<'_, PyAny>) -> PyResult<Self> {
        let (lo, hi) = (arrays::vector(lo, "lo")?, arrays::vector(hi, "hi")?);
        InputBox::new(lo, hi)
            .map(|inner| PyInputBox { inner })
            .map_err(py_err)
    }

    /// The lower corner, one value per input.
    #[getter]
    fn lo<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.inner.lo)
    }

    /// The upper corner, one value per input.
    #[getter]
    fn hi<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.inner.hi)
    }

    /// The number of inputs.
    #[getter]
    fn dim(&self) -> usize {
        self.inner.dim()
    }

    fn __repr__(&self) -> String {
        format!("InputBox(lo={:?}, hi={:?})", self.inner.lo, self.inner.hi)
    }
}

/// What a rule's `gradient(outcome)` receives: the step's outcome at touch-down.
#[pyclass(module = "steplearn", name = "StepOutcome", frozen)]
#[derive(Clone, Copy)]
pub(crate) struct PyStepOutcome {
    /// Trunk deviation angle theta_E (rad); positive = leaning forward.
    #[pyo3(get)]
    theta_e: f64,
    /// Its rate (rad/s).
    #[pyo3(get)]
    theta_e_dot: f64,
    /// Step size error F_E = F_hat - F_R (m).
    #[pyo3(get)]
    f_e: f64,
    /// The reference step size F_R (m).
    #[pyo3(get)]
    f_r: f64,
}

#[pymethods]
impl PyStepOutcome {
    /// An outcome (to try a rule by hand).
    #[new]
    #[pyo3(signature = (theta_e = 0.0, theta_e_dot = 0.0, f_e = 0.0, f_r = 0.0))]
    fn new(theta_e: f64, theta_e_dot: f64, f_e: f64, f_r: f64) -> Self {
        PyStepOutcome {
            theta_e,
            theta_e_dot,
            f_e,
            f_r,
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "StepOutcome(theta_e={}, theta_e_dot={}, f_e={}, f_r={})",
            self.theta_e, self.theta_e_dot, self.f_e, self.f_r
        )
    }
}

impl From<&StepOutcome> for PyStepOutcome {
    fn from(s: &StepOutcome) -> Self {
        PyStepOutcome::new(s.theta_e, s.theta_e_dot, s.f_e, s.f_r)
    }
}

/// A Python object with `predict(x)` and `update(x, y)`, called under the GIL.
struct PyModel {
    obj: Py<PyAny>,
    /// The registered name (for messages).
    name: Arc<str>,
    n_in: usize,
    n_out: usize,
    /// Why this copy cannot be used (its `copy.deepcopy` failed), if it cannot.
    broken: Option<String>,
    errors: Errors,
}

impl PyModel {
    fn usable(&self) -> Result<(), ApproxError> {
        match &self.broken {
            Some(why) => Err(approx_error(&self.errors, &self.name, "copy.deepcopy", why)),
            None => Ok(()),
        }
    }
}

impl FunctionApproximator for PyModel {
    fn input_dim(&self) -> usize {
        self.n_in
    }
    fn output_dim(&self) -> usize {
        self.n_out
    }
    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        check_vector("input x", x, self.n_in)?;
        check_output("output y", y, self.n_out)?;
        self.usable()?;
        let v = Python::attach(|py| {
            let x = PyArray1::from_slice(py, x);
            self.obj
                .bind(py)
                .call_method1(intern!(py, "predict"), (x,))
                .and_then(|r| arrays::vector(&r, "prediction"))
                .map_err(|e| approx_error(&self.errors, &self.name, "predict(x)", e))
        })?;
        if v.len() != self.n_out {
            return Err(ApproxError::DimensionMismatch {
                what: "prediction of the Python approximator",
                expected: self.n_out,
                got: v.len(),
            });
        }
        y.copy_from_slice(&v);
        Ok(())
    }
    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        check_vector("input x", x, self.n_in)?;
        check_vector("target y", y, self.n_out)?;
        self.usable()?;
        Python::attach(|py| {
            let (x, y) = (PyArray1::from_slice(py, x), PyArray1::from_slice(py, y));
            self.obj
                .bind(py)
                .call_method1(intern!(py, "update"), (x, y))
                .map(|_| ())
                .map_err(|e| approx_error(&self.errors, &self.name, "update(x, y)", e))
        })
    }
}

impl Clone for PyModel {
    /// A `copy.deepcopy` of the object (the learner trials an update on a copy); a copy that
    /// fails is marked broken and every call on it is an error with the reason.
    fn clone(&self) -> Self {
        Python::attach(|py| {
            let copied = py
                .import(intern!(py, "copy"))
                .and_then(|m| m.call_method1(intern!(py, "deepcopy"), (self.obj.bind(py),)));
            let (obj, broken) = match copied {
                Ok(o) => (o.unbind(), self.broken.clone()),
                Err(e) => (self.obj.clone_ref(py), Some(e.to_string())),
            };
            PyModel {
                obj,
                name: self.name.clone(),
                n_in: self.n_in,
                n_out: self.n_out,
                broken,
                errors: self.errors.clone(),
            }
        })
    }
}

/// The pickle protocol of a saved Python approximator (fixed, so that its fingerprint does not
/// change with Python's default).
const PICKLE_PROTOCOL: u8 = 4;

impl Serialize for PyModel {
    /// `{"python_pickle": hex of pickle.dumps(obj), "name", "n_in", "n_out"}`.
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let bytes = Python::attach(|py| -> PyResult<Vec<u8>> {
            let b = py
                .import(intern!(py, "pickle"))?
                .call_method1(intern!(py, "dumps"), (self.obj.bind(py), PICKLE_PROTOCOL))?;
            Ok(b.cast::<PyBytes>()?.as_bytes().to_vec())
        })
        .map_err(|e| {
            S::Error::custom(format!(
                "the Python approximator {:?} cannot be pickled ({e}); the bench fingerprints a \
                 fresh model by its pickle, so define its class at module level or give it \
                 __getstate__/__reduce__",
                self.name
            ))
        })?;
        let hex: String = bytes.iter().map(|b| format!("{b:02x}")).collect();
        let mut st = s.serialize_struct("PythonApproximator", 4)?;
        st.serialize_field("python_pickle", &hex)?;
        st.serialize_field("name", &*self.name)?;
        st.serialize_field("n_in", &self.n_in)?;
        st.serialize_field("n_out", &self.n_out)?;
        st.end()
    }
}

/// A bench approximator: a Rust model (from one of the package's classes) or a Python object.
enum BenchApprox {
    /// One of the crate's approximators, run with no Python call.
    Native(Box<AnyApproximator>),
    /// A Python object with `predict` and `update`.
    Python(PyModel),
}

impl Clone for BenchApprox {
    fn clone(&self) -> Self {
        match self {
            BenchApprox::Native(a) => BenchApprox::Native(a.clone()),
            BenchApprox::Python(m) => BenchApprox::Python(m.clone()),
        }
    }
}

impl FunctionApproximator for BenchApprox {
    fn input_dim(&self) -> usize {
        match self {
            BenchApprox::Native(a) => a.input_dim(),
            BenchApprox::Python(m) => m.input_dim(),
        }
    }
    fn output_dim(&self) -> usize {
        match self {
            BenchApprox::Native(a) => a.output_dim(),
            BenchApprox::Python(m) => m.output_dim(),
        }
    }
    fn predict(&self, x: &[f64], y: &mut [f64]) -> Result<(), ApproxError> {
        match self {
            BenchApprox::Native(a) => a.predict(x, y),
            BenchApprox::Python(m) => m.predict(x, y),
        }
    }
    fn update(&mut self, x: &[f64], y: &[f64]) -> Result<(), ApproxError> {
        match self {
            BenchApprox::Native(a) => a.update(x, y),
            BenchApprox::Python(m) => m.update(x, y),
        }
    }
}

impl Serialize for BenchApprox {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            BenchApprox::Native(a) => a.serialize(s),
            BenchApprox::Python(m) => m.serialize(s),
        }
    }
}

/// Parses the hex of [`PyModel`]'s JSON.
fn unhex(s: &str) -> Option<Vec<u8>> {
    if !s.len().is_multiple_of(2) {
        return None;
    }
    (0..s.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(s.get(i..i + 2)?, 16).ok())
        .collect()
}

impl<'de> Deserialize<'de> for BenchApprox {
    /// A crate model's JSON, or a Python approximator's (unpickled under the GIL).
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = serde_json::Value::deserialize(d)?;
        let Some(pickle) = v.get("python_pickle") else {
            return AnyApproximator::deserialize(v)
                .map(|a| BenchApprox::Native(Box::new(a)))
                .map_err(D::Error::custom);
        };
        let field = |k: &str| {
            v.get(k)
                .ok_or_else(|| D::Error::custom(format!("missing field {k}")))
        };
        let bytes = pickle
            .as_str()
            .and_then(unhex)
            .ok_or_else(|| D::Error::custom("python_pickle is not hex"))?;
        let dim = |k: &str| -> Result<usize, D::Error> {
            field(k)?
                .as_u64()
                .and_then(|n| usize::try_from(n).ok())
                .ok_or_else(|| D::Error::custom(format!("{k} is not a count")))
        };
        let name = field("name")?
            .as_str()
            .ok_or_else(|| D::Error::custom("name is not a string"))?;
        let obj = Python::attach(|py| -> PyResult<Py<PyAny>> {
            let b = PyBytes::new(py, &bytes);
            Ok(py
                .import(intern!(py, "pickle"))?
                .call_method1(intern!(py, "loads"), (b,))?
                .unbind())
        })
        .map_err(|e| D::Error::custom(format!("pickle.loads raised {e}")))?;
        Ok(BenchApprox::Python(PyModel {
            obj,
            name: name.into(),
            n_in: dim("n_in")?,
            n_out: dim("n_out")?,
            broken: None,
            errors: Errors::default(),
        }))
    }
}

impl Persist for BenchApprox {
    fn check_invariants(&self) -> Result<(), ApproxError> {
        match self {
            BenchApprox::Native(a) => a.check_invariants(),
            BenchApprox::Python(m) if m.n_in == 0 || m.n_out == 0 => Err(ApproxError::Corrupt(
                "a Python approximator needs at least one input and one output".into(),
            )),
            BenchApprox::Python(m) => m.usable(),
        }
    }
}

/// The Rust model of one of the package's classes, if `obj` is one (read through its JSON,
/// bit for bit).
fn native(obj: &Bound<'_, PyAny>) -> PyResult<Option<AnyApproximator>> {
    let json = || -> PyResult<String> { obj.call_method0(intern!(obj.py(), "to_json"))?.extract() };
    let model = if obj.is_instance_of::<model::Lwpr>() {
        AnyApproximator::Lwpr(rs::Lwpr::from_json(&json()?).map_err(py_err)?)
    } else if obj.is_instance_of::<model::Rbf>() {
        AnyApproximator::Rbf(rs::Rbf::from_json(&json()?).map_err(py_err)?)
    } else if obj.is_instance_of::<model::Grid>() {
        AnyApproximator::Grid(rs::Grid::from_json(&json()?).map_err(py_err)?)
    } else if obj.is_instance_of::<model::KernelRidge>() {
        AnyApproximator::KernelRidge(rs::KernelRidge::from_json(&json()?).map_err(py_err)?)
    } else {
        return Ok(None);
    };
    Ok(Some(model))
}

/// What `factory(box)` built: a native model, or a Python one with its dimensions (`n_in` and
/// `n_out` where the object has them, else the box's dimension and the length of a prediction
/// at the box's centre).
fn build_approx(
    py: Python<'_>,
    factory: &Py<PyAny>,
    bounds: &InputBox,
    name: &Arc<str>,
    errors: &Errors,
) -> PyResult<BenchApprox> {
    let b = Bound::new(
        py,
        PyInputBox {
            inner: bounds.clone(),
        },
    )?;
    let obj = factory.bind(py).call1((b,))?;
    if let Some(model) = native(&obj)? {
        return Ok(BenchApprox::Native(Box::new(model)));
    }
    for method in ["predict", "update"] {
        if !obj.getattr(method).is_ok_and(|m| m.is_callable()) {
            return Err(PyTypeError::new_err(format!(
                "the factory returned a {} without a method {method}",
                obj.get_type().name()?
            )));
        }
    }
    let attr = |k: &str| -> PyResult<Option<usize>> {
        match obj.getattr(k) {
            Ok(v) => v.extract().map(Some),
            Err(_) => Ok(None),
        }
    };
    let n_in = attr("n_in")?.unwrap_or(bounds.dim());
    if n_in != bounds.dim() {
        return Err(PyValueError::new_err(format!(
            "the model has n_in = {n_in}, but the learner has {} inputs",
            bounds.dim()
        )));
    }
    let n_out = match attr("n_out")? {
        Some(n) => n,
        None => {
            let centre: Vec<f64> = (0..bounds.dim())
                .map(|i| 0.5 * (bounds.lo[i] + bounds.hi[i]))
                .collect();
            let y = obj.call_method1("predict", (PyArray1::from_slice(py, &centre),))?;
            arrays::vector(&y, "prediction")?.len()
        }
    };
    if n_out == 0 {
        return Err(PyValueError::new_err("the model has no output"));
    }
    Ok(BenchApprox::Python(PyModel {
        obj: obj.unbind(),
        name: name.clone(),
        n_in,
        n_out,
        broken: None,
        errors: errors.clone(),
    }))
}

/// A Python object with `gradient(outcome)` (and optionally `reseed(seed)`, `explore()` and
/// `learn(outcome, exploration, fell)`), called under the GIL. An exception is recorded and
/// gives NaN, which the learner refuses (the run fails).
struct PyRule {
    /// The object, or why the factory could not build it.
    obj: Result<Py<PyAny>, String>,
    name: Arc<str>,
    has_reseed: bool,
    has_explore: bool,
    has_learn: bool,
    errors: Errors,
}

impl PyRule {
    fn build(factory: &Py<PyAny>, name: &Arc<str>, errors: &Errors) -> PyRule {
        Python::attach(|py| {
            let built = factory.bind(py).call0().and_then(|obj| {
                if obj.getattr("gradient").is_ok_and(|m| m.is_callable()) {
                    Ok(obj)
                } else {
                    Err(PyTypeError::new_err(format!(
                        "the factory returned a {} without a method gradient",
                        obj.get_type().name()?
                    )))
                }
            });
            let has = |k: &str| {
                built
                    .as_ref()
                    .is_ok_and(|o| o.getattr(k).is_ok_and(|m| m.is_callable()))
            };
            let (has_reseed, has_explore, has_learn) =
                (has("reseed"), has("explore"), has("learn"));
            PyRule {
                obj: built
                    .map(Bound::unbind)
                    .map_err(|e| format!("the factory raised {e}")),
                name: name.clone(),
                has_reseed,
                has_explore,
                has_learn,
                errors: errors.clone(),
            }
        })
    }

    /// `f` on the object under the GIL; an exception (or a factory that failed) is recorded
    /// and gives `failed`.
    fn call<T>(
        &self,
        what: &str,
        failed: T,
        f: impl FnOnce(&Bound<'_, PyAny>) -> PyResult<T>,
    ) -> T {
        let result = match &self.obj {
            Ok(obj) => {
                Python::attach(|py| f(obj.bind(py)).map_err(|e| format!("{what} raised {e}")))
            }
            Err(why) => Err(why.clone()),
        };
        result.unwrap_or_else(|message| {
            self.errors
                .record(format!("rule {:?}: {message}", self.name));
            failed
        })
    }
}

impl LearningRule for PyRule {
    fn gradient(&self, step: &StepOutcome) -> f64 {
        self.call("gradient(outcome)", f64::NAN, |o| {
            o.call_method1(intern!(o.py(), "gradient"), (PyStepOutcome::from(step),))?
                .extract()
        })
    }

    fn reseed(&mut self, seed: u64) {
        if self.has_reseed {
            self.call("reseed(seed)", (), |o| {
                o.call_method1(intern!(o.py(), "reseed"), (seed,))
                    .map(|_| ())
            });
        }
    }

    fn explore(&mut self) -> f64 {
        if !self.has_explore {
            return 0.0;
        }
        self.call("explore()", f64::NAN, |o| {
            o.call_method0(intern!(o.py(), "explore"))?.extract()
        })
    }

    fn learn(&mut self, step: &StepOutcome, exploration: f64, fell: bool) -> f64 {
        if !self.has_learn {
            return self.gradient(step);
        }
        self.call("learn(outcome, exploration, fell)", f64::NAN, |o| {
            o.call_method1(
                intern!(o.py(), "learn"),
                (PyStepOutcome::from(step), exploration, fell),
            )?
            .extract()
        })
    }
}

/// Approximators, rules and experiments by name: the Rust crate's `Registry`, with Python
/// factories.
#[pyclass(module = "steplearn", name = "Registry")]
pub(crate) struct PyRegistry {
    inner: Registry,
    errors: Errors,
}

/// `next` if its registrations are sound, else `ValueError` (the registry is left unchanged).
fn checked(next: Registry) -> PyResult<Registry> {
    next.check()
        .map(|()| next)
        .map_err(|e| PyValueError::new_err(e.to_string()))
}

fn callable(factory: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
    if factory.is_callable() {
        Ok(factory.clone().unbind())
    } else {
        Err(PyTypeError::new_err(format!(
            "the factory must be callable, got {}",
            factory.get_type().name()?
        )))
    }
}

#[pymethods]
impl PyRegistry {
    /// An empty registry.
    #[new]
    fn new() -> Self {
        PyRegistry {
            inner: Registry::new(),
            errors: Errors::default(),
        }
    }

    /// The built-ins: approximators `lwpr`, `rbf`, `grid`, `kernel-ridge`; rules
    /// `pendulum-cart`, `balance-only`, ...; experiments `tracking`, ... `omnidirectional`.
    #[staticmethod]
    fn builtin() -> Self {
        PyRegistry {
            inner: Registry::builtin(),
            errors: Errors::default(),
        }
    }

    /// Registers approximator `name`: `factory(box)` returns a fresh model over the input box.
    fn approximator<'py>(
        slf: Bound<'py, Self>,
        name: &str,
        factory: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, Self>> {
        let factory = callable(factory)?;
        {
            let mut r = slf.borrow_mut();
            let (errors, label): (Errors, Arc<str>) = (r.errors.clone(), name.into());
            let build = move |b: &InputBox| -> Result<BenchApprox, ApproxError> {
                Python::attach(|py| build_approx(py, &factory, b, &label, &errors)).map_err(|e| {
                    ApproxError::External(format!("{label:?}: the factory raised {e}"))
                })
            };
            r.inner = checked(r.inner.clone().approximator(name, build))?;
        }
        Ok(slf)
    }

    /// Registers rule `name`: `factory()` returns an object with `gradient(outcome)`.
    fn rule<'py>(
        slf: Bound<'py, Self>,
        name: &str,
        factory: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, Self>> {
        let factory = callable(factory)?;
        {
            let mut r = slf.borrow_mut();
            let (errors, label): (Errors, Arc<str>) = (r.errors.clone(), name.into());
            let build = move || PyRule::build(&factory, &label, &errors);
            r.inner = checked(r.inner.clone().rule(name, build))?;
        }
        Ok(slf)
    }

    /// The approximators' names, in registration order.
    #[getter]
    fn approximator_names(&self) -> Vec<String> {
        owned(self.inner.approximator_names())
    }

    /// The rules' names, in registration order.
    #[getter]
    fn rule_names(&self) -> Vec<String> {
        owned(self.inner.rule_names())
    }

    /// The experiments' names, in registration order.
    #[getter]
    fn experiment_names(&self) -> Vec<String> {
        owned(self.inner.experiment_names())
    }

    fn __repr__(&self) -> String {
        format!(
            "Registry(approximators={:?}, rules={:?}, experiments={:?})",
            self.inner.approximator_names(),
            self.inner.rule_names(),
            self.inner.experiment_names()
        )
    }
}

fn owned(names: Vec<&str>) -> Vec<String> {
    names.into_iter().map(str::to_string).collect()
}

/// A set of learned step parameters: `"step-x,step-time"` or `["step-x", "step-time"]`.
fn learn_set(obj: &Bound<'_, PyAny>) -> PyResult<LearnSet> {
    let parsed = match obj.extract::<String>() {
        Ok(s) => s.parse::<LearnSet>(),
        Err(_) => LearnSet::try_from(obj.extract::<Vec<String>>()?),
    };
    parsed.map_err(|e| PyValueError::new_err(e.to_string()))
}

/// The Rust builder's choices, applied to a `Bench` at `run`.
#[derive(Clone, Default)]
struct Choices {
    approximators: Option<Vec<String>>,
    rules: Option<Vec<String>>,
    experiments: Option<Vec<String>>,
    learn_sets: Option<Vec<LearnSet>>,
    seeds: Option<u64>,
    first_seed: Option<u64>,
    scale: Option<f64>,
    out: Option<PathBuf>,
    threads: Option<usize>,
    baseline: Option<(String, String)>,
    robots: Vec<PathBuf>,
    shard: Option<Shard>,
    config: Option<ConfigFile>,
    on_run: Option<Arc<Py<PyAny>>>,
    replays: bool,
}

/// A run's outcome as the dict `Bench.on_run`'s callback receives.
fn outcome_dict<'py>(py: Python<'py>, o: &RunOutcome) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("experiment", &o.spec.experiment)?;
    d.set_item("approx", &o.spec.approx)?;
    d.set_item("rule", &o.spec.rule)?;
    d.set_item("seed", o.spec.seed)?;
    let learn: Option<Vec<String>> = o
        .spec
        .learn
        .map(|set| set.iter().map(|p| p.to_string()).collect());
    d.set_item("learn", learn)?;
    match &o.status {
        RunStatus::Done { wall_time_s } => {
            d.set_item("status", "done")?;
            d.set_item("wall_time_s", *wall_time_s)?;
        }
        RunStatus::Skipped => d.set_item("status", "skipped")?,
        RunStatus::Failed(why) => {
            d.set_item("status", "failed")?;
            d.set_item("error", why)?;
        }
    }
    Ok(d)
}

impl Choices {
    /// The Rust bench of these choices; a Python callback's exception is recorded in `errors`.
    fn bench<'r>(&self, registry: &'r Registry, errors: &Errors) -> Bench<'r> {
        let mut b = Bench::new(registry).command("steplearn.Bench(...).run() (Python)");
        if let Some(v) = &self.approximators {
            b = b.approximators(v);
        }
        if let Some(v) = &self.rules {
            b = b.rules(v);
        }
        if let Some(v) = &self.experiments {
            b = b.experiments(v);
        }
        if let Some(v) = &self.learn_sets {
            b = b.learn_sets(v.iter().copied());
        }
        if let Some(n) = self.seeds {
            b = b.seeds(n);
        }
        if let Some(n) = self.first_seed {
            b = b.first_seed(n);
        }
        if let Some(s) = self.scale {
            b = b.scale(s);
        }
        if let Some(o) = &self.out {
            b = b.out(o);
        }
        if let Some(n) = self.threads {
            b = b.threads(n);
        }
        if let Some((a, r)) = &self.baseline {
            b = b.baseline(a, r);
        }
        if !self.robots.is_empty() {
            b = b.robots(&self.robots);
        }
        if let Some(s) = self.shard {
            b = b.shard(s);
        }
        if let Some(c) = &self.config {
            b = b.config(c.clone());
        }
        if let Some(callback) = &self.on_run {
            let (callback, errors) = (callback.clone(), errors.clone());
            b = b.on_run(move |o: &RunOutcome| {
                Python::attach(|py| {
                    let called = outcome_dict(py, o).and_then(|d| callback.bind(py).call1((d,)));
                    if let Err(e) = called {
                        errors.record(format!("on_run callback raised {e}"));
                    }
                })
            });
        }
        if self.replays {
            b = b.replays(move |leaderboard, dir| {
                steplearn::replay::moments::write_bench_replays(registry, dir, leaderboard)
            });
        }
        b
    }
}

/// A benchmark over a registry: the Rust crate's `Bench` builder; `run()` runs it without the
/// GIL and returns the leaderboard's rows.
#[pyclass(module = "steplearn", name = "Bench")]
pub(crate) struct PyBench {
    registry: Py<PyRegistry>,
    choices: Choices,
}

/// Applies `f` to the bench's choices and returns the bench (builder style).
fn choose<'py>(slf: Bound<'py, PyBench>, f: impl FnOnce(&mut Choices)) -> Bound<'py, PyBench> {
    f(&mut slf.borrow_mut().choices);
    slf
}

#[pymethods]
impl PyBench {
    /// A bench over `registry` with the Rust defaults (every registered name, 5 seeds, the
    /// paper's scale, `results/bench`).
    #[new]
    fn new(registry: Py<PyRegistry>) -> Self {
        PyBench {
            registry,
            choices: Choices::default(),
        }
    }

    /// The approximators to run, by registered name.
    fn approximators(slf: Bound<'_, Self>, names: Vec<String>) -> Bound<'_, Self> {
        choose(slf, |c| c.approximators = Some(names))
    }

    /// The rules to run, by registered name.
    fn rules(slf: Bound<'_, Self>, names: Vec<String>) -> Bound<'_, Self> {
        choose(slf, |c| c.rules = Some(names))
    }

    /// The experiments to run, by registered name.
    fn experiments(slf: Bound<'_, Self>, names: Vec<String>) -> Bound<'_, Self> {
        choose(slf, |c| c.experiments = Some(names))
    }

    /// The sets of learned step parameters, each `"step-x,step-time"` or a list of names.
    fn learn_sets<'py>(
        slf: Bound<'py, Self>,
        sets: Vec<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, Self>> {
        let sets = sets.iter().map(learn_set).collect::<PyResult<Vec<_>>>()?;
        Ok(choose(slf, |c| c.learn_sets = Some(sets)))
    }

    /// `n` seeds, from `first_seed` on.
    fn seeds(slf: Bound<'_, Self>, n: u64) -> Bound<'_, Self> {
        choose(slf, |c| c.seeds = Some(n))
    }

    /// The first seed (default 0).
    fn first_seed(slf: Bound<'_, Self>, first: u64) -> Bound<'_, Self> {
        choose(slf, |c| c.first_seed = Some(first))
    }

    /// The protocols' length as a fraction of the paper's, in (0, 1].
    fn scale(slf: Bound<'_, Self>, scale: f64) -> Bound<'_, Self> {
        choose(slf, |c| c.scale = Some(scale))
    }

    /// The output directory (runs there are reused when their identity matches).
    fn out(slf: Bound<'_, Self>, dir: PathBuf) -> Bound<'_, Self> {
        choose(slf, |c| c.out = Some(dir))
    }

    /// Worker threads (results do not depend on it).
    fn threads(slf: Bound<'_, Self>, n: usize) -> Bound<'_, Self> {
        choose(slf, |c| c.threads = Some(n))
    }

    /// The combination every other is compared with.
    fn baseline<'py>(slf: Bound<'py, Self>, approx: String, rule: String) -> Bound<'py, Self> {
        choose(slf, |c| c.baseline = Some((approx, rule)))
    }

    /// Runs only shard `index` of `count` of the grid of runs (0-based; the leaderboard covers
    /// every finished run of the selection). `ValueError` unless `count >= 1` and
    /// `index < count`.
    fn shard(slf: Bound<'_, Self>, index: usize, count: usize) -> PyResult<Bound<'_, Self>> {
        let shard = Shard::new(index, count).map_err(|e| {
            let reason = match e {
                SweepError::InvalidShard { reason, .. } => reason,
                other => other.to_string(),
            };
            PyValueError::new_err(format!("shard(index={index}, count={count}): {reason}"))
        })?;
        Ok(choose(slf, |c| c.shard = Some(shard)))
    }

    /// The settings and protocols of a config file, as `--config` reads it (`[settings]` and
    /// the experiments' tables, checked against the registry's experiments). `ValueError` for
    /// a file that does not load or holds a bad key or value; the bench keeps its choices.
    fn config(slf: Bound<'_, Self>, path: PathBuf) -> PyResult<Bound<'_, Self>> {
        let file = {
            let bench = slf.borrow();
            let registry = bench.registry.borrow(slf.py());
            ConfigFile::load_for(&path, registry.inner.experiments())
        }
        .map_err(|e| PyValueError::new_err(format!("config({}): {e}", path.display())))?;
        Ok(choose(slf, |c| c.config = Some(file)))
    }

    /// Calls `callback(run)` as each run ends (a progress report): `run` is a dict with
    /// `experiment`, `approx`, `rule`, `seed`, `learn` (names), `status` (`"done"`,
    /// `"skipped"` or `"failed"`) and `wall_time_s` (done) or `error` (failed). Called with
    /// the GIL from the bench's workers, one at a time; an exception in it makes `run()` raise
    /// `RuntimeError` after the bench finished. `TypeError` unless callable.
    fn on_run<'py>(
        slf: Bound<'py, Self>,
        callback: Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, Self>> {
        if !callback.is_callable() {
            return Err(PyTypeError::new_err(format!(
                "on_run: the callback must be callable, got {}",
                callback.get_type().name()?
            )));
        }
        let callback = callback.unbind();
        Ok(choose(slf, |c| c.on_run = Some(Arc::new(callback))))
    }

    /// Whether `run()` writes the replay pages of the best and the worst row beside
    /// `index.html`, as `steplearn bench` does (default: no).
    fn replays(slf: Bound<'_, Self>, write: bool) -> Bound<'_, Self> {
        choose(slf, |c| c.replays = write)
    }

    /// The robots to run on, from URDF files; with several, every row names its robot.
    fn robots(slf: Bound<'_, Self>, paths: Vec<PathBuf>) -> Bound<'_, Self> {
        choose(slf, |c| c.robots = paths)
    }

    /// Runs the bench (the GIL released; Python callbacks take it) and returns the
    /// leaderboard's rows as dicts with the keys of `leaderboard.json`. `ValueError` for a bad
    /// selection or configuration; `RuntimeError` when runs failed or a Python callback raised
    /// (the leaderboard of the finished runs is still written).
    fn run<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (registry, errors) = {
            let r = self.registry.borrow(py);
            (r.inner.clone(), r.errors.clone())
        };
        let choices = self.choices.clone();
        errors.take();
        let ran = py.detach(|| {
            catch_unwind(AssertUnwindSafe(|| {
                let report = choices.bench(&registry, &errors).run()?;
                serde_json::to_string(&report.leaderboard.rows)
                    .map_err(|e| BenchError::Selection(e.to_string()))
            }))
        });
        let raised = errors.take();
        let python = if raised.is_empty() {
            String::new()
        } else {
            format!("; Python callbacks raised: {}", raised.join("; "))
        };
        match ran {
            Err(payload) => Err(PyRuntimeError::new_err(format!(
                "internal error in steplearn (please report): {}{python}",
                model::panic_message(&*payload)
            ))),
            Ok(Err(e @ BenchError::RunsFailed(_))) => {
                Err(PyRuntimeError::new_err(format!("{e}{python}")))
            }
            Ok(Err(e)) => Err(PyValueError::new_err(format!("{e}{python}"))),
            Ok(Ok(_)) if !raised.is_empty() => Err(PyRuntimeError::new_err(format!(
                "the bench finished{python}"
            ))),
            Ok(Ok(json)) => py
                .import(intern!(py, "json"))?
                .call_method1(intern!(py, "loads"), (json,)),
        }
    }

    fn __repr__(&self) -> String {
        let c = &self.choices;
        format!(
            "Bench(approximators={:?}, rules={:?}, experiments={:?}, seeds={:?}, scale={:?}, \
             out={:?}, robots={:?})",
            c.approximators, c.rules, c.experiments, c.seeds, c.scale, c.out, c.robots
        )
    }
}

/// Adds the bench's classes to the module.
pub(crate) fn add_classes(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyRegistry>()?;
    m.add_class::<PyBench>()?;
    m.add_class::<PyInputBox>()?;
    m.add_class::<PyStepOutcome>()?;
    Ok(())
}
