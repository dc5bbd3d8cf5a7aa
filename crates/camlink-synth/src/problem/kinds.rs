//! Problem files of path generation (`type = "path"`), dead-centre
//! synthesis (`type = "dead_centre"`) and cognates (`type = "cognates"`);
//! fields in `docs/synthesis.md`.

use std::f64::consts::{FRAC_PI_2, TAU};
use std::path::Path;

use serde::Deserialize;
use serde_json::{json, Value};

use super::{
    checks_json, invalid, links_json, nan_null, requirements, value, values, Outcome, Solution,
    Table,
};
use crate::ball;
use crate::cognates::cognates;
use crate::dead_centre::{self, DeadCentreSpec};
use crate::error::{ErrorKind, SynthError};
use crate::fourbar::{norm, sub, Defect, DefectKind, FourBar, P2};
use crate::model_file::{coupler_along, model_toml, pose_times, ModelSpec};
use crate::path::{checked, fit, fit_from, CouplerLinkage, FitSpec, PathFit, Start, Timing};
use crate::precision::{three_points, ThreePoints};
use crate::properties::properties_json;

/// Most target points.
pub const MOST_TARGETS: usize = 1000;
/// Default starts of the global search: a fit, and precision points.
pub const DEFAULT_STARTS: usize = 96;
pub const DEFAULT_PRECISION_STARTS: usize = 256;
/// Samples of a candidate's coupler curve in its report.
const CURVE_SAMPLES: usize = 360;

/// The `four_bar` table of a cognates problem.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FourBarTable {
    #[serde(rename = "O2")]
    o2: Vec<super::Num>,
    #[serde(rename = "O4")]
    o4: Vec<super::Num>,
    crank: super::Num,
    coupler: super::Num,
    rocker: super::Num,
    point: Option<Vec<super::Num>>,
    branch: Option<i32>,
    crank_angle: Option<super::Num>,
}

fn unit_factor(u: &str) -> Option<f64> {
    match u {
        "m" => Some(1.0),
        "mm" => Some(1e-3),
        "cm" => Some(1e-2),
        "in" => Some(0.0254),
        _ => None,
    }
}

/// The unit in a CSV column header such as `x [mm]`, `x (mm)` or `x_mm`.
fn header_unit(h: &str) -> Option<String> {
    let h = h.trim();
    for (open, close) in [('[', ']'), ('(', ')')] {
        if let (Some(i), Some(j)) = (h.find(open), h.rfind(close)) {
            if j > i {
                return Some(h[i + 1..j].trim().to_string());
            }
        }
    }
    h.rsplit_once('_').map(|(_, u)| u.trim().to_string())
}

/// Reads target points (x, y per line) from the CSV `path`; the first
/// line may be a header naming each column's unit. Returns the points in
/// the file's numbers and the unit the header gives, if any.
fn read_csv(path: &Path, shown: &str) -> Result<(Vec<P2>, Option<String>), SynthError> {
    let f = "synthesis.target_file";
    let text = std::fs::read_to_string(path)
        .map_err(|e| invalid(f, format!("cannot read '{shown}': {e}")))?;
    let mut out = Vec::new();
    let mut unit = None;
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let nums: Vec<Option<f64>> = cells.iter().map(|c| c.parse::<f64>().ok()).collect();
        if out.is_empty() && unit.is_none() && nums.iter().any(Option::is_none) {
            // A header: the columns' units must agree.
            let units: Vec<Option<String>> = cells.iter().map(|c| header_unit(c)).collect();
            if cells.len() != 2 {
                return Err(invalid(
                    f,
                    format!("'{shown}' line {}: expected two columns, x and y", k + 1),
                ));
            }
            match (&units[0], &units[1]) {
                (Some(a), Some(b)) if a != b => {
                    return Err(invalid(
                        f,
                        format!(
                            "'{shown}' line {}: the columns are in mixed units ('{a}' and '{b}'); \
                             give x and y in one unit",
                            k + 1
                        ),
                    ))
                }
                (Some(a), _) | (_, Some(a)) => {
                    if unit_factor(a).is_none() {
                        return Err(invalid(
                            f,
                            format!(
                                "'{shown}' line {}: unknown unit '{a}'; expected m, mm, cm or in",
                                k + 1
                            ),
                        ));
                    }
                    unit = Some(a.clone());
                }
                _ => unit = Some(String::new()),
            }
            continue;
        }
        match nums.as_slice() {
            [Some(x), Some(y)] if x.is_finite() && y.is_finite() => out.push([*x, *y]),
            _ => {
                return Err(invalid(
                    f,
                    format!(
                        "'{shown}' line {}: expected two finite numbers x, y; found '{line}'",
                        k + 1
                    ),
                ))
            }
        }
        if out.len() > MOST_TARGETS {
            return Err(invalid(
                f,
                format!("'{shown}': more than {MOST_TARGETS} points"),
            ));
        }
    }
    Ok((out, unit.filter(|u| !u.is_empty())))
}

