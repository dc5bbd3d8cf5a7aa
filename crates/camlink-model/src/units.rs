//! Model files written in millimetres, degrees or other units
//! (`[model] units = { length = "mm", angle = "deg" }`): the file as written
//! is turned into SI (metres, radians) before it is resolved, so that the
//! core only ever sees SI.
//!
//! A value follows the units by what it measures:
//! - lengths (positions, points, radii, offsets, lifts, joint values,
//!   length drivers) and their rates (initial velocities, gravity) take
//!   the length unit;
//! - angles (body angles, arc ends, spans, angle drivers, free angles) and
//!   their rates (ω, a machine's speed) take the angle unit;
//! - a polynomial segment's end conditions s′, s″, s‴ take the lift's
//!   unit per angle unit, per angle unit², per angle unit³;
//! - a contact parameter or a curve-travel driver takes the unit of the
//!   curve's parameter: an angle on a polar profile or a synthesised cam,
//!   a length on a line, arc, circle or spline, nothing on a curve written
//!   as expressions in `s`;
//! - everything else stays SI: masses (kg), inertias (kg·m²), forces,
//!   torques, stiffnesses, dampings, times and solver settings.
//!
//! A number is converted exactly (divided by 1000 for mm); an expression
//! is wrapped, `(src)/1000`, so a driver in degrees gives its value in
//! degrees and its rates in deg/s, deg/s². The variables expressions read
//! keep their own units: time `t` in s, the polar angle `a` in rad (as
//! `cos` and `sin` take it), a curve's `s` its own parameter, and the
//! motion that a force reads in SI. Parameters are plain numbers: each
//! field that uses one converts it by what the field measures. Points of a
//! spline read from a CSV file are converted by [`points_to_si`].
//!
//! Each table is destructured in full, so a key added to the file format
//! does not compile until it is given its unit here.

use std::borrow::Cow;
use std::collections::{BTreeMap, HashMap};

use camlink_core::math::V2;
use camlink_core::quantity::{Angle, Length, Units};

use crate::file::*;

/// What a value measures, as powers of the length and angle units:
/// L^length · A^angle (a velocity is L¹, an angular velocity A¹: times
/// stay seconds).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Dim {
    length: i32,
    angle: i32,
}

const NONE: Dim = Dim {
    length: 0,
    angle: 0,
};
const LENGTH: Dim = Dim {
    length: 1,
    angle: 0,
};
const ANGLE: Dim = Dim {
    length: 0,
    angle: 1,
};

impl Dim {
    /// This per angle unit to the power `k`.
    fn per_angle(self, k: i32) -> Dim {
        Dim {
            length: self.length,
            angle: self.angle - k,
        }
    }
}

/// The declared units of `file` (SI where it declares none).
pub(crate) fn declared(file: &ModelFile) -> Units {
    let spec = file
        .model
        .as_ref()
        .and_then(|m| m.units)
        .unwrap_or_default();
    Units {
        length: match spec.length {
            None | Some(LengthUnit::M) => Length::M,
            Some(LengthUnit::Cm) => Length::Cm,
            Some(LengthUnit::Mm) => Length::Mm,
            Some(LengthUnit::In) => Length::In,
        },
        angle: match spec.angle {
            None | Some(AngleUnit::Rad) => Angle::Rad,
            Some(AngleUnit::Deg) => Angle::Deg,
        },
    }
}

/// `file` in SI: itself when it declares SI units (or none), else a copy
/// with every length and angle converted (see the module documentation).
pub(crate) fn to_si(file: &ModelFile) -> Cow<'_, ModelFile> {
    let units = declared(file);
    if units.is_si() {
        return Cow::Borrowed(file);
    }
    let mut out = file.clone();
    Convert::new(units, file).file(&mut out);
    Cow::Owned(out)
}

/// Spline points read from a file written in `units`, to SI: (α, ρ) of a
/// polar profile, (x, y) of a parametric curve.
pub(crate) fn points_to_si(units: Units, kind: CurveKind, points: &mut [V2]) {
    let scale = Convert::scale(units);
    let first = match kind {
        CurveKind::Polar => ANGLE,
        CurveKind::Parametric => LENGTH,
    };
    for p in points {
        p[0] = scale.value(p[0], first);
        p[1] = scale.value(p[1], LENGTH);
    }
}

/// One step of a conversion to SI: an operator and its operand, applied
/// to a number or appended to an expression.
#[derive(Clone, Copy)]
struct Step {
    divide: bool,
    k: f64,
}

impl Step {
    fn apply(self, v: f64, inverse: bool) -> f64 {
        if self.divide != inverse {
            v / self.k
        } else {
            v * self.k
        }
    }

