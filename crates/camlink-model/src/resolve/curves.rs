//! `[[curves]]`, the curve-contact joints and the `curve_travel` driver.
//!
//! A curve is built on its body from its `source`; joints then name curves
//! (a curve's body is the joint's body). Contact parameters the file gives
//! are starting guesses: the joint refines them at assembly. Given only one
//! of a cam–follower's two, the other is the point of the second curve
//! nearest the first curve's point.

use std::sync::Arc;

use camlink_core::cam::{Cam, Follower, LawKind, MotionError, Program, SegmentSpec};
use camlink_core::constraint::{Constraint, MAX_OWN};
use camlink_core::curve::{read_points_csv, search, Curve, Parametric, Polar, Radius};
use camlink_core::fmt_num::num;
use camlink_core::force::compliant_contact::HuntCrossley;
use camlink_core::math::{rot_t, sub, V2};
use camlink_core::model::Unilateral;
use camlink_core::BodyId;

use super::{check_name, fail, Ctx, JointInfo, R};
use crate::error::did_you_mean;
use crate::eval;
use crate::file::*;

/// Samples on which a new curve is checked (finite, non-zero tangent, ρ > 0).
const CHECK_SAMPLES: usize = 720;

/// A resolved `[[curves]]` entry.
#[derive(Clone, Debug)]
pub(super) struct CurveEntry {
    pub body: BodyId,
    pub curve: Curve,
}

impl CurveSpec {
    fn name_body(&self) -> (&str, &str) {
        match self {
            CurveSpec::Circle { name, body, .. }
            | CurveSpec::Line { name, body, .. }
            | CurveSpec::Arc { name, body, .. }
            | CurveSpec::Expression { name, body, .. }
            | CurveSpec::Fourier { name, body, .. }
            | CurveSpec::Spline { name, body, .. }
            | CurveSpec::Motion { name, body, .. } => (name, body),
        }
    }
}

/// The keys of a unilateral law, in the order [`Ctx::unilateral_law`] reads them.
const UNILATERAL_KEYS: [&str; 6] = [
    "restitution",
    "rest_speed",
    "event_tol",
    "stiffness",
    "exponent",
    "damping",
];

impl Ctx {
    /// Builds `curves[k]` on its body.
    pub(super) fn curve(&mut self, c: &CurveSpec, k: usize) -> R<()> {
        let path = format!("curves[{k}]");
        let (name, body) = c.name_body();
        check_name(name, "curve", &format!("{path}.name"))?;
        if self.curves.contains_key(name) {
            return fail(
                format!("{path}.name"),
                format!("duplicate curve name '{name}'"),
            );
        }
        let b = self.body(body, &format!("{path}.body"))?;
        let curve = self.build_curve(c, b, &path)?;
        if let Err(e) = curve.check(CHECK_SAMPLES) {
            return fail(path, format!("curve '{name}': {e}"));
        }
        if let CurveSpec::Motion { base_radius, .. } = c {
            let field = format!("{path}.base_radius");
            let rb = self.num(base_radius, &field)?;
            if let Some(question) = camlink_core::cam::base_radius_question(rb) {
                self.model.warnings.push(camlink_core::ModelWarning {
                    kind: super::scale::KIND,
                    field,
                    message: format!(
                        "{question} (lengths are in metres unless [model] units says otherwise)"
                    ),
                });
            }
        }
        self.curves
            .insert(name.to_string(), CurveEntry { body: b, curve });
        Ok(())
    }

