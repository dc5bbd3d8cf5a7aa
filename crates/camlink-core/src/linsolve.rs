//! Linear solves with matrices of fixed structure (Φ_q, and the augmented
//! matrices of dynamics).
//!
//! Structure once, numbers every step: a [`SystemMatrix`] is built from its
//! sparsity pattern once, then refilled and refactored in place. Small
//! systems use a dense LU with partial pivoting, large ones a sparse LU
//! whose symbolic analysis (fill-reducing ordering) is done once; both from
//! faer.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::linalg::LuError;
use faer::sparse::{Pair, SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, Mat, MatMut, MatRef, Par};

use crate::lu_program::Elimination;

/// Systems with at most this many unknowns are solved densely.
pub const DENSE_MAX: usize = 120;
/// Systems with at most this many unknowns use [`SmallLu`].
pub const SMALL_MAX: usize = 24;

/// The solve of a factorization from which [`SmallLu`] skips the factors'
/// numerical zeros: the augmented matrices of dynamics, solved many times
/// per factorization, have many (68 of the slider-crank's 162 structural
/// nonzeros); kinematics solves three times per factorization, where
/// gathering them costs more than it saves.
const COMPACT_AT: usize = 4;

/// A pivot smaller than this, relative to the largest entry of the matrix,
/// marks the matrix as singular.
const SINGULAR_PIVOT: f64 = 1e-12;

/// A factorization found the matrix singular at `column` (0-based) of U.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Singular {
    /// The row of the original matrix whose pivot vanished.
    pub row: usize,
    /// The pivot's size relative to the largest entry.
    pub pivot: f64,
}

/// P A = L U of a small square matrix: a direct row-major kernel with
/// partial pivoting, and the compiled elimination of [`crate::lu_program`]
/// that refactors with its pivot order.
///
/// For the handful of unknowns of a typical mechanism (9 for a four-bar),
/// faer's general LU spends most of its time in dispatch and set-up (about
/// 1.1 µs to factor a 9 × 9 on the reference machine, against some 0.1 µs
/// here); above [`SMALL_MAX`] unknowns faer's blocked kernels take over.
pub struct SmallLu {
    n: usize,
    /// The matrix being filled, row-major, then one zero (index n²) that
    /// the compiled elimination reads for fill-in.
    a: Vec<f64>,
    /// Dense factors of the pivoted kernel: unit lower L below the
    /// diagonal, U on and above.
    lu: Vec<f64>,
    /// Row k of the pivoted kernel's factors is row `perm[k]` of the matrix.
    perm: Vec<usize>,
    /// The factors' structural nonzeros, in the slots of `program` (a
    /// mechanism's factors are mostly zeros), and 1/U_kk.
    factors: Vec<f64>,
    inv_diag: Vec<f64>,
    /// Solves with the last factorization so far.
    solves: usize,
    /// The factors' numerical nonzeros, gathered at the [`COMPACT_AT`]-th
    /// solve of a factorization ([`Elimination::gather`]), and the number
    /// of L's and of all.
    nonzeros: Vec<(u32, u32, f64)>,
    gathered: (usize, usize),
    valid: bool,
    /// Smallest pivot of the last factorization relative to the largest entry.
    min_pivot: f64,
    /// The compiled elimination of the last pivoted factorization: the
    /// solves' structure, replayed by the next factorizations while its
    /// pivots stay acceptable ([`crate::lu_program`]).
    program: Box<Elimination>,
    /// Whether [`factor`](Self::factor) replays the recorded elimination
    /// (true) or always searches for pivots.
    pub fixed_pivots: bool,
    /// Factorizations done by replay and with a pivot search.
    pub replays: usize,
    pub pivoted: usize,
}

impl SmallLu {
    /// A dense n × n matrix.
    pub fn new(n: usize) -> Self {
        Self::with_pattern(n, (0..n).flat_map(|r| (0..n).map(move |c| (r, c))))
    }

    /// An n × n matrix whose nonzeros are at `pattern` (row, col).
    pub fn with_pattern(n: usize, pattern: impl IntoIterator<Item = (usize, usize)>) -> Self {
        SmallLu {
            program: Box::new(Elimination::new(n, pattern)),
            fixed_pivots: true,
            replays: 0,
            pivoted: 0,
            n,
            a: vec![0.0; n * n + 1],
            lu: vec![0.0; n * n],
            perm: (0..n).collect(),
            factors: vec![0.0; n * n],
            inv_diag: vec![0.0; n],
            solves: 0,
            nonzeros: vec![(0, 0, 0.0); n * n],
            gathered: (0, 0),
            valid: false,
            min_pivot: 0.0,
        }
    }

