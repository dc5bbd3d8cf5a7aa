//! The signed gap of an open cam contact: the least distance between a cam
//! curve and its follower's face or curve, with the witness points, the
//! contact parameters and the rate of the gap.
//!
//! The gap g (m) is measured along a unit normal N (global) that points
//! from the solid side of body i's feature to body j's: with witness
//! points P_i on body i and P_j on body j,
//!
//! g = Nᵀ (P_j − P_i),
//!
//! positive apart, zero in contact, negative when the features overlap
//! (the depth of the overlap). At the witnesses g is stationary in the
//! contact parameters, so its rate is that of the material points there
//! (the envelope theorem): ġ = Ṅᵀ (P_j − P_i) + Nᵀ (v_j − v_i), with N
//! turning with the body whose outline defines it.
//!
//! - A curve C_i on a face (the line through P_j with unit normal m
//!   pointing into the cam's side): g = min over C_i of mᵀ (p − P_j),
//!   N = −m; the minimum of a linear function over the whole curve
//!   ([`search::support`]: every sample, then Newton), so a concave
//!   profile is measured at its true nearest point.
//! - Two curves: the pairs whose points face each other along a common
//!   normal ([`search::contact_pair`]): the pair followed from the last
//!   witnesses and the pair found from every sample pair; the gap is the
//!   smaller of the two signed values, so an overlap followed from outside
//!   is measured at its depth and another part of a concave profile that
//!   comes closer is found. N is the outward normal of C_i when C_i is
//!   closed, else the inward normal of C_j.

use super::contact::{from_side, gap, gap_rate, outward_at};
use super::{search, Curve};
use crate::math::{dot, perp, point, point_vel, rot, rot_t, scale, sub, V2};

/// The gap of a contact at one configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gap {
    /// g (m): positive apart, negative in overlap.
    pub gap: f64,
    /// ġ (m/s).
    pub rate: f64,
    /// Contact parameters at the witnesses (s_i, s_j); s_j is 0 for a face.
    pub params: [f64; 2],
    /// Witness points P_i, P_j (global, m).
    pub points: [V2; 2],
    /// N (global unit vector), from body i's side to body j's.
    pub normal: V2,
}

/// The two features of a cam contact whose gap is measured.
#[derive(Clone, Debug)]
pub enum Features {
    /// Curve C_i on body i and a face of body j through `point` (body j
    /// frame, m) with unit normal `m` into the cam's side (body j frame).
    Face { curve: Curve, point: V2, m: V2 },
    /// Curves C_i and C_j; N from the closed curve of `side` (0: C_i
    /// outward, 1: C_j inward) with orientation σ.
    Curves {
        curves: [Curve; 2],
        side: usize,
        sigma: f64,
    },
}

impl Features {
    /// The gap at bodies (q_i, q_j), (q̇_i, q̇_j), from the last witness
    /// parameters `guess`.
    pub fn gap(&self, q: [[f64; 3]; 2], qd: [[f64; 3]; 2], guess: Option<[f64; 2]>) -> Gap {
        match self {
            Features::Face { curve, point, m } => {
                face_gap(curve, q, qd, *point, *m, guess.map(|g| g[0]))
            }
            Features::Curves {
                curves,
                side,
                sigma,
            } => curve_gap([&curves[0], &curves[1]], q, qd, (*side, *sigma), guess),
        }
    }

    /// N (global unit) of the closed contact at contact parameters `own`.
    pub fn normal(&self, q: [[f64; 3]; 2], own: [f64; 2]) -> V2 {
        match self {
            Features::Face { m, .. } => scale(-1.0, rot(q[1][2], *m)),
            Features::Curves {
                curves,
                side,
                sigma,
            } => from_side(
                *side,
                rot(q[*side][2], outward_at(&curves[*side], *sigma, own[*side])),
            ),
        }
    }
}

