//! Composite joints that replace a massless link.
//!
//! Revolute–revolute (coupler of length L between P_i and P_j):
//! Φ = dᵀd − L², d = r_j^P − r_i^P;
//! Φ_q = 2dᵀ[−I  −B_i s'_i | I  B_j s'_j], ν = 0,
//! γ = −2ḋᵀḋ + 2dᵀ(A_j s'_j φ̇_j² − A_i s'_i φ̇_i²),
//! η = −(dᵀd)⃛* = −2dᵀd⃛* − 6ḋᵀd̈ ([`motion`](crate::motion)).
//!
//! Revolute–translational (pin P_i of body i runs on the line through Q_j
//! along v'_j of body j, at a signed offset c to the left of v_j):
//! Φ = (A_j v'_j)⊥ᵀ (r_i^P − r_j^Q) − c;
//! the axis projection of `relative.rs` with a = j, b = i, w' = v'_j⊥ gives
//! Φ_q, γ and η; ν = 0. v'_j is normalised when the equation is evaluated, so
//! c is in metres whatever the length of the given vector (which must not be
//! zero).

use super::relative::{
    projection_eta, projection_gamma, projection_jac, projection_phi, rel, rel_centripetal,
    rel_path, rel_vel, unit,
};
use super::sketch::{Mark, Side, Sketch};
use super::{Equations, Jac, Local, Rows};
use crate::constraint::BodyId;
use crate::math::{dot, perp, rot_d, V2};
use crate::motion;

#[derive(Clone, Debug)]
pub struct RevoluteRevolute {
    pub body_i: BodyId,
    pub s_i: V2,
    pub body_j: BodyId,
    pub s_j: V2,
    /// L (m).
    pub length: f64,
}

#[derive(Clone, Debug)]
pub struct RevoluteTranslational {
    /// Body carrying the pin P_i.
    pub body_i: BodyId,
    pub s_i: V2,
    /// Body carrying the line.
    pub body_j: BodyId,
    /// Q_j, a point of the line (m).
    pub s_j: V2,
    /// v'_j, the line direction (unit vector).
    pub v_j: V2,
    /// c, the signed offset of the pin from the line (m).
    pub offset: f64,
}

impl Equations for RevoluteRevolute {
    fn kind(&self) -> &'static str {
        "revolute_revolute"
    }

    fn equations(&self) -> &'static [&'static str] {
        &["distance"]
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn sketch(&self) -> Sketch<'_> {
        vec![Mark::Rod {
            s_i: self.s_i,
            s_j: self.s_j,
        }]
    }

    fn joint_points(&self, _x: &Local) -> [V2; 2] {
        [self.s_i, self.s_j]
    }

    fn phi(&self, x: &Local, out: &mut Rows) {
        let d = rel(x, self.s_i, self.s_j);
        *out = [dot(d, d) - self.length * self.length, 0.0, 0.0];
    }

    fn jacobian(&self, x: &Local, out: &mut Jac) {
        let d = rel(x, self.s_i, self.s_j);
        let bi = rot_d(x.q[0][2], self.s_i);
        let bj = rot_d(x.q[1][2], self.s_j);
        *out = Jac::default();
        out.body[0][0] = [-2.0 * d[0], -2.0 * d[1], -2.0 * dot(d, bi)];
        out.body[1][0] = [2.0 * d[0], 2.0 * d[1], 2.0 * dot(d, bj)];
    }

    fn nu(&self, _x: &Local, out: &mut Rows) {
        *out = [0.0; 3];
    }

    fn gamma(&self, x: &Local, out: &mut Rows) {
        let d = rel(x, self.s_i, self.s_j);
        let d_d = rel_vel(x, self.s_i, self.s_j);
        let a = rel_centripetal(x, self.s_i, self.s_j);
        *out = [-2.0 * dot(d_d, d_d) + 2.0 * dot(d, a), 0.0, 0.0];
    }

    fn eta(&self, x: &Local, out: &mut Rows) {
        let d = rel_path(x, self.s_i, self.s_j);
        *out = [-motion::dot(&d, &d)[3], 0.0, 0.0];
    }
}

impl RevoluteTranslational {
    /// w' = v'_j⊥, the unit normal to the line in body j.
    fn normal(&self) -> V2 {
        perp(unit(self.v_j))
    }
}

