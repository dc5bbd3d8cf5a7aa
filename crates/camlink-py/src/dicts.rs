//! Core results as Python dicts: a joint sketch's marks and a run's
//! summary, with its flights, impacts and lift-off intervals.

use camlink_core::constraint::sketch::{Mark, Side};
use camlink_core::run::{LiftOff, Summary};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::to_array;

/// One mark of a joint's sketch as a dict (see `Model.geometry`); `bodies`
/// names the joint's bodies i and j; a curve is sampled for drawing
/// (`closed`, and `points` n × 2, body frame, m) within `tol` (m).
pub(crate) fn mark_dict<'py>(
    py: Python<'py>,
    mark: &Mark,
    bodies: [&String; 2],
    tol: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let body = |side: Side| match side {
        Side::I => bodies[0],
        Side::J => bodies[1],
    };
    match *mark {
        Mark::Pin { s_i, s_j } | Mark::Rod { s_i, s_j } => {
            let shape = if matches!(mark, Mark::Pin { .. }) {
                "pin"
            } else {
                "rod"
            };
            d.set_item("shape", shape)?;
            d.set_item("s_i", s_i)?;
            d.set_item("s_j", s_j)?;
        }
        Mark::Guide { s_i, v_i, s_j } => {
            d.set_item("shape", "guide")?;
            d.set_item("s_i", s_i)?;
            d.set_item("v_i", v_i)?;
            d.set_item("s_j", s_j)?;
        }
        Mark::Slider { side, s } => {
            d.set_item("shape", "slider")?;
            d.set_item("body", body(side))?;
            d.set_item("s", s)?;
        }
        Mark::Face { side, s, u } => {
            d.set_item("shape", "face")?;
            d.set_item("body", body(side))?;
            d.set_item("s", s)?;
            d.set_item("u", u)?;
        }
        Mark::Circle {
            side,
            s,
            radius,
            internal,
        } => {
            d.set_item("shape", "circle")?;
            d.set_item("body", body(side))?;
            d.set_item("s", s)?;
            d.set_item("radius", radius)?;
            d.set_item("internal", internal)?;
        }
        Mark::Curve { side, curve, role } => {
            let pts = curve.sample(tol);
            let flat: Vec<f64> = pts.iter().flat_map(|(_, p)| [p[0], p[1]]).collect();
            d.set_item("shape", "curve")?;
            d.set_item("body", body(side))?;
            d.set_item("role", role.drawn(curve.closed()))?;
            d.set_item("closed", curve.closed())?;
            d.set_item("points", to_array(py, flat, 2)?)?;
        }
    }
    Ok(d)
}

/// The run summary as a dict: counts, `warnings` as dicts (`kind`, `time`,
/// `joints`, `message`), `assembly_moves` as (body, (Δx, Δy, Δφ)) pairs,
/// `lift_off`, `flights` and `impacts` as lists of dicts, and the drifts.
pub(crate) fn summary_dict<'py>(py: Python<'py>, s: &Summary) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("steps", s.steps)?;
    d.set_item("newton_iterations", s.newton_iterations)?;
    d.set_item("factorizations", s.factorizations)?;
    d.set_item("halvings", s.halvings)?;
    let warnings = PyList::empty(py);
    for w in &s.warnings {
        let wd = PyDict::new(py);
        wd.set_item("kind", w.kind.name())?;
        wd.set_item("time", w.time)?;
        wd.set_item("joints", w.joints.clone())?;
        wd.set_item("message", &w.message)?;
        warnings.append(wd)?;
    }
    d.set_item("warnings", warnings)?;
    d.set_item("assembly_moves", s.assembly_moves.clone())?;
    let lift_off = PyList::empty(py);
    for l in &s.lift_off {
        lift_off.append(lift_off_dict(py, l)?)?;
    }
    d.set_item("lift_off", lift_off)?;
    let flights = PyList::empty(py);
    for f in &s.flights {
        flights.append(flight_dict(py, f)?)?;
    }
    d.set_item("flights", flights)?;
    let impacts = PyList::empty(py);
    for i in &s.impacts {
        impacts.append(impact_dict(py, i)?)?;
    }
    d.set_item("impacts", impacts)?;
    if let Some(drift) = s.drift {
        d.set_item("energy_drift", drift.energy)?;
        d.set_item("constraint_drift", drift.constraint)?;
        d.set_item("velocity_drift", drift.velocity)?;
    }
    Ok(d)
}

/// A flight of a unilateral contact as a dict: `joint`, `cam`,
/// `start_time` (s), `start_cam_angle` (rad), `end_time` (s) and
/// `end_cam_angle` (rad), None when the run ends in flight,
/// `greatest_gap` (m), `greatest_time` (s), `greatest_cam_angle` (rad).
fn flight_dict<'py>(
    py: Python<'py>,
    f: &camlink_core::run::Flight,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("joint", &f.joint)?;
    d.set_item("cam", &f.cam)?;
    d.set_item("start_time", f.start.time)?;
    d.set_item("start_cam_angle", f.start.cam_angle)?;
    d.set_item("end_time", f.end.map(|e| e.time))?;
    d.set_item("end_cam_angle", f.end.map(|e| e.cam_angle))?;
    d.set_item("greatest_gap", f.greatest_gap)?;
    d.set_item("greatest_time", f.greatest_at.time)?;
    d.set_item("greatest_cam_angle", f.greatest_at.cam_angle)?;
    Ok(d)
}

/// An impact as a dict: `joint`, `time` (s), `cam_angle` (rad),
/// `approach_speed` and `separation_speed` (m/s), `impulse` (N·s),
/// `closed` (bool).
fn impact_dict<'py>(
    py: Python<'py>,
    i: &camlink_core::run::Impact,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("joint", &i.joint)?;
    d.set_item("time", i.at.time)?;
    d.set_item("cam_angle", i.at.cam_angle)?;
    d.set_item("approach_speed", i.approach)?;
    d.set_item("separation_speed", i.separation)?;
    d.set_item("impulse", i.impulse)?;
    d.set_item("closed", i.closed)?;
    Ok(d)
}

/// A lift-off interval as a dict: `joint`, `cam`, `start_time` (s),
/// `start_cam_angle` (rad), `end_time` (s) and `end_cam_angle` (rad), None
/// when the run ends in lift-off, `least_force` (N), `least_time` (s),
/// `least_cam_angle` (rad).
fn lift_off_dict<'py>(py: Python<'py>, l: &LiftOff) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("joint", &l.joint)?;
    d.set_item("cam", &l.cam)?;
    d.set_item("start_time", l.start.time)?;
    d.set_item("start_cam_angle", l.start.cam_angle)?;
    d.set_item("end_time", l.end.map(|e| e.time))?;
    d.set_item("end_cam_angle", l.end.map(|e| e.cam_angle))?;
    d.set_item("least_force", l.least)?;
    d.set_item("least_time", l.least_at.time)?;
    d.set_item("least_cam_angle", l.least_at.cam_angle)?;
    Ok(d)
}
