//! Branch rows: following one branch of the motion through a bifurcation
//! point, where Φ_q loses rank and two branches of Φ = 0 cross (the flat
//! position of a parallelogram four-bar and its crossed twin).
//!
//! Near such a point, at a distance δ from it, a lost equation
//! f = wᵀΦ (w the left singular vector of Φ_q whose singular value falls
//! as δ) is a product of two factors to leading order, one vanishing on
//! each branch: f ≈ ℓ(q) m(q). Its gradient is of order δ, its roots on
//! the two branches are of order δ apart, and evaluated in floating point
//! its zero set is known only to about ε_mach/δ: within about 1e-8 rad of
//! the point the equations themselves no longer say which branch the
//! mechanism is on, and its multipliers, of order 1/δ, are lost in the
//! rounding. A mechanism that comes to rest there (released at rest at the
//! flat position, or turning at rest on it) has no speed to carry it along
//! its branch either.
//!
//! Inside a small window around the point the lost equations are
//! therefore joined by their factors that vanish on the followed branch,
//! k linear rows A (one per lost rank) with A t = 0 for the branch
//! tangent t, enforced as A (q − q_n) = 0 from the start q_n of each step:
//! well-conditioned rows whose multipliers μ are the finite forces that
//! hold the branch. The rows follow from the second-order part of Φ on
//! the kernel K of the lost directions (basis V, the right singular
//! vectors of the small singular values and the null space): with
//! G_w = Vᵀ (wᵀΦ)_qq V, the branch tangents y (t = V y) are the common
//! roots of the quadratic forms yᵀ G_w y, and for a transversal crossing
//! the factor of yᵀ G_w y that vanishes on t is (G_w y)ᵀ, so
//! A = rows (V G_w y)ᵀ. The tangent is found by Gauss–Newton on those
//! forms from the direction of the motion (the velocity, or at rest the
//! acceleration the loads give), so the branch followed is the one
//! nearest to the motion: the one a slightly compliant mechanism would
//! follow. The cone's root is the tangent of the point itself; as the
//! motion leaves the point (σ_rel, below, above [`NULL_TANGENT`]) the
//! rows are orthogonal instead to the branch's own tangent at q, Φ_q's
//! null direction, which the root picks out ([`branch_tangent`]).
//!
//! The rows are found anew after every step inside the window, from the
//! tangent of the step before, so A_n (q − q_n) = 0 holds along the
//! branch to second order in the step's own length (the branch is curved);
//! past the window the full equations alone hold the state on the branch.
//! Inside the window the rows take the place of the lost equations: the
//! integrator leaves their residual wᵀΦ out of the Newton iteration, since
//! they hold along the branch only to the rows' linearisation. The window
//! is entered when a step of a slowly moving mechanism ends with σ_rel, the
//! smallest lost singular value of Φ_q over the largest, below [`WINDOW`]
//! (or when Newton fails near a lost rank), and left when σ_rel rises above
//! [`WINDOW_EXIT`]: at σ_rel = 1e-5 the branches are far enough apart for
//! Φ to tell them apart (their distance, of order σ_rel, is well above the
//! rounding of Φ over it), and the multipliers of order 1/σ_rel are
//! resolved.

use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Scale};

use super::system::System;
use crate::diagnose::dense_jacobian;
use crate::linsolve::SparseLu;
use crate::math::{inner, norm2};

/// Singular values of Φ_q below this fraction of the largest count as
/// lost directions.
const LOST: f64 = 1e-3;

/// A step that ends with the smallest lost singular value below this
/// fraction of the largest starts using the rows.
pub(crate) const WINDOW: f64 = 1e-5;

/// Once in use, the rows are left when that value rises above this.
pub(crate) const WINDOW_EXIT: f64 = 4.0 * WINDOW;

/// Where the smallest lost singular value over the largest is above
/// this and the motion leaves the point, the tangent is Φ_q's own null
/// direction rather than the cone's root ([`branch_tangent`]).
pub(crate) const NULL_TANGENT: f64 = 2e-6;

/// Relative step of the central differences of Φ_q along the kernel.
const DIFF: f64 = 1e-5;

/// The tangent's iteration may end where its residual, relative to the
/// largest entry of G, stops falling below this (the noise of the
/// differences; see [`tangent_on_cone`]).
const STALL: f64 = 1e-9;

/// Largest residual of a refined pair of subspaces, ‖Φ_q V − W Σ‖ and
/// ‖Φ_qᵀ W − V Σ‖ per column, relative to σ_max, for [`analyse_from`] to
/// use them (a dense decomposition's is some 1e-15).
const REFINED: f64 = 1e-11;

/// Subspace iterations [`analyse_from`] takes at most before it falls
/// back to a dense decomposition.
const REFINE_ITER: usize = 4;

