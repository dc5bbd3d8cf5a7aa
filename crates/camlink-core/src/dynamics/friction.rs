//! Coulomb friction in joints, as the dynamic analyses see it
//! (`docs/friction.md`).
//!
//! A joint with [`Friction`] adds to Q the friction loads of
//! [`crate::force::friction`] at its normal force N, the magnitude of the
//! force its equations exert on body j,
//!
//! N = |F_j|,  (F_j, n_j) = −Φ^k_{q_j}ᵀ λ_k,
//!
//! which is the pin force of a revolute joint, the normal force of a
//! translational joint (its reaction moment is not counted) and the
//! contact force of a curve contact. The friction thus depends on the
//! multipliers, and the equations of motion become
//!
//! M q̈ + Φ_qᵀλ = Q(q, q̇, t) + Q_f(q, q̇, λ).
//!
//! **Coupling.** Forward dynamics evaluates Q_f inside Newton's iteration
//! at the current iterate of λ, so a converged step satisfies the equations
//! with the friction of its own multipliers (no lag, no splitting error).
//! The iteration matrix holds ∂Q_f/∂q̇ (with the secant slope f(v)/v of
//! the law, [`Friction::newton_slope`]: the steep 1.5 μN/v_s in the
//! transition band, which a stuck joint needs, and still μN/|v| outside
//! it, where the tangent slope 0 would let the iterates jump across the
//! band without end) and ∂Q_f/∂q at fixed N and contact geometry, but
//! not ∂Q_f/∂λ: Newton is then a chord iteration in
//! the multipliers, whose convergence slows with the friction's share of
//! the loads (μ r/ℓ for a pin of radius r on a link of length ℓ) but
//! whose converged answer is the same. Where the consistent q̈ and λ are
//! solved for directly (the start of a run, output times inside a step)
//! and in inverse dynamics, λ is found by fixed-point iteration on
//! Q_f(λ), from the frictionless answer, to [`FIXED_POINT_TOL`].

use crate::assembly::Assembly;
use crate::constraint::{Constraint, Equations, Feature, Jac, Local};
use crate::contact::ContactView;
use crate::force::friction::{Friction, PinFriction, SlideFriction};
use crate::force::{Applied, BodyJac, BodyQ};
use crate::math::{norm, V2};
use crate::model::Model;
use crate::quantity::{Channel, Quantity};
use crate::run::{AnalysisError, Kind};

/// The fixed-point iteration on the multipliers stops when no multiplier
/// changed by more than this fraction of the largest (plus this much).
pub const FIXED_POINT_TOL: f64 = 1e-11;

/// Most iterations of the fixed point; more means the friction carries the
/// mechanism's loads (a self-locking mechanism) and is refused.
pub const FIXED_POINT_ITER: usize = 100;

/// The joints with friction of one model, in joint order.
#[derive(Clone, Debug, Default)]
pub struct JointFrictions {
    items: Vec<(usize, Friction)>,
}

/// The friction load of one joint at one state.
pub enum Load {
    Pin(PinFriction),
    Slide(SlideFriction),
}

impl Load {
    pub fn applied(&self) -> &dyn Applied {
        match self {
            Load::Pin(p) => p,
            Load::Slide(s) => s,
        }
    }
}

impl JointFrictions {
    pub fn new(model: &Model) -> Self {
        let items = model
            .joints
            .iter()
            .enumerate()
            .filter_map(|(j, joint)| Some((j, joint.friction?)))
            .collect();
        JointFrictions { items }
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// The joint index of each friction, in order.
    pub fn joints(&self) -> impl Iterator<Item = usize> + '_ {
        self.items.iter().map(|&(j, _)| j)
    }

    /// The friction load of item `k` and the local state of its joint at
    /// (q, q̇, λ, t).
    #[allow(clippy::too_many_arguments)]
    pub fn load(
        &self,
        model: &Model,
        asm: &Assembly,
        k: usize,
        q: &[f64],
        qd: &[f64],
        lambda: &[f64],
        t: f64,
    ) -> (Load, Local) {
        let j = self.items[k].0;
        let x = asm.local(model, j, q, qd, t);
        let c = &model.joints[j].constraint;
        let normal = normal_force(c, &x, &lambda[asm.rows_of(j)]);
        (self.load_at(model, k, &x, normal), x)
    }

