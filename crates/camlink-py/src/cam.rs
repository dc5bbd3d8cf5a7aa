//! Binding of the cam design core: a synthesised cam, its motion, profile,
//! limits and round trip. Converts only; design files are read by
//! camlink-cam (`cam_design.rs`), and the Python module
//! `camlink.cam.design` builds the report.

use std::sync::Arc;

use camlink_cam::report::round_trip_errors;
use camlink_core::cam::hertz;
use camlink_core::cam::motion::EndConditions;
use camlink_core::cam::spring::Helical;
use camlink_core::cam::vibration::{self, Chain};
use camlink_core::cam::{Cam, Follower, LawKind, Program, SegmentSpec};
use camlink_core::cam_contact::{self, BearingSpec, ContactSpec};
use camlink_core::cam_limits::{self, Extreme, Train};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::to_array;

/// One segment as Python gives it: law, span (rad), lift, start and end
/// conditions `[s′, s″, s‴]` (None where free).
type SegmentArg = (String, f64, f64, [Option<f64>; 3], [Option<f64>; 3]);

/// A follower train as Python gives it: mass (kg), spring rate (N/m),
/// preload (N), damping (N·s/m), all at the follower.
type TrainArg = (f64, f64, f64, f64);

fn to_train((mass, spring_rate, preload, damping): TrainArg) -> Train {
    Train {
        mass,
        spring_rate,
        preload,
        damping,
    }
}

/// One segment's factors: (segment, law, [Cv, Ca, Cj], textbook values).
type FactorRow = (usize, String, [f64; 3], Option<[f64; 3]>);

/// A synthesised cam.
#[pyclass(frozen, module = "camlink._core")]
pub struct CamCore {
    pub(crate) cam: Arc<Cam>,
}

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

fn extreme(e: &Extreme) -> (f64, f64) {
    (e.value, e.theta)
}

#[pymethods]
impl CamCore {
    /// `follower`: translating-roller (offset, roller), translating-flat (),
    /// oscillating-roller (pivot, arm, roller), oscillating-flat (pivot,
    /// face_offset): its dimensions in that order (m).
    #[new]
    fn new(
        segments: Vec<SegmentArg>,
        follower: &str,
        dims: Vec<f64>,
        base_radius: f64,
        ccw: bool,
    ) -> PyResult<CamCore> {
        let mut specs = Vec::with_capacity(segments.len());
        for (k, (law, span, lift, start, end)) in segments.into_iter().enumerate() {
            let law = LawKind::parse(&law).ok_or_else(|| {
                let names: Vec<&str> = LawKind::ALL.iter().map(|l| l.name()).collect();
                value_error(format!(
                    "segment {k}: unknown law '{law}' (one of {})",
                    names.join(", ")
                ))
            })?;
            let (start, end): (EndConditions, EndConditions) = (start, end);
            specs.push(SegmentSpec {
                law,
                span,
                lift,
                start,
                end,
            });
        }
        let program = Program::new(&specs).map_err(value_error)?;
        let f = Follower::from_dims(follower, &dims).map_err(value_error)?;
        let cam = Cam::new(program, f, base_radius, ccw).map_err(value_error)?;
        Ok(CamCore { cam: Arc::new(cam) })
    }

