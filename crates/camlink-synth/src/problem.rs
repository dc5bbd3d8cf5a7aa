//! Synthesis problem files: one `[synthesis]` table in TOML, read with
//! errors that name the file, the line and the field.
//!
//! ```toml
//! [synthesis]
//! type = "motion"                 # rigid-body guidance through three poses
//! poses = [[0, 0, 0], [0.1, 0.05, "deg(20)"], [0.18, 0.02, "deg(40)"]]   # x, y (m), θ (rad)
//! crank = { moving = [-0.05, -0.02] }     # A in the coupler frame (m), or fixed = [x, y]
//! rocker = { moving = [0.08, 0.01] }      # B
//! ```
//!
//! ```toml
//! [synthesis]
//! type = "function"
//! function = "log(x)"             # y = f(x)
//! x = [1, 2]
//! input = ["deg(30)", "deg(120)"] # φ at x = 1 and x = 2 (rad)
//! output = ["deg(60)", "deg(120)"]
//! ground = 0.1                    # d (m)
//! ```
//!
//! Every field is documented in `docs/synthesis.md`.

use camlink_model::text::{field_path, line_col};
use std::collections::HashMap;
use std::path::Path;

use camlink_expr::Expr;
use camlink_model::file::Num;
use camlink_model::LoadError;
use serde::Deserialize;
use serde_json::{json, Value};

use crate::error::SynthError;
use crate::fourbar::{Checks, FourBar, Requirements, Turning};
use crate::function::{self, chebyshev, Fit, FunctionSolution, FunctionSpec};
use crate::model_file::{coupler_along, model_toml, pose_times, ModelSpec};
use crate::motion::{self, coupler_pose, MotionSolution, Pivot, Pose};
use crate::path::{fit_starts, Start};

// Two-position, Burmester and slider-crank problems.
mod guidance;
// Path generation, dead-centre synthesis and cognates.
mod kinds;

