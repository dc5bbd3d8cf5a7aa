//! The dynamics assembly: mass matrix, generalized forces and the augmented
//! matrix of the constrained equations, filled into preallocated buffers.
//!
//! The equations of motion of the constrained system (Haug ch. 6) are
//!
//! M(q) q̈ + Φ_qᵀ λ = Q(q, q̇, t),  Φ(q, t) = 0,
//!
//! with Q = Q_g + Q_v + Q_a: gravity, the velocity-quadratic force of
//! bodies whose frame is not at the centroid ([`super::mass`]), and the
//! applied forces ([`super::force`]). Joints' own coordinates (contact
//! parameters) carry no mass and no force.
//!
//! Every analysis solves linear systems with the augmented matrix
//!
//! S = [ D  Φ_qᵀ
//!       Φ_q  0  ],  D = a_M M + a_C ∂R/∂q̇ + a_K ∂R/∂q + a_I I,
//!
//! R = M q̈ − Q + Φ_qᵀλ being the residual of the equations of motion, for
//! coefficients chosen by the analysis (see [`Coefficients`]). Its
//! sparsity pattern (body blocks, force couplings, joint couplings and Φ_q)
//! is laid out once; values are refilled in place.
//!
//! S is singular wherever Φ_q loses rank: at singular positions (the flat
//! position of a parallelogram, a toggle) and, everywhere, in a model with
//! redundant equations. When the factorization of S finds it singular, the
//! regularised matrix is factored instead:
//!
//! S_ε = [ D  Φ_qᵀ
//!         Φ_q  −ε I ],
//!
//! the augmented Lagrangian form (Bayo & Ledesma 1996): eliminating the
//! multipliers gives D + Φ_qᵀΦ_q/ε, the penalty 1/ε on the constraints.
//! With D positive definite on the motions the constraints allow, S_ε is
//! nonsingular whatever the rank of Φ_q. ε is set per factorization to
//! [`EPS_REL`] · max(d, j²/d), d the largest diagonal entry of D and j the
//! largest entry of Φ_q: S_ε⁻¹ S then differs from the identity by about
//! ε/σ² in a constraint direction whose singular value of
//! Φ_q D^{-1/2} is σ, some 1e-8 in a healthy direction, and by ≈ 1 in
//! a direction that is lost (σ = 0), where the multipliers are not
//! determined. Near, not at, a singular position S itself is factored:
//! S_ε would converge as slowly as 1 − σ²/ε there. Newton iterations
//! on the exact residual absorb the difference (each iteration is one
//! augmented-Lagrangian update of λ); one-shot solves use
//! [`Augmented::solve_refined`], which iterates S_ε x_{k+1} = b − (S − S_ε) x_k
//! and converges to the solution of S x = b with the multipliers'
//! component in the null space of Φ_qᵀ (not determined by the equations)
//! left at zero: the minimum-norm multipliers.

use std::collections::HashMap;

use super::friction::JointFrictions;
use super::mass::Inertia;
use crate::assembly::Assembly;
use crate::constraint::{Equations, Jac, Local, Rows, LOCAL_COORDS, MAX_ROWS};
use crate::force::BodyJac;
use crate::force::{Applied, BodyQ, ForceJac, Reads, MAX_READ};
use crate::linsolve::{SetupError, Singular, SystemMatrix};
use crate::model::Model;
use crate::run::{AnalysisError, Kind};

/// The regularisation ε of the multiplier block relative to
/// max(d, j²/d) (see the module documentation).
pub const EPS_REL: f64 = 1e-8;

/// Passes of [`Augmented::solve_refined`]: each reduces the error in a
/// healthy direction by about [`EPS_REL`].
const REFINE: usize = 3;

/// The model with its layout and the inertia of each body.
pub struct System<'m> {
    pub model: &'m Model,
    pub asm: Assembly,
    /// (first column, inertia) of each moving body.
    bodies: Vec<(usize, Inertia)>,
    /// The joints with Coulomb friction ([`super::friction`]).
    pub friction: JointFrictions,
}

