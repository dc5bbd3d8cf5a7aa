//! Python bindings for camlink: `camlink._core`.
//!
//! Bindings convert, they do not think: this layer turns Python values into
//! core types and core results into NumPy arrays and Python exceptions. The
//! user-facing API lives in the `camlink` Python package.
//!
//! No Rust panic crosses into Python: every entry point runs under
//! [`guard`], which turns a panic into `RuntimeError("internal error: …")`.

#![warn(unreachable_pub)]

mod cam;
mod cam_design;
mod cam_export;
mod cam_timing;
mod csv_text;
mod dicts;
mod errors;
mod fourbar;
mod machine;
mod model_file;
mod py_force;
mod settings;
mod sink;
mod study;
mod synth;
mod units;

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;

use std::sync::Arc;

use camlink_core::design::{self, Severity};
use camlink_core::diagnose::diagnose;
use camlink_core::dynamics::integrator::{self, Adaptive};
use camlink_core::dynamics::{inverse, statics};
use camlink_core::force::callback::Callback;
use camlink_core::force::Force;
use camlink_core::kinematics;
use camlink_core::run::{
    self, AnalysisError as CoreAnalysisError, Kind, PointOutput, Settings, Summary,
};
use camlink_core::setting;
use camlink_core::Equations;
use camlink_model::{AnalysisType, Format, Loaded, OutlineShape};

use dicts::{mark_dict, summary_dict};
pub(crate) use errors::{
    analysis_error, guard, internal_error, model_error, AnalysisError, ModelError,
};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1};
use py_force::{call_force, FORCE_ERROR};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use pyo3::types::{PyDict, PyList};
use sink::{ChunkSink, Delivery, DEFAULT_CHUNK_ROWS};

/// A model file format by name: `"toml"` or `"json"`, any case.
fn model_format(name: &str) -> PyResult<Format> {
    match name.to_ascii_lowercase().as_str() {
        "toml" => Ok(Format::Toml),
        "json" => Ok(Format::Json),
        other => Err(ModelError::new_err(format!(
            "unknown model format '{other}' (expected 'toml' or 'json')"
        ))),
    }
}

/// What `run_kinematics` returns: channel names, data, summary and each
/// channel's quantity ([`Quantity::name`]).
type RunOutput<'py> = (
    Vec<String>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyDict>,
    Vec<&'static str>,
);

/// A loaded model: the core model and the file's `[analysis]` settings.
#[pyclass(frozen, module = "camlink._core")]
struct Model {
    loaded: Loaded,
}

#[pymethods]
impl Model {
    /// Loads a TOML or JSON model file (format from the extension); data
    /// files must lie in its folder or below unless `allow_outside`.
    #[staticmethod]
    #[pyo3(signature = (path, allow_outside = false))]
    fn load(py: Python<'_>, path: PathBuf, allow_outside: bool) -> PyResult<Model> {
        guard(|| {
            let options = camlink_model::LoadOptions {
                base_dir: None,
                allow_outside_data: allow_outside,
            };
            let loaded = py.detach(|| camlink_model::load_path_with(&path, &options));
            Ok(Model {
                loaded: loaded.map_err(model_error)?,
            })
        })
    }

    /// Loads a simEngine2D `.adm` model with the analysis of `acf` (default:
    /// the `.acf` beside it, if any).
    #[staticmethod]
    #[pyo3(signature = (path, acf = None))]
    fn load_adm(py: Python<'_>, path: PathBuf, acf: Option<PathBuf>) -> PyResult<Model> {
        guard(|| {
            let loaded = py.detach(|| camlink_adm::load_adm(&path, acf.as_deref()));
            Ok(Model {
                loaded: loaded.map_err(model_error)?,
            })
        })
    }

    /// Loads a model from text; `format` is `"toml"` or `"json"`; `source`
    /// names the text in error messages; data files resolve against
    /// `base_dir` (default: `source`'s folder) and must lie in it or below
    /// unless `allow_outside`.
    #[staticmethod]
    #[pyo3(signature = (text, format, source = "<string>", base_dir = None, allow_outside = false))]
    fn from_str(
        text: &str,
        format: &str,
        source: &str,
        base_dir: Option<PathBuf>,
        allow_outside: bool,
    ) -> PyResult<Model> {
        guard(|| {
            let format = model_format(format)?;
            let options = camlink_model::LoadOptions {
                base_dir,
                allow_outside_data: allow_outside,
            };
            let loaded = camlink_model::load_str_with(text, format, source, &options)
                .map_err(model_error)?;
            Ok(Model { loaded })
        })
    }

