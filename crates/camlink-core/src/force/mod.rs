//! Applied forces and their generalized forces Q.
//!
//! A force acts on one or two bodies, i and j (a single-body force has the
//! ground as j). It sees the same [`Local`] view as a constraint and writes
//! per-body blocks; only the dynamics assembly knows global indices.
//!
//! The generalized force on body k, Q_k = (F_x, F_y, n), is the virtual-work
//! conjugate of q_k = (x, y, φ): a force F (N, global frame) at body point P
//! (s'_P in the body frame) and a torque T (N·m) give
//!
//! Q_k = [F ; (B_k s'_P)ᵀ F + T],
//!
//! so n is the moment about the body-frame origin, (B s')ᵀF = (A s') × F.
//!
//! For the implicit integrator and the equilibrium solver every force also
//! gives its derivatives ∂Q/∂q and ∂Q/∂q̇ as per-body 3 × 3 blocks, and a
//! conservative force its potential energy V (J), so that energy can be
//! reported.
//!
//! Adding a force kind is one new file and one line in [`forces!`].

use std::sync::Arc;

use crate::constraint::BodyId;
use crate::constraint::Local;

pub mod callback;
pub mod compliant_contact;
pub mod friction;
pub mod joint_stop;
pub mod point;
pub mod rsda;
pub mod state;
pub mod translational_damper;
pub mod tsda;

/// Generalized forces (F_x, F_y, n) on bodies i and j (N, N, N·m).
pub type BodyQ = [[f64; 3]; 2];

/// Derivative blocks: `d[a][b][r][c]` = ∂Q_a,r / ∂q_b,c for bodies a, b ∈ {i, j}.
pub type BodyJac = [[[[f64; 3]; 3]; 2]; 2];

/// Most bodies, besides i and j, whose motion one force may read.
pub const MAX_READ: usize = 4;

/// Coordinates (x, y, φ) and velocities (ẋ, ẏ, φ̇) of the bodies a force
/// reads besides i and j, in the order of [`Applied::reads`] (m, rad;
/// m/s, rad/s); zero past them.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Reads {
    pub q: [[f64; 3]; MAX_READ],
    pub qd: [[f64; 3]; MAX_READ],
}

/// Derivative blocks of the read bodies: `d[a][k][r][c]` = ∂Q_a,r / ∂q_k,c
/// for a ∈ {i, j} and read body k.
pub(crate) type ReadJac = [[[[f64; 3]; 3]; MAX_READ]; 2];

/// ∂Q/∂q and ∂Q/∂q̇ of one force: the blocks of its bodies i and j
/// (`dq`, `dqd`) and of its read bodies (`rq`, `rqd`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ForceJac {
    pub dq: BodyJac,
    pub dqd: BodyJac,
    pub rq: ReadJac,
    pub rqd: ReadJac,
}

/// The equations of one applied force.
pub trait Applied {
    /// Short kind name, e.g. `"tsda"`.
    fn kind(&self) -> &'static str;
    /// The bodies i and j the force acts on (j is the ground for a
    /// single-body force).
    fn bodies(&self) -> [BodyId; 2];
    /// Checks the force's numbers (the model's validation calls it).
    fn validate(&self) -> Result<(), String> {
        Ok(())
    }
    /// Q_i and Q_j at the local state (every entry of `out` is written);
    /// an error when a user function fails.
    fn generalized(&self, x: &Local, out: &mut BodyQ) -> Result<(), ForceError>;
    /// ∂Q/∂q into `dq` and ∂Q/∂q̇ into `dqd` (every entry is written).
    fn derivatives(&self, x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac);
    /// Potential energy V (J) of a conservative part; 0 otherwise.
    fn potential(&self, _x: &Local) -> f64 {
        0.0
    }
    /// The load this force puts on the ground at the local state, as
    /// (F_x, F_y, M_O): force (N, global frame) and its moment about the
    /// global origin plus any torque (N·m, counter-clockwise); `None` when
    /// neither of its bodies is the ground. The ground's frame is the
    /// global frame, so by default this is the ground's slot of Q. A
    /// single-body load (a point force or torque of time, a callback)
    /// returns `None`: it comes from outside the machine and has no
    /// reaction in the model.
    fn frame_load(&self, x: &Local) -> Result<Option<[f64; 3]>, ForceError> {
        let [bi, bj] = self.bodies();
        let slot = match (bi.is_ground(), bj.is_ground()) {
            (_, true) => 1,
            (true, false) => 0,
            (false, false) => return Ok(None),
        };
        let mut q = BodyQ::default();
        self.generalized(x, &mut q)?;
        Ok(Some(q[slot]))
    }
    /// The bodies besides i and j whose motion the force reads (at most
    /// [`MAX_READ`]; none for most forces). Their forces are zero: the
    /// force acts on i and j only.
    fn reads(&self) -> &[BodyId] {
        &[]
    }
    /// Q_i and Q_j with the read bodies' state `r`; [`Applied::generalized`]
    /// for a force that reads none.
    fn generalized_reading(
        &self,
        x: &Local,
        _r: &Reads,
        out: &mut BodyQ,
    ) -> Result<(), ForceError> {
        self.generalized(x, out)
    }
    /// [`Applied::derivatives`] into `out.dq`, `out.dqd`, and ∂Q/∂q, ∂Q/∂q̇
    /// of the read bodies into `out.rq`, `out.rqd` (the blocks of read
    /// bodies k < `reads().len()` are written, no others).
    fn derivatives_reading(&self, x: &Local, _r: &Reads, out: &mut ForceJac) {
        self.derivatives(x, &mut out.dq, &mut out.dqd)
    }
}

