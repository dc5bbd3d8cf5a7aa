//! Design limits of a synthesised cam ([`crate::cam`]) over one turn.
//!
//! Sampled at [`SAMPLES`] cam angles, each extreme refined by golden-section
//! search and each range edge by bisection ([`Curve::ranges_where`] on the
//! surface as a curve over θ):
//! - pressure angle φ ([`Contact::pressure_angle`]): the largest |φ| on the
//!   rise segments and on the return segments, signed, with its angle;
//! - radius of curvature ρ of the cam surface (positive convex): the least
//!   value; concave ranges (a roller's pitch curve concave, ρ_pitch < 0);
//!   undercut ranges — for a roller where the pitch curve is convex with
//!   ρ_pitch < R_r (the surface loops), for a flat face where ρ < 0 (a cusp;
//!   the face cannot touch there);
//! - flat face: the contact's travel along the face, hence the least face
//!   width (Norton ch. 7: from min s′ to max s′ for a translating face);
//! - base circle sizing ([`smallest_base_radius`]): the least R_b meeting a
//!   pressure angle limit and a least radius of curvature, by bisection;
//! - follower dynamics ([`force`]): the follower (mass m, or inertia about
//!   its pivot) held on by a spring of rate k with preload F₀ at s = 0 and
//!   a viscous damper c; the cam must supply the generalised force
//!   Q = m ω² s″ + c ω s′ + F₀ + k s (inverse dynamics of the follower at
//!   constant cam speed ω; Norton ch. 10, gravity neglected), and the
//!   normal contact force F = Q/(|∂c/∂s| cos φ), c the follower's point at
//!   the contact. The follower leaves the cam where Q < 0: the jump speed
//!   is the least ω at which that happens anywhere in the turn, the
//!   smallest positive root of m s″ ω² + c s′ ω + F₀ + k s = 0 over the
//!   angles (none when every angle keeps Q > 0 at all speeds).

use std::f64::consts::TAU;

use std::sync::Arc;

use crate::cam::law::golden_max;
use crate::cam::{Cam, CamError, Contact, Follower};
use crate::curve::{Curve, Parametric};
use crate::math::{norm, sub};

/// Samples per turn.
pub const SAMPLES: usize = 3600;

/// A value and the cam angle θ (rad) where it occurs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extreme {
    pub value: f64,
    pub theta: f64,
}

/// The geometric limits of a cam over one turn.
#[derive(Clone, Debug, PartialEq)]
pub struct Geometry {
    /// Largest |φ| on the rise and on the return (signed, rad); `None`
    /// without such segments.
    pub pressure_rise: Option<Extreme>,
    pub pressure_return: Option<Extreme>,
    /// Least radius of curvature of the surface where it is convex (m).
    pub min_convex_radius: Extreme,
    /// Least |ρ| of the surface where it is concave (m); `None` if convex.
    pub min_concave_radius: Option<Extreme>,
    /// Least radius of curvature of a roller's pitch curve where it is
    /// convex (m); below the roller radius the cam is undercut.
    pub min_pitch_radius: Option<Extreme>,
    /// θ ranges (rad) where the surface is concave.
    pub concave: Vec<(f64, f64)>,
    /// θ ranges (rad) where the cam is undercut.
    pub undercut: Vec<(f64, f64)>,
    /// A flat face's contact travel along the face: least and greatest
    /// position (m) from its axis; the face must span them.
    pub face_travel: Option<(Extreme, Extreme)>,
    /// Largest distance of the surface from the cam centre (m).
    pub max_radius: f64,
}

/// What the cam's follower weighs and how it is held on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Train {
    /// Mass m (kg) of a translating follower, or inertia (kg·m²) of an
    /// oscillating one about its pivot.
    pub mass: f64,
    /// Spring rate k (N/m, or N·m/rad).
    pub spring_rate: f64,
    /// Spring preload F₀ at s = 0 (N, or N·m).
    pub preload: f64,
    /// Viscous damping c (N·s/m, or N·m·s/rad).
    pub damping: f64,
}

