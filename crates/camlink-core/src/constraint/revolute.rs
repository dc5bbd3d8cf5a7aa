//! Revolute joint: point P of body i coincides with point P of body j.
//!
//! Φ = r_i + A_i s'_i − r_j − A_j s'_j (2 equations, m)
//! Φ_q = [I  B_i s'_i | −I  −B_j s'_j]
//! ν = 0
//! γ = A_i s'_i φ̇_i² − A_j s'_j φ̇_j²
//! η = −(r⃛_i^P* − r⃛_j^P*), r⃛^P* = −3 A s' φ̇ φ̈ − B s' φ̇³ (see [`motion`](crate::motion))
//! (Φ_qᵀλ)_q: −λᵀA_i s'_i at (φ_i, φ_i), λᵀA_j s'_j at (φ_j, φ_j)

use super::sketch::{Mark, Sketch};
use super::{CoordMask, Equations, Jac, Local, LocalBlock, Rows, MAX_ROWS};
use crate::constraint::BodyId;
use crate::math::{perp, point, rot, rot_d, V2};
use crate::motion;

#[derive(Clone, Debug)]
pub struct Revolute {
    pub body_i: BodyId,
    /// s'_i: the joint point in body i's frame (m).
    pub s_i: V2,
    pub body_j: BodyId,
    /// s'_j: the joint point in body j's frame (m).
    pub s_j: V2,
}

impl Equations for Revolute {
    fn kind(&self) -> &'static str {
        "revolute"
    }

    fn equations(&self) -> &'static [&'static str] {
        &["x", "y"]
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn sketch(&self) -> Sketch<'_> {
        vec![Mark::Pin {
            s_i: self.s_i,
            s_j: self.s_j,
        }]
    }

    fn joint_points(&self, _x: &Local) -> [V2; 2] {
        [self.s_i, self.s_j]
    }

    /// φ_i and φ_j only.
    fn nonlinear(&self) -> CoordMask {
        1 << 2 | 1 << 5
    }

    /// x: x_i, φ_i, x_j, φ_j; y: y_i, φ_i, y_j, φ_j.
    fn jacobian_pattern(&self) -> [CoordMask; MAX_ROWS] {
        [0b10_1101, 0b11_0110, 0]
    }

    /// ∂²Φ/∂φ_i² = −A_i s'_i and ∂²Φ/∂φ_j² = A_j s'_j; nothing else.
    fn curvature(&self, x: &Local, lambda: &Rows, out: &mut LocalBlock) -> bool {
        let ai = rot(x.q[0][2], self.s_i);
        let aj = rot(x.q[1][2], self.s_j);
        out[2][2] = -(lambda[0] * ai[0] + lambda[1] * ai[1]);
        out[5][5] = lambda[0] * aj[0] + lambda[1] * aj[1];
        true
    }

    fn phi(&self, x: &Local, out: &mut Rows) {
        let pi = point(x.q[0], self.s_i);
        let pj = point(x.q[1], self.s_j);
        out[0] = pi[0] - pj[0];
        out[1] = pi[1] - pj[1];
    }

    fn jacobian(&self, x: &Local, out: &mut Jac) {
        let bi = rot_d(x.q[0][2], self.s_i);
        let bj = rot_d(x.q[1][2], self.s_j);
        jacobian_of(bi, bj, out);
    }

    /// With A_i s'_i and A_j s'_j evaluated once: B s' = (A s')⊥.
    fn phi_and_jacobian(&self, x: &Local, phi: &mut Rows, jac: &mut Jac) {
        let ai = rot(x.q[0][2], self.s_i);
        let aj = rot(x.q[1][2], self.s_j);
        let (qi, qj) = (x.q[0], x.q[1]);
        phi[0] = (qi[0] + ai[0]) - (qj[0] + aj[0]);
        phi[1] = (qi[1] + ai[1]) - (qj[1] + aj[1]);
        jacobian_of(perp(ai), perp(aj), jac);
    }

    fn nu(&self, _x: &Local, out: &mut Rows) {
        *out = [0.0; 3];
    }

    fn gamma(&self, x: &Local, out: &mut Rows) {
        let (wi, wj) = (x.qd[0][2], x.qd[1][2]);
        let ai = rot(x.q[0][2], self.s_i);
        let aj = rot(x.q[1][2], self.s_j);
        out[0] = ai[0] * wi * wi - aj[0] * wj * wj;
        out[1] = ai[1] * wi * wi - aj[1] * wj * wj;
        out[2] = 0.0;
    }

    fn eta(&self, x: &Local, out: &mut Rows) {
        let d = motion::sub(&x.point_path(0, self.s_i), &x.point_path(1, self.s_j));
        *out = [-d[3][0], -d[3][1], 0.0];
    }
}

/// Φ_q = [I  B_i s'_i | −I  −B_j s'_j] from `bi` = B_i s'_i and `bj` =
/// B_j s'_j.
#[inline]
fn jacobian_of(bi: V2, bj: V2, out: &mut Jac) {
    *out = Jac::default();
    out.body[0][0] = [1.0, 0.0, bi[0]];
    out.body[0][1] = [0.0, 1.0, bi[1]];
    out.body[1][0] = [-1.0, 0.0, -bj[0]];
    out.body[1][1] = [0.0, -1.0, -bj[1]];
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::check::check_random;

    #[test]
    fn derivatives_match_finite_differences() {
        let c = Revolute {
            body_i: BodyId(1),
            s_i: [0.4, -0.2],
            body_j: BodyId(2),
            s_j: [-0.3, 0.7],
        };
        check_random(&c, 50);
    }

    #[test]
    fn derivatives_match_with_ground() {
        let c = Revolute {
            body_i: BodyId(1),
            s_i: [1.0, 0.0],
            body_j: BodyId::GROUND,
            s_j: [0.5, 0.5],
        };
        check_random(&c, 20);
    }
}