/// The targets (m) and the field that names them in errors.
fn targets(t: &Table, source: &str) -> Result<(Vec<P2>, String), SynthError> {
    let unit = t.units.as_deref();
    if let Some(u) = unit {
        if unit_factor(u).is_none() {
            return Err(invalid(
                "synthesis.units",
                format!("'{u}'; expected \"m\", \"mm\", \"cm\" or \"in\""),
            ));
        }
    }
    let (points, file_unit, field) = match (&t.targets, &t.target_file) {
        (Some(list), None) => {
            let mut v = Vec::with_capacity(list.len());
            if list.len() > MOST_TARGETS {
                return Err(invalid(
                    "synthesis.targets",
                    format!("{} points; at most {MOST_TARGETS}", list.len()),
                ));
            }
            for (k, p) in list.iter().enumerate() {
                v.push(values::<2>(p, &format!("synthesis.targets[{k}]"), "x, y")?);
            }
            (v, None, "synthesis.targets".to_string())
        }
        (None, Some(file)) => {
            let base = Path::new(source).parent().unwrap_or(Path::new(""));
            let (v, u) = read_csv(&base.join(file), file)?;
            (v, u, "synthesis.target_file".to_string())
        }
        _ => {
            return Err(invalid(
                "synthesis.targets",
                "give the target points: targets = [[x, y], …] or target_file = \"points.csv\"",
            ))
        }
    };
    let unit = match (unit, file_unit.as_deref()) {
        (Some(a), Some(b)) if a != b => {
            return Err(invalid(
                "synthesis.units",
                format!(
                    "mixed units: units = \"{a}\" but the columns of the target file are in '{b}'"
                ),
            ))
        }
        (Some(a), _) | (None, Some(a)) => a,
        (None, None) => "m",
    };
    let k = unit_factor(unit).unwrap_or(1.0);
    Ok((points.iter().map(|p| [p[0] * k, p[1] * k]).collect(), field))
}

/// Consecutive targets that coincide, or a closed curve on a line.
fn check_targets(p: &[P2], closed: bool, field: &str) -> Result<f64, SynthError> {
    let size = p
        .iter()
        .flat_map(|a| p.iter().map(move |b| norm(sub(*a, *b))))
        .fold(0.0, f64::max);
    if size == 0.0 {
        return Err(SynthError::new(
            ErrorKind::Coincident,
            field,
            "all the target points coincide",
        ));
    }
    for k in 1..p.len() {
        if norm(sub(p[k], p[k - 1])) <= 1e-9 * size {
            return Err(SynthError::new(
                ErrorKind::Coincident,
                field,
                format!("points {} and {} coincide", k, k + 1),
            ));
        }
    }
    if closed {
        if norm(sub(p[p.len() - 1], p[0])) <= 1e-9 * size {
            return Err(SynthError::new(
                ErrorKind::Coincident,
                field,
                "the last point repeats the first; leave it out (closure = \"closed\" joins them)",
            ));
        }
        // The area the points span, from the point farthest from the first.
        let far = p
            .iter()
            .copied()
            .max_by(|x, y| norm(sub(*x, p[0])).total_cmp(&norm(sub(*y, p[0]))))
            .unwrap_or(p[0]);
        let extent = p
            .iter()
            .map(|q| crate::fourbar::cross(sub(far, p[0]), sub(*q, p[0])).abs())
            .fold(0.0, f64::max);
        if extent <= 1e-9 * size * size {
            return Err(SynthError::new(
                ErrorKind::Collinear,
                field,
                "the points of a closed curve lie on one line: a closed coupler curve needs \
                 points that enclose an area",
            ));
        }
    }
    Ok(size)
}

