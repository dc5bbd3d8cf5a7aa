//! Compliant end stop of a joint: a Hunt–Crossley force on a limited
//! joint coordinate c (a revolute's angle, a translational joint's stroke,
//! a revolute–translational pin's travel; [`crate::model::Limits`]).
//!
//! With the limit c₀ and σ = +1 for a lower stop, −1 for an upper one, the
//! gap is g = σ (c − c₀) (rad or m, positive inside the range) and the
//! penetration δ = −g, δ̇ = −ġ. The stop pushes the joint back into its
//! range with
//!
//! F = k δⁿ (1 + c_d δ̇)   for δ > 0, clamped at F ≥ 0; F = 0 apart,
//!
//! ([`HuntCrossley`]; k in N·m/radⁿ or N/mⁿ, c_d in s/rad or s/m), a
//! torque or a force along the coordinate, F ∂g/∂q in generalized
//! coordinates:
//!
//! Q_k = F σ (Φ_q)_k  (row of Φ = c − c₀ in body k's block, k = i, j),
//!
//! which for a revolute is a torque F on body i's side and −F on body j's
//! (σ = +1), and for a slider F along the axis. ∂Q/∂q and ∂Q/∂q̇ are
//! central differences of Q ([`super::central_derivatives`]); the elastic
//! part's potential is V = k δⁿ⁺¹/(n + 1).

use super::compliant_contact::HuntCrossley;
use super::{central_derivatives, Applied, BodyJac, BodyQ, ForceError};
use crate::constraint::relative::RelativeCoord;
use crate::constraint::{BodyId, Equations, Jac, Local};

#[derive(Clone, Debug)]
pub struct JointStop {
    /// Φ = c(q) − c₀, the joint's coordinate less its limit.
    pub coord: RelativeCoord,
    /// σ: +1 for a lower stop (g = c − c₀), −1 for an upper one (g = c₀ − c).
    pub sign: f64,
    pub law: HuntCrossley,
}

/// Step of the central differences of Q (m, rad; m/s, rad/s).
const H: f64 = 1e-7;

impl JointStop {
    /// The gap g and its rate ġ at the local state (rad or m, per second).
    pub fn gap(&self, x: &Local) -> (f64, f64) {
        let (c, rate) = self.coord.value_and_rate(x);
        let c0 = self.coord.f.value(x.t);
        (self.sign * (c - c0), self.sign * rate)
    }

    /// The stop's force F (N·m or N, pushing into the range) at `x`.
    pub fn force(&self, x: &Local) -> f64 {
        let (g, rate) = self.gap(x);
        self.law.force(-g, -rate)
    }

    fn stop_force(&self, x: &Local, out: &mut BodyQ) {
        *out = BodyQ::default();
        let f = self.force(x);
        if f == 0.0 {
            return;
        }
        let mut jac = Jac::default();
        self.coord.jacobian(x, &mut jac);
        for (q, block) in out.iter_mut().zip(&jac.body) {
            *q = block[0].map(|d| f * self.sign * d);
        }
    }
}

