//! Binding of the exports' geometry (`camlink_cam::export`): cam angles by
//! step or chordal tolerance, and lines and arcs fitted to a profile.
//! Converts only.

use camlink_cam::export;
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::cam::CamCore;

/// A fitted piece: (centre (m), radius (m, inf for a line), start and end
/// (deg), first and last point (m)).
type ArcRow = ([f64; 2], f64, f64, f64, [f64; 2], [f64; 2]);

/// Cam angles θ (rad) over one turn at `step` (rad), the end excluded;
/// ValueError for a step that is not positive or makes too many rows.
#[pyfunction]
pub(crate) fn cam_angles_by_step(py: Python<'_>, step: f64) -> PyResult<Bound<'_, PyArray1<f64>>> {
    let th = export::angles_by_step(step).map_err(PyValueError::new_err)?;
    Ok(th.into_pyarray(py))
}

/// ValueError when `tolerance` (m) is not positive or is too fine for the
/// size of the curve `offset` (m) outside `core`'s surface.
#[pyfunction]
#[pyo3(signature = (core, tolerance, offset = 0.0))]
pub(crate) fn cam_check_tolerance(
    core: PyRef<'_, CamCore>,
    tolerance: f64,
    offset: f64,
) -> PyResult<()> {
    export::check_tolerance(&core.cam, tolerance, offset).map_err(PyValueError::new_err)
}

/// Cam angles θ (rad) of the curve `offset` (m) outside `core`'s surface
/// within the chordal `tolerance` (m); with `check`, the tolerance is held
/// to the curve's size first.
#[pyfunction]
#[pyo3(signature = (core, tolerance, offset = 0.0, check = true))]
pub(crate) fn cam_angles_by_chord<'py>(
    py: Python<'py>,
    core: PyRef<'py, CamCore>,
    tolerance: f64,
    offset: f64,
    check: bool,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let cam = core.cam.clone();
    let th = py
        .detach(|| {
            if check {
                export::angles_by_chord(&cam, tolerance, offset)
            } else {
                export::chord_angles(|t| cam.offset_point(t, offset), tolerance)
            }
        })
        .map_err(PyValueError::new_err)?;
    Ok(th.into_pyarray(py))
}

/// Lines and arcs covering the closed polygon `points` ((n, 2), m), each
/// within `tolerance` − `slack` (m) of its run of points.
#[pyfunction]
#[pyo3(signature = (points, tolerance, slack = 0.0))]
pub(crate) fn cam_fit_arcs(
    py: Python<'_>,
    points: PyReadonlyArray2<'_, f64>,
    tolerance: f64,
    slack: f64,
) -> PyResult<Vec<ArcRow>> {
    let a = points.as_array();
    if a.ncols() != 2 {
        return Err(PyValueError::new_err(format!(
            "points must be (n, 2), got (n, {})",
            a.ncols()
        )));
    }
    let pts: Vec<[f64; 2]> = a.rows().into_iter().map(|r| [r[0], r[1]]).collect();
    let arcs = py
        .detach(|| export::fit_arcs(&pts, tolerance, slack))
        .map_err(PyValueError::new_err)?;
    Ok(arcs
        .into_iter()
        .map(|a| (a.centre, a.radius, a.start, a.end, a.p0, a.p1))
        .collect())
}

/// The bounds of the exports' geometry: `max_points`, the most angles
/// `cam_angles_by_chord` gives.
#[pyfunction]
pub(crate) fn cam_export_limits(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("max_points", export::MAX_POINTS)?;
    Ok(d)
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(cam_angles_by_step, m)?)?;
    m.add_function(wrap_pyfunction!(cam_check_tolerance, m)?)?;
    m.add_function(wrap_pyfunction!(cam_angles_by_chord, m)?)?;
    m.add_function(wrap_pyfunction!(cam_fit_arcs, m)?)?;
    m.add_function(wrap_pyfunction!(cam_export_limits, m)?)?;
    Ok(())
}