fn choice(
    v: Option<&str>,
    field: &str,
    options: &[&str],
    default: &str,
) -> Result<String, SynthError> {
    let v = v.unwrap_or(default);
    if options.contains(&v) {
        Ok(v.to_string())
    } else {
        Err(invalid(
            field,
            format!(
                "'{v}'; expected {}",
                options
                    .iter()
                    .map(|o| format!("\"{o}\""))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ))
    }
}

/// A path problem read from its table: the fit's spec, and the closed
/// form's when the coupler's and the rocker's rotations are given.
pub(super) struct PathPlan {
    pub(super) spec: FitSpec,
    method: String,
    closed_form: Option<ThreePoints>,
    /// The field naming the targets in errors, and their size (m).
    field: String,
    size: f64,
}

impl PathPlan {
    /// Whether the plan searches (its starts can be spread over workers).
    pub(super) fn searches(&self) -> bool {
        self.closed_form.is_none()
    }
}

/// Two rotations (rad) of a three-point closed form.
fn two_rotations(t: &Option<Vec<super::Num>>, f: &str) -> Result<[f64; 2], SynthError> {
    match t {
        Some(v) => values::<2>(v, f, "the rotations from point 1 to points 2 and 3 (rad)"),
        None => Err(invalid(
            f,
            "missing; the closed form of three precision points takes coupler_rotations and \
             rocker_rotations, the free choices (rad)",
        )),
    }
}

pub(super) fn path_plan(t: &Table, source: &str) -> Result<PathPlan, SynthError> {
    let method = choice(
        t.method.as_deref(),
        "synthesis.method",
        &["fit", "precision_points"],
        "fit",
    )?;
    let precision = method == "precision_points";
    let (points, field) = targets(t, source)?;
    let n = points.len();
    if precision && !(2..=5).contains(&n) {
        return Err(invalid(
            &field,
            format!("{n} points; precision points are 2 to 5 (use method = \"fit\" for more)"),
        ));
    }
    if !precision && n < 4 {
        return Err(invalid(
            &field,
            format!("{n} points; a fit needs at least 4"),
        ));
    }
    let closure = choice(
        t.closure.as_deref(),
        "synthesis.closure",
        &["open", "closed"],
        "open",
    )?;
    let closed = closure == "closed";
    if precision && closed {
        return Err(invalid(
            "synthesis.closure",
            "precision points are an open path",
        ));
    }
    check_targets(&points, closed, &field)?;
    let default_timing = if precision { "prescribed" } else { "free" };
    let timing_name = choice(
        t.timing.as_deref(),
        "synthesis.timing",
        &["free", "uniform", "prescribed"],
        default_timing,
    )?;
    if precision && timing_name != "prescribed" {
        return Err(invalid(
            "synthesis.timing",
            "precision points take prescribed crank rotations (crank_rotations)",
        ));
    }
    let timing = match timing_name.as_str() {
        "free" => Timing::Free,
        "uniform" => Timing::Uniform,
        _ => {
            let f = "synthesis.crank_rotations";
            let list = t.crank_rotations.as_ref().ok_or_else(|| {
                invalid(
                    f,
                    format!(
                        "missing; give the crank's rotation from point 1 to each of points 2 to {n} (rad)"
                    ),
                )
            })?;
            if list.len() != n - 1 {
                return Err(invalid(
                    f,
                    format!(
                        "{} rotations given; expected {} (points 2 to {n})",
                        list.len(),
                        n - 1
                    ),
                ));
            }
            let mut beta = vec![0.0];
            for (k, v) in list.iter().enumerate() {
                let b = value(v, &format!("{f}[{k}]"))?;
                if b == 0.0 || (k > 0 && (b - beta[k]).abs() == 0.0) {
                    return Err(SynthError::new(
                        ErrorKind::Coincident,
                        format!("{f}[{k}]"),
                        "two points at the same crank angle",
                    ));
                }
                beta.push(b);
            }
            let s = beta[1].signum();
            if beta.windows(2).any(|w| s * (w[1] - w[0]) <= 0.0) || s * beta[n - 1] >= TAU {
                return Err(invalid(
                    f,
                    "the rotations must grow in one sense within one turn (|β| < 2π)",
                ));
            }
            Timing::Prescribed(beta)
        }
    };
    if t.crank_rotations.is_some() && !matches!(timing, Timing::Prescribed(_)) {
        return Err(invalid(
            "synthesis.crank_rotations",
            "a field of timing = \"prescribed\"",
        ));
    }
    let order = choice(
        t.order.as_deref(),
        "synthesis.order",
        &["ordered", "any"],
        "ordered",
    )?;
    let starts = t.starts.unwrap_or(if precision {
        DEFAULT_PRECISION_STARTS
    } else {
        DEFAULT_STARTS
    });
    if !(1..=100_000).contains(&starts) {
        return Err(invalid(
            "synthesis.starts",
            format!("{starts}; expected 1 to 100000"),
        ));
    }
    let keep = t.keep.unwrap_or(3);
    if !(1..=100).contains(&keep) {
        return Err(invalid(
            "synthesis.keep",
            format!("{keep}; expected 1 to 100"),
        ));
    }
    let closed_form = match (&t.coupler_rotations, &t.rocker_rotations, &timing) {
        (None, None, _) => None,
        (_, _, Timing::Prescribed(beta)) if precision && n == 3 => {
            for (given, f) in [(t.starts.is_some(), "starts"), (t.keep.is_some(), "keep")] {
                if given {
                    return Err(invalid(
                        &format!("synthesis.{f}"),
                        "the closed form of three precision points has one solution; a field of \
                         the search",
                    ));
                }
            }
            Some(ThreePoints {
                points: [points[0], points[1], points[2]],
                crank: [beta[1], beta[2]],
                coupler: two_rotations(&t.coupler_rotations, "synthesis.coupler_rotations")?,
                rocker: two_rotations(&t.rocker_rotations, "synthesis.rocker_rotations")?,
            })
        }
        (c, _, _) => {
            return Err(invalid(
                if c.is_some() {
                    "synthesis.coupler_rotations"
                } else {
                    "synthesis.rocker_rotations"
                },
                format!(
                    "a field of the closed form of three precision points (method = \
                     \"precision_points\" with three targets); this problem has {n} points{}",
                    if precision { "" } else { " to fit" }
                ),
            ))
        }
    };
    let spec = FitSpec {
        targets: points.clone(),
        timing,
        closed,
        ordered: order == "ordered",
        starts,
        keep,
        requirements: requirements(t)?,
    };
    let size = check_targets(&points, false, &field)?;
    Ok(PathPlan {
        spec,
        method,
        closed_form,
        field,
        size,
    })
}

/// The solutions of `plan`: the closed form's, or the best of the
/// search's starts (`given` when they ran elsewhere, else all of them
/// here).
pub(super) fn path_outcome(
    plan: &PathPlan,
    name: &str,
    given: Option<&[Start]>,
) -> Result<Outcome, SynthError> {
    let (spec, field, size) = (&plan.spec, plan.field.as_str(), plan.size);
    let (method, precision, starts) = (
        plan.method.as_str(),
        plan.method == "precision_points",
        spec.starts,
    );
    if let Some(tp) = &plan.closed_form {
        let fields = [
            field,
            "synthesis.crank_rotations",
            "synthesis.coupler_rotations",
            "synthesis.rocker_rotations",
        ];
        let (mechanism, phi) = three_points(tp, fields)?;
        let s = if tp.crank[0] > 0.0 { 1.0 } else { -1.0 };
        let Some(mut found) = checked(spec, mechanism, &phi, s) else {
            return Err(SynthError::new(
                ErrorKind::NoSolution,
                "synthesis.rocker_rotations",
                "the four-bar of these rotations does not assemble on one branch at the three \
                 points; choose other rotations",
            ));
        };
        // The exact solution passes every point; on the branch of point 1
        // it may not.
        if found.max > 1e-9 * size {
            found.checks.defects.push(Defect {
                kind: DefectKind::Branch,
                message: format!(
                    "on the assembly branch of point 1 the coupler point misses a point by {:.3e} \
                     m: the four-bar passes it only on the other branch",
                    found.max
                ),
            });
        }
        let mut solution = path_solution(&found, spec, name, "precision_points_closed_form", 1, 1);
        if let Value::Object(r) = &mut solution.report {
            r.remove("search");
            r.insert(
                "rotations".into(),
                json!({"crank": tp.crank, "coupler": tp.coupler, "rocker": tp.rocker}),
            );
        }
        return Ok(Outcome {
            kind: "path".into(),
            solutions: vec![solution],
        });
    }
    let (mut found, converged) = match given {
        Some(st) => fit_from(spec, st),
        None => fit(spec),
    };
    if precision {
        let best = found.first().map(|c| c.max);
        found.retain(|c| c.max <= 1e-10 * size.max(1.0));
        if found.is_empty() {
            return Err(SynthError::new(
                ErrorKind::NoSolution,
                field,
                format!(
                    "no four-bar through the points with these crank rotations was found from \
                     {starts} starts{}; try other rotations or more starts",
                    best.map_or(String::new(), |b| format!(
                        " (the closest misses by {b:.3e} m)"
                    ))
                ),
            ));
        }
    }
    if found.is_empty() {
        return Err(SynthError::new(
            ErrorKind::NoSolution,
            field,
            format!("no start of {starts} converged to a linkage that assembles at every point"),
        ));
    }
    let solutions = found
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let label = if found.len() == 1 {
                name.to_string()
            } else {
                format!("{name}_{}", k + 1)
            };
            path_solution(c, spec, &label, method, k + 1, converged)
        })
        .collect();
    Ok(Outcome {
        kind: "path".into(),
        solutions,
    })
}

