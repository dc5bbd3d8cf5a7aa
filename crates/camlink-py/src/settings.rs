//! Binding of the run-setting rules ([`camlink_model::analysis`]): which
//! settings each analysis takes, the messages for those it does not, the
//! default output and integration steps and the rule of output times.
//! Converts only.

use camlink_model::{AnalysisSpec, AnalysisType, DynamicsSpec};
use numpy::PyReadonlyArray1;
use pyo3::prelude::*;

use crate::ModelError;
use pyo3::types::PyDict;

/// The run settings each analysis takes (besides `output`), as
/// `{type: [key, …]}`.
#[pyfunction]
fn analysis_settings(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    for kind in AnalysisType::ALL {
        d.set_item(kind.name(), kind.settings())?;
    }
    Ok(d)
}

/// The message for setting `key` given to the analysis `kind` that does
/// not take it, naming the analyses that do.
#[pyfunction]
fn not_applicable(key: &str, kind: &str) -> String {
    camlink_model::not_applicable(key, &format!("the {kind} analysis"))
}

/// The integration step (s) of a forward-dynamics run: `h`, else the
/// output step `step` but at most 1 ms, else 1 ms.
#[pyfunction]
#[pyo3(signature = (h = None, step = None))]
fn integration_step(h: Option<f64>, step: Option<f64>) -> f64 {
    DynamicsSpec::integration_step(h, step)
}

/// The output step (s) when none is given: a hundredth of `t_end` (s),
/// or 1 s when `t_end` is 0.
#[pyfunction]
fn default_step(t_end: f64) -> f64 {
    AnalysisSpec::default_step(t_end)
}

/// Checks a run's output times (s): at least one, finite, each after the
/// one before; raises `ModelError` saying which rule a time breaks.
#[pyfunction]
fn check_times(times: PyReadonlyArray1<'_, f64>) -> PyResult<()> {
    let times = times.as_array();
    let times = times
        .as_slice()
        .map_or_else(|| times.to_vec(), <[f64]>::to_vec);
    camlink_core::run::check_times(&times).map_err(|(_, e)| ModelError::new_err(e))
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(analysis_settings, m)?)?;
    m.add_function(wrap_pyfunction!(not_applicable, m)?)?;
    m.add_function(wrap_pyfunction!(integration_step, m)?)?;
    m.add_function(wrap_pyfunction!(check_times, m)?)?;
    m.add_function(wrap_pyfunction!(default_step, m)?)?;
    Ok(())
}
