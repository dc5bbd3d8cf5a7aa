//! Time derivatives along the motion, to third order, for the jerk analysis.
//!
//! Differentiating Φ(q, t) = 0 three times along a motion gives
//! Φ_q q⃛ = η, where η collects every term of d³Φ/dt³ that does not hold the
//! jerk q⃛: η = −d³Φ/dt³ evaluated with q⃛ = 0. The constraints build d³Φ/dt³
//! from the derivatives of the points and vectors they are made of, by the
//! product rule; this module holds those derivatives.
//!
//! A [`Path`] is a planar vector with its time derivatives
//! `[x, ẋ, ẍ, x⃛*]`, a [`Scalar`] the same for a number; the star marks a
//! third derivative taken with every jerk (q⃛, and the third derivative of
//! an own coordinate) set to zero. Leibniz's rule keeps that meaning:
//! (ab)⃛* = a⃛* b + 3ä ḃ + 3ȧ b̈ + a b⃛*, since a jerk enters a product's
//! third derivative only through a⃛ and b⃛.
//!
//! A vector v fixed or moving in a body frame at angle φ appears in the
//! global frame as A(φ) v; with ω = φ̇, ω̇ = φ̈, R the rotation by +π/2
//! (A R = B), and v's own derivatives v̇, v̈, v⃛*:
//!
//! ```text
//! d/dt  (A v) = A (v̇ + ω R v)
//! d²/dt²(A v) = A (v̈ + ω̇ R v + 2ω R v̇ − ω² v)
//! d³/dt³(A v)* = A (v⃛* + 3ω̇ R v̇ + 3ω R v̈ − 3ωω̇ v − 3ω² v̇ − ω³ R v)
//! ```
//!
//! (the last without the φ⃛ term B v φ⃛, which belongs to Φ_q q⃛).

use crate::math::{add, cross as cross2, dot as dot2, perp, rot, scale, sub as sub2, V2};

/// A number and its time derivatives `[x, ẋ, ẍ, x⃛*]`.
pub(crate) type Scalar = [f64; 4];

/// A planar vector and its time derivatives `[x, ẋ, ẍ, x⃛*]`.
pub(crate) type Path = [V2; 4];

/// A constant vector.
#[inline]
pub(crate) fn constant(v: V2) -> Path {
    [v, [0.0; 2], [0.0; 2], [0.0; 2]]
}

/// a − b.
#[inline]
pub(crate) fn sub(a: &Path, b: &Path) -> Path {
    std::array::from_fn(|k| sub2(a[k], b[k]))
}

/// a + b.
#[inline]
pub(crate) fn plus(a: &Path, b: &Path) -> Path {
    std::array::from_fn(|k| add(a[k], b[k]))
}

/// Leibniz's rule to third order for a bilinear product `f`.
#[inline]
fn leibniz(a: &Path, b: &Path, f: fn(V2, V2) -> f64) -> Scalar {
    [
        f(a[0], b[0]),
        f(a[1], b[0]) + f(a[0], b[1]),
        f(a[2], b[0]) + 2.0 * f(a[1], b[1]) + f(a[0], b[2]),
        f(a[3], b[0]) + 3.0 * (f(a[2], b[1]) + f(a[1], b[2])) + f(a[0], b[3]),
    ]
}

/// aᵀb and its derivatives.
#[inline]
pub(crate) fn dot(a: &Path, b: &Path) -> Scalar {
    leibniz(a, b, dot2)
}

/// a × b = a₀b₁ − a₁b₀ and its derivatives.
#[inline]
pub(crate) fn cross(a: &Path, b: &Path) -> Scalar {
    leibniz(a, b, cross2)
}

/// A(φ) v in the global frame, from the angle's `[φ, ω, ω̇]` and the
/// body-frame vector's `[v, v̇, v̈, v⃛*]` (the formulas of the module notes).
#[inline]
pub(crate) fn rotated(angle: [f64; 3], v: &Path) -> Path {
    let [phi, w, wd] = angle;
    let r = |u: V2| perp(u);
    let a = |u: V2| rot(phi, u);
    let lin = |terms: &[(f64, V2)]| {
        terms
            .iter()
            .fold([0.0; 2], |s, &(k, u)| add(s, scale(k, u)))
    };
    [
        a(v[0]),
        a(add(v[1], scale(w, r(v[0])))),
        a(lin(&[
            (1.0, v[2]),
            (wd, r(v[0])),
            (2.0 * w, r(v[1])),
            (-w * w, v[0]),
        ])),
        a(lin(&[
            (1.0, v[3]),
            (3.0 * wd, r(v[1])),
            (3.0 * w, r(v[2])),
            (-3.0 * w * wd, v[0]),
            (-3.0 * w * w, v[1]),
            (-w * w * w, r(v[0])),
        ])),
    ]
}