/// The gap between curve `ci` of a body at (q_i, q̇_i) and the face of a
/// body at (q_j, q̇_j) through `face_point` with unit normal `m` (both in
/// body j's frame; m points into the cam's side). `guess` is the last
/// witness parameter on C_i.
pub(crate) fn face_gap(
    ci: &Curve,
    q: [[f64; 3]; 2],
    qd: [[f64; 3]; 2],
    face_point: V2,
    m: V2,
    guess: Option<f64>,
) -> Gap {
    let mg = rot(q[1][2], m);
    let pj0 = point(q[1], face_point);
    let dir = rot_t(q[0][2], scale(-1.0, mg));
    let value = |s: f64| dot(mg, sub(point(q[0], ci.jet(s).p), pj0));
    let mut s = search::support(ci, dir, None);
    if let Some(g) = guess {
        let local = search::support(ci, dir, Some(g));
        if value(local) < value(s) {
            s = local;
        }
    }
    let pi = point(q[0], ci.jet(s).p);
    let n = scale(-1.0, mg);
    let g = gap(n, pi, pj0);
    let pj = sub(pi, scale(g, mg));
    // Rates of the material points at the witnesses.
    let vi = point_vel(q[0], qd[0], ci.jet(s).p);
    let vj = point_vel(q[1], qd[1], rot_t(q[1][2], sub(pj, [q[1][0], q[1][1]])));
    let n_dot = scale(qd[1][2], perp(n));
    Gap {
        gap: g,
        rate: gap_rate(n, n_dot, [pi, pj], [vi, vj]),
        params: [s, 0.0],
        points: [pi, pj],
        normal: n,
    }
}

/// The gap between curve `ci` on a body at (q_i, q̇_i) and curve `cj` on a
/// body at (q_j, q̇_j). `sigma` is the orientation of the closed curve
/// that defines N: `(0, σ_i)` for C_i, `(1, σ_j)` for C_j. `guess`: the
/// last witness parameters.
pub(crate) fn curve_gap(
    c: [&Curve; 2],
    q: [[f64; 3]; 2],
    qd: [[f64; 3]; 2],
    sigma: (usize, f64),
    guess: Option<[f64; 2]>,
) -> Gap {
    let at = |s: [f64; 2]| measure(c, q, qd, sigma, s);
    let mut best = at(search::contact_pair(c[0], q[0], c[1], q[1], None));
    if let Some(g) = guess {
        let local = at(search::contact_pair(c[0], q[0], c[1], q[1], Some(g)));
        if local.gap < best.gap {
            best = local;
        }
    }
    best
}

