//! Fourth-order jets: a value and its first four derivatives.
//!
//! A jet of u(x) at a point is `[u, u', u'', u''', u'''']`. The third-order
//! [`Jet`](crate::Jet) serves the usual kinematic step; this one serves the
//! jerk analysis, whose curve contacts need the fourth derivative of a
//! profile. Arithmetic follows the Leibniz and quotient rules to fourth
//! order; an elementary function g applied to a jet follows Faà di Bruno's
//! formula to fourth order:
//!
//! ```text
//! h = g(u):  h'    = g' u'
//!            h''   = g'' u'² + g' u''
//!            h'''  = g''' u'³ + 3 g'' u' u'' + g' u'''
//!            h'''' = g'''' u'⁴ + 6 g''' u'² u'' + g'' (3 u''² + 4 u' u''') + g' u''''
//! ```
//!
//! Each operation computes its value and its first three derivatives with
//! the same formulas as [`Jet`](crate::Jet), so the first four entries of
//! `Expr::jet4(x)` equal `Expr::jet(x)` up to rounding.
//!
//! Construction, the operations with a constant, sums, negation, uᵛ,
//! atan2, hypot and mod are shared with the other jet order
//! (`jet_common.rs`).

use std::ops::{Div, Mul};

use crate::jet::sign;

/// `[u, u', u'', u''', u'''']` of a function u(x) at one point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Jet4(pub [f64; 5]);

jet_common!(Jet4, 5);

impl Jet4 {
    /// g(u) from `g = [g, g', g'', g''', g'''']` at u by Faà di Bruno's
    /// formula; a flat u gives a flat result.
    #[inline]
    pub(crate) fn compose(self, g: [f64; 5]) -> Jet4 {
        let [_, u1, u2, u3, u4] = self.0;
        if self.is_flat() {
            return Jet4::constant(g[0]);
        }
        let u1s = u1 * u1;
        Jet4([
            g[0],
            g[1] * u1,
            g[2] * u1s + g[1] * u2,
            g[3] * u1s * u1 + 3.0 * g[2] * u1 * u2 + g[1] * u3,
            g[4] * u1s * u1s
                + 6.0 * g[3] * u1s * u2
                + g[2] * (3.0 * u2 * u2 + 4.0 * u1 * u3)
                + g[1] * u4,
        ])
    }

    /// c / u.
    #[inline]
    pub(crate) fn rdiv_c(self, c: f64) -> Jet4 {
        Jet4::constant(c) / self
    }

    /// uᶜ for a constant real exponent c; a falling factorial
    /// c(c−1)…(c−k+1) that is zero gives a zero term.
    pub(crate) fn pow_c(self, c: f64) -> Jet4 {
        let u0 = self.0[0];
        let g0 = u0.powf(c);
        let f = [
            1.0,
            c,
            c * (c - 1.0),
            c * (c - 1.0) * (c - 2.0),
            c * (c - 1.0) * (c - 2.0) * (c - 3.0),
        ];
        let g = if u0 != 0.0 && g0.is_finite() && g0 != 0.0 {
            let r = 1.0 / u0;
            let g1 = c * g0 * r;
            let g2 = (c - 1.0) * g1 * r;
            let g3 = (c - 2.0) * g2 * r;
            let g4 = (c - 3.0) * g3 * r;
            [g0, g1, g2, g3, g4]
        } else {
            let term = |k: usize| {
                if f[k] == 0.0 {
                    0.0
                } else {
                    f[k] * u0.powf(c - k as f64)
                }
            };
            [g0, term(1), term(2), term(3), term(4)]
        };
        self.compose(g)
    }

    /// uⁿ for an integer exponent n.
    pub(crate) fn pow_i(self, n: i32) -> Jet4 {
        let u0 = self.0[0];
        let nf = n as f64;
        let f = [
            1.0,
            nf,
            nf * (nf - 1.0),
            nf * (nf - 1.0) * (nf - 2.0),
            nf * (nf - 1.0) * (nf - 2.0) * (nf - 3.0),
        ];
        let term = |k: i32| {
            if f[k as usize] == 0.0 {
                0.0
            } else {
                f[k as usize] * u0.powi(n.saturating_sub(k))
            }
        };
        self.compose([u0.powi(n), term(1), term(2), term(3), term(4)])
    }

    /// sin u.
    pub fn sin(self) -> Jet4 {
        let (s, c) = self.0[0].sin_cos();
        self.compose([s, c, -s, -c, s])
    }

    /// cos u.
    pub fn cos(self) -> Jet4 {
        let (s, c) = self.0[0].sin_cos();
        self.compose([c, -s, -c, s, c])
    }

    /// tan u; with t = tan u, d = 1 + t²: tan'''' = 8td(2 + 3t²).
    pub fn tan(self) -> Jet4 {
        let t = self.0[0].tan();
        let d = 1.0 + t * t;
        self.compose([
            t,
            d,
            2.0 * t * d,
            2.0 * d * (1.0 + 3.0 * t * t),
            8.0 * t * d * (2.0 + 3.0 * t * t),
        ])
    }