/// The angle `[φ, φ̇, φ̈]` of body coordinates q, q̇, q̈.
#[inline]
pub(crate) fn angle(q: [f64; 3], qd: [f64; 3], qdd: [f64; 3]) -> [f64; 3] {
    [q[2], qd[2], qdd[2]]
}

/// r + A(φ) v for a body at (q, q̇, q̈) and a body-frame vector v with its
/// derivatives: a body point (v constant) or a point moving on the body.
#[inline]
pub(crate) fn on_body(q: [f64; 3], qd: [f64; 3], qdd: [f64; 3], v: &Path) -> Path {
    let origin = [[q[0], q[1]], [qd[0], qd[1]], [qdd[0], qdd[1]], [0.0; 2]];
    plus(&origin, &rotated(angle(q, qd, qdd), v))
}

/// The body point s′ (body frame, m) of a body at (q, q̇, q̈).
#[inline]
pub(crate) fn body_point(q: [f64; 3], qd: [f64; 3], qdd: [f64; 3], s: V2) -> Path {
    on_body(q, qd, qdd, &constant(s))
}

/// f² from f's `[f, f′, f″, f‴]`: `[f², 2ff′, 2(f′² + ff″), 2ff‴ + 6f′f″]`.
#[inline]
pub(crate) fn square(f: [f64; 4]) -> Scalar {
    let [f0, f1, f2, f3] = f;
    [
        f0 * f0,
        2.0 * f0 * f1,
        2.0 * (f1 * f1 + f0 * f2),
        2.0 * f0 * f3 + 6.0 * f1 * f2,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::point;

    /// A body point's derivatives against differences of its position along
    /// q(t) = q₀ + q̇ t + q̈ t²/2 (no jerk).
    #[test]
    fn body_point_derivatives_match_differences() {
        let (q, qd, qdd) = ([0.3, -0.2, 0.9], [1.1, -0.4, 2.3], [0.5, 0.7, -1.9]);
        let s = [0.6, -0.25];
        let at = |t: f64| {
            point(
                std::array::from_fn(|k| q[k] + qd[k] * t + 0.5 * qdd[k] * t * t),
                s,
            )
        };
        let p = body_point(q, qd, qdd, s);
        let h = 1e-3;
        let (pp, p0, pm) = (at(h), at(0.0), at(-h));
        let (pp2, pm2) = (at(2.0 * h), at(-2.0 * h));
        for c in 0..2 {
            let d1 = (pp[c] - pm[c]) / (2.0 * h);
            let d2 = (pp[c] - 2.0 * p0[c] + pm[c]) / (h * h);
            let d3 = (pp2[c] - 2.0 * pp[c] + 2.0 * pm[c] - pm2[c]) / (2.0 * h * h * h);
            assert!((p[1][c] - d1).abs() < 1e-5, "{c}");
            assert!((p[2][c] - d2).abs() < 1e-5, "{c}");
            assert!((p[3][c] - d3).abs() < 1e-4, "{c}: {} vs {d3}", p[3][c]);
        }
    }

    #[test]
    fn square_is_the_product_rule() {
        let f = [1.3, -0.4, 2.2, 0.7];
        let p = [[f[0], 0.0], [f[1], 0.0], [f[2], 0.0], [f[3], 0.0]];
        let (a, b) = (square(f), dot(&p, &p));
        assert!(
            (0..4).all(|k| (a[k] - b[k]).abs() < 1e-14),
            "{a:?} vs {b:?}"
        );
        // (f²)‴ = 2ff‴ + 6f′f″ in numbers.
        assert!((a[3] - (2.0 * 1.3 * 0.7 + 6.0 * -0.4 * 2.2)).abs() < 1e-14);
    }
}
