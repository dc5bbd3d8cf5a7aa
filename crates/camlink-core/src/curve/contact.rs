//! The geometry of a contact, in one place: which side of a curve or a
//! face is solid, the outward unit normal, the signed gap and its rate
//! along that normal, and the normal force from the force the contact's
//! equations put on a body. Every contact computation (the flat-faced
//! follower's start search, the gap of an open contact
//! ([`super::distance`]), the gap features of a unilateral joint, the
//! unilateral events and the contact-force outputs) takes these from here.
//!
//! Conventions (every vector in one frame, the caller's; lengths m):
//!
//! - A closed curve (every polar profile, a closed parametric curve) bounds
//!   its body's material; with tangent g = dp/ds and orientation σ (+1
//!   counterclockwise, −1 clockwise, [`Curve::orientation`]) its outward
//!   unit normal is n = −σ g⊥/|g| ([`outward`]).
//! - An open curve has its material on the side of the mean of its
//!   sampled points ([`sample_mean`], [`away_from`], [`side_of`]).
//! - Of a contact between the features of bodies i and j, N is the unit
//!   normal from the solid side of body i's feature to body j's: the
//!   outward normal of C_i when C_i is closed, else the inward normal of
//!   C_j ([`solid_side`], [`from_side`]).
//! - The gap is g = Nᵀ (P_j − P_i) between the witness points P_i, P_j:
//!   positive apart, negative in overlap ([`gap`]); its rate
//!   ġ = Ṅᵀ (P_j − P_i) + Nᵀ (v_j − v_i) ([`gap_rate`]).
//! - The normal force is N = F_j · N, F_j the force (N) the contact exerts
//!   on body j: positive when the bodies press on each other
//!   ([`normal_force`]). From the multipliers λ of a contact's rows,
//!   F_j = −Φ_{r_j}ᵀλ: λ itself for a point-on-curve contact (Φ_{r_j} = −I),
//!   n_f λ₀ for a face of unit normal n_f ([`face_normal_force`]).

use super::Curve;
use crate::math::{dot, norm, perp, scale, sub, V2};

/// Samples of a curve for its mean point.
pub(crate) const MEAN_SAMPLES: usize = 64;

/// The mean of [`MEAN_SAMPLES`] points of curve `c`, evenly spaced in its
/// parameter (body frame, m): a point on the solid side of an open curve.
pub(crate) fn sample_mean(c: &Curve) -> V2 {
    let (s0, s1) = c.range();
    let n = MEAN_SAMPLES as f64;
    (0..MEAN_SAMPLES).fold([0.0; 2], |m, k| {
        let p = c.jet(s0 + (s1 - s0) * k as f64 / n).p;
        [m[0] + p[0] / n, m[1] + p[1] / n]
    })
}

/// The outward unit normal n = −σ g⊥/|g| of a closed curve of orientation
/// σ (±1) whose tangent is `g` (same frame as g).
pub(crate) fn outward(sigma: f64, g: V2) -> V2 {
    let l = dot(g, g).sqrt();
    scale(-sigma / l, perp(g))
}

/// The outward unit normal (body frame) of closed curve `curve` of
/// orientation σ at parameter `s`.
pub(crate) fn outward_at(curve: &Curve, sigma: f64, s: f64) -> V2 {
    outward(sigma, curve.jet(s).d1)
}

/// N from the outward normal `out` of the closed curve of `side`: `out`
/// itself for body i's curve (side 0), −`out` for body j's (side 1).
pub(crate) fn from_side(side: usize, out: V2) -> V2 {
    if side == 0 {
        out
    } else {
        scale(-1.0, out)
    }
}

/// The side whose closed curve defines N, with its orientation σ, from
/// the orientations of C_i and C_j (`None`: open or absent): C_i when it
/// is closed, else C_j; `None` when neither is closed.
pub(crate) fn solid_side(sides: [Option<f64>; 2]) -> Option<(usize, f64)> {
    match sides {
        [Some(sigma), _] => Some((0, sigma)),
        [None, Some(sigma)] => Some((1, sigma)),
        [None, None] => None,
    }
}

/// N of two closed curves touching at outward normals `ni`, `nj` (unit,
/// global) with curvatures `ki`, `kj` (1/m): touching from outside
/// (nᵢ · nⱼ ≤ 0), N = nᵢ; one inside the other, the curve of smaller |κ|
/// encloses the other and is a hole in its body: N = −nⱼ when C_i is the
/// hole, nⱼ when C_j is.
pub(crate) fn closed_pair(ni: V2, nj: V2, ki: f64, kj: f64) -> V2 {
    if dot(ni, nj) <= 0.0 {
        ni
    } else if ki.abs() < kj.abs() {
        scale(-1.0, nj)
    } else {
        nj
    }
}

