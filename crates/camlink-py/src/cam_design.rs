//! Binding of cam design files (camlink-cam): a checked file, and its
//! design report, as plain Python data that `camlink.cam.design` turns
//! into its dataclasses. Converts only.

use std::collections::BTreeSet;

use camlink_cam::report::{
    self, BearingFigures, Boundary, Check, ContactFigures, FaceTravel, Factor, Polydyne, Report,
    ReportError, Residual, Sizing, SpringFigures, VibrationFigures,
};
use camlink_cam::{
    ContactSpec, Design, DxfMode, Dynamics, Export, Limits, Loaded, Segment, SpringSpec,
    VibrationSpec,
};
use camlink_core::cam::spring::Installed;
use camlink_core::cam::{Follower, LawKind};
use pyo3::conversion::FromPyObjectOwned;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

use crate::cam::CamCore;
use crate::ModelError;

/// Reads and checks the design file `text` (TOML, or with `json` the
/// file's data as JSON); `source` names it in messages. Returns the design
/// as a dict (SI units, radians; keys as `camlink.cam.design.Design`'s
/// fields) and the loader's warnings; raises `ModelError` naming the
/// file, line and field.
#[pyfunction]
#[pyo3(signature = (text, source, json = false))]
pub(crate) fn cam_design_load<'py>(
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
pub(crate) fn cam_design_read<'py>(
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
pub(crate) fn cam_design_limits<'py>(py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
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
pub(crate) fn cam_is_design(json: &str) -> bool {
    camlink_cam::load::json_table(json).is_ok_and(|t| camlink_cam::is_design(&t))
}

/// Why `name` is not a plain file name (a path separator, a folder, a
/// control character, a drive), or None.
#[pyfunction]
pub(crate) fn plain_file_name_problem(name: &str) -> Option<&'static str> {
    camlink_cam::load::not_plain(name)
}

/// ` (did you mean 'x'?)` for the candidate nearest `name`, or "".
#[pyfunction]
pub(crate) fn did_you_mean(name: &str, candidates: Vec<String>) -> String {
    camlink_core::names::did_you_mean(name, candidates.iter().map(String::as_str))
}

pub(crate) fn design_dict<'py>(py: Python<'py>, d: &Design) -> PyResult<Bound<'py, PyDict>> {
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
            t.set_item("figures", installed_dict(py, &s.figures)?)?;
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

/// The design report of `design` (a `camlink.cam.design.Design`), as a
/// dict with the keys of `camlink.cam.design.Report`'s fields (lengths in
/// m, angles in degrees; see `camlink_cam::report`). A design whose cam
/// does not synthesise, or an analysis behind a check that cannot run,
/// raises `ModelError` naming the file.
#[pyfunction]
pub(crate) fn cam_design_report<'py>(
    py: Python<'py>,
    design: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let design = design_from(design)?;
    let report = py
        .detach(|| report::analyse(&design))
        .map_err(|e| match e {
            ReportError::Design(m) => ModelError::new_err(format!("{}: {m}", design.source)),
            ReportError::Analysis(m) => ModelError::new_err(format!("{}: {m}", design.source)),
        })?;
    report_dict(py, &report)
}

/// `report` (a `camlink.cam.design.Report`) with its lengths in `units`
/// ("m" or "mm"; `Report::in_units`), as [`cam_design_report`]'s dict.
#[pyfunction]
pub(crate) fn cam_report_in_units<'py>(
    py: Python<'py>,
    report: &Bound<'py, PyAny>,
    units: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let r = report_from(report)?
        .in_units(units)
        .map_err(PyValueError::new_err)?;
    report_dict(py, &r)
}

/// θ ranges (rad) a tool of radius `tool_radius` (m) cannot cut on the
/// cam `core`, sampled at `n` angles (default
/// `camlink_cam::report::TOOL_SAMPLES`; `report::tool_undercut`).
#[pyfunction]
#[pyo3(signature = (core, tool_radius, n = None))]
pub(crate) fn cam_tool_undercut(
    core: &CamCore,
    tool_radius: f64,
    n: Option<usize>,
) -> PyResult<Vec<(f64, f64)>> {
    let n = n.unwrap_or(report::TOOL_SAMPLES);
    if n == 0 {
        return Err(PyValueError::new_err(
            "the tool check needs at least one sample",
        ));
    }
    Ok(report::tool_undercut(&core.cam, tool_radius, n))
}