    fn text(self, inverse: bool) -> String {
        let op = if self.divide != inverse { '/' } else { '*' };
        format!("{op}{:?}", self.k)
    }
}

/// The steps from the file's units to SI.
#[derive(Clone, Copy)]
struct Scale {
    /// File length unit → m: none for m; exact divisions for cm and mm.
    length: Option<Step>,
    /// File angle unit → rad: none for rad.
    angle: Option<Step>,
}

impl Scale {
    /// The steps of `dim`: (step, inverse?), one per power.
    fn steps(self, dim: Dim) -> Vec<(Step, bool)> {
        let mut out = Vec::new();
        for (step, power) in [(self.length, dim.length), (self.angle, dim.angle)] {
            if let Some(s) = step {
                for _ in 0..power.abs() {
                    out.push((s, power < 0));
                }
            }
        }
        out
    }

    fn value(self, v: f64, dim: Dim) -> f64 {
        self.steps(dim)
            .into_iter()
            .fold(v, |v, (s, inverse)| s.apply(v, inverse))
    }

    fn num(self, n: &mut Num, dim: Dim) {
        let steps = self.steps(dim);
        if steps.is_empty() {
            return;
        }
        match n {
            Num::Value(v) => *v = self.value(*v, dim),
            Num::Expr(src) => {
                let mut text = format!("({src})");
                for (s, inverse) in steps {
                    text.push_str(&s.text(inverse));
                }
                *src = text;
            }
        }
    }

    fn opt(self, n: &mut Option<Num>, dim: Dim) {
        if let Some(n) = n {
            self.num(n, dim);
        }
    }

    fn vec2(self, v: &mut Vec2, dim: Dim) {
        for n in &mut v.0 {
            self.num(n, dim);
        }
    }

    fn opt_vec2(self, v: &mut Option<Vec2>, dim: Dim) {
        if let Some(v) = v {
            self.vec2(v, dim);
        }
    }

    fn point(self, p: &mut Option<PointRef>) {
        if let Some(p) = p {
            self.point_ref(p);
        }
    }

    fn point_ref(self, p: &mut PointRef) {
        match p {
            PointRef::Name(_) => {}
            PointRef::Inline(v) => self.vec2(v, LENGTH),
        }
    }

    fn points(self, points: &mut BTreeMap<String, Vec2>) {
        for v in points.values_mut() {
            self.vec2(v, LENGTH);
        }
    }
}

/// The conversion of one file: its scale and what a contact parameter on
/// each named curve measures.
pub(crate) struct Convert {
    scale: Scale,
    /// Curve name → the dimension of its parameter.
    curves: HashMap<String, Dim>,
    /// Joint name → the curve a curve-travel driver runs along.
    slots: HashMap<String, String>,
}

impl Convert {
    fn scale(units: Units) -> Scale {
        let length = match units.length {
            Length::M => None,
            Length::Cm => Some(Step {
                divide: true,
                k: 100.0,
            }),
            Length::Mm => Some(Step {
                divide: true,
                k: 1000.0,
            }),
            Length::In => Some(Step {
                divide: false,
                k: Length::In.metres(),
            }),
        };
        let angle = match units.angle {
            Angle::Rad => None,
            Angle::Deg => Some(Step {
                divide: false,
                k: Angle::Deg.radians(),
            }),
        };
        Scale { length, angle }
    }

    fn new(units: Units, file: &ModelFile) -> Self {
        let curves = file
            .curves
            .iter()
            .map(|c| (curve_name(c).to_string(), parameter_dim(c)))
            .collect();
        let slots = file
            .joints
            .iter()
            .enumerate()
            .filter_map(|(k, j)| match j {
                JointSpec::PointFollower(p) => Some((
                    p.name
                        .clone()
                        .unwrap_or_else(|| format!("point_follower_{k}")),
                    p.curve_j.clone(),
                )),
                _ => None,
            })
            .collect();
        Convert {
            scale: Convert::scale(units),
            curves,
            slots,
        }
    }

    /// The dimension of a contact parameter on curve `name` (none for a
    /// curve the file does not declare: the resolver reports it).
    fn on_curve(&self, name: &str) -> Dim {
        self.curves.get(name).copied().unwrap_or(NONE)
    }