impl<'m> System<'m> {
    pub fn new(model: &'m Model) -> Self {
        let asm = Assembly::new(model);
        let bodies = model
            .moving_bodies()
            .map(|(id, b)| (asm.body_col(id.0).expect("moving body"), Inertia::from(b)))
            .collect();
        let friction = JointFrictions::new(model);
        System {
            model,
            asm,
            bodies,
            friction,
        }
    }

    /// Number of coordinates n.
    pub fn n(&self) -> usize {
        self.asm.n
    }

    /// Number of constraint equations m.
    pub fn m(&self) -> usize {
        self.asm.m
    }

    /// The local view of force `f` at (q, q̇, t).
    #[inline]
    pub fn force_local(&self, f: usize, q: &[f64], qd: &[f64], t: f64) -> Local {
        let mut x = Local {
            t,
            ..Local::default()
        };
        for (k, b) in self.model.forces[f].kind.bodies().iter().enumerate() {
            if let Some(c) = self.asm.body_col(b.0) {
                x.q[k].copy_from_slice(&q[c..c + 3]);
                x.qd[k].copy_from_slice(&qd[c..c + 3]);
            }
        }
        x
    }

    /// The state of the bodies force `f` reads besides its own, at (q, q̇).
    #[inline]
    pub fn force_reads(&self, f: usize, q: &[f64], qd: &[f64]) -> Reads {
        let mut r = Reads::default();
        for (k, b) in self.model.forces[f].kind.reads().iter().enumerate() {
            if let Some(c) = self.asm.body_col(b.0) {
                r.q[k].copy_from_slice(&q[c..c + 3]);
                r.qd[k].copy_from_slice(&qd[c..c + 3]);
            }
        }
        r
    }

    /// Q(q, q̇, t) = Q_g + Q_v + Q_a into `out` (length n); an error of
    /// kind `force_failed` when a user force function fails.
    pub fn forces(
        &self,
        q: &[f64],
        qd: &[f64],
        t: f64,
        out: &mut [f64],
    ) -> Result<(), AnalysisError> {
        out.fill(0.0);
        let g = self.model.gravity;
        for &(c, inertia) in &self.bodies {
            let l = inertia.loads(body(q, c), body(qd, c), g);
            out[c..c + 3].copy_from_slice(&l);
        }
        self.add_applied(q, qd, t, 1.0, out)
    }

    /// `out += w Q_a`, the applied forces times w.
    fn add_applied(
        &self,
        q: &[f64],
        qd: &[f64],
        t: f64,
        w: f64,
        out: &mut [f64],
    ) -> Result<(), AnalysisError> {
        let mut qf = BodyQ::default();
        for (f, force) in self.model.forces.iter().enumerate() {
            let x = self.force_local(f, q, qd, t);
            let r = self.force_reads(f, q, qd);
            force
                .kind
                .generalized_reading(&x, &r, &mut qf)
                .map_err(|e| {
                    AnalysisError::new(
                        Kind::ForceFailed,
                        t,
                        format!("force '{}' failed: {e}", force.name),
                    )
                })?;
            for (k, b) in force.kind.bodies().iter().enumerate() {
                if let Some(c) = self.asm.body_col(b.0) {
                    for d in 0..3 {
                        out[c + d] += w * qf[k][d];
                    }
                }
            }
        }
        Ok(())
    }

    /// `out += M(q) v` (length n).
    pub fn add_mass_times(&self, q: &[f64], v: &[f64], out: &mut [f64]) {
        for &(c, inertia) in &self.bodies {
            let mm = inertia.matrix(q[c + 2]);
            for r in 0..3 {
                out[c + r] += mm[r][0] * v[c] + mm[r][1] * v[c + 1] + mm[r][2] * v[c + 2];
            }
        }
    }

    /// `out += Φ_qᵀ λ` (length n).
    pub fn add_jt_lambda(&self, q: &[f64], t: f64, lambda: &[f64], out: &mut [f64]) {
        self.asm
            .jacobian(self.model, q, t, |r, c, v| out[c] += v * lambda[r]);
    }