/// Power iterations for σ_max from the last analysis' right vector.
const POWER_ITER: usize = 3;

/// The lost singular subspaces of Φ_q at one position: what an analysis
/// at a nearby position starts from.
pub(crate) struct Subspaces {
    /// The lost left singular vectors W, m × k.
    w: Mat<f64>,
    /// The kernel basis V, n × d: the lost right singular vectors (the
    /// first k columns, in W's order), then the null space of Φ_q.
    v: Mat<f64>,
    /// The lost singular values σ (k).
    sigma: Vec<f64>,
    /// The largest singular value σ_max of Φ_q and its right vector.
    smax: f64,
    top: Vec<f64>,
}

/// The branch rows at a position near a bifurcation point.
pub(crate) struct BranchRows {
    /// Number of rows k (lost ranks).
    pub k: usize,
    /// The rows A, k × n row-major, orthonormal, each with A t = 0.
    pub a: Vec<f64>,
    /// The branch tangent t (unit, n).
    pub tangent: Vec<f64>,
    /// The distance from the bifurcation point along the branch (m or
    /// rad, in q's units), positive ahead along the cone's root.
    s: f64,
    /// The smallest lost singular value of Φ_q over the largest.
    pub sigma_rel: f64,
    /// The singular subspaces they came from.
    sub: Subspaces,
}

impl BranchRows {
    /// The lost left singular vectors w (m each): the rows take the place
    /// of the equations wᵀΦ = 0.
    pub(crate) fn lost(&self) -> impl Iterator<Item = &[f64]> {
        (0..self.k).map(|c| self.sub.w.col_as_slice(c))
    }
}

#[cfg(test)]
impl BranchRows {
    /// One row `a` with the tangent `tangent` (n each) in a system of `m`
    /// equations, without the subspaces an analysis finds (for tests of
    /// the integrator's use of rows).
    pub(crate) fn one(a: Vec<f64>, tangent: Vec<f64>, m: usize) -> Self {
        let n = a.len();
        BranchRows {
            k: 1,
            a,
            tangent,
            s: 0.0,
            sigma_rel: 0.0,
            sub: Subspaces {
                w: Mat::zeros(m, 1),
                v: Mat::zeros(n, 1),
                sigma: vec![0.0],
                smax: 1.0,
                top: vec![0.0; n],
            },
        }
    }
}

/// The branch rows at `q` (time `t`) for the branch whose tangent is
/// nearest to `hint` (a direction of motion in q-space), or None when
/// Φ_q has no lost direction there or the branches cannot be told apart.
/// The lost subspaces come from a dense SVD of Φ_q.
pub(crate) fn analyse(sys: &System, q: &[f64], t: f64, hint: &[f64]) -> Option<BranchRows> {
    rows(sys, q, t, hint, dense_subspaces(sys, q, t)?, None)
}

/// [`analyse`] at a position near that of `prev`, the rows found there:
/// the lost subspaces are refined from `prev`'s by inverse subspace
/// iteration with a sparse factorization (Φ_q's lost directions move
/// little from one step to the next, and are apart from the others by
/// the gap that makes them lost), or, when that does not settle to
/// [`REFINED`] or a lost value has risen above [`LOST`], found anew by a
/// dense SVD. The number of lost directions is `prev`'s when refined:
/// the window's own analysis finds it.
pub(crate) fn analyse_from(
    sys: &System,
    q: &[f64],
    t: f64,
    hint: &[f64],
    prev: &BranchRows,
) -> Option<BranchRows> {
    let sub = match refine(sys, q, t, &prev.sub) {
        Some(sub) => sub,
        None => dense_subspaces(sys, q, t)?,
    };
    rows(sys, q, t, hint, sub, Some(prev))
}

/// The lost subspaces of Φ_q at `q` from its dense SVD; None when it has
/// no lost direction.
fn dense_subspaces(sys: &System, q: &[f64], t: f64) -> Option<Subspaces> {
    let (model, asm) = (sys.model, &sys.asm);
    let (n, m) = (asm.n, asm.m);
    if n == 0 || m == 0 {
        return None;
    }
    let j = dense_jacobian(model, asm, q, t);
    let svd = j.svd().ok()?;
    let s = svd.S().column_vector();
    let r = m.min(n);
    let (imax, smax) = (0..r).fold(
        (0, 0.0f64),
        |(ia, a), i| {
            if s[i] > a {
                (i, s[i])
            } else {
                (ia, a)
            }
        },
    );
    if smax <= 0.0 {
        return None;
    }
    let lost: Vec<usize> = (0..r).filter(|&i| s[i] < LOST * smax).collect();
    if lost.is_empty() {
        return None;
    }
    let (u, v) = (svd.U(), svd.V());
    // The kernel basis: the lost right singular vectors and the null space.
    let kernel: Vec<usize> = lost.iter().copied().chain(r..n).collect();
    Some(Subspaces {
        w: Mat::from_fn(m, lost.len(), |i, c| u[(i, lost[c])]),
        v: Mat::from_fn(n, kernel.len(), |i, c| v[(i, kernel[c])]),
        sigma: lost.iter().map(|&i| s[i]).collect(),
        smax,
        top: (0..n).map(|i| v[(i, imax)]).collect(),
    })
}

