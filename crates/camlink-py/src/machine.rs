//! Binding of the machine analysis ([`camlink_core::machine`]): a model
//! file's `[machine]` table run and its report as a dict of numbers and
//! arrays. Converts only; `camlink.machine` presents it.

use std::path::PathBuf;

use camlink_core::machine::{analyse, Report};
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::{analysis_error, guard, model_error};

/// The machine report of the model file at `path` (its `[machine]` table):
/// SI units, angles in rad.
#[pyfunction]
pub fn machine_report(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyDict>> {
    guard(|| {
        let loaded = py
            .detach(|| camlink_model::load_path(&path))
            .map_err(model_error)?;
        let Some(spec) = loaded.machine.clone() else {
            return Err(model_error(format!(
                "{}: no [machine] table (see docs/machine.md)",
                path.display()
            )));
        };
        let report = py
            .detach(|| analyse(&loaded.model, &spec))
            .map_err(|e| analysis_error(py, &e, Vec::new(), Vec::new(), None))?;
        to_dict(py, &report, &spec)
    })
}

fn to_dict<'py>(
    py: Python<'py>,
    r: &Report,
    spec: &camlink_core::machine::Spec,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let arr = |v: &[f64]| v.to_vec().into_pyarray(py);
    d.set_item("driver", &spec.driver)?;
    d.set_item("speed", r.speed)?;
    d.set_item("period", r.period)?;
    d.set_item("theta", arr(&r.theta))?;
    d.set_item("torque", arr(&r.torque))?;

    let s = PyDict::new(py);
    let sh = &r.shaking;
    s.set_item("fx", arr(&sh.fx))?;
    s.set_item("fy", arr(&sh.fy))?;
    s.set_item("moment", arr(&sh.moment))?;
    s.set_item("point", spec.point.to_vec())?;
    s.set_item("peak_force", sh.peak_force)?;
    s.set_item("peak_at", sh.peak_at)?;
    s.set_item("peak_dynamic", sh.peak_dynamic)?;
    s.set_item("peak_moment", sh.peak_moment)?;
    s.set_item("weight", sh.weight.to_vec())?;
    d.set_item("shaking", s)?;

    match &r.balance {
        None => d.set_item("balance", py.None())?,
        Some(Err(why)) => {
            let b = PyDict::new(py);
            b.set_item("error", why)?;
            d.set_item("balance", b)?;
        }
        Some(Ok(bal)) => {
            let b = PyDict::new(py);
            b.set_item("linkage", bal.linkage)?;
            b.set_item("balanced", bal.balanced)?;
            let list = PyList::empty(py);
            for c in &bal.counterweights {
                let cw = PyDict::new(py);
                cw.set_item("body", &c.body)?;
                cw.set_item("mass", c.mass)?;
                cw.set_item("at", c.at.to_vec())?;
                cw.set_item("radius", c.radius)?;
                cw.set_item("new_mass", c.new_mass)?;
                cw.set_item("new_centroid", c.new_centroid.to_vec())?;
                cw.set_item("new_inertia", c.new_inertia)?;
                list.append(cw)?;
            }
            b.set_item("counterweights", list)?;
            b.set_item("balanced_peak_dynamic", r.balanced_peak_force)?;
            d.set_item("balance", b)?;
        }
    }

    match &r.flywheel {
        None => d.set_item("flywheel", py.None())?,
        Some(f) => {
            let fw = PyDict::new(py);
            fw.set_item("mean_torque", f.mean_torque)?;
            fw.set_item("delta_e", f.delta_e)?;
            fw.set_item("cs", f.cs)?;
            fw.set_item("inertia", f.inertia)?;
            fw.set_item("theta_max", f.theta_max)?;
            fw.set_item("theta_min", f.theta_min)?;
            fw.set_item("omega_min", f.omega_min)?;
            fw.set_item("omega_max", f.omega_max)?;
            fw.set_item("cs_run", f.cs_run)?;
            d.set_item("flywheel", fw)?;
        }
    }

    let du = PyDict::new(py);
    du.set_item(
        "gear_ratio",
        spec.motor.as_ref().map_or(1.0, |m| m.gear_ratio),
    )?;
    du.set_item("peak_torque", r.duty.peak_torque)?;
    du.set_item("peak_at", r.duty.peak_at)?;
    du.set_item("rms_torque", r.duty.rms_torque)?;
    du.set_item("peak_power", r.duty.peak_power)?;
    let (w, t): (Vec<f64>, Vec<f64>) = r.duty.points.iter().copied().unzip();
    du.set_item("speed", arr(&w))?;
    du.set_item("torque", arr(&t))?;
    if let Some(m) = &spec.motor {
        du.set_item("curve", m.curve.clone())?;
        du.set_item("rated_torque", m.rated_torque)?;
        du.set_item("rated_power", m.rated_power)?;
    }
    d.set_item("motor", du)?;

    let checks = PyList::empty(py);
    for c in &r.checks {
        let x = PyDict::new(py);
        x.set_item("name", c.name)?;
        x.set_item("value", c.value)?;
        x.set_item("limit", c.limit)?;
        x.set_item("margin", c.margin)?;
        x.set_item("unit", c.unit)?;
        x.set_item("ok", c.ok)?;
        checks.append(x)?;
    }
    d.set_item("checks", checks)?;
    d.set_item("ok", r.ok())?;
    Ok(d)
}