    fn file(&self, f: &mut ModelFile) {
        let s = self.scale;
        let ModelFile {
            schema: _,
            model,
            parameters: _,
            ground,
            bodies,
            curves,
            joints,
            drivers,
            forces,
            analysis: _,
            machine,
        } = f;
        if let Some(ModelSection {
            name: _,
            gravity,
            units: _,
        }) = model
        {
            s.opt_vec2(gravity, LENGTH);
        }
        if let Some(GroundSection { points }) = ground {
            s.points(points);
        }
        for b in bodies {
            self.body(b);
        }
        for c in curves {
            self.curve(c);
        }
        for j in joints {
            self.joint(j);
        }
        for d in drivers {
            self.driver(d);
        }
        for x in forces {
            self.force(x);
        }
        if let Some(m) = machine {
            self.machine(m);
        }
    }

    fn body(&self, b: &mut BodySpec) {
        let s = self.scale;
        let BodySpec {
            name: _,
            position,
            angle,
            mass: _,
            inertia: _,
            centroid,
            velocity,
            omega,
            points,
            global_points,
            outline,
        } = b;
        s.opt_vec2(position, LENGTH);
        s.opt(angle, ANGLE);
        s.opt_vec2(centroid, LENGTH);
        s.opt_vec2(velocity, LENGTH);
        s.opt(omega, ANGLE);
        s.points(points);
        s.points(global_points);
        match outline {
            Some(OutlineSpec::Polyline(corners)) => {
                for c in corners {
                    s.vec2(c, LENGTH);
                }
            }
            Some(OutlineSpec::Curve(_)) | None => {}
        }
    }

    fn curve(&self, c: &mut CurveSpec) {
        let s = self.scale;
        match c {
            CurveSpec::Circle {
                name: _,
                body: _,
                kind: _,
                centre,
                radius,
                start,
            } => {
                s.point(centre);
                s.num(radius, LENGTH);
                s.opt(start, ANGLE);
            }
            CurveSpec::Line {
                name: _,
                body: _,
                from,
                to,
            } => {
                s.point_ref(from);
                s.point_ref(to);
            }
            CurveSpec::Arc {
                name: _,
                body: _,
                centre,
                radius,
                start,
                end,
            } => {
                s.point(centre);
                s.num(radius, LENGTH);
                s.num(start, ANGLE);
                s.num(end, ANGLE);
            }
            CurveSpec::Expression {
                name: _,
                body: _,
                kind: _,
                centre,
                rho,
                x,
                y,
                range: _,
                closed: _,
            } => {
                s.point(centre);
                for e in [rho, x, y].into_iter().flatten() {
                    let mut n = Num::Expr(std::mem::take(e));
                    s.num(&mut n, LENGTH);
                    if let Num::Expr(src) = n {
                        *e = src;
                    }
                }
            }
            CurveSpec::Fourier {
                name: _,
                body: _,
                centre,
                a0,
                a,
                b,
            } => {
                s.point(centre);
                s.num(a0, LENGTH);
                for n in a.iter_mut().chain(b.iter_mut()) {
                    s.num(n, LENGTH);
                }
            }
            CurveSpec::Spline {
                name: _,
                body: _,
                kind,
                centre,
                points,
                file: _,
                closed: _,
            } => {
                s.point(centre);
                let first = match kind {
                    CurveKind::Polar => ANGLE,
                    CurveKind::Parametric => LENGTH,
                };
                for p in points.iter_mut().flatten() {
                    s.num(&mut p.0[0], first);
                    s.num(&mut p.0[1], LENGTH);
                }
            }
            CurveSpec::Motion {
                name: _,
                body: _,
                follower,
                base_radius,
                rotation: _,
                offset,
                roller_radius,
                pivot_distance,
                arm_length,
                face_offset,
                curve: _,
                segments,
            } => {
                s.num(base_radius, LENGTH);
                for n in [
                    offset,
                    roller_radius,
                    pivot_distance,
                    arm_length,
                    face_offset,
                ] {
                    s.opt(n, LENGTH);
                }
                // An oscillating follower's lift is a swing angle.
                let lift = if follower.starts_with("oscillating") {
                    ANGLE
                } else {
                    LENGTH
                };
                for seg in segments {
                    let MotionSegmentSpec {
                        law: _,
                        span,
                        lift: l,
                        start,
                        end,
                    } = seg;
                    s.num(span, ANGLE);
                    s.opt(l, lift);
                    for e in [start, end].into_iter().flatten() {
                        let MotionEndSpec {
                            velocity,
                            acceleration,
                            jerk,
                        } = e;
                        s.opt(velocity, lift.per_angle(1));
                        s.opt(acceleration, lift.per_angle(2));
                        s.opt(jerk, lift.per_angle(3));
                    }
                }
            }
        }
    }

    /// A joint's values, by its kind ([`crate::resolve::JointKind::to_si`]).
    fn joint(&self, j: &mut JointSpec) {
        j.kind_mut().to_si(self);
    }