/// P over the crank's turn (or over its reach) for the report's picture.
fn curve(m: &CouplerLinkage) -> Vec<Value> {
    (0..=CURVE_SAMPLES)
        .map(|k| {
            let phi = TAU * k as f64 / CURVE_SAMPLES as f64;
            match m.trace(phi) {
                Some((_, _, p)) => json!(p),
                None => Value::Null,
            }
        })
        .collect()
}

fn path_solution(
    c: &PathFit,
    spec: &FitSpec,
    name: &str,
    method: &str,
    rank: usize,
    converged: usize,
) -> Solution {
    let m = &c.mechanism;
    let l = &m.linkage;
    let first = c.visit[0];
    let (a1, b1, _) = m
        .trace(c.crank_angles[first])
        .unwrap_or(([0.0; 2], [0.0; 2], [0.0; 2]));
    let mut angles: Vec<f64> = c.visit.iter().map(|&j| c.crank_angles[j]).collect();
    let s = if c.checks.turning == crate::fourbar::Turning::Ccw {
        1.0
    } else {
        -1.0
    };
    if spec.closed {
        angles.push(angles[0] + s * TAU);
    }
    let times = pose_times(&angles);
    let mut point_times = vec![0.0; c.visit.len()];
    for (k, &j) in c.visit.iter().enumerate() {
        point_times[j] = times[k];
    }
    let header = vec![
        format!("{name}: a four-bar whose coupler point P follows target points, synthesised by camlink ({method}, rank {rank})."),
        format!(
            "RMS distance to the {} targets {:.6e} m, largest {:.6e} m.",
            spec.targets.len(),
            c.rms,
            c.max
        ),
        "The coupler's frame sits at the crank pin A with x towards the rocker pin B.".into(),
    ];
    let rocker_start = (b1[1] - l.o4[1]).atan2(b1[0] - l.o4[0])
        - if l.rocker < 0.0 {
            std::f64::consts::PI
        } else {
            0.0
        };
    let model = model_toml(&ModelSpec {
        name,
        header,
        linkage: l,
        coupler_points: [[0.0, 0.0], [l.coupler, 0.0], m.point],
        coupler_start: coupler_along(a1, b1),
        crank_angles: &angles,
        rocker_start,
        stop: if spec.closed {
            "the target points (then a full turn)"
        } else {
            "the target points"
        },
    });
    let errors: Vec<f64> = spec
        .targets
        .iter()
        .zip(&c.crank_angles)
        .map(|(t, &phi)| m.trace(phi).map_or(f64::NAN, |(_, _, p)| norm(sub(p, *t))))
        .collect();
    let report = json!({
        "name": name,
        "method": match method { "fit" => "path_fit", m => m },
        "rank": rank,
        "links": links_json(l),
        "signed": { "crank": l.crank, "rocker": l.rocker },
        "coupler_point": m.point,
        "branch": m.sigma,
        "timing": spec.timing.name(),
        "closure": if spec.closed { "closed" } else { "open" },
        "targets": spec.targets,
        "visit": c.visit.iter().map(|j| j + 1).collect::<Vec<_>>(),
        "crank_angles": c.crank_angles,
        "point_times": point_times,
        "error": { "rms": c.rms, "max": c.max, "points": errors.iter().map(|e| nan_null(*e)).collect::<Vec<_>>() },
        "search": { "starts": spec.starts, "converged": converged },
        "curve": curve(m),
        "properties": properties_json(l),
        "checks": checks_json(&c.checks),
    });
    Solution {
        name: name.to_string(),
        model,
        report,
    }
}

