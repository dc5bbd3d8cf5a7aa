//! Binding of the model-file tools of camlink-model: the converter between
//! frame and global form, and the check of a model under construction that
//! the builder runs at each call. Converts only.

use std::path::PathBuf;

use camlink_model::convert::{convert_path, Form};
use camlink_model::LoadOptions;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::{guard, model_error, model_format, ModelError};

/// The model file at `path` rewritten in `form`, `"global"` (bodies by
/// `global_points`) or `"frame"` (bodies by `points`), and the names of
/// the bodies rewritten. Raises `ModelError` for a file that does not load.
#[pyfunction]
#[pyo3(signature = (path, form, allow_outside = false))]
fn convert_model(
    py: Python<'_>,
    path: PathBuf,
    form: &str,
    allow_outside: bool,
) -> PyResult<(String, Vec<String>)> {
    guard(|| {
        let form = match form {
            "global" => Form::Global,
            "frame" => Form::Frame,
            other => {
                return Err(ModelError::new_err(format!(
                    "unknown form '{other}' (expected 'global' or 'frame')"
                )))
            }
        };
        let options = LoadOptions {
            base_dir: None,
            allow_outside_data: allow_outside,
        };
        py.detach(|| convert_path(&path, form, &options))
            .map_err(model_error)
    })
}

/// The first error of the model `text` (`format` `"toml"` or `"json"`) as
/// a dict of `field` (the field path, or None), `message`, `line` and
/// `column` (None where unknown); None when it loads. Data files resolve
/// against `base_dir` (default: the current folder).
#[pyfunction]
#[pyo3(signature = (text, format, base_dir = None))]
fn model_error_of<'py>(
    py: Python<'py>,
    text: &str,
    format: &str,
    base_dir: Option<PathBuf>,
) -> PyResult<Option<Bound<'py, PyDict>>> {
    guard(|| {
        let format = model_format(format)?;
        let options = LoadOptions {
            base_dir: Some(base_dir.unwrap_or_else(|| PathBuf::from("."))),
            allow_outside_data: false,
        };
        let Err(e) = camlink_model::load_str_with(text, format, "<model>", &options) else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        d.set_item("field", e.field)?;
        d.set_item("message", e.message)?;
        d.set_item("line", e.line)?;
        d.set_item("column", e.column)?;
        Ok(Some(d))
    })
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(convert_model, m)?)?;
    m.add_function(wrap_pyfunction!(model_error_of, m)?)?;
    Ok(())
}
