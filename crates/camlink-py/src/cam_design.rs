//! Binding of cam design files (camlink-cam): a checked file as plain
//! Python data that `camlink.cam.design` turns into its dataclasses.
//! Converts only.

use camlink_cam::{Design, Loaded};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::ModelError;

/// Reads and checks the design file `text` (TOML, or with `json` the
/// file's data as JSON); `source` names it in messages. Returns the design
/// as a dict (SI units, radians; keys as `camlink.cam.design.Design`'s
/// fields) and the loader's warnings; raises `ModelError` naming the
/// file, line and field.
#[pyfunction]
#[pyo3(signature = (text, source, json = false))]
pub fn cam_design_load<'py>(
    py: Python<'py>,
    text: &str,
    source: &str,
    json: bool,
) -> PyResult<(Bound<'py, PyDict>, Vec<String>)> {
    let loaded = py
        .detach(|| {
            if json {
                camlink_cam::load_json(text, source)
            } else {
                camlink_cam::load_toml(text, source)
            }
        })
        .map_err(|e| ModelError::new_err(e.to_string()))?;
    let Loaded { design, warnings } = loaded;
    Ok((design_dict(py, &design)?, warnings))
}

/// Reads and checks the design file at `path` (TOML) as
/// [`cam_design_load`] does.
#[pyfunction]
pub fn cam_design_read<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
) -> PyResult<(Bound<'py, PyDict>, Vec<String>)> {
    let Loaded { design, warnings } = py
        .detach(|| camlink_cam::load_path(&path))
        .map_err(|e| ModelError::new_err(e.to_string()))?;
    Ok((design_dict(py, &design)?, warnings))
}

/// The bounds and defaults of design files (`camlink_cam::limits`), by
/// their lower-case names.
#[pyfunction]
pub fn cam_design_limits<'py>(py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
    use camlink_cam::limits::*;
    let d = PyDict::new(py);
    d.set_item("rpm", RPM)?;
    d.set_item("max_rpm", MAX_RPM)?;
    d.set_item("max_segments", MAX_SEGMENTS)?;
    d.set_item("min_span_deg", MIN_SPAN_DEG)?;
    d.set_item("max_length", MAX_LENGTH)?;
    d.set_item("max_csv_rows", MAX_CSV_ROWS)?;
    d.set_item("min_relative_tolerance", MIN_RELATIVE_TOLERANCE)?;
    d.set_item("surge_ratio", SURGE_RATIO)?;
    d.set_item("life_exponents", LIFE_EXPONENTS.to_vec())?;
    d.set_item("max_steps", MAX_STEPS)?;
    d.set_item("max_turns", MAX_TURNS)?;
    Ok(d)
}

/// Whether the data `json` (a parsed TOML file as JSON) is a cam design
/// file rather than a model file.
#[pyfunction]
pub fn cam_is_design(json: &str) -> bool {
    camlink_cam::load::json_table(json).is_ok_and(|t| camlink_cam::is_design(&t))
}

/// Why `name` is not a plain file name (a path separator, a folder, a
/// control character, a drive), or None.
#[pyfunction]
pub fn plain_file_name_problem(name: &str) -> Option<&'static str> {
    camlink_cam::load::not_plain(name)
}

/// ` (did you mean 'x'?)` for the candidate nearest `name`, or "".
#[pyfunction]
pub fn did_you_mean(name: &str, candidates: Vec<String>) -> String {
    camlink_core::names::did_you_mean(name, candidates.iter().map(String::as_str))
}

