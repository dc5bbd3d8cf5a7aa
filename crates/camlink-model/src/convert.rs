//! A model file rewritten between frame form and global form.
//!
//! In frame form a body's points are vectors s′ in its frame (`points`); in
//! global form they are global positions r at the initial instant
//! (`global_points`, docs/model-files.md, "Bodies in global coordinates").
//! [`convert`] rewrites every body with points into the form asked for,
//! with r = r₀ + A(φ₀) s′ and s′ = A(φ₀)ᵀ (r − r₀), r₀ and φ₀ being the
//! body frame's initial origin and angle, and with it every other position
//! written for the body: its `centroid`, its `outline` corners and the
//! points given as [x, y] in joints, drivers, forces and curves. The body
//! frames stay where they are: a body in global form keeps (or is given)
//! `position`, and `angle` when it is not 0, so that the converted file
//! describes the same model, body channels included.
//!
//! The text is edited in place: comments, the order of keys and every
//! value not named above stay as written. A value of a body whose frame is
//! not turned (φ₀ = 0) stays an expression of the parameters where it was
//! one (`"r"` on a body at `["d", 0]` becomes `"d + r"`); on a turned body
//! it is a number, the shortest decimal within the rounding of the
//! computation. The result is loaded and compared with the original before
//! it is returned.

use std::collections::HashMap;
use std::ops::Range;
use std::path::Path;

use camlink_core::math::{rot, V2};

use crate::file::{BodySpec, Num, OutlineSpec, Vec2};
use crate::{eval, load_path_with, load_str_with, locate, Format, LoadError, LoadOptions, Loaded};

/// The form a model file is converted to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    /// Bodies given by `points` in their frames.
    Frame,
    /// Bodies given by `global_points` at the initial instant.
    Global,
}

/// The keys of a [x, y] point written for a body, with the key naming
/// that body, in `[[joints]]`, `[[drivers]]`, `[[forces]]` and `[[curves]]`.
pub const POINT_KEYS: [(&str, &str); 7] = [
    ("point_i", "body_i"),
    ("point_j", "body_j"),
    ("point", "body"),
    ("centre", "body"),
    ("from", "body"),
    ("to", "body"),
    ("reaction_point", "reaction"),
];

/// The text of the model file at `path` in `form`, and the names of the
/// bodies rewritten. Errors name the file (a file that does not load is
/// not converted).
pub fn convert_path(
    path: &Path,
    form: Form,
    options: &LoadOptions,
) -> Result<(String, Vec<String>), LoadError> {
    let loaded = load_path_with(path, options)?;
    convert(&loaded, form, options)
}

/// The text of the loaded model file in `form` (see the module
/// documentation), and the names of the bodies rewritten; `options` are
/// those it was loaded with (for its data files).
pub fn convert(
    loaded: &Loaded,
    form: Form,
    options: &LoadOptions,
) -> Result<(String, Vec<String>), LoadError> {
    let Some(recipe) = loaded.recipe.as_deref() else {
        return Err(LoadError::file(
            "model",
            "only a camlink model file can be converted between frame and global form",
        ));
    };
    let (text, format, source) = (&recipe.text, recipe.format, recipe.source.as_str());
    let fail = |message: String| LoadError::file(source, message);
    let params = crate::resolve::parameters(&recipe.file.parameters)
        .map_err(|f| fail(format!("{}: {}", f.path, f.message)))?;
    let cx = Cx {
        params: &params,
        text,
        format,
    };
    let mut edits = Vec::new();
    let mut converted = Vec::new();
    let mut frames: HashMap<&str, Frame> = HashMap::new();
    for (k, body) in recipe.file.bodies.iter().enumerate() {
        let path = format!("bodies[{k}]");
        let from_global = !body.global_points.is_empty();
        let want_global = form == Form::Global;
        if from_global == want_global || (body.points.is_empty() && !from_global) {
            continue;
        }
        let frame = cx.frame(body, &path).map_err(fail)?;
        cx.body_edits(body, &path, &frame, form, &mut edits)
            .map_err(fail)?;
        frames.insert(&body.name, frame);
        converted.push(body.name.clone());
    }
    cx.reference_edits(&frames, form, &mut edits)
        .map_err(fail)?;
    let out = apply(text, edits);
    let again = load_str_with(&out, format, source, options).map_err(|e| {
        fail(format!(
            "the converted file does not load ({e}); write the bodies' points as inline tables"
        ))
    })?;
    same_model(loaded, &again).map_err(|e| fail(format!("the converted file differs: {e}")))?;
    Ok((out, converted))
}