    fn build_curve(&self, c: &CurveSpec, b: BodyId, p: &str) -> R<Curve> {
        let centre = |c: &Option<PointRef>| self.point(b, c.as_ref(), &format!("{p}.centre"));
        let bad = |field: &str, e: camlink_core::curve::CurveError| {
            fail::<Curve>(format!("{p}.{field}"), e.to_string())
        };
        match c {
            CurveSpec::Circle {
                kind,
                centre: cen,
                radius,
                start,
                ..
            } => {
                let q = centre(cen)?;
                let r = self.positive(radius, &format!("{p}.radius"), "radius")?;
                match kind.unwrap_or(CurveKind::Polar) {
                    CurveKind::Polar => {
                        if start.is_some() {
                            return fail(
                                format!("{p}.start"),
                                "`start` applies to a parametric circle; a polar circle's parameter is the angle α itself",
                            );
                        }
                        Polar::circle(q, r)
                            .map(Into::into)
                            .or_else(|e| bad("radius", e))
                    }
                    CurveKind::Parametric => {
                        let s = self.opt(start.as_ref(), 0.0, &format!("{p}.start"))?;
                        Parametric::circle(q, r, s)
                            .map(Into::into)
                            .or_else(|e| bad("radius", e))
                    }
                }
            }
            CurveSpec::Line { from, to, .. } => {
                let a = self.point(b, Some(from), &format!("{p}.from"))?;
                let z = self.point(b, Some(to), &format!("{p}.to"))?;
                Parametric::line(a, z)
                    .map(Into::into)
                    .or_else(|e| bad("to", e))
            }
            CurveSpec::Arc {
                centre: cen,
                radius,
                start,
                end,
                ..
            } => {
                let q = centre(cen)?;
                let r = self.positive(radius, &format!("{p}.radius"), "radius")?;
                let s = self.num(start, &format!("{p}.start"))?;
                let e = self.num(end, &format!("{p}.end"))?;
                Parametric::arc(q, r, s, e)
                    .map(Into::into)
                    .or_else(|err| bad("end", err))
            }
            CurveSpec::Expression {
                kind,
                centre: cen,
                rho,
                x,
                y,
                range,
                closed,
                ..
            } => {
                let inferred = match (rho.is_some(), x.is_some() || y.is_some()) {
                    (true, false) => CurveKind::Polar,
                    (false, true) => CurveKind::Parametric,
                    (true, true) => {
                        return fail(
                            format!("{p}.rho"),
                            "give either `rho` (a polar profile) or `x` and `y` (a parametric curve), not both",
                        )
                    }
                    (false, false) => {
                        return fail(
                            p,
                            "an expression curve needs `rho` (a polar profile ρ(a)) or `x` and `y` (a parametric curve in s)",
                        )
                    }
                };
                if let Some(k) = kind.filter(|k| *k != inferred) {
                    let want = match k {
                        CurveKind::Polar => "a polar expression curve needs `rho`",
                        CurveKind::Parametric => "a parametric expression curve needs `x` and `y`",
                    };
                    return fail(format!("{p}.kind"), want);
                }
                match inferred {
                    CurveKind::Polar => {
                        for (key, given) in
                            [("range", range.is_some()), ("closed", closed.is_some())]
                        {
                            if given {
                                return fail(
                                    format!("{p}.{key}"),
                                    format!("`{key}` applies to a parametric curve; a polar profile is closed, with α in [0, 2π)"),
                                );
                            }
                        }
                        let src = rho.as_deref().unwrap_or_default();
                        let e = eval::function_of(src, "a", &self.params)
                            .or_else(|m| fail(format!("{p}.rho"), m))?;
                        Ok(Polar {
                            q: centre(cen)?,
                            rho: Radius::Expr(Arc::new(e)),
                        }
                        .into())
                    }
                    CurveKind::Parametric => {
                        if cen.is_some() {
                            return fail(
                                format!("{p}.centre"),
                                "`centre` applies to a polar profile; write the offset into x and y",
                            );
                        }
                        let (Some(xs), Some(ys)) = (x, y) else {
                            let missing = if x.is_none() { "x" } else { "y" };
                            return fail(
                                p,
                                format!("a parametric expression curve needs both `x` and `y`; `{missing}` is missing"),
                            );
                        };
                        let Some(range) = range else {
                            return fail(
                                p,
                                "a parametric expression curve needs `range = [s0, s1]`",
                            );
                        };
                        let [s0, s1] = self.vec2(range, &format!("{p}.range"))?;
                        if s1 <= s0 {
                            return fail(
                                format!("{p}.range"),
                                format!("the range must increase, got [{}, {}]", num(s0), num(s1)),
                            );
                        }
                        let f = |src: &str, key: &str| {
                            eval::function_of(src, "s", &self.params)
                                .map(Arc::new)
                                .or_else(|m| fail(format!("{p}.{key}"), m))
                        };
                        Ok(Parametric::Expr {
                            x: f(xs, "x")?,
                            y: f(ys, "y")?,
                            s0,
                            s1,
                            closed: closed.unwrap_or(false),
                        }
                        .into())
                    }
                }
            }
            CurveSpec::Fourier {
                centre: cen,
                a0,
                a,
                b: bs,
                ..
            } => {
                let a0 = self.num(a0, &format!("{p}.a0"))?;
                let list = |v: &[Num], key: &str| -> R<Vec<f64>> {
                    v.iter()
                        .enumerate()
                        .map(|(k, n)| self.num(n, &format!("{p}.{key}[{k}]")))
                        .collect()
                };
                Polar::fourier(centre(cen)?, a0, &list(a, "a")?, &list(bs, "b")?)
                    .map(Into::into)
                    .or_else(|e| bad("a0", e))
            }
            CurveSpec::Motion {
                follower,
                base_radius,
                rotation,
                offset,
                roller_radius,
                pivot_distance,
                arm_length,
                face_offset,
                curve,
                segments,
                ..
            } => {
                let rb = self.positive(base_radius, &format!("{p}.base_radius"), "base_radius")?;
                let ccw = match rotation.as_deref().unwrap_or("ccw") {
                    "ccw" => true,
                    "cw" => false,
                    other => {
                        return fail(
                            format!("{p}.rotation"),
                            format!("'{other}' is not 'ccw' or 'cw'"),
                        )
                    }
                };
                let need = |v: Option<&Num>, key: &str| -> R<f64> {
                    match v {
                        Some(n) => self.positive(n, &format!("{p}.{key}"), key),
                        None => fail(
                            format!("{p}.{key}"),
                            format!("a {follower} follower needs `{key}`"),
                        ),
                    }
                };
                // The follower's dimensions in the order of the core's
                // table (`Follower::KINDS`), which design files share.
                let given = [
                    ("offset", offset),
                    ("roller_radius", roller_radius),
                    ("pivot_distance", pivot_distance),
                    ("arm_length", arm_length),
                    ("face_offset", face_offset),
                ];
                let mut keys: Vec<&str> = Vec::new();
                let read = Follower::read(follower, |key, zero_default| {
                    keys.push(key);
                    let v = given
                        .iter()
                        .find(|(k, _)| *k == key)
                        .and_then(|(_, v)| v.as_ref());
                    if zero_default {
                        self.opt(v, 0.0, &format!("{p}.{key}"))
                    } else {
                        need(v, key)
                    }
                });
                let Some(read) = read else {
                    let names = Follower::KINDS.iter().map(|(k, _)| *k);
                    return fail(
                        format!("{p}.follower"),
                        format!(
                            "unknown follower '{follower}' ({}){}",
                            Follower::kinds_text(),
                            did_you_mean(follower, names)
                        ),
                    );
                };
                let (f, _) = read?;
                if let Some((key, _)) = given.iter().find(|(k, v)| v.is_some() && !keys.contains(k))
                {
                    return fail(
                        format!("{p}.{key}"),
                        format!("`{key}` does not apply to a {follower} follower"),
                    );
                }
                let pitch = match curve.as_deref().unwrap_or("surface") {
                    "surface" => false,
                    "pitch" if f.roller().is_some() => true,
                    "pitch" => return fail(format!("{p}.curve"), "a flat face has no pitch curve"),
                    other => {
                        return fail(
                            format!("{p}.curve"),
                            format!("'{other}' is not 'surface' or 'pitch'"),
                        )
                    }
                };
                let mut specs = Vec::with_capacity(segments.len());
                for (k, sg) in segments.iter().enumerate() {
                    let sp = format!("{p}.segments[{k}]");
                    let Some(law) = LawKind::parse(&sg.law) else {
                        let names: Vec<&str> = LawKind::ALL.iter().map(|l| l.name()).collect();
                        return fail(
                            format!("{sp}.law"),
                            format!(
                                "unknown law '{}' ({}){}",
                                sg.law,
                                names.join(", "),
                                did_you_mean(&sg.law, names.iter().copied())
                            ),
                        );
                    };
                    let ends = |e: &Option<MotionEndSpec>, key: &str| -> R<[Option<f64>; 3]> {
                        let Some(e) = e else {
                            return Ok([None; 3]);
                        };
                        let one = |n: &Option<Num>, d: &str| {
                            n.as_ref()
                                .map(|n| self.num(n, &format!("{sp}.{key}.{d}")))
                                .transpose()
                        };
                        Ok([
                            one(&e.velocity, "velocity")?,
                            one(&e.acceleration, "acceleration")?,
                            one(&e.jerk, "jerk")?,
                        ])
                    };
                    specs.push(SegmentSpec {
                        law,
                        span: self.positive(&sg.span, &format!("{sp}.span"), "span")?,
                        lift: self.opt(sg.lift.as_ref(), 0.0, &format!("{sp}.lift"))?,
                        start: ends(&sg.start, "start")?,
                        end: ends(&sg.end, "end")?,
                    });
                }
                let program = Program::new(&specs).or_else(|e| match e {
                    MotionError::Segment { segment, message } => {
                        fail(format!("{p}.segments[{segment}]"), message)
                    }
                    other => fail(format!("{p}.segments"), other.to_string()),
                })?;
                let cam = Cam::new(program, f, rb, ccw).or_else(|e| fail(p, e.to_string()))?;
                Ok(Parametric::Cam {
                    cam: Arc::new(cam),
                    pitch,
                }
                .into())
            }
            CurveSpec::Spline {
                kind,
                centre: cen,
                points,
                file,
                closed,
                ..
            } => {
                let (pts, field) = match (points, file) {
                    (Some(list), None) => {
                        let pts = list
                            .iter()
                            .enumerate()
                            .map(|(k, v)| self.vec2(v, &format!("{p}.points[{k}]")))
                            .collect::<R<Vec<V2>>>()?;
                        (pts, "points")
                    }
                    (None, Some(f)) => {
                        let path = self
                            .data
                            .resolve(f)
                            .or_else(|e| fail(format!("{p}.file"), e))?;
                        let mut pts = read_points_csv(&path)
                            .or_else(|e| fail(format!("{p}.file"), e.to_string()))?;
                        crate::units::points_to_si(self.units, *kind, &mut pts);
                        (pts, "file")
                    }
                    (Some(_), Some(_)) => {
                        return fail(
                            format!("{p}.file"),
                            "give either `points` or `file`, not both",
                        )
                    }
                    (None, None) => {
                        return fail(
                            p,
                            "a spline needs `points = [[x, y], …]` or `file = \"points.csv\"`",
                        )
                    }
                };
                match kind {
                    CurveKind::Polar => {
                        if *closed == Some(false) {
                            return fail(
                                format!("{p}.closed"),
                                "a polar profile is always closed (periodic in α)",
                            );
                        }
                        Polar::spline(centre(cen)?, &pts)
                            .map(Into::into)
                            .or_else(|e| bad(field, e))
                    }
                    CurveKind::Parametric => {
                        if cen.is_some() {
                            return fail(
                                format!("{p}.centre"),
                                "`centre` applies to a polar profile",
                            );
                        }
                        Parametric::spline(&pts, closed.unwrap_or(false))
                            .map(Into::into)
                            .or_else(|e| bad(field, e))
                    }
                }
            }
        }
    }