    #[getter]
    fn name(&self) -> &str {
        &self.loaded.model.name
    }

    /// The data files the model read (canonical paths).
    #[getter]
    fn data_files(&self) -> Vec<PathBuf> {
        self.loaded.data_files.clone()
    }

    /// What the loader read and ignored, one line each naming the file,
    /// line and field (a simEngine2D file's parts the course engine does
    /// not use either).
    #[getter]
    fn load_warnings(&self) -> Vec<String> {
        self.loaded.warnings.clone()
    }

    /// Moving bodies (the ground is implicit): a list of dicts.
    #[getter]
    fn bodies<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for (_, b) in self.loaded.model.moving_bodies() {
            let d = PyDict::new(py);
            d.set_item("name", &b.name)?;
            d.set_item("position", [b.q0[0], b.q0[1]])?;
            d.set_item("angle", b.q0[2])?;
            d.set_item("mass", b.mass)?;
            d.set_item("inertia", b.inertia)?;
            d.set_item("centroid", b.centroid)?;
            let points = PyDict::new(py);
            for p in &b.points {
                points.set_item(&p.name, p.s)?;
            }
            d.set_item("points", points)?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// Joints and drivers in model order: a list of dicts.
    #[getter]
    fn joints<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let model = &self.loaded.model;
        let list = PyList::empty(py);
        for j in &model.joints {
            let d = PyDict::new(py);
            let [bi, bj] = j.constraint.bodies();
            d.set_item("name", &j.name)?;
            d.set_item("kind", j.constraint.kind())?;
            d.set_item("bodies", [&model.body(bi).name, &model.body(bj).name])?;
            d.set_item("equations", j.constraint.rows())?;
            d.set_item("equation_names", j.constraint.equations())?;
            d.set_item("driver", j.driver)?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// The file's `[analysis]` table as a dict. `tol` and `max_iter` are
    /// None unless the file gives them (each analysis has its own
    /// defaults); `h` is None when it follows the output step.
    #[getter]
    fn analysis<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let a = &self.loaded.analysis;
        let d = PyDict::new(py);
        d.set_item("type", a.kind.name())?;
        d.set_item("t_end", a.t_end)?;
        d.set_item("step", a.step)?;
        d.set_item("times", a.times.clone())?;
        d.set_item("time", a.time)?;
        d.set_item("tol", a.tol_set.then_some(a.tol))?;
        d.set_item("max_iter", a.max_iter_set.then_some(a.max_iter))?;
        d.set_item("points", a.points.clone())?;
        d.set_item("jerk", a.jerk)?;
        let dy = &a.dynamics;
        d.set_item("h", dy.h)?;
        d.set_item("rho_inf", dy.rho_inf)?;
        d.set_item("projection_tol", dy.projection_tol)?;
        d.set_item("adaptive", dy.adaptive.is_some())?;
        let ad = dy.adaptive.clone().unwrap_or(Adaptive {
            atol: camlink_model::DynamicsSpec::DEFAULT_ATOL,
            rtol: camlink_model::DynamicsSpec::DEFAULT_RTOL,
            h_min: camlink_model::DynamicsSpec::DEFAULT_H_MIN,
        });
        d.set_item("atol", ad.atol)?;
        d.set_item("rtol", ad.rtol)?;
        d.set_item("h_min", ad.h_min)?;
        Ok(d)
    }

    /// Gravity vector g (m/s²), global frame.
    #[getter]
    fn gravity(&self) -> [f64; 2] {
        self.loaded.model.gravity
    }

    /// Applied forces: a list of dicts with name, kind and bodies, and
    /// what a drawing shows: a spring–damper–actuator's (`tsda`) attachment
    /// points `s_i`, `s_j` (body frames, m), `stiffness` (N/m) and
    /// `damping` (N·s/m); a rotational one's (`rsda`) `stiffness`
    /// (N·m/rad) and `damping` (N·m·s/rad); None where the kind has none.
    #[getter]
    fn forces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        use camlink_core::force::{Applied, ForceKind};
        let model = &self.loaded.model;
        let list = PyList::empty(py);
        for f in &model.forces {
            let d = PyDict::new(py);
            let [bi, bj] = f.kind.bodies();
            d.set_item("name", &f.name)?;
            d.set_item("kind", f.kind.kind())?;
            d.set_item("bodies", [&model.body(bi).name, &model.body(bj).name])?;
            let (points, stiffness, damping) = match &f.kind {
                ForceKind::Tsda(s) => (Some([s.s_i, s.s_j]), Some(s.stiffness), Some(s.damping)),
                ForceKind::Rsda(s) => (None, Some(s.stiffness), Some(s.damping)),
                _ => (None, None, None),
            };
            d.set_item("s_i", points.map(|p| p[0]))?;
            d.set_item("s_j", points.map(|p| p[1]))?;
            d.set_item("stiffness", stiffness)?;
            d.set_item("damping", damping)?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// Warnings about the model found while it was loaded (a default
    /// measured in a placement that the assembly moved): a list of dicts
    /// with kind, field, message and text (one line, with the field).
    #[getter]
    fn warnings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for w in &self.loaded.model.warnings {
            let d = PyDict::new(py);
            d.set_item("kind", w.kind)?;
            d.set_item("field", &w.field)?;
            d.set_item("message", &w.message)?;
            d.set_item("text", format!("{}: {}", w.field, w.message))?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// The design checks of the curve contacts (flat follower on a concave
    /// profile, undercut roller): a list of dicts with severity
    /// (`"warning"` or `"error"`), joint, message and text (one line).
    fn design_check<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        guard(|| {
            let findings = py.detach(|| design::check(&self.loaded.model));
            let list = PyList::empty(py);
            for f in &findings {
                let d = PyDict::new(py);
                let severity = match f.severity {
                    Severity::Warning => "warning",
                    Severity::Error => "error",
                };
                d.set_item("severity", severity)?;
                d.set_item("joint", &f.joint)?;
                d.set_item("message", &f.message)?;
                d.set_item("text", f.to_string())?;
                list.append(d)?;
            }
            Ok(list)
        })
    }

    /// A copy of this model with a force computed by `f(t, q, qd)` acting
    /// on `body`: q = (x, y, φ) and qd = (ẋ, ẏ, φ̇) of the body frame, and
    /// the result (F_x, F_y, n) in N, N, N·m, n the moment about the
    /// body-frame origin. The slow path: `f` runs at every Newton iteration
    /// of the dynamic analyses, with the GIL held. An exception raised by
    /// `f` stops the run and is re-raised.
    fn with_callback_force(&self, name: String, body: &str, f: Py<PyAny>) -> PyResult<Model> {
        guard(|| {
            let model = &self.loaded.model;
            let id = model
                .body_id(body)
                .filter(|id| !id.is_ground())
                .ok_or_else(|| {
                    ModelError::new_err(format!("force '{name}': no moving body named '{body}'"))
                })?;
            if model.forces.iter().any(|x| x.name == name) {
                return Err(ModelError::new_err(format!(
                    "duplicate force name '{name}'"
                )));
            }
            let callback = Callback {
                body: id,
                f: Arc::new(move |t, q, qd| call_force(&f, t, q, qd)),
            };
            let mut loaded = self.loaded.clone();
            loaded.model.add_force(Force::new(name, callback));
            Ok(Model { loaded })
        })
    }

    /// What a drawing needs of every joint, in model order: a list of dicts
    /// with `name`, `kind`, `bodies` [i, j], `driver` and `marks`, the
    /// joint's sketch (`camlink_core::constraint::sketch::Mark`) as dicts
    /// with a `shape` and its fields: `pin` (`s_i`, `s_j`), `rod` (`s_i`,
    /// `s_j`), `guide` (`s_i`, `v_i`, `s_j`), `slider` (`body`, `s`), `face`
    /// (`body`, `s`, `u`), `circle` (`body`, `s`, `radius`, `internal`),
    /// `curve` (`body`, `role`, `closed`, `points` n × 2 within `tol` (m) of
    /// the exact curve). Points and directions are in the frame of the body
    /// that carries them (m).
    #[pyo3(signature = (tol = 1e-4))]
    fn geometry<'py>(&self, py: Python<'py>, tol: f64) -> PyResult<Bound<'py, PyList>> {
        guard(|| {
            let model = &self.loaded.model;
            let list = PyList::empty(py);
            for j in &model.joints {
                let d = PyDict::new(py);
                let bodies = j.constraint.bodies().map(|b| &model.body(b).name);
                d.set_item("name", &j.name)?;
                d.set_item("kind", j.constraint.kind())?;
                d.set_item("bodies", bodies)?;
                d.set_item("driver", j.driver)?;
                let marks = PyList::empty(py);
                for mark in j.constraint.sketch() {
                    marks.append(mark_dict(py, &mark, bodies, tol)?)?;
                }
                d.set_item("marks", marks)?;
                list.append(d)?;
            }
            Ok(list)
        })
    }