/// The contact force over a turn at one speed.
#[derive(Clone, Debug, PartialEq)]
pub struct Force {
    /// Cam speed ω (rad/s).
    pub omega: f64,
    /// Cam angles θ (rad).
    pub theta: Vec<f64>,
    /// Generalised force Q the cam supplies (N or N·m).
    pub generalised: Vec<f64>,
    /// Normal contact force F (N).
    pub normal: Vec<f64>,
    /// Least normal force (N) and where.
    pub min_normal: Extreme,
    /// Largest normal force (N) and where.
    pub max_normal: Extreme,
    /// Jump speed (rad/s) and the cam angle where contact is lost first;
    /// `None` when the follower never leaves the cam.
    pub jump: Option<Extreme>,
}

fn angles(n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |k| TAU * k as f64 / n as f64)
}

/// Maximum of f near θ by golden-section search on [θ − h, θ + h]; the
/// sample itself when it is higher.
fn refine_max(f: impl Fn(f64) -> f64, theta: f64, h: f64) -> Extreme {
    refine_max_within(f, theta, theta - h, theta + h)
}

/// Maximum of f near θ by golden-section search on [a, b] (a ≤ θ ≤ b,
/// rad); the sample itself when it is higher.
fn refine_max_within(f: impl Fn(f64) -> f64, theta: f64, a: f64, b: f64) -> Extreme {
    let m = golden_max(&f, a, b);
    if f(m) >= f(theta) {
        Extreme {
            value: f(m),
            theta: m.rem_euclid(TAU),
        }
    } else {
        Extreme {
            value: f(theta),
            theta,
        }
    }
}

