//! Profile synthesis: the cam surface that drives a follower through a
//! motion program, for four kinds of follower.
//!
//! Frames and conventions. The cam turns about the ground origin O; its
//! body angle is σθ with θ the cam angle of the motion program and σ = +1
//! for counterclockwise rotation, −1 for clockwise. A point fixed in the
//! ground at r(θ) lies in the cam frame at p(θ) = A(−σθ) r(θ). Every curve
//! below is parametrised by θ over [0, 2π) and is closed.
//!
//! Followers (ground frame, s from the [`Program`]):
//! - translating roller: roller centre at C = (σε, y₀ + s),
//!   y₀ = √(R_p² − ε²), prime circle R_p = R_b + R_r, moving along +y; a
//!   positive offset ε puts the stem where the cam surface moves in the
//!   rise direction, which lowers the pressure angle on the rise;
//! - translating flat-faced: face y = R_b + s, perpendicular to its +y
//!   motion; the envelope gives the contact at x = σ s′ on the face, so
//!   the surface is p = A(−σθ) (σ s′, R_b + s) and its radius of curvature
//!   ρ = R_b + s + s″;
//! - oscillating roller: arm pivoted at P = (d, 0), length L, at angle
//!   ψ = ψ₀ − s (s is the swing, rad), roller centre C = P + L (cos ψ, sin ψ),
//!   cos ψ₀ = (R_p² − d² − L²)/(2dL), ψ₀ in (0, π): a positive swing moves
//!   the roller away from O;
//! - oscillating flat-faced: arm pivoted at P = (d, 0); its face is the
//!   line m·(x − P) = e, m = (−sin ψ, cos ψ), at distance e from the pivot,
//!   ψ = ψ₀ − s, sin ψ₀ = (e − R_b)/d so that at s = 0 the face touches the
//!   base circle.
//!
//! A roller's pitch curve is the path of its centre, p(θ) = A(−σθ) C(θ);
//! the cam surface is the pitch curve moved the roller radius towards O
//! along the normal: q = p − R_r n̂, n̂ = σ p′⊥/|p′| (outward, since the
//! pitch curve runs clockwise in the cam frame when σ = +1). A flat face's
//! surface is the envelope of the face lines in the cam frame:
//! with m_c = A(−σθ) m, t_c = A(−σθ) t, h = e + m_c·A(−σθ)P and
//! β = ψ − σθ, q = h m_c − (h′/β′) t_c.
//!
//! Everything is computed as truncated Taylor series in θ ([`T`]) from the
//! program's exact derivatives, so the surface's p, p′, p″, p‴ are exact.
//!
//! Pressure angle φ (Norton ch. 7): the angle between the contact normal
//! and the direction w in which the follower's point at the contact (a
//! roller's centre) moves as s grows: φ = σ atan2(w × n, w · n), with n the
//! outward contact normal; a centred translating roller has
//! tan φ = s′/(R_p + s), positive on a rise.

use std::f64::consts::TAU;

use super::motion::Program;
use super::taylor::{T, TV};
use crate::math::{cross, dot, norm, rot, sub, V2};

/// The follower and its dimensions (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Follower {
    /// Roller of radius `roller` on a translating stem at offset ε (the
    /// stem on x = σε).
    TranslatingRoller { offset: f64, roller: f64 },
    /// Flat face perpendicular to a translating stem.
    TranslatingFlat,
    /// Roller of radius `roller` on an arm of length `arm`, pivoted at
    /// distance `pivot` from the cam centre.
    OscillatingRoller { pivot: f64, arm: f64, roller: f64 },
    /// Flat face at distance `face_offset` from the pivot of an arm
    /// pivoted at distance `pivot` from the cam centre.
    OscillatingFlat { pivot: f64, face_offset: f64 },
}

