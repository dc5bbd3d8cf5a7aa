//! Assembly: lays out the global coordinates and fills Φ, Φ_q, ν and γ.
//!
//! q = [moving bodies' (x, y, φ)…, joints' own coordinates…]. Equations are
//! stacked joint by joint in model order. Only this module knows global
//! indices; constraints see a [`Local`] view and write per-body blocks.

use crate::constraint::{Equations, Jac, Local, Rows, MAX_OWN, MAX_ROWS};
use crate::model::Model;

/// Where each entry of Φ_q goes, worked out once: per joint, the entries
/// of its [`Jac`] blocks that are in its pattern and their destinations
/// (indices into a matrix's value storage), so that
/// [`fill_jacobian`](Assembly::fill_jacobian) writes each value straight
/// into place.
#[derive(Clone, Debug, Default)]
pub struct JacobianPlan {
    /// (block entry, destination), joint by joint from `start`.
    entries: Vec<(JacEntry, u32)>,
    start: Vec<u32>,
}

/// An entry of a [`Jac`]: `body[k][r][d]` at index 3 MAX_ROWS k + 3r + d for body
/// k = 0, 1, `own[r][d]` at 6 MAX_ROWS + MAX_OWN r + d.
#[derive(Clone, Copy, Debug)]
struct JacEntry(u8);

/// Entries of [`Jac::body`].
const BODY_ENTRIES: usize = 2 * 3 * MAX_ROWS;

impl JacEntry {
    fn new(k: usize, r: usize, d: usize) -> Self {
        JacEntry(if k < 2 {
            3 * MAX_ROWS * k + 3 * r + d
        } else {
            BODY_ENTRIES + MAX_OWN * r + d
        } as u8)
    }

    #[inline]
    fn of(self, jac: &Jac) -> f64 {
        let i = self.0 as usize;
        if i < BODY_ENTRIES {
            jac.body.as_flattened().as_flattened()[i]
        } else {
            jac.own.as_flattened()[i - BODY_ENTRIES]
        }
    }
}

/// Where each body's and joint's coordinates and equations sit.
#[derive(Clone, Debug)]
pub struct Assembly {
    /// Number of coordinates n.
    pub n: usize,
    /// Number of equations m.
    pub m: usize,
    /// First column of each body (`None` for the ground), by body index.
    body_col: Vec<Option<usize>>,
    /// First column of each joint's own coordinates, by joint index.
    own_col: Vec<usize>,
    /// First row of each joint's equations, by joint index.
    row: Vec<usize>,
    /// Number of each joint's equations.
    row_count: Vec<usize>,
    /// For each joint: the first columns of its bodies i and j (`None` for
    /// the ground), and its number of own coordinates.
    joint_cols: Vec<([Option<usize>; 2], usize)>,
    /// Φ_q's structural entries, joint by joint from `entry_start`: the
    /// entry of the joint's [`Jac`] and its (row, column) in Φ_q, in the
    /// order [`jacobian`](Self::jacobian) visits them.
    entries: Vec<(JacEntry, u32, u32)>,
    entry_start: Vec<u32>,
}

impl Assembly {
    pub fn new(model: &Model) -> Self {
        let mut body_col = vec![None; model.bodies.len()];
        let mut n = 0;
        for (id, _) in model.moving_bodies() {
            body_col[id.0] = Some(n);
            n += 3;
        }
        let mut own_col = Vec::with_capacity(model.joints.len());
        let mut row = Vec::with_capacity(model.joints.len());
        let mut m = 0;
        for j in &model.joints {
            own_col.push(n);
            n += j.constraint.own_count();
            row.push(m);
            m += j.constraint.rows();
        }
        let row_count = model.joints.iter().map(|j| j.constraint.rows()).collect();
        let joint_cols = model
            .joints
            .iter()
            .map(|j| {
                let [bi, bj] = j.constraint.bodies();
                ([body_col[bi.0], body_col[bj.0]], j.constraint.own_count())
            })
            .collect();
        // Φ_q's structural entries from each joint's pattern: row by row,
        // body i's (x, y, φ), body j's, then the joint's own columns.
        let mut entries = Vec::new();
        let mut entry_start = Vec::with_capacity(model.joints.len() + 1);
        for (j, joint) in model.joints.iter().enumerate() {
            entry_start.push(entries.len() as u32);
            let c = &joint.constraint;
            let bodies = c.bodies();
            for (r, &row_pattern) in c.jacobian_pattern().iter().enumerate().take(c.rows()) {
                let to = (row[j] + r) as u32;
                for (k, b) in bodies.iter().enumerate() {
                    if let Some(col) = body_col[b.0] {
                        for d in 0..3 {
                            if row_pattern & (1 << (3 * k + d)) != 0 {
                                entries.push((JacEntry::new(k, r, d), to, (col + d) as u32));
                            }
                        }
                    }
                }
                for o in 0..c.own_count() {
                    if row_pattern & (1 << (6 + o)) != 0 {
                        entries.push((JacEntry::new(2, r, o), to, (own_col[j] + o) as u32));
                    }
                }
            }
        }
        entry_start.push(entries.len() as u32);
        Assembly {
            n,
            m,
            body_col,
            own_col,
            row,
            row_count,
            joint_cols,
            entries,
            entry_start,
        }
    }

