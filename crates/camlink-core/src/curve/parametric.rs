//! Parametric curves (x(s), y(s)) in a body frame.
//!
//! For slots and for shapes that are not star-shaped about any point. The
//! line, the arc, the circle and the spline use length along the curve as
//! parameter: s (m) runs from 0 at the start to the length L at the end
//! (chord length for the spline). An expression pair uses the user's own
//! parameter `s` on the range they give.
//!
//! - line from P₀ to P₁: p = P₀ + s e, e = (P₁ − P₀)/L;
//! - arc of radius r about C from angle θ₀ to θ₁ (rad, body frame; θ₁ < θ₀
//!   runs clockwise): θ(s) = θ₀ + σ s/r, σ = sign(θ₁ − θ₀),
//!   p = C + r u(θ), p′ = σ u⊥(θ), p″ = −u(θ)/r, p‴ = −σ u⊥(θ)/r²,
//!   p⁗ = u(θ)/r³;
//! - circle: the closed counterclockwise arc from θ₀ round to θ₀ + 2π,
//!   period 2πr;
//! - expressions x(s), y(s) on [s₀, s₁], open or closed (period s₁ − s₀);
//! - cubic spline through points, open or closed ([`PlanarSpline`]);
//! - a synthesised cam's surface or pitch curve ([`crate::cam::Cam`]),
//!   parametrised by the cam angle θ (rad), closed with period 2π.

use std::f64::consts::TAU;
use std::sync::Arc;

use camlink_expr::Expr;

use super::{CurveError, CurveJet, CurveJet4, PlanarSpline};
use crate::cam::Cam;
use crate::math::{norm, scale, sub, V2};

/// A parametric curve in a body frame.
#[derive(Clone, Debug)]
pub enum Parametric {
    /// Segment from `p0` along the unit vector `e`, of length `len` (m).
    Line { p0: V2, e: V2, len: f64 },
    /// Arc about `c` of radius `r` from angle `start`, turning with sign
    /// `sigma` (±1), of length `len` (m).
    Arc {
        c: V2,
        r: f64,
        start: f64,
        sigma: f64,
        len: f64,
    },
    /// Full circle about `c` of radius `r`, starting at angle `start`,
    /// counterclockwise.
    Circle { c: V2, r: f64, start: f64 },
    /// x(s), y(s) on [s0, s1].
    Expr {
        x: Arc<Expr>,
        y: Arc<Expr>,
        s0: f64,
        s1: f64,
        closed: bool,
    },
    /// Cubic spline through points, parametrised by chord length.
    Spline(PlanarSpline),
    /// A synthesised cam's surface (or a roller's pitch curve when `pitch`),
    /// parametrised by the cam angle θ (rad) over [0, 2π), closed.
    Cam { cam: Arc<Cam>, pitch: bool },
}

fn positive(what: &str, v: f64) -> Result<f64, CurveError> {
    if v > 0.0 && v.is_finite() {
        Ok(v)
    } else {
        Err(CurveError::Invalid(format!(
            "{what} must be positive, got {v}"
        )))
    }
}

impl Parametric {
    /// The segment from `p0` to `p1` (m).
    pub fn line(p0: V2, p1: V2) -> Result<Self, CurveError> {
        let d = sub(p1, p0);
        let len = norm(d);
        if !(len > 0.0 && len.is_finite()) {
            return Err(CurveError::Invalid(format!(
                "a line needs two distinct points, got ({}, {}) and ({}, {})",
                p0[0], p0[1], p1[0], p1[1]
            )));
        }
        Ok(Parametric::Line {
            p0,
            e: scale(1.0 / len, d),
            len,
        })
    }

    /// The arc about `c` of radius `r` (m) from angle `start` to `end`
    /// (rad; counterclockwise when end > start), at most one turn.
    pub fn arc(c: V2, r: f64, start: f64, end: f64) -> Result<Self, CurveError> {
        positive("an arc's radius", r)?;
        let sweep = end - start;
        if !(sweep != 0.0 && sweep.abs() <= TAU && sweep.is_finite()) {
            return Err(CurveError::Invalid(format!(
                "an arc must sweep a nonzero angle of at most 2π, got {start} to {end}"
            )));
        }
        Ok(Parametric::Arc {
            c,
            r,
            start,
            sigma: sweep.signum(),
            len: r * sweep.abs(),
        })
    }

    /// The full circle about `c` of radius `r` (m), s = 0 at angle `start`
    /// (rad), counterclockwise.
    pub fn circle(c: V2, r: f64, start: f64) -> Result<Self, CurveError> {
        positive("a circle's radius", r)?;
        Ok(Parametric::Circle { c, r, start })
    }