/// The geometric limits of `cam` over one turn.
pub fn geometry(cam: &Cam) -> Geometry {
    let n = SAMPLES;
    // The surface as a curve over θ, for its range search.
    let curve = Curve::Parametric(Parametric::Cam {
        cam: Arc::new(cam.clone()),
        pitch: false,
    });
    let h = TAU / n as f64;
    let contacts: Vec<Contact> = angles(n).map(|t| cam.contact(t)).collect();
    // Largest |φ| over the samples of rise (lift > 0) or return segments,
    // refined inside the segment of the best sample.
    let specs = cam.program.specs();
    let starts = cam.program.starts();
    let pressure = |rise: bool| {
        let inside = |c: &Contact| {
            let l = specs[cam.program.segment_at(c.theta)].lift;
            if rise {
                l > 0.0
            } else {
                l < 0.0
            }
        };
        let best = contacts
            .iter()
            .filter(|c| inside(c))
            .max_by(|a, b| a.pressure_angle.abs().total_cmp(&b.pressure_angle.abs()))?;
        // The segment's end belongs to the next segment: the search stops
        // just short of it.
        let k = cam.program.segment_at(best.theta);
        let (a, b) = (
            starts[k],
            (starts[k] + specs[k].span - 1e-12).max(starts[k]),
        );
        let e = refine_max_within(
            |t| cam.contact(t).pressure_angle.abs(),
            best.theta,
            (best.theta - h).max(a),
            (best.theta + h).min(b),
        );
        let c = cam.contact(e.theta);
        Some(Extreme {
            value: c.pressure_angle,
            theta: e.theta,
        })
    };
    let roller = cam.follower.roller();
    let min_over = |f: &dyn Fn(&Contact) -> Option<f64>| {
        let best = contacts
            .iter()
            .filter_map(|c| f(c).map(|v| (c.theta, v)))
            .min_by(|a, b| a.1.total_cmp(&b.1))?;
        let e = refine_max(
            |t| f(&cam.contact(t)).map_or(f64::NEG_INFINITY, |v| -v),
            best.0,
            h,
        );
        Some(Extreme {
            value: -e.value,
            theta: e.theta,
        })
    };
    let convex = |c: &Contact| match (roller, c.rho_pitch) {
        (Some(r), Some(rp)) => (rp > r).then_some(c.rho),
        _ => (c.rho > 0.0).then_some(c.rho),
    };
    let concave = |c: &Contact| match c.rho_pitch {
        Some(rp) => (rp < 0.0).then_some(-c.rho),
        None => None,
    };
    let undercut = |t: f64| {
        let c = cam.contact(t);
        match (roller, c.rho_pitch) {
            (Some(r), Some(rp)) => rp > 0.0 && rp < r,
            _ => c.rho < 0.0,
        }
    };
    let min_pitch = min_over(&|c: &Contact| c.rho_pitch.filter(|r| *r > 0.0));
    let mut undercut_ranges = curve.ranges_where(n, undercut);
    // A roller's undercut narrower than the samples holds no sample, but
    // the refined least pitch radius lies in it: its edges by bisection
    // within a sample step either side.
    if let (Some(r), Some(e)) = (roller, min_pitch) {
        let covered = undercut_ranges
            .iter()
            .any(|&(a, b)| (a..=b).contains(&e.theta) || (a..=b).contains(&(e.theta + TAU)));
        let edge = |mut inside: f64, mut outside: f64| {
            for _ in 0..60 {
                let m = 0.5 * (inside + outside);
                if undercut(m) {
                    inside = m;
                } else {
                    outside = m;
                }
            }
            0.5 * (inside + outside)
        };
        let (before, after) = (e.theta - h, e.theta + h);
        if e.value < r && undercut(e.theta) && !covered && !undercut(before) && !undercut(after) {
            let (a, b) = (edge(e.theta, before), edge(e.theta, after));
            let shift = if a < 0.0 { TAU } else { 0.0 };
            undercut_ranges.push((a + shift, b + shift));
            undercut_ranges.sort_by(|x, y| x.0.total_cmp(&y.0));
        }
    }
    let face_travel = contacts[0].face_position.map(|_| {
        let pos = |t: f64| cam.contact(t).face_position.unwrap_or(0.0);
        let lo = contacts
            .iter()
            .min_by(|a, b| {
                a.face_position
                    .partial_cmp(&b.face_position)
                    .expect("finite")
            })
            .expect("samples");
        let hi = contacts
            .iter()
            .max_by(|a, b| {
                a.face_position
                    .partial_cmp(&b.face_position)
                    .expect("finite")
            })
            .expect("samples");
        let lo = refine_max(|t| -pos(t), lo.theta, h);
        let hi = refine_max(pos, hi.theta, h);
        (
            Extreme {
                value: -lo.value,
                theta: lo.theta,
            },
            hi,
        )
    });
    Geometry {
        pressure_rise: pressure(true),
        pressure_return: pressure(false),
        min_convex_radius: min_over(&convex).unwrap_or(Extreme {
            value: f64::NAN,
            theta: 0.0,
        }),
        min_concave_radius: min_over(&concave),
        min_pitch_radius: min_pitch,
        concave: curve.ranges_where(n, |t| cam.contact(t).rho_pitch.is_some_and(|rp| rp < 0.0)),
        undercut: undercut_ranges,
        face_travel,
        max_radius: contacts.iter().map(|c| norm(c.point)).fold(0.0, f64::max),
    }
}

/// |∂c/∂s|: how far the follower's point at the contact (a roller's
/// centre) moves per unit of s (1 for a translating follower, its distance
/// from the pivot for an oscillating one).
fn lever(cam: &Cam, c: &Contact) -> f64 {
    match cam.follower {
        Follower::TranslatingRoller { .. } | Follower::TranslatingFlat => 1.0,
        Follower::OscillatingRoller { pivot, .. } => {
            let centre = cam.pitch(c.theta).expect("a roller has a pitch curve").p;
            let centre = crate::math::rot(cam.sigma * c.theta, centre);
            norm(sub(centre, [pivot, 0.0]))
        }
        Follower::OscillatingFlat { pivot, .. } => norm(sub(c.point, [pivot, 0.0])),
    }
}

