//! Bindings of camlink studies: model variants and batched runs.

use std::collections::HashMap;
use std::time::Duration;

use camlink_model::Loaded;
use camlink_study::{BatchSettings, Reduction};
use numpy::ndarray::Array2;
use numpy::{PyArray2, ToPyArray};
use pyo3::prelude::*;

use crate::{guard, model_error, Model, ModelError};

/// `base` with the `[parameters]` in `values` changed.
pub(crate) fn with_parameters(base: &Loaded, values: HashMap<String, f64>) -> PyResult<Model> {
    let mut values: Vec<(String, f64)> = values.into_iter().collect();
    values.sort_by(|a, b| a.0.cmp(&b.0));
    let loaded = base.with_parameters(&values).map_err(model_error)?;
    Ok(Model { loaded })
}

/// What `run_batch` returns: outputs (variants × outputs), status names,
/// error messages.
type BatchOutput<'py> = (Bound<'py, PyArray2<f64>>, Vec<&'static str>, Vec<String>);

/// Runs each parameter set of `variants` (dicts name → value) on `model`
/// with its file's `[analysis]`, on `threads` threads (default: all cores)
/// with the GIL released, and reduces each run to `outputs`: (name, JSON
/// declaration) pairs, e.g. `("swing", '{"kind": "range", "channel":
/// "rocker.phi"}')`. A variant taking longer than `time_limit` seconds is
/// stopped. Returns the outputs (one row per variant, NaN where not
/// computed), each variant's status (`ok`, `model_error`, `analysis_error`,
/// `output_error`, `internal_error`) and error message ("" when ok).
#[pyfunction]
#[pyo3(signature = (model, variants, outputs, *, threads = None, time_limit = None))]
pub(crate) fn run_batch<'py>(
    py: Python<'py>,
    model: &Model,
    variants: Vec<HashMap<String, f64>>,
    outputs: Vec<(String, String)>,
    threads: Option<usize>,
    time_limit: Option<f64>,
) -> PyResult<BatchOutput<'py>> {
    guard(|| {
        let outputs = outputs
            .iter()
            .map(|(name, spec)| Ok((name.clone(), Reduction::from_json(name, spec)?)))
            .collect::<Result<Vec<_>, String>>()
            .map_err(ModelError::new_err)?;
        let time_limit = match time_limit {
            None => None,
            Some(s) if s > 0.0 && s.is_finite() => Some(Duration::from_secs_f64(s)),
            Some(s) => {
                return Err(ModelError::new_err(format!(
                    "time_limit must be a positive number of seconds ({s})"
                )))
            }
        };
        let variants: Vec<Vec<(String, f64)>> = variants
            .into_iter()
            .map(|v| {
                let mut v: Vec<(String, f64)> = v.into_iter().collect();
                v.sort_by(|a, b| a.0.cmp(&b.0));
                v
            })
            .collect();
        let settings = BatchSettings {
            threads,
            time_limit,
        };
        let base = &model.loaded;
        let outcomes = py
            .detach(|| camlink_study::run_batch(base, &variants, &outputs, &settings))
            .map_err(ModelError::new_err)?;
        let mut values = Array2::<f64>::from_elem((outcomes.len(), outputs.len()), f64::NAN);
        let mut status = Vec::with_capacity(outcomes.len());
        let mut errors = Vec::with_capacity(outcomes.len());
        for (k, o) in outcomes.into_iter().enumerate() {
            for (j, v) in o.values.iter().enumerate() {
                values[[k, j]] = *v;
            }
            status.push(o.status.name());
            errors.push(o.error);
        }
        Ok((values.to_pyarray(py), status, errors))
    })
}

/// The 1-based (line, column) of the field `path` (e.g.
/// `study.parameters.a`) in TOML `text`, or None.
#[pyfunction]
pub(crate) fn toml_position(text: &str, path: &str) -> Option<(usize, usize)> {
    camlink_model::toml_position(text, path)
}