    /// The friction load of item `k` at its joint's local state `x` and
    /// normal force `normal` (N).
    fn load_at(&self, model: &Model, k: usize, x: &Local, normal: f64) -> Load {
        let (j, law) = self.items[k];
        let c = &model.joints[j].constraint;
        let bodies = c.bodies();
        match c {
            Constraint::Revolute(_) => Load::Pin(PinFriction {
                bodies,
                law,
                normal,
            }),
            _ => {
                let (tangent, frame) = tangent(model, j, c, x);
                Load::Slide(SlideFriction {
                    bodies,
                    law,
                    normal,
                    points: c.joint_points(x),
                    tangent,
                    frame,
                })
            }
        }
    }

    /// `out += w Q_f` (length n): the friction of every joint at
    /// (q, q̇, λ, t).
    #[allow(clippy::too_many_arguments)]
    pub fn add(
        &self,
        model: &Model,
        asm: &Assembly,
        q: &[f64],
        qd: &[f64],
        lambda: &[f64],
        t: f64,
        w: f64,
        out: &mut [f64],
    ) {
        let mut qf = BodyQ::default();
        for k in 0..self.items.len() {
            let (load, x) = self.load(model, asm, k, q, qd, lambda, t);
            let f = load.applied();
            // A friction load cannot fail: its law is built in.
            let _ = f.generalized(&x, &mut qf);
            for (b, body) in f.bodies().iter().enumerate() {
                if let Some(c) = asm.body_col(body.0) {
                    for d in 0..3 {
                        out[c + d] += w * qf[b][d];
                    }
                }
            }
        }
    }

    /// ∂Q_f/∂q and ∂Q_f/∂q̇ of item `k` at (q, q̇, λ, t), at fixed N and
    /// contact geometry, with the law's secant slope for its tangent
    /// ([`Friction::newton_slope`]): the blocks of Newton's matrix.
    #[allow(clippy::too_many_arguments)]
    pub fn derivatives(
        &self,
        model: &Model,
        asm: &Assembly,
        k: usize,
        q: &[f64],
        qd: &[f64],
        lambda: &[f64],
        t: f64,
        dq: &mut BodyJac,
        dqd: &mut BodyJac,
    ) {
        let (load, x) = self.load(model, asm, k, q, qd, lambda, t);
        match load {
            Load::Pin(p) => p.newton_derivatives(&x, dq, dqd),
            Load::Slide(f) => f.newton_derivatives(&x, dq, dqd),
        }
    }

    /// The fraction θ ∈ (0, 1] of Newton's correction `dx` (Δq in its
    /// first n entries, with Δq̇ = γ′ Δq) that keeps every joint's slip
    /// speed from jumping from outside its transition band across it: such
    /// a step is cut to land at v = 0, where the law's slope is steepest.
    /// Outside the band the law is flat, and a full step from there would
    /// land beyond the far side, then come back: Newton would cycle
    /// between the two sides of a stuck joint.
    #[allow(clippy::too_many_arguments)]
    pub fn step_fraction(
        &self,
        model: &Model,
        asm: &Assembly,
        q: &[f64],
        qd: &[f64],
        dx: &[f64],
        gp: f64,
        t: f64,
    ) -> f64 {
        let mut theta = 1.0f64;
        for (k, &(j, law)) in self.items.iter().enumerate() {
            let x = asm.local(model, j, q, qd, t);
            let mut moved = x;
            for (b, body) in model.joints[j].constraint.bodies().iter().enumerate() {
                if let Some(c) = asm.body_col(body.0) {
                    for d in 0..3 {
                        moved.qd[b][d] += gp * dx[c + d];
                    }
                }
            }
            let (v0, v1) = self.slips(model, k, &x, &moved);
            let vs = law.transition_speed;
            if v0.abs() >= vs && v1 * v0 < 0.0 && v1.abs() > vs {
                theta = theta.min(v0 / (v0 - v1));
            }
        }
        theta
    }