impl Follower {
    /// Every follower kind as design files name it, with the dimensions
    /// (m) it takes in the order [`Follower::from_dims`] reads them.
    pub const KINDS: [(&'static str, &'static [&'static str]); 4] = [
        ("translating-roller", &["offset", "roller_radius"]),
        ("translating-flat", &[]),
        (
            "oscillating-roller",
            &["pivot_distance", "arm_length", "roller_radius"],
        ),
        ("oscillating-flat", &["pivot_distance", "face_offset"]),
    ];

    /// The dimensions that a file may leave out: 0 when not given, and
    /// any sign (a stem's offset ε, a flat face's offset from the arm's
    /// pivot line). Every other dimension is required and positive.
    pub const ZERO_DEFAULT: [&'static str; 2] = ["offset", "face_offset"];

    /// Whether dimension `key` of [`Follower::KINDS`] is 0 when not given
    /// (and of any sign) rather than required and positive.
    pub fn zero_default(key: &str) -> bool {
        Follower::ZERO_DEFAULT.contains(&key)
    }

    /// The follower kinds' names, "translating-roller, …, or
    /// oscillating-flat" (for messages).
    pub fn kinds_text() -> String {
        let names: Vec<&str> = Follower::KINDS.iter().map(|(k, _)| *k).collect();
        let (last, init) = names.split_last().expect("follower kinds");
        format!("{} or {last}", init.join(", "))
    }

    /// The follower of kind `name` (one of [`Follower::KINDS`]) with the
    /// dimensions `dims` (m) in the order of its entry there.
    pub fn from_dims(name: &str, dims: &[f64]) -> Result<Follower, String> {
        let Some((kind, fields)) = Follower::KINDS.iter().find(|(k, _)| *k == name) else {
            return Err(format!("unknown follower type '{name}'"));
        };
        if dims.len() != fields.len() {
            return Err(format!(
                "a {name} follower takes {} dimensions, got {}",
                fields.len(),
                dims.len()
            ));
        }
        Ok(Follower::build(kind, dims))
    }

    /// The follower of kind `name` with each dimension of its entry in
    /// [`Follower::KINDS`] read, in that order, by `dim(key, zero_default)`
    /// (`zero_default`: the key may be left out, 0, of any sign; otherwise
    /// it is required and positive, [`Follower::zero_default`]); and the
    /// dimensions read. `None` when `name` is not a kind. The one reading
    /// of a follower's dimensions, for design files and model files alike.
    pub fn read<E>(
        name: &str,
        mut dim: impl FnMut(&'static str, bool) -> Result<f64, E>,
    ) -> Option<Result<(Follower, Vec<f64>), E>> {
        let (kind, keys) = Follower::KINDS.iter().find(|(k, _)| *k == name)?;
        let dims: Result<Vec<f64>, E> = keys
            .iter()
            .map(|key| dim(key, Follower::zero_default(key)))
            .collect();
        Some(dims.map(|d| (Follower::build(kind, &d), d)))
    }

    /// The follower of kind `kind` (of [`Follower::KINDS`]) from as many
    /// dimensions as its entry lists.
    fn build(kind: &str, dims: &[f64]) -> Follower {
        match kind {
            "translating-roller" => Follower::TranslatingRoller {
                offset: dims[0],
                roller: dims[1],
            },
            "translating-flat" => Follower::TranslatingFlat,
            "oscillating-roller" => Follower::OscillatingRoller {
                pivot: dims[0],
                arm: dims[1],
                roller: dims[2],
            },
            _ => Follower::OscillatingFlat {
                pivot: dims[0],
                face_offset: dims[1],
            },
        }
    }

    /// The name used in design files.
    pub fn name(&self) -> &'static str {
        match self {
            Follower::TranslatingRoller { .. } => "translating-roller",
            Follower::TranslatingFlat => "translating-flat",
            Follower::OscillatingRoller { .. } => "oscillating-roller",
            Follower::OscillatingFlat { .. } => "oscillating-flat",
        }
    }

    /// Roller radius; `None` for a flat face.
    pub fn roller(&self) -> Option<f64> {
        match *self {
            Follower::TranslatingRoller { roller, .. }
            | Follower::OscillatingRoller { roller, .. } => Some(roller),
            _ => None,
        }
    }

    /// True for an oscillating (swinging-arm) follower.
    pub fn oscillating(&self) -> bool {
        matches!(
            self,
            Follower::OscillatingRoller { .. } | Follower::OscillatingFlat { .. }
        )
    }
}

/// Why a cam cannot be synthesised.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct CamError(pub String);

/// A cam: motion program, follower, base circle and sense of rotation.
#[derive(Clone, Debug)]
pub struct Cam {
    pub program: Program,
    pub follower: Follower,
    /// Base circle radius R_b (m): the least radius of the cam surface
    /// on the dwell at s = 0.
    pub base_radius: f64,
    /// σ: +1 counterclockwise, −1 clockwise.
    pub sigma: f64,
    /// ψ₀ (rad) of an oscillating follower, y₀ (m) of a translating roller.
    start: f64,
}

/// The follower's contact with the cam at one cam angle, in the ground
/// frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// Cam angle θ (rad).
    pub theta: f64,
    /// `[s, s′, s″, s‴]`.
    pub motion: [f64; 4],
    /// Contact point on the cam surface (m).
    pub point: V2,
    /// Unit normal of the surface at the contact, pointing away from the cam.
    pub normal: V2,
    /// Pressure angle φ (rad), signed.
    pub pressure_angle: f64,
    /// Radius of curvature of the cam surface (m), positive where convex;
    /// infinite where straight.
    pub rho: f64,
    /// Radius of curvature of a roller's pitch curve (m); `None` for a flat face.
    pub rho_pitch: Option<f64>,
    /// A flat face's contact position along the face from the foot of the
    /// stem axis (translating) or of the perpendicular from the pivot
    /// (oscillating), m; `None` for a roller.
    pub face_position: Option<f64>,
}

fn positive(what: &str, v: f64) -> Result<(), CamError> {
    if v > 0.0 && v.is_finite() {
        Ok(())
    } else {
        Err(CamError(format!("{what} must be positive, got {v}")))
    }
}

impl Cam {
    /// A cam for `program` and `follower` with base circle `base_radius`
    /// (m), turning counterclockwise when `ccw`.
    pub fn new(
        program: Program,
        follower: Follower,
        base_radius: f64,
        ccw: bool,
    ) -> Result<Cam, CamError> {
        positive("base_radius", base_radius)?;
        let start = match follower {
            Follower::TranslatingRoller { offset, roller } => {
                positive("roller radius", roller)?;
                let rp = base_radius + roller;
                if !(offset.is_finite() && offset.abs() < rp) {
                    return Err(CamError(format!(
                        "offset {offset} m must be smaller than the prime circle radius {rp} m"
                    )));
                }
                (rp * rp - offset * offset).sqrt()
            }
            Follower::TranslatingFlat => 0.0,
            Follower::OscillatingRoller { pivot, arm, roller } => {
                positive("roller radius", roller)?;
                positive("pivot distance", pivot)?;
                positive("arm length", arm)?;
                let rp = base_radius + roller;
                let c = (rp * rp - pivot * pivot - arm * arm) / (2.0 * pivot * arm);
                if !(-1.0..=1.0).contains(&c) {
                    return Err(CamError(format!(
                        "an arm of {arm} m pivoted {pivot} m from the cam centre cannot reach \
                         the prime circle of radius {rp} m"
                    )));
                }
                c.acos()
            }
            Follower::OscillatingFlat { pivot, face_offset } => {
                positive("pivot distance", pivot)?;
                let sn = (face_offset - base_radius) / pivot;
                if !(pivot > base_radius && (-1.0..=1.0).contains(&sn)) {
                    return Err(CamError(format!(
                        "the pivot distance {pivot} m must exceed the base circle radius \
                         {base_radius} m and |e − R_b| ≤ d"
                    )));
                }
                sn.asin()
            }
        };
        Ok(Cam {
            program,
            follower,
            base_radius,
            sigma: if ccw { 1.0 } else { -1.0 },
            start,
        })
    }

    /// The same cam with another base circle radius.
    pub fn with_base_radius(&self, base_radius: f64) -> Result<Cam, CamError> {
        Cam::new(
            self.program.clone(),
            self.follower,
            base_radius,
            self.sigma > 0.0,
        )
    }

    /// Start of the follower's coordinate: ψ₀ (rad) for an oscillating
    /// follower, y₀ (m) for a translating roller, 0 for a translating face.
    pub fn start(&self) -> f64 {
        self.start
    }

    /// The follower's coordinate at cam angle θ: the stem's y (m) or the
    /// arm's angle ψ (rad).
    pub fn follower_coordinate(&self, theta: f64) -> [f64; 4] {
        let d = self.program.eval(theta);
        match self.follower {
            Follower::TranslatingRoller { .. } => [self.start + d[0], d[1], d[2], d[3]],
            Follower::TranslatingFlat => [self.base_radius + d[0], d[1], d[2], d[3]],
            _ => [self.start - d[0], -d[1], -d[2], -d[3]],
        }
    }

    /// Series of s at θ, and of θ itself.
    fn motion_series(&self, theta: f64) -> (T, T, [f64; 6]) {
        let d = self.program.eval(theta);
        (
            T::from_derivatives(d),
            T::from_derivatives([theta, 1.0, 0.0, 0.0, 0.0, 0.0]),
            d,
        )
    }

    /// Cam-frame series of the surface and of a roller's pitch curve at θ
    /// (the surface exact to degree 4, the pitch curve to degree 5).
    fn series(&self, theta: f64) -> (TV, Option<TV>) {
        let (s, th, d) = self.motion_series(theta);
        let back = th.scale(-self.sigma);
        let roller = |c: TV, r: f64| {
            let p = c.rot(back);
            let t = p.diff();
            let inv = t.dot(t).sqrt().recip();
            let n = t.perp().times(inv.scale(self.sigma));
            (p.minus(n.times(T::constant(r))), Some(p))
        };
        match self.follower {
            Follower::TranslatingRoller { offset, roller: r } => roller(
                TV(
                    T::constant(self.sigma * offset),
                    s + T::constant(self.start),
                ),
                r,
            ),
            Follower::TranslatingFlat => {
                let s1 = T::from_derivatives([d[1], d[2], d[3], d[4], d[5], 0.0]);
                let r = TV(s1.scale(self.sigma), s + T::constant(self.base_radius));
                (r.rot(back), None)
            }
            Follower::OscillatingRoller {
                pivot,
                arm,
                roller: r,
            } => {
                let psi = T::constant(self.start) - s;
                let (sn, cs) = psi.sin_cos();
                let c = TV(cs.scale(arm) + T::constant(pivot), sn.scale(arm));
                roller(c, r)
            }
            Follower::OscillatingFlat { pivot, face_offset } => {
                let psi = T::constant(self.start) - s;
                let (sn, cs) = psi.sin_cos();
                let m = TV(-sn, cs).rot(back);
                let t = TV(cs, sn).rot(back);
                let pc = TV(T::constant(pivot), T::constant(0.0)).rot(back);
                let h = m.dot(pc) + T::constant(face_offset);
                let beta_d = psi.diff() - T::constant(self.sigma);
                let q = m.times(h).minus(t.times(h.diff() * beta_d.recip()));
                (q, None)
            }
        }
    }

    /// The cam surface at θ: p, p′, p″, p‴, p⁗ in the cam frame (m, m/rad, …).
    pub fn surface(&self, theta: f64) -> ProfileJet {
        jet(self.series(theta).0)
    }

    /// A roller's pitch curve at θ in the cam frame; `None` for a flat face.
    pub fn pitch(&self, theta: f64) -> Option<ProfileJet> {
        self.series(theta).1.map(jet)
    }

    /// The curve at distance `offset` (m) outside the surface along its
    /// outward normal, in the cam frame: a cutter's or grinding wheel's
    /// centre path for a tool of that radius.
    pub fn offset_point(&self, theta: f64, offset: f64) -> V2 {
        let j = self.surface(theta);
        let n = outward(self.sigma, j.d1);
        [j.p[0] + offset * n[0], j.p[1] + offset * n[1]]
    }

    /// The contact at cam angle θ, in the ground frame.
    pub fn contact(&self, theta: f64) -> Contact {
        let (surf, pitch) = self.series(theta);
        let d = self.program.eval(theta);
        let ang = self.sigma * theta;
        let q = jet(surf);
        let point = rot(ang, q.p);
        // The normal: along the pitch curve's for a roller (the surface may
        // have a cusp), from the face otherwise.
        let (normal, rho_pitch, centre) = match pitch {
            Some(p) => {
                let pj = jet(p);
                let n = outward(self.sigma, pj.d1);
                (
                    rot(ang, n),
                    Some(radius(self.sigma, &pj, n)),
                    rot(ang, pj.p),
                )
            }
            None => {
                let n = match self.follower {
                    Follower::OscillatingFlat { .. } => {
                        let psi = self.start - d[0];
                        [-psi.sin(), psi.cos()]
                    }
                    _ => [0.0, 1.0],
                };
                (n, None, point)
            }
        };
        // w: how the follower's point at the contact moves as s grows.
        let (w, face_position) = match self.follower {
            Follower::TranslatingRoller { .. } => ([0.0, 1.0], None),
            Follower::TranslatingFlat => ([0.0, 1.0], Some(point[0])),
            Follower::OscillatingRoller { pivot, .. } => {
                let r = sub(centre, [pivot, 0.0]);
                ([r[1], -r[0]], None)
            }
            Follower::OscillatingFlat { pivot, .. } => {
                let r = sub(point, [pivot, 0.0]);
                let psi = self.start - d[0];
                ([r[1], -r[0]], Some(dot(r, [psi.cos(), psi.sin()])))
            }
        };
        let w = {
            let l = norm(w);
            [w[0] / l, w[1] / l]
        };
        let pressure_angle = self.sigma * cross(w, normal).atan2(dot(w, normal));
        Contact {
            theta,
            motion: [d[0], d[1], d[2], d[3]],
            point,
            normal,
            pressure_angle,
            rho: radius(self.sigma, &q, rot(-ang, normal)),
            rho_pitch,
            face_position,
        }
    }

    /// Surface points in the cam frame at `n` equal steps of θ over a turn.
    pub fn surface_points(&self, n: usize) -> Vec<V2> {
        (0..n)
            .map(|k| self.surface(TAU * k as f64 / n as f64).p)
            .collect()
    }
}

/// A point of a cam-frame curve and its derivatives with respect to θ:
/// p (m), p′ (m/rad), p″, p‴, p⁗.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ProfileJet {
    pub p: V2,
    pub d1: V2,
    pub d2: V2,
    pub d3: V2,
    pub d4: V2,
}

/// The jet of a cam-frame series (degree 0…4).
fn jet(v: TV) -> ProfileJet {
    ProfileJet {
        p: v.derivative(0),
        d1: v.derivative(1),
        d2: v.derivative(2),
        d3: v.derivative(3),
        d4: v.derivative(4),
    }
}

/// Outward unit normal σ p′⊥/|p′| of a cam-frame curve traversed with
/// the cam angle.
fn outward(sigma: f64, d1: V2) -> V2 {
    let l = norm(d1);
    [-sigma * d1[1] / l, sigma * d1[0] / l]
}

/// Radius of curvature, positive where convex: −σ |p′|³/(p′ × p″), with
/// the sign of p′ · t, t = −σ n⊥ the direction the curve runs where it is
/// sound (`n` the physical outward normal, cam frame). The second factor
/// makes a cusp's swallowtail, where the envelope runs backwards, count as
/// negative radius although it turns the same way.
fn radius(sigma: f64, j: &ProfileJet, n: V2) -> f64 {
    let t = [sigma * n[1], -sigma * n[0]];
    let forward = if dot(j.d1, t) < 0.0 { -1.0 } else { 1.0 };
    -sigma * forward * norm(j.d1).powi(3) / cross(j.d1, j.d2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cam::{LawKind, SegmentSpec};

    fn program(lift: f64) -> Program {
        let d = |x: f64| x.to_radians();
        Program::new(&[
            SegmentSpec::new(LawKind::Dwell, d(30.0), 0.0),
            SegmentSpec::new(LawKind::Cycloidal, d(120.0), lift),
            SegmentSpec::new(LawKind::Dwell, d(30.0), 0.0),
            SegmentSpec::new(LawKind::Poly345, d(180.0), -lift),
        ])
        .unwrap()
    }

    /// `Follower::read` asks for each dimension of the kind in the order
    /// of `KINDS`, says which may be left out, and stops at the first
    /// that cannot be read.
    #[test]
    fn read_asks_each_dimension_in_order() {
        let mut asked = Vec::new();
        let (f, dims) = Follower::read("oscillating-flat", |key, zero_default| {
            asked.push((key, zero_default));
            Ok::<f64, ()>(if zero_default { -0.01 } else { 0.2 })
        })
        .unwrap()
        .unwrap();
        assert_eq!(asked, [("pivot_distance", false), ("face_offset", true)]);
        assert_eq!(
            f,
            Follower::OscillatingFlat {
                pivot: 0.2,
                face_offset: -0.01
            }
        );
        assert_eq!(dims, [0.2, -0.01]);
        assert_eq!(Follower::from_dims("oscillating-flat", &dims), Ok(f));
        assert!(Follower::read("sideways", |_, _| Ok::<f64, ()>(1.0)).is_none());
        let missing = Follower::read("translating-roller", |key, _| match key {
            "roller_radius" => Err(key),
            _ => Ok(0.0),
        });
        assert_eq!(missing, Some(Err("roller_radius")));
    }

    fn cams() -> Vec<Cam> {
        let mut out = Vec::new();
        for ccw in [true, false] {
            let tr = Follower::TranslatingRoller {
                offset: 0.005,
                roller: 0.01,
            };
            out.push(Cam::new(program(0.015), tr, 0.04, ccw).unwrap());
            out.push(Cam::new(program(0.015), Follower::TranslatingFlat, 0.04, ccw).unwrap());
            let or = Follower::OscillatingRoller {
                pivot: 0.1,
                arm: 0.07,
                roller: 0.01,
            };
            out.push(Cam::new(program(0.25), or, 0.04, ccw).unwrap());
            let of = Follower::OscillatingFlat {
                pivot: 0.1,
                face_offset: 0.01,
            };
            out.push(Cam::new(program(0.15), of, 0.04, ccw).unwrap());
        }
        out
    }

    /// Each follower kind is made from its table entry and names itself.
    #[test]
    fn followers_from_their_dimensions() {
        for (name, fields) in Follower::KINDS {
            let dims: Vec<f64> = (1..=fields.len()).map(|k| k as f64 * 0.01).collect();
            assert_eq!(Follower::from_dims(name, &dims).unwrap().name(), name);
            assert_eq!(
                Follower::from_dims(name, &[0.0; 4]).unwrap_err(),
                format!("a {name} follower takes {} dimensions, got 4", fields.len())
            );
        }
        assert_eq!(
            Follower::from_dims("oscillating-roller", &[0.1, 0.2, 0.03]),
            Ok(Follower::OscillatingRoller {
                pivot: 0.1,
                arm: 0.2,
                roller: 0.03
            })
        );
        assert_eq!(
            Follower::kinds_text(),
            "translating-roller, translating-flat, oscillating-roller or oscillating-flat"
        );
        assert_eq!(
            Follower::from_dims("knife-edge", &[]).unwrap_err(),
            "unknown follower type 'knife-edge'"
        );
    }

    /// p′, p″, p‴ of the surface and pitch curve against central
    /// differences of the order below.
    #[test]
    fn surface_derivatives_match_differences() {
        let h = 1e-5;
        for cam in cams() {
            for &th in &[0.3, 0.9, 1.7, 2.4, 3.9, 5.0] {
                let curves: Vec<Box<dyn Fn(f64) -> ProfileJet>> = vec![
                    Box::new(|t| cam.surface(t)),
                    Box::new(|t| cam.pitch(t).unwrap_or_else(|| cam.surface(t))),
                ];
                for f in &curves {
                    let (p, m, j) = (f(th + h), f(th - h), f(th));
                    let pairs = [
                        (p.p, m.p, j.d1),
                        (p.d1, m.d1, j.d2),
                        (p.d2, m.d2, j.d3),
                        (p.d3, m.d3, j.d4),
                    ];
                    for (k, (a, b, d)) in pairs.into_iter().enumerate() {
                        for i in 0..2 {
                            let fd = (a[i] - b[i]) / (2.0 * h);
                            assert!(
                                (fd - d[i]).abs() < 1e-6 * (1.0 + d[i].abs()),
                                "{} order {} at {th}: {} vs {fd}",
                                cam.follower.name(),
                                k + 1,
                                d[i]
                            );
                        }
                    }
                }
            }
        }
    }

    /// Flat-faced translating follower: the contact lies on the face
    /// y = R_b + s at x = σ s′, and the cam's radius of
    /// curvature is R_b + s + s″ (eq. 7.29).
    #[test]
    fn flat_faced_profile_and_radius_match_closed_form() {
        for ccw in [true, false] {
            let rb = 0.04;
            let cam = Cam::new(program(0.015), Follower::TranslatingFlat, rb, ccw).unwrap();
            for k in 0..72 {
                let th = 0.05 + k as f64 * TAU / 72.0;
                let [s, s1, s2, _] = cam.contact(th).motion;
                let c = cam.contact(th);
                let sigma = if ccw { 1.0 } else { -1.0 };
                assert!((c.point[1] - (rb + s)).abs() < 1e-15);
                assert!((c.point[0] - sigma * s1).abs() < 1e-15);
                let rho = rb + s + s2;
                assert!(
                    (c.rho - rho).abs() < 1e-12 * rho.abs(),
                    "{} vs {rho}",
                    c.rho
                );
                assert_eq!(c.pressure_angle, 0.0);
            }
        }
    }

    /// Offset translating roller: tan φ = (s′ − ε)/(s + √(R_p² − ε²))
    ///, the stem at x = σε.
    #[test]
    fn offset_roller_pressure_angle_matches_closed_form() {
        for ccw in [true, false] {
            for eps in [0.0, 0.008, -0.012] {
                let (rb, rr) = (0.04, 0.01);
                let sigma = if ccw { 1.0 } else { -1.0 };
                let f = Follower::TranslatingRoller {
                    offset: eps,
                    roller: rr,
                };
                let cam = Cam::new(program(0.015), f, rb, ccw).unwrap();
                let rp: f64 = rb + rr;
                for k in 0..72 {
                    let th = 0.05 + k as f64 * TAU / 72.0;
                    let c = cam.contact(th);
                    let [s, s1, _, _] = c.motion;
                    let want = ((s1 - eps) / (s + (rp * rp - eps * eps).sqrt())).atan();
                    assert!(
                        (c.pressure_angle - want).abs() < 1e-12,
                        "ε {eps} ccw {ccw} at {th}: {} vs {want}",
                        c.pressure_angle
                    );
                    // The roller centre is on its stem at the programmed height.
                    let p = rot(sigma * th, cam.pitch(th).unwrap().p);
                    assert!((p[0] - sigma * eps).abs() < 1e-15);
                    assert!((p[1] - s - (rp * rp - eps * eps).sqrt()).abs() < 1e-15);
                }
            }
        }
    }

    /// Oscillating roller: the roller centre stays on its arm's circle and
    /// at the programmed angle; the surface is a roller radius away.
    #[test]
    fn oscillating_roller_centre_follows_the_arm() {
        let (d, l, rr) = (0.1, 0.07, 0.01);
        for ccw in [true, false] {
            let f = Follower::OscillatingRoller {
                pivot: d,
                arm: l,
                roller: rr,
            };
            let cam = Cam::new(program(0.25), f, 0.04, ccw).unwrap();
            let sigma = if ccw { 1.0 } else { -1.0 };
            let psi0 = ((0.05f64.powi(2) - d * d - l * l) / (2.0 * d * l)).acos();
            for k in 0..36 {
                let th = 0.05 + k as f64 * TAU / 36.0;
                let s = cam.program.eval(th)[0];
                let c = rot(sigma * th, cam.pitch(th).unwrap().p);
                let psi = psi0 - s;
                assert!((c[0] - d - l * psi.cos()).abs() < 1e-15);
                assert!((c[1] - l * psi.sin()).abs() < 1e-15);
                let q = rot(sigma * th, cam.surface(th).p);
                assert!((norm(sub(c, q)) - rr).abs() < 1e-15);
            }
        }
    }

    /// A plain rise pushes a centred translating roller: φ > 0 where
    /// s′ > 0, φ < 0 on the return, in both senses of rotation.
    #[test]
    fn pressure_angle_is_positive_on_the_rise() {
        for ccw in [true, false] {
            let f = Follower::TranslatingRoller {
                offset: 0.0,
                roller: 0.01,
            };
            let cam = Cam::new(program(0.015), f, 0.04, ccw).unwrap();
            let (rise, back) = (cam.contact(1.5), cam.contact(4.5));
            assert!(rise.motion[1] > 0.0 && back.motion[1] < 0.0);
            assert!(rise.pressure_angle > 0.0 && back.pressure_angle < 0.0);
        }
    }
}
