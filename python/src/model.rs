//! The four approximator classes, sharing one generic core ([`Core`]).

use crate::arrays;
use crate::settings::{self, dim};
use ndarray::{Array2, ArrayView2};
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use serde_json::Value;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;
use steplearn::approx::{self as rs, ApproxError, FunctionApproximator, InputBox, Persist};

/// A Rust error as a Python exception: `OSError` (or its subclasses) for file errors other
/// than undecodable contents, `ValueError` for everything else, with the Rust message.
pub(crate) fn py_err(e: ApproxError) -> PyErr {
    match e {
        ApproxError::Io(io) if io.kind() != std::io::ErrorKind::InvalidData => PyErr::from(io),
        ApproxError::Io(io) => {
            PyValueError::new_err(format!("corrupt or incompatible saved model: {io}"))
        }
        other => PyValueError::new_err(other.to_string()),
    }
}

pub(crate) fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".into())
}

/// Runs `f`, turning a panic into a `RuntimeError`; `poison` is set when the panic may have
/// left the model half-updated.
fn guarded<T>(poison: Option<&mut bool>, f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(r) => r,
        Err(payload) => {
            if let Some(p) = poison {
                *p = true;
            }
            Err(PyRuntimeError::new_err(format!(
                "internal error in steplearn (please report): {}",
                panic_message(&*payload)
            )))
        }
    }
}

/// Checks a batch's columns and every row (length, finiteness), naming the first bad row.
fn check_rows(
    what: &'static str,
    m: ArrayView2<'_, f64>,
    cols: usize,
    rows: Option<usize>,
) -> PyResult<()> {
    if m.ncols() != cols {
        return Err(PyValueError::new_err(format!(
            "{what}: expected {cols} columns, got {} (shape {:?})",
            m.ncols(),
            m.shape()
        )));
    }
    if let Some(rows) = rows
        && m.nrows() != rows
    {
        return Err(PyValueError::new_err(format!(
            "{what}: expected {rows} rows (one per row of X), got {}",
            m.nrows()
        )));
    }
    for (i, row) in m.rows().into_iter().enumerate() {
        if let Some(j) = row.iter().position(|v| !v.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "row {i}: {what}[{j}] is not finite ({})",
                row[j]
            )));
        }
    }
    Ok(())
}

/// What every class shares: the model, and whether a panic may have broken it.
pub(crate) struct Core<A> {
    model: A,
    poisoned: bool,
}

