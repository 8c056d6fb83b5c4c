//! Samples from Python: numpy arrays (any numeric dtype) or sequences of numbers.
//!
//! Only the shape is checked here (1-D for a sample, 2-D for a batch); lengths and
//! finiteness are checked by the Rust models, whose messages reach Python unchanged.

use ndarray::{Array2, ArrayView2};
use numpy::{PyReadonlyArray1, PyReadonlyArray2, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyString};

/// Rejects `str` and `bytes`, which would otherwise pass as sequences.
fn not_text(obj: &Bound<'_, PyAny>, name: &str, want: &str) -> PyResult<()> {
    if obj.is_instance_of::<PyString>() || obj.is_instance_of::<PyBytes>() {
        return Err(PyTypeError::new_err(format!(
            "{name} must be {want} of numbers, got {}",
            type_name(obj)
        )));
    }
    Ok(())
}

fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_else(|_| "?".into())
}

/// A numpy array of another dtype, cast to float64 (numpy's own error if it cannot be).
fn as_float64<'py>(obj: &Bound<'py, PyAny>) -> PyResult<Option<Bound<'py, PyAny>>> {
    if obj.cast::<PyUntypedArray>().is_ok() {
        Ok(Some(obj.call_method1("astype", ("float64",))?))
    } else {
        Ok(None)
    }
}

/// One sample (`x` or `y`) as a vector.
pub(crate) fn vector(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<f64>> {
    if let Ok(a) = obj.extract::<PyReadonlyArray1<'_, f64>>() {
        return Ok(a.as_array().to_vec());
    }
    if let Some(cast) = as_float64(obj)? {
        return match cast.extract::<PyReadonlyArray1<'_, f64>>() {
            Ok(a) => Ok(a.as_array().to_vec()),
            Err(_) => Err(PyTypeError::new_err(format!(
                "{name} must be a 1-D array, got a {}-D array",
                cast.cast::<PyUntypedArray>()?.ndim()
            ))),
        };
    }
    not_text(obj, name, "a 1-D sequence")?;
    obj.extract::<Vec<f64>>().map_err(|e| {
        PyTypeError::new_err(format!(
            "{name} must be a 1-D array or sequence of numbers, got {} ({})",
            type_name(obj),
            e.value(obj.py())
        ))
    })
}

/// A batch (`X` or `Y`, rows are samples): borrowed from a float64 numpy array when possible.
pub(crate) enum Matrix<'py> {
    /// A float64 numpy array, read in place.
    Numpy(PyReadonlyArray2<'py, f64>),
    /// Anything else, converted.
    Owned(Array2<f64>),
}

impl Matrix<'_> {
    /// The batch as a read-only view.
    pub(crate) fn view(&self) -> ArrayView2<'_, f64> {
        match self {
            Matrix::Numpy(a) => a.as_array(),
            Matrix::Owned(a) => a.view(),
        }
    }
}

/// Reads a batch argument.
pub(crate) fn matrix<'py>(obj: &Bound<'py, PyAny>, name: &str) -> PyResult<Matrix<'py>> {
    if let Ok(a) = obj.extract::<PyReadonlyArray2<'py, f64>>() {
        return Ok(Matrix::Numpy(a));
    }
    if let Some(cast) = as_float64(obj)? {
        return match cast.extract::<PyReadonlyArray2<'_, f64>>() {
            Ok(a) => Ok(Matrix::Owned(a.as_array().to_owned())),
            Err(_) => Err(PyTypeError::new_err(format!(
                "{name} must be a 2-D array (rows are samples), got a {}-D array",
                cast.cast::<PyUntypedArray>()?.ndim()
            ))),
        };
    }
    not_text(obj, name, "a 2-D sequence")?;
    let rows = obj.extract::<Vec<Vec<f64>>>().map_err(|e| {
        PyTypeError::new_err(format!(
            "{name} must be a 2-D array or a sequence of sequences of numbers, got {} ({})",
            type_name(obj),
            e.value(obj.py())
        ))
    })?;
    let cols = rows.first().map_or(0, Vec::len);
    if let Some((i, r)) = rows.iter().enumerate().find(|(_, r)| r.len() != cols) {
        return Err(PyTypeError::new_err(format!(
            "{name} is ragged: row {i} has {} entries, row 0 has {cols}",
            r.len()
        )));
    }
    let flat: Vec<f64> = rows.into_iter().flatten().collect();
    Array2::from_shape_vec((flat.len().checked_div(cols).unwrap_or(0), cols), flat)
        .map(Matrix::Owned)
        .map_err(|e| PyTypeError::new_err(format!("{name}: {e}")))
}
