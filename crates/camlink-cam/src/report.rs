//! The design report of a checked [`Design`]: which limits are checked,
//! each one's value, limit, margin and verdict, and the figures behind
//! them; and the report in another length unit ([`Report::in_units`]).
//!
//! Units of a report: angles in degrees (`*_deg`, a check's `at_deg`);
//! lengths in the report's `units` ("m" or "mm"), which are metres as
//! [`analyse`] makes it; each [`Check`] states its own unit (`deg`, `m`,
//! `mm`, `N`, `rpm`, `MPa`, `h`, `N·m`, `rad`, or "" for a ratio or a
//! count). [`Sizing`] stays in SI whatever the unit.

mod sizing;

use std::f64::consts::TAU;
use std::sync::Arc;

use camlink_core::cam::Cam;
use camlink_core::cam_limits::{self, Train};
use camlink_core::cam_mechanism::round_trip;
use camlink_core::fmt_num::{num, num_digits};
use camlink_core::run::Kind;

pub use sizing::VibrationFigures;
pub use sizing::{BearingFigures, ContactFigures, Polydyne, Residual, Sizing, SpringFigures};

use crate::design::{Design, Dynamics};
use crate::limits::RPM;

/// Samples over a turn at which a cutting tool is checked
/// ([`tool_undercut`]): every 0.1°.
pub const TOOL_SAMPLES: usize = 3600;

/// Steps of the round trip (one turn at ω = 1 rad/s).
pub const ROUND_TRIP_STEPS: usize = 720;

/// One design limit: its value, the user's limit, the margin and the
/// verdict, all in `unit`.
#[derive(Clone, Debug, PartialEq)]
pub struct Check {
    /// What is checked ("pressure angle, rise").
    pub name: String,
    /// The design's figure; NaN when there is none (a failing search).
    pub value: f64,
    /// The limit it is held to; `None` for a check without one.
    pub limit: Option<f64>,
    /// How far inside the limit (positive) or past it (negative).
    pub margin: Option<f64>,
    /// Unit of `value`, `limit` and `margin` ("" for a ratio or a count).
    pub unit: String,
    /// Cam angle θ (deg) where the figure is reached, when it is a point.
    pub at_deg: Option<f64>,
    pub ok: bool,
    /// More figures or why it failed; "" when nothing more.
    pub note: String,
}

impl Check {
    #[allow(clippy::too_many_arguments)]
    fn new(
        name: impl Into<String>,
        value: f64,
        limit: Option<f64>,
        margin: Option<f64>,
        unit: &str,
        at_deg: Option<f64>,
        ok: bool,
        note: impl Into<String>,
    ) -> Check {
        Check {
            name: name.into(),
            value,
            limit,
            margin,
            unit: unit.to_string(),
            at_deg,
            ok,
            note: note.into(),
        }
    }
}

/// The continuity where two segments meet.
#[derive(Clone, Debug, PartialEq)]
pub struct Boundary {
    /// Cam angle θ (deg).
    pub theta_deg: f64,
    /// Segments on either side (indices; the last meets the first).
    pub before: usize,
    pub after: usize,
    /// Highest continuous derivative: 0 (position) … 3 (jerk).
    pub continuity: usize,
    /// Jumps (after − before) of s′, s″, s‴ (per rad of cam angle).
    pub jumps: [f64; 3],
    /// The boundary in words ("C2 at 120°: jerk jumps by …").
    pub text: String,
}

/// A segment's peak dimensionless factors beside its law's textbook ones.
#[derive(Clone, Debug, PartialEq)]
pub struct Factor {
    pub segment: usize,
    /// The law's name in design files.
    pub law: String,
    /// max |S′|, |S″|, |S‴| over the segment (Cv, Ca, Cj).
    pub computed: [f64; 3],
    pub textbook: Option<[f64; 3]>,
}

/// Where the contact runs along a flat face over a turn: its least and
/// greatest position (report units) from the stem axis (translating) or
/// from the foot of the perpendicular from the pivot (oscillating), and
/// the cam angles (deg) where it gets there; the face must span them.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceTravel {
    pub lo: f64,
    pub hi: f64,
    pub lo_at_deg: f64,
    pub hi_at_deg: f64,
}

impl FaceTravel {
    /// The face width needed (report units).
    pub fn width(&self) -> f64 {
        self.hi - self.lo
    }
}

