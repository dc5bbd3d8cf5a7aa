//! Motion laws: smooth transitions from h0 at x0 to h1 at x1.
//!
//! Every law is called as `law(x, x0, h0, x1, h1)`, the argument order of
//! ADAMS `STEP`: it goes from the point (x0, h0) to the point (x1, h1). With
//! the normalized position u = (x − x0)/(x1 − x0) and a shape s(u) that rises
//! from s(0) = 0 to s(1) = 1,
//!
//! ```text
//! law(x) = h0                       when u ≤ 0
//!        = h0 + (h1 − h0) s(u)      when 0 < u < 1
//!        = h1                       when u ≥ 1
//! ```
//!
//! x1 may be less than x0: the law then runs towards decreasing x. x1 = x0
//! is a jump (`Expr::check` reports it). The shapes and their derivatives
//! are written out analytically in [`Law::shape`]; derivatives with respect
//! to the variable follow by the chain rule through u (and through h0, h1, x0,
//! x1 when those depend on the variable too).

use crate::jet::Jet;
use crate::jet4::Jet4;
use std::f64::consts::PI;

/// A motion law's shape s(u) on 0 ≤ u ≤ 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Law {
    /// `ramp`: constant velocity, s = u. Continuous value only (C0).
    Ramp,
    /// `step`: ADAMS STEP, the cubic s = u²(3 − 2u). Continuous slope (C1).
    Step,
    /// `step5` and `poly345`: the quintic s = 10u³ − 15u⁴ + 6u⁵ (ADAMS STEP5).
    /// Continuous acceleration (C2).
    Poly345,
    /// `harmonic`: simple harmonic rise s = (1 − cos πu)/2. C1.
    Harmonic,
    /// `cycloidal`: s = u − sin(2πu)/(2π). C2.
    Cycloidal,
}

impl Law {
    /// `[s, ds/du, d²s/du², d³s/du³]` at u, for 0 < u < 1.
    ///
    /// ```text
    /// ramp       s = u                      s' = 1             s'' = 0                s''' = 0
    /// step       s = u²(3 − 2u)             s' = 6u(1 − u)     s'' = 6 − 12u          s''' = −12
    /// poly345    s = u³(10 − 15u + 6u²)     s' = 30u²(1 − u)²  s'' = 60u(1 − u)(1 − 2u)
    ///                                                          s''' = 60(1 − 6u + 6u²)
    /// harmonic   s = (1 − cos πu)/2         s' = (π/2) sin πu  s'' = (π²/2) cos πu    s''' = −(π³/2) sin πu
    /// cycloidal  s = u − sin(2πu)/(2π)      s' = 1 − cos 2πu   s'' = 2π sin 2πu       s''' = 4π² cos 2πu
    /// ```
    pub fn shape(self, u: f64) -> [f64; 4] {
        match self {
            Law::Ramp => [u, 1.0, 0.0, 0.0],
            Law::Step => [
                u * u * (3.0 - 2.0 * u),
                6.0 * u * (1.0 - u),
                6.0 - 12.0 * u,
                -12.0,
            ],
            Law::Poly345 => {
                let v = 1.0 - u;
                [
                    u * u * u * (10.0 - 15.0 * u + 6.0 * u * u),
                    30.0 * u * u * v * v,
                    60.0 * u * v * (1.0 - 2.0 * u),
                    60.0 * (1.0 - 6.0 * u + 6.0 * u * u),
                ]
            }
            Law::Harmonic => {
                let (s, c) = (PI * u).sin_cos();
                [
                    0.5 * (1.0 - c),
                    0.5 * PI * s,
                    0.5 * PI * PI * c,
                    -0.5 * PI * PI * PI * s,
                ]
            }
            Law::Cycloidal => {
                let (s, c) = (2.0 * PI * u).sin_cos();
                [u - s / (2.0 * PI), 1.0 - c, 2.0 * PI * s, 4.0 * PI * PI * c]
            }
        }
    }