    #[inline]
    pub fn set(&mut self, r: usize, c: usize, v: f64) {
        debug_assert!(
            self.program.in_pattern(r, c),
            "entry ({r}, {c}) is outside the pattern"
        );
        self.a[r * self.n + c] = v;
    }

    /// The index of entry (r, c) in [`values_mut`](Self::values_mut).
    pub fn slot(&self, r: usize, c: usize) -> usize {
        r * self.n + c
    }

    /// The matrix's entries, row-major (only pattern entries may be set).
    pub fn values_mut(&mut self) -> &mut [f64] {
        let n = self.n;
        &mut self.a[..n * n]
    }

    /// P A = L U: the recorded elimination replayed when its pivots pass
    /// the threshold test, a pivoted factorization (recorded for the next
    /// call) otherwise.
    pub fn factor(&mut self) -> Result<(), Singular> {
        self.solves = 0;
        if self.fixed_pivots {
            if let Ok(min_pivot) = self.program.replay(
                &self.a,
                &mut self.factors,
                &mut self.inv_diag,
                SINGULAR_PIVOT,
            ) {
                self.min_pivot = min_pivot;
                self.valid = true;
                self.replays += 1;
                return Ok(());
            }
        }
        self.pivoted += 1;
        let outcome = self.factor_pivoted();
        match outcome {
            Ok(()) => {
                self.program.record(&self.perm);
                self.program
                    .load(&self.lu, &mut self.factors, &mut self.inv_diag);
            }
            Err(_) => self.program.forget(),
        }
        outcome
    }

    /// P A = L U with partial pivoting, into the dense `lu`.
    fn factor_pivoted(&mut self) -> Result<(), Singular> {
        let n = self.n;
        let mut scale = f64::MIN_POSITIVE;
        for x in &self.a[..n * n] {
            let v = x.abs();
            if v > scale {
                scale = v;
            }
        }
        self.lu.copy_from_slice(&self.a[..n * n]);
        for (k, p) in self.perm.iter_mut().enumerate() {
            *p = k;
        }
        let lu = &mut self.lu;
        let mut min_pivot = f64::INFINITY;
        for k in 0..n {
            // Pivot: the largest entry of column k on or below the diagonal.
            let mut p = k;
            let mut big = lu[k * n + k].abs();
            for i in k + 1..n {
                let v = lu[i * n + k].abs();
                if v > big {
                    big = v;
                    p = i;
                }
            }
            let ratio = big / scale;
            if ratio <= SINGULAR_PIVOT || ratio.is_nan() {
                self.valid = false;
                self.min_pivot = ratio;
                return Err(Singular {
                    row: self.perm[p],
                    pivot: ratio,
                });
            }
            if ratio < min_pivot {
                min_pivot = ratio;
            }
            if p != k {
                let (upper, lower) = lu.split_at_mut(p * n);
                upper[k * n..k * n + n].swap_with_slice(&mut lower[..n]);
                self.perm.swap(k, p);
            }
            // Eliminate below the pivot; rows whose multiplier is zero (most,
            // in a sparse Jacobian) are skipped.
            let inv = 1.0 / lu[k * n + k];
            let (top, rest) = lu.split_at_mut((k + 1) * n);
            let pivot_row = &top[k * n + k + 1..k * n + n];
            let len = pivot_row.len();
            for row in rest.chunks_exact_mut(n) {
                if row[k] == 0.0 {
                    continue;
                }
                let l = row[k] * inv;
                row[k] = l;
                let tail = &mut row[k + 1..k + 1 + len];
                for c in 0..len {
                    tail[c] -= l * pivot_row[c];
                }
            }
        }
        self.min_pivot = min_pivot;
        self.valid = true;
        Ok(())
    }