/// A named applied force.
#[derive(Clone, Debug)]
pub struct Force {
    pub name: String,
    pub kind: ForceKind,
}

impl Force {
    pub fn new(name: impl Into<String>, kind: impl Into<ForceKind>) -> Self {
        Force {
            name: name.into(),
            kind: kind.into(),
        }
    }
}

/// Declares [`ForceKind`] and dispatches [`Applied`] statically.
macro_rules! forces {
    ($($variant:ident($ty:ty)),* $(,)?) => {
        /// Every applied force camlink knows.
        #[derive(Clone, Debug)]
        pub enum ForceKind {
            $($variant($ty),)*
        }

        $(impl From<$ty> for ForceKind {
            fn from(c: $ty) -> Self {
                ForceKind::$variant(c)
            }
        })*

        impl Applied for ForceKind {
            fn kind(&self) -> &'static str {
                match self { $(ForceKind::$variant(c) => c.kind(),)* }
            }
            fn bodies(&self) -> [BodyId; 2] {
                match self { $(ForceKind::$variant(c) => c.bodies(),)* }
            }
            fn validate(&self) -> Result<(), String> {
                match self { $(ForceKind::$variant(c) => c.validate(),)* }
            }
            #[inline]
            fn generalized(&self, x: &Local, out: &mut BodyQ) -> Result<(), ForceError> {
                match self { $(ForceKind::$variant(c) => c.generalized(x, out),)* }
            }
            #[inline]
            fn derivatives(&self, x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac) {
                match self { $(ForceKind::$variant(c) => c.derivatives(x, dq, dqd),)* }
            }
            fn potential(&self, x: &Local) -> f64 {
                match self { $(ForceKind::$variant(c) => c.potential(x),)* }
            }
            fn frame_load(&self, x: &Local) -> Result<Option<[f64; 3]>, ForceError> {
                match self { $(ForceKind::$variant(c) => c.frame_load(x),)* }
            }
            fn reads(&self) -> &[BodyId] {
                match self { $(ForceKind::$variant(c) => c.reads(),)* }
            }
            #[inline]
            fn generalized_reading(
                &self,
                x: &Local,
                r: &Reads,
                out: &mut BodyQ,
            ) -> Result<(), ForceError> {
                match self { $(ForceKind::$variant(c) => c.generalized_reading(x, r, out),)* }
            }
            fn derivatives_reading(&self, x: &Local, r: &Reads, out: &mut ForceJac) {
                match self { $(ForceKind::$variant(c) => c.derivatives_reading(x, r, out),)* }
            }
        }
    };
}

forces! {
    PointForce(point::PointForce),
    Torque(point::Torque),
    Tsda(tsda::Tsda),
    Rsda(rsda::Rsda),
    TranslationalDamper(translational_damper::TranslationalDamper),
    Callback(callback::Callback),
    CompliantContact(compliant_contact::CompliantContact),
    JointStop(joint_stop::JointStop),
    State(state::StateForce),
}

