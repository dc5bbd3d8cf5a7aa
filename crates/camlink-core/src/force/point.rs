//! A force at a body point, and a pure torque on a body, as functions of time.
//!
//! Point force, F = (f_x(t), f_y(t)) (N) at P (s'_P in the body frame):
//! - global components (`local = false`): Q = [F ; (B s'_P)ᵀ F];
//!   ∂Q_φ/∂φ = −(A s'_P)ᵀ F, all else 0;
//! - body-frame components F' (`local = true`, a follower force that turns
//!   with the body): F = A F', Q = [A F' ; s'_P × F'];
//!   ∂Q_r/∂φ = B F', all else 0.
//!
//! Torque T(t) (N·m, counter-clockwise positive): Q = [0, 0, T].
//!
//! Neither depends on q̇; neither has a potential (their work shows up as a
//! change of the mechanism's energy).

use super::{Applied, BodyJac, BodyQ, ForceError};
use crate::constraint::BodyId;
use crate::constraint::Local;
use crate::function::TimeFn;
use crate::math::{dot, rot, rot_d, V2};

#[derive(Clone, Debug)]
pub struct PointForce {
    pub body: BodyId,
    /// s'_P: the point of application in the body frame (m).
    pub s: V2,
    /// f_x(t), f_y(t) (N).
    pub f: [TimeFn; 2],
    /// True when f gives components in the body frame (turning with the
    /// body); false for the global frame.
    pub local: bool,
}

#[derive(Clone, Debug)]
pub struct Torque {
    pub body: BodyId,
    /// T(t) (N·m), counter-clockwise positive.
    pub t: TimeFn,
}

impl PointForce {
    /// F in the global frame at the local state (N).
    pub fn global(&self, x: &Local) -> V2 {
        let f = [self.f[0].value(x.t), self.f[1].value(x.t)];
        if self.local {
            rot(x.q[0][2], f)
        } else {
            f
        }
    }
}

impl Applied for PointForce {
    fn kind(&self) -> &'static str {
        "point_force"
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body, BodyId::GROUND]
    }

    fn generalized(&self, x: &Local, out: &mut BodyQ) -> Result<(), ForceError> {
        let f = self.global(x);
        let b = rot_d(x.q[0][2], self.s);
        *out = [[f[0], f[1], dot(b, f)], [0.0; 3]];
        Ok(())
    }

    fn derivatives(&self, x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac) {
        *dq = BodyJac::default();
        *dqd = BodyJac::default();
        let phi = x.q[0][2];
        if self.local {
            let fl = [self.f[0].value(x.t), self.f[1].value(x.t)];
            let bf = rot_d(phi, fl);
            dq[0][0][0][2] = bf[0];
            dq[0][0][1][2] = bf[1];
        } else {
            dq[0][0][2][2] = -dot(rot(phi, self.s), self.global(x));
        }
    }

    /// A load from outside: no reaction on the ground.
    fn frame_load(&self, _x: &Local) -> Result<Option<[f64; 3]>, ForceError> {
        Ok(None)
    }
}

impl Applied for Torque {
    fn kind(&self) -> &'static str {
        "torque"
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body, BodyId::GROUND]
    }

    fn generalized(&self, x: &Local, out: &mut BodyQ) -> Result<(), ForceError> {
        *out = [[0.0, 0.0, self.t.value(x.t)], [0.0; 3]];
        Ok(())
    }

    fn derivatives(&self, _x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac) {
        *dq = BodyJac::default();
        *dqd = BodyJac::default();
    }

    /// A load from outside: no reaction on the ground.
    fn frame_load(&self, _x: &Local) -> Result<Option<[f64; 3]>, ForceError> {
        Ok(None)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::force::check;

    fn force(local: bool) -> PointForce {
        PointForce {
            body: BodyId(1),
            s: [0.3, -0.2],
            f: [
                TimeFn::Linear {
                    value: 2.0,
                    rate: 1.0,
                },
                TimeFn::Const(-3.0),
            ],
            local,
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        for seed in 0..10 {
            check::derivatives(&force(false), &check::state(seed));
            check::derivatives(&force(true), &check::state(seed));
        }
    }

    #[test]
    fn moment_is_about_the_body_origin() {
        // A body at φ = π/2: s' = (1, 0) is at (0, 1); a force (1, 0) there
        // turns the body clockwise, n = −1.
        let mut x = Local::default();
        x.q[0] = [5.0, 5.0, std::f64::consts::FRAC_PI_2];
        let f = PointForce {
            body: BodyId(1),
            s: [1.0, 0.0],
            f: [TimeFn::Const(1.0), TimeFn::Const(0.0)],
            local: false,
        };
        let mut q = BodyQ::default();
        f.generalized(&x, &mut q).unwrap();
        assert!((q[0][2] + 1.0).abs() < 1e-15, "{q:?}");
        // The same force in the body frame points along the body's x axis,
        // now global +y: no moment, since it acts along s'.
        let fl = PointForce { local: true, ..f };
        fl.generalized(&x, &mut q).unwrap();
        assert!(q[0][0].abs() < 1e-15 && (q[0][1] - 1.0).abs() < 1e-15);
        assert!(q[0][2].abs() < 1e-15);
    }
}