    /// `[s, s', s'', s''', s'''']` at u, for 0 < u < 1: [`Law::shape`] and
    /// the fourth derivative
    ///
    /// ```text
    /// ramp, step  s'''' = 0
    /// poly345     s'''' = 360(2u − 1)
    /// harmonic    s'''' = −(π⁴/2) cos πu
    /// cycloidal   s'''' = −8π³ sin 2πu
    /// ```
    pub fn shape4(self, u: f64) -> [f64; 5] {
        let [s0, s1, s2, s3] = self.shape(u);
        let s4 = match self {
            Law::Ramp | Law::Step => 0.0,
            Law::Poly345 => 360.0 * (2.0 * u - 1.0),
            Law::Harmonic => -0.5 * PI.powi(4) * (PI * u).cos(),
            Law::Cycloidal => -8.0 * PI.powi(3) * (2.0 * PI * u).sin(),
        };
        [s0, s1, s2, s3, s4]
    }

    /// `[s, s', …, s⁽⁵⁾]` at u, 0 ≤ u ≤ 1: [`Law::shape4`] and the fifth
    /// derivative
    ///
    /// ```text
    /// ramp, step  s⁽⁵⁾ = 0
    /// poly345     s⁽⁵⁾ = 720
    /// harmonic    s⁽⁵⁾ = (π⁵/2) sin πu
    /// cycloidal   s⁽⁵⁾ = −16π⁴ cos 2πu
    /// ```
    ///
    /// The cam design's motion laws of the same shapes (constant velocity,
    /// 3-4-5, simple harmonic, cycloidal) are these.
    pub fn shape5(self, u: f64) -> [f64; 6] {
        let [s0, s1, s2, s3, s4] = self.shape4(u);
        let s5 = match self {
            Law::Ramp | Law::Step => 0.0,
            Law::Poly345 => 720.0,
            Law::Harmonic => 0.5 * PI.powi(5) * (PI * u).sin(),
            Law::Cycloidal => -16.0 * PI.powi(4) * (2.0 * PI * u).cos(),
        };
        [s0, s1, s2, s3, s4, s5]
    }

    /// The highest order of derivative that is continuous at u = 0 and u = 1.
    pub fn continuity(self) -> usize {
        match self {
            Law::Ramp => 0,
            Law::Step | Law::Harmonic => 1,
            Law::Poly345 | Law::Cycloidal => 2,
        }
    }

    /// The law's value at x.
    #[inline]
    pub fn value(self, x: f64, x0: f64, h0: f64, x1: f64, h1: f64) -> f64 {
        let u = (x - x0) / (x1 - x0);
        if u <= 0.0 {
            h0
        } else if u >= 1.0 {
            h1
        } else {
            h0 + (h1 - h0) * self.shape(u)[0]
        }
    }

    /// The law's jet; its value equals [`Law::value`] exactly.
    #[inline]
    pub fn jet(self, x: Jet, x0: Jet, h0: Jet, x1: Jet, h1: Jet) -> Jet {
        let u = (x - x0) / (x1 - x0);
        let u0 = u.value();
        if u0 <= 0.0 {
            h0
        } else if u0 >= 1.0 {
            h1
        } else {
            h0 + (h1 - h0) * u.compose(self.shape(u0))
        }
    }

