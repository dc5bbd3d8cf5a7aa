//! Cam–follower: a curve C_i on body i touches a curve C_j on body j
//! (seed 3.4.2, Haug's Φ^cf(i,j)).
//!
//! Own coordinates α_i, α_j: the contact parameters on C_i and C_j (for a
//! polar profile the seed's angle α; for a parametric curve its length
//! parameter). With p_k(α_k) the curve point in body k's frame and
//! g′_k = dp_k/dα_k its tangent there (for a polar profile
//! p = s′_Q + ρ u′, g′ = ρ′ u′ + ρ u′⊥), g_k = A_k g′_k, and
//! A_ij = A_iᵀ A_j, B_ij = A_iᵀ B_j:
//!
//! Φ = [ r_i + A_i p_i − r_j − A_j p_j       (2 equations, m)
//!       g_i⊥ᵀ g_j = −g′_iᵀ B_ij g′_j ]      (tangents collinear)
//!
//! Φ_q, by blocks (q_k = (r_k, φ_k)):
//! - rows 1–2: q_i [I  B_i p_i], α_i A_i g′_i, q_j [−I  −B_j p_j],
//!   α_j −A_j g′_j;
//! - row 3: φ_i −g′_iᵀ A_ij g′_j, α_i −(g′_i)_αᵢᵀ B_ij g′_j,
//!   φ_j g′_iᵀ A_ij g′_j, α_j −g′_iᵀ B_ij (g′_j)_αⱼ.
//!
//! The seed's errata slide for page 80 prints the φ_j entry of row 3 as
//! g′_iᵀ A_ij g′_i; the finite-difference tests confirm g′_iᵀ A_ij g′_j
//! (above). Its α_i entry needs the derivative (g′_i)_αᵢ, as the α_j entry
//! has.
//!
//! ν = 0.
//!
//! γ = −[ r̈_i^P* − r̈_j^P* ;
//!        g̈_i*⊥ᵀ g_j + 2 ġ_i⊥ᵀ ġ_j + g_i⊥ᵀ g̈_j* ],
//! where * marks the velocity-quadratic part of a second derivative
//! ([`Carried`]): r̈^P* = A(−p φ̇² + 2 p′⊥ φ̇ α̇ + p″ α̇²),
//! g̈* = A(−p′ φ̇² + 2 p″⊥ φ̇ α̇ + p‴ α̇²).
//!
//! η = −[ r⃛_i^P* − r⃛_j^P* ; (g_i × g_j)⃛* ], the starred third derivatives
//! taken with the jerks set to zero ([`carried_paths`], which needs p⁗ for
//! g⃛*), the cross product's by Leibniz's rule.

use super::sketch::{CurveRole, Mark, Side, Sketch};
use super::{Equations, Feature, Jac, Local, Rows, MAX_OWN};
use crate::constraint::BodyId;
use crate::curve::{carried_paths, search, Carried, Curve};
use crate::math::{cross, V2};
use crate::motion;
use crate::quantity::Quantity;

#[derive(Clone, Debug)]
pub struct CamFollower {
    pub body_i: BodyId,
    /// C_i in body i's frame.
    pub curve_i: Curve,
    pub body_j: BodyId,
    /// C_j in body j's frame.
    pub curve_j: Curve,
}

impl CamFollower {
    /// The carried contact points on C_i and C_j.
    #[inline]
    fn carried(&self, x: &Local) -> (Carried, Carried) {
        let ji = self.curve_i.jet(x.own[0]);
        let jj = self.curve_j.jet(x.own[1]);
        (
            Carried::new(x.q[0], x.qd[0], &ji, x.own_d[0]),
            Carried::new(x.q[1], x.qd[1], &jj, x.own_d[1]),
        )
    }
}