pub(super) fn solve_dead_centre(t: &Table, name: &str) -> Result<Outcome, SynthError> {
    let need = |v: &Option<super::Num>, f: &str, what: &str| -> Result<f64, SynthError> {
        let field = format!("synthesis.{f}");
        match v {
            Some(n) => value(n, &field),
            None => Err(invalid(&field, format!("missing; give {what}"))),
        }
    };
    let c = need(
        &t.rocker_length,
        "rocker_length",
        "the rocker's length c (m)",
    )?;
    let swing = need(&t.swing, "swing", "the rocker's swing ψ (rad)")?;
    let q = need(
        &t.time_ratio,
        "time_ratio",
        "the time ratio Q = slow stroke / fast stroke",
    )?;
    let pivot = match &t.rocker_pivot {
        Some(v) => values::<2>(v, "synthesis.rocker_pivot", "x, y (m)")?,
        None => [0.0, 0.0],
    };
    let start = match &t.rocker_start {
        Some(n) => value(n, "synthesis.rocker_start")?,
        None => FRAC_PI_2 - swing / 2.0,
    };
    let ground = match &t.ground {
        Some(n) => Some(value(n, "synthesis.ground")?),
        None => None,
    };
    let spec = DeadCentreSpec {
        rocker_pivot: pivot,
        rocker: c,
        swing,
        rocker_start: start,
        time_ratio: q,
        ground,
        requirements: requirements(t)?,
    };
    let found = dead_centre::synthesise(
        &spec,
        [
            "synthesis.rocker_length",
            "synthesis.swing",
            "synthesis.time_ratio",
            "synthesis.ground",
        ],
    )?;
    let solutions = found
        .iter()
        .enumerate()
        .map(|(k, d)| {
            let label = if found.len() == 1 { name.to_string() } else { format!("{name}_{}", k + 1) };
            let l = &d.linkage;
            let s = if d.turning == crate::fourbar::Turning::Ccw { 1.0 } else { -1.0 };
            let angles = [d.crank_angles[0], d.crank_angles[1], d.crank_angles[0] + s * TAU];
            let a1 = l.crank_pin(angles[0]);
            let b1 = [pivot[0] + c * start.cos(), pivot[1] + c * start.sin()];
            let header = vec![
                format!("{label}: a crank-rocker from dead-centre synthesis by camlink."),
                format!(
                    "The rocker swings {swing} rad between {start} and {} rad with a time ratio of {q}:",
                    start + swing
                ),
                "the crank turns through the slow stroke first, then the fast one.".into(),
            ];
            let model = model_toml(&ModelSpec {
                name: &label,
                header,
                linkage: l,
                coupler_points: [[0.0, 0.0], [l.coupler, 0.0], [0.5 * l.coupler, 0.0]],
                coupler_start: coupler_along(a1, b1),
                crank_angles: &angles,
                rocker_start: start,
                stop: "the rocker's two extremes and the end of the turn",
            });
            let times = pose_times(&angles);
            let report = json!({
                "name": label,
                "method": "dead_centre",
                "links": links_json(l),
                "swing": swing,
                "time_ratio": q,
                "alpha": std::f64::consts::PI * (q - 1.0) / (q + 1.0),
                "strokes": d.strokes,
                "extremes": {
                    "crank_angles": d.crank_angles,
                    "rocker_angles": [start, start + swing],
                    "times": [times[0], times[1]],
                },
                "branch": d.sigma,
                "properties": properties_json(l),
                "checks": checks_json(&d.checks),
            });
            Solution {
                name: label,
                model,
                report,
            }
        })
        .collect();
    Ok(Outcome {
        kind: "dead_centre".into(),
        solutions,
    })
}

