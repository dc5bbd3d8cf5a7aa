//! Timing files: the cams of one machine on one master angle Θ, the
//! clearances between their followers, and each axis's servo cam table.
//!
//! A timing file (TOML, docs/cam-design.md, *Timing diagram and servo cam
//! tables*) holds `name`, `speed_rpm`, `[[axes]]` (a cam design file
//! beside it, its phase φ_k on the master angle, the follower tip's
//! `origin` O_k and `direction_deg` α_k), `[[clearances]]` (two
//! translating axes and their least tip distance) and `[export]`.
//!
//! Axis k at master angle Θ runs its own program at θ = Θ − φ_k (wrapped
//! into [0, 2π)); its follower's tip is at O_k + s_k(θ) (cos α_k, sin α_k)
//! in the machine's plane (m). Errors name the file, the line and column
//! and the field, as design files' do; an error in an axis's design file
//! names that file.

use std::f64::consts::TAU;
use std::path::{Path, PathBuf};

use camlink_core::cam::Program;
use camlink_core::fmt_num::num;
use camlink_core::names::did_you_mean;
use camlink_core::quantity::Length;
use camlink_model::LoadError;
use toml::{Table as Map, Value};

use crate::design::Design;
use crate::limits::{MAX_CSV_ROWS, MAX_LENGTH, MAX_RPM, RPM};
use crate::load::{located, not_plain, parse_toml, stem_and_name};
use crate::table::{fail, repr, Fail, Num, Table};

/// Length units of the cam tables and the diagram.
pub const UNITS: [&str; 2] = ["m", "mm"];

/// Master angles sampled over a turn for the clearance check.
pub const SAMPLES: usize = 36_000;

/// Points sampled over each segment (its ends included) for the extreme
/// velocity and acceleration of the segment table.
pub const SEGMENT_SAMPLES: usize = 2001;

/// A checked timing file.
#[derive(Clone, Debug)]
pub struct Timing {
    /// The file as errors name it.
    pub source: String,
    pub name: String,
    /// Machine speed ω (rad/s of the master).
    pub speed: f64,
    /// Master angle step of the cam tables (rad).
    pub resolution: f64,
    /// Length unit of the tables and the diagram (one of [`UNITS`]).
    pub units: String,
    pub axes: Vec<Axis>,
    pub clearances: Vec<Clearance>,
    /// The diagram's file name; `None` for none.
    pub diagram: Option<String>,
    /// Whether the cam tables are written.
    pub tables: bool,
}

/// One cam of the machine.
#[derive(Clone, Debug)]
pub struct Axis {
    pub name: String,
    /// Its checked design file (`design.source` names it).
    pub design: Design,
    /// The design's motion program.
    pub program: Program,
    /// Phase φ (rad) on the master angle.
    pub phase: f64,
    /// The follower's tip O at s = 0 (m, machine frame).
    pub origin: [f64; 2],
    /// Direction α (rad, machine frame) in which s moves the tip.
    pub direction: f64,
}

/// A least distance between the tips of two translating followers.
#[derive(Clone, Debug, PartialEq)]
pub struct Clearance {
    /// The axes, as indices into [`Timing::axes`].
    pub a: usize,
    pub b: usize,
    /// m
    pub min_distance: f64,
}

/// A checked timing file and the warnings of its design files.
#[derive(Clone, Debug)]
pub struct LoadedTiming {
    pub timing: Timing,
    pub warnings: Vec<String>,
}

/// The least tip distance of a [`Clearance`] over a master turn.
#[derive(Clone, Debug, PartialEq)]
pub struct ClearanceReport {
    pub a: usize,
    pub b: usize,
    /// Least tip distance (m).
    pub least: f64,
    /// Master angle (deg, in [0, 360)) where it occurs.
    pub at_deg: f64,
    /// The file's least allowed distance (m).
    pub limit: f64,
    pub ok: bool,
}