    /// Resolves a curve name.
    pub(super) fn curve_ref(&self, name: &str, path: &str) -> R<(BodyId, Curve)> {
        match self.curves.get(name) {
            Some(e) => Ok((e.body, e.curve.clone())),
            None => {
                let hint = if self.curves.is_empty() {
                    " (the file declares no [[curves]])".to_string()
                } else {
                    did_you_mean(name, self.curves.keys().map(String::as_str))
                };
                fail(path, format!("no curve named '{name}'{hint}"))
            }
        }
    }

    /// The parameter of the point of `c` (on body `b`) nearest to the global
    /// point `r`, at the initial placement.
    pub(super) fn nearest(&self, b: BodyId, c: &Curve, r: V2) -> f64 {
        let q = self.q0(b);
        let local = rot_t(q[2], sub(r, [q[0], q[1]]));
        search::closest(c, local, None)
    }

    /// Adds a contact joint with its starting guesses.
    pub(super) fn add_contact(
        &mut self,
        name: String,
        c: Constraint,
        own0: Option<[f64; MAX_OWN]>,
    ) {
        self.add(name, c, false);
        if let Some(j) = self.model.joints.last_mut() {
            j.own0 = own0;
        }
    }

    /// Makes the contact just added unilateral when `on`, with its law
    /// [restitution, rest_speed, event_tol, stiffness, exponent, damping]
    /// checked field by field.
    pub(super) fn set_unilateral(&mut self, on: bool, law: [&Option<Num>; 6], p: &str) -> R<()> {
        let names = UNILATERAL_KEYS;
        if !on {
            if let Some(k) = law.iter().position(|v| v.is_some()) {
                return fail(
                    format!("{p}.{}", names[k]),
                    "applies to a unilateral contact only: add unilateral = true",
                );
            }
            return Ok(());
        }
        let u = self.unilateral_law(law, p)?;
        if let Some(j) = self.model.joints.last_mut() {
            j.unilateral = Some(u);
        }
        Ok(())
    }