/// The linkage of a `four_bar` table, its branch σ and crank angle (rad);
/// `point` is P of the table, `None` if it gives none.
fn four_bar(t: &Table) -> Result<(FourBar, f64, f64, Option<P2>), SynthError> {
    let f = "synthesis.four_bar";
    let Some(fb) = &t.four_bar else {
        return Err(invalid(
            f,
            "missing; give four_bar = { O2 = [x, y], O4 = [x, y], crank = a, coupler = b, rocker = c, point = [p, q] }",
        ));
    };
    let o2 = values::<2>(&fb.o2, &format!("{f}.O2"), "x, y (m)")?;
    let o4 = values::<2>(&fb.o4, &format!("{f}.O4"), "x, y (m)")?;
    let len = |v: &super::Num, k: &str| -> Result<f64, SynthError> {
        let field = format!("{f}.{k}");
        let x = value(v, &field)?;
        if x <= 0.0 {
            return Err(invalid(
                &field,
                format!("{x} m; a link must be longer than 0"),
            ));
        }
        Ok(x)
    };
    let (a, b, c) = (
        len(&fb.crank, "crank")?,
        len(&fb.coupler, "coupler")?,
        len(&fb.rocker, "rocker")?,
    );
    let point = match &fb.point {
        Some(p) => Some(values::<2>(
            p,
            &format!("{f}.point"),
            "p, q: P in the coupler frame, origin A, x towards B (m)",
        )?),
        None => None,
    };
    let sigma = match fb.branch {
        None | Some(1) => 1.0,
        Some(-1) => -1.0,
        Some(o) => {
            return Err(invalid(
                &format!("{f}.branch"),
                format!("{o}; expected 1 or -1"),
            ))
        }
    };
    let phi0 = match &fb.crank_angle {
        Some(n) => value(n, &format!("{f}.crank_angle"))?,
        None => 0.0,
    };
    if norm(sub(o4, o2)) == 0.0 {
        return Err(SynthError::new(
            ErrorKind::Coincident,
            format!("{f}.O4"),
            "O2 and O4 coincide",
        ));
    }
    let linkage = FourBar {
        o2,
        o4,
        crank: a,
        coupler: b,
        rocker: c,
    };
    Ok((linkage, sigma, phi0, point))
}

