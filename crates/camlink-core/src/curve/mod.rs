//! Curves attached to bodies: cam profiles, follower faces and slots.
//!
//! A curve answers, at its parameter s, the point p(s) in the frame of the
//! body that carries it (m) and the derivatives p′ = dp/ds (the tangent g′
//! of the seed lecture), p″ and p‴ ([`CurveJet`]). The curve-contact
//! constraints need p‴ for γ.
//!
//! Two kinds of curve:
//!
//! - [`Polar`] — a profile ρ(α) about a body point Q, exactly the seed's
//!   convex-boundary parameterization: s′ = s′_Q + ρ(α) u(α),
//!   g′ = ρ′(α) u(α) + ρ(α) u⊥(α), u(α) = (cos α, sin α). The parameter is
//!   the angle α (rad) in the body frame; the profile is closed with period
//!   2π. Sources of ρ ([`Radius`]): a constant (circle), an expression in
//!   `a`, a Fourier series, a periodic cubic spline.
//! - [`Parametric`] — a curve (x(s), y(s)) for open slots and shapes that are
//!   not star-shaped: line segment, arc, full circle, an expression pair in
//!   `s`, a cubic spline through points. Built-in shapes and splines use arc
//!   length (m) as parameter (chord length for splines); an expression pair
//!   uses the user's parameter.
//!
//! A closed curve wraps its parameter ([`Curve::wrap`]): a contact
//! coordinate may grow without bound as a cam turns, and the curve is
//! evaluated at the wrapped value. An open curve has ends ([`Curve::range`])
//! and is evaluated past them by extension (the line goes on, the arc goes
//! round, a spline continues its end cubic); whether a contact left the
//! curve is a question for the analysis, which knows the range.
//!
//! Derivatives are exact: closed forms for lines, arcs, circles and Fourier
//! series, forward-mode jets for expressions, and the spline's own
//! polynomial pieces. A cubic spline is C² — position, tangent and
//! curvature are continuous — and its third derivative is piecewise
//! constant, jumping at the knots.

use std::f64::consts::TAU;

use crate::fmt_num::num;
use crate::math::{cross, norm, sub, V2};
use crate::quantity::Quantity;

pub mod carried;
pub mod contact;
pub mod distance;
pub mod fourier;
pub mod parametric;
pub mod points;
pub mod polar;
pub mod sample;
pub mod search;
pub mod spline;

pub use carried::{carried_paths, Carried};
pub use fourier::Fourier;
pub use parametric::Parametric;
pub use points::{excerpt, parse_points_csv, read_points_csv, MAX_POINTS_FILE_SIZE};
pub use polar::{Polar, Radius};
pub use spline::{PlanarSpline, Spline};

/// A curve point and its derivatives with respect to the curve parameter
/// s, all in the body frame: p (m), p′ = dp/ds, p″, p‴.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CurveJet {
    pub p: V2,
    pub d1: V2,
    pub d2: V2,
    pub d3: V2,
}

/// A [`CurveJet`] and the fourth derivative p⁗ = d⁴p/ds⁴ (body frame),
/// which the jerk analysis of a curve contact needs.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CurveJet4 {
    pub jet: CurveJet,
    pub d4: V2,
}

/// Why a curve could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CurveError {
    /// A points file could not be read.
    #[error("{file}: {message}")]
    Io { file: String, message: String },
    /// A row of a points file is not two numbers.
    #[error("{file}:{line}: {message}")]
    Csv {
        file: String,
        line: usize,
        message: String,
    },
    /// An expression did not parse.
    #[error("expression '{source_text}': {message}")]
    Expr {
        source_text: String,
        message: String,
    },
    /// A size, range or set of points that does not make a curve.
    #[error("{0}")]
    Invalid(String),
}

/// A curve in a body frame: a polar profile or a parametric curve.
#[derive(Clone, Debug)]
pub enum Curve {
    Polar(Polar),
    Parametric(Parametric),
}