    /// A body point: [x, y] is a length; a name stays.
    pub(crate) fn point(&self, p: &mut Option<PointRef>) {
        self.scale.point(p);
    }

    /// A point that must be given: [x, y] is a length; a name stays.
    pub(crate) fn point_ref(&self, p: &mut PointRef) {
        self.scale.point_ref(p);
    }

    /// A length that must be given.
    pub(crate) fn length(&self, n: &mut Num) {
        self.scale.num(n, LENGTH);
    }

    /// A length that may be left out.
    pub(crate) fn opt_length(&self, n: &mut Option<Num>) {
        self.scale.opt(n, LENGTH);
    }

    /// An angle that may be left out.
    pub(crate) fn opt_angle(&self, n: &mut Option<Num>) {
        self.scale.opt(n, ANGLE);
    }

    /// A contact parameter on curve `curve`: an angle on a polar profile,
    /// a length on a parametric curve.
    pub(crate) fn opt_on_curve(&self, n: &mut Option<Num>, curve: &str) {
        self.scale.opt(n, self.on_curve(curve));
    }

    /// End stops on a rotation (`lower`, `upper` are angles).
    pub(crate) fn angle_limits(&self, limits: &mut Option<LimitsSpec>) {
        self.limits(limits, ANGLE);
    }

    /// End stops on a travel (`lower`, `upper` are lengths).
    pub(crate) fn length_limits(&self, limits: &mut Option<LimitsSpec>) {
        self.limits(limits, LENGTH);
    }

    /// A joint's limits: `lower` and `upper` in the unit of the joint's
    /// coordinate (`dim`: an angle or a length); the law's figures
    /// (restitution, rest speed, event tolerance, stiffness, exponent,
    /// damping) stay SI, as a cam contact's do.
    fn limits(&self, limits: &mut Option<LimitsSpec>, dim: Dim) {
        let Some(LimitsSpec {
            lower,
            upper,
            restitution: _,
            rest_speed: _,
            event_tol: _,
            stiffness: _,
            exponent: _,
            damping: _,
        }) = limits
        else {
            return;
        };
        self.scale.opt(lower, dim);
        self.scale.opt(upper, dim);
    }

    /// A joint's friction: the pin `radius` is a length; μ and the
    /// transition speed (m/s) stay SI.
    pub(crate) fn friction(&self, friction: &mut Option<FrictionSpec>) {
        let Some(FrictionSpec {
            mu: _,
            radius,
            transition_speed: _,
        }) = friction
        else {
            return;
        };
        self.scale.opt(radius, LENGTH);
    }

    fn driver(&self, d: &mut DriverSpec) {
        let s = self.scale;
        match d {
            DriverSpec::AbsoluteX(a) | DriverSpec::AbsoluteY(a) => {
                let AbsoluteCoordDriver {
                    name: _,
                    body: _,
                    point,
                    f,
                } = a;
                s.point(point);
                s.num(f, LENGTH);
            }
            DriverSpec::AbsolutePhi(a) => {
                let AbsolutePhiDriver {
                    name: _,
                    body: _,
                    f,
                } = a;
                s.num(f, ANGLE);
            }
            DriverSpec::AbsoluteDistance(a) => {
                let AbsoluteDistanceDriver {
                    name: _,
                    body: _,
                    point,
                    ground_point,
                    f,
                } = a;
                s.point(point);
                s.point_ref(ground_point);
                s.num(f, LENGTH);
            }
            DriverSpec::RelativeX(r)
            | DriverSpec::RelativeY(r)
            | DriverSpec::RelativeDistance(r) => {
                let RelativeCoordDriver {
                    name: _,
                    body_i: _,
                    point_i,
                    body_j: _,
                    point_j,
                    f,
                } = r;
                s.point(point_i);
                s.point(point_j);
                s.num(f, LENGTH);
            }
            DriverSpec::RelativePhi(r) => {
                let RelativePhiDriver {
                    name: _,
                    body_i: _,
                    body_j: _,
                    f,
                } = r;
                s.num(f, ANGLE);
            }
            DriverSpec::RevoluteAngle(j) => s.num(&mut j.f, ANGLE),
            DriverSpec::TranslationalTravel(j) => s.num(&mut j.f, LENGTH),
            DriverSpec::CurveTravel(j) => {
                let dim = self
                    .slots
                    .get(&j.joint)
                    .map_or(NONE, |curve| self.on_curve(curve));
                s.num(&mut j.f, dim);
            }
        }
    }