    /// R = M q̈ − Q − Q_f(λ) + Φ_qᵀλ, the residual of the equations of
    /// motion with the joint friction Q_f at λ ([`super::friction`]), into
    /// `out` (length n).
    pub fn residual(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        lambda: &[f64],
        t: f64,
        out: &mut [f64],
    ) -> Result<(), AnalysisError> {
        self.motion_residual(q, qd, qdd, t, out)?;
        self.add_jt_lambda(q, t, lambda, out);
        self.friction
            .add(self.model, &self.asm, q, qd, lambda, t, -1.0, out);
        Ok(())
    }

    /// R as [`residual`](Self::residual) into `out` (length n), and Φ(q, t)
    /// into `phi` (length m), in one pass over the joints.
    #[allow(clippy::too_many_arguments)]
    pub fn residual_and_phi(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        lambda: &[f64],
        t: f64,
        out: &mut [f64],
        phi: &mut [f64],
    ) -> Result<(), AnalysisError> {
        self.motion_residual(q, qd, qdd, t, out)?;
        self.asm
            .phi_and_jacobian(self.model, q, t, phi, |r, c, v| out[c] += v * lambda[r]);
        self.friction
            .add(self.model, &self.asm, q, qd, lambda, t, -1.0, out);
        Ok(())
    }

    /// M q̈ − Q into `out`.
    fn motion_residual(
        &self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        t: f64,
        out: &mut [f64],
    ) -> Result<(), AnalysisError> {
        out.fill(0.0);
        let g = self.model.gravity;
        for &(c, inertia) in &self.bodies {
            let r = inertia.residual(body(q, c), body(qd, c), body(qdd, c), g);
            out[c..c + 3].copy_from_slice(&r);
        }
        self.add_applied(q, qd, t, -1.0, out)
    }

    /// Kinetic energy T = ½ q̇ᵀ M q̇ (J).
    pub fn kinetic(&self, q: &[f64], qd: &[f64]) -> f64 {
        self.bodies
            .iter()
            .map(|&(c, i)| i.kinetic(body(q, c), body(qd, c)))
            .sum()
    }

    /// Potential energy of gravity and springs (J), zero with every body
    /// frame at the origin and every spring at its free length.
    pub fn potential(&self, q: &[f64], t: f64) -> f64 {
        let g = self.model.gravity;
        let gravity: f64 = self
            .bodies
            .iter()
            .map(|&(c, i)| i.potential(body(q, c), g))
            .sum();
        let springs: f64 = (0..self.model.forces.len())
            .map(|f| {
                // Positions only: the velocities are set to zero.
                let x = Local {
                    qd: Local::default().qd,
                    ..self.force_local(f, q, q, t)
                };
                self.model.forces[f].kind.potential(&x)
            })
            .sum();
        gravity + springs
    }
}

/// `vals −= k.scale (k.stiffness ∂Q/∂q + k.damping ∂Q/∂q̇)` over one
/// 3 × 3 block (R has −Q).
fn add_block(
    vals: &mut [f64],
    slots: [usize; 9],
    dq: &[[f64; 3]; 3],
    dqd: &[[f64; 3]; 3],
    k: Coefficients,
) {
    for r in 0..3 {
        for col in 0..3 {
            vals[slots[3 * r + col]] -=
                k.scale * (k.stiffness * dq[r][col] + k.damping * dqd[r][col]);
        }
    }
}

/// [`add_block`] over the blocks `slots` of one force or friction on a
/// pair of bodies.
fn add_pair(vals: &mut [f64], slots: &PairSlots, dq: &BodyJac, dqd: &BodyJac, k: Coefficients) {
    for a in 0..2 {
        for b in 0..2 {
            if let Some(slots) = slots[a][b] {
                add_block(vals, slots, &dq[a][b], &dqd[a][b], k);
            }
        }
    }
}

/// (x, y, φ) of the body whose first column is `c`.
#[inline]
fn body(v: &[f64], c: usize) -> [f64; 3] {
    [v[c], v[c + 1], v[c + 2]]
}

/// Coefficients of D = a_M M + a_C ∂R/∂q̇ + a_K ∂R/∂q + a_I I, all of them
/// multiplied by `scale` (the identity term excepted).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Coefficients {
    pub mass: f64,
    pub damping: f64,
    pub stiffness: f64,
    pub identity: f64,
    pub scale: f64,
}

