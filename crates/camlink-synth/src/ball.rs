//! The instantaneous geometry of a four-bar's coupler at one crank angle:
//! its velocity pole, its inflection circle and Ball's point.
//!
//! A point X of the coupler (global frame, m) moves on P(φ) = A(φ) + u(φ),
//! u = X − A turning with the coupler: with complex numbers and ′ = d/dφ
//! (φ the crank angle, rad), u′ = c₁u, u″ = c₂u, u‴ = c₃u with
//!
//!   c₁ = iθ′,  c₂ = iθ″ − θ′²,  c₃ = iθ‴ − 3θ′θ″ − iθ′³,
//!
//! θ the coupler's angle, whose derivatives follow from differentiating
//! the loop A + (B − A) = O₄ + (B − O₄) three times (each derivative is
//! two linear equations in θ^(k) and the rocker's ψ^(k)). So P′ = a₁ + c₁u,
//! P″ = a₂ + c₂u, P‴ = a₃ + c₃u, a_k the crank pin's derivatives. In the
//! velocity w = P′ (zero at the pole X₀ = A − a₁/c₁), P″ = e₂ + f₂w and
//! P‴ = e₃ + f₃w with f_k = c_k/c₁, e_k = a_k − f_k a₁.
//!
//! - The path's curvature is κ = Im(w̄P″)/|w|³: zero on the inflection
//!   circle Im(w̄e₂) + |w|² Im f₂ = 0, a circle through the pole.
//! - Where κ = 0, dκ/dφ = Im(w̄P‴)/|w|³: zero where
//!   Im(w̄e₃) + |w|² Im f₃ = 0, which on the inflection circle is the cubic
//!   of stationary curvature's intersection with it.
//! - Ball's point is the point of both besides the pole: with z = 1/w the
//!   two conditions are linear, Im(e₂z) = −Im f₂ and Im(e₃z) = −Im f₃. Its
//!   path has zero curvature and zero rate of curvature there (four-point
//!   contact with its tangent): an approximate straight line.

use crate::complex::C;
use crate::fourbar::{angle, cross, rotate, sub, FourBar, P2};

/// The coupler's instantaneous geometry at one crank angle (global frame, m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Instant {
    /// The crank angle φ (rad) and the assembly branch σ.
    pub phi: f64,
    pub sigma: f64,
    /// The crank pin A and the rocker pin B.
    pub a: P2,
    pub b: P2,
    /// The velocity pole (the coupler's instant centre).
    pub pole: P2,
    /// The inflection circle's centre and radius; `None` where it is a
    /// line (Im f₂ = 0).
    pub inflection: Option<(P2, f64)>,
    /// Ball's point, global; `None` where it is at infinity or not
    /// determined.
    pub ball: Option<P2>,
    /// Ball's point in the coupler frame (origin A, x towards B).
    pub ball_local: Option<P2>,
    /// dθ/dφ, d²θ/dφ², d³θ/dφ³ of the coupler's angle θ.
    pub theta: [f64; 3],
}

/// x E₃ − y E₄ = S for (x, y); `None` at a toggle (E₃ ∥ E₄).
fn rates(s: C, e3: C, e4: C) -> Option<(f64, f64)> {
    let det = cross(e3.p(), e4.p());
    let size = e3.abs() * e4.abs();
    if det.is_nan() || det.abs() <= 1e-12 * size {
        return None;
    }
    Some((cross(s.p(), e4.p()) / det, cross(s.p(), e3.p()) / det))
}

/// The instantaneous geometry of `linkage`'s coupler at crank angle `phi`
/// (rad) on branch `sigma`; `None` where the linkage does not assemble,
/// is at a toggle (coupler and rocker in line) or its coupler does not
/// turn (the pole at infinity).
pub fn instant(linkage: &FourBar, phi: f64, sigma: f64) -> Option<Instant> {
    let pos = linkage.position(phi, sigma)?;
    let (a, b) = (C(pos.a[0], pos.a[1]), C(pos.b[0], pos.b[1]));
    let e3 = b - a;
    let e4 = b - C(linkage.o4[0], linkage.o4[1]);
    let i = C(0.0, 1.0);
    // The crank pin's derivatives: a e^{iφ} times i, −1, −i.
    let r = C::cis(phi).scale(linkage.crank);
    let a1 = i * r;
    let a2 = r.scale(-1.0);
    let a3 = (i * r).scale(-1.0);
    // i(θ^(k) E₃ − ψ^(k) E₄) = R_k, the known terms of the k-th derivative
    // of the loop moved to the right.
    let minus_i = C(0.0, -1.0);
    let (t1, p1) = rates(minus_i * a1.scale(-1.0), e3, e4)?;
    let r2 = a2.scale(-1.0) + e3.scale(t1 * t1) - e4.scale(p1 * p1);
    let (t2, p2) = rates(minus_i * r2, e3, e4)?;
    let k3 = |d1: f64, d2: f64| C(-3.0 * d1 * d2, -d1 * d1 * d1);
    let r3 = a3.scale(-1.0) - k3(t1, t2) * e3 + k3(p1, p2) * e4;
    let (t3, _) = rates(minus_i * r3, e3, e4)?;
    if t1 == 0.0 || !t1.is_finite() {
        return None;
    }
    let c1 = C(0.0, t1);
    let c2 = C(-t1 * t1, t2);
    let c3 = C(-3.0 * t1 * t2, t3 - t1 * t1 * t1);
    let (f2, f3) = (c2.div(c1), c3.div(c1));
    let (e2, e3k) = (a2 - f2 * a1, a3 - f3 * a1);
    // X = A + (w − a₁)/c₁.
    let place = |w: C| (a + (w - a1).div(c1)).p();
    let pole = place(C(0.0, 0.0));
    let inflection = if f2.1.abs() > 1e-12 * f2.abs().max(e2.abs()) {
        let wc = (i * e2).scale(0.5 / f2.1);
        Some((place(wc), wc.abs() / c1.abs()))
    } else {
        None
    };
    // Im(e z) = e_y z_x + e_x z_y.
    let det = e2.1 * e3k.0 - e2.0 * e3k.1;
    let size = e2.abs() * e3k.abs();
    let ball = if det.abs() > 1e-12 * size {
        let (g2, g3) = (-f2.1, -f3.1);
        let z = C(
            (g2 * e3k.0 - g3 * e2.0) / det,
            (e2.1 * g3 - e3k.1 * g2) / det,
        );
        if z.abs() > 0.0 {
            Some(place(C(1.0, 0.0).div(z)))
        } else {
            None
        }
    } else {
        None
    };
    let ball = ball.filter(|p| p[0].is_finite() && p[1].is_finite());
    let theta_ab = angle(sub(pos.b, pos.a));
    Some(Instant {
        phi,
        sigma,
        a: pos.a,
        b: pos.b,
        pole,
        inflection,
        ball,
        ball_local: ball.map(|p| rotate(-theta_ab, sub(p, pos.a))),
        theta: [t1, t2, t3],
    })
}
