//! From the file structs to a validated core [`Model`] and an [`AnalysisSpec`].
//!
//! Names become body ids and point vectors, numbers and expressions are
//! evaluated with the file's parameters, and defaults that depend on the
//! initial configuration (a coupler's length, a translational joint's angle,
//! a gear's phase) are computed from the bodies' initial coordinates.
//! Every failure carries the field path of the value at fault.

use crate::data_file::DataFiles;
use std::collections::{BTreeMap, HashMap};

use camlink_core::constraint::absolute::{AbsoluteCoord, AbsoluteDistance, Coord};
use camlink_core::constraint::relative::{RelCoord, RelativeCoord, RelativeDistance};
use camlink_core::math::{norm, point, rot, scale, sub, V2};
use camlink_core::{Body, BodyId, Constraint, Model, Point, TimeFn};

use crate::error::did_you_mean;
use crate::eval;
use crate::file::*;
use camlink_core::dynamics::integrator::Adaptive;
use camlink_core::fmt_num::num;

use crate::{AnalysisSpec, DynamicsSpec, Outline, OutlineShape};

mod curves;
mod forces;
mod friction;
mod initial;
pub(crate) mod joints;
mod limits;
mod machine;
pub(crate) use machine::machine;
mod scale;
mod state;

/// A semantic error: the field path and what is wrong.
#[derive(Debug)]
pub(crate) struct Fail {
    pub path: String,
    pub message: String,
}

pub(crate) type R<T> = Result<T, Fail>;

fn fail<T>(path: impl Into<String>, message: impl Into<String>) -> R<T> {
    Err(Fail {
        path: path.into(),
        message: message.into(),
    })
}

/// The time variable of driver expressions, so not a parameter name.
const TIME_VAR: &str = "t";