/// Φ_q at `q` as a sparse matrix (m × n).
fn sparse_jacobian(sys: &System, q: &[f64], t: f64) -> Option<SparseColMat<usize, f64>> {
    let mut e = Vec::new();
    sys.asm
        .jacobian(sys.model, q, t, |r, c, v| e.push(Triplet::new(r, c, v)));
    SparseColMat::try_new_from_triplets(sys.m(), sys.n(), &e).ok()
}

/// The lost subspaces at `q` refined from `prev`'s (see
/// [`analyse_from`]); None when they do not settle.
///
/// With μ the largest lost singular value of `prev` (at least 1e-8
/// σ_max), K = [μI Φ_q; Φ_qᵀ −μI] maps the pair (u, 0), (0, v) of a
/// singular triplet (σ, u, v) into itself, and K⁻¹ scales the left part
/// of (u, 0) and the right part of (0, v) by μ/(σ² + μ²): about 1/μ on
/// the lost triplets and the null space, 1/σ on the others. Solving with
/// K for W's and V's columns and orthonormalising each part therefore
/// turns them towards the lost subspaces at `q`; the Rayleigh–Ritz step,
/// the SVD of the small Wᵀ Φ_q V, pairs them and gives their values.
fn refine(sys: &System, q: &[f64], t: f64, prev: &Subspaces) -> Option<Subspaces> {
    let (n, m) = (sys.n(), sys.m());
    let (k, d) = (prev.w.ncols(), prev.v.ncols());
    let j = sparse_jacobian(sys, q, t)?;
    // σ_max by power iteration from the last right vector.
    let mut top = Mat::from_fn(n, 1, |i, _| prev.top[i]);
    let mut smax = 0.0;
    for _ in 0..POWER_ITER {
        let y = &j * &top;
        smax = y.norm_l2();
        let x = j.transpose() * &y;
        let nx = x.norm_l2();
        if !(nx > 0.0 && nx.is_finite()) {
            return None;
        }
        top = x * Scale(1.0 / nx);
    }
    if smax.is_nan() || smax <= 0.0 {
        return None;
    }
    let mu = prev.sigma.iter().fold(1e-8 * smax, |a, &s| a.max(s));
    // K's pattern: the diagonal, Φ_q at rows 0..m and columns m..m+n, Φ_qᵀ.
    let entries: Vec<(usize, usize, f64)> = (0..n)
        .flat_map(|c| {
            let col = j.col_range(c);
            let rows = &j.symbolic().row_idx()[col.clone()];
            rows.iter()
                .zip(&j.val()[col])
                .map(move |(&r, &v)| (r, c, v))
        })
        .collect();
    let pattern: Vec<(usize, usize)> = (0..m + n)
        .map(|i| (i, i))
        .chain(entries.iter().map(|&(r, c, _)| (r, m + c)))
        .chain(entries.iter().map(|&(r, c, _)| (m + c, r)))
        .collect();
    let mut lu = SparseLu::try_new(m + n, &pattern).ok()?;
    for i in 0..m + n {
        lu.put(i, if i < m { mu } else { -mu });
    }
    for (e, &(_, _, v)) in entries.iter().enumerate() {
        lu.put(m + n + e, v);
        lu.put(m + n + entries.len() + e, v);
    }
    lu.factor().ok()?;
    let (mut w, mut v) = (prev.w.clone(), prev.v.clone());
    let mut rhs = vec![0.0; m + n];
    for _ in 0..REFINE_ITER {
        // One step of inverse iteration on each part.
        let mut wn = Mat::<f64>::zeros(m, k);
        for c in 0..k {
            rhs.fill(0.0);
            for i in 0..m {
                rhs[i] = w[(i, c)];
            }
            lu.solve(&mut rhs);
            for i in 0..m {
                wn[(i, c)] = rhs[i];
            }
        }
        let mut vn = Mat::<f64>::zeros(n, d);
        for c in 0..d {
            rhs.fill(0.0);
            for i in 0..n {
                rhs[m + i] = v[(i, c)];
            }
            lu.solve(&mut rhs);
            for i in 0..n {
                vn[(i, c)] = rhs[m + i];
            }
        }
        let (wq, vq) = (wn.qr().compute_thin_Q(), vn.qr().compute_thin_Q());
        // Rayleigh–Ritz: B = Wᵀ Φ_q V and its SVD.
        let b = wq.transpose() * (&j * &vq);
        let svd = b.svd().ok()?;
        w = &wq * svd.U();
        v = &vq * svd.V();
        let sigma: Vec<f64> = (0..k).map(|i| svd.S().column_vector()[i]).collect();
        // The residuals of the pair, per column: Φ_q V − W Σ (Σ k × d,
        // zero on the null space) and Φ_qᵀ W − V_k Σ.
        let ws = Mat::from_fn(m, d, |i, c| if c < k { sigma[c] * w[(i, c)] } else { 0.0 });
        let vs = Mat::from_fn(n, k, |i, c| sigma[c] * v[(i, c)]);
        let (r_v, r_w) = (&j * &v - ws, j.transpose() * &w - vs);
        let resid = (0..d)
            .map(|c| r_v.col(c).norm_l2())
            .chain((0..k).map(|c| r_w.col(c).norm_l2()))
            .fold(0.0f64, f64::max);
        if resid <= REFINED * smax {
            if sigma.iter().any(|&s| s.is_nan() || s >= LOST * smax) {
                return None;
            }
            return Some(Subspaces {
                w,
                v,
                sigma,
                smax,
                top: top.col_as_slice(0).to_vec(),
            });
        }
    }
    None
}