/// One segment of an axis on the master angle, as the segment table
/// gives it (lengths in the table's unit, or rad for an oscillating
/// follower; time at the machine speed).
#[derive(Clone, Debug, PartialEq)]
pub struct SegmentRow {
    pub segment: usize,
    pub law: &'static str,
    /// Master angles (deg) of its start, in [0, 360), and its end, in (0, 360].
    pub start_deg: f64,
    pub end_deg: f64,
    pub lift: f64,
    /// Continuity class (0…3 for C0…C3) at its start and at its end.
    pub continuity_start: usize,
    pub continuity_end: usize,
    /// The velocity of largest size, per s, and its master angle (deg).
    pub peak_velocity: (f64, f64),
    /// The largest and the least acceleration, per s², and their angles.
    pub max_acceleration: (f64, f64),
    pub min_acceleration: (f64, f64),
    /// The acceleration of largest size.
    pub peak_acceleration: f64,
}

/// Whether `doc` is a timing file (it has `axes`).
pub fn is_timing(doc: &Map) -> bool {
    doc.contains_key("axes")
}

/// Whether the file at `path` is a TOML timing file; false when it cannot
/// be read or parsed.
pub fn is_timing_path(path: &Path) -> bool {
    let Ok(text) = camlink_model::text::read_text(path) else {
        return false;
    };
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    text.parse::<Map>().is_ok_and(|doc| is_timing(&doc))
}

/// Reads and checks the timing file at `path` and the design files it
/// names (beside it).
pub fn load_path(path: &Path) -> Result<LoadedTiming, LoadError> {
    let text = camlink_model::text::read_text(path)?;
    let dir = path.parent().unwrap_or(Path::new(""));
    load_toml(&text, &path.display().to_string(), dir)
}

/// Checks the timing file `text` (TOML); `source` names it in messages
/// (its stem names the default diagram) and the design files it names are
/// read from `dir`. Errors give the line and column of the field.
pub fn load_toml(text: &str, source: &str, dir: &Path) -> Result<LoadedTiming, LoadError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let doc = parse_toml(text, source)?;
    read(&doc, source, dir).map_err(|p| match p {
        Problem::Here(f) => located(f, Some(text), source),
        Problem::Design(e) => e,
    })
}

/// What stops a timing file: a field of its own, or a design file it names.
enum Problem {
    Here(Fail),
    Design(LoadError),
}

impl From<Fail> for Problem {
    fn from(f: Fail) -> Self {
        Problem::Here(f)
    }
}