/// The contact force over a turn at cam speed `omega` (rad/s), and the
/// jump speed.
pub fn force(cam: &Cam, train: &Train, omega: f64) -> Result<Force, CamError> {
    for (what, v) in [
        ("mass", train.mass),
        ("spring rate", train.spring_rate),
        ("preload", train.preload),
        ("damping", train.damping),
    ] {
        if !(v >= 0.0 && v.is_finite()) {
            return Err(CamError(format!(
                "{what} must be zero or positive, got {v}"
            )));
        }
    }
    if !(omega > 0.0 && omega.is_finite()) {
        return Err(CamError(format!(
            "the cam speed must be positive, got {omega} rad/s"
        )));
    }
    let n = SAMPLES;
    let q = |c: &Contact| {
        let [s, s1, s2, _] = c.motion;
        train.mass * omega * omega * s2
            + train.damping * omega * s1
            + train.preload
            + train.spring_rate * s
    };
    let normal = |c: &Contact| q(c) / (lever(cam, c) * c.pressure_angle.cos());
    let contacts: Vec<Contact> = angles(n).map(|t| cam.contact(t)).collect();
    let generalised: Vec<f64> = contacts.iter().map(q).collect();
    let normals: Vec<f64> = contacts.iter().map(normal).collect();
    let h = TAU / n as f64;
    let arg = |better: &dyn Fn(f64, f64) -> bool| {
        let mut k = 0;
        for i in 1..n {
            if better(normals[i], normals[k]) {
                k = i;
            }
        }
        contacts[k].theta
    };
    let lo = refine_max(|t| -normal(&cam.contact(t)), arg(&|a, b| a < b), h);
    let hi = refine_max(|t| normal(&cam.contact(t)), arg(&|a, b| a > b), h);
    // The smallest positive root of m s″ ω² + c s′ ω + F₀ + k s at θ.
    let root = |t: f64| {
        let [s, s1, s2, _] = cam.program.eval(t)[..4].try_into().expect("four");
        let (a, b, c) = (
            train.mass * s2,
            train.damping * s1,
            train.preload + train.spring_rate * s,
        );
        if c <= 0.0 {
            return Some(0.0);
        }
        if a >= 0.0 && (b >= 0.0 || b * b < 4.0 * a * c) {
            return None;
        }
        if a == 0.0 {
            return Some(-c / b);
        }
        let d = (b * b - 4.0 * a * c).sqrt();
        [(-b - d) / (2.0 * a), (-b + d) / (2.0 * a)]
            .into_iter()
            .filter(|w| *w > 0.0)
            .min_by(f64::total_cmp)
    };
    let jump = angles(n)
        .filter_map(|t| root(t).map(|w| (t, w)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(t, _)| {
            let e = refine_max(|x| root(x).map_or(f64::NEG_INFINITY, |w| -w), t, h);
            Extreme {
                value: -e.value,
                theta: e.theta,
            }
        });
    Ok(Force {
        omega,
        theta: contacts.iter().map(|c| c.theta).collect(),
        generalised,
        normal: normals,
        min_normal: Extreme {
            value: -lo.value,
            theta: lo.theta,
        },
        max_normal: hi,
        jump,
    })
}

/// The smallest base circle radius in [`lo`, `hi`] (m) for which every
/// pressure angle stays within `max_pressure` (rad) and the surface's least
/// convex radius of curvature is at least `min_radius` (m) with no
/// undercut (and, under a flat face, no concave part); `None` when no
/// radius on the search grid passes. The range is scanned at
/// [`BASE_GRID`] radii and the first passing one refined by bisection
/// against its failing neighbour to 1e-6 relative; the follower's other
/// dimensions stay as given (an oscillating arm that cannot reach a
/// radius fails there). A radius at which a sampled pressure angle
/// already exceeds the limit fails without the rest of its geometry
/// ([`pressure_exceeds`]): the same answer, sooner.
pub fn smallest_base_radius(
    cam: &Cam,
    max_pressure: Option<f64>,
    min_radius: Option<f64>,
    lo: f64,
    hi: f64,
) -> Result<Option<f64>, CamError> {
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return Err(CamError(format!(
            "the base circle search needs 0 < lo < hi, got {lo} and {hi} m"
        )));
    }
    let ok = |rb: f64| {
        let Ok(c) = cam.with_base_radius(rb) else {
            return false;
        };
        if max_pressure.is_some_and(|m| pressure_exceeds(&c, m)) {
            return false;
        }
        meets(&c, &geometry(&c), max_pressure, min_radius)
    };
    Ok(smallest_passing(ok, lo, hi))
}