    /// `[s, s′, s″, s‴]` at each θ (rad): an (n, 4) array.
    fn motion<'py>(
        &self,
        py: Python<'py>,
        theta: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let mut v = Vec::new();
        for &t in theta.as_slice()? {
            v.extend_from_slice(&self.cam.program.eval(t)[..4]);
        }
        to_array(py, v, 4)
    }

    /// Start angle (rad) of each segment.
    fn starts(&self) -> Vec<f64> {
        self.cam.program.starts()
    }

    /// Boundaries: (θ, before, after, continuity, [jumps of s′, s″, s‴], text).
    #[allow(clippy::type_complexity)]
    fn boundaries(&self) -> Vec<(f64, usize, usize, usize, [f64; 3], String)> {
        self.cam
            .program
            .boundaries()
            .into_iter()
            .map(|b| {
                let text = b.to_string();
                (b.theta, b.before, b.after, b.continuity, b.jumps, text)
            })
            .collect()
    }

    /// Factors: (segment, law, [Cv, Ca, Cj], textbook or None).
    fn factors(&self) -> Vec<FactorRow> {
        self.cam
            .program
            .factors()
            .into_iter()
            .map(|f| (f.segment, f.law.name().to_string(), f.computed, f.textbook))
            .collect()
    }

    /// Surface points (cam frame, m) at each θ: (n, 2); with `offset`, the
    /// curve that far outside the surface (a tool's centre path).
    #[pyo3(signature = (theta, offset = 0.0))]
    fn surface<'py>(
        &self,
        py: Python<'py>,
        theta: PyReadonlyArray1<'py, f64>,
        offset: f64,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let mut v = Vec::new();
        for &t in theta.as_slice()? {
            v.extend_from_slice(&self.cam.offset_point(t, offset));
        }
        to_array(py, v, 2)
    }

    /// A roller's pitch curve (cam frame, m) at each θ: (n, 2), or None.
    fn pitch<'py>(
        &self,
        py: Python<'py>,
        theta: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        if self.cam.follower.roller().is_none() {
            return Ok(None);
        }
        let mut v = Vec::new();
        for &t in theta.as_slice()? {
            v.extend_from_slice(&self.cam.pitch(t).map_or([f64::NAN; 2], |j| j.p));
        }
        to_array(py, v, 2).map(Some)
    }

    /// Contact quantities at each θ (ground frame): a dict of arrays
    /// `point` (n, 2), `normal` (n, 2), `pressure_angle`, `rho`,
    /// `rho_pitch`, `face_position` (NaN where not defined), `follower`
    /// (stem y in m or arm angle ψ in rad).
    fn contact<'py>(
        &self,
        py: Python<'py>,
        theta: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let th = theta.as_slice()?;
        let (mut point, mut normal) = (Vec::new(), Vec::new());
        let (mut phi, mut rho, mut rp, mut face, mut fol) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for &t in th {
            let c = self.cam.contact(t);
            point.extend_from_slice(&c.point);
            normal.extend_from_slice(&c.normal);
            phi.push(c.pressure_angle);
            rho.push(c.rho);
            rp.push(c.rho_pitch.unwrap_or(f64::NAN));
            face.push(c.face_position.unwrap_or(f64::NAN));
            fol.push(self.cam.follower_coordinate(t)[0]);
        }
        let d = PyDict::new(py);
        d.set_item("point", to_array(py, point, 2)?)?;
        d.set_item("normal", to_array(py, normal, 2)?)?;
        let arr = |v: Vec<f64>| -> Bound<'py, PyArray1<f64>> { v.into_pyarray(py) };
        d.set_item("pressure_angle", arr(phi))?;
        d.set_item("rho", arr(rho))?;
        d.set_item("rho_pitch", arr(rp))?;
        d.set_item("face_position", arr(face))?;
        d.set_item("follower", arr(fol))?;
        Ok(d)
    }

    /// The geometric limits over a turn, as a dict (angles in rad,
    /// lengths in m; extremes as (value, θ)).
    fn geometry<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let g = py.detach(|| cam_limits::geometry(&self.cam));
        let d = PyDict::new(py);
        d.set_item("pressure_rise", g.pressure_rise.as_ref().map(extreme))?;
        d.set_item("pressure_return", g.pressure_return.as_ref().map(extreme))?;
        d.set_item("min_convex_radius", extreme(&g.min_convex_radius))?;
        d.set_item(
            "min_concave_radius",
            g.min_concave_radius.as_ref().map(extreme),
        )?;
        d.set_item("min_pitch_radius", g.min_pitch_radius.as_ref().map(extreme))?;
        d.set_item("concave", g.concave)?;
        d.set_item("undercut", g.undercut)?;
        d.set_item(
            "face_travel",
            g.face_travel.map(|(a, b)| (extreme(&a), extreme(&b))),
        )?;
        d.set_item("max_radius", g.max_radius)?;
        Ok(d)
    }

    /// Contact force over a turn at ω (rad/s) and the jump speed, for the
    /// follower train `train`.
    fn force<'py>(
        &self,
        py: Python<'py>,
        train: TrainArg,
        omega: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let train = to_train(train);
        let f = py
            .detach(|| cam_limits::force(&self.cam, &train, omega))
            .map_err(value_error)?;
        let d = PyDict::new(py);
        d.set_item("omega", f.omega)?;
        d.set_item("theta", f.theta.into_pyarray(py))?;
        d.set_item("generalised", f.generalised.into_pyarray(py))?;
        d.set_item("normal", f.normal.into_pyarray(py))?;
        d.set_item("min_normal", extreme(&f.min_normal))?;
        d.set_item("max_normal", extreme(&f.max_normal))?;
        d.set_item("jump", f.jump.as_ref().map(extreme))?;
        Ok(d)
    }

    /// The least base circle radius (m) in [lo, hi] meeting the limits, or None.
    #[pyo3(signature = (max_pressure, min_radius, lo, hi))]
    fn smallest_base_radius(
        &self,
        py: Python<'_>,
        max_pressure: Option<f64>,
        min_radius: Option<f64>,
        lo: f64,
        hi: f64,
    ) -> PyResult<Option<f64>> {
        py.detach(|| cam_limits::smallest_base_radius(&self.cam, max_pressure, min_radius, lo, hi))
            .map_err(value_error)
    }

    /// Contact stress, camshaft torque and bearing life over a turn at ω
    /// (rad/s): the train as for `force`, the contact width (m) and
    /// contact modulus E* (Pa), and a bearing's dynamic rating C (N) and
    /// life exponent (None without a bearing), and a crowned roller's crown
    /// radius (m, None for a straight roller). A dict of arrays `theta`,
    /// `force`, `rho`, `half_width`, `pressure`, `torque` and extremes
    /// as (value, θ).
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (train, omega, width, modulus, rating = None, exponent = 3.0, crown = None))]
    fn stress<'py>(
        &self,
        py: Python<'py>,
        train: TrainArg,
        omega: f64,
        width: f64,
        modulus: f64,
        rating: Option<f64>,
        exponent: f64,
        crown: Option<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let train = to_train(train);
        let spec = ContactSpec {
            width,
            modulus,
            crown,
        };
        let bearing = rating.map(|rating| BearingSpec { rating, exponent });
        let s = py
            .detach(|| cam_contact::stress(&self.cam, &train, omega, &spec, bearing.as_ref()))
            .map_err(value_error)?;
        let d = PyDict::new(py);
        d.set_item("omega", s.omega)?;
        d.set_item("theta", s.theta.into_pyarray(py))?;
        d.set_item("force", s.force.into_pyarray(py))?;
        d.set_item("rho", s.rho.into_pyarray(py))?;
        d.set_item("half_width", s.half_width.into_pyarray(py))?;
        d.set_item("pressure", s.pressure.into_pyarray(py))?;
        d.set_item("max_pressure", extreme(&s.max_pressure))?;
        d.set_item("half_width_at_max", s.half_width_at_max)?;
        d.set_item("torque", s.torque.into_pyarray(py))?;
        d.set_item("peak_torque", extreme(&s.peak_torque))?;
        d.set_item("rms_torque", s.rms_torque)?;
        match s.bearing {
            Some(b) => {
                let e = PyDict::new(py);
                e.set_item("equivalent_load", b.equivalent_load)?;
                e.set_item("roller_turns", b.roller_turns)?;
                e.set_item("l10_revolutions", b.l10_revolutions)?;
                e.set_item("l10_turns", b.l10_turns)?;
                d.set_item("bearing", e)?;
            }
            None => d.set_item("bearing", py.None())?,
        }
        Ok(d)
    }

    /// The follower train (masses, stiffnesses, dampings from the cam
    /// outwards; return spring rate and preload) driven by the cam at ω
    /// (rad/s), `steps` steps a turn, `turns` turns (the last reported);
    /// with `polydyne`, by the program corrected for a one-mass train at
    /// that speed. A dict: `theta`, `input`, `position` (masses × samples),
    /// `velocity`, `deviation`, `contact` arrays and `residual`
    /// [(segment, amplitude, θ)].
    #[allow(clippy::too_many_arguments)]
    #[pyo3(signature = (masses, stiffness, damping, spring_rate, preload, omega, steps = 7200, turns = 3, polydyne = false))]
    fn vibration<'py>(
        &self,
        py: Python<'py>,
        masses: Vec<f64>,
        stiffness: Vec<f64>,
        damping: Vec<f64>,
        spring_rate: f64,
        preload: f64,
        omega: f64,
        steps: usize,
        turns: usize,
        polydyne: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let chain = Chain {
            masses,
            stiffness,
            damping,
            spring_rate,
            preload,
        };
        let program = &self.cam.program;
        let r = py
            .detach(|| {
                if polydyne {
                    let y = vibration::polydyne(program, &chain, omega)?;
                    vibration::simulate_input(program, &y, &chain, omega, steps, turns)
                } else {
                    vibration::simulate(program, &chain, omega, steps, turns)
                }
            })
            .map_err(value_error)?;
        let d = PyDict::new(py);
        let m = r.theta.len();
        d.set_item("omega", r.omega)?;
        d.set_item("theta", r.theta.into_pyarray(py))?;
        d.set_item("input", r.input.into_pyarray(py))?;
        d.set_item("position", to_array(py, r.position.concat(), m)?)?;
        d.set_item("velocity", to_array(py, r.velocity.concat(), m)?)?;
        d.set_item("deviation", r.deviation.into_pyarray(py))?;
        d.set_item("contact", r.contact.into_pyarray(py))?;
        let res: Vec<(usize, f64, f64)> = r
            .residual
            .iter()
            .map(|x| (x.segment, x.amplitude, x.theta))
            .collect();
        d.set_item("residual", res)?;
        Ok(d)
    }

    /// Round trip at ω (rad/s) in `steps` steps: (displacement, velocity,
    /// acceleration) relative errors. When the kinematic analysis of the
    /// cam mechanism stops, a `ValueError` says at which cam angle and why,
    /// in the design's terms (the mechanism's joints are camlink's own).
    fn round_trip(&self, py: Python<'_>, omega: f64, steps: usize) -> PyResult<(f64, f64, f64)> {
        let [d, v, a] = py
            .detach(|| round_trip_errors(&self.cam, omega, steps))
            .map_err(value_error)?;
        Ok((d, v, a))
    }
}

