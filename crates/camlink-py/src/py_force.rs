//! Forces written as Python functions, called from the core.

use camlink_core::force::ForceError;
use pyo3::prelude::*;

use crate::ModelError;

thread_local! {
    /// The exception of the Python force function that stopped the run on
    /// this thread, for [`Model::run_with`] to chain as the `__cause__` of
    /// the `force_failed` error.
    pub(crate) static FORCE_ERROR: std::cell::RefCell<Option<PyErr>> = const { std::cell::RefCell::new(None) };
}

/// Calls a Python force function `f(t, q, qd) -> (fx, fy, n)`; on an
/// exception or a bad return value, keeps the exception in [`FORCE_ERROR`]
/// and returns a [`ForceError`] that stops the run.
pub(crate) fn call_force(
    f: &Py<PyAny>,
    t: f64,
    q: [f64; 3],
    qd: [f64; 3],
) -> Result<[f64; 3], ForceError> {
    let result = Python::attach(|py| -> PyResult<[f64; 3]> {
        let out = f.call1(py, (t, (q[0], q[1], q[2]), (qd[0], qd[1], qd[2])))?;
        out.extract::<[f64; 3]>(py).map_err(|_| {
            let got = out
                .bind(py)
                .repr()
                .map(|r| r.to_string())
                .unwrap_or_else(|_| "?".to_string());
            ModelError::new_err(format!(
                "a force function must return three numbers (fx, fy, torque), not {got}"
            ))
        })
    });
    result.map_err(|e| {
        let what = Python::attach(|py| {
            let kind = e
                .get_type(py)
                .name()
                .map(|n| n.to_string())
                .unwrap_or_else(|_| "exception".to_string());
            let text = e.value(py).to_string();
            let text: String = text.chars().take(200).collect();
            if text.is_empty() {
                kind
            } else {
                format!("{kind}: {text}")
            }
        });
        FORCE_ERROR.with(|slot| *slot.borrow_mut() = Some(e));
        ForceError(what)
    })
}