/// The rows of the branch nearest to `hint` from the lost subspaces `sub`.
/// `prev`, the rows of the step before inside a window, tells whether
/// the motion leaves the point.
fn rows(
    sys: &System,
    q: &[f64],
    t: f64,
    hint: &[f64],
    sub: Subspaces,
    prev: Option<&BranchRows>,
) -> Option<BranchRows> {
    let (n, m) = (sys.n(), sys.m());
    let k = sub.w.ncols();
    let sigma_rel = sub.sigma.iter().fold(f64::INFINITY, |a, &s| a.min(s)) / sub.smax;
    let w = &sub.w;
    let second = SecondOrder {
        sys,
        q,
        t,
        eps: DIFF * q.iter().fold(1.0f64, |a, x| a.max(x.abs())),
        k,
        w_by_row: (0..m)
            .flat_map(|i| (0..k).map(move |c| w[(i, c)]))
            .collect(),
        v: &sub.v,
    };
    let (y, g) = tangent_on_cone(&second, hint)?;
    let cone = combine(&sub.v, &y);
    // The distance along the branch from the point, s = Σ g_w·(G_w y) /
    // Σ |G_w y|² with g_w = Vᵀ Φ_qᵀ w = σ_w e_w, the lost gradients in the
    // kernel's coordinates: on the branch g_w = ℓ_w ∇m_w and G_w y =
    // (∇ℓ_w·t) ∇m_w, with ℓ_w = (∇ℓ_w·t) s to first order.
    let (num, den) = g.iter().enumerate().fold((0.0, 0.0), |(a, b), (c, gy)| {
        (a + sub.sigma[c] * gy[c], b + inner(gy, gy))
    });
    let s = num / den;
    // Leaving the point: farther from it than the step before, or, at a
    // window's first step, ahead of it along the motion (the hint).
    let leaving = match prev {
        Some(p) => s.abs() > p.s.abs(),
        None => s > 0.0,
    };
    let tangent = if leaving && sigma_rel > NULL_TANGENT {
        branch_tangent(&sub.v, k, &y)?
    } else {
        cone
    };
    // A rows: V G_w y, orthonormalised, each orthogonal to t.
    let mut a = Vec::with_capacity(k * n);
    for gy in &g {
        let mut row = combine(&sub.v, gy);
        let along = inner(&row, &tangent);
        for i in 0..n {
            row[i] -= along * tangent[i];
        }
        let before = norm2(&row);
        for prev in a.chunks(n) {
            let c = inner(&row, prev);
            for i in 0..n {
                row[i] -= c * prev[i];
            }
        }
        let after = norm2(&row);
        if !(after > 1e-6 * before && before > 0.0) {
            return None;
        }
        row.iter_mut().for_each(|x| *x /= after);
        a.extend_from_slice(&row);
    }
    Some(BranchRows {
        k,
        a,
        tangent,
        s,
        sigma_rel,
        sub,
    })
}