/// The follower kinds of cam design files and the dimensions each takes,
/// as `{kind: [field, …]}` ([`Follower::KINDS`]).
#[pyfunction]
pub(crate) fn cam_followers() -> Vec<(&'static str, Vec<&'static str>)> {
    Follower::KINDS
        .iter()
        .map(|(k, fields)| (*k, fields.to_vec()))
        .collect()
}

/// The motion law names of cam design files, in the order of the docs.
#[pyfunction]
pub(crate) fn cam_laws() -> Vec<&'static str> {
    LawKind::ALL.iter().map(|l| l.name()).collect()
}

/// The materials table: name -> (E Pa, ν, G Pa, density kg/m³).
#[pyfunction]
pub(crate) fn cam_materials() -> Vec<(String, f64, f64, f64, f64)> {
    hertz::MATERIALS
        .iter()
        .map(|(n, m)| (n.to_string(), m.young, m.poisson, m.shear, m.density))
        .collect()
}

/// Contact modulus E* (Pa) of two materials given as (E Pa, ν).
#[pyfunction]
pub(crate) fn contact_modulus(a: (f64, f64), b: (f64, f64)) -> f64 {
    let m = |(young, poisson): (f64, f64)| hertz::Material {
        young,
        poisson,
        shear: f64::NAN,
        density: f64::NAN,
    };
    hertz::contact_modulus(&m(a), &m(b))
}