impl<A> Core<A>
where
    A: FunctionApproximator + Persist + Clone + Send + Sync,
{
    fn new(model: A) -> Self {
        Core {
            model,
            poisoned: false,
        }
    }

    fn ok(&self) -> PyResult<&A> {
        if self.poisoned {
            return Err(PyRuntimeError::new_err(
                "this model was left inconsistent by an internal error; load a saved copy",
            ));
        }
        Ok(&self.model)
    }

    fn predict_vec(&self, x: &[f64]) -> PyResult<Vec<f64>> {
        let model = self.ok()?;
        let mut y = vec![0.0; model.output_dim()];
        guarded(None, || model.predict(x, &mut y).map_err(py_err))?;
        Ok(y)
    }

    fn update(&mut self, x: &Bound<'_, PyAny>, y: &Bound<'_, PyAny>) -> PyResult<()> {
        self.ok()?;
        let x = arrays::vector(x, "x")?;
        let y = arrays::vector(y, "y")?;
        let model = &mut self.model;
        guarded(Some(&mut self.poisoned), || {
            model.update(&x, &y).map_err(py_err)
        })
    }

    fn predict<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let x = arrays::vector(x, "x")?;
        Ok(PyArray1::from_vec(py, self.predict_vec(&x)?))
    }

    /// Trains on a clone and keeps it only when every row was accepted, so a refused batch
    /// (or a panic) leaves the model exactly as it was.
    fn update_many(
        &mut self,
        py: Python<'_>,
        x: &Bound<'_, PyAny>,
        y: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        self.ok()?;
        let (xm, ym) = (arrays::matrix(x, "X")?, arrays::matrix(y, "Y")?);
        let (xv, yv) = (xm.view(), ym.view());
        let model = &mut self.model;
        py.detach(|| {
            check_rows("X", xv, model.input_dim(), None)?;
            check_rows("Y", yv, model.output_dim(), Some(xv.nrows()))?;
            let (xs, ys) = (xv.as_standard_layout(), yv.as_standard_layout());
            let (xs, ys) = (
                xs.as_slice().expect("standard layout"),
                ys.as_slice().expect("standard layout"),
            );
            let trained = guarded(None, || {
                let mut next = model.clone();
                for (i, (xi, yi)) in xs
                    .chunks_exact(model.input_dim())
                    .zip(ys.chunks_exact(model.output_dim()))
                    .enumerate()
                {
                    next.update(xi, yi).map_err(|e| {
                        PyValueError::new_err(format!("row {i}: {e} (the model is unchanged)"))
                    })?;
                }
                Ok(next)
            })?;
            *model = trained;
            Ok(())
        })
    }

    fn predict_many<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let model = self.ok()?;
        let xm = arrays::matrix(x, "X")?;
        let xv = xm.view();
        let out = py.detach(|| {
            check_rows("X", xv, model.input_dim(), None)?;
            guarded(None, || {
                let mut out = Array2::zeros((xv.nrows(), model.output_dim()));
                let mut xi = vec![0.0; xv.ncols()];
                for (i, (row, mut o)) in xv.rows().into_iter().zip(out.rows_mut()).enumerate() {
                    xi.iter_mut().zip(row).for_each(|(d, s)| *d = *s);
                    let yo = o.as_slice_mut().expect("standard layout");
                    model
                        .predict(&xi, yo)
                        .map_err(|e| PyValueError::new_err(format!("row {i}: {e}")))?;
                }
                Ok(out)
            })
        })?;
        Ok(out.into_pyarray(py))
    }

    fn to_json(&self) -> PyResult<String> {
        self.ok()?.to_json().map_err(py_err)
    }

    fn from_json(json: &str) -> PyResult<Self> {
        guarded(None, || A::from_json(json).map(Core::new).map_err(py_err))
    }

    fn save(&self, path: PathBuf) -> PyResult<()> {
        let model = self.ok()?;
        guarded(None, || model.save(&path).map_err(py_err))
    }

    fn load(path: PathBuf) -> PyResult<Self> {
        guarded(None, || A::load(&path).map(Core::new).map_err(py_err))
    }
}

/// Two 1-D arrays (LWPR's prediction and confidence).
type ArrayPair<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// A JSON value as the Python object `json.loads` would give.
fn json_to_py<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (v.to_string(),))
}

/// Declares a class around [`Core`], with the methods every approximator has, plus `extra`
/// (its constructor and its own methods).
macro_rules! approximator {
    ($(#[$doc:meta])* $name:ident, $rust:ty, { $($extra:tt)* }) => {
        $(#[$doc])*
        #[pyclass(module = "steplearn")]
        pub(crate) struct $name {
            core: Core<$rust>,
        }

        #[pymethods]
        impl $name {
            $($extra)*

            /// Number of inputs.
            #[getter]
            fn n_in(&self) -> usize {
                self.core.model.input_dim()
            }

            /// Number of outputs.
            #[getter]
            fn n_out(&self) -> usize {
                self.core.model.output_dim()
            }

            /// The model's settings, as a dict of the Rust config's fields.
            #[getter]
            fn settings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
                let v = serde_json::to_value(self.core.model.config())
                    .map_err(|e| PyValueError::new_err(e.to_string()))?;
                json_to_py(py, &v)
            }

            /// Trains on one sample.
            fn update(&mut self, x: &Bound<'_, PyAny>, y: &Bound<'_, PyAny>) -> PyResult<()> {
                self.core.update(x, y)
            }

            /// The prediction at one input, as a 1-D array.
            fn predict<'py>(
                &self,
                py: Python<'py>,
                x: &Bound<'py, PyAny>,
            ) -> PyResult<Bound<'py, PyArray1<f64>>> {
                self.core.predict(py, x)
            }

            /// Trains on every row of `X` and `Y` in order (bit-identical to a loop of
            /// `update`), without the GIL. All or nothing.
            #[pyo3(signature = (X, Y))]
            #[allow(non_snake_case)]
            fn update_many(
                &mut self,
                py: Python<'_>,
                X: &Bound<'_, PyAny>,
                Y: &Bound<'_, PyAny>,
            ) -> PyResult<()> {
                self.core.update_many(py, X, Y)
            }

            /// Predicts every row of `X`, without the GIL.
            #[pyo3(signature = (X))]
            #[allow(non_snake_case)]
            fn predict_many<'py>(
                &self,
                py: Python<'py>,
                X: &Bound<'py, PyAny>,
            ) -> PyResult<Bound<'py, PyArray2<f64>>> {
                self.core.predict_many(py, X)
            }

            /// The model as the Rust crate's JSON.
            fn to_json(&self) -> PyResult<String> {
                self.core.to_json()
            }

            /// A model from the Rust crate's JSON (checked).
            #[staticmethod]
            fn from_json(json: &str) -> PyResult<Self> {
                Core::from_json(json).map(|core| $name { core })
            }

            /// Writes the model to `path` atomically, in the Rust crate's format.
            fn save(&self, path: PathBuf) -> PyResult<()> {
                self.core.save(path)
            }

            /// Reads and checks a model saved by `save` or by the Rust crate.
            #[staticmethod]
            fn load(path: PathBuf) -> PyResult<Self> {
                Core::load(path).map(|core| $name { core })
            }

            fn __reduce__<'py>(
                slf: &Bound<'py, Self>,
            ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
                let json = slf.borrow().core.to_json()?;
                let py = slf.py();
                Ok((
                    py.import("steplearn")?.getattr(stringify!($name))?.getattr("from_json")?,
                    PyTuple::new(py, [json])?,
                ))
            }

            fn __copy__(&self) -> PyResult<Self> {
                self.core.ok()?;
                Ok($name { core: Core::new(self.core.model.clone()) })
            }

            fn __deepcopy__(&self, _memo: &Bound<'_, PyAny>) -> PyResult<Self> {
                self.__copy__()
            }

            fn __repr__(&self) -> String {
                format!(
                    "{}(n_in={}, n_out={})",
                    stringify!($name),
                    self.core.model.input_dim(),
                    self.core.model.output_dim()
                )
            }
        }
    };
}