/// The branch's own tangent at q (unit, n) from the cone's root y in the
/// kernel's coordinates: Φ_q's null direction, the part of the root
/// along the null columns of V (those after the k lost ones), normalised
/// (Φ_q V = W Σ on the lost columns, so this is c − V_k Σ⁻¹ Wᵀ Φ_q c
/// for c = V y).
///
/// The cone's root is the tangent of the bifurcation point, not of the
/// branch at q: at a distance s from the point it is off by order s,
/// and in the directions that part the two branches by order s² (on
/// IFToMM A02 with 40 four-bars, the cranks' rates differ by 1.9e-6 at
/// the window's exit, s = 0.025). The steps of a window move along it,
/// so across the window the mechanism drifts off its branch (the cranks
/// by 1e-9 rad there), and the first step with Φ alone pulls it back
/// with a jolt that changes the energy. Φ_q's null direction is the
/// branch's tangent where q is on the branch; a distance e off it, it is
/// the tangent of the level set of the lost equations through q, which
/// is off the branch's by e/s. A motion that leaves the point along
/// that level set comes closer to the branch (the level sets of ℓ m
/// close in on m = 0 as ℓ grows: e falls as 1/s); one that approaches
/// the point along it would move away from the branch. The null
/// direction therefore serves only for a motion that leaves the point,
/// and not too near it: above [`NULL_TANGENT`], where on A02 the two
/// errors cross (e some 1e-11, s some 1e-3).
fn branch_tangent(v: &Mat<f64>, k: usize, y: &[f64]) -> Option<Vec<f64>> {
    let mut t = vec![0.0; v.nrows()];
    for (col, &yc) in y.iter().enumerate().skip(k) {
        for (x, vc) in t.iter_mut().zip(v.col_as_slice(col)) {
            *x += yc * vc;
        }
    }
    let norm = norm2(&t);
    if !(norm.is_finite() && norm > 0.0) {
        return None;
    }
    t.iter_mut().for_each(|x| *x /= norm);
    Some(t)
}

/// The second-order part of the lost equations wᵀΦ on the kernel:
/// G_w = Vᵀ (wᵀΦ)_qq V, applied to a direction y of the kernel's
/// coordinates.
struct SecondOrder<'a, 's> {
    sys: &'a System<'s>,
    q: &'a [f64],
    /// Time (s).
    t: f64,
    /// Step of the central differences (m or rad, per unit direction).
    eps: f64,
    /// Number of lost equations k.
    k: usize,
    /// The lost left singular vectors, m × k row-major: the k weights of
    /// each equation together.
    w_by_row: Vec<f64>,
    /// The kernel basis V, n × d.
    v: &'a Mat<f64>,
}

impl SecondOrder<'_, '_> {
    /// G_w y for every lost w (k rows of d), from the central difference
    /// of wᵀΦ_q along the direction V y: (wᵀΦ_q)_q V y ≈ (wᵀΦ_q(q + εVy)
    /// − wᵀΦ_q(q − εVy))/(2ε), then Vᵀ of it. One difference along V y
    /// costs what one of the d columns of G did.
    fn apply(&self, y: &[f64]) -> Vec<Vec<f64>> {
        let (model, asm) = (self.sys.model, &self.sys.asm);
        let (n, k) = (asm.n, self.k);
        let dir = combine(self.v, y);
        let mut qp = self.q.to_vec();
        let mut wj = [vec![0.0; n * k], vec![0.0; n * k]];
        for (side, sign) in [(0, 1.0), (1, -1.0)] {
            for i in 0..n {
                qp[i] = self.q[i] + sign * self.eps * dir[i];
            }
            let out = &mut wj[side];
            asm.jacobian(model, &qp, self.t, |row, c, x| {
                let ws = &self.w_by_row[row * k..(row + 1) * k];
                for (o, w) in out[c * k..(c + 1) * k].iter_mut().zip(ws) {
                    *o += w * x;
                }
            });
        }
        let scale = 1.0 / (2.0 * self.eps);
        let h = Mat::from_fn(n, k, |c, w| (wj[0][c * k + w] - wj[1][c * k + w]) * scale);
        let gy = self.v.transpose() * &h;
        (0..k)
            .map(|w| (0..gy.nrows()).map(|a| gy[(a, w)]).collect())
            .collect()
    }
}