/// The attribute `name` of `o`.
fn attr<'py, T: FromPyObjectOwned<'py>>(o: &Bound<'py, PyAny>, name: &str) -> PyResult<T> {
    o.getattr(name)?.extract::<T>().map_err(Into::into)
}

/// The item `key` of the dict `o`.
fn item<'py, T: FromPyObjectOwned<'py>>(o: &Bound<'py, PyAny>, key: &str) -> PyResult<T> {
    o.get_item(key)?.extract::<T>().map_err(Into::into)
}

/// The attribute `name` of `o`, or `None` when it is None.
fn some<'py>(o: &Bound<'py, PyAny>, name: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
    let v = o.getattr(name)?;
    Ok((!v.is_none()).then_some(v))
}

/// A `camlink.cam.design.Design` as camlink-cam's [`Design`].
fn design_from(o: &Bound<'_, PyAny>) -> PyResult<Design> {
    let kind: String = attr(o, "follower")?;
    let follower = Follower::KINDS
        .iter()
        .map(|(k, _)| *k)
        .find(|k| *k == kind)
        .ok_or_else(|| PyValueError::new_err(format!("unknown follower type '{kind}'")))?;
    let mut segments = Vec::new();
    for s in o.getattr("segments")?.try_iter()? {
        let s = s?;
        let law: String = attr(&s, "law")?;
        let law = LawKind::parse(&law)
            .ok_or_else(|| PyValueError::new_err(format!("unknown law '{law}'")))?;
        segments.push(Segment {
            law,
            span: attr(&s, "span")?,
            lift: attr(&s, "lift")?,
            start: attr(&s, "start")?,
            end: attr(&s, "end")?,
        });
    }
    let l = o.getattr("limits")?;
    let limits = Limits {
        max_pressure_angle: attr(&l, "max_pressure_angle")?,
        min_radius: attr(&l, "min_radius")?,
        max_face_width: attr(&l, "max_face_width")?,
        base_radius_range: attr(&l, "base_radius_range")?,
        max_contact_stress: attr(&l, "max_contact_stress")?,
        min_bearing_life_hours: attr(&l, "min_bearing_life_hours")?,
        min_coil_clearance: attr(&l, "min_coil_clearance")?,
        min_surge_ratio: attr(&l, "min_surge_ratio")?,
        max_residual_vibration: attr(&l, "max_residual_vibration")?,
    };
    let dynamics = match some(o, "dynamics")? {
        None => None,
        Some(y) => Some(Dynamics {
            mass: attr(&y, "mass")?,
            spring_rate: attr(&y, "spring_rate")?,
            preload: attr(&y, "preload")?,
            damping: attr(&y, "damping")?,
            speed: attr(&y, "speed")?,
            redline: attr(&y, "redline")?,
        }),
    };
    let e = o.getattr("export")?;
    let mode: String = attr(&e, "dxf_mode")?;
    let given: BTreeSet<String> = attr(&e, "given")?;
    let export = Export {
        csv: attr(&e, "csv")?,
        csv_step: attr(&e, "csv_step")?,
        csv_chord: attr(&e, "csv_chord")?,
        dxf: attr(&e, "dxf")?,
        dxf_mode: match mode.as_str() {
            "polyline" => DxfMode::Polyline,
            "arcs" => DxfMode::Arcs,
            other => {
                return Err(PyValueError::new_err(format!(
                    "export.dxf_mode: '{other}' is not one of polyline, arcs"
                )))
            }
        },
        tolerance: attr(&e, "tolerance")?,
        svg: attr(&e, "svg")?,
        tool_radius: attr(&e, "tool_radius")?,
        svaj: attr(&e, "svaj")?,
        profile: attr(&e, "profile")?,
        given: given.into_iter().collect(),
        units: attr(&e, "units")?,
        svaj_time: attr(&e, "svaj_time")?,
        vibration: attr(&e, "vibration")?,
        bore_radius: attr(&e, "bore_radius")?,
        keyway_width: attr(&e, "keyway_width")?,
        keyway_depth: attr(&e, "keyway_depth")?,
        keyway_angle: attr(&e, "keyway_angle")?,
        timing_mark: attr(&e, "timing_mark")?,
    };
    let contact = match some(o, "contact")? {
        None => None,
        Some(c) => Some(ContactSpec {
            width: attr(&c, "width")?,
            modulus: attr(&c, "modulus")?,
            materials: attr(&c, "materials")?,
            rating: attr(&c, "rating")?,
            exponent: attr(&c, "exponent")?,
            crown: attr(&c, "crown")?,
        }),
    };
    let spring = match some(o, "spring")? {
        None => None,
        Some(s) => {
            let f = s.getattr("figures")?;
            Some(SpringSpec {
                wire: attr(&s, "wire")?,
                mean_diameter: attr(&s, "mean_diameter")?,
                active_coils: attr(&s, "active_coils")?,
                total_coils: attr(&s, "total_coils")?,
                free_length: attr(&s, "free_length")?,
                installed_length: attr(&s, "installed_length")?,
                shear_modulus: attr(&s, "shear_modulus")?,
                density: attr(&s, "density")?,
                figures: installed_from(&f)?,
            })
        }
    };
    let vibration = match some(o, "vibration")? {
        None => None,
        Some(v) => Some(VibrationSpec {
            masses: attr(&v, "masses")?,
            stiffness: attr(&v, "stiffness")?,
            damping: attr(&v, "damping")?,
            steps: attr(&v, "steps")?,
            turns: attr(&v, "turns")?,
            polydyne: attr(&v, "polydyne")?,
        }),
    };
    Ok(Design {
        source: o.getattr("path")?.str()?.to_string(),
        name: attr(o, "name")?,
        follower,
        dims: attr(o, "dims")?,
        base_radius: attr(o, "base_radius")?,
        ccw: attr(o, "ccw")?,
        segments,
        limits,
        dynamics,
        export,
        contact,
        spring,
        vibration,
    })
}