approximator!(
    /// Locally weighted projection regression (the Rust crate's `Lwpr`).
    Lwpr, rs::Lwpr, {
    #[new]
    #[pyo3(signature = (n_in, n_out, **settings))]
    fn new(n_in: i64, n_out: i64, settings: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let (n_in, n_out) = (dim("n_in", n_in)?, dim("n_out", n_out)?);
        let defaults = rs::LwprConfig::new(n_in, n_out);
        let config = settings::apply(&defaults, settings, &["max_rfs"], |map| {
            lwpr_init_d(map, n_in, n_out)
        })?;
        let model = guarded(None, || rs::Lwpr::new(config).map_err(py_err))?;
        Ok(Lwpr { core: Core::new(model) })
    }

    /// The prediction and, per output, the confidence bound (infinite where no receptive
    /// field is trusted), as two 1-D arrays.
    fn predict_conf<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
    ) -> PyResult<ArrayPair<'py>> {
        let model = self.core.ok()?;
        let x = arrays::vector(x, "x")?;
        let mut y = vec![0.0; model.output_dim()];
        let mut conf = vec![0.0; model.output_dim()];
        guarded(None, || {
            model.predict_with_confidence(&x, &mut y, &mut conf).map_err(py_err)
        })?;
        Ok((PyArray1::from_vec(py, y), PyArray1::from_vec(py, conf)))
    }

    /// Number of receptive fields over all outputs.
    #[getter]
    fn num_receptive_fields(&self) -> usize {
        self.core.model.num_receptive_fields()
    }

    /// Number of training samples seen.
    #[getter]
    fn n_data(&self) -> u64 {
        self.core.model.n_data()
    }
});

approximator!(
    /// A normalised Gaussian RBF network on a regular grid of centres (the Rust `Rbf`).
    Rbf, rs::Rbf, {
    #[new]
    #[pyo3(signature = (lo, hi, centres, output_dim = 1, **settings))]
    fn new(
        lo: &Bound<'_, PyAny>,
        hi: &Bound<'_, PyAny>,
        centres: Vec<usize>,
        output_dim: i64,
        settings: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let bounds = input_box(lo, hi)?;
        let defaults = rs::RbfConfig::new(bounds, centres, dim("output_dim", output_dim)?);
        let config = settings::apply(&defaults, settings, &[], |_| Ok(()))?;
        let model = guarded(None, || rs::Rbf::new(config).map_err(py_err))?;
        Ok(Rbf { core: Core::new(model) })
    }

    /// Number of centres.
    #[getter]
    fn num_centres(&self) -> usize {
        self.core.model.num_centres()
    }
});

