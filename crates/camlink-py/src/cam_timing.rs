//! Binding of timing files (`camlink_cam::timing`): the checked file as
//! plain Python data for `camlink.cam.timing`, and its motion, clearances
//! and cam tables as arrays. Converts only.

use std::path::PathBuf;

use camlink_cam::timing::{self, LoadedTiming, Timing};
use numpy::{PyArray2, PyReadonlyArray1};
use pyo3::exceptions::{PyIndexError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::cam_design::design_dict;
use crate::{to_array, ModelError};

/// A checked timing file (`camlink_cam::timing::Timing`); axes are named by
/// their index in the file.
#[pyclass(frozen, module = "camlink._core")]
pub struct TimingCore {
    timing: Timing,
}

impl TimingCore {
    fn axis(&self, k: usize) -> PyResult<&timing::Axis> {
        self.timing
            .axes
            .get(k)
            .ok_or_else(|| PyIndexError::new_err(format!("no axis {k}")))
    }
}

/// An (n, N) array: `f` of each of the n values of `x` (any strides).
fn rows<'py, const N: usize>(
    py: Python<'py>,
    x: &PyReadonlyArray1<'py, f64>,
    f: impl Fn(f64) -> [f64; N],
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    to_array(py, x.as_array().iter().flat_map(|&v| f(v)).collect(), N)
}

fn unknown_unit(units: &str) -> PyErr {
    PyValueError::new_err(format!(
        "'{units}' is not one of {}",
        timing::UNITS.join(", ")
    ))
}

#[pymethods]
impl TimingCore {
    /// [s, s′, s″, s‴] of axis `k` at each master angle Θ (rad): (n, 4),
    /// derivatives per radian of the master.
    fn motion<'py>(
        &self,
        py: Python<'py>,
        k: usize,
        master: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let axis = self.axis(k)?;
        rows(py, &master, |t| axis.motion(t))
    }

    /// The tip (m) of axis `k`'s follower at each displacement s (m): (n, 2).
    fn tips<'py>(
        &self,
        py: Python<'py>,
        k: usize,
        s: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let axis = self.axis(k)?;
        rows(py, &s, |s| axis.tip(s))
    }

    /// Each clearance over a master turn: (a, b, least (m), at (deg),
    /// limit (m), ok), a and b axis indices.
    fn clearances(&self, py: Python<'_>) -> Vec<(usize, usize, f64, f64, f64, bool)> {
        py.detach(|| self.timing.clearances())
            .into_iter()
            .map(|c| (c.a, c.b, c.least, c.at_deg, c.limit, c.ok))
            .collect()
    }

    /// The cam table of axis `k` in `units` (m or mm): rows [master (deg),
    /// position, velocity, acceleration, jerk].
    fn table<'py>(
        &self,
        py: Python<'py>,
        k: usize,
        units: &str,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.axis(k)?;
        let rows = self
            .timing
            .table(k, units)
            .ok_or_else(|| unknown_unit(units))?;
        to_array(py, rows.into_iter().flatten().collect(), 5)
    }

    /// The segment table of axis `k` in `units`: a dict per segment (keys
    /// and order of the segment CSV's columns).
    fn segments<'py>(
        &self,
        py: Python<'py>,
        k: usize,
        units: &str,
    ) -> PyResult<Vec<Bound<'py, PyDict>>> {
        self.axis(k)?;
        let rows = self
            .timing
            .segments(k, units)
            .ok_or_else(|| unknown_unit(units))?;
        rows.into_iter()
            .map(|r| {
                let d = PyDict::new(py);
                d.set_item("segment", r.segment)?;
                d.set_item("law", r.law)?;
                d.set_item("start_deg", r.start_deg)?;
                d.set_item("end_deg", r.end_deg)?;
                d.set_item("lift", r.lift)?;
                d.set_item("continuity_start", format!("C{}", r.continuity_start))?;
                d.set_item("continuity_end", format!("C{}", r.continuity_end))?;
                d.set_item("peak_velocity", r.peak_velocity.0)?;
                d.set_item("peak_velocity_deg", r.peak_velocity.1)?;
                d.set_item("max_acceleration", r.max_acceleration.0)?;
                d.set_item("max_acceleration_deg", r.max_acceleration.1)?;
                d.set_item("min_acceleration", r.min_acceleration.0)?;
                d.set_item("min_acceleration_deg", r.min_acceleration.1)?;
                d.set_item("peak_acceleration", r.peak_acceleration)?;
                Ok(d)
            })
            .collect()
    }
}

/// Reads and checks the timing file at `path` and its design files:
/// the core, the file as a dict (SI units, radians; each axis with its
/// design as `cam_design_read` gives it) and the design files' warnings.
/// Raises `ModelError` naming the file, line and field.
#[pyfunction]
pub(crate) fn cam_timing_read<'py>(
    py: Python<'py>,
    path: PathBuf,
) -> PyResult<(TimingCore, Bound<'py, PyDict>, Vec<String>)> {
    let LoadedTiming { timing, warnings } = py
        .detach(|| timing::load_path(&path))
        .map_err(|e| ModelError::new_err(e.to_string()))?;
    let d = PyDict::new(py);
    d.set_item("name", &timing.name)?;
    d.set_item("speed", timing.speed)?;
    d.set_item("resolution", timing.resolution)?;
    d.set_item("units", &timing.units)?;
    let axes = timing
        .axes
        .iter()
        .map(|a| {
            let t = PyDict::new(py);
            t.set_item("name", &a.name)?;
            t.set_item("design", design_dict(py, &a.design)?)?;
            t.set_item("design_path", &a.design.source)?;
            t.set_item("phase", a.phase)?;
            t.set_item("origin", a.origin)?;
            t.set_item("direction", a.direction)?;
            Ok(t)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("axes", axes)?;
    let clearances: Vec<_> = timing
        .clearances
        .iter()
        .map(|c| (c.a, c.b, c.min_distance))
        .collect();
    d.set_item("clearances", clearances)?;
    d.set_item("diagram", &timing.diagram)?;
    d.set_item("tables", timing.tables)?;
    Ok((TimingCore { timing }, d, warnings))
}

/// Whether the file at `path` is a timing file (TOML with `axes`).
#[pyfunction]
pub(crate) fn cam_is_timing(path: PathBuf) -> bool {
    timing::is_timing_path(&path)
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<TimingCore>()?;
    m.add_function(wrap_pyfunction!(cam_timing_read, m)?)?;
    m.add_function(wrap_pyfunction!(cam_is_timing, m)?)?;
    Ok(())
}