/// The side of a face line through `face` with normal `n` on which the
/// point `inside` lies: +1 where n points, −1 on the other side (+1 on the
/// line).
pub(crate) fn side_of(n: V2, face: V2, inside: V2) -> f64 {
    if dot(n, sub(inside, face)) < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// The unit normal to tangent `g` at `p` pointing away from `inside` (the
/// outward normal of an open curve whose material is on the side of
/// `inside`).
pub(crate) fn away_from(inside: V2, p: V2, g: V2) -> V2 {
    let n = perp(g);
    let n = scale(1.0 / norm(n), n);
    if dot(n, sub(p, inside)) < 0.0 {
        scale(-1.0, n)
    } else {
        n
    }
}

/// The signed gap g = Nᵀ (P_j − P_i) (m) between witness points `pi` on
/// body i and `pj` on body j along unit normal `n`.
pub fn gap(n: V2, pi: V2, pj: V2) -> f64 {
    dot(n, sub(pj, pi))
}

/// The rate ġ = Ṅᵀ (P_j − P_i) + Nᵀ (v_j − v_i) (m/s) of the gap at the
/// witnesses, with `p` = (P_i, P_j), the velocities `v` of the material
/// points there and the rate `n_dot` of N.
pub(crate) fn gap_rate(n: V2, n_dot: V2, p: [V2; 2], v: [V2; 2]) -> f64 {
    dot(n_dot, sub(p[1], p[0])) + dot(n, sub(v[1], v[0]))
}

/// The normal force N = F_j · N (N) from the force `fj` the contact exerts
/// on body j (N) and the unit normal `n` out of body i's solid side. For a
/// point-on-curve contact (a cam–follower) F_j is the multiplier pair λ.
pub fn normal_force(fj: V2, n: V2) -> f64 {
    dot(fj, n)
}

/// The normal force N = (N · n_f) λ₀ (N) of a face contact whose first row
/// keeps a point on the face of unit normal `face_n` (global), from that
/// row's multiplier `lam0`: F_j = n_f λ₀.
pub(crate) fn face_normal_force(n: V2, face_n: V2, lam0: f64) -> f64 {
    dot(n, face_n) * lam0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::Polar;
    use crate::math::{point, rot};

    fn circle(c: V2, r: f64) -> Curve {
        Polar::circle(c, r).expect("circle").into()
    }

    #[test]
    fn a_disc_on_a_line_has_its_normal_and_gap_in_closed_form() {
        // Disc of radius r = 0.25 centred at (x, y) = (0.3, 0.4), turned by
        // φ = 0.9, above the face y = 0 (normal +y): the nearest point is
        // (x, y − r), N = −ŷ from the disc down to the face, g = y − r.
        let (r, c) = (0.25, [0.3, 0.4]);
        let disc = circle([0.0, 0.0], r);
        let sigma = disc.orientation().expect("closed");
        let q = [c[0], c[1], 0.9];
        // The disc's material is on the +y side of the face.
        let face_n = [0.0, 1.0];
        assert_eq!(
            side_of(face_n, [0.0, 0.0], point(q, sample_mean(&disc))),
            1.0
        );
        // The parameter of the disc point facing −y (polar angle −π/2 − φ).
        let s = -0.5 * std::f64::consts::PI - 0.9;
        let n = rot(q[2], outward_at(&disc, sigma, s));
        assert!((n[0]).abs() < 1e-14 && (n[1] + 1.0).abs() < 1e-14, "{n:?}");
        let pi = point(q, disc.jet(s).p);
        let pj = [pi[0], 0.0];
        let g = gap(n, pi, pj);
        assert!((g - (c[1] - r)).abs() < 1e-14, "{g}");
        // Falling at 2 m/s: ġ = −2 m/s.
        let rate = gap_rate(n, [0.0; 2], [pi, pj], [[0.0, -2.0], [0.0; 2]]);
        assert!((rate + 2.0).abs() < 1e-14, "{rate}");
        // A point pressed by the face with force F_j = (0, −5) on the
        // face body: N = 5 N, by either form.
        assert!((normal_force([0.0, -5.0], n) - 5.0).abs() < 1e-14);
        assert!((face_normal_force(n, face_n, -5.0) - 5.0).abs() < 1e-14);
    }

    #[test]
    fn a_roller_on_a_circle_has_its_normal_and_gap_in_closed_form() {
        // Cam circle R = 0.5 about the origin, roller r = 0.1 centred at
        // distance d from it along direction θ: N = (cos θ, sin θ),
        // g = d − R − r outside; a roller inside a ring groove of radius R
        // (C_i the hole, |κ_i| < |κ_j|) has N = −n_j and g = R − r − d.
        let (big, small, d, th): (f64, f64, f64, f64) = (0.5, 0.1, 0.7, 0.6);
        let u = [th.cos(), th.sin()];
        let cam = circle([0.0, 0.0], big);
        let roller = circle([0.0, 0.0], small);
        let (si, sj) = (cam.orientation().unwrap(), roller.orientation().unwrap());
        assert_eq!(solid_side([Some(si), Some(sj)]), Some((0, si)));
        assert_eq!(solid_side([None, Some(sj)]), Some((1, sj)));
        assert_eq!(solid_side([None, None]), None);
        let ni = outward_at(&cam, si, th);
        let nj = outward_at(&roller, sj, th + std::f64::consts::PI);
        assert!((ni[0] - u[0]).abs() < 1e-14 && (ni[1] - u[1]).abs() < 1e-14);
        let n = closed_pair(ni, nj, 1.0 / big, 1.0 / small);
        assert_eq!(n, ni);
        assert_eq!(from_side(1, nj), scale(-1.0, nj));
        let pi = scale(big, u);
        let pj = scale(d - small, u);
        assert!((gap(n, pi, pj) - (d - big - small)).abs() < 1e-14);
        // Inside a ring groove: the roller's outward normal at its point
        // facing the ring is +u as the ring's, so the ring is the hole.
        let d_in = 0.3;
        let nj_in = outward_at(&roller, sj, th);
        let n_in = closed_pair(ni, nj_in, 1.0 / big, 1.0 / small);
        assert_eq!(n_in, scale(-1.0, nj_in));
        let pj_in = scale(d_in + small, u);
        assert!((gap(n_in, pi, pj_in) - (big - small - d_in)).abs() < 1e-14);
    }
}
