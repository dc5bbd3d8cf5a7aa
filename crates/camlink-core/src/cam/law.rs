//! Motion laws: normalised shapes S(u) on 0 ≤ u ≤ 1 with their
//! derivatives to the fifth, and the textbook peak factors.
//!
//! A law rises from S(0) = 0 to S(1) = 1. A segment of span β (rad) and
//! lift h follows s(θ) = s₀ + h S(u), u = (θ − θ₀)/β, so
//! s⁽ᵏ⁾ = h S⁽ᵏ⁾(u)/βᵏ. The peak factors Cv = max|S′|, Ca = max|S″|,
//! Cj = max|S‴| are the dimensionless velocity, acceleration and jerk
//! (Norton, *Cam Design and Manufacturing Handbook*, 2nd ed.;
//! Rothbart, *Cam Design Handbook*).
//!
//! Constant velocity, 3-4-5, simple harmonic and cycloidal are the
//! expression language's motion laws ([`camlink_expr::Law`]: `ramp`,
//! `poly345`, `harmonic`, `cycloidal`), one implementation of each. The
//! others are exact in closed form too:
//! - polynomials in u (4-5-6-7 and the fitted polynomial);
//! - piecewise trigonometric accelerations
//!   S″ = A₀ + A₁ sin ω(u − u_k) + A₂ cos ω(u − u_k) on [u_k, u_{k+1}],
//!   integrated exactly from S(0) = S′(0) = 0 and scaled so S(1) = 1
//!   (simple harmonic, cycloidal, modified trapezoid, modified sine).

use std::f64::consts::PI;

/// Derivatives `[S, S′, S″, S‴, S⁗, S⁽⁵⁾]` with respect to u.
pub type Shape5 = [f64; 6];

/// A named motion law.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LawKind {
    Dwell,
    ConstantVelocity,
    SimpleHarmonic,
    Cycloidal,
    ModifiedTrapezoid,
    ModifiedSine,
    Poly345,
    Poly4567,
    /// A polynomial fitted to boundary conditions.
    Polynomial,
}

impl LawKind {
    /// Every named law, in the order of the docs.
    pub const ALL: [LawKind; 9] = [
        LawKind::Dwell,
        LawKind::ConstantVelocity,
        LawKind::SimpleHarmonic,
        LawKind::Cycloidal,
        LawKind::ModifiedTrapezoid,
        LawKind::ModifiedSine,
        LawKind::Poly345,
        LawKind::Poly4567,
        LawKind::Polynomial,
    ];

    /// The name used in design files.
    pub fn name(self) -> &'static str {
        match self {
            LawKind::Dwell => "dwell",
            LawKind::ConstantVelocity => "constant-velocity",
            LawKind::SimpleHarmonic => "simple-harmonic",
            LawKind::Cycloidal => "cycloidal",
            LawKind::ModifiedTrapezoid => "modified-trapezoid",
            LawKind::ModifiedSine => "modified-sine",
            LawKind::Poly345 => "3-4-5",
            LawKind::Poly4567 => "4-5-6-7",
            LawKind::Polynomial => "polynomial",
        }
    }

    /// The law named `name`.
    pub fn parse(name: &str) -> Option<LawKind> {
        LawKind::ALL.into_iter().find(|k| k.name() == name)
    }

    /// Textbook (Cv, Ca, Cj) of a rise by this law (Norton ch. 3):
    /// peaks of |S′|, |S″|, |S‴| inside the segment. `None` for a dwell and
    /// a fitted polynomial, whose factors depend on the segment.
    pub fn textbook(self) -> Option<[f64; 3]> {
        match self {
            LawKind::ConstantVelocity => Some([1.0, 0.0, 0.0]),
            LawKind::SimpleHarmonic => Some([PI / 2.0, PI * PI / 2.0, PI.powi(3) / 2.0]),
            LawKind::Cycloidal => Some([2.0, 2.0 * PI, 4.0 * PI * PI]),
            LawKind::ModifiedTrapezoid => Some([2.0, 4.888, 61.43]),
            LawKind::ModifiedSine => Some([1.760, 5.528, 69.47]),
            LawKind::Poly345 => Some([1.875, 5.7735, 60.0]),
            LawKind::Poly4567 => Some([2.1875, 7.5132, 52.5]),
            LawKind::Dwell | LawKind::Polynomial => None,
        }
    }
}

/// One piece of a trigonometric acceleration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    /// Start u_k of the piece.
    u0: f64,
    a0: f64,
    a1: f64,
    a2: f64,
    /// ω (rad per unit u); 0 for a constant piece.
    w: f64,
    /// S and S′ at u_k.
    s0: f64,
    v0: f64,
}