    /// The bodies' drawn outlines from the model file: body name → corners
    /// (n × 2, body frame, m) of a closed polyline; a curve outline is
    /// sampled within `tol` (m).
    #[pyo3(signature = (tol = 1e-4))]
    fn outlines<'py>(&self, py: Python<'py>, tol: f64) -> PyResult<Bound<'py, PyDict>> {
        guard(|| {
            let d = PyDict::new(py);
            for o in &self.loaded.outlines {
                let flat: Vec<f64> = match &o.shape {
                    OutlineShape::Polyline(p) => p.iter().flat_map(|v| [v[0], v[1]]).collect(),
                    OutlineShape::Curve(c) => c
                        .sample(tol)
                        .iter()
                        .flat_map(|(_, v)| [v[0], v[1]])
                        .collect(),
                };
                d.set_item(&o.body, to_array(py, flat, 2)?)?;
            }
            Ok(d)
        })
    }

    /// The ground's named points: name → [x, y] (m).
    #[getter]
    fn ground_points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let points = PyDict::new(py);
        for p in &self.loaded.model.bodies[0].points {
            points.set_item(&p.name, p.s)?;
        }
        Ok(points)
    }

    /// Counts of bodies, coordinates and equations, every constraint with
    /// its kind and equation count, and the diagnosis of Φ_q at t = 0:
    /// rank, degrees of freedom, redundant equations (and the drivers among
    /// them, which make the model over-driven) and free motions. Unilateral
    /// contacts open at the placement (or compliant) remove no freedom at
    /// the start: `released` lists them (`joint`, `gap` in m or None for a
    /// compliant one, `text`), and rank and degrees of freedom leave them out.
    fn check<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        guard(|| {
            let model = &self.loaded.model;
            let (report, diagnosis) = py.detach(|| {
                (
                    kinematics::check(model),
                    diagnose(model, 0.0, self.loaded.analysis.tol),
                )
            });
            let d = PyDict::new(py);
            d.set_item("bodies", report.bodies)?;
            d.set_item("coordinates", report.coordinates)?;
            d.set_item("equations", report.equations)?;
            let joints = PyList::empty(py);
            for (name, kind, equations, driver) in &report.joints {
                let j = PyDict::new(py);
                j.set_item("name", name)?;
                j.set_item("kind", kind)?;
                j.set_item("equations", equations)?;
                j.set_item("driver", driver)?;
                joints.append(j)?;
            }
            d.set_item("joints", joints)?;
            d.set_item("rank", diagnosis.rank)?;
            d.set_item("dof", diagnosis.dof)?;
            let redundant = PyList::empty(py);
            for r in &diagnosis.redundant {
                let e = PyDict::new(py);
                e.set_item("equation", &r.equation)?;
                e.set_item("depends_on", r.depends_on.clone())?;
                redundant.append(e)?;
            }
            d.set_item("redundant", redundant)?;
            d.set_item("redundant_drivers", diagnosis.redundant_drivers.clone())?;
            d.set_item("free_motions", diagnosis.free_motions.clone())?;
            d.set_item("residual", diagnosis.residual)?;
            d.set_item("condition", diagnosis.condition)?;
            d.set_item("open_joints", diagnosis.open_joints.clone())?;
            let released = PyList::empty(py);
            for r in &diagnosis.released {
                let e = PyDict::new(py);
                e.set_item("joint", &r.joint)?;
                e.set_item("gap", r.gap)?;
                e.set_item("text", &r.text)?;
                released.append(e)?;
            }
            d.set_item("released", released)?;
            Ok(d)
        })
    }

    /// Kinematic analysis at `times` (s). Returns `(names, data, summary,
    /// quantities)`: channel names starting with `"t"`, a `steps ×
    /// len(names)` array, a dict of solver counts, warnings, assembly moves
    /// and `lift_off` (empty here; see `run_inverse_dynamics`), and what
    /// each channel measures (`"time"`, `"angle"`, `"force"`…, the names of
    /// `quantity_unit`). With `jerk`, Φ_q q⃛ = η is
    /// solved too and the jerk channels `<body>.jx .jy .jphi` and
    /// `<point>.jx .jy` follow the others.
    ///
    /// `on_chunk(names, rows, quantities)` is called every `chunk_rows` rows (fewer
    /// when that many would exceed [`CHUNK_BYTES`]) and once at the end,
    /// also when the analysis fails, so a caller can write results as the
    /// run goes; `rows` is a column-major (Fortran-order) array, so that
    /// each channel `rows[:, k]` is contiguous. With `keep_rows = False`
    /// the binding keeps only the current chunk and the returned array (and
    /// an `AnalysisError`'s `data`) has no rows: the caller has them from
    /// `on_chunk`. The GIL is released while the core computes. An
    /// exception raised by `on_chunk` (or a Ctrl-C, seen at chunk
    /// boundaries) stops the run and is re-raised.
    ///
    /// `start`, if given, is q to assemble the first time from instead of
    /// the model's placement (m, rad; in the order of `coordinates`).
    #[pyo3(signature = (times, *, tol = None, max_iter = None, points = Vec::new(), on_chunk = None, chunk_rows = DEFAULT_CHUNK_ROWS, keep_rows = true, jerk = false, start = None))]
    #[allow(clippy::too_many_arguments)]
    fn run_kinematics<'py>(
        &self,
        py: Python<'py>,
        times: PyReadonlyArray1<'py, f64>,
        tol: Option<f64>,
        max_iter: Option<usize>,
        points: Vec<String>,
        on_chunk: Option<Py<PyAny>>,
        chunk_rows: usize,
        keep_rows: bool,
        jerk: bool,
        start: Option<PyReadonlyArray1<'py, f64>>,
    ) -> PyResult<RunOutput<'py>> {
        let (tol, max_iter) = self.solver(AnalysisType::Kinematics, tol, max_iter)?;
        let settings = Settings {
            tol,
            max_iter,
            jerk,
        };
        let times = times.as_array().to_vec();
        let start = start.map(|q| q.as_array().to_vec());
        self.run_with(
            py,
            &points,
            Delivery::new(on_chunk, chunk_rows, keep_rows),
            |model, points, sink| {
                kinematics::run_from(model, &times, &settings, points, sink, start.as_deref())
            },
        )
    }

    /// The names of the model's coordinates in the order of q: `<body>.x`,
    /// `.y`, `.phi` for every moving body, then `<joint>.<own>` for each
    /// joint's own coordinates (the run's channels of the same names).
    #[getter]
    fn coordinates(&self) -> Vec<String> {
        kinematics::coordinate_names(&self.loaded.model)
    }

    /// Inverse dynamics at `times` (s) of a driven (zero-DOF) model: the
    /// kinematic channels, then joint reactions, driver efforts, energy and
    /// drift. Arguments and return value as `run_kinematics`.
    ///
    /// The summary's `lift_off` lists the intervals where a cam contact's
    /// normal force is negative (the follower would leave the cam), by
    /// start time, each also a warning. Each is a dict: `joint` and `cam`
    /// (names), `start_time` (s) and `start_cam_angle` (rad) where the
    /// force falls through zero, `end_time` (s) and `end_cam_angle` (rad)
    /// where it rises again (None when the run ends in lift-off),
    /// `least_force` (N, negative) and where it is, `least_time` (s) and
    /// `least_cam_angle` (rad). The cam angle is φ of the cam body.
    #[pyo3(signature = (times, *, tol = None, max_iter = None, points = Vec::new(), on_chunk = None, chunk_rows = DEFAULT_CHUNK_ROWS, keep_rows = true))]
    #[allow(clippy::too_many_arguments)]
    fn run_inverse_dynamics<'py>(
        &self,
        py: Python<'py>,
        times: PyReadonlyArray1<'py, f64>,
        tol: Option<f64>,
        max_iter: Option<usize>,
        points: Vec<String>,
        on_chunk: Option<Py<PyAny>>,
        chunk_rows: usize,
        keep_rows: bool,
    ) -> PyResult<RunOutput<'py>> {
        let (tol, max_iter) = self.solver(AnalysisType::InverseDynamics, tol, max_iter)?;
        let settings = Settings {
            tol,
            max_iter,
            ..Settings::default()
        };
        self.run_grid(
            py,
            times,
            settings,
            points,
            Delivery::new(on_chunk, chunk_rows, keep_rows),
            inverse::run,
        )
    }

    /// The equilibrium at `time` (s), as one row with the channels of
    /// `run_inverse_dynamics` (velocities and accelerations zero).
    #[pyo3(signature = (time = 0.0, *, tol = None, max_iter = None, points = Vec::new(), on_chunk = None, chunk_rows = DEFAULT_CHUNK_ROWS, keep_rows = true))]
    #[allow(clippy::too_many_arguments)]
    fn run_equilibrium<'py>(
        &self,
        py: Python<'py>,
        time: f64,
        tol: Option<f64>,
        max_iter: Option<usize>,
        points: Vec<String>,
        on_chunk: Option<Py<PyAny>>,
        chunk_rows: usize,
        keep_rows: bool,
    ) -> PyResult<RunOutput<'py>> {
        let (tol, max_iter) = self.solver(AnalysisType::Equilibrium, tol, max_iter)?;
        let settings = statics::Settings { tol, max_iter };
        let delivery = Delivery::new(on_chunk, chunk_rows, keep_rows);
        self.run_with(py, &points, delivery, |model, points, sink| {
            statics::run(model, time, &settings, points, sink)
        })
    }

    /// Forward dynamics with output at `times` (s; the first is the start
    /// time), generalized-α. Each setting left `None` takes the file's
    /// `[analysis]` value, else the default
    /// ([`camlink_model::AnalysisSpec::integrator_settings_with`]): `step`
    /// is the output step that sets the default integration step `h` (s,
    /// the largest step when `adaptive`), `rho_inf` the spectral radius,
    /// `atol`, `rtol`, `h_min` the error control of the adaptive mode.
    /// Channels and the summary's `lift_off` as `run_inverse_dynamics`.
    #[pyo3(signature = (times, *, step = None, h = None, rho_inf = None, adaptive = None, atol = None, rtol = None, h_min = None, projection_tol = None, tol = None, max_iter = None, points = Vec::new(), on_chunk = None, chunk_rows = DEFAULT_CHUNK_ROWS, keep_rows = true))]
    #[allow(clippy::too_many_arguments)]
    fn run_dynamics<'py>(
        &self,
        py: Python<'py>,
        times: PyReadonlyArray1<'py, f64>,
        step: Option<f64>,
        h: Option<f64>,
        rho_inf: Option<f64>,
        adaptive: Option<bool>,
        atol: Option<f64>,
        rtol: Option<f64>,
        h_min: Option<f64>,
        projection_tol: Option<f64>,
        tol: Option<f64>,
        max_iter: Option<usize>,
        points: Vec<String>,
        on_chunk: Option<Py<PyAny>>,
        chunk_rows: usize,
        keep_rows: bool,
    ) -> PyResult<RunOutput<'py>> {
        let times = times.as_array().to_vec();
        let args = camlink_model::DynamicsArgs {
            step,
            h,
            rho_inf,
            adaptive,
            atol,
            rtol,
            h_min,
            projection_tol,
            tol,
            max_iter,
        };
        let settings = self
            .loaded
            .analysis
            .integrator_settings_with(&args)
            .map_err(|e| ModelError::new_err(e.message))?;
        let delivery = Delivery::new(on_chunk, chunk_rows, keep_rows);
        self.run_with(py, &points, delivery, |model, points, sink| {
            integrator::run(model, &times, &settings, points, sink)
        })
    }

    /// This model with the `[parameters]` named in `values` (name → number
    /// or expression string) changed and everything depending on them
    /// resolved again; an unknown name raises `ModelError` naming it.
    fn with_parameters(
        &self,
        values: std::collections::HashMap<String, study::ParameterValue>,
    ) -> PyResult<Model> {
        guard(|| study::with_parameters(&self.loaded, values))
    }

    /// The names of the file's `[parameters]` (empty for a simEngine2D model).
    #[getter]
    fn parameter_names(&self) -> Vec<String> {
        self.loaded
            .recipe
            .as_ref()
            .map_or_else(Vec::new, |r| r.parameter_names())
    }

    fn __repr__(&self) -> String {
        let m = &self.loaded.model;
        format!(
            "<camlink Model '{}': {} bodies, {} joints>",
            m.name,
            m.bodies.len() - 1,
            m.joints.len()
        )
    }
}