/// A spring's figures as a dict: rate, preload, solid, shortest,
/// clash_margin, mass, surge, index.
pub(crate) fn installed_dict<'py>(py: Python<'py>, f: &Installed) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("rate", f.rate)?;
    d.set_item("preload", f.preload)?;
    d.set_item("solid", f.solid)?;
    d.set_item("shortest", f.shortest)?;
    d.set_item("clash_margin", f.clash_margin)?;
    d.set_item("mass", f.mass)?;
    d.set_item("surge", f.surge)?;
    d.set_item("index", f.index)?;
    Ok(d)
}

/// A spring's figures dict ([`installed_dict`]) as [`Installed`].
fn installed_from(f: &Bound<'_, PyAny>) -> PyResult<Installed> {
    Ok(Installed {
        rate: item(f, "rate")?,
        preload: item(f, "preload")?,
        solid: item(f, "solid")?,
        shortest: item(f, "shortest")?,
        clash_margin: item(f, "clash_margin")?,
        mass: item(f, "mass")?,
        surge: item(f, "surge")?,
        index: item(f, "index")?,
    })
}

/// The report as a dict of `camlink.cam.design.Report`'s fields (the
/// checks, boundaries, factors and face travel as dicts of their
/// dataclasses' fields; `sizing` as `Report.sizing` holds it).
fn report_dict<'py>(py: Python<'py>, r: &Report) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", &r.name)?;
    d.set_item("follower", &r.follower)?;
    d.set_item("base_radius", r.base_radius)?;
    let boundaries = PyList::empty(py);
    for b in &r.boundaries {
        let t = PyDict::new(py);
        t.set_item("theta_deg", b.theta_deg)?;
        t.set_item("before", b.before)?;
        t.set_item("after", b.after)?;
        t.set_item("continuity", b.continuity)?;
        t.set_item("jumps", PyTuple::new(py, b.jumps)?)?;
        t.set_item("text", &b.text)?;
        boundaries.append(t)?;
    }
    d.set_item("boundaries", boundaries)?;
    let factors = PyList::empty(py);
    for f in &r.factors {
        let t = PyDict::new(py);
        t.set_item("segment", f.segment)?;
        t.set_item("law", &f.law)?;
        t.set_item("computed", PyTuple::new(py, f.computed)?)?;
        let textbook = f.textbook.map(|v| PyTuple::new(py, v)).transpose()?;
        t.set_item("textbook", textbook)?;
        factors.append(t)?;
    }
    d.set_item("factors", factors)?;
    let checks = PyList::empty(py);
    for c in &r.checks {
        let t = PyDict::new(py);
        t.set_item("name", &c.name)?;
        t.set_item("value", c.value)?;
        t.set_item("limit", c.limit)?;
        t.set_item("margin", c.margin)?;
        t.set_item("unit", &c.unit)?;
        t.set_item("at_deg", c.at_deg)?;
        t.set_item("ok", c.ok)?;
        t.set_item("note", &c.note)?;
        checks.append(t)?;
    }
    d.set_item("checks", checks)?;
    d.set_item("concave_deg", r.concave_deg.clone())?;
    d.set_item("undercut_deg", r.undercut_deg.clone())?;
    d.set_item("tool_undercut_deg", r.tool_undercut_deg.clone())?;
    d.set_item("smallest_base_radius", r.smallest_base_radius)?;
    let round = r.round_trip.map(|v| PyTuple::new(py, v)).transpose()?;
    d.set_item("round_trip", round)?;
    let travel = match &r.face_travel {
        None => None,
        Some(f) => {
            let t = PyDict::new(py);
            t.set_item("lo", f.lo)?;
            t.set_item("hi", f.hi)?;
            t.set_item("lo_at_deg", f.lo_at_deg)?;
            t.set_item("hi_at_deg", f.hi_at_deg)?;
            Some(t)
        }
    };
    d.set_item("face_travel", travel)?;
    d.set_item("units", &r.units)?;
    d.set_item("sizing", sizing_dict(py, &r.sizing)?)?;
    Ok(d)
}