/// What a driver of a named joint needs to know about that joint.
#[derive(Clone, Debug)]
pub(crate) enum JointInfo {
    Revolute {
        bi: BodyId,
        s_i: V2,
        bj: BodyId,
        s_j: V2,
    },
    Translational {
        bi: BodyId,
        s_i: V2,
        v_i: V2,
        bj: BodyId,
        s_j: V2,
    },
    Other(&'static str),
}

pub(crate) struct Ctx {
    params: HashMap<String, f64>,
    model: Model,
    /// File path of each joint or driver name, for duplicate reports.
    names: HashMap<String, String>,
    joints: HashMap<String, JointInfo>,
    /// Named curves (`[[curves]]`).
    curves: HashMap<String, curves::CurveEntry>,
    /// Where data files resolve, and those read.
    data: DataFiles,
    /// Body ids by name, ground included (a scan per reference is quadratic).
    body_ids: HashMap<String, BodyId>,
    /// Values left out and measured in the placement ([`initial`]).
    deferred: Vec<initial::Deferred>,
    /// Per body id: the initial frame (x, y, φ) of a body given by
    /// `global_points`, whose [x, y] points are global.
    global_frames: Vec<Option<[f64; 3]>>,
    /// The units the file declares, for the data files it reads (its own
    /// values are SI already, [`crate::units::to_si`]).
    units: camlink_core::quantity::Units,
}

/// Builds the model and analysis settings described by `file`, which is
/// in SI ([`crate::units::to_si`]) but for the data files it names, read
/// through `data` in the file's declared `units`.
pub(crate) fn resolve(
    file: &ModelFile,
    default_name: &str,
    data: DataFiles,
) -> R<(Model, AnalysisSpec, Vec<Outline>, DataFiles)> {
    let params = parameters(&file.parameters)?;
    let units = crate::units::declared(file);
    let mut cx = Ctx {
        params,
        model: Model::new(default_name),
        names: HashMap::new(),
        joints: HashMap::new(),
        curves: HashMap::new(),
        data,
        body_ids: HashMap::from([("ground".to_string(), BodyId::GROUND)]),
        deferred: Vec::new(),
        global_frames: vec![None],
        units,
    };
    if let Some(m) = &file.model {
        if let Some(name) = &m.name {
            cx.model.name = name.clone();
        }
        if let Some(g) = &m.gravity {
            cx.model.gravity = cx.vec2(g, "model.gravity")?;
        }
    }
    if let Some(g) = &file.ground {
        cx.model.bodies[0].points = cx.points(&g.points, "ground.points")?;
    }
    cx.bodies(&file.bodies)?;
    for (k, c) in file.curves.iter().enumerate() {
        cx.curve(c, k)?;
    }
    for (k, j) in file.joints.iter().enumerate() {
        cx.joint(j, k)?;
    }
    for (k, d) in file.drivers.iter().enumerate() {
        cx.driver(d, k)?;
    }
    for (k, f) in file.forces.iter().enumerate() {
        cx.force(f, k)?;
    }
    initial::check(&mut cx.model, &cx.deferred);
    scale::check(&mut cx.model);
    let analysis = cx.analysis(file.analysis.as_ref())?;
    let outlines = cx.outlines(&file.bodies)?;
    cx.model.validate().or_else(|e| fail("", e.to_string()))?;
    Ok((cx.model, analysis, outlines, cx.data))
}

/// The frame origin of a body given by `global_points`: the mean of the
/// points (m).
fn frame_origin(points: &[Point]) -> V2 {
    let n = points.len() as f64;
    let sum = points
        .iter()
        .fold([0.0; 2], |a, p| [a[0] + p.s[0], a[1] + p.s[1]]);
    [sum[0] / n, sum[1] / n]
}

/// Evaluates `[parameters]` in dependency order, whatever order the file lists them in.
pub(crate) fn parameters(list: &BTreeMap<String, Num>) -> R<HashMap<String, f64>> {
    for name in list.keys() {
        let path = format!("parameters.{name}");
        if !is_identifier(name) {
            return fail(
                path,
                format!("parameter name '{name}' is not an identifier (letters, digits and _, not starting with a digit)"),
            );
        }
        if name == TIME_VAR {
            return fail(
                path,
                "the name 't' is reserved for time in driver expressions",
            );
        }
    }
    // Each parameter's dependencies: the other parameters its expression reads.
    let names: Vec<&String> = list.keys().collect();
    let index: HashMap<&str, usize> = names
        .iter()
        .enumerate()
        .map(|(k, n)| (n.as_str(), k))
        .collect();
    let mut needs: Vec<Vec<usize>> = vec![Vec::new(); names.len()];
    for (k, value) in list.values().enumerate() {
        if let Num::Expr(src) = value {
            // A malformed expression has no dependencies; evaluating it below
            // reports the fault with its caret.
            for n in camlink_expr::names(src).unwrap_or_default() {
                if let Some(&j) = index.get(n) {
                    needs[k].push(j);
                }
            }
        }
    }
    // Evaluate in dependency order (depth first, iterative): linear in the
    // number of parameters and references.
    let mut state = vec![Visit::New; names.len()];
    let mut done: HashMap<String, f64> = HashMap::with_capacity(names.len());
    let values: Vec<&Num> = list.values().collect();
    for root in 0..names.len() {
        if state[root] != Visit::New {
            continue;
        }
        // Stack of (parameter, next dependency to look at).
        let mut stack = vec![(root, 0usize)];
        state[root] = Visit::Open;
        while let Some(&mut (k, ref mut next)) = stack.last_mut() {
            if let Some(&j) = needs[k].get(*next) {
                *next += 1;
                match state[j] {
                    Visit::New => {
                        state[j] = Visit::Open;
                        stack.push((j, 0));
                    }
                    Visit::Open => {
                        // j is on the stack: the cycle runs from j to k.
                        let from = stack.iter().position(|&(p, _)| p == j).unwrap_or(0);
                        let cycle: Vec<&str> = stack[from..]
                            .iter()
                            .map(|&(p, _)| names[p].as_str())
                            .collect();
                        return fail(
                            format!("parameters.{}", names[j]),
                            format!(
                                "parameters {} refer to each other in a cycle",
                                cycle.join(", ")
                            ),
                        );
                    }
                    Visit::Done => {}
                }
                continue;
            }
            stack.pop();
            state[k] = Visit::Done;
            let name = names[k];
            let v = match values[k] {
                Num::Value(v) => *v,
                Num::Expr(src) => match eval::constant(src, &done) {
                    Ok(v) => v,
                    Err(e) => return fail(format!("parameters.{name}"), e),
                },
            };
            if !v.is_finite() {
                return fail(
                    format!("parameters.{name}"),
                    format!("value is not a finite number ({})", num(v)),
                );
            }
            done.insert(name.clone(), v);
        }
    }
    Ok(done)
}

/// Where a parameter stands in the depth-first ordering of [`parameters`].
#[derive(Clone, Copy, PartialEq)]
enum Visit {
    New,
    Open,
    Done,
}

fn is_identifier(s: &str) -> bool {
    let mut c = s.chars();
    matches!(c.next(), Some(ch) if ch.is_ascii_alphabetic() || ch == '_')
        && c.all(|ch| ch.is_ascii_alphanumeric() || ch == '_')
}

/// Checks a body, point, curve, joint or force name: letters (any
/// script), digits, `_` and `-`, not starting with `-`. Names become output
/// channels, so this keeps CSV headers whole (no `,` or quotes), keeps
/// spreadsheets from reading a name as a formula (`=`, `+`, `-`, `@`),
/// keeps `.` for `body.point`, and keeps control characters and
/// bidirectional overrides out of terminals.
fn check_name(name: &str, what: &str, path: &str) -> R<()> {
    if name.trim().is_empty() {
        return fail(path, format!("{what} name is empty"));
    }
    let bad = name
        .chars()
        .find(|&c| !(c.is_alphanumeric() || c == '_' || c == '-'));
    if let Some(c) = bad {
        let shown = if c.is_ascii_graphic() {
            c.to_string()
        } else {
            c.escape_unicode().to_string()
        };
        return fail(
            path,
            format!(
                "{what} name '{name}' may contain only letters, digits, '_' and '-' \
                 (found '{shown}')"
            ),
        );
    }
    if name.starts_with('-') {
        return fail(path, format!("{what} name '{name}' may not start with '-'"));
    }
    Ok(())
}

impl Ctx {
    /// A constant number: a value or a constant expression.
    fn num(&self, n: &Num, path: &str) -> R<f64> {
        let v = match n {
            Num::Value(v) => *v,
            Num::Expr(src) => match eval::constant(src, &self.params) {
                Ok(v) => v,
                Err(e) => return fail(path, e),
            },
        };
        if !v.is_finite() {
            return fail(path, format!("value is not a finite number ({})", num(v)));
        }
        Ok(v)
    }

