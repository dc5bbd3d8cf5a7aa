//! Polar profiles: the seed's convex-boundary parameterization.
//!
//! A point of the boundary of body i is located by the angle α (rad),
//! measured in the body frame from the x′ axis about a body point Q:
//!
//! s′(α) = s′_Q + ρ(α) u(α),   u(α) = (cos α, sin α), u⊥ = (−sin α, cos α)
//! g′(α) = ds′/dα = ρ′ u + ρ u⊥
//! s″ = (ρ″ − ρ) u + 2ρ′ u⊥
//! s‴ = (ρ‴ − 3ρ′) u + (3ρ″ − ρ) u⊥
//! s⁗ = (ρ⁗ − 6ρ″ + ρ) u + (4ρ‴ − 4ρ′) u⊥
//!
//! ρ (m) is evaluated at α wrapped into [0, 2π), the range on which a
//! piecewise profile such as the seed's example 3.4.3 is written.

use std::f64::consts::TAU;
use std::sync::Arc;

use camlink_expr::Expr;

use super::{CurveError, CurveJet, CurveJet4, Fourier, Spline};
use crate::math::V2;

/// Largest angle between neighbouring points of a polar spline (rad): 90°.
pub(crate) const MAX_GAP: f64 = std::f64::consts::FRAC_PI_2;

/// The radius function ρ(α) (m) of a polar profile.
#[derive(Clone, Debug)]
pub enum Radius {
    /// A circle of radius ρ about Q.
    Const(f64),
    /// An expression of `a` (the angle α), e.g.
    /// `if(a <= 2*pi/3, 5/4 - cos(3*a)/4, 1)`.
    Expr(Arc<Expr>),
    /// ρ = a₀ + Σ (aₖ cos kα + bₖ sin kα).
    Fourier(Fourier),
    /// The periodic cubic spline through measured (α_k, ρ_k).
    Spline(Spline),
}

impl Radius {
    /// `[ρ, ρ′, ρ″, ρ‴]` at α (rad).
    #[inline]
    pub fn jet(&self, alpha: f64) -> [f64; 4] {
        let a = alpha.rem_euclid(TAU);
        match self {
            Radius::Const(r) => [*r, 0.0, 0.0, 0.0],
            Radius::Expr(e) => e.jet(a),
            Radius::Fourier(f) => f.jet(a),
            Radius::Spline(s) => s.jet(a),
        }
    }

    /// `[ρ, ρ′, ρ″, ρ‴, ρ⁗]` at α (rad).
    pub fn jet4(&self, alpha: f64) -> [f64; 5] {
        let a = alpha.rem_euclid(TAU);
        match self {
            Radius::Const(r) => [*r, 0.0, 0.0, 0.0, 0.0],
            Radius::Expr(e) => e.jet4(a),
            Radius::Fourier(f) => f.jet4(a),
            Radius::Spline(s) => s.jet4(a),
        }
    }
}

/// A polar profile s′(α) = s′_Q + ρ(α) u(α) in a body frame.
#[derive(Clone, Debug)]
pub struct Polar {
    /// s′_Q: the centre Q of the profile in the body frame (m).
    pub q: V2,
    /// ρ(α) (m).
    pub rho: Radius,
}

impl Polar {
    /// A circle of radius `r` (m) about Q.
    pub fn circle(q: V2, r: f64) -> Result<Self, CurveError> {
        if !(r > 0.0 && r.is_finite()) {
            return Err(CurveError::Invalid(format!(
                "a circle's radius must be positive, got {r}"
            )));
        }
        Ok(Polar {
            q,
            rho: Radius::Const(r),
        })
    }

    /// ρ given by the expression `src` of the angle `a`.
    pub fn expr(q: V2, src: &str) -> Result<Self, CurveError> {
        let e = Expr::parse(src, "a").map_err(|e| CurveError::Expr {
            source_text: src.to_string(),
            message: e.to_string(),
        })?;
        Ok(Polar {
            q,
            rho: Radius::Expr(Arc::new(e)),
        })
    }

    /// ρ = a₀ + Σ (aₖ cos kα + bₖ sin kα).
    pub fn fourier(q: V2, a0: f64, a: &[f64], b: &[f64]) -> Result<Self, CurveError> {
        Ok(Polar {
            q,
            rho: Radius::Fourier(Fourier::new(a0, a, b)?),
        })
    }