approximator!(
    /// A multilinear interpolation table trained by normalised LMS (the Rust `Grid`).
    Grid, rs::Grid, {
    #[new]
    #[pyo3(signature = (lo, hi, resolution, output_dim = 1, **settings))]
    fn new(
        lo: &Bound<'_, PyAny>,
        hi: &Bound<'_, PyAny>,
        resolution: Vec<usize>,
        output_dim: i64,
        settings: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let bounds = input_box(lo, hi)?;
        let defaults = rs::GridConfig::new(bounds, resolution, dim("output_dim", output_dim)?);
        let config = settings::apply(&defaults, settings, &[], |_| Ok(()))?;
        let model = guarded(None, || rs::Grid::new(config).map_err(py_err))?;
        Ok(Grid { core: Core::new(model) })
    }

    /// Number of table nodes.
    #[getter]
    fn num_nodes(&self) -> usize {
        self.core.model.num_nodes()
    }
});

approximator!(
    /// Sparse online kernel ridge regression, KRLS-T style (the Rust `KernelRidge`).
    KernelRidge, rs::KernelRidge, {
    #[new]
    #[pyo3(signature = (length_scales, output_dim = 1, **settings))]
    fn new(
        length_scales: &Bound<'_, PyAny>,
        output_dim: i64,
        settings: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let scales = arrays::vector(length_scales, "length_scales")?;
        if scales.len() as i64 > settings::MAX_DIM {
            return Err(PyValueError::new_err(format!(
                "invalid configuration: length_scales has more than {} entries",
                settings::MAX_DIM
            )));
        }
        let defaults = rs::KernelRidgeConfig::new(scales, dim("output_dim", output_dim)?);
        let config = settings::apply(&defaults, settings, &[], |_| Ok(()))?;
        let model = guarded(None, || rs::KernelRidge::new(config).map_err(py_err))?;
        Ok(KernelRidge { core: Core::new(model) })
    }

    /// Number of atoms in the dictionary.
    #[getter]
    fn dictionary_size(&self) -> usize {
        self.core.model.dictionary_size()
    }

    /// The predictive variance of output 0 at `x` (the latent function's, without noise).
    fn predict_variance(&self, x: &Bound<'_, PyAny>) -> PyResult<f64> {
        let model = self.core.ok()?;
        let x = arrays::vector(x, "x")?;
        guarded(None, || model.predict_variance(&x).map_err(py_err))
    }
});

/// The input box `[lo, hi]` (checked by the Rust `InputBox`).
fn input_box(lo: &Bound<'_, PyAny>, hi: &Bound<'_, PyAny>) -> PyResult<InputBox> {
    let (lo, hi) = (arrays::vector(lo, "lo")?, arrays::vector(hi, "hi")?);
    if lo.len() as i64 > settings::MAX_DIM {
        return Err(PyValueError::new_err(format!(
            "invalid configuration: bounds has more than {} inputs",
            settings::MAX_DIM
        )));
    }
    InputBox::new(lo, hi).map_err(py_err)
}

/// LWPR's `init_d` may be a number (`value * I`), a sequence of `n_in` numbers (the diagonal)
/// or the full metric (`n_in * n_in` numbers, flat or nested); the Rust setters build it.
fn lwpr_init_d(
    map: &mut serde_json::Map<String, Value>,
    n_in: usize,
    n_out: usize,
) -> PyResult<()> {
    let Some(v) = map.get("init_d") else {
        return Ok(());
    };
    let base = rs::LwprConfig::new(n_in, n_out);
    let numbers =
        |items: &[Value]| -> Option<Vec<f64>> { items.iter().map(Value::as_f64).collect() };
    let d = match v {
        Value::Number(n) => base.init_d(n.as_f64().unwrap_or(f64::NAN)).init_d,
        Value::Array(items) if items.iter().all(Value::is_array) && !items.is_empty() => {
            let mut flat = Vec::new();
            for row in items {
                let row = row.as_array().and_then(|r| numbers(r)).ok_or_else(|| {
                    PyTypeError::new_err("setting init_d: rows must hold numbers")
                })?;
                flat.extend(row);
            }
            flat
        }
        Value::Array(items) => {
            let diag = numbers(items)
                .ok_or_else(|| PyTypeError::new_err("setting init_d: must hold numbers"))?;
            if diag.len() == n_in && n_in > 1 {
                base.init_d_diag(diag).init_d
            } else {
                base.init_d_matrix(diag).init_d
            }
        }
        _ => return Ok(()), // serde reports the type
    };
    map.insert("init_d".into(), serde_json::to_value(d).expect("floats"));
    Ok(())
}