    fn opt(&self, n: Option<&Num>, default: f64, path: &str) -> R<f64> {
        n.map_or(Ok(default), |n| self.num(n, path))
    }

    /// The run setting `analysis.<key>`, if given, checked by the rule every
    /// way of giving it shares ([`camlink_core::setting`]).
    fn setting(&self, n: Option<&Num>, key: &str) -> R<Option<f64>> {
        let path = format!("analysis.{key}");
        let Some(n) = n else { return Ok(None) };
        let v = self.num(n, &path)?;
        camlink_core::setting::check(key, v).or_else(|e| fail(path, e))?;
        Ok(Some(v))
    }

    fn vec2(&self, v: &Vec2, path: &str) -> R<V2> {
        Ok([
            self.num(&v.0[0], &format!("{path}[0]"))?,
            self.num(&v.0[1], &format!("{path}[1]"))?,
        ])
    }

    /// A unit vector from a direction; zero length is an error.
    fn axis(&self, v: &Vec2, path: &str) -> R<V2> {
        let a = self.vec2(v, path)?;
        let n = norm(a);
        if n <= f64::MIN_POSITIVE || !n.is_finite() {
            return fail(path, "axis has zero length");
        }
        Ok(scale(1.0 / n, a))
    }

    fn points(&self, pts: &BTreeMap<String, Vec2>, path: &str) -> R<Vec<Point>> {
        pts.iter()
            .map(|(name, v)| {
                let p = format!("{path}.{name}");
                check_name(name, "point", &p)?;
                Ok(Point {
                    name: name.clone(),
                    s: self.vec2(v, &p)?,
                })
            })
            .collect()
    }