/// The signed gap of two curves at the parameters `s`.
fn measure(
    c: [&Curve; 2],
    q: [[f64; 3]; 2],
    qd: [[f64; 3]; 2],
    (side, sign): (usize, f64),
    s: [f64; 2],
) -> Gap {
    let p = [0, 1].map(|k| c[k].jet(s[k]).p);
    let pw = [0, 1].map(|k| point(q[k], p[k]));
    let v = [0, 1].map(|k| point_vel(q[k], qd[k], p[k]));
    // N: outward of C_i, or inward of C_j.
    let n = from_side(side, rot(q[side][2], outward_at(c[side], sign, s[side])));
    let n_dot = scale(qd[side][2], perp(n));
    Gap {
        gap: gap(n, pw[0], pw[1]),
        rate: gap_rate(n, n_dot, pw, v),
        params: s,
        points: pw,
        normal: n,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::Polar;

    /// A circle of radius `r` about the body origin (polar profile).
    fn circle(r: f64) -> Curve {
        Polar::circle([0.0, 0.0], r).expect("circle").into()
    }

    #[test]
    fn face_gap_of_a_circle_is_centre_height_minus_radius() {
        // Circle r = 0.3 at (0.1, 0.5) above the face y = 0 (ground face,
        // m = +y into the cam's side): g = 0.5 − 0.3 = 0.2.
        let q = [[0.1, 0.5, 0.7], [0.0, 0.0, 0.0]];
        let qd = [[0.0, -2.0, 1.0], [0.0; 3]];
        let g = face_gap(&circle(0.3), q, qd, [0.0, 0.0], [0.0, 1.0], None);
        assert!((g.gap - 0.2).abs() < 1e-12, "{g:?}");
        assert!((g.rate + 2.0).abs() < 1e-9, "{g:?}");
        assert!((g.points[1][0] - 0.1).abs() < 1e-9);
    }

    #[test]
    fn curve_gap_of_two_circles_is_centre_distance_minus_radii() {
        let c = [circle(0.3), circle(0.1)];
        let q = [[0.0, 0.0, 0.2], [0.3, 0.4, -1.0]];
        let qd = [[0.0; 3], [0.0; 3]];
        let g = curve_gap([&c[0], &c[1]], q, qd, (0, 1.0), None);
        assert!((g.gap - (0.5 - 0.4)).abs() < 1e-10, "{g:?}");
        // Overlap: centres 0.35 apart, depth 0.05.
        let q = [[0.0, 0.0, 0.2], [0.21, 0.28, -1.0]];
        let g = curve_gap([&c[0], &c[1]], q, qd, (0, 1.0), Some(g.params));
        assert!((g.gap + 0.05).abs() < 1e-10, "{g:?}");
    }

    #[test]
    fn face_gap_finds_the_nearest_point_of_a_concave_profile() {
        // A peanut ρ = 1 + 0.6 cos 2α (concave near α = ±π/2) whose waist
        // faces the ground: the nearest points are the lobes' flanks, not
        // the waist the local search starts from.
        let curve: Curve = Polar::expr([0.0, 0.0], "1 + 0.6*cos(2*a)")
            .expect("profile")
            .into();
        let q = [[0.0, 2.0, 0.0], [0.0; 3]];
        let g = face_gap(
            &curve,
            q,
            [[0.0; 3]; 2],
            [0.0, 0.0],
            [0.0, 1.0],
            Some(-0.5 * std::f64::consts::PI),
        );
        // min over α of 2 + ρ(α) sin α, by dense sampling.
        let exact = (0..200_000)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 200_000.0;
                2.0 + (1.0 + 0.6 * (2.0 * a).cos()) * a.sin()
            })
            .fold(f64::INFINITY, f64::min);
        assert!((g.gap - exact).abs() < 1e-8, "{} vs {exact}", g.gap);
    }

    #[test]
    fn gap_rate_matches_finite_differences_on_random_motions() {
        // q(t) = q0 + q̇ t for random q0, q̇; ġ against the central
        // difference of g(t).
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
        };
        let cam: Curve = Polar::expr([0.05, 0.0], "0.4 + 0.1*cos(a) + 0.03*sin(3*a)")
            .expect("profile")
            .into();
        let roller = circle(0.08);
        for _ in 0..20 {
            let q0 = [
                [rnd(), rnd(), 3.0 * rnd()],
                [rnd() * 0.1, 0.7 + 0.2 * rnd(), rnd()],
            ];
            let qd = [[rnd(), rnd(), rnd()], [rnd(), rnd(), rnd()]];
            let at = |t: f64| {
                let mut q = q0;
                for k in 0..2 {
                    for d in 0..3 {
                        q[k][d] += qd[k][d] * t;
                    }
                }
                q
            };
            let h = 1e-6;
            let f = |t: f64| face_gap(&cam, at(t), qd, [0.0, 0.0], [0.0, -1.0], None);
            let fd = (f(h).gap - f(-h).gap) / (2.0 * h);
            assert!(
                (f(0.0).rate - fd).abs() < 1e-6,
                "face: {} vs {fd}",
                f(0.0).rate
            );
            let g = |t: f64| curve_gap([&cam, &roller], at(t), qd, (0, 1.0), None);
            let fd = (g(h).gap - g(-h).gap) / (2.0 * h);
            assert!(
                (g(0.0).rate - fd).abs() < 1e-6,
                "curves: {} vs {fd}",
                g(0.0).rate
            );
        }
    }
}