    /// The law of a unilateral contact or a joint stop at field `p`, from
    /// [restitution, rest_speed, event_tol, stiffness, exponent, damping],
    /// checked field by field.
    pub(super) fn unilateral_law(&self, law: [&Option<Num>; 6], p: &str) -> R<Unilateral> {
        let names = UNILATERAL_KEYS;
        let mut vals = [None; 6];
        for (k, v) in law.iter().enumerate() {
            if let Some(n) = v {
                vals[k] = Some(self.num(n, &format!("{p}.{}", names[k]))?);
            }
        }
        let mut u = Unilateral::default();
        let [e, rest, tol, k, n, c] = vals;
        let field = |k: usize| format!("{p}.{}", names[k]);
        if let Some(e) = e {
            if !(0.0..=1.0).contains(&e) {
                return fail(field(0), format!("must be between 0 and 1, not {e}"));
            }
            u.restitution = e;
        }
        if let Some(rest) = rest {
            if !(rest >= 0.0 && rest.is_finite()) {
                return fail(
                    field(1),
                    format!("must be a speed ≥ 0 (m/s), not {}", num(rest)),
                );
            }
            u.rest_speed = rest;
        }
        if let Some(tol) = tol {
            if !(tol > 0.0 && tol.is_finite()) {
                return fail(
                    field(2),
                    format!("must be a time > 0 (s), not {}", num(tol)),
                );
            }
            u.event_tol = tol;
        }
        match k {
            Some(k) => {
                if !(k > 0.0 && k.is_finite()) {
                    return fail(field(3), format!("must be a stiffness > 0 (N/mⁿ), not {k}"));
                }
                if e.is_some() {
                    return fail(
                        field(0),
                        "a compliant contact (stiffness given) has no impacts: its damping \
                         sets the losses",
                    );
                }
                let n = n.unwrap_or(1.5);
                if !(n >= 1.0 && n.is_finite()) {
                    return fail(field(4), format!("must be ≥ 1, not {n}"));
                }
                let c = c.unwrap_or(0.0);
                if !(c >= 0.0 && c.is_finite()) {
                    return fail(
                        field(5),
                        format!("must be a damping factor ≥ 0 (s/m), not {c}"),
                    );
                }
                u.compliant = Some(HuntCrossley {
                    stiffness: k,
                    exponent: n,
                    damping: c,
                });
            }
            None => {
                if let Some(i) = [n, c].iter().position(Option::is_some) {
                    return fail(
                        field(4 + i),
                        "applies to a compliant contact: give its stiffness",
                    );
                }
            }
        }
        Ok(u)
    }