    fn bodies(&mut self, bodies: &[BodySpec]) -> R<()> {
        let mut seen: HashMap<&str, usize> = HashMap::new();
        for (k, b) in bodies.iter().enumerate() {
            let path = format!("bodies[{k}]");
            check_name(&b.name, "body", &format!("{path}.name"))?;
            if let Some(e) = camlink_core::model::reserved_name(&b.name, "body") {
                return fail(format!("{path}.name"), e);
            }
            if b.name == "ground" {
                return fail(
                    format!("{path}.name"),
                    "'ground' is the implicit fixed body; declare its points in [ground] points",
                );
            }
            if let Some(first) = seen.insert(&b.name, k) {
                return fail(
                    format!("{path}.name"),
                    format!("duplicate body name '{}' (also bodies[{first}])", b.name),
                );
            }
            let global = !b.global_points.is_empty();
            if global && !b.points.is_empty() {
                return fail(
                    format!("{path}.global_points"),
                    "give the body's points either in its frame (`points`) or in the global frame (`global_points`), not both",
                );
            }
            let global_points = self.points(&b.global_points, &format!("{path}.global_points"))?;
            let pos = match &b.position {
                Some(v) => self.vec2(v, &format!("{path}.position"))?,
                None if global => frame_origin(&global_points),
                None => [0.0; 2],
            };
            let angle = self.opt(b.angle.as_ref(), 0.0, &format!("{path}.angle"))?;
            // A global point r at the initial instant is s' = Aᵀ (r − r₀) in the frame.
            let local = |r: V2| {
                if global {
                    rot(-angle, sub(r, pos))
                } else {
                    r
                }
            };
            let vel = match &b.velocity {
                Some(v) => self.vec2(v, &format!("{path}.velocity"))?,
                None => [0.0; 2],
            };
            let mass = self.opt(b.mass.as_ref(), 0.0, &format!("{path}.mass"))?;
            if mass < 0.0 {
                return fail(
                    format!("{path}.mass"),
                    format!("mass must not be negative ({mass} kg)"),
                );
            }
            let inertia = self.opt(b.inertia.as_ref(), 0.0, &format!("{path}.inertia"))?;
            if inertia < 0.0 {
                return fail(
                    format!("{path}.inertia"),
                    format!("inertia must not be negative ({inertia} kg·m²)"),
                );
            }
            let body = Body {
                name: b.name.clone(),
                mass,
                inertia,
                centroid: match &b.centroid {
                    Some(v) => local(self.vec2(v, &format!("{path}.centroid"))?),
                    None => [0.0; 2],
                },
                q0: [pos[0], pos[1], angle],
                qd0: [
                    vel[0],
                    vel[1],
                    self.opt(b.omega.as_ref(), 0.0, &format!("{path}.omega"))?,
                ],
                points: if global {
                    global_points
                        .into_iter()
                        .map(|p| Point {
                            s: local(p.s),
                            name: p.name,
                        })
                        .collect()
                } else {
                    self.points(&b.points, &format!("{path}.points"))?
                },
            };
            let id = self.model.add_body(body);
            self.body_ids.insert(b.name.clone(), id);
            self.global_frames
                .push(global.then_some([pos[0], pos[1], angle]));
        }
        if bodies.is_empty() {
            return fail(
                "bodies",
                "the model has no moving bodies; add at least one [[bodies]] entry",
            );
        }
        Ok(())
    }

    /// The bodies' `outline`s: polylines evaluated, curve names looked up
    /// among the closed curves of the same body.
    fn outlines(&self, bodies: &[BodySpec]) -> R<Vec<Outline>> {
        let mut out = Vec::new();
        for (k, b) in bodies.iter().enumerate() {
            let path = format!("bodies[{k}].outline");
            let shape = match &b.outline {
                None => continue,
                Some(OutlineSpec::Polyline(corners)) => {
                    if corners.len() < 3 {
                        return fail(
                            path,
                            format!(
                                "an outline needs at least three corners, got {}",
                                corners.len()
                            ),
                        );
                    }
                    let id = self.body_ids[&b.name];
                    let pts = corners
                        .iter()
                        .enumerate()
                        .map(|(n, v)| Ok(self.local(id, self.vec2(v, &format!("{path}[{n}]"))?)))
                        .collect::<R<Vec<V2>>>()?;
                    OutlineShape::Polyline(pts)
                }
                Some(OutlineSpec::Curve(name)) => {
                    let Some(entry) = self.curves.get(name) else {
                        return fail(
                            path,
                            format!(
                                "no curve named '{name}'{}",
                                did_you_mean(name, self.curves.keys().map(String::as_str))
                            ),
                        );
                    };
                    if self.model.body(entry.body).name != b.name {
                        return fail(
                            path,
                            format!(
                                "curve '{name}' is on body '{}', not on '{}'",
                                self.model.body(entry.body).name,
                                b.name
                            ),
                        );
                    }
                    if !entry.curve.closed() {
                        return fail(
                            path,
                            format!("curve '{name}' is open; an outline must be closed"),
                        );
                    }
                    OutlineShape::Curve(entry.curve.clone())
                }
            };
            out.push(Outline {
                body: b.name.clone(),
                shape,
            });
        }
        Ok(out)
    }