fn design_dict<'py>(py: Python<'py>, d: &Design) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("name", &d.name)?;
    out.set_item("follower", d.follower)?;
    out.set_item("dims", d.dims.clone())?;
    out.set_item("base_radius", d.base_radius)?;
    out.set_item("ccw", d.ccw)?;
    let segments: Vec<_> = d
        .segments
        .iter()
        .map(|s| (s.law.name(), s.span, s.lift, s.start, s.end))
        .collect();
    out.set_item("segments", segments)?;
    let l = &d.limits;
    let limits = PyDict::new(py);
    limits.set_item("max_pressure_angle", l.max_pressure_angle)?;
    limits.set_item("min_radius", l.min_radius)?;
    limits.set_item("max_face_width", l.max_face_width)?;
    limits.set_item("base_radius_range", l.base_radius_range)?;
    limits.set_item("max_contact_stress", l.max_contact_stress)?;
    limits.set_item("min_bearing_life_hours", l.min_bearing_life_hours)?;
    limits.set_item("min_coil_clearance", l.min_coil_clearance)?;
    limits.set_item("min_surge_ratio", l.min_surge_ratio)?;
    limits.set_item("max_residual_vibration", l.max_residual_vibration)?;
    out.set_item("limits", limits)?;
    let dynamics = match &d.dynamics {
        None => None,
        Some(y) => {
            let t = PyDict::new(py);
            t.set_item("mass", y.mass)?;
            t.set_item("spring_rate", y.spring_rate)?;
            t.set_item("preload", y.preload)?;
            t.set_item("damping", y.damping)?;
            t.set_item("speed", y.speed)?;
            t.set_item("redline", y.redline)?;
            Some(t)
        }
    };
    out.set_item("dynamics", dynamics)?;
    let e = &d.export;
    let export = PyDict::new(py);
    export.set_item("csv", &e.csv)?;
    export.set_item("csv_step", e.csv_step)?;
    export.set_item("csv_chord", e.csv_chord)?;
    export.set_item("dxf", &e.dxf)?;
    export.set_item("dxf_mode", e.dxf_mode.name())?;
    export.set_item("tolerance", e.tolerance)?;
    export.set_item("svg", &e.svg)?;
    export.set_item("tool_radius", e.tool_radius)?;
    export.set_item("svaj", &e.svaj)?;
    export.set_item("profile", &e.profile)?;
    export.set_item("given", e.given.clone())?;
    export.set_item("units", &e.units)?;
    export.set_item("svaj_time", &e.svaj_time)?;
    export.set_item("vibration", &e.vibration)?;
    export.set_item("bore_radius", e.bore_radius)?;
    export.set_item("keyway_width", e.keyway_width)?;
    export.set_item("keyway_depth", e.keyway_depth)?;
    export.set_item("keyway_angle", e.keyway_angle)?;
    export.set_item("timing_mark", e.timing_mark)?;
    out.set_item("export", export)?;
    let contact = match &d.contact {
        None => None,
        Some(c) => {
            let t = PyDict::new(py);
            t.set_item("width", c.width)?;
            t.set_item("modulus", c.modulus)?;
            t.set_item("materials", c.materials.clone())?;
            t.set_item("rating", c.rating)?;
            t.set_item("exponent", c.exponent)?;
            t.set_item("crown", c.crown)?;
            Some(t)
        }
    };
    out.set_item("contact", contact)?;
    let spring = match &d.spring {
        None => None,
        Some(s) => {
            let t = PyDict::new(py);
            t.set_item("wire", s.wire)?;
            t.set_item("mean_diameter", s.mean_diameter)?;
            t.set_item("active_coils", s.active_coils)?;
            t.set_item("total_coils", s.total_coils)?;
            t.set_item("free_length", s.free_length)?;
            t.set_item("installed_length", s.installed_length)?;
            t.set_item("shear_modulus", s.shear_modulus)?;
            t.set_item("density", s.density)?;
            let f = &s.figures;
            let figures = PyDict::new(py);
            figures.set_item("rate", f.rate)?;
            figures.set_item("preload", f.preload)?;
            figures.set_item("solid", f.solid)?;
            figures.set_item("shortest", f.shortest)?;
            figures.set_item("clash_margin", f.clash_margin)?;
            figures.set_item("mass", f.mass)?;
            figures.set_item("surge", f.surge)?;
            figures.set_item("index", f.index)?;
            t.set_item("figures", figures)?;
            Some(t)
        }
    };
    out.set_item("spring", spring)?;
    let vibration = match &d.vibration {
        None => None,
        Some(v) => {
            let t = PyDict::new(py);
            t.set_item("masses", v.masses.clone())?;
            t.set_item("stiffness", v.stiffness.clone())?;
            t.set_item("damping", v.damping.clone())?;
            t.set_item("steps", v.steps)?;
            t.set_item("turns", v.turns)?;
            t.set_item("polydyne", v.polydyne)?;
            Some(t)
        }
    };
    out.set_item("vibration", vibration)?;
    Ok(out)
}