fn read(doc: &Map, source: &str, dir: &Path) -> Result<LoadedTiming, Problem> {
    let (stem, file_name) = stem_and_name(source);
    let mut warnings = Vec::new();
    let mut top = Table::root(doc);
    let name = top.text("name", Some(&stem), &[])?;
    let speed = top.number("speed_rpm", None, Num::POSITIVE.most(MAX_RPM, " rpm"))? * RPM;

    // [[axes]]
    top.mark("axes");
    let raw = match top.get("axes") {
        Some(Value::Array(a)) if !a.is_empty() => a,
        _ => fail("axes", "a timing diagram needs at least one axis")?,
    };
    let mut axes: Vec<Axis> = Vec::with_capacity(raw.len());
    for (i, r) in raw.iter().enumerate() {
        let mut t = Table::new(format!("axes[{i}]"), Some(r))?;
        let an = t.text("name", None, &[])?;
        if axes.iter().any(|a| a.name == an) {
            t.fail::<()>("name", format!("'{an}' names two axes"))?;
        }
        let file = t.text("design", None, &[])?;
        if let Some(problem) = not_plain(&file) {
            t.fail::<()>(
                "design",
                format!("'{file}' {problem}; name a design file beside {file_name}"),
            )?;
        }
        let dp: PathBuf = dir.join(&file);
        if !dp.is_file() {
            t.fail::<()>(
                "design",
                format!("'{file}': no such file beside {file_name}"),
            )?;
        }
        let own = dir.join(&file_name);
        if let (Ok(d), Ok(o)) = (dp.canonicalize(), own.canonicalize()) {
            if d == o {
                t.fail::<()>("design", "names the timing file itself")?;
            }
        }
        let loaded = crate::load::load_path(&dp).map_err(Problem::Design)?;
        warnings.extend(loaded.warnings);
        let design = loaded.design;
        let program = design
            .program()
            .map_err(|e| Problem::Design(LoadError::file(&design.source, e.to_string())))?;
        t.mark("origin");
        let origin = match t.get("origin") {
            None => [0.0, 0.0],
            Some(v) => match point(v) {
                Some(p) => p,
                None => t.fail("origin", format!("must be [x, y] (m), got {}", repr(v)))?,
            },
        };
        let phase = t
            .number("phase_deg", Some(0.0), Num::ANY.most(360.0, "°"))?
            .to_radians();
        let direction = t
            .number("direction_deg", Some(90.0), Num::ANY.most(360.0, "°"))?
            .to_radians();
        t.finish()?;
        axes.push(Axis {
            name: an,
            design,
            program,
            phase,
            origin,
            direction,
        });
    }

    // [[clearances]]
    top.mark("clearances");
    let raw = match top.get("clearances") {
        None => &Vec::new(),
        Some(Value::Array(a)) => a,
        Some(_) => fail("clearances", "must be an array of tables ([[clearances]])")?,
    };
    let names: Vec<&str> = axes.iter().map(|a| a.name.as_str()).collect();
    let mut clearances = Vec::with_capacity(raw.len());
    for (i, r) in raw.iter().enumerate() {
        let mut t = Table::new(format!("clearances[{i}]"), Some(r))?;
        t.mark("between");
        let pair = match t.get("between") {
            Some(Value::Array(a)) if a.len() == 2 => match (&a[0], &a[1]) {
                (Value::String(x), Value::String(y)) => Some([x.as_str(), y.as_str()]),
                _ => None,
            },
            _ => None,
        };
        let Some(pair) = pair else {
            let got = t.get("between").map_or("nothing".to_string(), repr);
            return Ok(t.fail("between", format!("must name two axes, got {got}"))?);
        };
        let mut at = [0; 2];
        for (k, x) in pair.iter().enumerate() {
            let j = match names.iter().position(|n| n == x) {
                Some(j) => j,
                None => t.fail(
                    "between",
                    format!(
                        "'{x}' is not an axis{}; the axes are {}",
                        did_you_mean(x, names.iter().copied()),
                        names.join(", ")
                    ),
                )?,
            };
            if axes[j].design.oscillating() {
                t.fail::<()>(
                    "between",
                    format!(
                        "'{x}' has an oscillating follower; a clearance needs translating \
                         followers"
                    ),
                )?;
            }
            at[k] = j;
        }
        if at[0] == at[1] {
            t.fail::<()>("between", "names one axis twice")?;
        }
        let min_distance = t.number("min_distance", None, Num::POSITIVE_LENGTH)?;
        t.finish()?;
        clearances.push(Clearance {
            a: at[0],
            b: at[1],
            min_distance,
        });
    }

    // [export]
    let mut ex = top.table("export")?;
    let step = ex.number("resolution_deg", Some(1.0), Num::POSITIVE.most(90.0, "°"))?;
    if 360.0 / step > MAX_CSV_ROWS as f64 {
        ex.fail::<()>(
            "resolution_deg",
            format!(
                "{}° makes more than {MAX_CSV_ROWS} rows (a step of at least {}°)",
                num(step),
                num(360.0 / MAX_CSV_ROWS as f64)
            ),
        )?;
    }
    let units = ex.text("units", Some("m"), &UNITS)?;
    ex.mark("diagram");
    let diagram = match ex.get("diagram") {
        None => Some(format!("{stem}_timing.png")),
        Some(Value::Boolean(false)) => None,
        Some(Value::String(s)) if !s.is_empty() && not_plain(s).is_none() => Some(s.clone()),
        Some(other) => ex.fail(
            "diagram",
            format!("must be a plain file name or false, got {}", repr(other)),
        )?,
    };
    let tables = ex.flag("tables", true)?;
    ex.finish()?;
    top.finish()?;
    Ok(LoadedTiming {
        timing: Timing {
            source: source.to_string(),
            name,
            speed,
            resolution: step.to_radians(),
            units,
            axes,
            clearances,
            diagram,
            tables,
        },
        warnings,
    })
}