    pub(super) fn different(
        &self,
        bi: BodyId,
        bj: BodyId,
        ci: &str,
        cj: &str,
        path: &str,
    ) -> R<()> {
        if bi == bj {
            return fail(
                path,
                format!(
                    "curves '{ci}' and '{cj}' are both on body '{}'; a contact needs two different bodies",
                    self.model.body(bi).name
                ),
            );
        }
        Ok(())
    }

    /// `curve_travel`: drives the named point–follower's α_j = f(t); the
    /// joint gains the equation `travel`.
    pub(super) fn curve_travel(&mut self, jd: &JointDriver, k: usize) -> R<()> {
        let path = format!("drivers[{k}]");
        let p = path.as_str();
        self.name(jd.name.as_ref(), format!("curve_travel_driver_{k}"), p)?;
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
        let f = self.time_fn(&jd.f, &format!("{p}.f"))?;
        let joint = self.model.joints.iter_mut().find(|j| j.name == jd.joint);
        match joint.map(|j| &mut j.constraint) {
            Some(Constraint::PointFollower(pf)) => {
                if pf.travel.is_some() {
                    return fail(
                        jp,
                        format!(
                            "joint '{}' is already driven by another curve_travel driver",
                            jd.joint
                        ),
                    );
                }
                pf.travel = Some(f);
                Ok(())
            }
            _ => {
                let is = match info {
                    JointInfo::Revolute { .. } => "revolute",
                    JointInfo::Translational { .. } => "translational",
                    JointInfo::Other(kind) => kind,
                };
                fail(
                    jp,
                    format!(
                        "joint '{}' is a {is} joint, but a curve_travel driver needs a point_follower joint",
                        jd.joint
                    ),
                )
            }
        }
    }
}