/// The augmented matrix S, its pattern and its factorization.
pub struct Augmented {
    n: usize,
    m: usize,
    sys: SystemMatrix,
    pattern: Vec<(usize, usize)>,
    /// Where each entry of the pattern goes in the system matrix's values
    /// ([`SystemMatrix::slot`]).
    dest: Vec<usize>,
    /// Values of the pattern's entries, then one trash slot that takes
    /// entries known to be zero.
    vals: Vec<f64>,
    /// Slots of each moving body's 3 × 3 block, row-major.
    body_slots: Vec<[usize; 9]>,
    /// Slots of each own coordinate's diagonal entry.
    own_slots: Vec<usize>,
    /// Per force, per (a, b) body pair, the 3 × 3 block's slots (None for ground).
    force_slots: Vec<PairSlots>,
    /// The same for each joint friction.
    friction_slots: Vec<PairSlots>,
    /// Per force, per body a ∈ {i, j} and read body k, the 3 × 3 block's
    /// slots of ∂Q_a/∂q_k (None for the ground or past the reads).
    read_slots: Vec<[[Option<[usize; 9]>; MAX_READ]; 2]>,
    /// Per joint: the local coordinates its Φ is nonlinear in (local
    /// index, global column) and the slots of their L × L curvature block,
    /// row-major.
    joint_slots: Vec<JointSlots>,
    /// Slots (lower Φ_q, upper Φ_qᵀ) of each Jacobian entry, in fill order.
    jac_slots: Vec<(usize, usize)>,
    /// Slots of the multiplier block's diagonal, which holds −ε.
    mult_slots: Vec<usize>,
    /// ε of the last factorization.
    eps: f64,
    /// Factor S_ε at once, S being known singular (redundant equations).
    regularised: bool,
    /// Scratch for [`solve_refined`](Self::solve_refined).
    work: [Vec<f64>; 2],
    /// Scratch for (Φ_qᵀλ)_q.
    jac: [Jac; 2],
}

/// Per (a, b) body pair of a force, the slots of its 3 × 3 block (None
/// for the ground).
type PairSlots = [[Option<[usize; 9]>; 2]; 2];

/// A joint's nonlinear local coordinates (local index, global column) and
/// the slots of its curvature block.
type JointSlots = (Vec<(usize, usize)>, Vec<usize>);

/// Marks a block entry known to be zero, until the trash slot exists.
const TRASH: usize = usize::MAX;

/// Local coordinate index k of a joint: 0–2 body i, 3–5 body j, 6+ own.
const OWN0: usize = 6;

