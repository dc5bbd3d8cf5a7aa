//! Third-order jets: a value and its first three derivatives.
//!
//! A jet of u(x) at a point is `[u, u', u'', u''']`, derivatives with respect
//! to the expression's variable x. Arithmetic on jets follows the product and
//! quotient rules; an elementary function g applied to a jet follows the
//! chain rule to third order (Faà di Bruno):
//!
//! ```text
//! h = g(u):  h'   = g'(u) u'
//!            h''  = g''(u) u'² + g'(u) u''
//!            h''' = g'''(u) u'³ + 3 g''(u) u' u'' + g'(u) u'''
//! ```
//!
//! The value component of every operation is computed by the same `f64`
//! operation that value-only evaluation uses, so `Expr::eval(x)` and
//! `Expr::jet(x)[0]` agree bit for bit.
//!
//! Construction, the operations with a constant, sums, negation, uᵛ,
//! atan2, hypot and mod are shared with the other jet order
//! (`jet_common.rs`).

use std::ops::{Div, Mul};

/// `[u, u', u'', u''']` of a function u(x) at one point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Jet(pub [f64; 4]);

jet_common!(Jet, 4);

impl Jet {
    /// g(u) from `g = [g(u), g'(u), g''(u), g'''(u)]` by the chain rule.
    ///
    /// A flat u gives a flat result whatever g's derivatives are, so a
    /// singular g' (sqrt at 0) does not turn a constant into NaN.
    #[inline]
    pub(crate) fn compose(self, g: [f64; 4]) -> Jet {
        let [_, u1, u2, u3] = self.0;
        if self.is_flat() {
            return Jet::constant(g[0]);
        }
        let u1s = u1 * u1;
        Jet([
            g[0],
            g[1] * u1,
            g[2] * u1s + g[1] * u2,
            g[3] * u1s * u1 + 3.0 * g[2] * u1 * u2 + g[1] * u3,
        ])
    }

    /// c / u, the quotient rule with a constant numerator.
    #[inline]
    pub(crate) fn rdiv_c(self, c: f64) -> Jet {
        let [v0, v1, v2, v3] = self.0;
        let w0 = c / v0;
        let r = 1.0 / v0;
        let w1 = -w0 * v1 * r;
        let w2 = (-2.0 * w1 * v1 - w0 * v2) * r;
        let w3 = (-3.0 * w2 * v1 - 3.0 * w1 * v2 - w0 * v3) * r;
        Jet([w0, w1, w2, w3])
    }

    /// uᶜ for a constant real exponent c.
    ///
    /// g⁽ᵏ⁾(u) = c(c−1)…(c−k+1) u^(c−k); a factor c(c−1)…(c−k+1) that is zero
    /// gives a zero term, so `u^2` at u = 0 has u''' = 0 rather than 0·∞.
    pub(crate) fn pow_c(self, c: f64) -> Jet {
        let u0 = self.0[0];
        let g0 = u0.powf(c);
        let (f1, f2, f3) = (c, c * (c - 1.0), c * (c - 1.0) * (c - 2.0));
        let g = if u0 != 0.0 && g0.is_finite() && g0 != 0.0 {
            // Successive powers by division: g1 = c g0 / u, ...
            let r = 1.0 / u0;
            let g1 = f1 * g0 * r;
            let g2 = (c - 1.0) * g1 * r;
            let g3 = (c - 2.0) * g2 * r;
            [g0, g1, g2, g3]
        } else {
            let term = |f: f64, k: f64| if f == 0.0 { 0.0 } else { f * u0.powf(c - k) };
            [g0, term(f1, 1.0), term(f2, 2.0), term(f3, 3.0)]
        };
        self.compose(g)
    }

    /// uⁿ for an integer exponent n, by repeated multiplication (`powi`).
    pub(crate) fn pow_i(self, n: i32) -> Jet {
        let u0 = self.0[0];
        let g = match n {
            2 => [u0.powi(2), 2.0 * u0, 2.0, 0.0],
            _ => {
                let nf = n as f64;
                let (f1, f2, f3) = (nf, nf * (nf - 1.0), nf * (nf - 1.0) * (nf - 2.0));
                let term = |f: f64, k: i32| {
                    if f == 0.0 {
                        0.0
                    } else {
                        f * u0.powi(n.saturating_sub(k))
                    }
                };
                [u0.powi(n), term(f1, 1), term(f2, 2), term(f3, 3)]
            }
        };
        self.compose(g)
    }

    /// sin u.
    #[inline]
    pub fn sin(self) -> Jet {
        let (s, c) = self.0[0].sin_cos();
        self.compose([s, c, -s, -c])
    }

    /// cos u.
    #[inline]
    pub fn cos(self) -> Jet {
        let (s, c) = self.0[0].sin_cos();
        self.compose([c, -s, -c, s])
    }

    /// tan u; with t = tan u and d = 1 + t²: tan' = d, tan'' = 2td,
    /// tan''' = 2d(1 + 3t²).
    pub fn tan(self) -> Jet {
        let t = self.0[0].tan();
        let d = 1.0 + t * t;
        self.compose([t, d, 2.0 * t * d, 2.0 * d * (1.0 + 3.0 * t * t)])
    }