    /// asin u; with p = 1/√(1−u²): asin'''' = 3u p⁵ (3 + 5u² p²).
    pub fn asin(self) -> Jet4 {
        let u = self.0[0];
        let p = 1.0 / (1.0 - u * u).sqrt();
        let (p2, p3) = (p * p, p * p * p);
        self.compose([
            u.asin(),
            p,
            u * p3,
            p3 * (1.0 + 3.0 * u * u * p2),
            3.0 * u * p3 * p2 * (3.0 + 5.0 * u * u * p2),
        ])
    }

    /// acos u: the derivatives of asin with the sign changed.
    pub fn acos(self) -> Jet4 {
        let mut w = -self.asin();
        w.0[0] = self.0[0].acos();
        w
    }

    /// atan u; with q = 1/(1+u²): atan'''' = 24u(1 − u²) q⁴.
    pub fn atan(self) -> Jet4 {
        let u = self.0[0];
        let q = 1.0 / (1.0 + u * u);
        let q2 = q * q;
        self.compose([
            u.atan(),
            q,
            -2.0 * u * q2,
            (6.0 * u * u - 2.0) * q2 * q,
            24.0 * u * (1.0 - u * u) * q2 * q2,
        ])
    }

    /// sinh u.
    pub fn sinh(self) -> Jet4 {
        let u = self.0[0];
        let (s, c) = (u.sinh(), u.cosh());
        self.compose([s, c, s, c, s])
    }

    /// cosh u.
    pub fn cosh(self) -> Jet4 {
        let u = self.0[0];
        let (s, c) = (u.sinh(), u.cosh());
        self.compose([c, s, c, s, c])
    }

    /// tanh u; with t = tanh u, d = 1 − t²: tanh'''' = 8td(2 − 3t²).
    pub fn tanh(self) -> Jet4 {
        let t = self.0[0].tanh();
        let d = 1.0 - t * t;
        self.compose([
            t,
            d,
            -2.0 * t * d,
            d * (6.0 * t * t - 2.0),
            8.0 * t * d * (2.0 - 3.0 * t * t),
        ])
    }

    /// exp u.
    pub fn exp(self) -> Jet4 {
        let e = self.0[0].exp();
        self.compose([e; 5])
    }

    /// ln u; ln'''' = −6/u⁴.
    pub fn ln(self) -> Jet4 {
        let u = self.0[0];
        let r = 1.0 / u;
        let r2 = r * r;
        self.compose([u.ln(), r, -r2, 2.0 * r2 * r, -6.0 * r2 * r2])
    }

    /// √u; with r = √u: √'''' = −15/(16 r u³).
    pub fn sqrt(self) -> Jet4 {
        let u = self.0[0];
        let r = u.sqrt();
        self.compose([
            r,
            0.5 / r,
            -0.25 / (r * u),
            0.375 / (r * u * u),
            -0.9375 / (r * u * u * u),
        ])
    }

    /// |u|; its derivative is sign(u), 0 at u = 0.
    pub fn abs(self) -> Jet4 {
        let u = self.0[0];
        self.compose([u.abs(), sign(u), 0.0, 0.0, 0.0])
    }
}

/// Leibniz rule: (uv)'''' = u''''v + 4u'''v' + 6u''v'' + 4u'v''' + uv''''.
impl Mul for Jet4 {
    type Output = Jet4;
    #[inline]
    fn mul(self, o: Jet4) -> Jet4 {
        let ([u0, u1, u2, u3, u4], [v0, v1, v2, v3, v4]) = (self.0, o.0);
        Jet4([
            u0 * v0,
            u1 * v0 + u0 * v1,
            u2 * v0 + 2.0 * u1 * v1 + u0 * v2,
            u3 * v0 + 3.0 * (u2 * v1 + u1 * v2) + u0 * v3,
            u4 * v0 + 4.0 * (u3 * v1 + u1 * v3) + 6.0 * u2 * v2 + u0 * v4,
        ])
    }
}

/// Quotient rule solved term by term from u = w v:
/// w'''' = (u'''' − 4w'''v' − 6w''v'' − 4w'v''' − w v'''')/v.
impl Div for Jet4 {
    type Output = Jet4;
    #[inline]
    fn div(self, o: Jet4) -> Jet4 {
        let ([u0, u1, u2, u3, u4], [v0, v1, v2, v3, v4]) = (self.0, o.0);
        let w0 = u0 / v0;
        let r = 1.0 / v0;
        let w1 = (u1 - w0 * v1) * r;
        let w2 = (u2 - 2.0 * w1 * v1 - w0 * v2) * r;
        let w3 = (u3 - 3.0 * (w2 * v1 + w1 * v2) - w0 * v3) * r;
        let w4 = (u4 - 4.0 * (w3 * v1 + w1 * v3) - 6.0 * w2 * v2 - w0 * v4) * r;
        Jet4([w0, w1, w2, w3, w4])
    }
}