    /// Solves A x = b in place with the last factorization: over the
    /// factors' structural nonzeros for the first solves, over their
    /// numerical nonzeros (gathered once) from the [`COMPACT_AT`]-th on.
    #[inline]
    pub fn solve(&mut self, b: &mut [f64], work: &mut [f64]) {
        self.solves += 1;
        if self.solves < COMPACT_AT {
            self.program.solve(&self.factors, &self.inv_diag, b, work);
            return;
        }
        if self.solves == COMPACT_AT {
            self.gathered = self.program.gather(&self.factors, &mut self.nonzeros);
        }
        let (lower, len) = self.gathered;
        // SAFETY: `nonzeros` were gathered by this `program`, whose rows
        // and columns are below its n, the length of its permutation.
        unsafe {
            crate::lu_program::solve_gathered(
                &self.nonzeros[..len],
                lower,
                self.program.perm(),
                &self.inv_diag,
                b,
                work,
            );
        }
    }

    /// The matrix as a faer matrix (for diagnostics).
    pub fn to_dense(&self) -> Mat<f64> {
        Mat::from_fn(self.n, self.n, |r, c| self.a[r * self.n + c])
    }
}

/// P A = L U of a square matrix, with reusable storage.
pub struct DenseLu {
    lu: Mat<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    scratch: MemBuffer,
    valid: bool,
    min_pivot: f64,
}

impl DenseLu {
    pub fn new(n: usize) -> Self {
        let req = factor::lu_in_place_scratch::<usize, f64>(n, n, Par::Seq, Default::default())
            .or(solve::solve_in_place_scratch::<usize, f64>(n, 1, Par::Seq));
        DenseLu {
            lu: Mat::zeros(n, n),
            perm: vec![0; n],
            perm_inv: vec![0; n],
            scratch: MemBuffer::new(req),
            valid: false,
            min_pivot: 0.0,
        }
    }

    pub fn dim(&self) -> usize {
        self.lu.nrows()
    }

    /// True after a successful [`factor`](Self::factor).
    pub fn is_valid(&self) -> bool {
        self.valid
    }

    /// Forgets the factorization, so the next solve needs a new one.
    pub fn invalidate(&mut self) {
        self.valid = false;
    }

    /// Factors `a` (copied; `a` is left untouched).
    pub fn factor(&mut self, a: MatRef<'_, f64>) -> Result<(), Singular> {
        self.lu.copy_from(a);
        let scale = max_abs(a).max(f64::MIN_POSITIVE);
        factor::lu_in_place(
            self.lu.as_mut(),
            &mut self.perm,
            &mut self.perm_inv,
            Par::Seq,
            MemStack::new(&mut self.scratch),
            Default::default(),
        );
        let n = self.dim();
        self.min_pivot = f64::INFINITY;
        for k in 0..n {
            let pivot = self.lu[(k, k)].abs() / scale;
            self.min_pivot = self.min_pivot.min(pivot);
            if pivot <= SINGULAR_PIVOT || pivot.is_nan() {
                self.valid = false;
                return Err(Singular {
                    row: self.perm[k],
                    pivot,
                });
            }
        }
        self.valid = true;
        Ok(())
    }

    /// Solves A x = b in place (`b` becomes x).
    pub fn solve(&mut self, b: &mut [f64]) {
        let n = self.dim();
        let rhs = MatMut::from_column_major_slice_mut(b, n, 1);
        let perm = unsafe { faer::perm::PermRef::new_unchecked(&self.perm, &self.perm_inv, n) };
        solve::solve_in_place(
            self.lu.as_ref(),
            self.lu.as_ref(),
            perm,
            rhs,
            Par::Seq,
            MemStack::new(&mut self.scratch),
        );
    }
}

/// Sparse LU of a square matrix A with a fixed pattern.
///
/// The factorization is of Aᵀ, and A x = b is solved as (Aᵀ)ᵀ x = b: the
/// columns faer eliminates are then the rows of A (the equations), so when
/// no pivot is found in one, that row is a dependent equation and
/// [`Singular::row`] names it.
pub struct SparseLu {
    /// The pattern of Aᵀ.
    pattern: SymbolicSparseColMat<usize>,
    /// Values of Aᵀ in column-compressed order.
    values: Vec<f64>,
    /// Position in `values` of the k-th pattern entry.
    pos: Vec<usize>,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    scratch: MemBuffer,
    valid: bool,
    /// The probe of the pivot check: A·1, then its solution.
    probe: Vec<f64>,
    /// The probe's largest error in the last factorization's check.
    probe_err: f64,
}

/// Largest error of the probe solve A x = A·1 (in x, against 1) that a
/// sparse factorization may show; beyond it the pivots have grown or
/// vanished and the matrix counts as singular.
const PROBE_TOL: f64 = 1e-6;

