//! Rotational spring–damper–actuator (RSDA) between bodies i and j
//! (Haug §6.3.3); with k = 0 it is the viscous friction of a revolute joint.
//!
//! With θ = φ_j − φ_i (rad) the twist T (N·m) is
//!
//! T = k (θ − θ₀) + c θ̇ + T_a(t),
//!
//! k the stiffness (N·m/rad), θ₀ the free angle, c the damping
//! (N·m·s/rad), T_a the actuator torque. The spring resists the twist: the
//! torque on body j is −T and on body i is +T, so
//!
//! Q_i = [0, 0, T],  Q_j = [0, 0, −T].
//!
//! ∂Q/∂q has ±k in the (φ_a, φ_b) entries (−k on the diagonal), ∂Q/∂q̇
//! likewise ±c. Potential V = ½ k (θ − θ₀)².

use super::{Applied, BodyJac, BodyQ, ForceError};
use crate::constraint::BodyId;
use crate::constraint::Local;
use crate::function::TimeFn;

#[derive(Clone, Debug)]
pub struct Rsda {
    pub body_i: BodyId,
    pub body_j: BodyId,
    /// k (N·m/rad).
    pub stiffness: f64,
    /// θ₀ (rad).
    pub free_angle: f64,
    /// c (N·m·s/rad).
    pub damping: f64,
    /// T_a(t) (N·m).
    pub actuator: TimeFn,
}

impl Rsda {
    /// The twist T (N·m).
    pub(crate) fn twist(&self, x: &Local) -> f64 {
        let th = x.q[1][2] - x.q[0][2];
        let thd = x.qd[1][2] - x.qd[0][2];
        self.stiffness * (th - self.free_angle) + self.damping * thd + self.actuator.value(x.t)
    }
}

impl Applied for Rsda {
    fn kind(&self) -> &'static str {
        "rsda"
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn validate(&self) -> Result<(), String> {
        if !(self.stiffness >= 0.0 && self.damping >= 0.0) {
            return Err("stiffness and damping must be ≥ 0".into());
        }
        Ok(())
    }

    fn generalized(&self, x: &Local, out: &mut BodyQ) -> Result<(), ForceError> {
        let t = self.twist(x);
        *out = [[0.0, 0.0, t], [0.0, 0.0, -t]];
        Ok(())
    }

    fn derivatives(&self, _x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac) {
        *dq = BodyJac::default();
        *dqd = BodyJac::default();
        // ∂θ/∂φ_i = −1, ∂θ/∂φ_j = +1; Q_i = +T, Q_j = −T.
        let s = [-1.0, 1.0];
        for a in 0..2 {
            for b in 0..2 {
                dq[a][b][2][2] = -s[a] * self.stiffness * s[b];
                dqd[a][b][2][2] = -s[a] * self.damping * s[b];
            }
        }
    }

    fn potential(&self, x: &Local) -> f64 {
        let th = x.q[1][2] - x.q[0][2];
        0.5 * self.stiffness * (th - self.free_angle).powi(2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::force::check;

    fn rsda(c: f64) -> Rsda {
        Rsda {
            body_i: BodyId(1),
            body_j: BodyId(2),
            stiffness: 40.0,
            free_angle: 0.3,
            damping: c,
            actuator: TimeFn::Const(0.0),
        }
    }

    #[test]
    fn derivatives_and_potential_match_finite_differences() {
        for seed in 0..10 {
            check::derivatives(&rsda(2.0), &check::state(seed));
            check::potential(&rsda(0.0), &check::state(seed));
        }
    }
}