/// The root y (unit) of the quadratic forms yᵀ G_w y nearest to the
/// direction `hint` projected on the kernel, and G_w y there: Gauss–Newton
/// with minimum-norm corrections, each from one application of G.
fn tangent_on_cone(
    second: &SecondOrder<'_, '_>,
    hint: &[f64],
) -> Option<(Vec<f64>, Vec<Vec<f64>>)> {
    let k = second.k;
    let v = second.v;
    let mut y: Vec<f64> = (0..v.ncols())
        .map(|c| inner(v.col_as_slice(c), hint))
        .collect();
    let d = y.len();
    let ny = norm2(&y);
    if ny.is_nan() || ny <= 0.0 {
        return None;
    }
    y.iter_mut().for_each(|x| *x /= ny);
    // The scale of G: its largest entry along the first direction.
    let mut gmax = None;
    // The iterate with the smallest residual so far: max |F_w|, y, G y.
    let mut best: Option<(f64, Vec<f64>, Vec<Vec<f64>>)> = None;
    for _ in 0..50 {
        // F_w = yᵀ G_w y, J = 2 (G_w y)ᵀ.
        let gy = second.apply(&y);
        let scale = *gmax.get_or_insert_with(|| {
            gy.iter()
                .flatten()
                .fold(0.0f64, |a: f64, x: &f64| a.max(x.abs()))
        });
        if scale == 0.0 || !scale.is_finite() {
            return None;
        }
        let f: Vec<f64> = gy.iter().map(|row| inner(row, &y)).collect();
        let fmax = f.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        if fmax <= 1e-14 * scale {
            return Some((y, gy));
        }
        // G y comes from differences along y, whose rounding varies with
        // y: the iteration ends at that noise (some 1e-14 to 1e-11 of G)
        // when a correction no longer halves the residual.
        if let Some((fbest, ..)) = &best {
            if fmax >= 0.5 * fbest && *fbest <= STALL * scale {
                return best.map(|(_, y, gy)| (y, gy));
            }
        }
        if best.as_ref().is_none_or(|(fbest, ..)| fmax < *fbest) {
            best = Some((fmax, y.clone(), gy.clone()));
        }
        // Δy = Jᵀ (J Jᵀ)⁻¹ F.
        let jjt = Mat::from_fn(k, k, |a, b| 4.0 * inner(&gy[a], &gy[b]));
        let rhs = Mat::from_fn(k, 1, |a, _| f[a]);
        let z = jjt.partial_piv_lu().solve(&rhs);
        for c in 0..d {
            let step: f64 = (0..k).map(|w| 2.0 * gy[w][c] * z[(w, 0)]).sum();
            y[c] -= step;
        }
        let ny = norm2(&y);
        if !ny.is_finite() || ny == 0.0 {
            return None;
        }
        y.iter_mut().for_each(|x| *x /= ny);
    }
    None
}