/// Refuses a linkage whose crank does not turn fully: its model could not
/// be driven round.
fn full_turn(l: &FourBar) -> Result<(), SynthError> {
    if l.grashof().crank_turns_fully() {
        return Ok(());
    }
    Err(SynthError::new(
        ErrorKind::NoSolution,
        "synthesis.four_bar",
        format!(
            "a {} linkage: its crank does not turn fully, so its models cannot trace the \
             whole coupler curve; give a crank-rocker or a double-crank",
            l.grashof().name()
        ),
    ))
}

pub(super) fn solve_cognates(t: &Table, name: &str) -> Result<Outcome, SynthError> {
    let f = "synthesis.four_bar";
    let (linkage, sigma, phi0, point) = four_bar(t)?;
    let Some(point) = point else {
        return Err(invalid(
            &format!("{f}.point"),
            "missing; give P in the coupler frame, point = [p, q] (origin A, x towards B, m)",
        ));
    };
    let given = CouplerLinkage {
        linkage,
        point,
        sigma,
    };
    full_turn(&given.linkage)?;
    let Some(cogs) = cognates(&given, phi0) else {
        return Err(invalid(
            &format!("{f}.point"),
            "the coupler point lies on the crank pin A or the rocker pin B: its cognates \
             degenerate; choose a point off the pins",
        ));
    };
    let (ga, gb, _) = given.trace(phi0).expect("assembles: checked by cognates");
    // Every model of the set traces the given curve, driven as written.
    let traced = curve(&given);
    let mut solutions = vec![cognate_solution(
        &given,
        &traced,
        &format!("{name}_given"),
        "the given four-bar",
        (ga, gb, phi0),
        None,
    )];
    for (k, cg) in cogs.iter().enumerate() {
        let theta = match cg.driven {
            "coupler" => coupler_along(cg.a, cg.b).theta,
            _ => (cg.b[1] - cg.mechanism.linkage.o4[1]).atan2(cg.b[0] - cg.mechanism.linkage.o4[0]),
        };
        solutions.push(cognate_solution(
            &cg.mechanism,
            &traced,
            &format!("{name}_cognate{}", k + 1),
            &format!("cognate {} of the given four-bar", k + 1),
            (cg.a, cg.b, cg.crank_angle),
            Some((cg.driven, theta, cg.offset)),
        ));
    }
    Ok(Outcome {
        kind: "cognates".into(),
        solutions,
    })
}

/// The model and report of one linkage of a cognate set; `traced` is the
/// given linkage's coupler curve, which each model traces. `drive`: the
/// body driven, its angle at t = 0 and its offset from the given crank;
/// `None`: the crank through joint O2.
fn cognate_solution(
    m: &CouplerLinkage,
    traced: &[Value],
    name: &str,
    what: &str,
    (a, b, phi0): (P2, P2, f64),
    drive: Option<(&str, f64, f64)>,
) -> Solution {
    let l = &m.linkage;
    let header = vec![
        format!("{name}: {what}, a Roberts–Chebyshev cognate set written by camlink."),
        "Its coupler point P traces the given four-bar's coupler curve; driven as below,".into(),
        "at the same instants as the given four-bar's P.".into(),
    ];
    let angles = [phi0, phi0 + TAU];
    let rocker_start = (b[1] - l.o4[1]).atan2(b[0] - l.o4[0]);
    let mut model = model_toml(&ModelSpec {
        name,
        header,
        linkage: l,
        coupler_points: [[0.0, 0.0], [l.coupler, 0.0], m.point],
        coupler_start: coupler_along(a, b),
        crank_angles: &angles,
        rocker_start,
        stop: "the start and the end of the turn",
    });
    if let Some((body, theta, _)) = drive {
        let crank_driver = "[[drivers]]\nname = \"motor\"\ntype = \"revolute_angle\"\njoint = \"O2\"\nf = \"theta1 + w*t\"\n";
        let own = format!(
            "# The {body} turns with the given four-bar's crank: its angle is driven.\n\
             [[drivers]]\nname = \"motor\"\ntype = \"absolute_phi\"\nbody = \"{body}\"\nf = \"{theta:?} + w*t\"\n"
        );
        model = model.replace(crank_driver, &own).replace(
            "# The crank is driven at constant speed from t = 0 to t = 1 s;",
            &format!("# The {body} is driven at constant speed from t = 0 to t = 1 s;"),
        );
    }
    let checks = json!({
        "grashof": l.grashof().name(),
        "turning": "ccw",
        "crank_angles": angles,
        "branches": [m.sigma],
        "transmission": properties_json(l).get("transmission").cloned().unwrap_or(json!({"min": null, "max": null})),
        "defects": [],
    });
    let report = json!({
        "name": name,
        "method": "cognates",
        "links": links_json(l),
        "coupler_point": m.point,
        "branch": m.sigma,
        "driven": drive.map_or("crank", |d| d.0),
        "offset": drive.map_or(0.0, |d| d.2),
        "curve": traced,
        "properties": properties_json(l),
        "checks": checks,
    });
    Solution {
        name: name.to_string(),
        model,
        report,
    }
}

