//! Translational (prismatic) joint: P_j slides on the line through P_i along
//! v'_i (body i), and the bodies do not rotate relative to each other.
//!
//! Φ₁ = (A_i v'_i)⊥ᵀ (r_j^P − r_i^P)
//! Φ₂ = φ_j − φ_i − θ₀
//!
//! Φ₁ is the projection of d = r_j^P − r_i^P on the normal A_i v'_i⊥ to the
//! axis: the axis projection of `relative.rs` with a = i, w' = v'_i⊥, so
//! Φ₁_q = [−(A_i v'_i⊥)ᵀ  −(A_i v'_i)ᵀd − (A_i v'_i⊥)ᵀB_i s'_i |
//!         (A_i v'_i⊥)ᵀ  (A_i v'_i⊥)ᵀB_j s'_j],
//! γ₁ = (A_i v'_i⊥)ᵀd φ̇_i² + 2 φ̇_i (A_i v'_i)ᵀḋ
//!      − (A_i v'_i⊥)ᵀ(A_i s'_i φ̇_i² − A_j s'_j φ̇_j²);
//! Φ₂_q = [0 0 −1 | 0 0 1], γ₂ = 0; ν = 0;
//! η₁ = −((A_i v'_i⊥)ᵀd)⃛* by the product rule ([`motion`](crate::motion)),
//! η₂ = 0.
//!
//! v'_i is normalised when the equations are evaluated, so Φ₁ is a distance
//! in metres whatever the length of the given vector (which must not be zero).

use super::relative::{
    projection_eta, projection_gamma, projection_jac, projection_phi, projection_phi_and_jac, unit,
};
use super::sketch::{Mark, Sketch};
use super::{Equations, Jac, Local, Rows};
use crate::constraint::BodyId;
use crate::math::{perp, V2};

#[derive(Clone, Debug)]
pub struct Translational {
    pub body_i: BodyId,
    /// P_i in body i (m).
    pub s_i: V2,
    /// v'_i: the sliding axis in body i (unit vector).
    pub v_i: V2,
    pub body_j: BodyId,
    /// P_j in body j (m).
    pub s_j: V2,
    /// θ₀: the fixed relative angle φ_j − φ_i (rad).
    pub angle: f64,
}

impl Translational {
    /// θ₀ = φ_j − φ_i for bodies at `qi` and `qj` = (x, y, φ), so that an
    /// initial placement satisfies Φ₂.
    pub fn angle_from(qi: [f64; 3], qj: [f64; 3]) -> f64 {
        qj[2] - qi[2]
    }

    /// w' = v'_i⊥, the unit normal to the axis in body i.
    fn normal(&self) -> V2 {
        perp(unit(self.v_i))
    }
}

impl Equations for Translational {
    fn kind(&self) -> &'static str {
        "translational"
    }

    fn equations(&self) -> &'static [&'static str] {
        &["normal", "angle"]
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn sketch(&self) -> Sketch<'_> {
        vec![Mark::Guide {
            s_i: self.s_i,
            v_i: self.v_i,
            s_j: self.s_j,
        }]
    }

    fn joint_points(&self, _x: &Local) -> [V2; 2] {
        [self.s_i, self.s_j]
    }

    fn phi(&self, x: &Local, out: &mut Rows) {
        out[0] = projection_phi(x, 0, self.s_i, self.normal(), self.s_j);
        out[1] = x.q[1][2] - x.q[0][2] - self.angle;
        out[2] = 0.0;
    }

    fn jacobian(&self, x: &Local, out: &mut Jac) {
        let [ji, jj] = projection_jac(x, 0, self.s_i, self.normal(), self.s_j);
        jacobian_of(ji, jj, out);
    }

    /// With the axis normal, d and A_i w' evaluated once.
    fn phi_and_jacobian(&self, x: &Local, phi: &mut Rows, jac: &mut Jac) {
        let (normal, [ji, jj]) = projection_phi_and_jac(x, 0, self.s_i, self.normal(), self.s_j);
        phi[0] = normal;
        phi[1] = x.q[1][2] - x.q[0][2] - self.angle;
        phi[2] = 0.0;
        jacobian_of(ji, jj, jac);
    }

    fn nu(&self, _x: &Local, out: &mut Rows) {
        *out = [0.0; 3];
    }

    fn gamma(&self, x: &Local, out: &mut Rows) {
        out[0] = projection_gamma(x, 0, self.s_i, self.normal(), self.s_j);
        out[1] = 0.0;
        out[2] = 0.0;
    }

    fn eta(&self, x: &Local, out: &mut Rows) {
        out[0] = projection_eta(x, 0, self.s_i, self.normal(), self.s_j);
        out[1] = 0.0;
        out[2] = 0.0;
    }
}