/// Everything `camlink cam` reports of a design.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    pub name: String,
    pub follower: String,
    /// Base circle radius R_b (report units).
    pub base_radius: f64,
    pub boundaries: Vec<Boundary>,
    pub factors: Vec<Factor>,
    pub checks: Vec<Check>,
    /// θ ranges (deg) where the surface is concave.
    pub concave_deg: Vec<(f64, f64)>,
    /// θ ranges (deg) where the follower undercuts the profile.
    pub undercut_deg: Vec<(f64, f64)>,
    /// θ ranges (deg) the export's cutting tool cannot cut.
    pub tool_undercut_deg: Vec<(f64, f64)>,
    /// The least base circle radius (report units) in the search range
    /// meeting the limits; `None` without a search or when none does.
    pub smallest_base_radius: Option<f64>,
    /// Largest relative errors of displacement, velocity, acceleration of
    /// camlink's kinematics against the program; `None` when the
    /// kinematics could not run the cam (a failing check says where).
    pub round_trip: Option<[f64; 3]>,
    /// A flat face's contact travel; `None` for a roller.
    pub face_travel: Option<FaceTravel>,
    /// Length unit of the report: "m" or "mm".
    pub units: String,
    /// Contact stress, bearing, spring and vibration figures (SI) behind
    /// their checks.
    pub sizing: Sizing,
}

/// Why a design cannot be reported.
#[derive(Clone, Debug, PartialEq)]
pub enum ReportError {
    /// The design does not synthesise (program or follower geometry).
    Design(String),
    /// An analysis behind a check cannot run (forces, stress, vibration,
    /// the base circle search).
    Analysis(String),
}

impl std::fmt::Display for ReportError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ReportError::Design(m) | ReportError::Analysis(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for ReportError {}

fn analysis(e: impl std::fmt::Display) -> ReportError {
    ReportError::Analysis(e.to_string())
}

impl Report {
    /// Whether every limit holds.
    pub fn ok(&self) -> bool {
        self.checks.iter().all(|c| c.ok)
    }

    /// The report with its lengths in `units` ("m" or "mm"): the checks
    /// in a length unit, the base circle, the smallest base circle and
    /// the face travel (angles are in degrees already, [`Sizing`] stays
    /// SI).
    pub fn in_units(&self, units: &str) -> Result<Report, String> {
        let to = length_unit(units)?;
        let from = length_unit(&self.units)?;
        if to == from {
            return Ok(self.clone());
        }
        // Metres to millimetres multiply by 1000, the way back divides.
        let conv = |v: f64| if to == "mm" { v * 1000.0 } else { v / 1000.0 };
        let travel = self.face_travel.as_ref().map(|t| FaceTravel {
            lo: conv(t.lo),
            hi: conv(t.hi),
            ..t.clone()
        });
        let checks = self
            .checks
            .iter()
            .map(|c| {
                if c.unit != from {
                    return c.clone();
                }
                let note = match &travel {
                    Some(t) if c.name == FACE_WIDTH => face_note(t, to),
                    _ => c.note.clone(),
                };
                Check {
                    value: conv(c.value),
                    limit: c.limit.map(conv),
                    margin: c.margin.map(conv),
                    unit: to.to_string(),
                    note,
                    ..c.clone()
                }
            })
            .collect();
        Ok(Report {
            base_radius: conv(self.base_radius),
            checks,
            smallest_base_radius: self.smallest_base_radius.map(conv),
            face_travel: travel,
            units: to.to_string(),
            ..self.clone()
        })
    }
}

/// `units` if it is a report's length unit ("m" or "mm").
fn length_unit(units: &str) -> Result<&'static str, String> {
    match units {
        "m" => Ok("m"),
        "mm" => Ok("mm"),
        other => Err(format!(
            "'{other}' is not a length unit of the cam report (m or mm)"
        )),
    }
}

/// The name of the face width check.
const FACE_WIDTH: &str = "face width needed";

/// The face width check's note: where the contact travels (in `unit`).
fn face_note(t: &FaceTravel, unit: &str) -> String {
    format!(
        "contact travels from {} to {} {unit} along the face",
        num_digits(t.lo, 6),
        num_digits(t.hi, 6)
    )
}