    /// Resolves a body name.
    fn body(&self, name: &str, path: &str) -> R<BodyId> {
        match self.body_ids.get(name) {
            Some(&id) => Ok(id),
            None => fail(
                path,
                format!(
                    "no body named '{name}'{}",
                    did_you_mean(name, self.model.bodies.iter().map(|b| b.name.as_str()))
                ),
            ),
        }
    }

    /// A point [x, y] as written for `body`, in its frame: as is, or, for
    /// a body given by `global_points`, from its global position at the
    /// initial instant.
    fn local(&self, body: BodyId, r: V2) -> V2 {
        match self.global_frames.get(body.0).copied().flatten() {
            Some([x, y, phi]) => rot(-phi, sub(r, [x, y])),
            None => r,
        }
    }

    /// Resolves a point of `body`; `None` is the body origin.
    fn point(&self, body: BodyId, p: Option<&PointRef>, path: &str) -> R<V2> {
        match p {
            None => Ok([0.0; 2]),
            Some(PointRef::Inline(v)) => Ok(self.local(body, self.vec2(v, path)?)),
            Some(PointRef::Name(name)) => {
                let b = self.model.body(body);
                if let Some(s) = b.point(name) {
                    return Ok(s);
                }
                let hint = if b.points.is_empty() {
                    " (it declares no points; add it to the body's points or give [x, y])"
                        .to_string()
                } else {
                    did_you_mean(name, b.points.iter().map(|p| p.name.as_str()))
                };
                fail(
                    path,
                    format!("body '{}' has no point named '{name}'{hint}", b.name),
                )
            }
        }
    }

    /// Body id and local point, from a name field and a point field.
    fn at(
        &self,
        body: &str,
        p: Option<&PointRef>,
        path: &str,
        bf: &str,
        pf: &str,
    ) -> R<(BodyId, V2)> {
        let id = self.body(body, &format!("{path}.{bf}"))?;
        Ok((id, self.point(id, p, &format!("{path}.{pf}"))?))
    }

    fn q0(&self, b: BodyId) -> [f64; 3] {
        self.model.body(b).q0
    }

    /// Initial global position of a body point (m).
    fn r0(&self, b: BodyId, s: V2) -> V2 {
        point(self.q0(b), s)
    }

    /// Registers a joint or driver name, rejecting duplicates.
    fn name(&mut self, given: Option<&String>, default: String, path: &str) -> R<String> {
        let name = given.cloned().unwrap_or(default);
        check_name(&name, "joint", &format!("{path}.name"))?;
        let what = if path.starts_with("drivers") {
            "driver"
        } else {
            "joint"
        };
        if let Some(e) = camlink_core::model::reserved_name(&name, what) {
            return fail(format!("{path}.name"), e);
        }
        if let Some(first) = self.names.insert(name.clone(), path.to_string()) {
            return fail(
                format!("{path}.name"),
                format!("duplicate joint or driver name '{name}' (also {first})"),
            );
        }
        Ok(name)
    }

    /// Records that `key` of the joint just added (`path` its field) was
    /// left out and measured in the placement ([`initial`]), if `left_out`.
    fn defer_joint(&mut self, left_out: bool, path: &str, key: &'static str, unit: &'static str) {
        if !left_out {
            return;
        }
        let j = self.model.joints.len() - 1;
        self.deferred.push(initial::Deferred {
            quantity: initial::Quantity::Joint(j),
            field: format!("{path}.{key}"),
            owner: format!("joint '{}'", self.model.joints[j].name),
            key,
            unit,
        });
    }

    fn add(&mut self, name: String, c: impl Into<Constraint>, driver: bool) {
        if driver {
            self.model.add_driver(name, c);
        } else {
            self.model.add_joint(name, c);
        }
    }

    fn time_fn(&self, f: &Num, path: &str) -> R<TimeFn> {
        match f {
            Num::Value(v) if v.is_finite() => Ok(TimeFn::Const(*v)),
            Num::Value(v) => fail(path, format!("value is not a finite number ({})", num(*v))),
            Num::Expr(src) => eval::time_fn(src, &self.params).or_else(|e| fail(path, e)),
        }
    }

    fn positive(&self, n: &Num, path: &str, what: &str) -> R<f64> {
        let v = self.num(n, path)?;
        if v <= 0.0 {
            return fail(path, format!("{what} must be positive ({} m)", num(v)));
        }
        Ok(v)
    }