impl Curve {
    /// p(s), p′, p″, p‴ in the body frame at parameter `s` (closed curves
    /// wrap `s`).
    #[inline]
    pub fn jet(&self, s: f64) -> CurveJet {
        match self {
            Curve::Polar(c) => c.jet(s),
            Curve::Parametric(c) => c.jet(s),
        }
    }

    /// p(s) … p⁗(s) in the body frame at parameter `s` (closed curves wrap
    /// `s`): [`jet`](Self::jet) one order further, for the jerk analysis.
    pub fn jet4(&self, s: f64) -> CurveJet4 {
        match self {
            Curve::Polar(c) => c.jet4(s),
            Curve::Parametric(c) => c.jet4(s),
        }
    }

    /// What the parameter measures: the angle α (rad) of a polar profile
    /// or a synthesised cam, arc length (m) of a line, arc, circle or
    /// spline, a pure number for a curve written as expressions in `s`.
    pub(crate) fn parameter_quantity(&self) -> Quantity {
        match self {
            Curve::Polar(_) | Curve::Parametric(Parametric::Cam { .. }) => Quantity::Angle,
            Curve::Parametric(Parametric::Expr { .. }) => Quantity::Dimensionless,
            Curve::Parametric(_) => Quantity::Length,
        }
    }

    /// True for a closed curve (its parameter wraps).
    pub fn closed(&self) -> bool {
        match self {
            Curve::Polar(_) => true,
            Curve::Parametric(c) => c.closed(),
        }
    }

    /// The parameter range (s₀, s₁): the ends of an open curve, one period
    /// of a closed one ((0, 2π) for a polar profile).
    pub fn range(&self) -> (f64, f64) {
        match self {
            Curve::Polar(_) => (0.0, TAU),
            Curve::Parametric(c) => c.range(),
        }
    }

    /// The period s₁ − s₀ of a closed curve; `None` for an open one.
    pub fn period(&self) -> Option<f64> {
        let (s0, s1) = self.range();
        self.closed().then_some(s1 - s0)
    }

    /// `s` wrapped into [s₀, s₁) for a closed curve; `s` itself for an open
    /// one.
    #[inline]
    pub fn wrap(&self, s: f64) -> f64 {
        let (s0, s1) = self.range();
        if self.closed() {
            s0 + (s - s0).rem_euclid(s1 - s0)
        } else {
            s
        }
    }

    /// Signed curvature κ = (p′ × p″)/|p′|³ (1/m) in the body frame:
    /// positive where the curve turns left (counterclockwise) as s grows.
    /// A convex polar profile has κ > 0 everywhere.
    pub fn curvature(&self, s: f64) -> f64 {
        let j = self.jet(s);
        cross(j.d1, j.d2) / norm(j.d1).powi(3)
    }

    /// +1 for a counterclockwise closed curve, −1 for a clockwise one (the
    /// sign of its enclosed area ½∮ p × p′ ds, summed at 720 midpoints);
    /// `None` for an open curve.
    pub(crate) fn orientation(&self) -> Option<f64> {
        const SAMPLES: usize = 720;
        if !self.closed() {
            return None;
        }
        let (s0, s1) = self.range();
        let h = (s1 - s0) / SAMPLES as f64;
        let area: f64 = (0..SAMPLES)
            .map(|k| {
                let j = self.jet(s0 + (k as f64 + 0.5) * h);
                cross(j.p, j.d1)
            })
            .sum();
        Some(if area < 0.0 { -1.0 } else { 1.0 })
    }

    /// The centre (m, body frame) and radius r (m) of a circular curve (a
    /// roller: a constant-radius polar profile, a circle or an arc); `None`
    /// for any other curve.
    pub(crate) fn circle_centre(&self) -> Option<(V2, f64)> {
        match self {
            Curve::Polar(p) => match p.rho {
                Radius::Const(r) => Some((p.q, r)),
                _ => None,
            },
            Curve::Parametric(Parametric::Circle { c, r, .. })
            | Curve::Parametric(Parametric::Arc { c, r, .. }) => Some((*c, *r)),
            _ => None,
        }
    }