/// Largest problem file read (bytes).
pub const MAX_FILE_SIZE: u64 = 1024 * 1024;
/// Default number of least-squares points.
pub const DEFAULT_FIT_POINTS: usize = 20;
/// Default number of samples of the structural error.
pub const DEFAULT_SAMPLES: usize = 201;
/// Most points and samples accepted.
pub const MOST_POINTS: usize = 100_000;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ProblemFile {
    synthesis: Table,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Table {
    #[serde(rename = "type")]
    kind: String,
    name: Option<String>,
    poses: Option<Vec<Vec<Num>>>,
    crank: Option<PivotTable>,
    rocker: Option<PivotTable>,
    turning: Option<String>,
    function: Option<String>,
    x: Option<Vec<Num>>,
    input: Option<Vec<Num>>,
    output: Option<Vec<Num>>,
    ground: Option<Num>,
    method: Option<String>,
    points: Option<Vec<Num>>,
    count: Option<usize>,
    samples: Option<usize>,
    min_transmission: Option<Num>,
    full_turn: Option<bool>,
    // Two-position, Burmester and slider-crank problems (problem/guidance.rs).
    along: Option<Vec<Num>>,
    keep: Option<usize>,
    dyads: Option<usize>,
    curve_samples: Option<usize>,
    region: Option<Vec<Num>>,
    max_link_ratio: Option<Num>,
    slider: Option<guidance::SliderTable>,
    // --- Path generation, dead-centre synthesis, cognates (problem/kinds.rs) ---
    targets: Option<Vec<Vec<Num>>>,
    target_file: Option<String>,
    units: Option<String>,
    timing: Option<String>,
    crank_rotations: Option<Vec<Num>>,
    coupler_rotations: Option<Vec<Num>>,
    rocker_rotations: Option<Vec<Num>>,
    closure: Option<String>,
    order: Option<String>,
    starts: Option<usize>,
    rocker_pivot: Option<Vec<Num>>,
    rocker_length: Option<Num>,
    rocker_start: Option<Num>,
    swing: Option<Num>,
    time_ratio: Option<Num>,
    four_bar: Option<kinds::FourBarTable>,
    // --- end of path generation, dead-centre synthesis, cognates ---
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PivotTable {
    moving: Option<Vec<Num>>,
    fixed: Option<Vec<Num>>,
}

/// One synthesised mechanism: its name, its model file (TOML) and its
/// report (JSON; fields in `docs/synthesis.md`).
#[derive(Clone, Debug)]
pub struct Solution {
    pub name: String,
    pub model: String,
    pub report: Value,
}

/// What a problem file gave: its kind (`motion`, `function`) and the
/// solutions.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub kind: String,
    pub solutions: Vec<Solution>,
}

/// Reads and solves the problem file at `path`.
pub fn solve_path(path: &Path) -> Result<Outcome, LoadError> {
    let text = read_file(path)?;
    let stem = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("synthesis");
    solve_str(&text, &path.display().to_string(), stem)
}

/// The text of the problem file at `path`: at most [`MAX_FILE_SIZE`]
/// bytes of UTF-8.
pub fn read_file(path: &Path) -> Result<String, LoadError> {
    let err = |m: String| LoadError {
        source: path.display().to_string(),
        line: None,
        column: None,
        field: None,
        message: m,
    };
    let meta = std::fs::metadata(path).map_err(|e| err(format!("cannot read: {e}")))?;
    if meta.len() > MAX_FILE_SIZE {
        return Err(err(format!(
            "file is too large ({} bytes; the limit is {MAX_FILE_SIZE} bytes)",
            meta.len()
        )));
    }
    let bytes = std::fs::read(path).map_err(|e| err(format!("cannot read: {e}")))?;
    String::from_utf8(bytes).map_err(|_| err("not UTF-8 text; save the file as UTF-8".into()))
}

/// Solves the problem in `text`; `source` names it in errors and `stem`
/// names the solutions unless the file gives `name`.
pub fn solve_str(text: &str, source: &str, stem: &str) -> Result<Outcome, LoadError> {
    solve_with(text, source, stem, None)
}

/// Solves the path problem in `text` from the refined starts of its
/// search, run elsewhere by [`path_starts`] (all of them, joined in any
/// order): the same solutions as [`solve_str`]. A problem without a search
/// (another type, or the closed form) ignores `starts`.
pub fn solve_str_from_starts(
    text: &str,
    source: &str,
    stem: &str,
    starts: &[Start],
) -> Result<Outcome, LoadError> {
    solve_with(text, source, stem, Some(starts))
}

/// Runs starts `range` of the search of the path problem in `text` (see
/// [`crate::path::fit_starts`]); the number of starts the problem asks for
/// besides. Another type of problem, or one without a search, gives no
/// starts and 0.
pub fn path_starts(
    text: &str,
    source: &str,
    stem: &str,
    range: std::ops::Range<usize>,
) -> Result<(Vec<Start>, usize), LoadError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let (t, _) = read(text, source, stem)?;
    if t.kind != "path" {
        return Ok((Vec::new(), 0));
    }
    let plan = kinds::path_plan(&t, source).map_err(|e| load_error(text, source, e))?;
    if !plan.searches() {
        return Ok((Vec::new(), 0));
    }
    Ok((fit_starts(&plan.spec, range), plan.spec.starts))
}

/// The error `e` located in `text`: its field's line and column.
fn load_error(text: &str, source: &str, e: SynthError) -> LoadError {
    located(text, source, e.field, e.message)
}

fn located(text: &str, source: &str, field: Option<String>, message: String) -> LoadError {
    let pos = field
        .as_deref()
        .and_then(|f| camlink_model::toml_position(text, f));
    LoadError {
        source: source.to_string(),
        line: pos.map(|p| p.0),
        column: pos.map(|p| p.1),
        field,
        message,
    }
}

