//! Binding of linkage synthesis: a problem file solved by camlink-synth.
//! Converts only; `camlink.synth` builds the Python objects and reports.

use std::path::PathBuf;

use camlink_synth::path::Start;
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

/// The text of the problem file at `path` (checked for size and UTF-8).
#[pyfunction]
fn synth_read(path: PathBuf) -> PyResult<String> {
    guard(|| camlink_synth::problem::read_file(&path).map_err(model_error))
}

/// One refined start of a path search: its index and parameters.
type StartRow = (usize, Vec<f64>);

/// Runs starts `lo`..`hi` of the search of the path problem in `text`:
/// (the starts that converged, the number of starts the problem asks for);
/// no starts and 0 for a problem without a search.
#[pyfunction]
fn synth_path_starts(
    py: Python<'_>,
    text: &str,
    source: &str,
    stem: &str,
    lo: usize,
    hi: usize,
) -> PyResult<(Vec<StartRow>, usize)> {
    guard(|| {
        let out = py.detach(|| camlink_synth::path_starts(text, source, stem, lo..hi.max(lo)));
        out.map(|(starts, total)| (starts.into_iter().map(|s| (s.k, s.x)).collect(), total))
            .map_err(model_error)
    })
}

/// Solves the path problem in `text` from the refined `starts` of its
/// whole search (run by `synth_path_starts`, joined in any order).
#[pyfunction]
fn synth_str_from_starts(
    py: Python<'_>,
    text: &str,
    source: &str,
    stem: &str,
    starts: Vec<StartRow>,
) -> PyResult<(String, Vec<SolutionRow>)> {
    guard(|| {
        let starts: Vec<Start> = starts.into_iter().map(|(k, x)| Start { k, x }).collect();
        let out = py.detach(|| camlink_synth::solve_str_from_starts(text, source, stem, &starts));
        out.map(rows).map_err(model_error)
    })
}

/// Adds the synthesis functions to `_core`.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(synth_file, m)?)?;
    m.add_function(wrap_pyfunction!(synth_str, m)?)?;
    m.add_function(wrap_pyfunction!(synth_read, m)?)?;
    m.add_function(wrap_pyfunction!(synth_path_starts, m)?)?;
    m.add_function(wrap_pyfunction!(synth_str_from_starts, m)?)?;
    Ok(())
}