    /// Parameter intervals (a, b) where the curve is concave, κ < 0 (below
    /// −10⁻⁹ times the largest |κ| found, so straight pieces do not count).
    /// The curvature is sampled at `samples` points over the range and each
    /// sign change located by bisection. For a closed curve an interval
    /// that crosses the start of the range is returned once, as (a, b) with
    /// s₀ ≤ a < s₁ < b. A flat-faced follower needs a cam with no concave
    /// interval.
    pub fn concave_ranges(&self, samples: usize) -> Vec<(f64, f64)> {
        let n = samples.max(8);
        let tol = 1e-9 * self.max_curvature(n);
        self.ranges_where(n, |s| self.curvature(s) < -tol)
    }

    /// Largest |κ| (1/m) over `samples` points spread over the range.
    pub(crate) fn max_curvature(&self, samples: usize) -> f64 {
        let (s0, s1) = self.range();
        (0..samples)
            .map(|k| {
                self.curvature(s0 + (s1 - s0) * k as f64 / samples as f64)
                    .abs()
            })
            .fold(0.0, f64::max)
    }

    /// Parameter intervals (a, b) of the range where `inside` holds, sampled
    /// at `samples` points and each edge located by bisection. On a closed
    /// curve an interval across the start of the range is returned once, as
    /// (a, b) with s₀ ≤ a < s₁ < b; a jump of the predicate at the seam is
    /// not an edge.
    pub(crate) fn ranges_where(
        &self,
        samples: usize,
        inside: impl Fn(f64) -> bool,
    ) -> Vec<(f64, f64)> {
        let (s0, s1) = self.range();
        let at = |k: usize| s0 + (s1 - s0) * k as f64 / samples as f64;
        // Locate the change between a and b by bisection.
        let edge = |mut a: f64, mut b: f64| {
            let sa = inside(a);
            for _ in 0..60 {
                let m = 0.5 * (a + b);
                if inside(m) == sa {
                    a = m;
                } else {
                    b = m;
                }
            }
            0.5 * (a + b)
        };
        let mut out = Vec::new();
        let mut start = inside(s0).then_some(s0);
        let mut prev = start.is_some();
        for k in 0..samples {
            let (a, b) = (at(k), at(k + 1));
            let now = if k + 1 == samples && self.closed() {
                inside(s0)
            } else {
                inside(b)
            };
            if now != prev {
                let e = edge(a, b);
                if now {
                    start = Some(e);
                } else if let Some(st) = start.take() {
                    out.push((st, e));
                }
            }
            prev = now;
        }
        if let Some(st) = start {
            if self.closed() && !out.is_empty() && out[0].0 == s0 {
                // An interval running over the end joins the one that
                // started at s₀; an edge found within rounding of s₁ is
                // that start itself (the predicate jumps at the seam).
                if s1 - st > 1e-9 * (s1 - s0) {
                    let first = out.remove(0);
                    out.push((st, first.1 + (s1 - s0)));
                }
            } else {
                out.push((st, s1));
            }
        }
        out
    }

    /// Checks the curve on a grid of `samples` points: every jet finite,
    /// the tangent nonzero, and ρ > 0 for a polar profile.
    pub fn check(&self, samples: usize) -> Result<(), CurveError> {
        let (s0, s1) = self.range();
        let n = samples.max(2);
        for k in 0..=n {
            let s = s0 + (s1 - s0) * k as f64 / n as f64;
            let j = self.jet(s);
            let all = [j.p, j.d1, j.d2, j.d3];
            if all.iter().flatten().any(|v| !v.is_finite()) {
                return Err(CurveError::Invalid(format!(
                    "the curve is not finite at parameter {}",
                    num(s)
                )));
            }
            if norm(j.d1) == 0.0 {
                return Err(CurveError::Invalid(format!(
                    "the curve has no tangent (p′ = 0) at parameter {}",
                    num(s)
                )));
            }
            if let Curve::Polar(p) = self {
                let rho = p.rho.jet(s)[0];
                if rho <= 0.0 {
                    return Err(CurveError::Invalid(format!(
                        "the polar profile has ρ = {} ≤ 0 at α = {}",
                        num(rho),
                        num(s)
                    )));
                }
            }
        }
        self.check_continuity(n)
    }