/// Synthesises the design's cam and checks every limit: pressure angles,
/// least convex radius, a roller's pitch curve, undercut, a flat face's
/// width and concave parts, contact force and jump speed (with
/// `[dynamics]`), the smallest base circle (with a search range), contact
/// stress, bearing life, spring and vibration ([`Sizing`]), and the round
/// trip of camlink's own kinematics. The report is in metres.
pub fn analyse(design: &Design) -> Result<Report, ReportError> {
    let cam = Arc::new(
        design
            .cam()
            .map_err(|e| ReportError::Design(e.to_string()))?,
    );
    let g = cam_limits::geometry(&cam);
    let lim = &design.limits;
    let mut checks = Vec::new();

    // Pressure angles (a translating flat face has none).
    if design.follower != "translating-flat" {
        for (e, label) in [
            (&g.pressure_rise, "pressure angle, rise"),
            (&g.pressure_return, "pressure angle, return"),
        ] {
            let Some(e) = e else { continue };
            let margin = lim
                .max_pressure_angle
                .map(|l| (l - e.value.abs()).to_degrees());
            checks.push(Check::new(
                label,
                e.value.to_degrees(),
                lim.max_pressure_angle.map(f64::to_degrees),
                margin,
                "deg",
                Some(e.theta.to_degrees()),
                margin.is_none_or(|m| m >= 0.0),
                "",
            ));
        }
    }

    // Least convex radius of curvature of the surface.
    let r = &g.min_convex_radius;
    let margin = lim.min_radius.map(|l| r.value - l);
    checks.push(Check::new(
        "least radius of curvature (convex)",
        r.value,
        lim.min_radius,
        margin,
        "m",
        Some(r.theta.to_degrees()),
        margin.is_none_or(|m| m >= 0.0),
        "",
    ));

    // A roller's pitch curve must be rounder than the roller.
    if let (Some(p), Some(roller)) = (&g.min_pitch_radius, design.dims.last()) {
        checks.push(Check::new(
            "least convex pitch-curve radius vs roller radius",
            p.value,
            Some(*roller),
            Some(p.value - roller),
            "m",
            Some(p.theta.to_degrees()),
            p.value > *roller,
            "",
        ));
    }

    checks.push(Check::new(
        "undercut ranges",
        g.undercut.len() as f64,
        None,
        None,
        "",
        None,
        g.undercut.is_empty(),
        "",
    ));

    // A flat face: the width its contact travels over, no concave part.
    let mut travel = None;
    if design.follower.ends_with("flat") {
        if let Some((lo, hi)) = &g.face_travel {
            let t = FaceTravel {
                lo: lo.value,
                hi: hi.value,
                lo_at_deg: lo.theta.to_degrees(),
                hi_at_deg: hi.theta.to_degrees(),
            };
            let width = t.width();
            let margin = lim.max_face_width.map(|l| l - width);
            checks.push(Check::new(
                FACE_WIDTH,
                width,
                lim.max_face_width,
                margin,
                "m",
                None,
                margin.is_none_or(|m| m >= 0.0),
                face_note(&t, "m"),
            ));
            travel = Some(t);
        }
        if !g.concave.is_empty() {
            checks.push(Check::new(
                "concave ranges under a flat face",
                g.concave.len() as f64,
                None,
                None,
                "",
                None,
                false,
                "",
            ));
        }
    }

    // Contact force at the running speed and the speed of jump.
    if let Some(d) = &design.dynamics {
        let f = cam_limits::force(&cam, &train(d), d.speed).map_err(analysis)?;
        let rpm = d.speed / RPM;
        let least = &f.min_normal;
        checks.push(Check::new(
            format!("least contact force at {} rpm", num(rpm)),
            least.value,
            Some(0.0),
            Some(least.value),
            "N",
            Some(least.theta.to_degrees()),
            least.value > 0.0,
            "",
        ));
        let jump_rpm = f.jump.as_ref().map_or(f64::INFINITY, |j| j.value / RPM);
        let at = f.jump.as_ref().map(|j| j.theta.to_degrees());
        checks.push(match d.redline {
            Some(red) => {
                let red = red / RPM;
                Check::new(
                    "jump speed vs redline",
                    jump_rpm,
                    Some(red),
                    Some(jump_rpm - red),
                    "rpm",
                    at,
                    jump_rpm > red,
                    "",
                )
            }
            None => Check::new(
                "jump speed",
                jump_rpm,
                None,
                None,
                "rpm",
                at,
                jump_rpm > rpm,
                "",
            ),
        });
    }

    let tool = design
        .export
        .tool_radius
        .map_or_else(Vec::new, |r| tool_undercut(&cam, r, TOOL_SAMPLES));

    // The smallest base circle that meets the limits.
    let mut smallest = None;
    if let Some((lo, hi)) = lim.base_radius_range {
        smallest =
            cam_limits::smallest_base_radius(&cam, lim.max_pressure_angle, lim.min_radius, lo, hi)
                .map_err(analysis)?;
        let limit = design.base_radius;
        checks.push(Check::new(
            "smallest base circle meeting the limits",
            smallest.unwrap_or(f64::NAN),
            Some(limit),
            smallest.map(|s| limit - s),
            "m",
            None,
            smallest.is_some_and(|s| s <= limit),
            "",
        ));
    }

    let sizing = sizing::checks(design, &cam, &mut checks)?;

    // camlink's own kinematics of the synthesised cam against the program.
    let round = match round_trip_errors(&cam, 1.0, ROUND_TRIP_STEPS) {
        Ok(r) => Some(r),
        Err(e) => {
            checks.push(Check::new(
                "round trip",
                f64::NAN,
                None,
                None,
                "",
                None,
                false,
                e,
            ));
            None
        }
    };

    let deg_ranges = |r: &[(f64, f64)]| -> Vec<(f64, f64)> {
        r.iter()
            .map(|(a, b)| (a.to_degrees(), b.to_degrees()))
            .collect()
    };
    Ok(Report {
        name: design.name.clone(),
        follower: design.follower.to_string(),
        base_radius: design.base_radius,
        boundaries: cam
            .program
            .boundaries()
            .into_iter()
            .map(|b| Boundary {
                theta_deg: b.theta.to_degrees(),
                before: b.before,
                after: b.after,
                continuity: b.continuity,
                jumps: b.jumps,
                text: b.to_string(),
            })
            .collect(),
        factors: cam
            .program
            .factors()
            .into_iter()
            .map(|f| Factor {
                segment: f.segment,
                law: f.law.name().to_string(),
                computed: f.computed,
                textbook: f.textbook,
            })
            .collect(),
        checks,
        concave_deg: deg_ranges(&g.concave),
        undercut_deg: deg_ranges(&g.undercut),
        tool_undercut_deg: deg_ranges(&tool),
        smallest_base_radius: smallest,
        round_trip: round,
        face_travel: travel,
        units: "m".into(),
        sizing,
    })
}