    /// Joint `j`'s structural entries of Φ_q: (entry of its [`Jac`], row,
    /// column).
    #[inline]
    fn entries_of(&self, j: usize) -> &[(JacEntry, u32, u32)] {
        &self.entries[self.entry_start[j] as usize..self.entry_start[j + 1] as usize]
    }

    /// First column of a body's (x, y, φ), or `None` for the ground.
    pub fn body_col(&self, body: usize) -> Option<usize> {
        self.body_col[body]
    }

    /// First column of joint `j`'s own coordinates.
    pub(crate) fn own_col(&self, j: usize) -> usize {
        self.own_col[j]
    }

    /// Rows of joint `j`'s equations.
    #[inline]
    pub(crate) fn rows_of(&self, j: usize) -> std::ops::Range<usize> {
        self.row[j]..self.row[j] + self.row_count[j]
    }

    /// The joint owning equation `row`, and the equation's index within it.
    pub(crate) fn joint_of_row(&self, row: usize) -> (usize, usize) {
        let j = self.row.partition_point(|&r| r <= row) - 1;
        (j, row - self.row[j])
    }

    /// The body or joint owning coordinate `col`, as a readable name such as
    /// `crank.phi` or `gear.theta`.
    pub fn coordinate_name(&self, model: &Model, col: usize) -> String {
        for (k, c) in self.body_col.iter().enumerate() {
            if let Some(c) = *c {
                if (c..c + 3).contains(&col) {
                    return format!("{}.{}", model.bodies[k].name, ["x", "y", "phi"][col - c]);
                }
            }
        }
        for (j, joint) in model.joints.iter().enumerate() {
            let c = self.own_col[j];
            let names = joint.constraint.own_names();
            if (c..c + joint.constraint.own_count()).contains(&col) {
                let k = col - c;
                let name = names.get(k).copied().unwrap_or("own");
                return format!("{}.{}", joint.name, name);
            }
        }
        format!("coordinate {col}")
    }

    /// True for the coordinates that are angles: bodies' φ and joints' own
    /// coordinates (contact parameters and centre-line angles).
    pub(crate) fn angle_mask(&self, model: &Model) -> Vec<bool> {
        let mut mask = vec![false; self.n];
        for c in self.body_col.iter().flatten() {
            mask[c + 2] = true;
        }
        for (j, joint) in model.joints.iter().enumerate() {
            for k in 0..joint.constraint.own_count() {
                mask[self.own_col[j] + k] = true;
            }
        }
        mask
    }

    /// The local view of joint `j` at (q, q̇, t); `qd` may be empty for
    /// position-only evaluations.
    #[inline]
    pub fn local(&self, _model: &Model, j: usize, q: &[f64], qd: &[f64], t: f64) -> Local {
        let (cols, own) = self.joint_cols[j];
        let mut x = Local {
            t,
            ..Local::default()
        };
        for (k, col) in cols.iter().enumerate() {
            if let Some(c) = *col {
                x.q[k] = [q[c], q[c + 1], q[c + 2]];
                if !qd.is_empty() {
                    x.qd[k] = [qd[c], qd[c + 1], qd[c + 2]];
                }
            }
        }
        let o = self.own_col[j];
        for k in 0..own {
            x.own[k] = q[o + k];
            if !qd.is_empty() {
                x.own_d[k] = qd[o + k];
            }
        }
        x
    }