/// The sizing figures as `Report.sizing`'s dict: keys `contact`,
/// `bearing`, `spring`, `vibration` where the design has them (SI).
fn sizing_dict<'py>(py: Python<'py>, s: &Sizing) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    if let Some(c) = &s.contact {
        let t = PyDict::new(py);
        t.set_item("max_pressure", c.max_pressure)?;
        t.set_item("max_pressure_at_deg", c.max_pressure_at_deg)?;
        t.set_item("half_width", c.half_width)?;
        t.set_item("modulus", c.modulus)?;
        t.set_item("peak_torque", c.peak_torque)?;
        t.set_item("peak_torque_at_deg", c.peak_torque_at_deg)?;
        t.set_item("rms_torque", c.rms_torque)?;
        d.set_item("contact", t)?;
    }
    if let Some(b) = &s.bearing {
        let t = PyDict::new(py);
        t.set_item("equivalent_load", b.equivalent_load)?;
        t.set_item("roller_turns", b.roller_turns)?;
        t.set_item("l10_revolutions", b.l10_revolutions)?;
        t.set_item("l10_turns", b.l10_turns)?;
        t.set_item("l10_hours", b.l10_hours)?;
        d.set_item("bearing", t)?;
    }
    if let Some(sp) = &s.spring {
        let t = installed_dict(py, &sp.installed)?;
        t.set_item("surge_ratio", sp.surge_ratio)?;
        d.set_item("spring", t)?;
    }
    if let Some(v) = &s.vibration {
        let t = PyDict::new(py);
        t.set_item("max_deviation", v.max_deviation)?;
        let residual = PyList::empty(py);
        for x in &v.residual {
            let e = PyDict::new(py);
            e.set_item("segment", x.segment)?;
            e.set_item("amplitude", x.amplitude)?;
            e.set_item("at_deg", x.at_deg)?;
            residual.append(e)?;
        }
        t.set_item("residual", residual)?;
        t.set_item("min_contact", v.min_contact)?;
        if let Some(p) = &v.polydyne {
            let e = PyDict::new(py);
            e.set_item("max_departure", p.max_departure)?;
            e.set_item("max_correction", p.max_correction)?;
            t.set_item("polydyne", e)?;
        }
        d.set_item("vibration", t)?;
    }
    Ok(d)
}

