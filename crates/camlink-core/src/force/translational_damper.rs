//! Viscous friction of a translational joint: a force −c ṡ along the
//! sliding axis, ṡ the sliding speed of body j on body i.
//!
//! The axis is u = A_i v′_i (v′_i a unit vector in body i's frame); the
//! force acts at P_j (s′_j in body j's frame) on body j and, equal and
//! opposite, at the same global point on body i, so it has no moment of its
//! own: the joint's reaction torque is not disturbed. With
//! a_j = A_j s′_j (from j's origin to P_j) and a_i = r_j + a_j − r_i (from
//! i's origin to P_j), the sliding speed is the velocity of P_j on body j
//! relative to the material point of body i under it, along u:
//!
//! ṡ = uᵀ(ṙ_j − ṙ_i) + φ̇_j (a_j × u) − φ̇_i (a_i × u) = wᵀ q̇,
//!
//! w = [w_i; w_j] = [−u; −a_i × u;  u; a_j × u] (6 entries), and the
//! generalized force is that of the Rayleigh function ½ c ṡ²:
//!
//! Q = −c ṡ w,  f = −c ṡ (N) the force on body j along u.
//!
//! Derivatives: ∂Q/∂q̇ = −c w wᵀ, ∂Q/∂q = −c (ṡ ∂w/∂q + w q̇ᵀ ∂w/∂q),
//! with ∂u/∂φ_i = u⊥, ∂a_j/∂φ_j = a_j⊥, ∂a_i/∂r_i = −I, ∂a_i/∂r_j = I,
//! ∂a_i/∂φ_j = a_j⊥ and ∂(a × u)/∂a = (u_y, −u_x). The force dissipates
//! power c ṡ² and stores no energy.

use super::{Applied, BodyJac, BodyQ, ForceError};
use crate::constraint::BodyId;
use crate::constraint::Local;
use crate::math::{cross, norm, perp, rot, scale, V2};

#[derive(Clone, Debug)]
pub struct TranslationalDamper {
    pub body_i: BodyId,
    /// v′_i: the sliding axis in body i's frame (unit vector).
    pub v_i: V2,
    pub body_j: BodyId,
    /// s′_j: the point P_j of body j where the friction acts (m).
    pub s_j: V2,
    /// c (N·s/m).
    pub damping: f64,
}

impl TranslationalDamper {
    /// A damper along `v_i` (normalized). `None` when `v_i` is zero or not
    /// finite.
    pub fn new(body_i: BodyId, v_i: V2, body_j: BodyId, s_j: V2, damping: f64) -> Option<Self> {
        let l = norm(v_i);
        (l > 0.0 && l.is_finite()).then(|| TranslationalDamper {
            body_i,
            v_i: scale(1.0 / l, v_i),
            body_j,
            s_j,
            damping,
        })
    }

    /// w (so that ṡ = wᵀq̇) and ∂w/∂q, both over (q_i, q_j).
    fn w(&self, x: &Local) -> ([f64; 6], [[f64; 6]; 6]) {
        let u = rot(x.q[0][2], self.v_i);
        let up = perp(u);
        let aj = rot(x.q[1][2], self.s_j);
        let ajp = perp(aj);
        let ai = [x.q[1][0] + aj[0] - x.q[0][0], x.q[1][1] + aj[1] - x.q[0][1]];
        let w = [-u[0], -u[1], -cross(ai, u), u[0], u[1], cross(aj, u)];
        let ut = [u[1], -u[0]];
        let mut dw = [[0.0; 6]; 6];
        // u through φ_i.
        dw[0][2] = -up[0];
        dw[1][2] = -up[1];
        dw[3][2] = up[0];
        dw[4][2] = up[1];
        // −a_i × u.
        dw[2][0] = ut[0];
        dw[2][1] = ut[1];
        dw[2][2] = -cross(ai, up);
        dw[2][3] = -ut[0];
        dw[2][4] = -ut[1];
        dw[2][5] = -cross(ajp, u);
        // a_j × u.
        dw[5][2] = cross(aj, up);
        dw[5][5] = cross(ajp, u);
        (w, dw)
    }