impl Augmented {
    pub fn new(s: &System, q: &[f64]) -> Result<Self, SetupError> {
        let (n, m) = (s.n(), s.m());
        let mut map: HashMap<(usize, usize), usize> = HashMap::new();
        let mut pattern = Vec::new();
        let mut slot = |r: usize, c: usize| -> usize {
            *map.entry((r, c)).or_insert_with(|| {
                pattern.push((r, c));
                pattern.len() - 1
            })
        };
        let block = |slot: &mut dyn FnMut(usize, usize) -> usize, ra: usize, cb: usize| {
            let mut b = [0; 9];
            for r in 0..3 {
                for c in 0..3 {
                    b[3 * r + c] = slot(ra + r, cb + c);
                }
            }
            b
        };
        // A centred body's block is diagonal; its off-diagonal entries,
        // always zero, go to the trash slot.
        let mut body_slots: Vec<[usize; 9]> = s
            .bodies
            .iter()
            .map(|&(c, inertia)| {
                if inertia.centred() {
                    std::array::from_fn(|k| {
                        let (r, col) = (k / 3, k % 3);
                        if r == col {
                            slot(c + r, c + r)
                        } else {
                            TRASH
                        }
                    })
                } else {
                    block(&mut slot, c, c)
                }
            })
            .collect();
        let mut own_slots = Vec::new();
        for j in 0..s.model.joints.len() {
            let o = s.asm.own_col(j);
            for k in 0..s.model.joints[j].constraint.own_count() {
                own_slots.push(slot(o + k, o + k));
            }
        }
        let mut pair_slots = |bodies: [crate::constraint::BodyId; 2]| {
            let cols = bodies.map(|b| s.asm.body_col(b.0));
            let mut out: PairSlots = [[None; 2]; 2];
            for a in 0..2 {
                for b in 0..2 {
                    if let (Some(ca), Some(cb)) = (cols[a], cols[b]) {
                        out[a][b] = Some(block(&mut slot, ca, cb));
                    }
                }
            }
            out
        };
        let force_slots = s
            .model
            .forces
            .iter()
            .map(|f| pair_slots(f.kind.bodies()))
            .collect();
        let friction_slots = s
            .friction
            .joints()
            .map(|j| pair_slots(s.model.joints[j].constraint.bodies()))
            .collect();
        let read_slots = s
            .model
            .forces
            .iter()
            .map(|f| {
                let cols = f.kind.bodies().map(|b| s.asm.body_col(b.0));
                let mut out = [[None; MAX_READ]; 2];
                for (k, b) in f.kind.reads().iter().enumerate() {
                    for a in 0..2 {
                        if let (Some(ca), Some(cb)) = (cols[a], s.asm.body_col(b.0)) {
                            out[a][k] = Some(block(&mut slot, ca, cb));
                        }
                    }
                }
                out
            })
            .collect();
        let joint_slots = (0..s.model.joints.len())
            .map(|j| {
                let c = &s.model.joints[j].constraint;
                let nonlinear = c.nonlinear();
                let mut local = Vec::new();
                for (k, b) in c.bodies().iter().enumerate() {
                    if let Some(col) = s.asm.body_col(b.0) {
                        for d in 0..3 {
                            local.push((3 * k + d, col + d));
                        }
                    }
                }
                for o in 0..c.own_count() {
                    local.push((OWN0 + o, s.asm.own_col(j) + o));
                }
                local.retain(|&(k, _)| nonlinear & (1 << k) != 0);
                let mut slots = Vec::with_capacity(local.len() * local.len());
                for &(_, r) in &local {
                    for &(_, col) in &local {
                        slots.push(slot(r, col));
                    }
                }
                (local, slots)
            })
            .collect();
        let mut jac_slots = Vec::new();
        s.asm.jacobian(s.model, q, 0.0, |r, c, _| {
            jac_slots.push((slot(n + r, c), slot(c, n + r)));
        });
        // The multiplier block's diagonal, −ε.
        let mult_slots: Vec<usize> = (0..m).map(|r| slot(n + r, n + r)).collect();
        let sys = SystemMatrix::try_new(n + m, &pattern)?;
        let dest = pattern
            .iter()
            .enumerate()
            .map(|(k, &(r, c))| sys.slot(k, r, c))
            .collect();
        let vals = vec![0.0; pattern.len() + 1];
        let trash = vals.len() - 1;
        for b in &mut body_slots {
            for k in b.iter_mut().filter(|k| **k == TRASH) {
                *k = trash;
            }
        }
        Ok(Augmented {
            n,
            m,
            vals,
            sys,
            pattern,
            dest,
            body_slots,
            own_slots,
            force_slots,
            friction_slots,
            read_slots,
            joint_slots,
            jac_slots,
            mult_slots,
            eps: 0.0,
            regularised: false,
            work: [vec![0.0; n + m], vec![0.0; n + m]],
            jac: [Jac::default(); 2],
        })
    }

    /// Dimension n + m.
    pub fn dim(&self) -> usize {
        self.n + self.m
    }

