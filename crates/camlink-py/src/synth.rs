//! Binding of linkage synthesis: a problem file solved by camlink-synth.
//! Converts only; `camlink.synth` builds the Python objects and reports.

use std::path::PathBuf;

use pyo3::prelude::*;

use crate::{guard, model_error};

/// One solution: (name, model file text in TOML, report as JSON text).
type SolutionRow = (String, String, String);

fn rows(out: camlink_synth::Outcome) -> (String, Vec<SolutionRow>) {
    let rows = out
        .solutions
        .into_iter()
        .map(|s| (s.name, s.model, s.report.to_string()))
        .collect();
    (out.kind, rows)
}

/// Solves the synthesis problem file at `path`: (kind, solutions).
#[pyfunction]
fn synth_file(py: Python<'_>, path: PathBuf) -> PyResult<(String, Vec<SolutionRow>)> {
    guard(|| {
        let out = py.detach(|| camlink_synth::solve_path(&path));
        out.map(rows).map_err(model_error)
    })
}

/// Solves the synthesis problem in `text`; `source` names it in errors,
/// `stem` names the solutions unless the problem gives `name`.
#[pyfunction]
fn synth_str(text: &str, source: &str, stem: &str) -> PyResult<(String, Vec<SolutionRow>)> {
    guard(|| {
        camlink_synth::solve_str(text, source, stem)
            .map(rows)
            .map_err(model_error)
    })
}

/// Adds the synthesis functions to `_core`.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(synth_file, m)?)?;
    m.add_function(wrap_pyfunction!(synth_str, m)?)?;
    Ok(())
}