    /// The slip speeds of item `k` at two local states of its joint (the
    /// geometry of the first).
    fn slips(&self, model: &Model, k: usize, a: &Local, b: &Local) -> (f64, f64) {
        match self.load_at(model, k, a, 0.0) {
            Load::Pin(p) => (p.slip(a), p.slip(b)),
            Load::Slide(f) => (f.slip(a), f.slip(b)),
        }
    }

    /// The bodies of item `k`'s joint.
    pub fn bodies(&self, model: &Model, k: usize) -> [crate::model::BodyId; 2] {
        model.joints[self.items[k].0].constraint.bodies()
    }

    /// The friction channels of joint `j` (none without friction):
    /// `<joint>.friction_torque` (N·m, on body j) for a revolute joint,
    /// `<joint>.friction_force` (N, on body j along the contact tangent)
    /// otherwise, then `<joint>.friction_power` (W, ≤ 0: the power of the
    /// friction on both bodies).
    pub fn channels_of(model: &Model, j: usize) -> Vec<Channel> {
        let joint = &model.joints[j];
        if joint.friction.is_none() {
            return Vec::new();
        }
        let (what, quantity) = match joint.constraint {
            Constraint::Revolute(_) => ("friction_torque", Quantity::Torque),
            _ => ("friction_force", Quantity::Force),
        };
        vec![
            Channel::new(format!("{}.{what}", joint.name), quantity),
            Channel::new(format!("{}.friction_power", joint.name), Quantity::Power),
        ]
    }

    /// The two channels of item `k` at (q, q̇, λ, t), the friction torque
    /// or force on body j and the friction power, and the friction load
    /// (F_x, F_y, moment about the global origin) on the ground, zero when
    /// neither body is the ground (for the shaking channels).
    #[allow(clippy::too_many_arguments)]
    pub fn channels(
        &self,
        model: &Model,
        asm: &Assembly,
        k: usize,
        q: &[f64],
        qd: &[f64],
        lambda: &[f64],
        t: f64,
    ) -> ([f64; 2], [f64; 3]) {
        let (load, x) = self.load(model, asm, k, q, qd, lambda, t);
        let value = match &load {
            Load::Pin(p) => p.torque(&x).0,
            Load::Slide(f) => {
                let (force, _) = f.force(&x);
                let t = crate::math::rot(x.q[f.frame][2], f.tangent);
                crate::math::dot(force, t)
            }
        };
        let mut qf = BodyQ::default();
        let _ = load.applied().generalized(&x, &mut qf);
        let power = (0..2)
            .map(|b| (0..3).map(|c| qf[b][c] * x.qd[b][c]).sum::<f64>())
            .sum();
        // The ground's frame is the global one: its Q is the load about O.
        let bodies = load.applied().bodies();
        let ground = (0..2)
            .find(|&b| bodies[b].is_ground())
            .map_or([0.0; 3], |b| qf[b]);
        ([value, power], ground)
    }

    /// [M Φ_qᵀ; Φ_q 0][q̈; λ] = [Q + Q_f(λ); γ] in place in `rhs` (length
    /// n + m), which holds [Q; γ] on entry; `solve` applies the factored
    /// matrix's inverse in place. One solve without friction, then, when the
    /// model has friction, fixed-point iteration on λ.
    #[allow(clippy::too_many_arguments)]
    pub fn consistent(
        &self,
        model: &Model,
        asm: &Assembly,
        t: f64,
        q: &[f64],
        qd: &[f64],
        rhs: &mut [f64],
        solve: &mut dyn FnMut(&mut [f64]),
    ) -> Result<(), AnalysisError> {
        if self.is_empty() {
            solve(rhs);
            return Ok(());
        }
        let n = asm.n;
        let base = rhs.to_vec();
        solve(rhs);
        let g = |lambda: &[f64], next: &mut [f64]| {
            next.copy_from_slice(&base);
            self.add(model, asm, q, qd, lambda, t, 1.0, &mut next[..n]);
            solve(next);
        };
        fixed_point(t, g, rhs, n)
    }