impl Piece {
    /// `[S, S′, S″, S‴, S⁗, S⁽⁵⁾]` at u, x = u − u_k.
    fn eval(&self, u: f64) -> Shape5 {
        let x = u - self.u0;
        let (a0, a1, a2, w) = (self.a0, self.a1, self.a2, self.w);
        let mut d = [
            self.s0 + self.v0 * x + 0.5 * a0 * x * x,
            self.v0 + a0 * x,
            a0,
            0.0,
            0.0,
            0.0,
        ];
        if w != 0.0 {
            let (sn, cs) = (w * x).sin_cos();
            d[0] += a1 * (x - sn / w) / w + a2 * (1.0 - cs) / (w * w);
            d[1] += a1 * (1.0 - cs) / w + a2 * sn / w;
            d[2] += a1 * sn + a2 * cs;
            d[3] = w * (a1 * cs - a2 * sn);
            d[4] = -w * w * (a1 * sn + a2 * cs);
            d[5] = -w * w * w * (a1 * cs - a2 * sn);
        }
        d
    }
}

/// A normalised shape S(u).
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A motion law of the expression language.
    Law(camlink_expr::Law),
    /// S = Σ c_i uⁱ.
    Poly(Vec<f64>),
    /// Piecewise trigonometric acceleration.
    Trig(Vec<Piece>),
}

impl Shape {
    /// The shape of a named law (a dwell is S = 0, a fitted polynomial has
    /// no standard shape: both give `None`).
    pub fn of(kind: LawKind) -> Option<Shape> {
        use camlink_expr::Law;
        match kind {
            LawKind::Dwell | LawKind::Polynomial => None,
            LawKind::ConstantVelocity => Some(Shape::Law(Law::Ramp)),
            LawKind::Poly345 => Some(Shape::Law(Law::Poly345)),
            LawKind::SimpleHarmonic => Some(Shape::Law(Law::Harmonic)),
            LawKind::Cycloidal => Some(Shape::Law(Law::Cycloidal)),
            LawKind::Poly4567 => Some(Shape::Poly(vec![
                0.0, 0.0, 0.0, 0.0, 35.0, -84.0, 70.0, -20.0,
            ])),
            // Sine ramps over eighths, constant over quarters.
            LawKind::ModifiedTrapezoid => trig(&[
                (0.0, 0.0, 1.0, 0.0, 4.0 * PI),
                (0.125, 1.0, 0.0, 0.0, 0.0),
                (0.375, 0.0, 0.0, 1.0, 4.0 * PI),
                (0.625, -1.0, 0.0, 0.0, 0.0),
                (0.875, 0.0, 0.0, -1.0, 4.0 * PI),
            ]),
            // A quarter sine of period 1/2, a half cosine of period 3/2, a
            // quarter sine back to zero.
            LawKind::ModifiedSine => trig(&[
                (0.0, 0.0, 1.0, 0.0, 4.0 * PI),
                (0.125, 0.0, 0.0, 1.0, 4.0 * PI / 3.0),
                (0.875, 0.0, 0.0, -1.0, 4.0 * PI),
            ]),
        }
    }

    /// `[S, S′, S″, S‴, S⁗, S⁽⁵⁾]` at u (clamped to [0, 1]).
    pub fn eval(&self, u: f64) -> Shape5 {
        let u = u.clamp(0.0, 1.0);
        match self {
            Shape::Law(law) => law.shape5(u),
            Shape::Poly(c) => poly_eval(c, u),
            Shape::Trig(pieces) => {
                let k = pieces.iter().rposition(|p| p.u0 <= u).unwrap_or(0);
                pieces[k].eval(u)
            }
        }
    }
}

/// Builds the trigonometric shape from pieces (u_k, A₀, A₁, A₂, ω): chains
/// S and S′ across the pieces from zero, then scales so S(1) = 1.
fn trig(spec: &[(f64, f64, f64, f64, f64)]) -> Option<Shape> {
    let mut pieces: Vec<Piece> = Vec::with_capacity(spec.len());
    let (mut s0, mut v0) = (0.0, 0.0);
    for (k, &(u0, a0, a1, a2, w)) in spec.iter().enumerate() {
        let p = Piece {
            u0,
            a0,
            a1,
            a2,
            w,
            s0,
            v0,
        };
        let end = spec.get(k + 1).map_or(1.0, |n| n.0);
        let d = p.eval(end);
        (s0, v0) = (d[0], d[1]);
        pieces.push(p);
    }
    let k = 1.0 / s0;
    for p in &mut pieces {
        p.a0 *= k;
        p.a1 *= k;
        p.a2 *= k;
        p.s0 *= k;
        p.v0 *= k;
    }
    Some(Shape::Trig(pieces))
}

/// `[P, P′, …, P⁽⁵⁾]` of P(u) = Σ c_i uⁱ (Horner on each derivative).
pub fn poly_eval(c: &[f64], u: f64) -> Shape5 {
    let mut d = [0.0; 6];
    for (k, dk) in d.iter_mut().enumerate() {
        let mut acc = 0.0;
        for i in (k..c.len()).rev() {
            // i!/(i−k)! c_i u^(i−k)
            let f: f64 = ((i - k + 1)..=i).map(|m| m as f64).product();
            acc = acc * u + f * c[i];
        }
        *dk = acc;
    }
    d
}

/// The argument of the maximum of a unimodal f on [a, b], by golden-section
/// search (60 steps: the bracket shrinks by 0.618⁶⁰ ≈ 3e-13).
pub fn golden_max(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..60 {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if f(c) > f(d) {
            b = d;
        } else {
            a = c;
        }
    }
    0.5 * (a + b)
}