/// The follower train of `[dynamics]`.
pub(crate) fn train(d: &Dynamics) -> Train {
    Train {
        mass: d.mass,
        spring_rate: d.spring_rate,
        preload: d.preload,
        damping: d.damping,
    }
}

/// The round trip of camlink's kinematics of `cam` at ω (rad/s) in
/// `steps` steps: largest relative errors of displacement, velocity and
/// acceleration; or where and why the kinematics stops, in the design's
/// terms (the mechanism's joints are camlink's own).
pub fn round_trip_errors(cam: &Arc<Cam>, omega: f64, steps: usize) -> Result<[f64; 3], String> {
    match round_trip(cam, omega, steps) {
        Ok(r) => Ok([r.displacement, r.velocity, r.acceleration]),
        Err(e) => {
            let why = match e.kind {
                Kind::NotFinite => "the profile's geometry is not finite there",
                Kind::Undercut => "the follower meets an undercut or concave part of the profile",
                _ => "the follower cannot stay on the profile there (a steep, cusped or undercut part)",
            };
            Err(format!(
                "camlink's kinematics of the synthesised cam stops at θ = {}° ({}): {why}",
                num((omega * e.time).to_degrees()),
                e.kind.name()
            ))
        }
    }
}

/// θ ranges (rad) a tool of radius `tool_radius` (m) cannot cut, sampled
/// at `n` angles θ_k = 2πk/n: where the surface is concave tighter than
/// the tool (ρ < 0 and −ρ < r_tool) or its radius of curvature ρ is not
/// finite (a cusp). Each range runs from its first bad sample to the next
/// good one; a range still open at the last sample ends at 2π (and one
/// that goes on past θ = 0 is the range that starts at 0).
pub fn tool_undercut(cam: &Cam, tool_radius: f64, n: usize) -> Vec<(f64, f64)> {
    let step = TAU / n as f64;
    let bad: Vec<bool> = (0..n)
        .map(|k| {
            let rho = cam.contact(k as f64 * step).rho;
            (rho < 0.0 && -rho < tool_radius) || !rho.is_finite()
        })
        .collect();
    bad_ranges(&bad)
}

/// The ranges (rad) of the samples θ_k = 2πk/n flagged in `bad`, as
/// [`tool_undercut`] gives them.
fn bad_ranges(bad: &[bool]) -> Vec<(f64, f64)> {
    let step = TAU / bad.len() as f64;
    let mut out = Vec::new();
    let mut start: Option<f64> = None;
    for (k, &b) in bad.iter().enumerate() {
        let theta = k as f64 * step;
        match start {
            None if b => start = Some(theta),
            Some(s) if !b => {
                out.push((s, theta));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, TAU));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::bad_ranges;
    use std::f64::consts::TAU;

    #[test]
    fn bad_ranges_from_their_first_bad_sample_to_the_next_good_one() {
        let q = TAU / 8.0;
        let (f, t) = (false, true);
        assert_eq!(bad_ranges(&[f, t, t, f, f, f, f, f]), [(q, 3.0 * q)]);
        // From θ = 0, the last sample good: one range, none at 2π.
        assert_eq!(bad_ranges(&[t, t, f, f, f, f, f, f]), [(0.0, 2.0 * q)]);
        // Open at the last sample: it ends at 2π; with θ = 0 bad too, the
        // range across 0 is its two ends.
        assert_eq!(bad_ranges(&[f, f, f, f, f, f, t, t]), [(6.0 * q, TAU)]);
        assert_eq!(
            bad_ranges(&[t, f, f, f, f, f, f, t]),
            [(0.0, q), (7.0 * q, TAU)]
        );
        assert_eq!(bad_ranges(&[t; 8]), [(0.0, TAU)]);
        assert!(bad_ranges(&[f; 8]).is_empty());
    }
}