/// Largest matrix whose singular row the sparse path locates by a dense LU
/// when the probe fails (the diagnosis' limit).
const LOCATE_MAX: usize = 2000;

/// Why a sparse matrix could not be set up.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("sparse matrix setup failed: {0}")]
pub struct SetupError(String);

impl SparseLu {
    /// Analyses the pattern `(row, col)` (no duplicates) of an n × n matrix.
    pub fn try_new(n: usize, pattern: &[(usize, usize)]) -> Result<Self, SetupError> {
        // The pattern of Aᵀ: entry (r, c) of A is (c, r) of Aᵀ.
        let pairs: Vec<Pair<usize, usize>> = pattern
            .iter()
            .map(|&(row, col)| Pair { row: col, col: row })
            .collect();
        let (sym, _) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs)
            .map_err(|e| SetupError(format!("pattern: {e:?}")))?;
        let pos = pattern
            .iter()
            .map(|&(r, c)| {
                let start = sym.col_ptr()[r];
                let rows = &sym.row_idx()[start..sym.col_ptr()[r + 1]];
                rows.binary_search(&c)
                    .map(|k| start + k)
                    .map_err(|_| SetupError(format!("entry ({r}, {c}) is not in the pattern")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let symbolic = factorize_symbolic_lu(sym.as_ref(), Default::default())
            .map_err(|e| SetupError(format!("symbolic LU: {e:?}")))?;
        let req = symbolic
            .factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default())
            .or(symbolic.solve_transpose_in_place_scratch::<f64>(1, Par::Seq));
        Ok(SparseLu {
            values: vec![0.0; sym.row_idx().len()],
            pattern: sym,
            pos,
            symbolic,
            numeric: NumericLu::new(),
            scratch: MemBuffer::new(req),
            valid: false,
            probe: vec![0.0; n],
            probe_err: 0.0,
        })
    }

    /// Sets the k-th pattern entry.
    #[inline]
    pub fn put(&mut self, k: usize, v: f64) {
        self.values[self.pos[k]] = v;
    }

    /// Factors the current values; a singular matrix names the row of A
    /// (the equation) where elimination found no pivot.
    pub fn factor(&mut self) -> Result<(), Singular> {
        let a = SparseColMatRef::new(self.pattern.as_ref(), &self.values);
        let res = self.symbolic.factorize_numeric_lu(
            &mut self.numeric,
            a,
            Par::Seq,
            MemStack::new(&mut self.scratch),
            Default::default(),
        );
        self.valid = res.is_ok();
        match res {
            Ok(_) => self.check_pivots(),
            // Elimination step `index` works on column col_perm[index] of Aᵀ.
            Err(LuError::SymbolicSingular { index }) => Err(Singular {
                row: self.symbolic.col_perm().arrays().0[index],
                pivot: 0.0,
            }),
            Err(LuError::Generic(_)) => Err(Singular { row: 0, pivot: 0.0 }),
        }
    }

    /// The pivot check: faer's sparse LU pivots on any nonzero, so a
    /// vanished or grown pivot shows as an inaccurate solve of A x = A·1.
    /// A singular matrix's row comes from a dense LU of A, up to
    /// [`LOCATE_MAX`] unknowns.
    fn check_pivots(&mut self) -> Result<(), Singular> {
        // probe = A·1: column c of Aᵀ sums into entry c of A·1.
        let n = self.probe.len();
        for c in 0..n {
            let range = self.pattern.col_ptr()[c]..self.pattern.col_ptr()[c + 1];
            self.probe[c] = self.values[range].iter().sum();
        }
        let mut probe = std::mem::take(&mut self.probe);
        self.solve(&mut probe);
        let err = probe.iter().fold(0.0f64, |e, x| {
            if x.is_finite() {
                e.max((x - 1.0).abs())
            } else {
                f64::INFINITY
            }
        });
        self.probe = probe;
        self.probe_err = err;
        if err <= PROBE_TOL {
            return Ok(());
        }
        self.valid = false;
        let row = if n <= LOCATE_MAX {
            let mut dense = DenseLu::new(n);
            dense
                .factor(self.to_dense().as_ref())
                .err()
                .map_or(0, |s| s.row)
        } else {
            0
        };
        Err(Singular { row, pivot: 0.0 })
    }

    pub fn solve(&mut self, b: &mut [f64]) {
        let n = b.len();
        let rhs = MatMut::from_column_major_slice_mut(b, n, 1);
        let lu = LuRef::new_unchecked(&self.symbolic, &self.numeric);
        lu.solve_transpose_in_place_with_conj(
            Conj::No,
            rhs,
            Par::Seq,
            MemStack::new(&mut self.scratch),
        );
    }

    /// The matrix A as a dense one (for diagnostics).
    pub fn to_dense(&self) -> Mat<f64> {
        let n = self.pattern.nrows();
        let mut a = Mat::zeros(n, n);
        for c in 0..n {
            for k in self.pattern.col_ptr()[c]..self.pattern.col_ptr()[c + 1] {
                a[(c, self.pattern.row_idx()[k])] = self.values[k];
            }
        }
        a
    }
}

/// A square matrix of fixed pattern with its LU factorization, dense or
/// sparse by size.
pub enum SystemMatrix {
    Small {
        lu: SmallLu,
        work: Vec<f64>,
    },
    /// `a` column-major.
    Dense {
        a: Vec<f64>,
        lu: DenseLu,
    },
    Sparse(Box<SparseLu>),
}

impl SystemMatrix {
    /// An n × n matrix with the entries `pattern` (row, col), in the order
    /// [`put`](Self::put) will fill them.
    pub fn try_new(n: usize, pattern: &[(usize, usize)]) -> Result<Self, SetupError> {
        Ok(if n <= SMALL_MAX {
            SystemMatrix::Small {
                lu: SmallLu::with_pattern(n, pattern.iter().copied()),
                work: vec![0.0; n],
            }
        } else if n <= DENSE_MAX {
            SystemMatrix::Dense {
                a: vec![0.0; n * n],
                lu: DenseLu::new(n),
            }
        } else {
            SystemMatrix::Sparse(Box::new(SparseLu::try_new(n, pattern)?))
        })
    }

    /// Sets entry k of the pattern, at (r, c).
    #[inline]
    pub fn put(&mut self, k: usize, r: usize, c: usize, v: f64) {
        match self {
            SystemMatrix::Small { lu, .. } => lu.set(r, c, v),
            SystemMatrix::Dense { a, lu } => a[c * lu.dim() + r] = v,
            SystemMatrix::Sparse(s) => s.put(k, v),
        }
    }

    /// The index in [`values_mut`](Self::values_mut) of entry k of the
    /// pattern, at (r, c): a destination that a fill computed once writes
    /// straight into.
    pub fn slot(&self, k: usize, r: usize, c: usize) -> usize {
        match self {
            SystemMatrix::Small { lu, .. } => lu.slot(r, c),
            SystemMatrix::Dense { lu, .. } => c * lu.dim() + r,
            SystemMatrix::Sparse(s) => s.pos[k],
        }
    }

    /// The storage of the matrix's values, indexed by [`slot`](Self::slot).
    #[inline]
    pub fn values_mut(&mut self) -> &mut [f64] {
        match self {
            SystemMatrix::Small { lu, .. } => lu.values_mut(),
            SystemMatrix::Dense { a, .. } => a,
            SystemMatrix::Sparse(s) => &mut s.values,
        }
    }

    /// Factors the current values.
    pub fn factor(&mut self) -> Result<(), Singular> {
        match self {
            SystemMatrix::Small { lu, .. } => lu.factor(),
            SystemMatrix::Dense { a, lu } => {
                let n = lu.dim();
                lu.factor(MatRef::from_column_major_slice(a, n, n))
            }
            SystemMatrix::Sparse(s) => s.factor(),
        }
    }

    /// Solves A x = b in place with the last factorization.
    #[inline]
    pub fn solve(&mut self, b: &mut [f64]) {
        match self {
            SystemMatrix::Small { lu, work } => lu.solve(b, work),
            SystemMatrix::Dense { lu, .. } => lu.solve(b),
            SystemMatrix::Sparse(s) => s.solve(b),
        }
    }

    pub fn is_valid(&self) -> bool {
        match self {
            SystemMatrix::Small { lu, .. } => lu.valid,
            SystemMatrix::Dense { lu, .. } => lu.is_valid(),
            SystemMatrix::Sparse(s) => s.valid,
        }
    }

    pub fn invalidate(&mut self) {
        match self {
            SystemMatrix::Small { lu, .. } => lu.valid = false,
            SystemMatrix::Dense { lu, .. } => lu.invalidate(),
            SystemMatrix::Sparse(s) => s.valid = false,
        }
    }

    /// Whether the small kernel replays its recorded pivot order
    /// ([`crate::lu_program`]); on by default, off to search for pivots at
    /// every factorization. The other kernels ignore it.
    pub fn set_fixed_pivots(&mut self, on: bool) {
        if let SystemMatrix::Small { lu, .. } = self {
            lu.fixed_pivots = on;
        }
    }

    /// (replayed, pivoted) factorizations of the small kernel so far
    /// ([`SmallLu::replays`], [`SmallLu::pivoted`]); None for the others.
    pub fn factorization_counts(&self) -> Option<(usize, usize)> {
        match self {
            SystemMatrix::Small { lu, .. } => Some((lu.replays, lu.pivoted)),
            _ => None,
        }
    }

    /// The smallest pivot of the last factorization relative to the largest
    /// entry, a cheap sign of near-singularity. The sparse kernel has no
    /// pivot order to read: its figure is ε_mach over the error of the
    /// probe solve of its pivot check, an estimate of 1/cond of the same
    /// order.
    pub fn min_pivot(&self) -> Option<f64> {
        match self {
            SystemMatrix::Small { lu, .. } => Some(lu.min_pivot),
            SystemMatrix::Dense { lu, .. } => Some(lu.min_pivot),
            SystemMatrix::Sparse(s) => Some((f64::EPSILON / s.probe_err).min(1.0)),
        }
    }

    /// The current values as a dense matrix (for diagnostics).
    pub fn to_dense(&self) -> Mat<f64> {
        match self {
            SystemMatrix::Small { lu, .. } => lu.to_dense(),
            SystemMatrix::Dense { a, lu } => {
                MatRef::from_column_major_slice(a, lu.dim(), lu.dim()).to_owned()
            }
            SystemMatrix::Sparse(s) => s.to_dense(),
        }
    }
}

/// Largest absolute entry of `a`.
pub fn max_abs(a: MatRef<'_, f64>) -> f64 {
    let mut m = 0.0f64;
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            m = m.max(a[(i, j)].abs());
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_small_system() {
        let a = Mat::from_fn(3, 3, |i, j| {
            [[0.0, 2.0, 1.0], [1.0, 1.0, 0.0], [3.0, 0.0, 1.0]][i][j]
        });
        let x = [1.0, -2.0, 0.5];
        let mut b: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|j| a[(i, j)] * x[j]).sum())
            .collect();
        let mut lu = DenseLu::new(3);
        lu.factor(a.as_ref()).unwrap();
        lu.solve(&mut b);
        for i in 0..3 {
            assert!((b[i] - x[i]).abs() < 1e-14, "{b:?}");
        }
    }