    /// The multipliers λ of inverse dynamics with friction, by fixed-point
    /// iteration from the frictionless λ they hold on entry: `base` is the
    /// right side without friction (Q − M q̈ in its first n entries) and
    /// `solve(f, λ)` writes the multipliers of right side f into λ.
    #[allow(clippy::too_many_arguments)]
    pub fn inverse(
        &self,
        model: &Model,
        asm: &Assembly,
        t: f64,
        q: &[f64],
        qd: &[f64],
        base: &[f64],
        lambda: &mut [f64],
        solve: &mut dyn FnMut(&mut [f64], &mut [f64]),
    ) -> Result<(), AnalysisError> {
        let n = asm.n;
        let mut f = vec![0.0; base.len()];
        let g = |lam: &[f64], next: &mut [f64]| {
            f.copy_from_slice(base);
            self.add(model, asm, q, qd, lam, t, 1.0, &mut f[..n]);
            solve(&mut f, next);
        };
        fixed_point(t, g, lambda, 0)
    }
}

/// N = |F_j|, the force (N) that joint `c`'s equations exert on body j at
/// multipliers `lam` (its rows): F_j = −Φ_{r_j}ᵀλ.
fn normal_force(c: &Constraint, x: &Local, lam: &[f64]) -> f64 {
    let mut jac = Jac::default();
    c.jacobian(x, &mut jac);
    let mut f = [0.0; 2];
    for (r, &l) in lam.iter().enumerate() {
        f[0] -= jac.body[1][r][0] * l;
        f[1] -= jac.body[1][r][1] * l;
    }
    norm(f)
}

/// The unit tangent t′ of a sliding joint and the body (0: i, 1: j) whose
/// frame it is fixed in: a translational joint's axis (body i), a face's
/// direction, else the tangent of the curve of the first contact parameter.
fn tangent(model: &Model, j: usize, c: &Constraint, x: &Local) -> (V2, usize) {
    let unit = |v: V2| {
        let l = norm(v);
        [v[0] / l, v[1] / l]
    };
    if let Constraint::Translational(tr) = c {
        return (unit(tr.v_i), 0);
    }
    let Some(view) = ContactView::of(model, j) else {
        return ([f64::NAN; 2], 0);
    };
    for (side, f) in view.sides.iter().enumerate() {
        if let Feature::Face(u) = f {
            return (unit(*u), side);
        }
    }
    match view.own_curve(0) {
        Some((side, curve)) => (unit(curve.jet(x.own[0]).d1), side),
        None => ([f64::NAN; 2], 0),
    }
}

/// Fixed-point iteration x ← g(x) where g reads only the multipliers
/// `x[off..]`; stops when they settle to [`FIXED_POINT_TOL`].
fn fixed_point(
    t: f64,
    mut g: impl FnMut(&[f64], &mut [f64]),
    x: &mut [f64],
    off: usize,
) -> Result<(), AnalysisError> {
    let mut next = vec![0.0; x.len()];
    let mut change = f64::INFINITY;
    for _ in 0..FIXED_POINT_ITER {
        g(&x[off..], &mut next);
        let big = next[off..].iter().fold(0.0f64, |a, v| a.max(v.abs()));
        change = x[off..]
            .iter()
            .zip(&next[off..])
            .fold(0.0f64, |a, (u, v)| a.max((u - v).abs()));
        x.copy_from_slice(&next);
        if !change.is_finite() {
            break;
        }
        if change <= FIXED_POINT_TOL * (1.0 + big) {
            return Ok(());
        }
    }
    Err(AnalysisError::new(
        Kind::NotConverged,
        t,
        format!(
            "the joint friction and the multipliers it depends on do not settle \
             (last change {}): the friction carries the mechanism's loads \
             (a self-locking mechanism?)",
            crate::fmt_num::num(change)
        ),
    ))
}