/// A body frame at the initial instant: origin r₀ and angle φ₀, as
/// written (or as the loader places it) and evaluated.
struct Frame {
    origin: [Term; 2],
    /// φ₀ (rad).
    angle: f64,
    /// True when the file gives no `position`.
    implicit: bool,
}

/// A number or expression of the file with its value.
#[derive(Clone, Debug)]
struct Term {
    /// The expression text, `None` for a plain number.
    src: Option<String>,
    v: f64,
}

impl Term {
    fn number(v: f64) -> Term {
        Term { src: None, v }
    }

    /// True for a plain number 0.
    fn is_zero(&self) -> bool {
        self.src.is_none() && self.v == 0.0
    }

    /// The text inside a sum: a name or an unsigned number as is, anything
    /// else in parentheses.
    fn operand(&self) -> String {
        match &self.src {
            None if self.v >= 0.0 => fmt(self.v),
            None => format!("({})", fmt(self.v)),
            Some(s) if is_simple(s) => s.clone(),
            Some(s) => format!("({s})"),
        }
    }

    /// a + b, or a − b with `minus`, kept an expression where one of them
    /// is one.
    fn combine(a: &Term, b: &Term, minus: bool) -> Term {
        let v = if minus { a.v - b.v } else { a.v + b.v };
        if b.is_zero() {
            return a.clone();
        }
        if a.is_zero() && !minus {
            return b.clone();
        }
        if minus && a.src.is_some() && a.src == b.src {
            return Term::number(0.0);
        }
        // (b + s) − b is s as written.
        if let (true, Some(sum)) = (minus, &a.src) {
            if let Some(rest) = sum.strip_prefix(&format!("{} + ", b.operand())) {
                let inner = rest
                    .strip_prefix('(')
                    .and_then(|r| r.strip_suffix(')'))
                    .filter(|r| balanced(r));
                let src = inner.unwrap_or(rest).to_string();
                let v = match src.parse::<f64>() {
                    Ok(n) => return Term::number(n),
                    Err(_) => v,
                };
                return Term { src: Some(src), v };
            }
        }
        if a.src.is_none() && b.src.is_none() {
            return Term::number(v);
        }
        // A negative number is added as a positive one taken away.
        let (minus, b) = match b.src {
            None if b.v < 0.0 => (!minus, Term::number(-b.v)),
            _ => (minus, b.clone()),
        };
        let src = match (a.is_zero(), minus) {
            (true, true) => format!("-{}", b.operand()),
            (true, false) => b.operand(),
            (false, true) => format!("{} - {}", a.operand(), b.operand()),
            (false, false) => format!("{} + {}", a.operand(), b.operand()),
        };
        Term { src: Some(src), v }
    }
}

/// True when the parentheses of `s` never close more than they opened.
fn balanced(s: &str) -> bool {
    let mut depth = 0i32;
    for c in s.chars() {
        depth += match c {
            '(' => 1,
            ')' => -1,
            _ => 0,
        };
        if depth < 0 {
            return false;
        }
    }
    depth == 0
}

/// True for a parameter name or an unsigned number literal.
fn is_simple(s: &str) -> bool {
    let s = s.trim();
    !s.is_empty()
        && (s.chars().all(|c| c.is_alphanumeric() || c == '_')
            || s.parse::<f64>()
                .is_ok_and(|v| v >= 0.0 && !s.starts_with('+')))
}