/// Φ_q from the normal equation's blocks `ji` (body i) and `jj` (body j);
/// the angle equation's are constant.
#[inline]
fn jacobian_of(ji: [f64; 3], jj: [f64; 3], out: &mut Jac) {
    *out = Jac::default();
    out.body[0][0] = ji;
    out.body[1][0] = jj;
    out.body[0][1] = [0.0, 0.0, -1.0];
    out.body[1][1] = [0.0, 0.0, 1.0];
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::check::check_random;

    fn joint(body_i: BodyId, body_j: BodyId) -> Translational {
        Translational {
            body_i,
            s_i: [0.4, -0.2],
            v_i: [0.8, 0.3],
            body_j,
            s_j: [-0.3, 0.7],
            angle: 0.25,
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        check_random(&joint(BodyId(1), BodyId(2)), 50);
    }

    #[test]
    fn derivatives_match_with_ground() {
        check_random(&joint(BodyId::GROUND, BodyId(2)), 20);
        check_random(&joint(BodyId(1), BodyId::GROUND), 20);
    }

    #[test]
    fn slides_along_the_axis_at_fixed_relative_angle() {
        // Body i turned by 0.6 rad; body j placed on the axis, at the angle
        // given by angle_from.
        let c = Translational {
            body_i: BodyId(1),
            s_i: [0.4, -0.2],
            v_i: [2.0, 0.0],
            body_j: BodyId(2),
            s_j: [0.0, 0.0],
            angle: 0.0,
        };
        let qi = [0.5, -1.0, 0.6];
        let pi = crate::math::point(qi, c.s_i);
        let axis = crate::math::rot(qi[2], [1.0, 0.0]);
        let qj = [pi[0] + 1.3 * axis[0], pi[1] + 1.3 * axis[1], 1.9];
        let c = Translational {
            angle: Translational::angle_from(qi, qj),
            ..c
        };
        let mut x = Local {
            q: [qi, qj],
            ..Local::default()
        };
        let mut out = [0.0; 3];
        c.phi(&x, &mut out);
        assert!(out[0].abs() < 1e-12 && out[1].abs() < 1e-12);

        // Φ_q annihilates a slide of body j along the axis ...
        let mut jac = Jac::default();
        c.jacobian(&x, &mut jac);
        for r in 0..2 {
            let slide = jac.body[1][r][0] * axis[0] + jac.body[1][r][1] * axis[1];
            assert!(slide.abs() < 1e-12);
        }
        // ... but not a slide across it, nor a relative rotation.
        let across = jac.body[1][0][0] * -axis[1] + jac.body[1][0][1] * axis[0];
        assert!((across - 1.0).abs() < 1e-12);
        assert_eq!(jac.body[1][1][2], 1.0);

        // Turning body i by δ and carrying body j with it keeps Φ = 0.
        let delta = 0.7;
        let qi2 = [qi[0], qi[1], qi[2] + delta];
        let pi2 = crate::math::point(qi2, c.s_i);
        let axis2 = crate::math::rot(qi2[2], [1.0, 0.0]);
        x.q = [
            qi2,
            [
                pi2[0] - 0.4 * axis2[0],
                pi2[1] - 0.4 * axis2[1],
                qj[2] + delta,
            ],
        ];
        c.phi(&x, &mut out);
        assert!(out[0].abs() < 1e-12 && out[1].abs() < 1e-12);
    }
}