    /// A well-conditioned test matrix of size n with pivoting needed.
    fn test_matrix(n: usize) -> (Vec<(usize, usize)>, Vec<f64>) {
        let mut pattern = Vec::new();
        let mut vals = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let v = ((i * 7 + j * 13) % 11) as f64 / 11.0 - 0.5;
                // Dominant off the diagonal, so partial pivoting must swap.
                let v = if j == (i + 1) % n { v + 3.0 } else { v };
                pattern.push((i, j));
                vals.push(v);
            }
        }
        (pattern, vals)
    }

    #[test]
    fn small_dense_and_sparse_kernels_agree() {
        for n in [1, 2, 9, SMALL_MAX, SMALL_MAX + 1, 40] {
            let (pattern, vals) = test_matrix(n);
            let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).cos()).collect();
            let b: Vec<f64> = (0..n)
                .map(|i| (0..n).map(|j| vals[i * n + j] * x[j]).sum())
                .collect();
            let mut small = SmallLu::new(n);
            let mut dense = DenseLu::new(n);
            let mut sparse = SparseLu::try_new(n, &pattern).unwrap();
            for (k, (&(r, c), &v)) in pattern.iter().zip(&vals).enumerate() {
                small.set(r, c, v);
                sparse.put(k, v);
            }
            small.factor().unwrap();
            dense.factor(small.to_dense().as_ref()).unwrap();
            sparse.factor().unwrap();
            let mut work = vec![0.0; n];
            let (mut xs, mut xd, mut xp) = (b.clone(), b.clone(), b.clone());
            small.solve(&mut xs, &mut work);
            dense.solve(&mut xd);
            sparse.solve(&mut xp);
            for i in 0..n {
                assert!((xs[i] - x[i]).abs() < 1e-12, "small n={n} {i}");
                assert!((xd[i] - x[i]).abs() < 1e-12, "dense n={n} {i}");
                assert!((xp[i] - x[i]).abs() < 1e-12, "sparse n={n} {i}");
            }
        }
    }

    /// A sparse saddle-point matrix (zero diagonal block, pivoting needed):
    /// the small kernel's solve visits only the factors' structural nonzeros.
    #[test]
    fn small_kernel_solves_a_sparse_saddle_point_system() {
        let n = 11;
        let mut a = vec![0.0; n * n];
        for i in 0..7 {
            a[i * n + i] = 2.0 + i as f64;
        }
        for r in 0..4 {
            for c in [r, r + 2, r + 3] {
                a[(7 + r) * n + c] = 1.0 + 0.1 * (r + c) as f64;
                a[c * n + 7 + r] = 1.0 + 0.1 * (r + c) as f64;
            }
        }
        let nonzeros = (0..n * n).filter(|&k| a[k] != 0.0);
        let mut lu = SmallLu::with_pattern(n, nonzeros.map(|k| (k / n, k % n)));
        for (k, &v) in a.iter().enumerate() {
            if v != 0.0 {
                lu.set(k / n, k % n, v);
            }
        }
        lu.factor().unwrap();
        assert!(
            lu.program.solve_entries() < n * (n - 1),
            "the factors have zeros to skip"
        );
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.9).cos()).collect();
        let ax: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| a[i * n + j] * x[j]).sum())
            .collect();
        // Solves over the structural nonzeros, then over the gathered ones.
        for solve in 1..=COMPACT_AT + 1 {
            let mut b = ax.clone();
            lu.solve(&mut b, &mut vec![0.0; n]);
            for i in 0..n {
                assert!(
                    (b[i] - x[i]).abs() < 1e-13,
                    "solve {solve}, {i}: {} vs {}",
                    b[i],
                    x[i]
                );
            }
        }
    }

    #[test]
    fn small_kernel_reports_a_singular_matrix() {
        let mut lu = SmallLu::new(3);
        for (r, row) in [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 1.0, 1.0]]
            .iter()
            .enumerate()
        {
            for (c, &v) in row.iter().enumerate() {
                lu.set(r, c, v);
            }
        }
        let err = lu.factor().unwrap_err();
        assert!(err.pivot < 1e-12);
        assert!(!lu.valid);
    }

    #[test]
    fn sparse_and_dense_agree() {
        // A tridiagonal system large enough to take the sparse path.
        let n = DENSE_MAX + 30;
        let mut pattern = Vec::new();
        let mut vals = Vec::new();
        for i in 0..n {
            for j in i.saturating_sub(1)..(i + 2).min(n) {
                pattern.push((i, j));
                vals.push(if i == j { 4.0 + i as f64 * 0.01 } else { -1.0 });
            }
        }
        let mut sys = SystemMatrix::try_new(n, &pattern).unwrap();
        assert!(matches!(sys, SystemMatrix::Sparse(_)));
        for (k, (&(r, c), &v)) in pattern.iter().zip(&vals).enumerate() {
            sys.put(k, r, c, v);
        }
        let a = sys.to_dense();
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        let mut b: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| a[(i, j)] * x[j]).sum())
            .collect();
        let mut dense = DenseLu::new(n);
        dense.factor(a.as_ref()).unwrap();
        let mut xd = b.clone();
        dense.solve(&mut xd);
        sys.factor().unwrap();
        sys.solve(&mut b);
        for i in 0..n {
            assert!((b[i] - x[i]).abs() < 1e-12, "{i}: {} vs {}", b[i], x[i]);
            assert!(
                (b[i] - xd[i]).abs() < 1e-13,
                "{i}: sparse {} vs dense {}",
                b[i],
                xd[i]
            );
        }
    }

    #[test]
    fn sparse_lu_names_the_row_without_a_pivot() {
        // A tridiagonal matrix large enough for the sparse path whose row
        // 131 is zero (a joint whose Jacobian row vanishes): the error
        // names that row, not the first.
        let n = DENSE_MAX + 30;
        let zero = 131;
        let mut entries = Vec::new();
        for i in 0..n {
            for j in i.saturating_sub(1)..(i + 2).min(n) {
                let v = if i == zero {
                    0.0
                } else if i == j {
                    4.0 + i as f64 * 0.01
                } else {
                    -1.0
                };
                entries.push(((i, j), v));
            }
        }
        let pattern: Vec<(usize, usize)> = entries.iter().map(|e| e.0).collect();
        let mut sys = SystemMatrix::try_new(n, &pattern).unwrap();
        assert!(matches!(sys, SystemMatrix::Sparse(_)));
        for (k, &((r, c), v)) in entries.iter().enumerate() {
            sys.put(k, r, c, v);
        }
        let err = sys.factor().unwrap_err();
        assert_eq!(err.row, zero, "{err:?}");
        assert!(!sys.is_valid());
    }

    #[test]
    fn reports_a_singular_matrix() {
        let a = Mat::from_fn(3, 3, |i, j| {
            [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 1.0, 1.0]][i][j]
        });
        let mut lu = DenseLu::new(3);
        let err = lu.factor(a.as_ref()).unwrap_err();
        assert!(err.pivot < 1e-12);
        assert!(!lu.is_valid());
    }

    // The recorded pivot order of the small kernel (crate::lu_program).

    /// A four-bar-like sparse matrix: a band with a few off-band entries
    /// whose values turn with `angle`, so that the pivot rows change over a
    /// turn.
    fn band_pattern(n: usize) -> Vec<(usize, usize)> {
        let mut p = Vec::new();
        for r in 0..n {
            for c in 0..n {
                if r.abs_diff(c) <= 1 || (r + 2 * c) % 5 == 0 {
                    p.push((r, c));
                }
            }
        }
        p
    }

    fn fill(lu: &mut SmallLu, p: &[(usize, usize)], angle: f64) {
        for &(r, c) in p {
            let v =
                (angle + 0.7 * r as f64 - 1.3 * c as f64).sin() + if r == c { 0.3 } else { 0.0 };
            lu.set(r, c, v);
        }
    }

    fn solve(lu: &mut SmallLu, n: usize) -> Vec<f64> {
        let mut b: Vec<f64> = (0..n).map(|k| 1.0 + k as f64).collect();
        let mut work = vec![0.0; n];
        lu.solve(&mut b, &mut work);
        b
    }

    /// Over a full turn of the values, the replayed factorizations solve
    /// like pivoted ones (to rounding), and the pivot order is refreshed
    /// where the pivots grow too small; the test fails if the replay is
    /// wrong or if it never replays (same results and no saving).
    #[test]
    fn replayed_factorizations_solve_like_pivoted_ones() {
        let n = 9;
        let p = band_pattern(n);
        let mut fixed = SmallLu::with_pattern(n, p.iter().copied());
        let mut pivoted = SmallLu::with_pattern(n, p.iter().copied());
        pivoted.fixed_pivots = false;
        for step in 0..2000 {
            let angle = step as f64 * 2e-3 * std::f64::consts::PI;
            fill(&mut fixed, &p, angle);
            fill(&mut pivoted, &p, angle);
            fixed.factor().unwrap();
            pivoted.factor().unwrap();
            let (x, y) = (solve(&mut fixed, n), solve(&mut pivoted, n));
            let size = y.iter().fold(1.0f64, |a, v| a.max(v.abs()));
            for (a, b) in x.iter().zip(&y) {
                assert!(
                    (a - b).abs() <= 1e-12 * size,
                    "step {step}: {x:?} against {y:?}"
                );
            }
        }
        let (replays, refreshes) = (fixed.replays, fixed.pivoted);
        assert!(replays > 1500, "{replays} replays, {refreshes} refreshes");
        assert!(refreshes > 1, "{replays} replays, {refreshes} refreshes");
        assert_eq!(pivoted.replays, 0);
    }

    /// Where partial pivoting would keep the recorded order, the replay's
    /// factors are those of the pivoted kernel, bit for bit.
    #[test]
    fn a_replay_in_the_pivoted_order_is_exact() {
        let n = 9;
        let p = band_pattern(n);
        let mut fixed = SmallLu::with_pattern(n, p.iter().copied());
        let mut pivoted = SmallLu::with_pattern(n, p.iter().copied());
        pivoted.fixed_pivots = false;
        fill(&mut fixed, &p, 0.1);
        fixed.factor().unwrap();
        fill(&mut fixed, &p, 0.1 + 1e-6);
        fill(&mut pivoted, &p, 0.1 + 1e-6);
        fixed.factor().unwrap();
        pivoted.factor().unwrap();
        assert_eq!(fixed.replays, 1);
        let (x, y) = (solve(&mut fixed, n), solve(&mut pivoted, n));
        assert_eq!(x, y);
    }
}
