//! Joint reactions and driver efforts from the Lagrange multipliers
//! (Haug §6.6).
//!
//! Joint k's equations Φ^k enter the equations of motion as Φ^k_qᵀ λ_k on the
//! left, so the joint acts on body b with the generalized force
//!
//! Q_b^k = −Φ^k_{q_b}ᵀ λ_k = (F, n_O),
//!
//! a force F (N, global frame) and a moment n_O (N·m) about body b's frame
//! origin. Moved to the joint point P of body b (s'_P in its frame), the same
//! load is the force F at P and the torque
//!
//! T_P = n_O − (A_b s'_P) × F,
//!
//! and in body b's frame the force is F' = A_bᵀ F. This is the force and
//! torque exerted ON body b BY the joint: on the other body of a revolute
//! joint it is exactly −F (action and reaction), and T_P = 0 for a revolute.
//!
//! The joint point P of each body is the joint's own point on it (s'_i,
//! s'_j); for a constraint of one body against the ground the ground side
//! uses the same global point; for a curve contact it is the current
//! contact point; for a gear the centre of each gear.
//!
//! A driver Φ = c(q) − f(t) (or c² − f² for a distance) acts on the
//! mechanism with −Φ_qᵀλ, whose power is P = −λ Φ_q q̇ = −λ ν. Its effort is
//! the generalized force conjugate to the driven coordinate,
//! E = λ ∂Φ/∂f (N for a length, N·m for an angle), so that P = E ḟ: the
//! torque a motor must apply to the driven body j (and −E to body i), or
//! the force an actuator pushes with along its coordinate.

use crate::assembly::Assembly;
use crate::constraint::{Equations, Jac};
use crate::math::{cross, point, rot, rot_t, V2};
use crate::model::Model;

/// The load a joint exerts on one of its bodies.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Reaction {
    /// F, global frame (N).
    pub force: V2,
    /// F' = Aᵀ F in the body's frame (N); the global frame for the ground.
    pub force_local: V2,
    /// T about the joint point (N·m), counter-clockwise positive.
    pub torque: f64,
    /// The joint point P in the global frame (m).
    pub point: V2,
}

/// The reactions of joint `j` on its bodies i and j at q, from its
/// multipliers in the full λ.
pub fn reactions(
    model: &Model,
    asm: &Assembly,
    j: usize,
    q: &[f64],
    lambda: &[f64],
    t: f64,
) -> [Reaction; 2] {
    let c = &model.joints[j].constraint;
    let x = asm.local(model, j, q, &[], t);
    let mut jac = Jac::default();
    c.jacobian(&x, &mut jac);
    let lam = &lambda[asm.rows_of(j)];
    let pts = c.joint_points(&x);
    let mut out = [Reaction::default(); 2];
    for (b, o) in out.iter_mut().enumerate() {
        // Q_b = −Φ_{q_b}ᵀ λ.
        let mut g = [0.0; 3];
        for (r, &l) in lam.iter().enumerate() {
            for (gd, jd) in g.iter_mut().zip(jac.body[b][r]) {
                *gd -= jd * l;
            }
        }
        let f = [g[0], g[1]];
        let arm = rot(x.q[b][2], pts[b]);
        *o = Reaction {
            force: f,
            force_local: rot_t(x.q[b][2], f),
            torque: g[2] - cross(arm, f),
            point: point(x.q[b], pts[b]),
        };
    }
    out
}

/// (effort E, power P) of driver `j`, from its multiplier λ_j and ν_j.
pub fn effort(model: &Model, j: usize, lambda_j: f64, nu_j: f64, t: f64) -> (f64, f64) {
    let c = &model.joints[j].constraint;
    (lambda_j * c.driver_slope(t), -lambda_j * nu_j)
}