    /// Fills S at (q, q̇, q̈, λ, t) with the coefficients `k` and factors it.
    /// The curvature (Φ_qᵀλ)_q enters with `k.stiffness` when `lambda` is
    /// given.
    #[allow(clippy::too_many_arguments)]
    pub fn refactor(
        &mut self,
        s: &System,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        lambda: Option<&[f64]>,
        t: f64,
        k: Coefficients,
    ) -> Result<(), Singular> {
        self.vals.fill(0.0);
        let g = s.model.gravity;
        // Body blocks: a_M M + a_K ∂R/∂q + a_C ∂R/∂q̇ + a_I I.
        for (b, &(c, inertia)) in s.bodies.iter().enumerate() {
            let slots = &self.body_slots[b];
            let mm = inertia.matrix(q[c + 2]);
            let (dphi, domega) = inertia.derivatives(body(q, c), body(qd, c), body(qdd, c), g);
            for r in 0..3 {
                for col in 0..3 {
                    self.vals[slots[3 * r + col]] += k.scale * k.mass * mm[r][col];
                }
                self.vals[slots[3 * r + 2]] +=
                    k.scale * (k.stiffness * dphi[r] + k.damping * domega[r]);
                self.vals[slots[3 * r + r]] += k.identity;
            }
        }
        for &o in &self.own_slots {
            self.vals[o] += k.identity;
        }
        // Applied forces: R has −Q.
        let mut jac = ForceJac::default();
        for (f, force) in s.model.forces.iter().enumerate() {
            let x = s.force_local(f, q, qd, t);
            let reads = s.force_reads(f, q, qd);
            force.kind.derivatives_reading(&x, &reads, &mut jac);
            add_pair(&mut self.vals, &self.force_slots[f], &jac.dq, &jac.dqd, k);
            for a in 0..2 {
                for r in 0..force.kind.reads().len() {
                    if let Some(slots) = self.read_slots[f][a][r] {
                        add_block(&mut self.vals, slots, &jac.rq[a][r], &jac.rqd[a][r], k);
                    }
                }
            }
        }
        // Joint friction at λ: R has −Q_f.
        if let Some(lambda) = lambda {
            for (f, slots) in self.friction_slots.iter().enumerate() {
                s.friction.derivatives(
                    s.model,
                    &s.asm,
                    f,
                    q,
                    qd,
                    lambda,
                    t,
                    &mut jac.dq,
                    &mut jac.dqd,
                );
                add_pair(&mut self.vals, slots, &jac.dq, &jac.dqd, k);
            }
        }
        // Constraint curvature (Φ_qᵀλ)_q, by central differences of the
        // analytic Jacobian blocks, joint by joint.
        if let (Some(lambda), true) = (lambda, k.stiffness != 0.0) {
            for j in 0..s.model.joints.len() {
                self.curvature(s, j, q, lambda, t, k.scale * k.stiffness);
            }
        }
        // Φ_q below, Φ_qᵀ to the right.
        let (vals, slots) = (&mut self.vals, &self.jac_slots);
        let mut e = 0;
        let mut jmax = 0.0f64;
        s.asm.jacobian(s.model, q, t, |_, _, v| {
            let (lo, up) = slots[e];
            vals[lo] = v;
            vals[up] = v;
            jmax = jmax.max(v.abs());
            e += 1;
        });
        // −ε on the multiplier block's diagonal.
        let diag = self.body_slots.iter().flat_map(|b| [b[0], b[4], b[8]]);
        let dmax = diag
            .chain(self.own_slots.iter().copied())
            .fold(0.0f64, |a, k| a.max(self.vals[k].abs()));
        // S itself when it is nonsingular, else S_ε.
        self.eps = 0.0;
        if !self.regularised && self.put_and_factor().is_ok() {
            return Ok(());
        }
        self.eps = if dmax > 0.0 && jmax > 0.0 {
            EPS_REL * dmax.max(jmax * jmax / dmax)
        } else {
            EPS_REL * jmax.max(1.0)
        };
        self.put_and_factor()
    }

    /// Puts −ε on the multiplier block's diagonal, hands the values to the
    /// system matrix and factors it.
    fn put_and_factor(&mut self) -> Result<(), Singular> {
        for &k in &self.mult_slots {
            self.vals[k] = -self.eps;
        }
        let values = self.sys.values_mut();
        for (&d, &v) in self.dest.iter().zip(&self.vals) {
            values[d] = v;
        }
        self.sys.factor()
    }

    /// Factors S_ε always, for a model whose equations are known to be
    /// redundant (S is singular everywhere; a sparse LU need not notice).
    pub fn set_regularised(&mut self, on: bool) {
        self.regularised = on;
    }

