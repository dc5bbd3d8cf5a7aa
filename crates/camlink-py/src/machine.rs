//! Binding of the machine analysis ([`camlink_core::machine`]): a model
//! file's `[machine]` table run and its report as a dict of numbers and
//! arrays, and the cycle a partial balance evaluates. Converts only;
//! `camlink.machine` and `camlink.study.balance` present them.

use std::path::{Path, PathBuf};

use camlink_core::machine::balance::{self, Balance, Counterweight};
use camlink_core::machine::{analyse, Cycle, Figures, Report};
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::{analysis_error, guard, model_error};

/// The model and `[machine]` table of the file at `path`.
fn load(
    py: Python<'_>,
    path: &Path,
) -> PyResult<(camlink_model::Loaded, camlink_core::machine::Spec)> {
    let loaded = py
        .detach(|| camlink_model::load_path(path))
        .map_err(model_error)?;
    let Some(spec) = loaded.machine.clone() else {
        return Err(model_error(format!(
            "{}: no [machine] table (see docs/machine.md)",
            path.display()
        )));
    };
    Ok((loaded, spec))
}

/// The machine report of the model file at `path` (its `[machine]` table):
/// SI units, angles in rad.
#[pyfunction]
pub(crate) fn machine_report(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyDict>> {
    guard(|| {
        let (loaded, spec) = load(py, &path)?;
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
            b.set_item("counterweights", counterweights(py, &bal.counterweights)?)?;
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
            fw.set_item("law", f.law)?;
            fw.set_item("settle_cycles", f.settle_cycles)?;
            fw.set_item("omega_mean", f.omega_mean)?;
            fw.set_item("motor_torque", f.motor_torque)?;
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

/// Counterweights as a list of dicts (SI units, body frame).
fn counterweights<'py>(py: Python<'py>, cws: &[Counterweight]) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for c in cws {
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
    Ok(list)
}

fn figures(f: &Figures) -> (f64, f64, f64) {
    (f.force, f.moment, f.torque_swing)
}

/// The cycle of a machine and its full force balance, for a partial
/// balance: each counterweight of the full balance scaled by a factor.
#[pyclass(frozen, module = "camlink._core")]
pub struct MachineCycle {
    cycle: Cycle,
    full: Balance,
    unbalanced: Figures,
    balanced: Figures,
}

impl MachineCycle {
    /// The figures of the machine with factors `k`.
    fn run(&self, k: &[f64]) -> Result<Figures, String> {
        let b = balance::scaled(&self.cycle.driven, &self.full, k)?;
        self.cycle
            .figures(&balance::apply(&self.cycle.driven, &b))
            .map_err(|e| e.to_string())
    }
}

#[pymethods]
impl MachineCycle {
    /// The machine of the model file at `path` (its `[machine]` table);
    /// a `ModelError` when it has no full force balance.
    #[new]
    fn new(py: Python<'_>, path: PathBuf) -> PyResult<MachineCycle> {
        guard(|| {
            let (loaded, spec) = load(py, &path)?;
            let model = &loaded.model;
            py.detach(|| {
                let cycle = Cycle::new(model, &spec).map_err(|e| e.to_string())?;
                let full = balance::full_force_balance(model, cycle.crank)?;
                if full.counterweights.is_empty() {
                    return Err(
                        "the machine is force balanced already: no counterweight to trade".into(),
                    );
                }
                let unbalanced = cycle.figures(&cycle.driven).map_err(|e| e.to_string())?;
                let balanced = cycle
                    .figures(&balance::apply(&cycle.driven, &full))
                    .map_err(|e| e.to_string())?;
                Ok(MachineCycle {
                    cycle,
                    full,
                    unbalanced,
                    balanced,
                })
            })
            .map_err(|e: String| model_error(format!("{}: partial balance: {e}", path.display())))
        })
    }

    /// The counterweighted bodies, in the order of the factors.
    #[getter]
    fn bodies(&self) -> Vec<String> {
        self.full
            .counterweights
            .iter()
            .map(|c| c.body.clone())
            .collect()
    }

    /// `"four_bar"` or `"slider_crank"`.
    #[getter]
    fn linkage(&self) -> &'static str {
        self.full.linkage
    }

    /// (peak |F_s − W| N, peak |M_P| N·m, input torque swing N·m) of the
    /// machine as it is.
    #[getter]
    fn unbalanced(&self) -> (f64, f64, f64) {
        figures(&self.unbalanced)
    }

    /// The same of the full force balance (every factor 1).
    #[getter]
    fn balanced(&self) -> (f64, f64, f64) {
        figures(&self.balanced)
    }

    /// For each row of factors: (force, moment, torque swing, objective J
    /// with `weights` (w_F, w_M, w_T), relative to the unbalanced
    /// machine); NaN where the run fails. Rows run on all cores, the GIL
    /// released.
    fn evaluate(
        &self,
        py: Python<'_>,
        points: Vec<Vec<f64>>,
        weights: [f64; 3],
    ) -> PyResult<Vec<(f64, f64, f64, f64)>> {
        guard(|| {
            let one = |k: &Vec<f64>| match self.run(k) {
                Ok(f) => {
                    let (a, b, c) = figures(&f);
                    (a, b, c, f.objective(&self.unbalanced, weights))
                }
                Err(_) => (f64::NAN, f64::NAN, f64::NAN, f64::NAN),
            };
            Ok(py.detach(|| {
                let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
                let chunk = points.len().div_ceil(threads).max(1);
                std::thread::scope(|s| {
                    let parts: Vec<_> = points
                        .chunks(chunk)
                        .map(|c| {
                            (
                                c.len(),
                                s.spawn(move || c.iter().map(one).collect::<Vec<_>>()),
                            )
                        })
                        .collect();
                    let failed = (f64::NAN, f64::NAN, f64::NAN, f64::NAN);
                    parts
                        .into_iter()
                        .flat_map(|(n, h)| h.join().unwrap_or_else(|_| vec![failed; n]))
                        .collect()
                })
            }))
        })
    }

    /// The counterweights with factors `k` (a dict per counterweighted
    /// body, as in the machine report); a `ModelError` for a bad factor.
    fn counterweights<'py>(&self, py: Python<'py>, k: Vec<f64>) -> PyResult<Bound<'py, PyList>> {
        let b = balance::scaled(&self.cycle.driven, &self.full, &k).map_err(model_error)?;
        counterweights(py, &b.counterweights)
    }
}