/// `v` as a decimal that both TOML and JSON read back as `v`: an integer
/// without a point.
fn fmt(v: f64) -> String {
    if v == v.trunc() && v.abs() < 1e15 {
        return format!("{}", v as i64);
    }
    format!("{v:?}")
}

/// The shortest decimal within `err` of `v` (0 when |v| ≤ err).
fn clean(v: f64, err: f64) -> f64 {
    if v.abs() <= err {
        return 0.0;
    }
    for digits in 1..17 {
        if let Ok(y) = format!("{:.*e}", digits - 1, v).parse::<f64>() {
            if (y - v).abs() <= err {
                return y;
            }
        }
    }
    v
}

/// One replacement of a byte range of the text.
struct Edit {
    at: Range<usize>,
    text: String,
}

/// Applies non-overlapping edits.
fn apply(text: &str, mut edits: Vec<Edit>) -> String {
    edits.sort_by_key(|e| (e.at.start, e.at.end));
    let mut out = String::with_capacity(text.len() + 64 * edits.len());
    let mut k = 0;
    for e in edits {
        out.push_str(&text[k..e.at.start]);
        out.push_str(&e.text);
        k = e.at.end;
    }
    out.push_str(&text[k..]);
    out
}

/// The text of a pair in either format: `[a, b]`.
fn pair(p: &[Term; 2]) -> String {
    let one = |t: &Term| match &t.src {
        None => fmt(t.v),
        Some(s) => serde_json::Value::String(s.clone()).to_string(),
    };
    format!("[{}, {}]", one(&p[0]), one(&p[1]))
}

/// What the conversion reads: the parameters and the file's text.
struct Cx<'a> {
    params: &'a HashMap<String, f64>,
    text: &'a str,
    format: Format,
}

