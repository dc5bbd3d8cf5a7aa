//! A curve point carried by a moving body, in the global frame.
//!
//! Body coordinates q = (x, y, φ), rates q̇, a curve point p(s) (body frame)
//! at parameter s moving along the curve at rate ṡ. With A = A(φ),
//! B = dA/dφ = A R (R the rotation by +π/2):
//!
//! - position r^P = r + A p(s); ∂r^P/∂φ = B p; ∂r^P/∂s = g = A p′;
//! - tangent g = A p′; ∂g/∂φ = B p′ = g⊥; ∂g/∂s = A p″;
//! - ṙ^P = ṙ + B p φ̇ + A p′ ṡ; ġ = B p′ φ̇ + A p″ ṡ;
//! - the velocity-quadratic parts of the second derivatives (what remains
//!   when r̈, φ̈ and s̈ vanish), which make up γ:
//!   r̈^P* = A(−p φ̇² + 2 p′⊥ φ̇ ṡ + p″ ṡ²),
//!   g̈* = A(−p′ φ̇² + 2 p″⊥ φ̇ ṡ + p‴ ṡ²).
//!
//! A point fixed in the body is the case p′ = p″ = p‴ = 0.

use super::CurveJet;
use crate::math::{add, perp, rot, scale, V2};

/// Global position, tangent and their derivatives of a carried curve point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Carried {
    /// r^P = r + A p (m).
    pub p: V2,
    /// ∂r^P/∂φ = B p (m/rad).
    pub p_phi: V2,
    /// g = ∂r^P/∂s = A p′.
    pub g: V2,
    /// ∂g/∂φ = B p′.
    pub g_phi: V2,
    /// ∂g/∂s = A p″.
    pub g_s: V2,
    /// ṙ^P (m/s).
    pub v: V2,
    /// ġ.
    pub gd: V2,
    /// Velocity-quadratic part of r̈^P (m/s²).
    pub p_quad: V2,
    /// Velocity-quadratic part of g̈.
    pub g_quad: V2,
}

impl Carried {
    /// The curve point with jet `j` (body frame) at rate `sd` on a body at
    /// `q` moving with `qd`.
    #[inline]
    pub fn new(q: [f64; 3], qd: [f64; 3], j: &CurveJet, sd: f64) -> Self {
        let phi = q[2];
        let w = qd[2];
        let a = |v: V2| rot(phi, v);
        let (p, g, g_s) = (a(j.p), a(j.d1), a(j.d2));
        let (p_phi, g_phi) = (perp(p), perp(g));
        let ww = w * w;
        Carried {
            p: add([q[0], q[1]], p),
            p_phi,
            g,
            g_phi,
            g_s,
            v: add([qd[0], qd[1]], add(scale(w, p_phi), scale(sd, g))),
            gd: add(scale(w, g_phi), scale(sd, g_s)),
            p_quad: add(
                scale(-ww, p),
                add(scale(2.0 * w * sd, g_phi), scale(sd * sd, g_s)),
            ),
            g_quad: add(
                scale(-ww, g),
                add(scale(2.0 * w * sd, perp(g_s)), scale(sd * sd, a(j.d3))),
            ),
        }
    }

    /// A point fixed at `s` (m) in the body frame.
    #[inline]
    pub fn fixed(q: [f64; 3], qd: [f64; 3], s: V2) -> Self {
        let j = CurveJet {
            p: s,
            ..CurveJet::default()
        };
        Self::new(q, qd, &j, 0.0)
    }
}
