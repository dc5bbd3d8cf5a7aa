//! Translational spring–damper–actuator (TSDA) between point P_i of body i
//! and point P_j of body j (Haug §6.3.2).
//!
//! With d = r_j^P − r_i^P (global, m), l = |d|, u = d / l and
//! l̇ = uᵀḋ (m/s), the tension is
//!
//! f = k (l − l₀) + c l̇ + f_a(t)  (N, positive when it pulls P_i and P_j together),
//!
//! k the stiffness (N/m), l₀ the free length (m), c the damping (N·s/m) and
//! f_a the actuator force. The force on body i at P_i is F_i = f u, on body j
//! at P_j it is F_j = −f u, so with G_k = [I  B_k s'_k] (2 × 3, ∂r_k^P/∂q_k):
//!
//! Q_i = G_iᵀ f u,  Q_j = −G_jᵀ f u.
//!
//! Derivatives, with σ_i = −1, σ_j = +1 (∂d/∂q_b = σ_b G_b) and
//! P = I − u uᵀ:
//! - ∂(f u)/∂d = H = (f/l) P + k u uᵀ + (c/l) u ḋᵀP,
//!   ∂(f u)/∂ḋ = c u uᵀ;
//! - ḋ depends on φ_b through ∂ḋ/∂φ_b = −σ_b A_b s'_b φ̇_b;
//! - ∂Q_a/∂q_b = −σ_a G_aᵀ [H σ_b G_b + c u uᵀ ∂ḋ/∂q_b]
//!   + δ_ab e_φ e_φᵀ (−(A_a s'_a)ᵀ F_a), the last from ∂(B s')/∂φ = −A s';
//! - ∂Q_a/∂q̇_b = −σ_a σ_b c G_aᵀ u uᵀ G_b.
//!
//! Potential V = ½ k (l − l₀)²; the damper and actuator are not conservative.
//! At l = 0 the direction u is undefined and the force is taken as zero.

use super::{Applied, BodyJac, BodyQ, ForceError};
use crate::constraint::BodyId;
use crate::constraint::Local;
use crate::function::TimeFn;
use crate::math::{dot, norm, point, point_vel, rot, rot_d, scale, sub, V2};

#[derive(Clone, Debug)]
pub struct Tsda {
    pub body_i: BodyId,
    /// s'_i: P_i in body i's frame (m).
    pub s_i: V2,
    pub body_j: BodyId,
    /// s'_j: P_j in body j's frame (m).
    pub s_j: V2,
    /// k (N/m).
    pub stiffness: f64,
    /// l₀ (m).
    pub free_length: f64,
    /// c (N·s/m).
    pub damping: f64,
    /// f_a(t) (N), tension positive.
    pub actuator: TimeFn,
}

/// Lengths below this (m) leave the direction undefined.
const TINY: f64 = 1e-12;

impl Tsda {
    /// (d, ḋ, l, l̇) at the local state.
    pub fn geometry(&self, x: &Local) -> (V2, V2, f64, f64) {
        let d = sub(point(x.q[1], self.s_j), point(x.q[0], self.s_i));
        let dd = sub(
            point_vel(x.q[1], x.qd[1], self.s_j),
            point_vel(x.q[0], x.qd[0], self.s_i),
        );
        let l = norm(d);
        let ld = if l > TINY { dot(d, dd) / l } else { 0.0 };
        (d, dd, l, ld)
    }

    /// The tension f (N).
    pub fn tension(&self, x: &Local) -> f64 {
        let (_, _, l, ld) = self.geometry(x);
        self.stiffness * (l - self.free_length) + self.damping * ld + self.actuator.value(x.t)
    }

    fn s(&self, k: usize) -> V2 {
        [self.s_i, self.s_j][k]
    }
}

impl Applied for Tsda {
    fn kind(&self) -> &'static str {
        "tsda"
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn validate(&self) -> Result<(), String> {
        if !(self.stiffness >= 0.0 && self.damping >= 0.0 && self.free_length >= 0.0) {
            return Err("stiffness, damping and free length must be ≥ 0".into());
        }
        Ok(())
    }

    fn generalized(&self, x: &Local, out: &mut BodyQ) -> Result<(), ForceError> {
        let (d, _, l, _) = self.geometry(x);
        *out = BodyQ::default();
        if l <= TINY {
            return Ok(());
        }
        let fu = scale(self.tension(x) / l, d);
        for (k, sign) in [(0, 1.0), (1, -1.0)] {
            let b = rot_d(x.q[k][2], self.s(k));
            let f = scale(sign, fu);
            out[k] = [f[0], f[1], dot(b, f)];
        }
        Ok(())
    }