/// `[x, y]`: two finite numbers, each at most [`MAX_LENGTH`] in size.
fn point(v: &Value) -> Option<[f64; 2]> {
    let Value::Array(a) = v else { return None };
    let x: Vec<f64> = a
        .iter()
        .filter_map(|x| match x {
            Value::Integer(i) => Some(*i as f64),
            Value::Float(f) => Some(*f),
            _ => None,
        })
        .filter(|x| x.is_finite() && x.abs() <= MAX_LENGTH)
        .collect();
    match (a.len(), x.as_slice()) {
        (2, &[x, y]) => Some([x, y]),
        _ => None,
    }
}

/// `x` mod `p` for p > 0, in [0, p) (a zero is +0).
fn wrap(x: f64, p: f64) -> f64 {
    let r = x.rem_euclid(p);
    if r == 0.0 {
        0.0
    } else {
        r
    }
}

/// Metres in one `unit` (one of [`UNITS`]).
pub fn metres(unit: &str) -> Option<f64> {
    UNITS
        .contains(&unit)
        .then(|| Length::ALL.iter().find(|l| l.name() == unit))
        .flatten()
        .map(|l| l.metres())
}

impl Axis {
    /// [s, s′, s″, s‴] at master angle Θ (rad): the program at Θ − φ
    /// wrapped into [0, 2π); derivatives per radian of the master. s is in
    /// m, or rad for an oscillating follower.
    pub fn motion(&self, master: f64) -> [f64; 4] {
        let m = self.program.eval(wrap(master - self.phase, TAU));
        [m[0], m[1], m[2], m[3]]
    }

    /// The follower's tip (m, machine frame) at displacement `s` (m).
    pub fn tip(&self, s: f64) -> [f64; 2] {
        [
            self.origin[0] + s * self.direction.cos(),
            self.origin[1] + s * self.direction.sin(),
        ]
    }
}

impl Timing {
    /// The least distance between each clearance's tips over a master turn:
    /// sampled at [`SAMPLES`] angles, the least refined by the parabola
    /// through it and its two neighbours.
    pub fn clearances(&self) -> Vec<ClearanceReport> {
        let h = TAU / SAMPLES as f64;
        let master: Vec<f64> = (0..SAMPLES).map(|k| k as f64 * h).collect();
        self.clearances
            .iter()
            .map(|c| {
                let (a, b) = (&self.axes[c.a], &self.axes[c.b]);
                let d: Vec<f64> = master
                    .iter()
                    .map(|&t| {
                        let pa = a.tip(a.motion(t)[0]);
                        let pb = b.tip(b.motion(t)[0]);
                        (pa[0] - pb[0]).hypot(pa[1] - pb[1])
                    })
                    .collect();
                // The first least sample.
                let k = (0..SAMPLES).fold(0, |k, j| if d[j] < d[k] { j } else { k });
                let (mut least, mut at) = (d[k], master[k]);
                let (y0, y1, y2) = (d[(k + SAMPLES - 1) % SAMPLES], d[k], d[(k + 1) % SAMPLES]);
                let curv = y0 - 2.0 * y1 + y2;
                if curv > 0.0 {
                    let x = 0.5 * (y0 - y2) / curv;
                    least = y1 - 0.25 * (y0 - y2) * x;
                    at = master[k] + x * (master[1] - master[0]);
                }
                ClearanceReport {
                    a: c.a,
                    b: c.b,
                    least,
                    at_deg: wrap(at.to_degrees(), 360.0),
                    limit: c.min_distance,
                    ok: least >= c.min_distance,
                }
            })
            .collect()
    }

    /// The scale from metres to `units` of axis `k` (1 for an oscillating
    /// follower, whose lengths are angles); `None` for an unknown unit.
    fn scale(&self, k: usize, units: &str) -> Option<f64> {
        let m = metres(units)?;
        Some(if self.axes[k].design.oscillating() {
            1.0
        } else {
            1.0 / m
        })
    }