    /// Joint `j`'s positions at (q, t) into the view `x`: t, its bodies'
    /// (x, y, φ) (zero for the ground) and its own coordinates; the rates
    /// are left as they are.
    #[inline(always)]
    fn set_positions(&self, j: usize, q: &[f64], t: f64, x: &mut Local) {
        let (cols, own) = self.joint_cols[j];
        x.t = t;
        for (k, col) in cols.iter().enumerate() {
            x.q[k] = col.map_or([0.0; 3], |c| [q[c], q[c + 1], q[c + 2]]);
        }
        let o = self.own_col[j];
        // Element by element: a copy of a slice this short calls memcpy.
        x.own = std::array::from_fn(|k| if k < own { q[o + k] } else { 0.0 });
    }

    /// The starting coordinate vector: bodies at their given placement, own
    /// coordinates from the model's guesses refined by each joint.
    pub fn initial_q(&self, model: &Model) -> Vec<f64> {
        let mut q = vec![0.0; self.n];
        for (id, b) in model.moving_bodies() {
            let c = self.body_col[id.0].expect("moving body has columns");
            q[c..c + 3].copy_from_slice(&b.q0);
        }
        for (j, joint) in model.joints.iter().enumerate() {
            let k = joint.constraint.own_count();
            if k == 0 {
                continue;
            }
            let x = self.local(model, j, &q, &[], 0.0);
            let own = joint.constraint.initial_own(&x, joint.own0);
            q[self.own_col[j]..self.own_col[j] + k].copy_from_slice(&own[..k]);
        }
        q
    }

    /// Φ(q, t) into `out` (length m).
    pub fn phi(&self, model: &Model, q: &[f64], t: f64, out: &mut [f64]) {
        let mut rows: Rows = [0.0; 3];
        let mut x = Local::default();
        for (j, joint) in model.joints.iter().enumerate() {
            self.set_positions(j, q, t, &mut x);
            joint.constraint.phi(&x, &mut rows);
            let rows_j = self.rows_of(j);
            out[rows_j.clone()].copy_from_slice(&rows[..rows_j.len()]);
        }
    }

    /// Φ_q(q, t): calls `put(row, col, value)` for every structural entry, in
    /// the same order every time.
    #[inline]
    pub fn jacobian(&self, model: &Model, q: &[f64], t: f64, put: impl FnMut(usize, usize, f64)) {
        self.jacobian_pass(model, q, t, None, put);
    }

    /// Φ(q, t) into `phi` (length m) and Φ_q as [`jacobian`](Self::jacobian)
    /// does, in one pass over the joints.
    #[inline]
    pub(crate) fn phi_and_jacobian(
        &self,
        model: &Model,
        q: &[f64],
        t: f64,
        phi: &mut [f64],
        put: impl FnMut(usize, usize, f64),
    ) {
        self.jacobian_pass(model, q, t, Some(phi), put);
    }

    #[inline]
    fn jacobian_pass(
        &self,
        model: &Model,
        q: &[f64],
        t: f64,
        mut phi: Option<&mut [f64]>,
        mut put: impl FnMut(usize, usize, f64),
    ) {
        let mut jac = Jac::default();
        let mut rows: Rows = [0.0; 3];
        // One view for every joint: the rates stay zero.
        let mut x = Local::default();
        for (j, joint) in model.joints.iter().enumerate() {
            let c = &joint.constraint;
            self.set_positions(j, q, t, &mut x);
            if let Some(out) = phi.as_deref_mut() {
                c.phi_and_jacobian(&x, &mut rows, &mut jac);
                let rows_j = self.rows_of(j);
                out[rows_j.clone()].copy_from_slice(&rows[..rows_j.len()]);
            } else {
                c.jacobian(&x, &mut jac);
            }
            for &(e, r, col) in self.entries_of(j) {
                put(r as usize, col as usize, e.of(&jac));
            }
        }
    }

    /// The plan of Φ_q's entries: `dest(row, col)` is called once for every
    /// structural entry, in the order of [`jacobian`](Self::jacobian), and
    /// gives its destination (None leaves the entry out).
    pub fn jacobian_plan(
        &self,
        model: &Model,
        mut dest: impl FnMut(usize, usize) -> Option<usize>,
    ) -> JacobianPlan {
        let mut plan = JacobianPlan::default();
        for j in 0..model.joints.len() {
            plan.start.push(plan.entries.len() as u32);
            for &(e, r, col) in self.entries_of(j) {
                if let Some(to) = dest(r as usize, col as usize) {
                    plan.entries.push((e, to as u32));
                }
            }
        }
        plan.start.push(plan.entries.len() as u32);
        plan
    }