impl Equations for CamFollower {
    fn kind(&self) -> &'static str {
        "cam-follower"
    }

    fn equations(&self) -> &'static [&'static str] {
        &["x", "y", "tangent"]
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn contact_sides(&self) -> Option<[Feature<'_>; 2]> {
        Some([Feature::Curve(&self.curve_i), Feature::Curve(&self.curve_j)])
    }

    fn sketch(&self) -> Sketch<'_> {
        vec![
            Mark::Curve {
                side: Side::I,
                curve: &self.curve_i,
                role: CurveRole::Cam,
            },
            Mark::Curve {
                side: Side::J,
                curve: &self.curve_j,
                role: CurveRole::Roller,
            },
        ]
    }

    fn joint_points(&self, x: &Local) -> [V2; 2] {
        [self.curve_i.jet(x.own[0]).p, self.curve_j.jet(x.own[1]).p]
    }

    fn own_count(&self) -> usize {
        2
    }

    fn own_names(&self) -> &'static [&'static str] {
        &["alpha_i", "alpha_j"]
    }

    fn own_quantity(&self, k: usize) -> Quantity {
        [&self.curve_i, &self.curve_j][k.min(1)].parameter_quantity()
    }

    /// The contact pair from [`search::contact_pair`]: refined from the
    /// guess when there is one, else searched from samples.
    fn initial_own(&self, x: &Local, guess: Option<[f64; MAX_OWN]>) -> [f64; MAX_OWN] {
        search::contact_pair(&self.curve_i, x.q[0], &self.curve_j, x.q[1], guess)
    }

    fn phi(&self, x: &Local, out: &mut Rows) {
        let (a, b) = self.carried(x);
        out[0] = a.p[0] - b.p[0];
        out[1] = a.p[1] - b.p[1];
        out[2] = cross(a.g, b.g);
    }

    fn jacobian(&self, x: &Local, out: &mut Jac) {
        let (a, b) = self.carried(x);
        *out = Jac::default();
        // Contact point.
        for r in 0..2 {
            out.body[0][r][r] = 1.0;
            out.body[0][r][2] = a.p_phi[r];
            out.own[r][0] = a.g[r];
            out.body[1][r][r] = -1.0;
            out.body[1][r][2] = -b.p_phi[r];
            out.own[r][1] = -b.g[r];
        }
        // Tangents: ∂(g_i × g_j) through g_i and g_j.
        out.body[0][2][2] = cross(a.g_phi, b.g);
        out.own[2][0] = cross(a.g_s, b.g);
        out.body[1][2][2] = cross(a.g, b.g_phi);
        out.own[2][1] = cross(a.g, b.g_s);
    }

    fn nu(&self, _x: &Local, out: &mut Rows) {
        *out = [0.0; 3];
    }

    fn gamma(&self, x: &Local, out: &mut Rows) {
        let (a, b) = self.carried(x);
        out[0] = b.p_quad[0] - a.p_quad[0];
        out[1] = b.p_quad[1] - a.p_quad[1];
        out[2] = -(cross(a.g_quad, b.g) + 2.0 * cross(a.gd, b.gd) + cross(a.g, b.g_quad));
    }

    fn eta(&self, x: &Local, out: &mut Rows) {
        let ji = self.curve_i.jet4(x.own[0]);
        let jj = self.curve_j.jet4(x.own[1]);
        let (pi, gi) = carried_paths(x.q[0], x.qd[0], x.qdd[0], &ji, x.own_path(0));
        let (pj, gj) = carried_paths(x.q[1], x.qd[1], x.qdd[1], &jj, x.own_path(1));
        let d = motion::sub(&pi, &pj);
        *out = [-d[3][0], -d[3][1], -motion::cross(&gi, &gj)[3]];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::check::check_random_own;
    use crate::curve::{Parametric, Polar};
    use crate::math::{dot, norm, point, sub};
    use std::f64::consts::{PI, TAU};

    fn cam() -> Curve {
        Polar::fourier([0.1, -0.05], 1.0, &[0.2, 0.0, 0.05], &[0.1])
            .unwrap()
            .into()
    }

    #[test]
    fn derivatives_match_finite_differences_polar_on_polar() {
        let c = CamFollower {
            body_i: BodyId(1),
            curve_i: cam(),
            body_j: BodyId(2),
            curve_j: Polar::circle([0.3, 0.0], 0.25).unwrap().into(),
        };
        check_random_own(&c, 40, [(-TAU, 2.0 * TAU); MAX_OWN]);
    }

    #[test]
    fn derivatives_match_finite_differences_parametric_open_and_closed() {
        let slot = Parametric::spline(
            &[[0.0, 0.0], [0.4, 0.2], [0.9, 0.1], [1.3, 0.5], [1.6, 0.4]],
            false,
        )
        .unwrap();
        let (_, len) = slot.range();
        let c = CamFollower {
            body_i: BodyId(1),
            curve_i: Parametric::spline(&[[1.0, 0.0], [0.0, 0.8], [-1.1, 0.1], [0.1, -0.9]], true)
                .unwrap()
                .into(),
            body_j: BodyId(2),
            curve_j: slot.into(),
        };
        check_random_own(&c, 40, [(-3.0, 9.0), (0.05 * len, 0.95 * len)]);
        let c = CamFollower {
            body_i: BodyId::GROUND,
            curve_i: Parametric::arc([0.0, 0.0], 1.5, 0.2, 2.0).unwrap().into(),
            body_j: BodyId(1),
            curve_j: cam(),
        };
        check_random_own(&c, 30, [(0.1, 2.6), (-PI, PI)]);
    }

    #[test]
    fn circular_cam_and_roller_keep_centre_distance_r_plus_r() {
        // Ground cam R = 1 about Q = (0.3, 0.2); roller r = 0.25 about the
        // origin of body 1, whose height y and angle φ are held. Solving
        // Φ = 0 for (x, α_i, α_j) must give |C_roller − Q| = R + r, as a
        // distance constraint would.
        let c = CamFollower {
            body_i: BodyId::GROUND,
            curve_i: Polar::circle([0.3, 0.2], 1.0).unwrap().into(),
            body_j: BodyId(1),
            curve_j: Polar::circle([0.0, 0.0], 0.25).unwrap().into(),
        };
        let (y, phi) = (0.9, 0.7);
        let mut x = Local::default();
        x.q[1] = [1.5, y, phi];
        x.own = c.initial_own(&x, None);
        for _ in 0..30 {
            let (mut f, mut jac) = ([0.0; 3], Jac::default());
            c.phi(&x, &mut f);
            c.jacobian(&x, &mut jac);
            // Unknowns (x_j, α_i, α_j).
            let m = [0, 1, 2].map(|r| [jac.body[1][r][0], jac.own[r][0], jac.own[r][1]]);
            let d = solve3(m, f);
            x.q[1][0] -= d[0];
            x.own[0] -= d[1];
            x.own[1] -= d[2];
        }
        let mut f = [0.0; 3];
        c.phi(&x, &mut f);
        assert!(f.iter().all(|v| v.abs() < 1e-12), "{f:?}");
        let dist = norm(sub([x.q[1][0], y], [0.3, 0.2]));
        assert!((dist - 1.25).abs() < 1e-12, "{dist}");
        let want_x = 0.3 + (1.25f64.powi(2) - (y - 0.2).powi(2)).sqrt();
        assert!((x.q[1][0] - want_x).abs() < 1e-12);
    }

    #[test]
    fn initial_own_puts_the_contact_on_the_centre_line() {
        let c = CamFollower {
            body_i: BodyId(1),
            curve_i: Polar::circle([0.0, 0.0], 1.0).unwrap().into(),
            body_j: BodyId(2),
            curve_j: Parametric::circle([0.0, 0.0], 0.5, 0.0).unwrap().into(),
        };
        let mut x = Local::default();
        x.q[0] = [0.0, 0.0, 0.5];
        x.q[1] = [0.0, 1.5, 0.0];
        let own = c.initial_own(&x, None);
        // Contact at global (0, 1): α_i = π/2 − 0.5; on the roller, angle
        // −π/2 from its centre, arc length 0.5·3π/2.
        assert!((own[0] - (PI / 2.0 - 0.5)).abs() < 1e-9, "{own:?}");
        assert!((own[1] - 0.75 * PI).abs() < 1e-9, "{own:?}");
        let mut f = [0.0; 3];
        c.phi(&Local { own, ..x }, &mut f);
        assert!(f.iter().all(|v| v.abs() < 1e-9));
        // A guess is refined, not replaced.
        let own2 = c.initial_own(&x, Some([PI / 2.0 - 0.5 + TAU + 0.1, 0.75 * PI - 0.05]));
        assert!((own2[0] - (PI / 2.0 - 0.5 + TAU)).abs() < 1e-9, "{own2:?}");
        let n = [0.0, 1.0];
        let a = point(x.q[0], c.curve_i.jet(own2[0]).p);
        assert!((dot(a, n) - 1.0).abs() < 1e-9);
    }

    /// Solves the 3×3 system m d = f by Cramer's rule.
    pub(crate) fn solve3(m: [[f64; 3]; 3], f: [f64; 3]) -> [f64; 3] {
        let det = |a: [[f64; 3]; 3]| {
            a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
                - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
                + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
        };
        let d = det(m);
        [0, 1, 2].map(|c| {
            let mut a = m;
            for r in 0..3 {
                a[r][c] = f[r];
            }
            det(a) / d
        })
    }
}

#[cfg(test)]
mod expr_tests {
    use super::*;
    use crate::constraint::check::check_random_own;
    use crate::curve::{Parametric, Polar};

    #[test]
    fn derivatives_match_finite_differences_seed_example() {
        // Example 3.4.3: the lobed cam ρ₁ and a roller ρ₂ = 1/4; α₁ kept
        // inside the lobe, away from the curvature jumps at 0 and 2π/3.
        let c = CamFollower {
            body_i: BodyId(1),
            curve_i: Polar::expr([0.0, 0.0], "if(a <= 2*pi/3, 5/4 - cos(3*a)/4, 1)")
                .unwrap()
                .into(),
            body_j: BodyId(2),
            curve_j: Polar::circle([0.0, 0.0], 0.25).unwrap().into(),
        };
        check_random_own(&c, 30, [(0.05, 2.0), (-6.0, 6.0)]);
        let c = CamFollower {
            curve_j: Parametric::expr("0.3*cos(s)", "0.2*sin(s) + 0.1*s", -1.0, 2.0, false)
                .unwrap()
                .into(),
            ..c
        };
        check_random_own(&c, 30, [(0.05, 2.0), (-0.9, 1.9)]);
    }
}