/// Whether the cam `c` of geometry `g` keeps every pressure angle within
/// `max_pressure` (rad) and its least convex radius of curvature at least
/// `min_radius` (m), with no undercut (and, under a flat face, no concave
/// part).
fn meets(c: &Cam, g: &Geometry, max_pressure: Option<f64>, min_radius: Option<f64>) -> bool {
    let phi = [g.pressure_rise, g.pressure_return]
        .iter()
        .flatten()
        .map(|e| e.value.abs())
        .fold(0.0, f64::max);
    let pressure_ok = max_pressure.is_none_or(|m| phi <= m);
    let radius_ok = g.undercut.is_empty()
        && min_radius.is_none_or(|m| g.min_convex_radius.value >= m)
        && (c.follower.roller().is_some() || g.concave.is_empty());
    pressure_ok && radius_ok
}

/// The smallest radius in [`lo`, `hi`] (m) that passes `ok`, as
/// [`smallest_base_radius`] searches: the first of [`BASE_GRID`] + 1
/// radii that passes, refined by bisection against its failing
/// neighbour to 1e-6 relative.
fn smallest_passing(ok: impl Fn(f64) -> bool, lo: f64, hi: f64) -> Option<f64> {
    let at = |k: usize| lo + (hi - lo) * k as f64 / BASE_GRID as f64;
    let k = (0..=BASE_GRID).find(|&k| ok(at(k)))?;
    if k == 0 {
        return Some(lo);
    }
    let (mut a, mut b) = (at(k - 1), at(k));
    while b - a > 1e-6 * b {
        let m = 0.5 * (a + b);
        if ok(m) {
            b = m;
        } else {
            a = m;
        }
    }
    Some(b)
}

/// Whether the pressure angle of `cam` at one of [`geometry`]'s samples in
/// a rise or a return exceeds `max` (rad) in size. Then so does the
/// extreme [`geometry`] reports for that rise or return, which is refined
/// from the largest such sample and never below it: the cam fails a
/// pressure limit of `max`. Stops at the first such sample.
fn pressure_exceeds(cam: &Cam, max: f64) -> bool {
    let specs = cam.program.specs();
    angles(SAMPLES).any(|t| {
        specs[cam.program.segment_at(t)].lift != 0.0 && cam.contact(t).pressure_angle.abs() > max
    })
}