    /// asin u; with p = 1/√(1−u²): asin' = p, asin'' = u p³,
    /// asin''' = p³ (1 + 3u² p²).
    pub fn asin(self) -> Jet {
        let u = self.0[0];
        let p = 1.0 / (1.0 - u * u).sqrt();
        let p3 = p * p * p;
        self.compose([u.asin(), p, u * p3, p3 * (1.0 + 3.0 * u * u * p * p)])
    }

    /// acos u; the derivatives are those of asin with the sign changed.
    pub fn acos(self) -> Jet {
        let u = self.0[0];
        let p = 1.0 / (1.0 - u * u).sqrt();
        let p3 = p * p * p;
        self.compose([u.acos(), -p, -u * p3, -p3 * (1.0 + 3.0 * u * u * p * p)])
    }

    /// atan u; with q = 1/(1+u²): atan' = q, atan'' = −2u q²,
    /// atan''' = (6u² − 2) q³.
    pub fn atan(self) -> Jet {
        let u = self.0[0];
        let q = 1.0 / (1.0 + u * u);
        let q2 = q * q;
        self.compose([u.atan(), q, -2.0 * u * q2, (6.0 * u * u - 2.0) * q2 * q])
    }

    /// sinh u.
    pub fn sinh(self) -> Jet {
        let u = self.0[0];
        let (s, c) = (u.sinh(), u.cosh());
        self.compose([s, c, s, c])
    }

    /// cosh u.
    pub fn cosh(self) -> Jet {
        let u = self.0[0];
        let (s, c) = (u.sinh(), u.cosh());
        self.compose([c, s, c, s])
    }

    /// tanh u; with t = tanh u and d = 1 − t²: tanh' = d, tanh'' = −2td,
    /// tanh''' = d (6t² − 2).
    pub fn tanh(self) -> Jet {
        let t = self.0[0].tanh();
        let d = 1.0 - t * t;
        self.compose([t, d, -2.0 * t * d, d * (6.0 * t * t - 2.0)])
    }

    /// exp u.
    #[inline]
    pub fn exp(self) -> Jet {
        let e = self.0[0].exp();
        self.compose([e, e, e, e])
    }

    /// ln u; ln' = 1/u, ln'' = −1/u², ln''' = 2/u³.
    pub fn ln(self) -> Jet {
        let u = self.0[0];
        let r = 1.0 / u;
        self.compose([u.ln(), r, -r * r, 2.0 * r * r * r])
    }

    /// √u; with r = √u: √' = 1/(2r), √'' = −1/(4ru), √''' = 3/(8ru²).
    pub fn sqrt(self) -> Jet {
        let u = self.0[0];
        let r = u.sqrt();
        self.compose([r, 0.5 / r, -0.25 / (r * u), 0.375 / (r * u * u)])
    }

    /// |u|; its derivative is sign(u), taken as 0 at u = 0.
    pub fn abs(self) -> Jet {
        let u = self.0[0];
        self.compose([u.abs(), sign(u), 0.0, 0.0])
    }
}

/// sign(u): −1, 0 or 1 (NaN for NaN).
#[inline]
pub(crate) fn sign(u: f64) -> f64 {
    if u > 0.0 {
        1.0
    } else if u < 0.0 {
        -1.0
    } else if u == 0.0 {
        0.0
    } else {
        f64::NAN
    }
}

/// u mod v with the sign of v (floored division), as in Python.
#[inline]
pub(crate) fn floor_mod(u: f64, v: f64) -> f64 {
    let r = u % v;
    if r != 0.0 && ((r < 0.0) != (v < 0.0)) {
        r + v
    } else {
        r
    }
}

/// Leibniz rule: (uv)''' = u'''v + 3u''v' + 3u'v'' + uv'''.
impl Mul for Jet {
    type Output = Jet;
    #[inline]
    fn mul(self, o: Jet) -> Jet {
        let ([u0, u1, u2, u3], [v0, v1, v2, v3]) = (self.0, o.0);
        Jet([
            u0 * v0,
            u1 * v0 + u0 * v1,
            u2 * v0 + 2.0 * u1 * v1 + u0 * v2,
            u3 * v0 + 3.0 * (u2 * v1 + u1 * v2) + u0 * v3,
        ])
    }
}

/// Quotient rule solved term by term from u = w v:
/// w = u/v, w' = (u' − w v')/v, w'' = (u'' − 2w'v' − w v'')/v,
/// w''' = (u''' − 3w''v' − 3w'v'' − w v''')/v.
impl Div for Jet {
    type Output = Jet;
    #[inline]
    fn div(self, o: Jet) -> Jet {
        let ([u0, u1, u2, u3], [v0, v1, v2, v3]) = (self.0, o.0);
        let w0 = u0 / v0;
        let r = 1.0 / v0;
        let w1 = (u1 - w0 * v1) * r;
        let w2 = (u2 - 2.0 * w1 * v1 - w0 * v2) * r;
        let w3 = (u3 - 3.0 * (w2 * v1 + w1 * v2) - w0 * v3) * r;
        Jet([w0, w1, w2, w3])
    }
}