    /// The sliding speed ṡ (m/s).
    pub fn speed(&self, x: &Local) -> f64 {
        let (w, _) = self.w(x);
        let qd = flat(&x.qd);
        (0..6).map(|k| w[k] * qd[k]).sum()
    }
}

/// (q_i, q_j) as one 6-vector.
fn flat(v: &[[f64; 3]; 2]) -> [f64; 6] {
    [v[0][0], v[0][1], v[0][2], v[1][0], v[1][1], v[1][2]]
}

impl Applied for TranslationalDamper {
    fn kind(&self) -> &'static str {
        "translational_damper"
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn validate(&self) -> Result<(), String> {
        if !(self.damping >= 0.0 && self.damping.is_finite()) {
            return Err("damping must be ≥ 0".into());
        }
        Ok(())
    }

    fn generalized(&self, x: &Local, out: &mut BodyQ) -> Result<(), ForceError> {
        let (w, _) = self.w(x);
        let f = -self.damping * self.speed(x);
        for k in 0..6 {
            out[k / 3][k % 3] = f * w[k];
        }
        Ok(())
    }

    fn derivatives(&self, x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac) {
        let (w, dw) = self.w(x);
        let qd = flat(&x.qd);
        let sd: f64 = (0..6).map(|k| w[k] * qd[k]).sum();
        let c = self.damping;
        for col in 0..6 {
            // q̇ᵀ ∂w/∂q_col.
            let qdw: f64 = (0..6).map(|k| qd[k] * dw[k][col]).sum();
            for r in 0..6 {
                dq[r / 3][col / 3][r % 3][col % 3] = -c * (sd * dw[r][col] + w[r] * qdw);
                dqd[r / 3][col / 3][r % 3][col % 3] = -c * w[r] * w[col];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::force::check;

    fn damper() -> TranslationalDamper {
        TranslationalDamper::new(BodyId(1), [0.6, 0.8], BodyId(2), [0.3, -0.2], 4.5).unwrap()
    }

    #[test]
    fn derivatives_match_finite_differences() {
        for seed in 0..20 {
            check::derivatives(&damper(), &check::state(seed));
        }
    }

    #[test]
    fn opposes_sliding_with_no_moment_of_its_own() {
        // Body j slides at 2 m/s along the x axis of ground body i.
        let d = TranslationalDamper::new(BodyId::GROUND, [1.0, 0.0], BodyId(1), [0.0, 0.5], 3.0)
            .unwrap();
        let mut x = Local::default();
        x.q[1] = [0.4, 1.0, 0.0];
        x.qd[1] = [2.0, 0.0, 0.0];
        let mut q = BodyQ::default();
        d.generalized(&x, &mut q).unwrap();
        // F = −6 N along x at P_j, a_j = (0, 0.5) from j's origin:
        // moment a_j × F = 3 N·m.
        assert_eq!(q[1], [-6.0, 0.0, 3.0]);
        // On body i (the ground) the same force reversed at the same
        // point: the net moment about any point is zero.
        assert_eq!(q[0][0], 6.0);
        let net_moment = q[0][2] + q[1][2] + cross([0.4, 1.0], [q[1][0], q[1][1]]);
        assert!(net_moment.abs() < 1e-15, "{net_moment}");
        // Power −c ṡ².
        let p: f64 = (0..2)
            .flat_map(|b| (0..3).map(move |k| (b, k)))
            .map(|(b, k)| q[b][k] * x.qd[b][k])
            .sum();
        assert!((p + 3.0 * 4.0).abs() < 1e-12);
        // Rotating body i with j riding along slides nothing.
        let mut x = Local::default();
        x.q[0] = [0.1, 0.2, 0.7];
        x.q[1] = [0.5, -0.3, 0.7];
        x.qd[0] = [0.0, 0.0, 1.3];
        // r_j's velocity as a point of body i: ω k × (r_j − r_i).
        x.qd[1] = [1.3 * 0.5, 1.3 * 0.4, 1.3];
        assert!(damper().speed(&x).abs() < 1e-15);
    }
}