/// Hertz line contact of cylinders of radii r1, r2 (m; negative concave,
/// inf flat) under force (N) over length (m), modulus E* (Pa):
/// (half-width m, p_max Pa), or None without contact.
#[pyfunction]
pub(crate) fn line_contact(
    r1: f64,
    r2: f64,
    force: f64,
    length: f64,
    modulus: f64,
) -> Option<(f64, f64)> {
    hertz::line_contact(r1, r2, force, length, modulus).map(|c| (c.half_width, c.max_pressure))
}

/// A helical compression spring (d, D, N_a, N_t, L₀ in m or coils; G Pa;
/// density kg/m³) installed at `installed` (m) and lifted by `max_lift`
/// (m): a dict of rate, preload, solid, shortest, clash_margin, mass,
/// surge (Hz), index. A `ValueError` names the field (`field: message`).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub(crate) fn helical_spring<'py>(
    py: Python<'py>,
    wire: f64,
    mean_diameter: f64,
    active_coils: f64,
    total_coils: f64,
    free_length: f64,
    shear_modulus: f64,
    density: f64,
    installed: f64,
    max_lift: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let s = Helical {
        wire,
        mean_diameter,
        active_coils,
        total_coils,
        free_length,
        shear_modulus,
        density,
    };
    let i = s
        .install(installed, max_lift)
        .map_err(|e| value_error(format!("{}: {}", e.field, e.message)))?;
    crate::cam_design::installed_dict(py, &i)
}