    /// ρ the periodic spline through points (α_k, ρ_k) (rad, m), α strictly
    /// increasing over less than one turn (a last point at α₀ + 2π repeating
    /// the first is accepted).
    ///
    /// The points must go all round: a gap of more than [`MAX_GAP`] between
    /// neighbouring angles (the last to the first across 2π included) is an
    /// error, as the spline would invent the profile there.
    pub fn spline(q: V2, points: &[V2]) -> Result<Self, CurveError> {
        let mut angles: Vec<f64> = points.iter().map(|p| p[0]).collect();
        angles.sort_by(f64::total_cmp);
        if let (Some(&first), Some(&last)) = (angles.first(), angles.last()) {
            let wrap = (first + TAU - last, last, first + TAU);
            let gap = angles
                .windows(2)
                .map(|w| (w[1] - w[0], w[0], w[1]))
                .chain(std::iter::once(wrap))
                .fold(
                    (0.0, 0.0, 0.0),
                    |best, g| if g.0 > best.0 { g } else { best },
                );
            if gap.0 > MAX_GAP {
                return Err(CurveError::Invalid(format!(
                    "the points leave a gap of {}° between α = {} and {} rad; \
                     a polar profile needs points all round (gaps of at most {}°)",
                    crate::fmt_num::num(gap.0.to_degrees()),
                    crate::fmt_num::num(gap.1),
                    crate::fmt_num::num(gap.2),
                    crate::fmt_num::num(MAX_GAP.to_degrees())
                )));
            }
        }
        Ok(Polar {
            q,
            rho: Radius::Spline(Spline::periodic(points, TAU)?),
        })
    }

    /// s′, g′ = s′_α, s′_αα, s′_ααα at α (rad).
    #[inline]
    pub fn jet(&self, alpha: f64) -> CurveJet {
        let [r, r1, r2, r3] = self.rho.jet(alpha);
        let (sn, cs) = alpha.sin_cos();
        // In the basis (u, u⊥): position r u; derivatives by u′ = u⊥,
        // u⊥′ = −u.
        let at = |cu: f64, cp: f64| [cu * cs - cp * sn, cu * sn + cp * cs];
        let p = at(r, 0.0);
        CurveJet {
            p: [self.q[0] + p[0], self.q[1] + p[1]],
            d1: at(r1, r),
            d2: at(r2 - r, 2.0 * r1),
            d3: at(r3 - 3.0 * r1, 3.0 * r2 - r),
        }
    }