    /// ε of the last factorization: 0 when S was nonsingular.
    pub fn eps(&self) -> f64 {
        self.eps
    }

    /// Adds `w (Φ^jᵀ λ_j)_q` of joint `j` to its curvature block: the
    /// constraint's own when it has one, else central differences of its
    /// analytic Jacobian.
    fn curvature(&mut self, s: &System, j: usize, q: &[f64], lambda: &[f64], t: f64, w: f64) {
        let c = &s.model.joints[j].constraint;
        let rows = s.asm.rows_of(j);
        let lam = &lambda[rows];
        let x0 = s.asm.local(s.model, j, q, &[], t);
        let (local, slots) = &self.joint_slots[j];
        let l = local.len();
        let mut lam_rows: Rows = [0.0; MAX_ROWS];
        lam_rows[..lam.len()].copy_from_slice(lam);
        let mut block = [[0.0; LOCAL_COORDS]; LOCAL_COORDS];
        if c.curvature(&x0, &lam_rows, &mut block) {
            for (ka, &(a, _)) in local.iter().enumerate() {
                for (kb, &(b, _)) in local.iter().enumerate() {
                    self.vals[slots[ka * l + kb]] += w * block[a][b];
                }
            }
            return;
        }
        let h = 1e-6;
        for (kb, &(kk, _)) in local.iter().enumerate() {
            for (sign, jac) in [(1.0, 0), (-1.0, 1)] {
                let mut x = x0;
                let v = if kk < OWN0 {
                    &mut x.q[kk / 3][kk % 3]
                } else {
                    &mut x.own[kk - OWN0]
                };
                *v += sign * h;
                c.jacobian(&x, &mut self.jac[jac]);
            }
            for (ka, &(k, _)) in local.iter().enumerate() {
                let mut d = 0.0;
                for (r, &lr) in lam.iter().enumerate() {
                    let (p, m) = if k < OWN0 {
                        (
                            self.jac[0].body[k / 3][r][k % 3],
                            self.jac[1].body[k / 3][r][k % 3],
                        )
                    } else {
                        (self.jac[0].own[r][k - OWN0], self.jac[1].own[r][k - OWN0])
                    };
                    d += lr * (p - m);
                }
                self.vals[slots[ka * l + kb]] += w * d / (2.0 * h);
            }
        }
    }

    /// Solves S_ε x = b in place with the last factorization: one Newton
    /// (augmented-Lagrangian) update.
    #[inline]
    pub fn solve(&mut self, b: &mut [f64]) {
        self.sys.solve(b);
    }

    /// Solves S x = b (the matrix without ε) in place by iterating on the
    /// last factorization of S_ε; the multipliers come out with no
    /// component in the null space of Φ_qᵀ.
    pub fn solve_refined(&mut self, b: &mut [f64]) {
        let [rhs, x] = &mut self.work;
        rhs.copy_from_slice(b);
        x.fill(0.0);
        for _ in 0..REFINE {
            // b ← rhs − S x, then x += S_ε⁻¹ b.
            b.copy_from_slice(rhs);
            for (&(r, c), &v) in self.pattern.iter().zip(&self.vals) {
                b[r] -= v * x[c];
            }
            for r in self.n..self.n + self.m {
                b[r] -= self.eps * x[r];
            }
            self.sys.solve(b);
            for (xk, bk) in x.iter_mut().zip(b.iter()) {
                *xk += bk;
            }
        }
        b.copy_from_slice(x);
    }

    /// The smallest pivot of the last factorization relative to the
    /// largest entry, or its estimate for the sparse kernel
    /// ([`crate::linsolve::SystemMatrix::min_pivot`]).
    pub fn min_pivot(&self) -> Option<f64> {
        self.sys.min_pivot()
    }

    pub fn is_valid(&self) -> bool {
        self.sys.is_valid()
    }

    pub fn invalidate(&mut self) {
        self.sys.invalidate();
    }
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;
    use std::sync::Arc;

    use super::*;
    use crate::force::state::{Channel, StateExpr, StateForce, READ_SLOT};
    use crate::force::Force;
    use crate::model::Body;
    use crate::model::BodyId;
    use camlink_expr::Expr;