/// Peak |S′|, |S″|, |S‴| of a shape, sampled at `n` points and refined.
pub fn peaks(eval: impl Fn(f64) -> Shape5, n: usize) -> [f64; 3] {
    let mut out = [0.0f64; 3];
    for (k, o) in out.iter_mut().enumerate() {
        let f = |u: f64| eval(u)[k + 1].abs();
        let mut best = (0.0, f(0.0));
        for i in 1..=n {
            let u = i as f64 / n as f64;
            let v = f(u);
            if v > best.1 {
                best = (u, v);
            }
        }
        // Golden-section refinement around the best sample.
        let h = 1.0 / n as f64;
        let u = golden_max(f, (best.0 - h).max(0.0), (best.0 + h).min(1.0));
        *o = best.1.max(f(u));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shapes() -> Vec<(LawKind, Shape)> {
        LawKind::ALL
            .into_iter()
            .filter_map(|k| Shape::of(k).map(|s| (k, s)))
            .collect()
    }

    /// Each derivative against a central difference of the order below.
    #[test]
    fn shape_derivatives_match_differences() {
        let h = 1e-5;
        for (kind, s) in shapes() {
            for &u in &[0.05, 0.2, 0.3, 0.45, 0.55, 0.7, 0.8, 0.95] {
                let (p, m, d) = (s.eval(u + h), s.eval(u - h), s.eval(u));
                for k in 0..5 {
                    let fd = (p[k] - m[k]) / (2.0 * h);
                    let tol = 1e-6 * (1.0 + d[k + 1].abs());
                    assert!(
                        (fd - d[k + 1]).abs() < tol,
                        "{kind:?} order {} at {u}: {} vs {fd}",
                        k + 1,
                        d[k + 1]
                    );
                }
            }
        }
    }

    /// Every law rises from 0 to 1 with zero end velocity (constant velocity
    /// excepted).
    #[test]
    fn shapes_rise_from_zero_to_one() {
        for (kind, s) in shapes() {
            let (a, b) = (s.eval(0.0), s.eval(1.0));
            assert!(a[0].abs() < 1e-14 && (b[0] - 1.0).abs() < 1e-13, "{kind:?}");
            if kind != LawKind::ConstantVelocity {
                assert!(a[1].abs() < 1e-13 && b[1].abs() < 1e-12, "{kind:?}");
            }
        }
    }

    /// Cv, Ca, Cj against the textbook's table (to its printed digits).
    #[test]
    fn peak_factors_match_textbook_table() {
        for (kind, s) in shapes() {
            let got = peaks(|u| s.eval(u), 2000);
            let want = kind.textbook().unwrap();
            for k in 0..3 {
                let tol = 1e-3 * want[k].max(1.0);
                assert!(
                    (got[k] - want[k]).abs() < tol,
                    "{kind:?} C{}: {} vs textbook {}",
                    ["v", "a", "j"][k],
                    got[k],
                    want[k]
                );
            }
        }
    }

    /// Constant velocity and 3-4-5 are their polynomials, simple harmonic
    /// (1 − cos πu)/2, each with its derivatives to the fifth.
    #[test]
    fn polynomial_and_harmonic_laws_are_their_closed_forms() {
        for &u in &[0.0, 0.1, 0.37, 0.8, 1.0] {
            let (sn, cs) = (PI * u).sin_cos();
            let harmonic = [
                0.5 * (1.0 - cs),
                0.5 * PI * sn,
                0.5 * PI * PI * cs,
                -0.5 * PI.powi(3) * sn,
                -0.5 * PI.powi(4) * cs,
                0.5 * PI.powi(5) * sn,
            ];
            for (kind, want) in [
                (LawKind::ConstantVelocity, poly_eval(&[0.0, 1.0], u)),
                (
                    LawKind::Poly345,
                    poly_eval(&[0.0, 0.0, 0.0, 10.0, -15.0, 6.0], u),
                ),
                (LawKind::SimpleHarmonic, harmonic),
            ] {
                let got = Shape::of(kind).unwrap().eval(u);
                for k in 0..6 {
                    let tol = 1e-12 * (1.0 + want[k].abs());
                    assert!((got[k] - want[k]).abs() < tol, "{kind:?} order {k} at {u}");
                }
            }
        }
    }

    /// The exact cycloidal shape u − sin(2πu)/(2π) and its derivatives.
    #[test]
    fn cycloidal_is_the_closed_form() {
        let s = Shape::of(LawKind::Cycloidal).unwrap();
        for &u in &[0.1, 0.37, 0.8] {
            let w = 2.0 * PI;
            let (sn, cs) = (w * u).sin_cos();
            let want = [
                u - sn / w,
                1.0 - cs,
                w * sn,
                w * w * cs,
                -w * w * w * sn,
                -w.powi(4) * cs,
            ];
            let got = s.eval(u);
            for k in 0..6 {
                assert!((got[k] - want[k]).abs() < 1e-12 * (1.0 + want[k].abs()));
            }
        }
    }
}