    /// Body i and its point (`body_i`, `point_i`) and body j and its point
    /// (`body_j`, `point_j`) of the joint at `path`, two different bodies.
    fn two_bodies(
        &self,
        body_i: &str,
        point_i: Option<&PointRef>,
        body_j: &str,
        point_j: Option<&PointRef>,
        path: &str,
    ) -> R<((BodyId, V2), (BodyId, V2))> {
        let i = self.at(body_i, point_i, path, "body_i", "point_i")?;
        let j = self.at(body_j, point_j, path, "body_j", "point_j")?;
        self.distinct(i.0, j.0, path)?;
        Ok((i, j))
    }

    fn distinct(&self, bi: BodyId, bj: BodyId, path: &str) -> R<()> {
        if bi == bj {
            return fail(
                format!("{path}.body_j"),
                format!(
                    "body_i and body_j are both '{}'; a joint needs two different bodies",
                    self.model.body(bi).name
                ),
            );
        }
        Ok(())
    }

    fn moving(&self, b: BodyId, path: &str) -> R<()> {
        if b.is_ground() {
            return fail(path, "this constraint needs a moving body, not the ground");
        }
        Ok(())
    }

    fn driver(&mut self, d: &DriverSpec, k: usize) -> R<()> {
        let path = format!("drivers[{k}]");
        let p = path.as_str();
        let fp = format!("{p}.f");
        let c: (String, Constraint) = match d {
            DriverSpec::AbsoluteX(a) | DriverSpec::AbsoluteY(a) => {
                let (kind, coord) = match d {
                    DriverSpec::AbsoluteX(_) => ("absolute_x", Coord::X),
                    _ => ("absolute_y", Coord::Y),
                };
                let name = self.name(a.name.as_ref(), format!("{kind}_driver_{k}"), p)?;
                let (b, s) = self.at(&a.body, a.point.as_ref(), p, "body", "point")?;
                self.moving(b, &format!("{p}.body"))?;
                let f = self.time_fn(&a.f, &fp)?;
                (
                    name,
                    AbsoluteCoord {
                        body: b,
                        s,
                        coord,
                        f,
                    }
                    .into(),
                )
            }
            DriverSpec::AbsolutePhi(a) => {
                let name = self.name(a.name.as_ref(), format!("absolute_phi_driver_{k}"), p)?;
                let b = self.body(&a.body, &format!("{p}.body"))?;
                self.moving(b, &format!("{p}.body"))?;
                let f = self.time_fn(&a.f, &fp)?;
                (
                    name,
                    AbsoluteCoord {
                        body: b,
                        s: [0.0; 2],
                        coord: Coord::Phi,
                        f,
                    }
                    .into(),
                )
            }
            DriverSpec::AbsoluteDistance(a) => {
                let name =
                    self.name(a.name.as_ref(), format!("absolute_distance_driver_{k}"), p)?;
                let (b, s) = self.at(&a.body, a.point.as_ref(), p, "body", "point")?;
                self.moving(b, &format!("{p}.body"))?;
                let c0 = self.point(
                    BodyId::GROUND,
                    Some(&a.ground_point),
                    &format!("{p}.ground_point"),
                )?;
                let f = self.time_fn(&a.f, &fp)?;
                (
                    name,
                    AbsoluteDistance {
                        body: b,
                        s,
                        ground_point: c0,
                        f,
                    }
                    .into(),
                )
            }
            DriverSpec::RelativeX(r)
            | DriverSpec::RelativeY(r)
            | DriverSpec::RelativeDistance(r) => {
                let kind = match d {
                    DriverSpec::RelativeX(_) => "relative_x",
                    DriverSpec::RelativeY(_) => "relative_y",
                    _ => "relative_distance",
                };
                let name = self.name(r.name.as_ref(), format!("{kind}_driver_{k}"), p)?;
                let (bi, s_i) = self.at(&r.body_i, r.point_i.as_ref(), p, "body_i", "point_i")?;
                let (bj, s_j) = self.at(&r.body_j, r.point_j.as_ref(), p, "body_j", "point_j")?;
                self.distinct(bi, bj, p)?;
                let f = self.time_fn(&r.f, &fp)?;
                let c: Constraint = match kind {
                    "relative_x" => RelativeCoord {
                        body_i: bi,
                        s_i,
                        body_j: bj,
                        s_j,
                        coord: RelCoord::X,
                        f,
                    }
                    .into(),
                    "relative_y" => RelativeCoord {
                        body_i: bi,
                        s_i,
                        body_j: bj,
                        s_j,
                        coord: RelCoord::Y,
                        f,
                    }
                    .into(),
                    _ => RelativeDistance {
                        body_i: bi,
                        s_i,
                        body_j: bj,
                        s_j,
                        f,
                    }
                    .into(),
                };
                (name, c)
            }
            DriverSpec::RelativePhi(r) => {
                let name = self.name(r.name.as_ref(), format!("relative_phi_driver_{k}"), p)?;
                let bi = self.body(&r.body_i, &format!("{p}.body_i"))?;
                let bj = self.body(&r.body_j, &format!("{p}.body_j"))?;
                self.distinct(bi, bj, p)?;
                let f = self.time_fn(&r.f, &fp)?;
                let c = RelativeCoord {
                    body_i: bi,
                    s_i: [0.0; 2],
                    body_j: bj,
                    s_j: [0.0; 2],
                    coord: RelCoord::Phi,
                    f,
                };
                (name, c.into())
            }
            DriverSpec::CurveTravel(jd) => return self.curve_travel(jd, k),
            DriverSpec::RevoluteAngle(jd) | DriverSpec::TranslationalTravel(jd) => {
                let want = if matches!(d, DriverSpec::RevoluteAngle(_)) {
                    "revolute"
                } else {
                    "translational"
                };
                let kind = format!(
                    "{}_driver_{k}",
                    if want == "revolute" {
                        "revolute_angle"
                    } else {
                        "translational_travel"
                    }
                );
                let name = self.name(jd.name.as_ref(), kind, p)?;
                let jp = format!("{p}.joint");
                let Some(info) = self.joints.get(&jd.joint).cloned() else {
                    return fail(
                        jp,
                        format!(
                            "no joint named '{}'{}",
                            jd.joint,
                            did_you_mean(&jd.joint, self.joints.keys().map(String::as_str))
                        ),
                    );
                };
                let f = self.time_fn(&jd.f, &fp)?;
                let c = match (want, info) {
                    ("revolute", JointInfo::Revolute { bi, s_i, bj, s_j }) => RelativeCoord {
                        body_i: bi,
                        s_i,
                        body_j: bj,
                        s_j,
                        coord: RelCoord::Phi,
                        f,
                    },
                    (
                        "translational",
                        JointInfo::Translational {
                            bi,
                            s_i,
                            v_i,
                            bj,
                            s_j,
                        },
                    ) => RelativeCoord {
                        body_i: bi,
                        s_i,
                        body_j: bj,
                        s_j,
                        coord: RelCoord::Along(v_i),
                        f,
                    },
                    (_, other) => {
                        let is = match other {
                            JointInfo::Revolute { .. } => "revolute",
                            JointInfo::Translational { .. } => "translational",
                            JointInfo::Other(kind) => kind,
                        };
                        let ty = if want == "revolute" {
                            "revolute_angle"
                        } else {
                            "translational_travel"
                        };
                        return fail(
                            jp,
                            format!("joint '{}' is a {is} joint, but a {ty} driver needs a {want} joint", jd.joint),
                        );
                    }
                };
                (name, c.into())
            }
        };
        self.add(c.0, c.1, true);
        Ok(())
    }