/// The `[synthesis]` table of `text`, its fields checked against its
/// type, and the solutions' name.
fn read(text: &str, source: &str, stem: &str) -> Result<(Table, String), LoadError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let de = toml::Deserializer::parse(text).map_err(|e| {
        let mut le = located(
            text,
            source,
            None,
            format!("syntax error: {}", e.message().trim()),
        );
        if let Some(span) = e.span() {
            let (l, c) = line_col(text, span.start);
            (le.line, le.column) = (Some(l), Some(c));
        }
        le
    })?;
    let file: ProblemFile = serde_path_to_error::deserialize(de).map_err(|e| {
        let path = field_path(e.path());
        let span = e.inner().span();
        let mut le = located(
            text,
            source,
            Some(path).filter(|p| !p.is_empty()),
            e.inner().message().trim().to_string(),
        );
        if let Some(span) = span {
            let (l, c) = line_col(text, span.start);
            (le.line, le.column) = (Some(l), Some(c));
        }
        le
    })?;
    let t = file.synthesis;
    let name = match &t.name {
        Some(n) => {
            check_name(n).map_err(|m| located(text, source, Some("synthesis.name".into()), m))?
        }
        None => check_name(stem).map_err(|m| {
            located(
                text,
                source,
                None,
                format!("the file's name does not make a model name ({m}); give [synthesis] name"),
            )
        })?,
    };
    check_fields(&t).map_err(|e| load_error(text, source, e))?;
    Ok((t, name))
}

fn solve_with(
    text: &str,
    source: &str,
    stem: &str,
    starts: Option<&[Start]>,
) -> Result<Outcome, LoadError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let (t, name) = read(text, source, stem)?;
    let to_load = |e: SynthError| load_error(text, source, e);
    match t.kind.as_str() {
        "motion" => solve_motion(&t, &name).map_err(to_load),
        "function" => solve_function(&t, &name).map_err(to_load),
        // Two-position, Burmester and slider-crank problems (problem/guidance.rs).
        "two_positions" => guidance::solve_two(&t, &name).map_err(to_load),
        "burmester" => guidance::solve_burmester(&t, &name).map_err(to_load),
        "slider_motion" => guidance::solve_slider_motion(&t, &name).map_err(to_load),
        "slider_function" => guidance::solve_slider_function(&t, &name).map_err(to_load),
        // Path generation, dead-centre synthesis, cognates (problem/kinds.rs).
        "path" => kinds::path_plan(&t, source)
            .and_then(|plan| kinds::path_outcome(&plan, &name, starts))
            .map_err(to_load),
        "dead_centre" => kinds::solve_dead_centre(&t, &name).map_err(to_load),
        "cognates" => kinds::solve_cognates(&t, &name).map_err(to_load),
        "ball_point" => kinds::solve_ball(&t, &name).map_err(to_load),
        other => Err(to_load(unknown_type(other))),
    }
}

/// The requirements every guidance and path problem takes.
const REQUIREMENTS: [&str; 3] = ["turning", "min_transmission", "full_turn"];

/// The fields each problem type takes besides `type` and `name` (and the
/// [`REQUIREMENTS`] where it says so): one table, read by
/// [`check_fields`], so that a field given to a type that does not use it
/// is refused, never ignored.
const FIELDS: [(&str, bool, &[&str]); 10] = [
    ("motion", true, &["poses", "crank", "rocker"]),
    (
        "function",
        true,
        &[
            "function", "x", "input", "output", "ground", "method", "points", "count", "samples",
        ],
    ),
    (
        "two_positions",
        true,
        &["poses", "crank", "rocker", "along"],
    ),
    (
        "burmester",
        true,
        &[
            "poses",
            "keep",
            "dyads",
            "curve_samples",
            "region",
            "max_link_ratio",
        ],
    ),
    (
        "slider_motion",
        true,
        &["poses", "crank", "slider", "along"],
    ),
    (
        "slider_function",
        true,
        &[
            "function", "x", "input", "output", "method", "points", "count", "samples",
        ],
    ),
    (
        "path",
        true,
        &[
            "targets",
            "target_file",
            "units",
            "method",
            "timing",
            "crank_rotations",
            "coupler_rotations",
            "rocker_rotations",
            "closure",
            "order",
            "starts",
            "keep",
        ],
    ),
    (
        "dead_centre",
        false,
        &[
            "rocker_pivot",
            "rocker_length",
            "rocker_start",
            "swing",
            "time_ratio",
            "ground",
            "min_transmission",
        ],
    ),
    ("cognates", false, &["four_bar"]),
    ("ball_point", false, &["four_bar"]),
];