/// Radii scanned by [`smallest_base_radius`].
pub const BASE_GRID: usize = 40;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cam::{LawKind, Program, SegmentSpec};
    use std::f64::consts::PI;

    fn deg(x: f64) -> f64 {
        x.to_radians()
    }

    fn program(lift: f64, rise: f64) -> Program {
        Program::new(&[
            SegmentSpec::new(LawKind::Cycloidal, deg(rise), lift),
            SegmentSpec::new(LawKind::Dwell, deg(180.0 - rise), 0.0),
            SegmentSpec::new(LawKind::Cycloidal, deg(rise), -lift),
            SegmentSpec::new(LawKind::Dwell, deg(180.0 - rise), 0.0),
        ])
        .unwrap()
    }

    /// Flat face: the least radius of curvature min(R_b + s + s″) and the
    /// face travel min/max s′ against the closed forms on a fine grid.
    #[test]
    fn flat_face_radius_and_travel_match_closed_form() {
        let (rb, h, b) = (0.05, 0.01, deg(90.0));
        let cam = Cam::new(program(h, 90.0), Follower::TranslatingFlat, rb, true).unwrap();
        let g = geometry(&cam);
        let grid = (0..200_000).map(|k| TAU * k as f64 / 200_000.0);
        let rho = grid
            .clone()
            .map(|t| {
                let d = cam.program.eval(t);
                rb + d[0] + d[2]
            })
            .fold(f64::INFINITY, f64::min);
        assert!(
            (g.min_convex_radius.value - rho).abs() < 1e-9,
            "{} vs {rho}",
            g.min_convex_radius.value
        );
        // Cycloidal: s′ peaks at 2h/β.
        let (lo, hi) = g.face_travel.unwrap();
        assert!((hi.value - 2.0 * h / b).abs() < 1e-12, "{}", hi.value);
        assert!((lo.value + 2.0 * h / b).abs() < 1e-12);
        assert!(g.undercut.is_empty() && g.concave.is_empty());
        // Centred cycloidal rise of a translating roller: the largest
        // pressure angle against the fine grid of atan(s′/(R_p + s)).
        let f = Follower::TranslatingRoller {
            offset: 0.0,
            roller: 0.005,
        };
        let cam = Cam::new(program(h, 90.0), f, rb, true).unwrap();
        let g = geometry(&cam);
        let want = grid
            .map(|t| {
                let d = cam.program.eval(t);
                (d[1] / (rb + 0.005 + d[0])).atan()
            })
            .fold(0.0, f64::max);
        let got = g.pressure_rise.unwrap();
        assert!((got.value - want).abs() < 1e-10, "{} vs {want}", got.value);
        assert!(got.theta > 0.0 && got.theta < deg(90.0));
        assert!(g.pressure_return.unwrap().value < 0.0);
    }

    /// A published problem (Shigley & Uicker, *Theory of Machines and
    /// Mechanisms*, disk cam chapter): a disk cam drives a radial
    /// flat-faced follower with simple harmonic motion, out and back in one
    /// revolution, total displacement 50 mm, minimum radius 25 mm. Its
    /// answer: s = 25(1 − cos θ) mm, the contour is a circle of radius
    /// 50 mm whose centre lies 25 mm from the cam centre (an eccentric), and
    /// the face needs 50 mm (contact ±25 mm from the stem axis).
    #[test]
    fn published_harmonic_flat_face_cam_is_an_eccentric_circle() {
        let program = Program::new(&[
            SegmentSpec::new(LawKind::SimpleHarmonic, PI, 0.05),
            SegmentSpec::new(LawKind::SimpleHarmonic, PI, -0.05),
        ])
        .unwrap();
        for ccw in [true, false] {
            let cam = Cam::new(program.clone(), Follower::TranslatingFlat, 0.025, ccw).unwrap();
            for k in 0..360 {
                let th = TAU * k as f64 / 360.0;
                let p = cam.surface(th).p;
                assert!((norm(sub(p, [0.0, -0.025])) - 0.05).abs() < 1e-15, "{p:?}");
                assert!((cam.contact(th).rho - 0.05).abs() < 1e-14);
                assert!((cam.program.eval(th)[0] - 0.025 * (1.0 - th.cos())).abs() < 1e-15);
            }
            let g = geometry(&cam);
            let (lo, hi) = g.face_travel.unwrap();
            assert!((hi.value - lo.value - 0.05).abs() < 1e-12);
            assert!((g.min_convex_radius.value - 0.05).abs() < 1e-12);
        }
    }

    /// A flat face on a small base circle with a steep rise has a cusp
    /// where R_b + s + s″ < 0: the undercut range's edges are the roots.
    #[test]
    fn flat_face_undercut_is_where_the_radius_is_negative() {
        let (rb, h) = (0.01, 0.02);
        let cam = Cam::new(program(h, 60.0), Follower::TranslatingFlat, rb, true).unwrap();
        let g = geometry(&cam);
        assert!(!g.undercut.is_empty());
        for &(a, b) in &g.undercut {
            for t in [a, b] {
                let d = cam.program.eval(t);
                assert!(
                    (rb + d[0] + d[2]).abs() < 1e-9,
                    "ρ at an edge: {}",
                    rb + d[0] + d[2]
                );
            }
            let d = cam.program.eval(0.5 * (a + b));
            assert!(rb + d[0] + d[2] < 0.0);
        }
    }

    /// Jump speed without damping: ω² = min over s″ < 0 of (F₀ + k s)/(m|s″|).
    #[test]
    fn jump_speed_matches_closed_form() {
        let cam = Cam::new(program(0.008, 70.0), Follower::TranslatingFlat, 0.02, true).unwrap();
        let train = Train {
            mass: 0.2,
            spring_rate: 20_000.0,
            preload: 200.0,
            damping: 0.0,
        };
        let f = force(&cam, &train, 100.0).unwrap();
        let want = (0..400_000)
            .map(|k| TAU * k as f64 / 400_000.0)
            .filter_map(|t| {
                let d = cam.program.eval(t);
                (d[2] < 0.0).then(|| ((200.0 + 20_000.0 * d[0]) / (0.2 * -d[2])).sqrt())
            })
            .fold(f64::INFINITY, f64::min);
        let got = f.jump.unwrap().value;
        assert!((got - want).abs() < 1e-7 * want, "{got} vs {want}");
        // Below the jump speed the contact force stays positive; above it
        // it goes negative.
        assert!(force(&cam, &train, 0.99 * got).unwrap().min_normal.value > 0.0);
        assert!(force(&cam, &train, 1.01 * got).unwrap().min_normal.value < 0.0);
        // At rest the force is the spring's: F₀ + k s.
        let slow = force(&cam, &train, 1e-9).unwrap();
        assert!((slow.min_normal.value - 200.0).abs() < 1e-6);
        assert!((slow.max_normal.value - (200.0 + 20_000.0 * 0.008)).abs() < 1e-6);
    }

    /// Issue 27: each pressure angle extreme is reported at an angle inside
    /// a segment of its kind (a rise for the rise, a return for the
    /// return), also where |φ| grows towards the segment's ends (the
    /// golden-section search used to step over them into the dwells: to
    /// 359.95° for a rise from 0°, to 270° for a return ending there).
    #[test]
    fn issue27_pressure_extreme_inside_its_segment() {
        let mut checked = 0;
        for (rb, pivot, arm, swing, ccw) in [
            (0.05, 0.1, 0.06, 15.0, true),
            (0.03, 0.1, 0.06, 15.0, true),
            (0.03, 0.12, 0.08, 30.0, false),
            (0.05, 0.12, 0.08, 30.0, true),
        ] {
            let f = Follower::OscillatingRoller {
                pivot,
                arm,
                roller: 0.01,
            };
            let Ok(cam) = Cam::new(program(deg(swing), 90.0), f, rb, ccw) else {
                continue;
            };
            let g = geometry(&cam);
            let starts = cam.program.starts();
            let specs = cam.program.specs();
            for (e, rise) in [(g.pressure_rise, true), (g.pressure_return, false)] {
                let e = e.unwrap();
                let k = cam.program.segment_at(e.theta);
                assert!(
                    e.theta >= starts[k] && e.theta < starts[k] + specs[k].span,
                    "{e:?}"
                );
                assert_eq!(specs[k].lift > 0.0, rise, "{e:?} in segment {k}");
                assert_eq!(specs[k].lift < 0.0, !rise, "{e:?} in segment {k}");
                // The value is the pressure angle there.
                assert_eq!(e.value, cam.contact(e.theta).pressure_angle);
                checked += 1;
            }
        }
        assert_eq!(checked, 8);
    }

    /// Issue 27: a rise so steep that the roller's undercut is narrower
    /// than the samples (0.1°) is still reported as an undercut range, in
    /// agreement with the least pitch radius below the roller radius; its
    /// edges are where ρ_pitch = R_r.
    #[test]
    fn issue27_narrow_undercut_is_reported() {
        let roller = 0.01;
        let f = Follower::TranslatingRoller {
            offset: 0.0,
            roller,
        };
        let program = Program::new(&[
            SegmentSpec::new(LawKind::Cycloidal, deg(0.5), 0.01),
            SegmentSpec::new(LawKind::Dwell, deg(179.5), 0.0),
            SegmentSpec::new(LawKind::Cycloidal, deg(90.0), -0.01),
            SegmentSpec::new(LawKind::Dwell, deg(90.0), 0.0),
        ])
        .unwrap();
        let cam = Cam::new(program, f, 0.03, true).unwrap();
        let g = geometry(&cam);
        let least = g.min_pitch_radius.unwrap();
        assert!(least.value < roller, "{least:?}");
        assert!(!g.undercut.is_empty());
        assert!(g
            .undercut
            .iter()
            .any(|&(a, b)| a <= least.theta && least.theta <= b));
        for &(a, b) in &g.undercut {
            assert!(a < b);
            let rp = |t: f64| cam.contact(t).rho_pitch.unwrap();
            let mid = rp(0.5 * (a + b));
            assert!(mid > 0.0 && mid < roller, "{mid}");
            for t in [a, b] {
                assert!((rp(t) - roller).abs() < 1e-6 * roller, "{} at {t}", rp(t));
            }
        }
    }

    /// Base circle sizing: the smallest R_b keeps a centred roller's
    /// pressure angle at the limit (checked at the answer and just below).
    #[test]
    fn smallest_base_radius_meets_the_pressure_limit() {
        let f = Follower::TranslatingRoller {
            offset: 0.0,
            roller: 0.005,
        };
        let cam = Cam::new(program(0.01, 60.0), f, 0.05, true).unwrap();
        let limit = deg(30.0);
        let rb = smallest_base_radius(&cam, Some(limit), None, 0.001, 0.2)
            .unwrap()
            .unwrap();
        let phi = |rb: f64| {
            let g = geometry(&cam.with_base_radius(rb).unwrap());
            g.pressure_rise.unwrap().value.abs()
        };
        assert!(phi(rb) <= limit);
        assert!(phi(rb * 0.999) > limit);
    }

    /// The search with the early pressure check answers as the scan and
    /// bisection of whole geometries: a centred and an offset translating
    /// roller and an oscillating roller, against pressure and radius limits.
    #[test]
    fn smallest_base_radius_is_that_of_whole_geometries() {
        // The search of `smallest_base_radius` with every radius judged by
        // its whole geometry.
        let whole = |cam: &Cam, max: Option<f64>, min: Option<f64>, lo: f64, hi: f64| {
            let ok = |rb: f64| {
                cam.with_base_radius(rb)
                    .is_ok_and(|c| meets(&c, &geometry(&c), max, min))
            };
            smallest_passing(ok, lo, hi)
        };
        let followers = [
            Follower::TranslatingRoller {
                offset: 0.0,
                roller: 0.005,
            },
            Follower::TranslatingRoller {
                offset: 0.004,
                roller: 0.006,
            },
            Follower::OscillatingRoller {
                pivot: 0.14,
                arm: 0.08,
                roller: 0.012,
            },
        ];
        let mut found = 0;
        for f in followers {
            // A swing (rad) for the arm, a lift (m) for the stems.
            let lift = if matches!(f, Follower::OscillatingRoller { .. }) {
                deg(30.0)
            } else {
                0.01
            };
            let cam = Cam::new(program(lift, 70.0), f, 0.08, true).unwrap();
            for (max, min) in [
                (Some(deg(30.0)), None),
                (Some(deg(35.0)), Some(0.01)),
                (None, Some(0.02)),
            ] {
                let got = smallest_base_radius(&cam, max, min, 0.02, 0.2).unwrap();
                assert_eq!(
                    got,
                    whole(&cam, max, min, 0.02, 0.2),
                    "{f:?} {max:?} {min:?}"
                );
                found += usize::from(got.is_some());
            }
        }
        assert!(found >= 6, "{found}");
    }
}