    /// The cam table of axis `k`: rows [Θ (deg), s, v, a, j] every
    /// [`Timing::resolution`] over a turn, both ends included, in `units`
    /// (or rad) and seconds at the machine speed ω; `None` for an unknown
    /// unit.
    pub fn table(&self, k: usize, units: &str) -> Option<Vec<[f64; 5]>> {
        let scale = self.scale(k, units)?;
        let axis = &self.axes[k];
        let n = ((TAU / self.resolution).round_ties_even() as usize).max(2);
        let step = TAU / n as f64;
        let w = self.speed;
        let w3 = w.powf(3.0);
        Some(
            (0..=n)
                .map(|i| {
                    let t = if i == n { TAU } else { i as f64 * step };
                    let m = axis.motion(t);
                    [
                        t.to_degrees(),
                        m[0] * scale,
                        m[1] * w * scale,
                        m[2] * w * w * scale,
                        m[3] * w3 * scale,
                    ]
                })
                .collect(),
        )
    }

    /// Each segment of axis `k` on the master angle, with its continuity at
    /// either end and its extreme velocity and acceleration, sampled at
    /// [`SEGMENT_SAMPLES`] points over the segment (the last just inside
    /// its end); lengths in `units` (or rad). `None` for an unknown unit.
    pub fn segments(&self, k: usize, units: &str) -> Option<Vec<SegmentRow>> {
        let scale = self.scale(k, units)?;
        let axis = &self.axes[k];
        let osc = axis.design.oscillating();
        let mut starts = axis.program.starts();
        starts.push(TAU);
        let bounds = axis.program.boundaries();
        let class = |at: &dyn Fn(&camlink_core::cam::Boundary) -> usize, seg: usize| {
            bounds
                .iter()
                .rev()
                .find(|b| at(b) == seg)
                .map_or(3, |b| b.continuity)
        };
        let deg = |t: f64| wrap((t + axis.phase).to_degrees(), 360.0);
        let w = self.speed;
        let mut rows = Vec::with_capacity(axis.design.segments.len());
        for (s, seg) in axis.design.segments.iter().enumerate() {
            let (a, b) = (starts[s], starts[s + 1]);
            let n = SEGMENT_SAMPLES - 1;
            let step = (b - a) / n as f64;
            let mut v = Vec::with_capacity(SEGMENT_SAMPLES);
            let mut acc = Vec::with_capacity(SEGMENT_SAMPLES);
            let mut at = Vec::with_capacity(SEGMENT_SAMPLES);
            for i in 0..=n {
                let th = if i == n {
                    next_down(b)
                } else {
                    i as f64 * step + a
                };
                let m = axis.program.eval(th);
                v.push(m[1] * w * scale);
                acc.push(m[2] * w * w * scale);
                at.push(round9_fast(deg(th)));
            }
            let first = |better: &dyn Fn(f64, f64) -> bool, x: &[f64]| {
                (0..x.len()).fold(0, |k, j| if better(x[j], x[k]) { j } else { k })
            };
            let iv = first(&|x, y| x.abs() > y.abs(), &v);
            let ia = first(&|x, y| x.abs() > y.abs(), &acc);
            let ip = first(&|x, y| x > y, &acc);
            let iq = first(&|x, y| x < y, &acc);
            let end = round9(deg(b));
            rows.push(SegmentRow {
                segment: s,
                law: seg.law.name(),
                start_deg: round9(deg(a)),
                end_deg: if end == 0.0 { 360.0 } else { end },
                lift: if osc { seg.lift } else { seg.lift * scale },
                continuity_start: class(&|b| b.after, s),
                continuity_end: class(&|b| b.before, s),
                peak_velocity: (v[iv], at[iv]),
                max_acceleration: (acc[ip], at[ip]),
                min_acceleration: (acc[iq], at[iq]),
                peak_acceleration: acc[ia],
            });
        }
        Some(rows)
    }
}

/// The largest f64 below `x` (x finite and positive).
fn next_down(x: f64) -> f64 {
    f64::from_bits(x.to_bits() - 1)
}

/// `x` correctly rounded to 9 decimals (the nearest decimal, ties to even).
fn round9(x: f64) -> f64 {
    format!("{x:.9}").parse().unwrap_or(x)
}

/// `x` rounded to 9 decimals as rint(x · 10⁹) / 10⁹.
fn round9_fast(x: f64) -> f64 {
    (x * 1e9).round_ties_even() / 1e9
}
