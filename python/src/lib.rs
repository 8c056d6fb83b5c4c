//! Python bindings of steplearn's online approximators (`steplearn._steplearn`).
//!
//! Every class wraps one Rust approximator. Settings go through the Rust config's serde form
//! ([`settings`]), inputs are checked by the Rust model itself, and every failure (including a
//! panic, which the crate never intends) becomes a Python exception.

mod arrays;
mod bench;
mod env;
mod model;
mod settings;

use pyo3::prelude::*;

/// The compiled module; `steplearn/__init__.py` re-exports it.
#[pymodule]
fn _steplearn(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<model::Lwpr>()?;
    m.add_class::<model::Rbf>()?;
    m.add_class::<model::Grid>()?;
    m.add_class::<model::KernelRidge>()?;
    bench::add_classes(m)?;
    m.add_class::<env::FootstepEnv>()?;
    m.add("MAX_INPUT", steplearn::approx::MAX_INPUT)?;
    m.add("MAX_TARGET", steplearn::approx::MAX_TARGET)?;
    Ok(())
}