    fn force(&self, f: &mut ForceSpec) {
        let s = self.scale;
        match f {
            ForceSpec::PointForce {
                name: _,
                body: _,
                point,
                fx: _,
                fy: _,
                local: _,
                reaction: _,
                reaction_point,
            } => {
                s.point(point);
                s.point(reaction_point);
            }
            ForceSpec::Torque {
                name: _,
                body: _,
                torque: _,
                reaction: _,
            } => {}
            ForceSpec::Tsda {
                name: _,
                body_i: _,
                point_i,
                body_j: _,
                point_j,
                stiffness: _,
                free_length,
                damping: _,
                actuator: _,
            } => {
                s.point(point_i);
                s.point(point_j);
                s.opt(free_length, LENGTH);
            }
            ForceSpec::Rsda {
                name: _,
                body_i: _,
                body_j: _,
                stiffness: _,
                free_angle,
                damping: _,
                actuator: _,
            } => s.opt(free_angle, ANGLE),
            ForceSpec::ViscousFriction {
                name: _,
                joint: _,
                damping: _,
            } => {}
        }
    }

    fn machine(&self, m: &mut MachineSection) {
        let s = self.scale;
        let MachineSection {
            driver: _,
            speed,
            speed_band: _,
            steps: _,
            moment_point,
            balance: _,
            motor,
        } = m;
        s.num(speed, ANGLE);
        s.opt_vec2(moment_point, LENGTH);
        if let Some(MotorSection {
            curve,
            gear_ratio: _,
            rated_torque: _,
            rated_power: _,
        }) = motor
        {
            // Pairs [speed, torque]: the speed follows the angle unit.
            for p in curve {
                s.num(&mut p.0[0], ANGLE);
            }
        }
    }
}

/// The name of a curve.
fn curve_name(c: &CurveSpec) -> &str {
    match c {
        CurveSpec::Circle { name, .. }
        | CurveSpec::Line { name, .. }
        | CurveSpec::Arc { name, .. }
        | CurveSpec::Expression { name, .. }
        | CurveSpec::Fourier { name, .. }
        | CurveSpec::Spline { name, .. }
        | CurveSpec::Motion { name, .. } => name,
    }
}

/// What a curve's parameter measures: an angle on a polar profile or a
/// synthesised cam, a length on a parametric line, arc, circle or spline,
/// nothing on a parametric curve written as expressions.
fn parameter_dim(c: &CurveSpec) -> Dim {
    match c {
        CurveSpec::Circle { kind, .. } => match kind {
            Some(CurveKind::Parametric) => LENGTH,
            Some(CurveKind::Polar) | None => ANGLE,
        },
        CurveSpec::Line { .. } | CurveSpec::Arc { .. } => LENGTH,
        CurveSpec::Expression { kind, rho, .. } => {
            if *kind == Some(CurveKind::Polar) || (kind.is_none() && rho.is_some()) {
                ANGLE
            } else {
                NONE
            }
        }
        CurveSpec::Fourier { .. } | CurveSpec::Motion { .. } => ANGLE,
        CurveSpec::Spline { kind, .. } => match kind {
            CurveKind::Polar => ANGLE,
            CurveKind::Parametric => LENGTH,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mm_deg() -> Scale {
        Convert::scale(Units::parse("mm,deg").unwrap())
    }

    #[test]
    fn numbers_are_converted_exactly_and_expressions_wrapped() {
        let s = mm_deg();
        let mut n = Num::Value(100.0);
        s.num(&mut n, LENGTH);
        assert_eq!(n, Num::Value(0.1));
        let mut n = Num::Expr("30 + 360*t".into());
        s.num(&mut n, ANGLE);
        assert_eq!(n, Num::Expr("(30 + 360*t)*0.017453292519943295".into()));
        // s′ of a lift in mm per degree of cam angle: m per rad.
        let mut n = Num::Value(1.0);
        s.num(&mut n, LENGTH.per_angle(1));
        let Num::Value(v) = n else { unreachable!() };
        assert!((v - 0.001 * 180.0 / std::f64::consts::PI).abs() < 1e-15);
        let mut n = Num::Expr("2".into());
        s.num(&mut n, NONE);
        assert_eq!(n, Num::Expr("2".into()));
    }

    #[test]
    fn csv_points_follow_the_kind_of_spline() {
        let units = Units::parse("mm,deg").unwrap();
        let mut pts = [[90.0, 25.0]];
        points_to_si(units, CurveKind::Polar, &mut pts);
        assert!((pts[0][0] - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        assert_eq!(pts[0][1], 0.025);
        let mut pts = [[90.0, 25.0]];
        points_to_si(units, CurveKind::Parametric, &mut pts);
        assert_eq!(pts[0], [0.09, 0.025]);
    }
}