/// A core analysis over output times with the kinematic settings
/// (`inverse::run`).
type GridAnalysis = fn(
    &camlink_core::Model,
    &[f64],
    &Settings,
    &[PointOutput],
    &mut dyn camlink_core::run::Sink,
) -> Result<Summary, CoreAnalysisError>;

impl Model {
    /// The Newton tolerance and most iterations of a `kind` run: those
    /// given, else the file's, else the defaults of `kind`; each checked by
    /// its rule.
    fn solver(
        &self,
        kind: AnalysisType,
        tol: Option<f64>,
        max_iter: Option<usize>,
    ) -> PyResult<(f64, usize)> {
        let (tol, max_iter) = self.loaded.analysis.solver(kind, tol, max_iter);
        setting::check("tol", tol).map_err(ModelError::new_err)?;
        setting::check("max_iter", max_iter as f64).map_err(ModelError::new_err)?;
        Ok((tol, max_iter))
    }

    /// Runs `analysis` at `times` (s) with `settings`, as [`Model::run_with`].
    #[allow(clippy::too_many_arguments)]
    fn run_grid<'py>(
        &self,
        py: Python<'py>,
        times: PyReadonlyArray1<'py, f64>,
        settings: Settings,
        points: Vec<String>,
        delivery: Delivery,
        analysis: GridAnalysis,
    ) -> PyResult<RunOutput<'py>> {
        let times = times.as_array().to_vec();
        self.run_with(py, &points, delivery, |model, points, sink| {
            analysis(model, &times, &settings, points, sink)
        })
    }

    /// Runs `analysis` with the GIL released, rows going to a [`ChunkSink`];
    /// turns its outcome, a panic, a failing `on_chunk` or a failing
    /// callback force into the Python result or exception.
    fn run_with<'py, F>(
        &self,
        py: Python<'py>,
        points: &[String],
        delivery: Delivery,
        analysis: F,
    ) -> PyResult<RunOutput<'py>>
    where
        F: FnOnce(
                &camlink_core::Model,
                &[PointOutput],
                &mut ChunkSink,
            ) -> Result<Summary, CoreAnalysisError>
            + Send,
    {
        guard(|| {
            let points = resolve_points(&self.loaded.model, points)?;
            let mut sink = ChunkSink::new(delivery);
            let model = &self.loaded.model;
            FORCE_ERROR.with(|slot| slot.borrow_mut().take());
            let outcome = py
                .detach(|| catch_unwind(AssertUnwindSafe(|| analysis(model, &points, &mut sink))));
            let force_error = FORCE_ERROR.with(|slot| slot.borrow_mut().take());
            sink.flush();
            let ChunkSink {
                names,
                quantities,
                all,
                callback_error,
                ..
            } = sink;
            let data = to_array(py, all, names.len())?;
            if let Some(e) = callback_error {
                return Err(e);
            }
            match outcome {
                Err(payload) => Err(internal_error(payload)),
                Ok(Err(e)) if e.kind == Kind::Stopped => Err(PyRuntimeError::new_err(format!(
                    "internal error: run stopped without a Python error ({e})"
                ))),
                Ok(Err(e)) => {
                    let err = analysis_error(py, &e, names, quantities, Some(data));
                    if e.kind == Kind::ForceFailed {
                        err.set_cause(py, force_error);
                    }
                    Err(err)
                }
                Ok(Ok(summary)) => Ok((names, data, summary_dict(py, &summary)?, quantities)),
            }
        })
    }
}