    fn derivatives(&self, x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac) {
        *dq = BodyJac::default();
        *dqd = BodyJac::default();
        let (d, dd, l, _) = self.geometry(x);
        if l <= TINY {
            return;
        }
        let f = self.tension(x);
        let (k, c) = (self.stiffness, self.damping);
        let u = scale(1.0 / l, d);
        // P = I − u uᵀ, H = (f/l) P + k u uᵀ + (c/l) u (P ḋ)ᵀ.
        let p = |r: usize, s: usize| (r == s) as u8 as f64 - u[r] * u[s];
        let pdd = [
            p(0, 0) * dd[0] + p(0, 1) * dd[1],
            p(1, 0) * dd[0] + p(1, 1) * dd[1],
        ];
        let h = |r: usize, s: usize| f / l * p(r, s) + k * u[r] * u[s] + c / l * u[r] * pdd[s];
        let sigma = [-1.0, 1.0];
        // G_b = [I  B_b s'_b] as columns (x, y, φ), each a 2-vector.
        let g = |b: usize| -> [V2; 3] { [[1.0, 0.0], [0.0, 1.0], rot_d(x.q[b][2], self.s(b))] };
        for b in 0..2 {
            let gb = g(b);
            // ∂(f u)/∂q_b and ∂(f u)/∂q̇_b, column by column.
            let mut dfu = [[0.0; 2]; 3];
            let mut dfu_v = [[0.0; 2]; 3];
            for col in 0..3 {
                for r in 0..2 {
                    let hg = h(r, 0) * gb[col][0] + h(r, 1) * gb[col][1];
                    let uug = u[r] * dot(u, gb[col]);
                    dfu[col][r] = sigma[b] * hg;
                    dfu_v[col][r] = c * sigma[b] * uug;
                }
            }
            // ḋ's dependence on φ_b.
            let ddot_phi = scale(-sigma[b] * x.qd[b][2], rot(x.q[b][2], self.s(b)));
            for r in 0..2 {
                dfu[2][r] += c * u[r] * dot(u, ddot_phi);
            }
            for a in 0..2 {
                let ga = g(a);
                for col in 0..3 {
                    for row in 0..3 {
                        dq[a][b][row][col] = -sigma[a] * dot(ga[row], dfu[col]);
                        dqd[a][b][row][col] = -sigma[a] * dot(ga[row], dfu_v[col]);
                    }
                }
            }
        }
        // ∂(B s')ᵀF/∂φ = −(A s')ᵀF on each body's own φ.
        for a in 0..2 {
            let fa = scale(-sigma[a] * f / l, d);
            dq[a][a][2][2] -= dot(rot(x.q[a][2], self.s(a)), fa);
        }
    }

    fn potential(&self, x: &Local) -> f64 {
        let (_, _, l, _) = self.geometry(x);
        0.5 * self.stiffness * (l - self.free_length).powi(2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::force::check;

    fn spring(c: f64) -> Tsda {
        Tsda {
            body_i: BodyId(1),
            s_i: [0.2, 0.1],
            body_j: BodyId(2),
            s_j: [-0.3, 0.4],
            stiffness: 150.0,
            free_length: 0.4,
            damping: c,
            actuator: TimeFn::Linear {
                value: 3.0,
                rate: -1.0,
            },
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        for seed in 0..20 {
            check::derivatives(&spring(7.0), &check::state(seed));
        }
    }

    #[test]
    fn spring_force_is_minus_the_potential_gradient() {
        let s = Tsda {
            actuator: TimeFn::Const(0.0),
            ..spring(0.0)
        };
        for seed in 0..10 {
            check::potential(&s, &check::state(seed));
        }
    }

    #[test]
    fn a_stretched_spring_pulls_the_points_together() {
        let s = Tsda {
            body_i: BodyId(1),
            s_i: [0.0, 0.0],
            body_j: BodyId(2),
            s_j: [0.0, 0.0],
            stiffness: 10.0,
            free_length: 1.0,
            damping: 0.0,
            actuator: TimeFn::Const(0.0),
        };
        let mut x = Local::default();
        x.q[1] = [3.0, 0.0, 0.0];
        let mut q = BodyQ::default();
        s.generalized(&x, &mut q).unwrap();
        assert_eq!(q, [[20.0, 0.0, 0.0], [-20.0, 0.0, 0.0]]);
    }
}