/// Σ_b c_b v_b over the columns v_b of `v`.
fn combine(v: &Mat<f64>, c: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; v.nrows()];
    for (b, &cb) in c.iter().enumerate() {
        for (o, x) in out.iter_mut().zip(v.col_as_slice(b)) {
            *o += cb * x;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::revolute::Revolute;
    use crate::model::{Body, BodyId, Model};

    /// Crank length a and pitch d (m) of the four-bar below.
    const A: f64 = 0.2;
    const D: f64 = 0.5;

    /// A parallelogram four-bar at crank angle `th`: cranks of length a
    /// pivoted at (0, 0) and (d, 0), coupler of length d; Φ_q loses one
    /// rank at th = 0 and ±π, where the crossed branch meets it.
    fn four_bar(th: f64) -> Model {
        let mut m = Model::new("parallelogram");
        let tip = [A * th.cos(), A * th.sin()];
        let mut add = |name: &str, q0: [f64; 3]| {
            let mut b = Body::new(name, q0);
            b.mass = 1.0;
            b.inertia = 0.01;
            m.add_body(b)
        };
        let c0 = add("crank0", [0.0, 0.0, th]);
        let c1 = add("crank1", [D, 0.0, th]);
        let bar = add("coupler", [tip[0], tip[1], 0.0]);
        let rev = |bi, si, bj, sj| Revolute {
            body_i: bi,
            s_i: si,
            body_j: bj,
            s_j: sj,
        };
        let g = BodyId::GROUND;
        m.add_joint("O0", rev(g, [0.0, 0.0], c0, [0.0, 0.0]));
        m.add_joint("O1", rev(g, [D, 0.0], c1, [0.0, 0.0]));
        m.add_joint("L", rev(c0, [A, 0.0], bar, [0.0, 0.0]));
        m.add_joint("R", rev(bar, [D, 0.0], c1, [A, 0.0]));
        m
    }

    /// The largest |Φ| at q after Gauss–Newton from q + τ t, with
    /// minimum-norm corrections: how far q + τ t is from Φ = 0 (the
    /// correction is of order τ² along a branch tangent, of order τ off it).
    fn correction(sys: &System, q: &[f64], dir: &[f64], tau: f64) -> f64 {
        let (model, asm) = (sys.model, &sys.asm);
        let mut x: Vec<f64> = q.iter().zip(dir).map(|(a, b)| a + tau * b).collect();
        let start = x.clone();
        let mut phi = vec![0.0; asm.m];
        for _ in 0..50 {
            asm.phi(model, &x, 0.0, &mut phi);
            let j = dense_jacobian(model, asm, &x, 0.0);
            let f = Mat::from_fn(asm.m, 1, |r, _| phi[r]);
            let dx = j.svd().unwrap().pseudoinverse() * &f;
            for (xi, d) in x.iter_mut().zip(dx.col(0).iter()) {
                *xi -= d;
            }
        }
        x.iter()
            .zip(&start)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    }

    /// The angle columns of the two cranks.
    fn crank_rates(t: &[f64]) -> (f64, f64) {
        (t[2], t[5])
    }

    #[test]
    fn rows_follow_the_parallelogram_branch_nearest_to_the_motion() {
        let model = four_bar(0.0);
        let sys = System::new(&model);
        let q = sys.asm.initial_q(&model);
        // The loads alone would turn the cranks at different rates.
        let mut hint = vec![0.0; sys.n()];
        hint[2] = -1.0;
        hint[5] = -0.7;
        let rows = analyse(&sys, &q, 0.0, &hint).expect("a lost rank at the flat position");
        assert_eq!(rows.k, 1);
        assert!(rows.sigma_rel < 1e-12, "σ_rel {}", rows.sigma_rel);
        let (w0, w1) = crank_rates(&rows.tangent);
        assert!((w0 - w1).abs() < 1e-9 * w0.abs(), "cranks {w0} and {w1}");
        // The row vanishes on the tangent and is a unit row.
        let at: f64 = rows.a.iter().zip(&rows.tangent).map(|(a, t)| a * t).sum();
        assert!(at.abs() < 1e-12, "A t = {at}");
        let norm: f64 = rows.a.iter().map(|a| a * a).sum::<f64>().sqrt();
        assert!((norm - 1.0).abs() < 1e-12);
        // The tangent is one of Φ = 0: the correction back onto it falls
        // as τ².
        let (c1, c2) = (
            correction(&sys, &q, &rows.tangent, 1e-3),
            correction(&sys, &q, &rows.tangent, 5e-4),
        );
        assert!(c1 / c2 > 3.5 && c1 < 1e-5, "corrections {c1:e}, {c2:e}");
        // The row holds the cranks together: it is not orthogonal to
        // turning one crank alone.
        assert!(rows.a[2].abs() > 0.1 || rows.a[5].abs() > 0.1);
    }

    #[test]
    fn a_motion_along_the_crossed_branch_gets_its_rows() {
        let model = four_bar(0.0);
        let sys = System::new(&model);
        let q = sys.asm.initial_q(&model);
        // Cranks turning against each other: the crossed four-bar.
        let mut hint = vec![0.0; sys.n()];
        hint[2] = -1.0;
        hint[5] = 0.5;
        let rows = analyse(&sys, &q, 0.0, &hint).expect("a lost rank at the flat position");
        let (w0, w1) = crank_rates(&rows.tangent);
        assert!(w0 * w1 < 0.0, "cranks {w0} and {w1} turn the same way");
        let (c1, c2) = (
            correction(&sys, &q, &rows.tangent, 1e-3),
            correction(&sys, &q, &rows.tangent, 5e-4),
        );
        assert!(c1 / c2 > 3.5 && c1 < 1e-5, "corrections {c1:e}, {c2:e}");
    }

    #[test]
    fn off_the_cone_the_correction_is_first_order() {
        // The check above can fail: a direction of the kernel that is on
        // neither branch needs a correction of order τ.
        let model = four_bar(0.0);
        let sys = System::new(&model);
        let q = sys.asm.initial_q(&model);
        let mut dir = vec![0.0; sys.n()];
        dir[2] = -1.0;
        dir[5] = -0.7;
        // The coupler (frame at its left pin) moving with the cranks'
        // tips: a null direction of Φ_q there.
        dir[7] = -A;
        dir[8] = A * 0.3 / D;
        let (c1, c2) = (
            correction(&sys, &q, &dir, 1e-3),
            correction(&sys, &q, &dir, 5e-4),
        );
        assert!(c1 / c2 < 2.5, "corrections {c1:e}, {c2:e}");
    }

    #[test]
    fn no_rows_away_from_the_flat_position() {
        let model = four_bar(0.7);
        let sys = System::new(&model);
        let q = sys.asm.initial_q(&model);
        let mut hint = vec![0.0; sys.n()];
        hint[2] = 1.0;
        assert!(analyse(&sys, &q, 0.0, &hint).is_none());
    }

    /// The projector V Vᵀ (n × n) on the columns of `v`.
    fn projector(v: &Mat<f64>) -> Mat<f64> {
        v * v.transpose()
    }

    /// The rows found from the last step's subspaces are those of a dense
    /// decomposition at the new position: the same lost values, the same
    /// subspaces (their projectors) and the same tangent, near the flat
    /// position and across a step of 1e-4 rad.
    #[test]
    fn refined_subspaces_are_the_dense_ones() {
        for (th0, th1) in [(1e-3, 1.1e-3), (-2e-5, 3e-5), (1e-3, 0.8e-3)] {
            let model0 = four_bar(th0);
            let sys0 = System::new(&model0);
            let q0 = sys0.asm.initial_q(&model0);
            let model1 = four_bar(th1);
            let sys1 = System::new(&model1);
            let q1 = sys1.asm.initial_q(&model1);
            let mut hint = vec![0.0; sys0.n()];
            hint[2] = -1.0;
            hint[5] = -1.0;
            let prev = analyse(&sys0, &q0, 0.0, &hint).expect("rows at th0");
            let dense = dense_subspaces(&sys1, &q1, 0.0).expect("lost rank at th1");
            let refined = refine(&sys1, &q1, 0.0, &prev.sub).expect("refined at th1");
            assert_eq!(refined.sigma.len(), dense.sigma.len());
            for (a, b) in refined.sigma.iter().zip(&dense.sigma) {
                assert!((a - b).abs() <= 1e-12 * dense.smax, "σ {a:e} against {b:e}");
            }
            // σ_max, a scale only (of σ_rel and LOST), from a few power
            // iterations: within some 1e-11 of it.
            assert!(
                (refined.smax - dense.smax).abs() <= 1e-9 * dense.smax,
                "σ_max {:e} against {:e}",
                refined.smax,
                dense.smax
            );
            for (x, y) in [(&refined.w, &dense.w), (&refined.v, &dense.v)] {
                let diff = projector(x) - projector(y);
                let worst = (0..diff.nrows())
                    .flat_map(|i| (0..diff.ncols()).map(move |j| (i, j)))
                    .fold(0.0f64, |a, (i, j)| a.max(diff[(i, j)].abs()));
                assert!(worst < 1e-10, "projectors differ by {worst:e}");
            }
            let from = analyse_from(&sys1, &q1, 0.0, &hint, &prev).expect("rows at th1");
            let anew = analyse(&sys1, &q1, 0.0, &hint).expect("rows at th1");
            assert_eq!(from.k, anew.k);
            let dot: f64 = inner(&from.tangent, &anew.tangent);
            assert!((dot.abs() - 1.0).abs() < 1e-12, "tangents at {dot}");
            assert!((from.sigma_rel - anew.sigma_rel).abs() <= 1e-12);
        }
    }

    /// Near the flat position, but not at it, a motion that leaves the
    /// point gets the branch's own tangent (the cranks at equal rates and
    /// the coupler's pin on its circle) within 4e-16, where the cone's
    /// root, the point's tangent, is off by 5.3e-9 at 1e-3 rad from the
    /// point and 5.3e-7 at 1e-2 rad (its largest component); a motion
    /// that approaches the point keeps the root.
    #[test]
    fn leaving_the_point_the_tangent_is_the_branch_s() {
        for (th, dir, leaving) in [
            (1e-3, 1.0, true),
            (-1e-3, -1.0, true),
            (1e-2, 1.0, true),
            (1e-3, -1.0, false),
            (-1e-2, 1.0, false),
        ] {
            let model = four_bar(th);
            let sys = System::new(&model);
            let q = sys.asm.initial_q(&model);
            let mut hint = vec![0.0; sys.n()];
            hint[2] = dir;
            hint[5] = dir;
            let rows = analyse(&sys, &q, 0.0, &hint).expect("a lost rank near the flat position");
            // s, the arc length from the point in q, ahead along the motion.
            let arc = dir * th * (2.0 + A * A).sqrt();
            assert!(
                (rows.s / arc - 1.0).abs() < 1e-2,
                "θ = {th}: s = {} against {arc}",
                rows.s
            );
            // dq/dθ on the parallelogram branch, normalised.
            let mut exact = vec![
                0.0,
                0.0,
                1.0,
                0.0,
                0.0,
                1.0,
                -A * th.sin(),
                A * th.cos(),
                0.0,
            ];
            let norm = norm2(&exact) * dir;
            exact.iter_mut().for_each(|x| *x /= norm);
            let off: f64 = rows
                .tangent
                .iter()
                .zip(&exact)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            if leaving {
                assert!(off < 1e-12, "θ = {th}: tangent off the branch's by {off:e}");
            } else {
                assert!(
                    off > 1e-9 && off < 1e-6,
                    "θ = {th}: the root is off by {off:e}"
                );
            }
        }
    }

    /// Away from the flat position nothing is lost: the refinement gives
    /// up (a lost value above [`LOST`]) and the dense decomposition finds
    /// no rows, as [`analyse`] does.
    #[test]
    fn refinement_far_from_the_point_finds_no_rows() {
        let model0 = four_bar(0.0);
        let sys0 = System::new(&model0);
        let q0 = sys0.asm.initial_q(&model0);
        let mut hint = vec![0.0; sys0.n()];
        hint[2] = 1.0;
        hint[5] = 1.0;
        let prev = analyse(&sys0, &q0, 0.0, &hint).expect("rows at the flat position");
        let model1 = four_bar(0.7);
        let sys1 = System::new(&model1);
        let q1 = sys1.asm.initial_q(&model1);
        assert!(refine(&sys1, &q1, 0.0, &prev.sub).is_none());
        assert!(analyse_from(&sys1, &q1, 0.0, &hint, &prev).is_none());
    }
}