impl Equations for RevoluteTranslational {
    fn kind(&self) -> &'static str {
        "revolute_translational"
    }

    fn equations(&self) -> &'static [&'static str] {
        &["normal"]
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn sketch(&self) -> Sketch<'_> {
        vec![
            Mark::Slider {
                side: Side::I,
                s: self.s_i,
            },
            Mark::Face {
                side: Side::J,
                s: self.s_j,
                u: self.v_j,
            },
        ]
    }

    fn joint_points(&self, x: &Local) -> [V2; 2] {
        [self.s_i, x.on_j(self.s_i)]
    }

    fn phi(&self, x: &Local, out: &mut Rows) {
        let n = projection_phi(x, 1, self.s_j, self.normal(), self.s_i);
        *out = [n - self.offset, 0.0, 0.0];
    }

    fn jacobian(&self, x: &Local, out: &mut Jac) {
        *out = Jac::default();
        let [ji, jj] = projection_jac(x, 1, self.s_j, self.normal(), self.s_i);
        out.body[0][0] = ji;
        out.body[1][0] = jj;
    }

    fn nu(&self, _x: &Local, out: &mut Rows) {
        *out = [0.0; 3];
    }

    fn gamma(&self, x: &Local, out: &mut Rows) {
        let g = projection_gamma(x, 1, self.s_j, self.normal(), self.s_i);
        *out = [g, 0.0, 0.0];
    }

    fn eta(&self, x: &Local, out: &mut Rows) {
        let e = projection_eta(x, 1, self.s_j, self.normal(), self.s_i);
        *out = [e, 0.0, 0.0];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::check::check_random;

    fn rr(body_i: BodyId, body_j: BodyId) -> RevoluteRevolute {
        RevoluteRevolute {
            body_i,
            s_i: [0.4, -0.2],
            body_j,
            s_j: [-0.3, 0.7],
            length: 1.3,
        }
    }

    fn rt(body_i: BodyId, body_j: BodyId) -> RevoluteTranslational {
        RevoluteTranslational {
            body_i,
            s_i: [0.4, -0.2],
            body_j,
            s_j: [-0.3, 0.7],
            v_j: [0.5, -1.2],
            offset: 0.15,
        }
    }

    #[test]
    fn revolute_revolute_matches_finite_differences() {
        check_random(&rr(BodyId(1), BodyId(2)), 40);
        check_random(&rr(BodyId::GROUND, BodyId(2)), 20);
        check_random(&rr(BodyId(1), BodyId::GROUND), 20);
    }

    #[test]
    fn revolute_translational_matches_finite_differences() {
        check_random(&rt(BodyId(1), BodyId(2)), 40);
        check_random(&rt(BodyId::GROUND, BodyId(2)), 20);
        check_random(&rt(BodyId(1), BodyId::GROUND), 20);
    }

    #[test]
    fn coupler_residual_is_distance_squared_minus_length_squared() {
        // P_i = (1, 1) + A(π/2)(0.4, −0.2) = (1.2, 1.4);
        // P_j = (4, 5) + (−0.3, 0.7) = (3.7, 5.7); d = (2.5, 4.3).
        let x = Local {
            q: [[1.0, 1.0, std::f64::consts::FRAC_PI_2], [4.0, 5.0, 0.0]],
            ..Local::default()
        };
        let mut out = [0.0; 3];
        rr(BodyId(1), BodyId(2)).phi(&x, &mut out);
        let want = 2.5 * 2.5 + 4.3 * 4.3 - 1.3 * 1.3;
        assert!((out[0] - want).abs() < 1e-12, "{} vs {want}", out[0]);
    }

    #[test]
    fn pin_offset_is_measured_to_the_left_of_the_line() {
        // Line through the ground origin along +x; the pin of body i at
        // (2, 0.15) is 0.15 to the left (above) of the line: Φ = 0.
        let c = RevoluteTranslational {
            body_i: BodyId(1),
            s_i: [0.0, 0.0],
            body_j: BodyId::GROUND,
            s_j: [0.0, 0.0],
            v_j: [3.0, 0.0],
            offset: 0.15,
        };
        let mut x = Local {
            q: [[2.0, 0.15, 1.0], [0.0; 3]],
            ..Local::default()
        };
        let mut out = [0.0; 3];
        c.phi(&x, &mut out);
        assert!(out[0].abs() < 1e-12);
        // Below the line by the same amount: Φ = −2c.
        x.q[0][1] = -0.15;
        c.phi(&x, &mut out);
        assert!((out[0] + 0.3).abs() < 1e-12);
    }
}