impl Cx<'_> {
    fn term(&self, n: &Num, path: &str) -> Result<Term, String> {
        match n {
            Num::Value(v) => Ok(Term::number(*v)),
            Num::Expr(src) => eval::constant(src, self.params)
                .map(|v| Term {
                    src: Some(src.clone()),
                    v,
                })
                .map_err(|e| format!("{path}: {e}")),
        }
    }

    fn pair(&self, v: &Vec2, path: &str) -> Result<[Term; 2], String> {
        Ok([
            self.term(&v.0[0], &format!("{path}[0]"))?,
            self.term(&v.0[1], &format!("{path}[1]"))?,
        ])
    }

    /// Key and value spans of the field at `path`.
    fn entry(&self, path: &str) -> Result<(Range<usize>, Range<usize>), String> {
        match self.format {
            Format::Toml => locate::toml_entry(self.text, path),
            Format::Json => locate::json_entry(self.text, path),
        }
        .ok_or_else(|| format!("{path}: not found in the text"))
    }

    fn value_span(&self, path: &str) -> Result<Range<usize>, String> {
        match self.format {
            Format::Toml => locate::toml_span(self.text, path),
            Format::Json => locate::json_span(self.text, path),
        }
        .ok_or_else(|| format!("{path}: not found in the text"))
    }

    /// The body's frame as the loader places it.
    fn frame(&self, b: &BodySpec, path: &str) -> Result<Frame, String> {
        let angle = match &b.angle {
            Some(n) => self.term(n, &format!("{path}.angle"))?.v,
            None => 0.0,
        };
        let origin = match &b.position {
            Some(v) => self.pair(v, &format!("{path}.position"))?,
            None if !b.global_points.is_empty() => {
                // The mean of the global points, as the loader takes it,
                // written exactly so that the frame stays the same.
                let mut sum = [0.0; 2];
                for (name, v) in &b.global_points {
                    let r = self.pair(v, &format!("{path}.global_points.{name}"))?;
                    sum = [sum[0] + r[0].v, sum[1] + r[1].v];
                }
                let n = b.global_points.len() as f64;
                [Term::number(sum[0] / n), Term::number(sum[1] / n)]
            }
            None => [Term::number(0.0), Term::number(0.0)],
        };
        Ok(Frame {
            origin,
            angle,
            implicit: b.position.is_none(),
        })
    }

    /// A position written for the body, converted: r = r₀ + A(φ₀) s′ to
    /// global form, s′ = A(φ₀)ᵀ (r − r₀) to frame form.
    fn map(&self, f: &Frame, p: &[Term; 2], to: Form) -> [Term; 2] {
        let o = &f.origin;
        if f.angle == 0.0 {
            let minus = to == Form::Frame;
            return [
                if minus {
                    Term::combine(&p[0], &o[0], true)
                } else {
                    Term::combine(&o[0], &p[0], false)
                },
                if minus {
                    Term::combine(&p[1], &o[1], true)
                } else {
                    Term::combine(&o[1], &p[1], false)
                },
            ];
        }
        let (v, o): (V2, V2) = ([p[0].v, p[1].v], [o[0].v, o[1].v]);
        let r = match to {
            Form::Global => camlink_core::math::point([o[0], o[1], f.angle], v),
            Form::Frame => rot(-f.angle, [v[0] - o[0], v[1] - o[1]]),
        };
        let size = o[0].abs() + o[1].abs() + v[0].abs() + v[1].abs();
        let err = 2.0 * f64::EPSILON * size;
        [
            Term::number(clean(r[0], err)),
            Term::number(clean(r[1], err)),
        ]
    }

    /// The edits of one body: its points table renamed and converted, its
    /// position written where the default would change, its centroid and
    /// outline corners converted.
    fn body_edits(
        &self,
        b: &BodySpec,
        path: &str,
        f: &Frame,
        to: Form,
        edits: &mut Vec<Edit>,
    ) -> Result<(), String> {
        let (from_key, to_key, points) = match to {
            Form::Global => ("points", "global_points", &b.points),
            Form::Frame => ("global_points", "points", &b.global_points),
        };
        let (key, _) = self.entry(&format!("{path}.{from_key}"))?;
        let quoted = self.text[key.clone()].starts_with('"');
        edits.push(Edit {
            at: key,
            text: if quoted {
                format!("\"{to_key}\"")
            } else {
                to_key.to_string()
            },
        });
        for (name, v) in points {
            let p = format!("{path}.{from_key}.{name}");
            let (_, at) = self.entry(&p)?;
            edits.push(Edit {
                at,
                text: pair(&self.map(f, &self.pair(v, &p)?, to)),
            });
        }
        // The default origin differs between the forms: write it.
        if f.implicit {
            let (_, name) = self.entry(&format!("{path}.name"))?;
            edits.push(self.insert_after(name, "position", &pair(&f.origin)));
        }
        if let Some(c) = &b.centroid {
            let p = format!("{path}.centroid");
            edits.push(Edit {
                at: self.value_span(&p)?,
                text: pair(&self.map(f, &self.pair(c, &p)?, to)),
            });
        }
        if let Some(OutlineSpec::Polyline(corners)) = &b.outline {
            for (m, c) in corners.iter().enumerate() {
                let p = format!("{path}.outline[{m}]");
                edits.push(Edit {
                    at: self.value_span(&p)?,
                    text: pair(&self.map(f, &self.pair(c, &p)?, to)),
                });
            }
        }
        Ok(())
    }

    /// An insertion of `key = value` after the value at `after` (a key of
    /// the same table): on the next line in a TOML table, after a comma in
    /// an inline table or JSON.
    fn insert_after(&self, after: Range<usize>, key: &str, value: &str) -> Edit {
        let rest = &self.text[after.end..];
        let inline = rest.trim_start_matches([' ', '\t']).starts_with([',', '}']);
        match self.format {
            Format::Json => Edit {
                at: after.end..after.end,
                text: format!(", \"{key}\": {value}"),
            },
            Format::Toml if inline => Edit {
                at: after.end..after.end,
                text: format!(", {key} = {value}"),
            },
            Format::Toml => {
                let end = rest
                    .find('\n')
                    .map_or(self.text.len(), |k| after.end + k + 1);
                let newline = if end == self.text.len() && !self.text.ends_with('\n') {
                    "\n"
                } else {
                    ""
                };
                Edit {
                    at: end..end,
                    text: format!("{newline}{key} = {value}\n"),
                }
            }
        }
    }

    /// The [x, y] points of the converted bodies written in joints,
    /// drivers, forces and curves.
    fn reference_edits(
        &self,
        frames: &HashMap<&str, Frame>,
        to: Form,
        edits: &mut Vec<Edit>,
    ) -> Result<(), String> {
        let tree: serde_json::Value = match self.format {
            Format::Toml => toml::from_str(self.text).map_err(|e| e.to_string())?,
            Format::Json => serde_json::from_str(self.text).map_err(|e| e.to_string())?,
        };
        for section in ["joints", "drivers", "forces", "curves"] {
            let Some(items) = tree.get(section).and_then(|v| v.as_array()) else {
                continue;
            };
            for (k, item) in items.iter().enumerate() {
                for (pk, bk) in POINT_KEYS {
                    let Some(frame) = item
                        .get(bk)
                        .and_then(|b| b.as_str())
                        .and_then(|b| frames.get(b))
                    else {
                        continue;
                    };
                    let Some([x, y]) = item
                        .get(pk)
                        .and_then(|v| v.as_array())
                        .and_then(|a| <&[serde_json::Value; 2]>::try_from(a.as_slice()).ok())
                    else {
                        continue;
                    };
                    let path = format!("{section}[{k}].{pk}");
                    let num = |v: &serde_json::Value| match v {
                        serde_json::Value::String(s) => Ok(Num::Expr(s.clone())),
                        v => v
                            .as_f64()
                            .map(Num::Value)
                            .ok_or_else(|| format!("{path}: not a number")),
                    };
                    let p = self.pair(&Vec2([num(x)?, num(y)?]), &path)?;
                    edits.push(Edit {
                        at: self.value_span(&path)?,
                        text: pair(&self.map(frame, &p, to)),
                    });
                }
            }
        }
        Ok(())
    }
}