    /// The local views of every joint at (q, t), velocities zero, into
    /// `locals` (one per joint).
    pub fn gather(&self, _model: &Model, q: &[f64], t: f64, locals: &mut [Local]) {
        for (j, x) in locals.iter_mut().enumerate() {
            self.set_positions(j, q, t, x);
            x.qd = [[0.0; 3]; 2];
            x.own_d = [0.0; MAX_OWN];
        }
    }

    /// Φ_q at the views `locals` ([`gather`](Self::gather)) written by
    /// `plan` into `values`; with `nu`, ν there too, in the same pass.
    pub fn fill_jacobian(
        &self,
        model: &Model,
        plan: &JacobianPlan,
        locals: &[Local],
        values: &mut [f64],
        mut nu: Option<&mut [f64]>,
    ) {
        let mut jac = Jac::default();
        let mut rows: Rows = [0.0; 3];
        for (j, (joint, x)) in model.joints.iter().zip(locals).enumerate() {
            let c = &joint.constraint;
            c.jacobian(x, &mut jac);
            let entries = &plan.entries[plan.start[j] as usize..plan.start[j + 1] as usize];
            for &(e, to) in entries {
                values[to as usize] = e.of(&jac);
            }
            if let Some(out) = nu.as_deref_mut() {
                c.nu(x, &mut rows);
                let rows_j = self.rows_of(j);
                out[rows_j.clone()].copy_from_slice(&rows[..rows_j.len()]);
            }
        }
    }

    /// Joint `j`'s entries of a rate vector `v` (q̇ or q̈): its bodies'
    /// into `bodies` (the ground's left as they are) and its own into `own`.
    #[inline]
    fn rates_into(&self, j: usize, v: &[f64], bodies: &mut [[f64; 3]; 2], own: &mut [f64]) {
        let (cols, n_own) = self.joint_cols[j];
        for (k, col) in cols.iter().enumerate() {
            if let Some(c) = *col {
                bodies[k] = [v[c], v[c + 1], v[c + 2]];
            }
        }
        let o = self.own_col[j];
        own[..n_own].copy_from_slice(&v[o..o + n_own]);
    }

    /// γ at the views `locals` ([`gather`](Self::gather)) with the
    /// velocities `qd`, which are set into the views, into `out`.
    pub fn gamma_at(&self, model: &Model, locals: &mut [Local], qd: &[f64], out: &mut [f64]) {
        let mut rows: Rows = [0.0; 3];
        for (j, (joint, x)) in model.joints.iter().zip(locals.iter_mut()).enumerate() {
            self.rates_into(j, qd, &mut x.qd, &mut x.own_d);
            joint.constraint.gamma(x, &mut rows);
            let rows_j = self.rows_of(j);
            out[rows_j.clone()].copy_from_slice(&rows[..rows_j.len()]);
        }
    }

    /// ν(q, t) into `out`.
    pub fn nu(&self, model: &Model, q: &[f64], t: f64, out: &mut [f64]) {
        let mut rows: Rows = [0.0; 3];
        let mut x = Local::default();
        for (j, joint) in model.joints.iter().enumerate() {
            self.set_positions(j, q, t, &mut x);
            joint.constraint.nu(&x, &mut rows);
            let rows_j = self.rows_of(j);
            out[rows_j.clone()].copy_from_slice(&rows[..rows_j.len()]);
        }
    }

    /// η(q, q̇, q̈, t) into `out`, the right side of Φ_q q⃛ = η.
    pub(crate) fn eta(
        &self,
        model: &Model,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        t: f64,
        out: &mut [f64],
    ) {
        let mut rows: Rows = [0.0; 3];
        for (j, joint) in model.joints.iter().enumerate() {
            let mut x = self.local(model, j, q, qd, t);
            self.rates_into(j, qdd, &mut x.qdd, &mut x.own_dd);
            joint.constraint.eta(&x, &mut rows);
            let rows_j = self.rows_of(j);
            out[rows_j.clone()].copy_from_slice(&rows[..rows_j.len()]);
        }
    }

    /// γ(q, q̇, t) into `out`.
    pub fn gamma(&self, model: &Model, q: &[f64], qd: &[f64], t: f64, out: &mut [f64]) {
        let mut rows: Rows = [0.0; 3];
        for (j, joint) in model.joints.iter().enumerate() {
            let x = self.local(model, j, q, qd, t);
            joint.constraint.gamma(&x, &mut rows);
            let rows_j = self.rows_of(j);
            out[rows_j.clone()].copy_from_slice(&rows[..rows_j.len()]);
        }
    }
}