/// `"body.point"` names to core point outputs; a name given twice is an
/// error (it would give two sets of identical channels).
fn resolve_points(model: &camlink_core::Model, names: &[String]) -> PyResult<Vec<PointOutput>> {
    names
        .iter()
        .enumerate()
        .map(|(k, full)| {
            if names[..k].contains(full) {
                return Err(ModelError::new_err(format!(
                    "point '{full}' is listed twice"
                )));
            }
            PointOutput::named(model, full).map_err(ModelError::new_err)
        })
        .collect()
}

/// A `rows × width` NumPy array from row-major values.
fn to_array(py: Python<'_>, values: Vec<f64>, width: usize) -> PyResult<Bound<'_, PyArray2<f64>>> {
    let rows = values.len().checked_div(width).unwrap_or(0);
    let a = Array2::from_shape_vec((rows, width), values)
        .map_err(|e| PyRuntimeError::new_err(format!("internal error: {e}")))?;
    Ok(a.into_pyarray(py))
}

/// Times 0, h, 2h, … up to `t_end` (inclusive, within rounding).
#[pyfunction]
fn time_grid(py: Python<'_>, t_end: f64, step: f64) -> PyResult<Bound<'_, PyArray1<f64>>> {
    guard(|| {
        let times = run::time_grid(t_end, step).map_err(ModelError::new_err)?;
        Ok(times.into_pyarray(py))
    })
}

/// The number of output rows of [`time_grid`] for `t_end` and `step` (s),
/// without building them (however many).
#[pyfunction]
fn time_grid_rows(t_end: f64, step: f64) -> PyResult<f64> {
    run::check_grid(t_end, step).map_err(ModelError::new_err)?;
    Ok(run::grid_steps(t_end, step) + 1.0)
}

/// Checks the run setting `key` = `value` by the rule a model file's
/// `[analysis]` key follows; raises `ModelError` naming the setting.
#[pyfunction]
fn check_setting(key: &str, value: f64) -> PyResult<()> {
    camlink_core::setting::check(key, value).map_err(ModelError::new_err)
}

/// True when the run setting `key` is a flag (true or false).
#[pyfunction]
fn setting_is_flag(key: &str) -> bool {
    setting::rule(key) == Some(setting::Rule::Flag)
}

/// A simEngine2D `.adm` model (with the analysis of `acf`, default the
/// `.acf` beside it) written as a camlink model file; `format` is `"toml"`
/// or `"json"`.
#[pyfunction]
#[pyo3(signature = (path, format, acf = None))]
fn convert_adm(path: PathBuf, format: &str, acf: Option<PathBuf>) -> PyResult<String> {
    guard(|| {
        let format = model_format(format)?;
        camlink_adm::convert_adm(&path, acf.as_deref(), format).map_err(model_error)
    })
}

/// The JSON Schema of model files, as JSON text.
#[pyfunction]
fn json_schema() -> PyResult<String> {
    guard(|| {
        serde_json::to_string_pretty(&camlink_model::json_schema())
            .map_err(|e| PyRuntimeError::new_err(format!("internal error: {e}")))
    })
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<Model>()?;
    m.add_class::<cam::CamCore>()?;
    m.add_class::<machine::MachineCycle>()?;
    m.add_function(wrap_pyfunction!(cam::cam_materials, m)?)?;
    m.add_function(wrap_pyfunction!(cam::cam_followers, m)?)?;
    m.add_function(wrap_pyfunction!(cam::cam_laws, m)?)?;
    m.add_function(wrap_pyfunction!(cam::contact_modulus, m)?)?;
    m.add_function(wrap_pyfunction!(cam::line_contact, m)?)?;
    m.add_function(wrap_pyfunction!(cam::helical_spring, m)?)?;
    m.add_function(wrap_pyfunction!(cam_design::cam_design_load, m)?)?;
    m.add_function(wrap_pyfunction!(cam_design::cam_design_read, m)?)?;
    m.add_function(wrap_pyfunction!(cam_design::cam_design_limits, m)?)?;
    m.add_function(wrap_pyfunction!(cam_design::cam_is_design, m)?)?;
    m.add_function(wrap_pyfunction!(cam_design::did_you_mean, m)?)?;
    m.add_function(wrap_pyfunction!(cam_design::plain_file_name_problem, m)?)?;
    m.add_function(wrap_pyfunction!(cam_design::cam_design_report, m)?)?;
    m.add_function(wrap_pyfunction!(cam_design::cam_report_in_units, m)?)?;
    m.add_function(wrap_pyfunction!(cam_design::cam_tool_undercut, m)?)?;
    m.add_function(wrap_pyfunction!(json_schema, m)?)?;
    m.add_function(wrap_pyfunction!(convert_adm, m)?)?;
    m.add_function(wrap_pyfunction!(time_grid, m)?)?;
    m.add_function(wrap_pyfunction!(time_grid_rows, m)?)?;
    m.add_function(wrap_pyfunction!(csv_text::csv_rows, m)?)?;
    m.add_function(wrap_pyfunction!(check_setting, m)?)?;
    m.add_function(wrap_pyfunction!(setting_is_flag, m)?)?;
    m.add_function(wrap_pyfunction!(machine::machine_report, m)?)?;
    m.add_function(wrap_pyfunction!(study::run_batch, m)?)?;
    m.add_function(wrap_pyfunction!(study::toml_position, m)?)?;
    m.add_function(wrap_pyfunction!(study::output_kinds, m)?)?;
    m.add_function(wrap_pyfunction!(study::check_output, m)?)?;
    synth::register(m)?;
    fourbar::register(m)?;
    units::register(m)?;
    cam_timing::register(m)?;
    cam_export::register(m)?;
    model_file::register(m)?;
    settings::register(m)?;
    m.add("ModelError", py.get_type::<ModelError>())?;
    m.add("AnalysisError", py.get_type::<AnalysisError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    let kinds = |warning: bool| -> Vec<&'static str> {
        camlink_core::run::Kind::ALL
            .iter()
            .filter(|k| k.is_warning() == warning)
            .map(|k| k.name())
            .collect()
    };
    m.add("ERROR_KINDS", PyTuple::new(py, kinds(false))?)?;
    m.add("WARNING_KINDS", PyTuple::new(py, kinds(true))?)?;
    let analyses = AnalysisType::ALL.map(|k| k.name());
    m.add("ANALYSES", PyTuple::new(py, analyses)?)?;
    let statuses = camlink_study::Status::RESULTS.map(|s| s.name());
    m.add("STUDY_STATUSES", PyTuple::new(py, statuses)?)?;
    m.add(
        "CAM_ROUND_TRIP_STEPS",
        camlink_cam::report::ROUND_TRIP_STEPS,
    )?;
    Ok(())
}