    /// Checks that the curve has no jump in position or tangent direction
    /// between `samples` grid points (a jump is a change far beyond what
    /// p′ and p″ allow over the spacing), and that a closed curve closes:
    /// p and the tangent direction at the end of the range meet those at
    /// its start. Errors name the parameter.
    fn check_continuity(&self, samples: usize) -> Result<(), CurveError> {
        let (s0, s1) = self.range();
        let h = (s1 - s0) / samples as f64;
        let jets: Vec<(f64, CurveJet)> = (0..=samples)
            .map(|k| {
                // The end of a closed range wraps to its start: approach it.
                let s = if k == samples && self.closed() {
                    s1 - 1e-9 * (s1 - s0)
                } else {
                    s0 + h * k as f64
                };
                (s, self.jet(s))
            })
            .collect();
        let size = jets
            .iter()
            .map(|(_, j)| norm(j.p))
            .fold(0.0_f64, f64::max)
            .max(1e-300);
        let angle = |a: V2, b: V2| (a[0] * b[1] - a[1] * b[0]).atan2(a[0] * b[0] + a[1] * b[1]);
        for w in jets.windows(2) {
            let ((sa, a), (sb, b)) = (w[0], w[1]);
            let ds = sb - sa;
            let dp = norm(sub(b.p, a.p));
            // Taylor: |Δp| ≤ |p′|Δs + |p″|Δs²/2; far beyond it is a jump.
            let speed = norm(a.d1).max(norm(b.d1));
            let bend = norm(a.d2).max(norm(b.d2));
            if dp > 4.0 * (speed * ds + bend * ds * ds) + 1e-9 * size {
                return Err(CurveError::Invalid(format!(
                    "the curve jumps by {} between parameter {} and {} (not continuous)",
                    num(dp),
                    num(sa),
                    num(sb)
                )));
            }
            let turn = angle(a.d1, b.d1).abs();
            let rate = |j: &CurveJet| {
                let v = norm(j.d1);
                (j.d1[0] * j.d2[1] - j.d1[1] * j.d2[0]).abs() / (v * v)
            };
            let third = norm(a.d3).max(norm(b.d3)) / speed.max(1e-300);
            if turn > 0.1 && turn > 4.0 * (rate(&a).max(rate(&b)) * ds + third * ds * ds) {
                return Err(CurveError::Invalid(format!(
                    "the tangent turns by {} rad between parameter {} and {} (a corner)",
                    num(turn),
                    num(sa),
                    num(sb)
                )));
            }
        }
        if self.closed() {
            let (start, end) = (&jets[0].1, &jets[samples].1);
            let gap = norm(sub(end.p, start.p));
            if gap > 1e-6 * size + 1e-6 * norm(end.d1) * (s1 - s0) {
                return Err(CurveError::Invalid(format!(
                    "the closed curve does not close: its ends at parameter {} and {} are {} apart",
                    num(s0),
                    num(s1),
                    num(gap)
                )));
            }
            let turn = angle(end.d1, start.d1).abs();
            if turn > 1e-3 {
                return Err(CurveError::Invalid(format!(
                    "the closed curve has a corner where it closes (parameter {}): the tangent turns by {} rad",
                    num(s0),
                    num(turn)
                )));
            }
        }
        Ok(())
    }
}

impl From<Polar> for Curve {
    fn from(c: Polar) -> Self {
        Curve::Polar(c)
    }
}

