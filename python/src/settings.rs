//! Keyword settings to a Rust config, through the config's serde form.
//!
//! The defaults are serialized to a JSON object, each keyword replaces the field of its name,
//! and the object is deserialized back. A keyword the config does not read is a `TypeError`
//! naming it; a value of the wrong type is a `TypeError` with serde's message; range checks
//! are left to the model's own validation. No field is copied by hand.

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyList, PyString, PyTuple};
use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::{Map, Value};

/// Most inputs or outputs a model may be built with from Python: larger sizes would make the
/// Rust defaults (e.g. LWPR's `n_in x n_in` metric) allocate before validation can refuse them.
pub(crate) const MAX_DIM: i64 = 4096;

/// A dimension argument (`n_in`, `n_out`, `output_dim`) as a `usize`, refused (ValueError) when
/// negative or above [`MAX_DIM`]; zero is left to the model's validation.
pub(crate) fn dim(name: &str, value: i64) -> PyResult<usize> {
    if !(0..=MAX_DIM).contains(&value) {
        return Err(PyValueError::new_err(format!(
            "invalid configuration: {name} must be in [1, {MAX_DIM}], got {value}"
        )));
    }
    Ok(value as usize)
}

/// A Python value as JSON (None, bool, int, float, str, dict, list, tuple, numpy arrays and
/// scalars). `key` names the setting in errors; a non-finite float is refused as the Rust
/// validation would refuse it.
pub(crate) fn to_json(obj: &Bound<'_, PyAny>, key: &str) -> PyResult<Value> {
    if obj.is_none() {
        return Ok(Value::Null);
    }
    if let Ok(b) = obj.cast::<PyBool>() {
        return Ok(Value::Bool(b.is_true()));
    }
    if let Ok(s) = obj.cast::<PyString>() {
        return Ok(Value::String(s.to_string()));
    }
    if let Ok(i) = obj.extract::<i64>() {
        return Ok(Value::from(i));
    }
    if let Ok(f) = obj.extract::<f64>() {
        return serde_json::Number::from_f64(f)
            .map(Value::Number)
            .ok_or_else(|| {
                PyValueError::new_err(format!(
                    "invalid configuration: {key} must be finite, got {f}"
                ))
            });
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut map = Map::new();
        for (k, v) in d.iter() {
            let k: String = k.extract().map_err(|_| {
                PyTypeError::new_err(format!("setting {key}: dictionary keys must be strings"))
            })?;
            let v = to_json(&v, &format!("{key}.{k}"))?;
            map.insert(k, v);
        }
        return Ok(Value::Object(map));
    }
    if obj.hasattr("tolist")? && !obj.is_instance_of::<PyList>() {
        // numpy arrays (and scalars not caught above)
        return to_json(&obj.call_method0("tolist")?, key);
    }
    let items: Vec<Bound<'_, PyAny>> = if let Ok(l) = obj.cast::<PyList>() {
        l.iter().collect()
    } else if let Ok(t) = obj.cast::<PyTuple>() {
        t.iter().collect()
    } else {
        return Err(PyTypeError::new_err(format!(
            "setting {key}: unsupported type {}",
            obj.get_type().name()?
        )));
    };
    items
        .iter()
        .map(|v| to_json(v, key))
        .collect::<PyResult<Vec<_>>>()
        .map(Value::Array)
}

/// `defaults` with the keyword `settings` applied; `fixup` may rewrite the JSON object first
/// (e.g. LWPR's `init_d` given as a number). `optional` lists fields that the defaults omit
/// from their JSON (`None` options), for the list of settings in the unknown-keyword error.
pub(crate) fn apply<C: Serialize + DeserializeOwned>(
    defaults: &C,
    settings: Option<&Bound<'_, PyDict>>,
    optional: &[&str],
    fixup: impl FnOnce(&mut Map<String, Value>) -> PyResult<()>,
) -> PyResult<C> {
    let Value::Object(mut map) = serde_json::to_value(defaults)
        .map_err(|e| PyValueError::new_err(format!("internal error: {e}")))?
    else {
        return Err(PyValueError::new_err("internal error: config is not a map"));
    };
    let mut known: Vec<String> = map.keys().cloned().collect();
    known.extend(optional.iter().map(|s| s.to_string()));
    if let Some(settings) = settings {
        for (k, v) in settings.iter() {
            let k: String = k.extract()?;
            let v = to_json(&v, &k)?;
            map.insert(k, v);
        }
    }
    fixup(&mut map)?;
    let mut unknown = Vec::new();
    let mut record = |path: serde_ignored::Path<'_>| unknown.push(path.to_string());
    let de = serde_ignored::Deserializer::new(Value::Object(map), &mut record);
    let result: Result<C, _> = serde_path_to_error::deserialize(de);
    if !unknown.is_empty() {
        return Err(PyTypeError::new_err(format!(
            "unknown setting {}; the settings are: {}",
            unknown
                .iter()
                .map(|u| format!("'{u}'"))
                .collect::<Vec<_>>()
                .join(", "),
            known.join(", ")
        )));
    }
    result.map_err(|e| {
        let message = format!("setting {}: {}", e.path(), e.inner());
        if e.inner().to_string().starts_with("invalid type") {
            PyTypeError::new_err(message)
        } else {
            PyValueError::new_err(format!("invalid configuration: {message}"))
        }
    })
}
