//! Bindings of camlink studies: model variants and batched runs.

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc};
use std::time::Duration;

use camlink_model::file::Num;
use camlink_model::Loaded;
use camlink_study::declaration::{self, Value};
use camlink_study::{BatchSettings, Reduction};
use numpy::ndarray::Array2;
use numpy::{PyArray2, ToPyArray};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::{guard, model_error, Model, ModelError};

/// A new value of a parameter: a number, or an expression string as the
/// file's `[parameters]` take.
#[derive(FromPyObject)]
pub(crate) enum ParameterValue {
    Number(f64),
    Expression(String),
}

/// `base` with the `[parameters]` in `values` changed.
pub(crate) fn with_parameters(
    base: &Loaded,
    values: HashMap<String, ParameterValue>,
) -> PyResult<Model> {
    let mut values: Vec<(String, Num)> = values
        .into_iter()
        .map(|(name, v)| {
            let v = match v {
                ParameterValue::Number(x) => Num::Value(x),
                ParameterValue::Expression(src) => Num::Expr(src),
            };
            (name, v)
        })
        .collect();
    values.sort_by(|a, b| a.0.cmp(&b.0));
    let loaded = base.with_parameter_values(&values).map_err(model_error)?;
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
                    "time_limit must be a positive number of seconds ({})",
                    camlink_core::fmt_num::num(s)
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
        let stop = Arc::new(AtomicBool::new(false));
        let settings = BatchSettings {
            threads,
            time_limit,
            stop: Some(Arc::clone(&stop)),
        };
        let base = &model.loaded;
        let (variants, declared) = (&variants, &outputs);
        let (outcomes, interrupted) = py.detach(|| {
            std::thread::scope(|s| {
                let (done, finished) = mpsc::channel::<()>();
                let batch = s.spawn(move || {
                    let out = camlink_study::run_batch(base, variants, declared, &settings);
                    let _ = done.send(());
                    out
                });
                let interrupted = watch_signals(&finished, &stop);
                (batch.join(), interrupted)
            })
        });
        if let Some(e) = interrupted {
            return Err(e);
        }
        let outcomes = outcomes
            .map_err(crate::internal_error)?
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

/// How often a running batch looks for Ctrl-C and other signals.
const SIGNAL_INTERVAL: Duration = Duration::from_millis(50);

/// Runs Python's signal handlers every [`SIGNAL_INTERVAL`] until the
/// batch says it has `finished`; when one raises (Ctrl-C), sets `stop` so
/// that the batch ends at the next step of each run, and returns the
/// exception.
fn watch_signals(finished: &mpsc::Receiver<()>, stop: &AtomicBool) -> Option<PyErr> {
    while let Err(mpsc::RecvTimeoutError::Timeout) = finished.recv_timeout(SIGNAL_INTERVAL) {
        if let Err(e) = Python::attach(|py| py.check_signals()) {
            stop.store(true, Ordering::Relaxed);
            return Some(e);
        }
    }
    None
}

/// The 1-based (line, column) of the field `path` (e.g.
/// `study.parameters.a`) in TOML `text`, or None.
#[pyfunction]
pub(crate) fn toml_position(text: &str, path: &str) -> Option<(usize, usize)> {
    camlink_model::toml_position(text, path)
}

/// The study output kinds and the fields each needs, as
/// `{kind: [field, …]}` ([`declaration::KINDS`]).
#[pyfunction]
pub(crate) fn output_kinds(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    for &(kind, needed, _) in declaration::KINDS {
        d.set_item(kind, needed.to_vec())?;
    }
    Ok(d)
}

/// A field's value in an output declaration, as Python gives it.
#[derive(FromPyObject)]
enum FieldValue {
    Flag(bool),
    Number(f64),
    Text(String),
    List(Vec<FieldValue>),
    Other(Py<PyAny>),
}

impl FieldValue {
    fn value(self, py: Python<'_>) -> Value {
        match self {
            FieldValue::Flag(b) => Value::Flag(b),
            FieldValue::Number(x) => Value::Number(x),
            FieldValue::Text(s) => Value::Text(s),
            FieldValue::List(items) => {
                Value::List(items.into_iter().map(|v| v.value(py)).collect())
            }
            FieldValue::Other(o) => Value::Other(
                o.bind(py)
                    .repr()
                    .map_or_else(|_| "?".to_string(), |r| r.to_string()),
            ),
        }
    }
}

/// Checks the output declaration `spec` (a dict with its `kind`) at
/// `field` by [`declaration::declared`]; raises `ModelError` naming the
/// output and the field at fault.
#[pyfunction]
pub(crate) fn check_output(field: &str, spec: &Bound<'_, PyDict>) -> PyResult<()> {
    let py = spec.py();
    let mut fields = Vec::with_capacity(spec.len());
    for (key, value) in spec.iter() {
        let key = key.str()?.to_string();
        fields.push((key, value.extract::<FieldValue>()?.value(py)));
    }
    declaration::declared(field, &fields)
        .map(|_| ())
        .map_err(ModelError::new_err)
}