    fn analysis(&self, a: Option<&AnalysisSection>) -> R<AnalysisSpec> {
        let Some(a) = a else {
            return Ok(AnalysisSpec::default());
        };
        let kind = a.kind.unwrap_or_default();
        // Keys that only some analyses take (crate::analysis).
        let adaptive = kind == AnalysisType::Dynamics && a.adaptive == Some(true);
        let given = [
            ("t_end", a.t_end.is_some()),
            ("step", a.step.is_some()),
            ("times", a.times.is_some()),
            ("time", a.time.is_some()),
            ("h", a.h.is_some()),
            ("rho_inf", a.rho_inf.is_some()),
            ("adaptive", a.adaptive.is_some()),
            ("projection_tol", a.projection_tol.is_some()),
            ("atol", a.atol.is_some()),
            ("rtol", a.rtol.is_some()),
            ("h_min", a.h_min.is_some()),
        ];
        for (key, _) in given.into_iter().filter(|&(_, given)| given) {
            let message = if !kind.takes(key) {
                crate::not_applicable(key, &format!("type = \"{}\"", kind.name()))
            } else if crate::ERROR_CONTROL.contains(&key) && !adaptive {
                crate::needs_adaptive(key)
            } else {
                continue;
            };
            return fail(format!("analysis.{key}"), message);
        }
        let t_end = self.setting(a.t_end.as_ref(), "t_end")?;
        let step = self.setting(a.step.as_ref(), "step")?;
        let times = match &a.times {
            Some(list) => {
                if t_end.is_some() || step.is_some() {
                    return fail(
                        "analysis.times",
                        "give either times or t_end/step, not both",
                    );
                }
                let mut out = Vec::with_capacity(list.len());
                for (k, n) in list.iter().enumerate() {
                    out.push(self.num(n, &format!("analysis.times[{k}]"))?);
                }
                if let Err((k, e)) = camlink_core::run::check_times(&out) {
                    let field = if out.is_empty() {
                        "analysis.times".to_string()
                    } else {
                        format!("analysis.times[{k}]")
                    };
                    return fail(field, e);
                }
                Some(out)
            }
            None => None,
        };
        let tol = self
            .setting(a.tol.as_ref(), "tol")?
            .unwrap_or(AnalysisSpec::default_tol(kind));
        if let Some(m) = a.max_iter {
            camlink_core::setting::check("max_iter", f64::from(m))
                .or_else(|e| fail("analysis.max_iter", e))?;
        }
        let max_iter = a
            .max_iter
            .map_or(AnalysisSpec::default_max_iter(kind), |m| m as usize);
        let time = self.setting(a.time.as_ref(), "time")?.unwrap_or(0.0);
        let dynamics = self.dynamics_spec(a)?;
        let jerk = a.jerk.unwrap_or(false);
        if jerk && kind != AnalysisType::Kinematics {
            return fail(
                "analysis.jerk",
                format!(
                    "jerk is an option of kinematic analysis (type = \"kinematics\"), not of \"{}\"",
                    kind.name()
                ),
            );
        }
        for (k, name) in a.points.iter().enumerate() {
            let path = format!("analysis.points[{k}]");
            if let Some(first) = a.points[..k].iter().position(|n| n == name) {
                return fail(
                    path,
                    format!("'{name}' is listed twice (also analysis.points[{first}])"),
                );
            }
            let Some((b, pt)) = name.split_once('.') else {
                return fail(path, format!("expected \"body.point\", found '{name}'"));
            };
            let id = self.body(b, &path)?;
            self.point(id, Some(&PointRef::Name(pt.to_string())), &path)?;
        }
        Ok(AnalysisSpec {
            kind,
            t_end,
            step,
            times,
            time,
            tol,
            max_iter,
            tol_set: a.tol.is_some(),
            max_iter_set: a.max_iter.is_some(),
            points: a.points.clone(),
            jerk,
            dynamics,
        })
    }