    /// x(s), y(s) from expressions of `s` on [s0, s1].
    pub fn expr(x: &str, y: &str, s0: f64, s1: f64, closed: bool) -> Result<Self, CurveError> {
        if !(s1 > s0 && s0.is_finite() && s1.is_finite()) {
            return Err(CurveError::Invalid(format!(
                "a parametric curve needs a range s0 < s1, got {s0} to {s1}"
            )));
        }
        let parse = |src: &str| {
            Expr::parse(src, "s").map_err(|e| CurveError::Expr {
                source_text: src.to_string(),
                message: e.to_string(),
            })
        };
        Ok(Parametric::Expr {
            x: Arc::new(parse(x)?),
            y: Arc::new(parse(y)?),
            s0,
            s1,
            closed,
        })
    }

    /// The cubic spline through `points` (m), open or closed.
    pub fn spline(points: &[V2], closed: bool) -> Result<Self, CurveError> {
        Ok(Parametric::Spline(PlanarSpline::new(points, closed)?))
    }

    pub fn closed(&self) -> bool {
        match self {
            Parametric::Line { .. } | Parametric::Arc { .. } => false,
            Parametric::Circle { .. } => true,
            Parametric::Expr { closed, .. } => *closed,
            Parametric::Spline(s) => s.closed(),
            Parametric::Cam { .. } => true,
        }
    }

    pub fn range(&self) -> (f64, f64) {
        match self {
            Parametric::Line { len, .. } | Parametric::Arc { len, .. } => (0.0, *len),
            Parametric::Circle { r, .. } => (0.0, TAU * r),
            Parametric::Expr { s0, s1, .. } => (*s0, *s1),
            Parametric::Spline(s) => s.range(),
            Parametric::Cam { .. } => (0.0, TAU),
        }
    }

    /// An expression pair's parameter: `s` wrapped into [s₀, s₁) when the
    /// curve is closed, else `s`.
    #[inline]
    fn wrap_expr(&self, s: f64) -> f64 {
        match self {
            Parametric::Expr {
                s0,
                s1,
                closed: true,
                ..
            } => s0 + (s - s0).rem_euclid(s1 - s0),
            _ => s,
        }
    }

    /// p(s), p′, p″, p‴ in the body frame.
    #[inline]
    pub fn jet(&self, s: f64) -> CurveJet {
        match self {
            Parametric::Line { p0, e, .. } => CurveJet {
                p: [p0[0] + s * e[0], p0[1] + s * e[1]],
                d1: *e,
                ..CurveJet::default()
            },
            Parametric::Arc {
                c, r, start, sigma, ..
            } => arc_jet(*c, *r, *start, *sigma, s),
            Parametric::Circle { c, r, start } => arc_jet(*c, *r, *start, 1.0, s),
            Parametric::Expr { x, y, .. } => {
                let s = self.wrap_expr(s);
                let (x, y) = (x.jet(s), y.jet(s));
                CurveJet {
                    p: [x[0], y[0]],
                    d1: [x[1], y[1]],
                    d2: [x[2], y[2]],
                    d3: [x[3], y[3]],
                }
            }
            Parametric::Spline(sp) => sp.jet(s),
            Parametric::Cam { .. } => self.jet4(s).jet,
        }
    }

    /// p(s) … p⁗(s) in the body frame.
    pub fn jet4(&self, s: f64) -> CurveJet4 {
        match self {
            Parametric::Line { .. } => CurveJet4 {
                jet: self.jet(s),
                d4: [0.0; 2],
            },
            Parametric::Arc {
                c, r, start, sigma, ..
            } => arc_jet4(*c, *r, *start, *sigma, s),
            Parametric::Circle { c, r, start } => arc_jet4(*c, *r, *start, 1.0, s),
            Parametric::Expr { x, y, .. } => {
                let s = self.wrap_expr(s);
                let (x, y) = (x.jet4(s), y.jet4(s));
                CurveJet4 {
                    jet: CurveJet {
                        p: [x[0], y[0]],
                        d1: [x[1], y[1]],
                        d2: [x[2], y[2]],
                        d3: [x[3], y[3]],
                    },
                    d4: [x[4], y[4]],
                }
            }
            Parametric::Spline(sp) => sp.jet4(s),
            Parametric::Cam { cam, pitch } => {
                let th = s.rem_euclid(TAU);
                let j = match pitch {
                    true => cam.pitch(th).unwrap_or_else(|| cam.surface(th)),
                    false => cam.surface(th),
                };
                CurveJet4 {
                    jet: CurveJet {
                        p: j.p,
                        d1: j.d1,
                        d2: j.d2,
                        d3: j.d3,
                    },
                    d4: j.d4,
                }
            }
        }
    }
}