    /// s′ … s′_αααα at α (rad).
    pub fn jet4(&self, alpha: f64) -> CurveJet4 {
        let [r, r1, r2, r3, r4] = self.rho.jet4(alpha);
        let (sn, cs) = alpha.sin_cos();
        let at = |cu: f64, cp: f64| [cu * cs - cp * sn, cu * sn + cp * cs];
        let p = at(r, 0.0);
        CurveJet4 {
            jet: CurveJet {
                p: [self.q[0] + p[0], self.q[1] + p[1]],
                d1: at(r1, r),
                d2: at(r2 - r, 2.0 * r1),
                d3: at(r3 - 3.0 * r1, 3.0 * r2 - r),
            },
            d4: at(r4 - 6.0 * r2 + r, 4.0 * (r3 - r1)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::Curve;

    #[test]
    fn offset_circle_jet_is_closed_form() {
        let c = Polar::circle([0.3, -0.1], 0.5).unwrap();
        for &a in &[0.0, 1.0, -2.0, 9.0] {
            let j = c.jet(a);
            let (s, k) = a.sin_cos();
            let close = |u: V2, v: V2| (u[0] - v[0]).abs() < 1e-14 && (u[1] - v[1]).abs() < 1e-14;
            assert!(close(j.p, [0.3 + 0.5 * k, -0.1 + 0.5 * s]));
            assert!(close(j.d1, [-0.5 * s, 0.5 * k]));
            assert!(close(j.d2, [-0.5 * k, -0.5 * s]));
            assert!(close(j.d3, [0.5 * s, -0.5 * k]));
        }
        let c = Curve::from(c);
        assert!((c.curvature(0.7) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn jet_derivatives_match_finite_differences() {
        let c = Polar::fourier([0.1, 0.2], 1.0, &[0.2, 0.05], &[0.0, 0.1]).unwrap();
        let h = 1e-6;
        for &a in &[0.3, 2.0, 4.4, -0.7] {
            let (p, m, j) = (c.jet(a + h), c.jet(a - h), c.jet(a));
            let pairs = [(p.p, m.p, j.d1), (p.d1, m.d1, j.d2), (p.d2, m.d2, j.d3)];
            for (u, v, d) in pairs {
                for k in 0..2 {
                    let fd = (u[k] - v[k]) / (2.0 * h);
                    assert!((fd - d[k]).abs() < 1e-7, "{fd} vs {}", d[k]);
                }
            }
        }
    }

    #[test]
    fn seed_tangent_formula() {
        // g′ = ρ′ u + ρ u⊥ (seed, boundary of a convex shape (2)).
        let c = Polar::fourier([0.0, 0.0], 1.0, &[0.3], &[]).unwrap();
        let a: f64 = 0.8;
        let (rho, drho) = (1.0 + 0.3 * a.cos(), -0.3 * a.sin());
        let u = [a.cos(), a.sin()];
        let up = [-a.sin(), a.cos()];
        let g = c.jet(a).d1;
        for k in 0..2 {
            assert!((g[k] - (drho * u[k] + rho * up[k])).abs() < 1e-14);
        }
    }

    #[test]
    fn rejects_bad_radius() {
        assert!(Polar::circle([0.0, 0.0], 0.0).is_err());
        assert!(Polar::circle([0.0, 0.0], f64::NAN).is_err());
    }
}

#[cfg(test)]
mod expr_tests {
    use super::*;
    use crate::curve::{parse_points_csv, Curve};
    use std::f64::consts::PI;

    /// The seed's example 3.4.3 cam.
    const SEED_CAM: &str = "if(a <= 2*pi/3, 5/4 - cos(3*a)/4, 1)";

    #[test]
    fn seed_example_cam_from_an_expression() {
        let c = Polar::expr([0.0, 0.0], SEED_CAM).unwrap();
        for &a in &[0.5, 1.7] {
            let j = c.jet(a);
            let (rho, drho) = (1.25 - (3.0 * a).cos() / 4.0, 0.75 * (3.0 * a).sin());
            let g = [
                drho * a.cos() - rho * a.sin(),
                drho * a.sin() + rho * a.cos(),
            ];
            assert!((j.d1[0] - g[0]).abs() < 1e-14 && (j.d1[1] - g[1]).abs() < 1e-14);
        }
        // The base circle, also one turn on.
        let j = c.jet(3.0 + 2.0 * PI);
        assert!((j.p[0] - 3.0f64.cos()).abs() < 1e-14);
        // The lobe is concave near its flanks, α ∈ (0, α₁) and
        // (2π/3 − α₁, 2π/3).
        let r = Curve::from(c).concave_ranges(720);
        assert_eq!(r.len(), 2, "{r:?}");
        assert!(
            r[0].0 == 0.0 && (r[1].1 - 2.0 * PI / 3.0).abs() < 1e-9,
            "{r:?}"
        );
        assert!((r[0].1 - (2.0 * PI / 3.0 - r[1].0)).abs() < 1e-9, "{r:?}");
    }

    #[test]
    fn expression_errors_name_the_source() {
        let e = Polar::expr([0.0, 0.0], "1 + cos(b)").unwrap_err();
        assert!(e.to_string().contains("1 + cos(b)"), "{e}");
    }

    #[test]
    fn spline_profile_from_csv() {
        let mut text = String::from("alpha,rho\n");
        for k in 0..=24 {
            let a = k as f64 * 2.0 * PI / 24.0;
            text += &format!("{a},{}\n", 1.0 + 0.1 * (2.0 * a).cos());
        }
        let pts = parse_points_csv(&text, "cam.csv").unwrap();
        let c = Polar::spline([0.0, 0.0], &pts).unwrap();
        for p in &pts {
            assert!((c.rho.jet(p[0])[0] - p[1]).abs() < 1e-12);
        }
        let a: f64 = 1.234;
        assert!((c.rho.jet(a)[0] - (1.0 + 0.1 * (2.0 * a).cos())).abs() < 1e-5);
        assert!(Curve::from(c).check(360).is_ok());
    }
}