    /// The integrator keys of `[analysis]`, checked; defaults for the rest.
    fn dynamics_spec(&self, a: &AnalysisSection) -> R<DynamicsSpec> {
        let d = DynamicsSpec::default();
        let positive = |n: Option<&Num>, default: Option<f64>, key: &str| -> R<Option<f64>> {
            Ok(self.setting(n, key)?.or(default))
        };
        let h = positive(a.h.as_ref(), None, "h")?;
        let projection_tol = positive(
            a.projection_tol.as_ref(),
            Some(d.projection_tol),
            "projection_tol",
        )?
        .unwrap_or(d.projection_tol);
        let rho_inf = self
            .setting(a.rho_inf.as_ref(), "rho_inf")?
            .unwrap_or(d.rho_inf);
        let adaptive = if a.adaptive == Some(true) {
            let mut tols = [0.0; 2];
            for (k, (n, default, key)) in [
                (a.atol.as_ref(), DynamicsSpec::DEFAULT_ATOL, "atol"),
                (a.rtol.as_ref(), DynamicsSpec::DEFAULT_RTOL, "rtol"),
            ]
            .into_iter()
            .enumerate()
            {
                tols[k] = self.setting(n, key)?.unwrap_or(default);
            }
            if let Err(e) = camlink_core::setting::check_error_control(tols[0], tols[1]) {
                return fail("analysis.atol", e);
            }
            let h_min = positive(a.h_min.as_ref(), Some(DynamicsSpec::DEFAULT_H_MIN), "h_min")?
                .unwrap_or(DynamicsSpec::DEFAULT_H_MIN);
            Some(Adaptive {
                atol: tols[0],
                rtol: tols[1],
                h_min,
            })
        } else {
            None
        };
        Ok(DynamicsSpec {
            h,
            rho_inf,
            projection_tol,
            adaptive,
        })
    }
}