    /// The law's fourth-order jet; its value equals [`Law::value`] exactly.
    #[inline]
    pub fn jet4(self, x: Jet4, x0: Jet4, h0: Jet4, x1: Jet4, h1: Jet4) -> Jet4 {
        let u = (x - x0) / (x1 - x0);
        let u0 = u.value();
        if u0 <= 0.0 {
            h0
        } else if u0 >= 1.0 {
            h1
        } else {
            h0 + (h1 - h0) * u.compose(self.shape4(u0))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LAWS: [Law; 5] = [
        Law::Ramp,
        Law::Step,
        Law::Poly345,
        Law::Harmonic,
        Law::Cycloidal,
    ];

    /// Each shape derivative against a central difference of the order below.
    #[test]
    fn shape_derivatives_match_differences() {
        let h = 1e-5;
        for law in LAWS {
            for &u in &[0.1, 0.3, 0.5, 0.77, 0.9] {
                let s = law.shape(u);
                let (p, m) = (law.shape(u + h), law.shape(u - h));
                for k in 0..3 {
                    let fd = (p[k] - m[k]) / (2.0 * h);
                    let tol = 1e-8 * (1.0 + s[k + 1].abs());
                    assert!(
                        (fd - s[k + 1]).abs() < tol,
                        "{law:?} order {} at u = {u}: {} vs {fd}",
                        k + 1,
                        s[k + 1]
                    );
                }
            }
        }
    }

    /// The fourth and fifth derivatives against central differences of
    /// the orders below.
    #[test]
    fn fourth_and_fifth_derivatives_match_differences() {
        let h = 1e-5;
        for law in LAWS {
            for &u in &[0.1, 0.3, 0.5, 0.77, 0.9] {
                let s = law.shape5(u);
                let (p, m) = (law.shape5(u + h), law.shape5(u - h));
                assert_eq!(s[..4], law.shape(u), "{law:?}");
                for k in 3..5 {
                    let fd = (p[k] - m[k]) / (2.0 * h);
                    let tol = 1e-6 * (1.0 + s[k + 1].abs());
                    assert!(
                        (fd - s[k + 1]).abs() < tol,
                        "{law:?} order {} at u = {u}",
                        k + 1
                    );
                }
            }
        }
    }

    /// s(0) = 0, s(1) = 1; derivatives up to the law's continuity order vanish
    /// at both ends, the next one does not (at one end at least).
    #[test]
    fn shapes_meet_the_constant_pieces_as_smoothly_as_documented() {
        for law in LAWS {
            let (a, b) = (law.shape(0.0), law.shape(1.0));
            assert!(a[0].abs() < 1e-15, "{law:?}");
            assert!((b[0] - 1.0).abs() < 1e-15, "{law:?}");
            let c = law.continuity();
            for k in 1..=c {
                assert!(a[k].abs() < 1e-12 && b[k].abs() < 1e-12, "{law:?} {k}");
            }
            assert!(
                a[c + 1].abs() > 1e-3 || b[c + 1].abs() > 1e-3,
                "{law:?} is smoother than documented"
            );
        }
    }

    #[test]
    fn boundary_values_are_exact() {
        for law in LAWS {
            assert_eq!(law.value(0.0, 0.0, 0.1, 1.0, 0.3), 0.1);
            assert_eq!(law.value(1.0, 0.0, 0.1, 1.0, 0.3), 0.3);
            assert_eq!(law.value(-5.0, 0.0, 0.1, 1.0, 0.3), 0.1);
            assert_eq!(law.value(5.0, 0.0, 0.1, 1.0, 0.3), 0.3);
            // Reversed direction: from (2, 7) down in x to (1, 3).
            assert_eq!(law.value(2.5, 2.0, 7.0, 1.0, 3.0), 7.0);
            assert_eq!(law.value(0.5, 2.0, 7.0, 1.0, 3.0), 3.0);
        }
    }

    #[test]
    fn adams_step_midpoint_and_slope() {
        // STEP(x, 0, 0, 2, 10) at x = 1 is 5 with slope 10·1.5/2 = 7.5 and
        // third derivative 10·(−12)/2³ = −15.
        let j = Law::Step.jet(
            Jet::variable(1.0),
            Jet::constant(0.0),
            Jet::constant(0.0),
            Jet::constant(2.0),
            Jet::constant(10.0),
        );
        assert_eq!(j.0, [5.0, 7.5, 0.0, -15.0]);
    }
}