impl Applied for JointStop {
    fn kind(&self) -> &'static str {
        "joint_stop"
    }

    fn bodies(&self) -> [BodyId; 2] {
        self.coord.bodies()
    }

    fn generalized(&self, x: &Local, out: &mut BodyQ) -> Result<(), ForceError> {
        self.stop_force(x, out);
        Ok(())
    }

    fn derivatives(&self, x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac) {
        central_derivatives(x, H, |x, out| self.stop_force(x, out), dq, dqd);
    }

    fn potential(&self, x: &Local) -> f64 {
        self.law.potential(-self.gap(x).0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::relative::RelCoord;
    use crate::function::TimeFn;

    /// An upper stop at 0.05 m on the stroke of a slider (body j) along
    /// the ground's x axis, from ground point (0.1, 0).
    fn slider_stop(damping: f64) -> JointStop {
        JointStop {
            coord: RelativeCoord {
                body_i: BodyId(0),
                s_i: [0.1, 0.0],
                body_j: BodyId(1),
                s_j: [0.0, 0.0],
                coord: RelCoord::Along([2.0, 0.0]),
                f: TimeFn::Const(0.05),
            },
            sign: -1.0,
            law: HuntCrossley {
                stiffness: 1e6,
                exponent: 1.5,
                damping,
            },
        }
    }

    fn at(x: f64, vx: f64) -> Local {
        let mut l = Local::default();
        l.q[1] = [x, 0.02, 0.3];
        l.qd[1] = [vx, 0.0, 0.0];
        l
    }

    #[test]
    fn force_pushes_the_slider_back_into_its_range() {
        // Stroke 0.152 − 0.1 = 0.052 m: 2 mm past the stop, moving on at
        // 0.2 m/s, c = 0.5 s/m: F = 1e6 · 2e-3^1.5 · 1.1 along −x.
        let s = slider_stop(0.5);
        let mut q = BodyQ::default();
        s.generalized(&at(0.152, 0.2), &mut q).unwrap();
        let f = 1e6 * 2e-3f64.powf(1.5) * 1.1;
        assert!((q[1][0] + f).abs() < 1e-9 * f, "{q:?}");
        assert!(q[1][1].abs() < 1e-12 && q[1][2].abs() < 1e-12, "{q:?}");
        // Inside the range: no force.
        s.generalized(&at(0.149, 0.2), &mut q).unwrap();
        assert_eq!(q, BodyQ::default());
    }

    #[test]
    fn potential_is_the_work_of_the_elastic_force() {
        let s = slider_stop(0.0);
        let h = 1e-7;
        let mut q = BodyQ::default();
        s.generalized(&at(0.153, 0.0), &mut q).unwrap();
        let dv = (s.potential(&at(0.153 + h, 0.0)) - s.potential(&at(0.153 - h, 0.0))) / (2.0 * h);
        assert!(
            (q[1][0] + dv).abs() < 1e-6 * dv.abs(),
            "{} vs {}",
            q[1][0],
            -dv
        );
    }

    #[test]
    fn derivatives_match_finite_differences_of_q() {
        // A revolute's lower stop at 0.2 rad between two moving bodies.
        let s = JointStop {
            coord: RelativeCoord {
                body_i: BodyId(1),
                s_i: [0.1, 0.0],
                body_j: BodyId(2),
                s_j: [0.0, 0.0],
                coord: RelCoord::Phi,
                f: TimeFn::Const(0.2),
            },
            sign: 1.0,
            law: HuntCrossley {
                stiffness: 500.0,
                exponent: 1.0,
                damping: 0.3,
            },
        };
        let x = Local {
            q: [[0.0, 0.0, 0.4], [0.1, 0.0, 0.55]],
            qd: [[0.0, 0.0, 0.5], [0.0, 0.0, -1.0]],
            ..Local::default()
        };
        let (mut dq, mut dqd) = (BodyJac::default(), BodyJac::default());
        s.derivatives(&x, &mut dq, &mut dqd);
        // θ = 0.15 rad: 0.05 rad into the stop, closing at 1.5 rad/s.
        let f = 500.0 * 0.05 * (1.0 + 0.3 * 1.5);
        let mut q = BodyQ::default();
        s.generalized(&x, &mut q).unwrap();
        assert!(
            (q[1][2] - f).abs() < 1e-12 && (q[0][2] + f).abs() < 1e-12,
            "{q:?}"
        );
        // ∂Q_j,φ/∂φ_j = −k (1 + c δ̇), ∂Q_j,φ/∂φ̇_j = −k δ c.
        let k_eff = 500.0 * (1.0 + 0.3 * 1.5);
        assert!((dq[1][1][2][2] + k_eff).abs() < 1e-5, "{}", dq[1][1][2][2]);
        assert!((dqd[1][1][2][2] + 500.0 * 0.05 * 0.3).abs() < 1e-5);
        assert!((dq[0][1][2][2] - k_eff).abs() < 1e-5);
    }
}
