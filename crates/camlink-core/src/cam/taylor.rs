//! Truncated Taylor series of degree 5 in the cam angle θ.
//!
//! A cam surface point needs the follower motion one order beyond its own:
//! the surface's third derivative p‴ (which the curve contacts need for γ)
//! involves s⁗, and its fourth p⁗ (the jerk analysis) s⁽⁵⁾. A series
//! `T(c)` holds the normalised coefficients c_k = f⁽ᵏ⁾(θ)/k!, k = 0…5, so
//! that products are convolutions and the elementary functions follow from
//! their differential equations.

// Series arithmetic reads as the formulas with explicit indices.
#![allow(clippy::needless_range_loop)]

use std::ops::{Add, Mul, Neg, Sub};

/// Terms kept: degree 5.
pub const N: usize = 6;

/// f(θ + h) = Σ c_k h^k, k = 0…5.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct T(pub [f64; N]);

const FACT: [f64; N] = [1.0, 1.0, 2.0, 6.0, 24.0, 120.0];

impl T {
    /// A constant.
    pub fn constant(c: f64) -> T {
        let mut t = [0.0; N];
        t[0] = c;
        T(t)
    }

    /// The series of a function from its derivatives `[f, f′, …, f⁽⁵⁾]`.
    pub fn from_derivatives(d: [f64; N]) -> T {
        let mut c = [0.0; N];
        for k in 0..N {
            c[k] = d[k] / FACT[k];
        }
        T(c)
    }

    /// The derivatives `[f, f′, …, f⁽⁵⁾]`.
    pub fn derivatives(self) -> [f64; N] {
        let mut d = [0.0; N];
        for k in 0..N {
            d[k] = self.0[k] * FACT[k];
        }
        d
    }

    /// The value f(θ).
    pub fn value(self) -> f64 {
        self.0[0]
    }

    /// df/dθ, one degree lower (its last term is unknown and set to 0).
    pub fn diff(self) -> T {
        let mut c = [0.0; N];
        for k in 0..N - 1 {
            c[k] = (k + 1) as f64 * self.0[k + 1];
        }
        T(c)
    }

    /// c f.
    pub fn scale(self, c: f64) -> T {
        T(self.0.map(|v| c * v))
    }

    /// 1/f: b₀ = 1/a₀, b_k = −(Σ_{i=1..k} a_i b_{k−i})/a₀.
    pub fn recip(self) -> T {
        let a = self.0;
        let mut b = [0.0; N];
        b[0] = 1.0 / a[0];
        for k in 1..N {
            let s: f64 = (1..=k).map(|i| a[i] * b[k - i]).sum();
            b[k] = -s * b[0];
        }
        T(b)
    }

    /// √f: b₀ = √a₀, b_k = (a_k − Σ_{i=1..k−1} b_i b_{k−i})/(2 b₀).
    pub fn sqrt(self) -> T {
        let a = self.0;
        let mut b = [0.0; N];
        b[0] = a[0].sqrt();
        for k in 1..N {
            let s: f64 = (1..k).map(|i| b[i] * b[k - i]).sum();
            b[k] = (a[k] - s) / (2.0 * b[0]);
        }
        T(b)
    }

    /// (sin f, cos f), from s′ = c f′, c′ = −s f′:
    /// k s_k = Σ_{j=1..k} j a_j c_{k−j}, k c_k = −Σ_{j=1..k} j a_j s_{k−j}.
    pub fn sin_cos(self) -> (T, T) {
        let a = self.0;
        let (mut s, mut c) = ([0.0; N], [0.0; N]);
        (s[0], c[0]) = a[0].sin_cos();
        for k in 1..N {
            let (mut ss, mut cc) = (0.0, 0.0);
            for j in 1..=k {
                ss += j as f64 * a[j] * c[k - j];
                cc -= j as f64 * a[j] * s[k - j];
            }
            s[k] = ss / k as f64;
            c[k] = cc / k as f64;
        }
        (T(s), T(c))
    }
}