impl From<Parametric> for Curve {
    fn from(c: Parametric) -> Self {
        Curve::Parametric(c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// Numerator of the polar curvature, ρ² + 2ρ′² − ρρ″.
    fn polar_numerator(p: &Polar, a: f64) -> f64 {
        let [r, r1, r2, _] = p.rho.jet(a);
        r * r + 2.0 * r1 * r1 - r * r2
    }

    #[test]
    fn polar_curvature_matches_the_polar_formula() {
        let p = Polar::fourier([0.2, 0.1], 1.0, &[0.3, 0.1], &[0.0, 0.05]).unwrap();
        let c = Curve::from(p.clone());
        for &a in &[0.1, 1.0, 2.5, 4.0] {
            let [r, r1, _, _] = p.rho.jet(a);
            let want = polar_numerator(&p, a) / (r * r + r1 * r1).powf(1.5);
            assert!((c.curvature(a) - want).abs() < 1e-12);
        }
    }

    #[test]
    fn concave_ranges_of_a_three_lobe_cam() {
        // ρ = 1 + 0.3 cos 3α is concave about α = π/3, π, 5π/3.
        let p = Polar::fourier([0.0, 0.0], 1.0, &[0.0, 0.0, 0.3], &[]).unwrap();
        let c = Curve::from(p.clone());
        let r = c.concave_ranges(360);
        assert_eq!(r.len(), 3, "{r:?}");
        for (k, &(a, b)) in r.iter().enumerate() {
            let mid = (2 * k + 1) as f64 * PI / 3.0;
            assert!(((a + b) / 2.0 - mid).abs() < 1e-9, "{r:?}");
            // The edges are where κ crosses −10⁻⁹ max|κ|.
            assert!(polar_numerator(&p, a).abs() < 1e-7 && polar_numerator(&p, b).abs() < 1e-7);
            assert!(c.curvature(mid) < 0.0);
        }
        // A circle has none; a concave range across α = 0 comes back whole.
        assert!(Curve::from(Polar::circle([0.0, 0.0], 1.0).unwrap())
            .concave_ranges(90)
            .is_empty());
        let p = Polar::fourier([0.0, 0.0], 1.0, &[0.0, 0.0, -0.3], &[]).unwrap();
        let r = Curve::from(p).concave_ranges(360);
        assert_eq!(r.len(), 3, "{r:?}");
        let (a, b) = r[2];
        assert!(
            a < TAU && b > TAU && ((a + b) / 2.0 - TAU).abs() < 1e-9,
            "{r:?}"
        );
    }

    #[test]
    fn concave_ranges_of_an_open_s_curve() {
        // y = sin x for x in (0.5, 5): concave (κ < 0) where sin x > 0.
        let pts: Vec<V2> = (0..=90)
            .map(|k| {
                let x = 0.5 + 4.5 * k as f64 / 90.0;
                [x, x.sin()]
            })
            .collect();
        let c = Curve::from(Parametric::spline(&pts, false).unwrap());
        let r = c.concave_ranges(400);
        assert_eq!(r.len(), 1, "{r:?}");
        assert_eq!(r[0].0, 0.0);
        let x_end = c.jet(r[0].1).p[0];
        assert!((x_end - PI).abs() < 1e-3, "{x_end}");
    }

    /// Every curve source: polar circle, expression, Fourier series and
    /// spline; parametric line, arc, circle, expression pair, open and
    /// closed splines.
    fn every_source() -> Vec<(Curve, (f64, f64))> {
        let pts = [[0.0, 0.0], [0.4, 0.2], [0.9, 0.1], [1.3, 0.5], [1.6, 0.4]];
        let radii: Vec<V2> = (0..7)
            .map(|k| [k as f64 * TAU / 7.0, 1.0 + 0.1 * (k as f64).sin()])
            .collect();
        vec![
            (Polar::circle([0.1, 0.2], 0.7).unwrap().into(), (-1.0, 7.0)),
            (
                Polar::expr([0.0, 0.1], "1 + 0.2*sin(2*a) + 0.05*exp(cos(a))")
                    .unwrap()
                    .into(),
                (0.1, 6.0),
            ),
            (
                Polar::fourier([0.1, 0.0], 1.0, &[0.2, 0.0, 0.05], &[0.1, 0.03])
                    .unwrap()
                    .into(),
                (-3.0, 9.0),
            ),
            (
                Polar::spline([0.0, 0.0], &radii).unwrap().into(),
                (0.1, 6.0),
            ),
            (
                Parametric::line([0.0, 0.0], [1.0, 2.0]).unwrap().into(),
                (-1.0, 3.0),
            ),
            (
                Parametric::arc([0.2, 0.0], 1.5, 0.2, 2.0).unwrap().into(),
                (0.1, 2.6),
            ),
            (
                Parametric::circle([0.0, 0.3], 0.4, 1.0).unwrap().into(),
                (-2.0, 5.0),
            ),
            (
                Parametric::expr(
                    "0.3*cos(s) + s^3/10",
                    "0.2*sin(s) + 0.1*s",
                    -1.0,
                    2.0,
                    false,
                )
                .unwrap()
                .into(),
                (-0.9, 1.9),
            ),
            (Parametric::spline(&pts, false).unwrap().into(), (0.05, 1.8)),
            (Parametric::spline(&pts, true).unwrap().into(), (-1.0, 5.0)),
        ]
    }

    /// jet4 extends jet: the same p … p‴, and p⁗ against central
    /// differences of p‴ (on a polar spline at parameters away from the
    /// knots, where ρ‴ jumps); a parametric cubic spline's p⁗ is exactly
    /// zero.
    #[test]
    fn fourth_derivative_of_every_source_matches_differences() {
        for (c, (s0, s1)) in every_source() {
            for k in 0..23 {
                let s = s0 + (s1 - s0) * (k as f64 + 0.5) / 23.0;
                let (j, j4) = (c.jet(s), c.jet4(s));
                let close = |a: V2, b: V2, tol: f64| {
                    (0..2).all(|i| (a[i] - b[i]).abs() <= tol * (1.0 + b[i].abs()))
                };
                assert!(
                    close(j4.jet.p, j.p, 1e-13) && close(j4.jet.d1, j.d1, 1e-13),
                    "{c:?} at {s}"
                );
                assert!(
                    close(j4.jet.d2, j.d2, 1e-13) && close(j4.jet.d3, j.d3, 1e-13),
                    "{c:?} at {s}"
                );
                let h = 1e-5;
                let (p, m) = (c.jet(s + h).d3, c.jet(s - h).d3);
                let fd = [(p[0] - m[0]) / (2.0 * h), (p[1] - m[1]) / (2.0 * h)];
                let spline = matches!(&c, Curve::Parametric(Parametric::Spline(_)));
                if spline {
                    assert_eq!(j4.d4, [0.0; 2], "{c:?} at {s}");
                } else {
                    assert!(
                        close(j4.d4, fd, 1e-6),
                        "{c:?} at {s}: {:?} vs {fd:?}",
                        j4.d4
                    );
                }
            }
        }
    }

    /// p⁗ of a circle of radius r about c, parametrised by arc length from
    /// angle θ₀: u(θ)/r³, θ = θ₀ + s/r; of a polar circle: ρ u(α).
    #[test]
    fn fourth_derivative_of_circles_in_closed_form() {
        let (r, th0, s) = (0.4, 1.0, 0.9);
        let c = Curve::from(Parametric::circle([0.0, 0.3], r, th0).unwrap());
        let th = th0 + s / r;
        let d4 = c.jet4(s).d4;
        assert!((d4[0] - th.cos() / r.powi(3)).abs() < 1e-12);
        assert!((d4[1] - th.sin() / r.powi(3)).abs() < 1e-12);
        let c = Curve::from(Polar::circle([0.1, 0.2], 0.7).unwrap());
        let d4 = c.jet4(2.0).d4;
        assert!(
            (d4[0] - 0.7 * 2f64.cos()).abs() < 1e-15 && (d4[1] - 0.7 * 2f64.sin()).abs() < 1e-15
        );
    }

    #[test]
    fn curves_are_shareable_across_threads() {
        fn shareable<T: Clone + std::fmt::Debug + Send + Sync>() {}
        shareable::<Curve>();
        shareable::<CurveJet>();
    }

    #[test]
    fn check_reports_a_bad_profile() {
        assert!(Curve::from(Polar::circle([0.0, 0.0], 1.0).unwrap())
            .check(100)
            .is_ok());
        let p = Polar::fourier([0.0, 0.0], 0.5, &[1.0], &[]).unwrap();
        let e = Curve::from(p).check(100).unwrap_err();
        assert!(e.to_string().contains("ρ"), "{e}");
    }
}