/// Ball's point of a four-bar at one crank angle (`type = "ball_point"`):
/// the model of the four-bar with its coupler point there, driven over a
/// turn from that angle, and the coupler's instantaneous geometry.
pub(super) fn solve_ball(t: &Table, name: &str) -> Result<Outcome, SynthError> {
    let f = "synthesis.four_bar";
    let (linkage, sigma, phi0, point) = four_bar(t)?;
    if point.is_some() {
        return Err(invalid(
            &format!("{f}.point"),
            "Ball's point is the coupler point this problem finds; leave point out",
        ));
    }
    full_turn(&linkage)?;
    let Some(g) = ball::instant(&linkage, phi0, sigma) else {
        return Err(SynthError::new(
            ErrorKind::NoSolution,
            format!("{f}.crank_angle"),
            "at this crank angle the linkage does not assemble on this branch, is at a toggle \
             (coupler and rocker in line) or its coupler does not turn; choose another angle",
        ));
    };
    let (Some(ball), Some(local)) = (g.ball, g.ball_local) else {
        return Err(SynthError::new(
            ErrorKind::NoSolution,
            format!("{f}.crank_angle"),
            "Ball's point is at infinity at this crank angle (the cubic of stationary \
             curvature meets the inflection circle only at the pole); choose another angle",
        ));
    };
    let m = CouplerLinkage {
        linkage,
        point: local,
        sigma,
    };
    let angles = [phi0, phi0 + TAU];
    let header = vec![
        format!("{name}: a four-bar with its coupler point P at Ball's point, written by camlink."),
        format!(
            "At crank angle {phi0} rad (t = 0) P's path has zero curvature and zero rate of \
             curvature:"
        ),
        "it runs along its tangent there, an approximate straight line.".into(),
    ];
    let model = model_toml(&ModelSpec {
        name,
        header,
        linkage: &linkage,
        coupler_points: [[0.0, 0.0], [linkage.coupler, 0.0], local],
        coupler_start: coupler_along(g.a, g.b),
        crank_angles: &angles,
        rocker_start: (g.b[1] - linkage.o4[1]).atan2(g.b[0] - linkage.o4[0]),
        stop: "the start and the end of the turn",
    });
    let props = properties_json(&linkage);
    let report = json!({
        "name": name,
        "method": "ball_point",
        "links": links_json(&linkage),
        "coupler_point": local,
        "branch": sigma,
        "instant": {
            "crank_angle": phi0,
            "A": g.a,
            "B": g.b,
            "pole": g.pole,
            "inflection_circle": g.inflection.map(|(c, r)| json!({"centre": c, "radius": r})),
            "ball": ball,
            "ball_local": local,
            "coupler_rates": g.theta,
        },
        "curve": curve(&m),
        "properties": props,
        "checks": {
            "grashof": linkage.grashof().name(),
            "turning": "ccw",
            "crank_angles": angles,
            "branches": [sigma],
            "transmission": props.get("transmission").cloned().unwrap_or(json!({"min": null, "max": null})),
            "defects": [],
        },
    });
    Ok(Outcome {
        kind: "ball_point".into(),
        solutions: vec![Solution {
            name: name.to_string(),
            model,
            report,
        }],
    })
}