/// Every field of the table (besides `type` and `name`) and whether it is given.
fn given(t: &Table) -> [(&'static str, bool); 38] {
    [
        ("poses", t.poses.is_some()),
        ("crank", t.crank.is_some()),
        ("rocker", t.rocker.is_some()),
        ("turning", t.turning.is_some()),
        ("function", t.function.is_some()),
        ("x", t.x.is_some()),
        ("input", t.input.is_some()),
        ("output", t.output.is_some()),
        ("ground", t.ground.is_some()),
        ("method", t.method.is_some()),
        ("points", t.points.is_some()),
        ("count", t.count.is_some()),
        ("samples", t.samples.is_some()),
        ("min_transmission", t.min_transmission.is_some()),
        ("full_turn", t.full_turn.is_some()),
        ("along", t.along.is_some()),
        ("keep", t.keep.is_some()),
        ("dyads", t.dyads.is_some()),
        ("curve_samples", t.curve_samples.is_some()),
        ("region", t.region.is_some()),
        ("max_link_ratio", t.max_link_ratio.is_some()),
        ("slider", t.slider.is_some()),
        ("targets", t.targets.is_some()),
        ("target_file", t.target_file.is_some()),
        ("units", t.units.is_some()),
        ("timing", t.timing.is_some()),
        ("crank_rotations", t.crank_rotations.is_some()),
        ("coupler_rotations", t.coupler_rotations.is_some()),
        ("rocker_rotations", t.rocker_rotations.is_some()),
        ("closure", t.closure.is_some()),
        ("order", t.order.is_some()),
        ("starts", t.starts.is_some()),
        ("rocker_pivot", t.rocker_pivot.is_some()),
        ("rocker_length", t.rocker_length.is_some()),
        ("rocker_start", t.rocker_start.is_some()),
        ("swing", t.swing.is_some()),
        ("time_ratio", t.time_ratio.is_some()),
        ("four_bar", t.four_bar.is_some()),
    ]
}

fn unknown_type(kind: &str) -> SynthError {
    let kinds: Vec<String> = FIELDS.iter().map(|(k, _, _)| format!("\"{k}\"")).collect();
    invalid(
        "synthesis.type",
        format!(
            "unknown synthesis type '{kind}'; expected {} or {}",
            kinds[..kinds.len() - 1].join(", "),
            kinds[kinds.len() - 1]
        ),
    )
}

/// Refuses an unknown `type` and every field given that the type does
/// not take ([`FIELDS`]).
fn check_fields(t: &Table) -> Result<(), SynthError> {
    let Some((_, requirements, fields)) = FIELDS.iter().find(|(k, _, _)| *k == t.kind) else {
        return Err(unknown_type(&t.kind));
    };
    for (name, present) in given(t) {
        let takes = fields.contains(&name) || (*requirements && REQUIREMENTS.contains(&name));
        if present && !takes {
            return Err(invalid(
                &format!("synthesis.{name}"),
                format!("not a field of a {} problem", t.kind),
            ));
        }
    }
    Ok(())
}

/// Most characters in a solution's name.
const MOST_NAME: usize = 100;

/// `name` if it makes a file name in the output folder: letters, digits,
/// `_`, `-` and `.`, not starting with `.`, at most [`MOST_NAME`] characters.
fn check_name(name: &str) -> Result<String, String> {
    let ok = !name.is_empty()
        && name.chars().count() <= MOST_NAME
        && !name.starts_with('.')
        && name
            .chars()
            .all(|c| c.is_alphanumeric() || matches!(c, '_' | '-' | '.'));
    if ok {
        Ok(name.to_string())
    } else {
        Err(format!(
            "'{}' is not a name for a model file: use letters, digits, '_', '-' and '.' \
             (not first), at most {MOST_NAME} characters",
            name.escape_debug()
        ))
    }
}

fn invalid(field: &str, message: impl Into<String>) -> SynthError {
    SynthError::new(crate::error::ErrorKind::Invalid, field, message)
}

/// The value of a number or a constant expression (`"deg(30)"`), finite.
fn value(n: &Num, field: &str) -> Result<f64, SynthError> {
    let v = match n {
        Num::Value(v) => *v,
        Num::Expr(src) => camlink_expr::eval_constant(src, &HashMap::new())
            .map_err(|e| invalid(field, e.render(src)))?,
    };
    if v.is_finite() {
        Ok(v)
    } else {
        Err(invalid(field, format!("{v} is not a finite number")))
    }
}

fn values<const N: usize>(v: &[Num], field: &str, what: &str) -> Result<[f64; N], SynthError> {
    if v.len() != N {
        return Err(invalid(
            field,
            format!("{} numbers given; expected {N}: {what}", v.len()),
        ));
    }
    let mut out = [0.0; N];
    for (k, n) in v.iter().enumerate() {
        out[k] = value(n, &format!("{field}[{k}]"))?;
    }
    Ok(out)
}

fn requirements(t: &Table) -> Result<Requirements, SynthError> {
    let turning = match t.turning.as_deref() {
        None | Some("either") => None,
        Some("ccw") => Some(Turning::Ccw),
        Some("cw") => Some(Turning::Cw),
        Some(other) => {
            return Err(invalid(
                "synthesis.turning",
                format!("'{other}'; expected \"ccw\", \"cw\" or \"either\""),
            ))
        }
    };
    let min_transmission = match &t.min_transmission {
        None => None,
        Some(n) => {
            let f = "synthesis.min_transmission";
            let mu = value(n, f)?;
            if !(0.0..=std::f64::consts::FRAC_PI_2).contains(&mu) {
                return Err(invalid(
                    f,
                    format!("{mu} rad; expected an angle in [0, π/2] (rad)"),
                ));
            }
            Some(mu)
        }
    };
    Ok(Requirements {
        turning,
        min_transmission,
        full_turn: t.full_turn.unwrap_or(false),
    })
}

fn pivot(p: &Option<PivotTable>, name: &str) -> Result<Pivot, SynthError> {
    let field = format!("synthesis.{name}");
    let Some(p) = p else {
        return Err(invalid(
            &field,
            "missing; give the moving pivot in the coupler frame (moving = [x, y]) or the \
             ground pivot (fixed = [x, y]) (m)",
        ));
    };
    match (&p.moving, &p.fixed) {
        (Some(m), None) => Ok(Pivot::Moving(values::<2>(
            m,
            &format!("{field}.moving"),
            "x, y (m)",
        )?)),
        (None, Some(f)) => Ok(Pivot::Fixed(values::<2>(
            f,
            &format!("{field}.fixed"),
            "x, y (m)",
        )?)),
        _ => Err(invalid(
            &field,
            "give exactly one of moving = [x, y] and fixed = [x, y] (m)",
        )),
    }
}

fn checks_json(c: &Checks) -> Value {
    json!({
        "grashof": c.grashof.name(),
        "turning": c.turning.name(),
        "crank_angles": c.crank_angles,
        "branches": c.branches,
        "transmission": { "min": nan_null(c.transmission_min), "max": nan_null(c.transmission_max) },
        "defects": c.defects.iter().map(|d| json!({"kind": d.kind.name(), "message": d.message})).collect::<Vec<_>>(),
    })
}

fn nan_null(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

fn links_json(l: &FourBar) -> Value {
    let [d, a, b, c] = l.lengths();
    json!({
        "ground": d, "crank": a, "coupler": b, "rocker": c,
        "O2": l.o2, "O4": l.o4,
    })
}

fn solve_motion(t: &Table, name: &str) -> Result<Outcome, SynthError> {
    let Some(list) = &t.poses else {
        return Err(invalid(
            "synthesis.poses",
            "missing; give three poses [x (m), y (m), θ (rad)]",
        ));
    };
    if list.len() != 3 {
        return Err(invalid(
            "synthesis.poses",
            format!(
                "{} poses given; this version synthesises motion through exactly three",
                list.len()
            ),
        ));
    }
    let mut poses = [Pose {
        x: 0.0,
        y: 0.0,
        theta: 0.0,
    }; 3];
    for (k, p) in list.iter().enumerate() {
        let [x, y, theta] =
            values::<3>(p, &format!("synthesis.poses[{k}]"), "x (m), y (m), θ (rad)")?;
        poses[k] = Pose { x, y, theta };
    }
    let req = requirements(t)?;
    let crank = pivot(&t.crank, "crank")?;
    let rocker = pivot(&t.rocker, "rocker")?;
    let s = motion::three_positions(
        &poses,
        crank,
        rocker,
        &req,
        ["synthesis.poses", "synthesis.crank", "synthesis.rocker"],
    )?;
    Ok(Outcome {
        kind: "motion".into(),
        solutions: vec![motion_solution(&s, name)],
    })
}

fn motion_solution(s: &MotionSolution, name: &str) -> Solution {
    let (a1, b1) = s.pins(0);
    let l = &s.linkage;
    let rocker_start = (b1[1] - l.o4[1]).atan2(b1[0] - l.o4[0]);
    let header = vec![
        format!(
            "{name}: a four-bar synthesised by camlink to guide its coupler through three poses."
        ),
        "The coupler's frame is the coupler line: at each pose its origin (point P)".into(),
        "and its angle are those prescribed.".into(),
        format!(
            "Poses (x, y, θ): {}.",
            s.poses
                .iter()
                .map(|p| format!("({}, {}, {})", p.x, p.y, p.theta))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    ];
    let model = model_toml(&ModelSpec {
        name,
        header,
        linkage: l,
        coupler_points: [s.moving[0], s.moving[1], [0.0, 0.0]],
        coupler_start: coupler_pose(s.moving[0], s.moving[1], a1, b1),
        crank_angles: &s.checks.crank_angles,
        rocker_start,
        stop: "the poses",
    });
    let report = json!({
        "name": name,
        "method": "three_positions",
        "links": links_json(l),
        "moving_pivots": { "A": s.moving[0], "B": s.moving[1] },
        "poses": s.poses.iter().map(|p| [p.x, p.y, p.theta]).collect::<Vec<_>>(),
        "pose_times": pose_times(&s.checks.crank_angles),
        "checks": checks_json(&s.checks),
    });
    Solution {
        name: name.to_string(),
        model,
        report,
    }
}

fn solve_function(t: &Table, name: &str) -> Result<Outcome, SynthError> {
    let missing =
        |f: &str, what: &str| invalid(&format!("synthesis.{f}"), format!("missing; give {what}"));
    let src = t
        .function
        .as_deref()
        .ok_or_else(|| missing("function", "y = f(x) as an expression in x"))?;
    let f = Expr::parse(src, "x").map_err(|e| invalid("synthesis.function", e.render(src)))?;
    let x = values::<2>(
        t.x.as_deref()
            .ok_or_else(|| missing("x", "[x_start, x_end]"))?,
        "synthesis.x",
        "x_start, x_end",
    )?;
    let input = values::<2>(
        t.input
            .as_deref()
            .ok_or_else(|| missing("input", "the crank angles [φ_start, φ_end] (rad)"))?,
        "synthesis.input",
        "φ_start, φ_end (rad)",
    )?;
    let output = values::<2>(
        t.output
            .as_deref()
            .ok_or_else(|| missing("output", "the rocker angles [ψ_start, ψ_end] (rad)"))?,
        "synthesis.output",
        "ψ_start, ψ_end (rad)",
    )?;
    let ground = value(
        t.ground
            .as_ref()
            .ok_or_else(|| missing("ground", "the ground link d (m)"))?,
        "synthesis.ground",
    )?;
    if ground <= 0.0 {
        return Err(invalid(
            "synthesis.ground",
            format!("{ground} m; the ground link must be longer than 0"),
        ));
    }
    if x[0] == x[1] {
        return Err(invalid("synthesis.x", "x_start equals x_end; give a range"));
    }
    if input[0] == input[1] {
        return Err(invalid(
            "synthesis.input",
            "φ_start equals φ_end; the crank must turn",
        ));
    }
    if output[0] == output[1] {
        return Err(invalid(
            "synthesis.output",
            "ψ_start equals ψ_end; the rocker must turn",
        ));
    }
    let samples = t.samples.unwrap_or(DEFAULT_SAMPLES);
    if !(2..=MOST_POINTS).contains(&samples) {
        return Err(invalid(
            "synthesis.samples",
            format!("{samples}; expected 2 to {MOST_POINTS}"),
        ));
    }
    // f must be finite over the range (checked at the samples) and differ at the ends.
    for i in 0..samples {
        let xi = x[0] + (x[1] - x[0]) * i as f64 / (samples - 1) as f64;
        if let Err(e) = f.check(xi) {
            return Err(invalid("synthesis.function", e.to_string()));
        }
    }
    // f(x_e) − f(x_s) within rounding of the values of f over the range.
    let largest = (0..samples)
        .map(|i| {
            f.eval(x[0] + (x[1] - x[0]) * i as f64 / (samples - 1) as f64)
                .abs()
        })
        .fold(0.0, f64::max);
    if (f.eval(x[1]) - f.eval(x[0])).abs() <= 1e-12 * largest {
        return Err(invalid(
            "synthesis.function",
            "f(x_start) equals f(x_end), so the output range cannot be mapped to the rocker angles",
        ));
    }
    let method = t.method.as_deref().unwrap_or("three_point");
    let given = match &t.points {
        None => None,
        Some(p) => {
            let mut v = Vec::with_capacity(p.len());
            for (k, n) in p.iter().enumerate() {
                let field = format!("synthesis.points[{k}]");
                let xv = value(n, &field)?;
                let (lo, hi) = (x[0].min(x[1]), x[0].max(x[1]));
                if !(lo..=hi).contains(&xv) {
                    return Err(invalid(
                        &field,
                        format!("x = {xv} lies outside the range [{lo}, {hi}]"),
                    ));
                }
                v.push(xv);
            }
            // In the order the crank reaches them, from x_start.
            v.sort_by(|p, q| (p - x[0]).abs().total_cmp(&(q - x[0]).abs()));
            Some(v)
        }
    };
    let fit = match method {
        "three_point" => {
            if t.count.is_some() {
                return Err(invalid(
                    "synthesis.count",
                    "a least_squares field; three_point uses three points",
                ));
            }
            let p = given.unwrap_or_else(|| chebyshev(3, x[0], x[1]));
            if p.len() != 3 {
                return Err(invalid(
                    "synthesis.points",
                    format!("{} points; three_point takes three", p.len()),
                ));
            }
            Fit::ThreePoint(p)
        }
        "least_squares" => {
            let p = match (given, t.count) {
                (Some(_), Some(_)) => {
                    return Err(invalid("synthesis.count", "give points or count, not both"));
                }
                (Some(p), None) => p,
                (None, n) => {
                    let n = n.unwrap_or(DEFAULT_FIT_POINTS);
                    if !(3..=MOST_POINTS).contains(&n) {
                        return Err(invalid(
                            "synthesis.count",
                            format!("{n}; expected 3 to {MOST_POINTS}"),
                        ));
                    }
                    chebyshev(n, x[0], x[1])
                }
            };
            if p.len() < 3 {
                return Err(invalid(
                    "synthesis.points",
                    format!("{} points; least_squares needs at least three", p.len()),
                ));
            }
            Fit::LeastSquares(p)
        }
        other => {
            return Err(invalid(
                "synthesis.method",
                format!("'{other}'; expected \"three_point\" or \"least_squares\""),
            ))
        }
    };
    // Two points with one x are one point.
    let (Fit::ThreePoint(p) | Fit::LeastSquares(p)) = &fit;
    let mut sorted = p.clone();
    sorted.sort_by(f64::total_cmp);
    if sorted.windows(2).any(|w| w[0] == w[1]) {
        return Err(SynthError::new(
            crate::error::ErrorKind::Coincident,
            "synthesis.points",
            "two points have the same x",
        ));
    }
    let spec = FunctionSpec {
        f,
        source: src.to_string(),
        x,
        input,
        output,
        ground,
    };
    let req = requirements(t)?;
    let field = if t.points.is_some() {
        "synthesis.points"
    } else {
        "synthesis.function"
    };
    let s = function::synthesise(&spec, &fit, samples, &req, field)?;
    Ok(Outcome {
        kind: "function".into(),
        solutions: vec![function_solution(&s, &spec, &fit, name)],
    })
}

fn function_solution(s: &FunctionSolution, spec: &FunctionSpec, fit: &Fit, name: &str) -> Solution {
    let l = &s.linkage;
    let method = match fit {
        Fit::ThreePoint(_) => "three_point",
        Fit::LeastSquares(_) => "least_squares",
    };
    // The crank from φ_start to φ_end, the precision points' times between.
    let mut angles = vec![spec.input[0]];
    angles.extend(s.pairs.iter().map(|p| p.0));
    angles.push(spec.input[1]);
    let start = l
        .position(spec.input[0], s.sigma)
        .map(|p| (p.a, p.b, p.psi))
        .unwrap_or_else(|| {
            let (_, psi) = spec.angles(spec.x[0]);
            let a = l.crank_pin(spec.input[0]);
            let b = [
                l.o4[0] + l.rocker * psi.cos(),
                l.o4[1] + l.rocker * psi.sin(),
            ];
            (a, b, psi)
        });
    let header = vec![
        format!("{name}: a four-bar function generator synthesised by camlink ({method})."),
        format!(
            "y = {} for x from {} to {}; crank angle φ from {} to {} rad, rocker angle ψ from {} to {} rad,",
            spec.source, spec.x[0], spec.x[1], spec.input[0], spec.input[1], spec.output[0], spec.output[1]
        ),
        "both from the ground line O2→O4 (+x); the rocker body's angle is ψ.".into(),
        "Negative crank or rocker lengths point the link against its body axis.".into(),
    ];
    let model = model_toml(&ModelSpec {
        name,
        header,
        linkage: l,
        coupler_points: [[0.0, 0.0], [l.coupler, 0.0], [0.5 * l.coupler, 0.0]],
        coupler_start: coupler_along(start.0, start.1),
        crank_angles: &angles,
        rocker_start: start.2,
        stop: "φ_start, the points fitted and φ_end",
    });
    let times = pose_times(&angles);
    let report = json!({
        "name": name,
        "method": method,
        "function": spec.source,
        "links": links_json(l),
        "signed": { "crank": l.crank, "rocker": l.rocker },
        "k": s.k,
        "x": s.x,
        "angles": s.pairs.iter().map(|p| [p.0, p.1]).collect::<Vec<_>>(),
        "point_times": &times[1..times.len() - 1],
        "branch": s.sigma,
        "structural_error": {
            "max": s.error.max, "at_x": s.error.at_x, "rms": s.error.rms,
            "samples": s.error.samples, "unassembled_at": s.error.unassembled_at,
        },
        "checks": checks_json(&s.checks),
    });
    Solution {
        name: name.to_string(),
        model,
        report,
    }
}