/// Jet of the arc to fourth order: p⁗ = u(θ)/r³.
fn arc_jet4(c: V2, r: f64, start: f64, sigma: f64, s: f64) -> CurveJet4 {
    let (sn, cs) = (start + sigma * s / r).sin_cos();
    CurveJet4 {
        jet: arc_jet(c, r, start, sigma, s),
        d4: scale(1.0 / (r * r * r), [cs, sn]),
    }
}

/// Jet of the arc p = C + r u(θ₀ + σ s/r).
#[inline]
fn arc_jet(c: V2, r: f64, start: f64, sigma: f64, s: f64) -> CurveJet {
    let (sn, cs) = (start + sigma * s / r).sin_cos();
    let (u, up) = ([cs, sn], [-sn, cs]);
    CurveJet {
        p: [c[0] + r * u[0], c[1] + r * u[1]],
        d1: scale(sigma, up),
        d2: scale(-1.0 / r, u),
        d3: scale(-sigma / (r * r), up),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::Curve;

    fn fd_check(c: &Parametric, ss: &[f64]) {
        let h = 1e-6;
        for &s in ss {
            let (p, m, j) = (c.jet(s + h), c.jet(s - h), c.jet(s));
            for (u, v, d) in [(p.p, m.p, j.d1), (p.d1, m.d1, j.d2), (p.d2, m.d2, j.d3)] {
                for k in 0..2 {
                    let fd = (u[k] - v[k]) / (2.0 * h);
                    assert!((fd - d[k]).abs() < 1e-6, "{c:?} at {s}: {fd} vs {}", d[k]);
                }
            }
        }
    }

    #[test]
    fn line_arc_circle_are_unit_speed_and_differentiate() {
        let l = Parametric::line([1.0, 1.0], [4.0, 5.0]).unwrap();
        assert_eq!(l.range(), (0.0, 5.0));
        assert_eq!(l.jet(5.0).p, [4.0, 5.0]);
        let a = Parametric::arc([0.5, 0.0], 2.0, 1.0, -0.5).unwrap();
        let (_, len) = a.range();
        assert!((len - 3.0).abs() < 1e-15);
        let end = a.jet(len).p;
        assert!((end[0] - (0.5 + 2.0 * (-0.5f64).cos())).abs() < 1e-14);
        let c = Parametric::circle([0.0, 1.0], 0.5, 0.3).unwrap();
        assert!(c.closed() && !a.closed() && !l.closed());
        for p in [&l, &a, &c] {
            fd_check(p, &[0.2, 1.1, 2.9]);
            assert!((norm(p.jet(0.7).d1) - 1.0).abs() < 1e-14);
        }
        // The clockwise arc curves right.
        assert!((Curve::from(a).curvature(0.3) + 0.5).abs() < 1e-12);
        assert!((Curve::from(c).curvature(0.3) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn closed_circle_wraps() {
        let c = Curve::from(Parametric::circle([0.0, 0.0], 1.0, 0.0).unwrap());
        assert_eq!(c.period(), Some(TAU));
        assert!((c.wrap(7.0) - (7.0 - TAU)).abs() < 1e-15);
        let (a, b) = (c.jet(0.5).p, c.jet(0.5 + 3.0 * TAU).p);
        assert!((a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12);
    }

    #[test]
    fn rejects_degenerate_shapes() {
        assert!(Parametric::line([1.0, 1.0], [1.0, 1.0]).is_err());
        assert!(Parametric::arc([0.0, 0.0], 1.0, 0.0, 0.0).is_err());
        assert!(Parametric::arc([0.0, 0.0], 1.0, 0.0, 7.0).is_err());
        assert!(Parametric::circle([0.0, 0.0], -1.0, 0.0).is_err());
        assert!(Parametric::expr("s", "s", 1.0, 0.0, false).is_err());
    }
}

#[cfg(test)]
mod expr_tests {
    use super::*;
    use crate::curve::Curve;

    #[test]
    fn ellipse_from_expressions() {
        let e = Parametric::expr("2*cos(s)", "sin(s)", 0.0, TAU, true).unwrap();
        let c = Curve::from(e);
        assert!(c.closed());
        let j = c.jet(0.7 + TAU);
        let want = [2.0 * 0.7f64.cos(), 0.7f64.sin()];
        assert!((j.p[0] - want[0]).abs() < 1e-14 && (j.p[1] - want[1]).abs() < 1e-14);
        assert!((j.d3[0] - 2.0 * 0.7f64.sin()).abs() < 1e-14);
        assert!((c.curvature(0.0) - 2.0).abs() < 1e-12);
        assert!(Parametric::expr("2*cos(s)", "sin(t)", 0.0, 1.0, false).is_err());
    }
}
