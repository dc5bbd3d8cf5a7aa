//! A force computed by a user function: the slow path.
//!
//! The function receives (t, q_k, q̇_k) of its body, (s, (m, m, rad),
//! (m/s, m/s, rad/s)), and returns the generalized force
//! Q_k = (F_x, F_y, n) (N, N, N·m), n being the moment about the body-frame
//! origin (for a force F at s'_P add (A s'_P) × F). It is called at least
//! once per Newton iteration, so a function that crosses into an
//! interpreter (the Python binding) costs far more than the built-in forces.
//! Its derivatives are unknown and taken as zero in the Newton iteration
//! matrix: the integrator still converges to the right answer, in more
//! iterations when the force is stiff. A function that fails returns a
//! [`ForceError`], which stops the run.

use super::{Applied, BodyJac, BodyQ, ForceError, ForceFn};
use crate::constraint::BodyId;
use crate::constraint::Local;

#[derive(Clone)]
pub struct Callback {
    pub body: BodyId,
    pub f: ForceFn,
}

impl std::fmt::Debug for Callback {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Callback")
            .field("body", &self.body)
            .finish()
    }
}

impl Applied for Callback {
    fn kind(&self) -> &'static str {
        "callback"
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body, BodyId::GROUND]
    }

    fn generalized(&self, x: &Local, out: &mut BodyQ) -> Result<(), ForceError> {
        *out = [(self.f)(x.t, x.q[0], x.qd[0])?, [0.0; 3]];
        Ok(())
    }

    fn derivatives(&self, _x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac) {
        *dq = BodyJac::default();
        *dqd = BodyJac::default();
    }

    /// A load from outside: no reaction on the ground (and the user
    /// function is not called again for it).
    fn frame_load(&self, _x: &Local) -> Result<Option<[f64; 3]>, ForceError> {
        Ok(None)
    }
}