impl Add for T {
    type Output = T;
    fn add(self, o: T) -> T {
        let mut c = self.0;
        for k in 0..N {
            c[k] += o.0[k];
        }
        T(c)
    }
}

impl Sub for T {
    type Output = T;
    fn sub(self, o: T) -> T {
        self + (-o)
    }
}

impl Neg for T {
    type Output = T;
    fn neg(self) -> T {
        self.scale(-1.0)
    }
}

impl Mul for T {
    type Output = T;
    fn mul(self, o: T) -> T {
        let mut c = [0.0; N];
        for k in 0..N {
            for i in 0..=k {
                c[k] += self.0[i] * o.0[k - i];
            }
        }
        T(c)
    }
}

/// A planar vector whose components are series.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TV(pub T, pub T);

impl TV {
    /// The sum of two vectors.
    pub fn plus(self, o: TV) -> TV {
        TV(self.0 + o.0, self.1 + o.1)
    }
    /// The difference of two vectors.
    pub fn minus(self, o: TV) -> TV {
        TV(self.0 - o.0, self.1 - o.1)
    }
    /// Multiplied by a scalar series.
    pub fn times(self, k: T) -> TV {
        TV(self.0 * k, self.1 * k)
    }
    pub fn dot(self, o: TV) -> T {
        self.0 * o.0 + self.1 * o.1
    }
    /// The left normal (−y, x).
    pub fn perp(self) -> TV {
        TV(-self.1, self.0)
    }
    pub fn diff(self) -> TV {
        TV(self.0.diff(), self.1.diff())
    }
    /// Rotated by the angle series `a`.
    pub fn rot(self, a: T) -> TV {
        let (s, c) = a.sin_cos();
        TV(c * self.0 - s * self.1, s * self.0 + c * self.1)
    }
    /// The vector's value.
    pub fn value(self) -> [f64; 2] {
        [self.0.value(), self.1.value()]
    }
    /// The k-th derivative's value.
    pub fn derivative(self, k: usize) -> [f64; 2] {
        [self.0 .0[k] * FACT[k], self.1 .0[k] * FACT[k]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each operation's derivatives against closed forms at a point.
    #[test]
    fn series_match_closed_form_derivatives() {
        let x = 0.7;
        let th = T::from_derivatives([x, 1.0, 0.0, 0.0, 0.0, 0.0]);
        // f = sin(2θ)·θ, derivatives by hand.
        let (s2, _) = th.scale(2.0).sin_cos();
        let f = (s2 * th).derivatives();
        let (s, c) = (2.0 * x).sin_cos();
        let want = [
            s * x,
            2.0 * c * x + s,
            -4.0 * s * x + 4.0 * c,
            -8.0 * c * x - 12.0 * s,
            16.0 * s * x - 32.0 * c,
            32.0 * c * x + 80.0 * s,
        ];
        for k in 0..N {
            assert!(
                (f[k] - want[k]).abs() < 1e-12,
                "order {k}: {} vs {}",
                f[k],
                want[k]
            );
        }
        // 1/θ and √θ: (−1)^k k!/θ^(k+1) and the falling powers of 1/2.
        let r = th.recip().derivatives();
        let q = th.sqrt().derivatives();
        let mut fall = 1.0;
        for k in 0..N {
            let kf = k as f64;
            let want_r = (-1f64).powi(k as i32) * FACT[k] / x.powi(k as i32 + 1);
            assert!(
                (r[k] - want_r).abs() < 1e-10 * want_r.abs(),
                "1/θ order {k}"
            );
            let want_q = fall * x.powf(0.5 - kf);
            assert!(
                (q[k] - want_q).abs() < 1e-12 * (1.0 + want_q.abs()),
                "√θ order {k}"
            );
            fall *= 0.5 - kf;
        }
    }
}