/// A `camlink.cam.design.Report` as camlink-cam's [`Report`].
fn report_from(o: &Bound<'_, PyAny>) -> PyResult<Report> {
    let mut boundaries = Vec::new();
    for b in o.getattr("boundaries")?.try_iter()? {
        let b = b?;
        boundaries.push(Boundary {
            theta_deg: attr(&b, "theta_deg")?,
            before: attr(&b, "before")?,
            after: attr(&b, "after")?,
            continuity: attr(&b, "continuity")?,
            jumps: attr(&b, "jumps")?,
            text: attr(&b, "text")?,
        });
    }
    let mut factors = Vec::new();
    for f in o.getattr("factors")?.try_iter()? {
        let f = f?;
        factors.push(Factor {
            segment: attr(&f, "segment")?,
            law: attr(&f, "law")?,
            computed: attr(&f, "computed")?,
            textbook: attr(&f, "textbook")?,
        });
    }
    let mut checks = Vec::new();
    for c in o.getattr("checks")?.try_iter()? {
        let c = c?;
        checks.push(Check {
            name: attr(&c, "name")?,
            value: attr(&c, "value")?,
            limit: attr(&c, "limit")?,
            margin: attr(&c, "margin")?,
            unit: attr(&c, "unit")?,
            at_deg: attr(&c, "at_deg")?,
            ok: attr(&c, "ok")?,
            note: attr(&c, "note")?,
        });
    }
    let face_travel = match some(o, "face_travel")? {
        None => None,
        Some(f) => Some(FaceTravel {
            lo: attr(&f, "lo")?,
            hi: attr(&f, "hi")?,
            lo_at_deg: attr(&f, "lo_at_deg")?,
            hi_at_deg: attr(&f, "hi_at_deg")?,
        }),
    };
    Ok(Report {
        name: attr(o, "name")?,
        follower: attr(o, "follower")?,
        base_radius: attr(o, "base_radius")?,
        boundaries,
        factors,
        checks,
        concave_deg: attr(o, "concave_deg")?,
        undercut_deg: attr(o, "undercut_deg")?,
        tool_undercut_deg: attr(o, "tool_undercut_deg")?,
        smallest_base_radius: attr(o, "smallest_base_radius")?,
        round_trip: attr(o, "round_trip")?,
        face_travel,
        units: attr(o, "units")?,
        sizing: sizing_from(&o.getattr("sizing")?)?,
    })
}

/// `Report.sizing`'s dict as [`Sizing`].
fn sizing_from(d: &Bound<'_, PyAny>) -> PyResult<Sizing> {
    let part = |key: &str| -> PyResult<Option<Bound<'_, PyAny>>> {
        Ok(d.call_method1("get", (key,))?
            .extract::<Option<Bound<'_, PyAny>>>()?)
    };
    let contact = match part("contact")? {
        None => None,
        Some(c) => Some(ContactFigures {
            max_pressure: item(&c, "max_pressure")?,
            max_pressure_at_deg: item(&c, "max_pressure_at_deg")?,
            half_width: item(&c, "half_width")?,
            modulus: item(&c, "modulus")?,
            peak_torque: item(&c, "peak_torque")?,
            peak_torque_at_deg: item(&c, "peak_torque_at_deg")?,
            rms_torque: item(&c, "rms_torque")?,
        }),
    };
    let bearing = match part("bearing")? {
        None => None,
        Some(b) => Some(BearingFigures {
            equivalent_load: item(&b, "equivalent_load")?,
            roller_turns: item(&b, "roller_turns")?,
            l10_revolutions: item(&b, "l10_revolutions")?,
            l10_turns: item(&b, "l10_turns")?,
            l10_hours: item(&b, "l10_hours")?,
        }),
    };
    let spring = match part("spring")? {
        None => None,
        Some(s) => Some(SpringFigures {
            installed: installed_from(&s)?,
            surge_ratio: item(&s, "surge_ratio")?,
        }),
    };
    let vibration = match part("vibration")? {
        None => None,
        Some(v) => {
            let mut residual = Vec::new();
            for x in v.get_item("residual")?.try_iter()? {
                let x = x?;
                residual.push(Residual {
                    segment: item(&x, "segment")?,
                    amplitude: item(&x, "amplitude")?,
                    at_deg: item(&x, "at_deg")?,
                });
            }
            let polydyne = match v
                .call_method1("get", ("polydyne",))?
                .extract::<Option<Bound<'_, PyAny>>>()?
            {
                None => None,
                Some(p) => Some(Polydyne {
                    max_departure: item(&p, "max_departure")?,
                    max_correction: item(&p, "max_correction")?,
                }),
            };
            Some(VibrationFigures {
                max_deviation: item(&v, "max_deviation")?,
                residual,
                min_contact: item(&v, "min_contact")?,
                polydyne,
            })
        }
    };
    Ok(Sizing {
        contact,
        bearing,
        spring,
        vibration,
    })
}