/// Checks that two loads describe the same bodies: frames, points and
/// centroids equal to within rounding of the model's size.
fn same_model(a: &Loaded, b: &Loaded) -> Result<(), String> {
    let size = a
        .model
        .bodies
        .iter()
        .flat_map(|b| {
            b.points
                .iter()
                .flat_map(|p| p.s)
                .chain(b.q0[..2].iter().copied())
        })
        .fold(1e-3f64, |m, v| m.max(v.abs()));
    let tol = 1e-12 * size;
    let close = |x: &[f64], y: &[f64]| x.iter().zip(y).all(|(u, v)| (u - v).abs() <= tol);
    if a.model.bodies.len() != b.model.bodies.len() {
        return Err("the number of bodies".into());
    }
    for (p, q) in a.model.bodies.iter().zip(&b.model.bodies) {
        if !close(&p.q0[..2], &q.q0[..2]) || (p.q0[2] - q.q0[2]).abs() > 1e-14 {
            return Err(format!("the frame of body '{}'", p.name));
        }
        if !close(&p.centroid, &q.centroid) {
            return Err(format!("the centroid of body '{}'", p.name));
        }
        if p.points.len() != q.points.len() {
            return Err(format!("the points of body '{}'", p.name));
        }
        for (s, t) in p.points.iter().zip(&q.points) {
            if s.name != t.name || !close(&s.s, &t.s) {
                return Err(format!("point '{}' of body '{}'", s.name, p.name));
            }
        }
    }
    Ok(())
}