/// ∂Q/∂q into `dq` and ∂Q/∂q̇ into `dqd` by central differences of step
/// `h` (m, rad; m/s, rad/s) of `q_of`, Q at a local state: for forces
/// whose Q is continuous but awkward to differentiate by hand (a contact's
/// witness points move with the bodies).
pub(crate) fn central_derivatives(
    x: &Local,
    h: f64,
    q_of: impl Fn(&Local, &mut BodyQ),
    dq: &mut BodyJac,
    dqd: &mut BodyJac,
) {
    for b in 0..2 {
        for c in 0..3 {
            for vel in [false, true] {
                let (mut xp, mut xm) = (*x, *x);
                let (p, m) = if vel {
                    (&mut xp.qd[b][c], &mut xm.qd[b][c])
                } else {
                    (&mut xp.q[b][c], &mut xm.q[b][c])
                };
                *p += h;
                *m -= h;
                let (mut qp, mut qm) = (BodyQ::default(), BodyQ::default());
                q_of(&xp, &mut qp);
                q_of(&xm, &mut qm);
                let d = if vel { &mut *dqd } else { &mut *dq };
                for a in 0..2 {
                    for r in 0..3 {
                        d[a][b][r][c] = (qp[a][r] - qm[a][r]) / (2.0 * h);
                    }
                }
            }
        }
    }
}

/// A force that could not be computed: a user function failed. The
/// message says why; the run that meets it stops with an error of kind
/// `force_failed` naming the force and the time.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct ForceError(pub String);

/// A shared user function, for [`callback::Callback`]: (t, q_k, q̇_k) to
/// Q_k, or an error that stops the run.
pub(crate) type ForceFn =
    Arc<dyn Fn(f64, [f64; 3], [f64; 3]) -> Result<[f64; 3], ForceError> + Send + Sync>;

/// Finite-difference checks of `generalized` against `derivatives`, shared
/// by the force kinds' tests.
#[cfg(test)]
#[allow(clippy::needless_range_loop)]
pub(crate) mod check {
    use super::*;

    /// A deterministic state with both bodies moving.
    pub(crate) fn state(seed: u64) -> Local {
        let mut s = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let mut r = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let mut x = Local {
            t: 0.3 + 0.5 * r(),
            ..Local::default()
        };
        for k in 0..2 {
            for c in 0..3 {
                x.q[k][c] = r();
                x.qd[k][c] = r();
            }
        }
        x
    }

    /// Compares ∂Q/∂q and ∂Q/∂q̇ with central differences of Q, and −∂V/∂q
    /// with the conservative part `q_cons` when given.
    pub(crate) fn derivatives<F: Applied>(f: &F, x: &Local) {
        let mut dq = BodyJac::default();
        let mut dqd = BodyJac::default();
        f.derivatives(x, &mut dq, &mut dqd);
        let h = 1e-6;
        for b in 0..2 {
            for c in 0..3 {
                for vel in [false, true] {
                    let (mut xp, mut xm) = (*x, *x);
                    if vel {
                        xp.qd[b][c] += h;
                        xm.qd[b][c] -= h;
                    } else {
                        xp.q[b][c] += h;
                        xm.q[b][c] -= h;
                    }
                    let (mut qp, mut qm) = (BodyQ::default(), BodyQ::default());
                    f.generalized(&xp, &mut qp).unwrap();
                    f.generalized(&xm, &mut qm).unwrap();
                    for a in 0..2 {
                        for r in 0..3 {
                            let fd = (qp[a][r] - qm[a][r]) / (2.0 * h);
                            let an = if vel { dqd[a][b][r][c] } else { dq[a][b][r][c] };
                            assert!(
                                (fd - an).abs() <= 1e-6 * (1.0 + fd.abs()),
                                "{}: d Q[{a}][{r}] / d {}[{b}][{c}]: analytic {an}, numeric {fd}",
                                f.kind(),
                                if vel { "qd" } else { "q" }
                            );
                        }
                    }
                }
            }
        }
    }

    /// Checks Q = −∂V/∂q for a force with no velocity or time dependence.
    pub(crate) fn potential<F: Applied>(f: &F, x: &Local) {
        let mut q = BodyQ::default();
        f.generalized(x, &mut q).unwrap();
        let h = 1e-6;
        for b in 0..2 {
            for c in 0..3 {
                let (mut xp, mut xm) = (*x, *x);
                xp.q[b][c] += h;
                xm.q[b][c] -= h;
                let fd = -(f.potential(&xp) - f.potential(&xm)) / (2.0 * h);
                assert!(
                    (fd - q[b][c]).abs() <= 1e-6 * (1.0 + fd.abs()),
                    "{}: Q[{b}][{c}] = {} but -dV/dq = {fd}",
                    f.kind(),
                    q[b][c]
                );
            }
        }
    }
}
