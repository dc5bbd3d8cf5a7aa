//! The exceptions camlink raises and the guard every entry point runs
//! under.

use std::panic::{catch_unwind, AssertUnwindSafe};

use camlink_core::run::AnalysisError as CoreAnalysisError;
use numpy::PyArray2;
use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

create_exception!(
    camlink,
    ModelError,
    PyValueError,
    "A model file, a builder call or an argument is not valid."
);
create_exception!(
    camlink,
    AnalysisError,
    PyRuntimeError,
    "An analysis could not proceed. Attributes: time (s), joints (names), \
     residual (largest |Φ|), names, quantities and data (the results computed \
     so far)."
);

/// Runs `f`, turning a Rust panic into a Python `RuntimeError`.
pub(crate) fn guard<T>(f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|payload| Err(internal_error(payload)))
}

/// The `RuntimeError` for a caught panic.
pub(crate) fn internal_error(payload: Box<dyn std::any::Any + Send>) -> PyErr {
    let what = payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".to_string());
    PyRuntimeError::new_err(format!(
        "internal error: {what}; this is a bug in camlink, please report it with the model that caused it"
    ))
}

pub(crate) fn model_error(e: impl std::fmt::Display) -> PyErr {
    ModelError::new_err(e.to_string())
}

/// The Python `AnalysisError` for a core analysis error, with the partial
/// results attached.
pub(crate) fn analysis_error(
    py: Python<'_>,
    e: &CoreAnalysisError,
    names: Vec<String>,
    quantities: Vec<&'static str>,
    data: Option<Bound<'_, PyArray2<f64>>>,
) -> PyErr {
    let err = AnalysisError::new_err(e.to_string());
    let value = err.value(py);
    let set = || -> PyResult<()> {
        value.setattr("kind", e.kind.name())?;
        value.setattr("time", e.time)?;
        value.setattr("joints", e.joints.clone())?;
        value.setattr("residual", e.residual)?;
        value.setattr("names", names)?;
        value.setattr("quantities", quantities)?;
        match data {
            Some(d) => value.setattr("data", d)?,
            None => value.setattr("data", py.None())?,
        }
        Ok(())
    };
    match set() {
        Ok(()) => err,
        Err(e) => e,
    }
}
