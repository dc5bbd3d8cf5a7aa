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
//! follow.
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
use faer::Mat;

use super::system::System;
use crate::diagnose::dense_jacobian;
use crate::math::{inner, norm2};

/// Singular values of Φ_q below this fraction of the largest count as
/// lost directions.
const LOST: f64 = 1e-3;

/// A step that ends with the smallest lost singular value below this
/// fraction of the largest starts using the rows.
pub(crate) const WINDOW: f64 = 1e-5;

/// Once in use, the rows are left when that value rises above this.
pub(crate) const WINDOW_EXIT: f64 = 4.0 * WINDOW;

/// Relative step of the central differences of Φ_q along the kernel.
const DIFF: f64 = 1e-5;

/// The tangent's iteration may end where its residual, relative to the
/// largest entry of G, stops falling below this (the noise of the
/// differences; see [`tangent_on_cone`]).
const STALL: f64 = 1e-9;

/// The branch rows at a position near a bifurcation point.
pub(crate) struct BranchRows {
    /// Number of rows k (lost ranks).
    pub k: usize,
    /// The rows A, k × n row-major, orthonormal, each with A t = 0.
    pub a: Vec<f64>,
    /// The branch tangent t (unit, n).
    pub tangent: Vec<f64>,
    /// The smallest lost singular value of Φ_q over the largest.
    pub sigma_rel: f64,
    /// The lost left singular vectors w, k × m row-major: the rows take
    /// the place of the equations wᵀΦ = 0.
    pub lost: Vec<f64>,
}

/// The branch rows at `q` (time `t`) for the branch whose tangent is
/// nearest to `hint` (a direction of motion in q-space), or None when
/// Φ_q has no lost direction there or the branches cannot be told apart.
pub(crate) fn analyse(sys: &System, q: &[f64], t: f64, hint: &[f64]) -> Option<BranchRows> {
    let (model, asm) = (sys.model, &sys.asm);
    let (n, m) = (asm.n, asm.m);
    if n == 0 || m == 0 {
        return None;
    }
    let j = dense_jacobian(model, asm, q, t);
    let svd = j.svd().ok()?;
    let s = svd.S().column_vector();
    let r = m.min(n);
    let smax = (0..r).fold(0.0f64, |a, i| a.max(s[i]));
    if smax <= 0.0 {
        return None;
    }
    let lost: Vec<usize> = (0..r).filter(|&i| s[i] < LOST * smax).collect();
    let k = lost.len();
    if k == 0 {
        return None;
    }
    let sigma_rel = lost.iter().fold(f64::INFINITY, |a, &i| a.min(s[i])) / smax;
    let (u, v) = (svd.U(), svd.V());
    // The kernel basis: the lost right singular vectors and the null space.
    let kernel: Vec<usize> = lost.iter().copied().chain(r..n).collect();
    let d = kernel.len();
    let basis: Vec<Vec<f64>> = kernel
        .iter()
        .map(|&c| (0..n).map(|i| v[(i, c)]).collect())
        .collect();
    // The lost left singular vectors w, k × m row-major.
    let w_rows: Vec<f64> = lost
        .iter()
        .flat_map(|&lw| (0..m).map(move |row| u[(row, lw)]))
        .collect();
    let second = SecondOrder {
        sys,
        q,
        t,
        eps: DIFF * q.iter().fold(1.0f64, |a, x| a.max(x.abs())),
        k,
        w_by_row: (0..m)
            .flat_map(|row| lost.iter().map(move |&lw| u[(row, lw)]))
            .collect(),
        vk: Mat::from_fn(n, d, |i, a| basis[a][i]),
        basis: &basis,
    };
    let (y, g) = tangent_on_cone(&second, hint)?;
    let tangent = combine(&basis, &y);
    // A rows: V G_w y, orthonormalised, each orthogonal to t.
    let mut a = Vec::with_capacity(k * n);
    for gy in &g {
        let mut row = combine(&basis, gy);
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
        sigma_rel,
        lost: w_rows,
    })
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
    /// The kernel basis V as a matrix, n × d.
    vk: Mat<f64>,
    /// The same, one vector per column of V.
    basis: &'a [Vec<f64>],
}

impl SecondOrder<'_, '_> {
    /// G_w y for every lost w (k rows of d), from the central difference
    /// of wᵀΦ_q along the direction V y: (wᵀΦ_q)_q V y ≈ (wᵀΦ_q(q + εVy)
    /// − wᵀΦ_q(q − εVy))/(2ε), then Vᵀ of it. One difference along V y
    /// costs what one of the d columns of G did.
    fn apply(&self, y: &[f64]) -> Vec<Vec<f64>> {
        let (model, asm) = (self.sys.model, &self.sys.asm);
        let (n, k) = (asm.n, self.k);
        let dir = combine(self.basis, y);
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
        let gy = self.vk.transpose() * &h;
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
    let mut y: Vec<f64> = second.basis.iter().map(|v| inner(v, hint)).collect();
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

/// Σ_b c_b v_b.
fn combine(basis: &[Vec<f64>], c: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; basis[0].len()];
    for (vb, &cb) in basis.iter().zip(c) {
        for (o, x) in out.iter_mut().zip(vb) {
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
}