    /// Three free bodies; a force of state on body 1 that reads bodies 2
    /// and 3 besides its own.
    fn model() -> Model {
        let mut m = Model::new("reads");
        for k in 1..=3 {
            let mut b = Body::new(format!("b{k}"), [0.1 * k as f64, -0.2, 0.3 * k as f64]);
            b.mass = 1.0;
            b.inertia = 0.5;
            b.qd0 = [0.2, -0.1 * k as f64, 0.4];
            m.add_body(b);
        }
        let names = ["x1", "phi2", "w3", "p3y"];
        let channels = vec![
            Channel::Body {
                slot: 0,
                c: 0,
                rate: false,
            },
            Channel::Body {
                slot: READ_SLOT,
                c: 2,
                rate: false,
            },
            Channel::Body {
                slot: READ_SLOT + 1,
                c: 2,
                rate: true,
            },
            Channel::Point {
                slot: READ_SLOT + 1,
                s: [0.3, 0.1],
                axis: 1,
                rate: false,
            },
        ];
        let part = |src: &str| {
            Some(StateExpr {
                expr: Arc::new(Expr::parse_inputs(src, &names, &HashMap::new()).unwrap()),
                channels: channels.clone(),
            })
        };
        m.add_force(Force::new(
            "f",
            StateForce {
                reads: vec![BodyId(2), BodyId(3)],
                body_i: BodyId(1),
                s_i: [0.2, 0.1],
                body_j: BodyId::GROUND,
                s_j: [0.0; 2],
                f: [part("-3*sin(phi2)*w3 + x1^2"), part("p3y*w3 - phi2")],
                torque: part("phi2*x1 + 0.5*w3"),
                local: false,
            },
        ));
        m
    }

    #[test]
    fn issue30_the_matrix_holds_the_read_bodies_columns() {
        let m = model();
        let s = System::new(&m);
        let n = s.n();
        let q: Vec<f64> = (0..n).map(|k| 0.1 + 0.37 * k as f64).collect();
        let qd: Vec<f64> = (0..n).map(|k| 0.3 - 0.21 * k as f64).collect();
        let t = 0.2;
        let mut aug = Augmented::new(&s, &q).unwrap();
        // D = ∂R/∂q with R = M q̈ − Q: the stiffness block alone, then
        // the damping block alone.
        for (stiffness, damping) in [(1.0, 0.0), (0.0, 1.0)] {
            let k = Coefficients {
                mass: 0.0,
                damping,
                stiffness,
                identity: 0.0,
                scale: 1.0,
            };
            let _ = aug.refactor(&s, &q, &qd, &vec![0.0; n], None, t, k);
            let entry = |r: usize, c: usize| {
                aug.pattern
                    .iter()
                    .position(|&p| p == (r, c))
                    .map_or(0.0, |k| aug.vals[k])
            };
            let h = 1e-6;
            let mut checked = 0;
            for c in 0..n {
                let forces = |dh: f64| {
                    let (mut q, mut qd) = (q.clone(), qd.clone());
                    if stiffness != 0.0 {
                        q[c] += dh;
                    } else {
                        qd[c] += dh;
                    }
                    let mut out = vec![0.0; n];
                    s.forces(&q, &qd, t, &mut out).unwrap();
                    out
                };
                let (qp, qm) = (forces(h), forces(-h));
                for r in 0..n {
                    let fd = -(qp[r] - qm[r]) / (2.0 * h);
                    let an = entry(r, c);
                    assert!(
                        (fd - an).abs() <= 1e-6 * (1.0 + fd.abs()),
                        "d R[{r}] / d {}[{c}]: {an} vs {fd}",
                        if stiffness != 0.0 { "q" } else { "qd" }
                    );
                    checked += usize::from(fd.abs() > 1e-3);
                }
            }
            // Body 1's rows depend on bodies 2 and 3: f_x on φ₂ (column 5)
            // and φ̇₃ (column 8).
            assert!(checked >= 3, "{checked}");
            let column = if stiffness != 0.0 { 5 } else { 8 };
            assert!(entry(0, column).abs() > 1e-3, "{}", entry(0, column));
        }
    }
}
