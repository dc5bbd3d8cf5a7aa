//! A compiled elimination for the small dense LU ([`crate::linsolve::SmallLu`]):
//! the factors' structure as flat index lists, and refactorization with the
//! pivot order of the last pivoted factorization.
//!
//! A mechanism's Φ_q keeps its sparsity pattern, and from one step to the
//! next its values change little, so the rows that partial pivoting picks
//! rarely change. After a pivoted factorization P A = L U, the elimination
//! is recorded symbolically over A's pattern (with fill-in) and compiled.
//! The structural nonzeros of the factors get slots in a compact vector:
//! L's strictly lower part row by row, the diagonal, U's strictly upper
//! part row by row. The elimination becomes, for each pivot k, the list of
//! slots of L_ik (i > k) and the list of updates (target, L_ik, U_kj), one
//! per structural product L_ik U_kj. The next factorization fills the
//! slots from A (finding A's largest entry in the same pass), runs those
//! lists in the same order, with no pivot search and no dense storage, and
//! divides U's strictly upper part by its pivots. The solves are then two
//! flat loops over the slots in order: L forward, U backward.
//!
//! The replay accepts a pivot only while it is at least [`THRESHOLD`] times
//! the largest entry below it in its column (threshold partial pivoting,
//! growth at most 1 + 1/[`THRESHOLD`] per elimination step) and not below
//! the singular level; otherwise it gives up and the caller factors with
//! pivoting again, which records a new order. With the pivot order
//! unchanged, the replay does the same arithmetic as the pivoted kernel on
//! the same nonzeros, so its factors are the same to the last bit.

/// A pivot is kept while |U_kk| ≥ THRESHOLD · max_{i>k} |L_ik U_kk| (the
/// entries below it before elimination).
pub(crate) const THRESHOLD: f64 = 0.1;

/// An index in the compiled lists (a slot, a row or a column).
type Ix = u32;

/// The compiled elimination of an n × n matrix with a fixed pattern.
#[derive(Clone, Debug)]
pub(crate) struct Elimination {
    n: usize,
    /// The structural nonzeros of A, row-major.
    pattern: Vec<bool>,
    /// Scratch: the pattern of the factors being recorded, row-major, in
    /// the permuted row order.
    filled: Vec<bool>,
    /// Scratch: the slot of each entry of `filled`.
    slot_of: Vec<Ix>,
    /// Row k of the factors is row `perm[k]` of A.
    perm: Vec<usize>,
    /// For each slot, the index in the row-major A (with its trailing zero,
    /// index n², for fill-in) it starts from.
    src: Vec<Ix>,
    /// For each slot, its index in row-major dense factors.
    dense: Vec<Ix>,
    /// For each slot, its (row, column).
    at: Vec<(Ix, Ix)>,
    /// For pivot k: the slot of U_kk and the ends of its lists in `below`
    /// and `updates` (each list starts where the one of pivot k − 1 ends).
    pivots: Vec<Pivot>,
    /// The slots of L_ik, i > k, pivot by pivot.
    below: Vec<Ix>,
    /// (slot of A_ij, slot of L_ik, slot of U_kj), A_ij −= L_ik U_kj, pivot
    /// by pivot.
    updates: Vec<[Ix; 3]>,
    /// Slots `..lower` hold L's strictly lower part, `lower..lower + n` the
    /// diagonal, the rest U's strictly upper part.
    lower: usize,
    recorded: bool,
}

/// One pivot of the compiled elimination.
#[derive(Clone, Copy, Debug, Default)]
struct Pivot {
    /// The slot of U_kk.
    diag: Ix,
    below_end: Ix,
    update_end: Ix,
}

/// Why a replay stopped: the caller factors with pivoting instead.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Refresh;

impl Elimination {
    /// For an n × n matrix whose nonzeros are at `pattern` (row, col);
    /// all storage is made here, so recording and replaying allocate nothing.
    pub(crate) fn new(n: usize, pattern: impl IntoIterator<Item = (usize, usize)>) -> Self {
        let mut p = vec![false; n * n];
        for (r, c) in pattern {
            p[r * n + c] = true;
        }
        let triangle = n * n.saturating_sub(1) / 2;
        // Σ_k (n − 1 − k)², the most updates a dense matrix needs.
        let products = n.saturating_sub(1) * n * (2 * n).saturating_sub(1) / 6;
        Elimination {
            n,
            pattern: p,
            filled: vec![false; n * n],
            slot_of: vec![0; n * n],
            perm: (0..n).collect(),
            src: Vec::with_capacity(n * n),
            dense: Vec::with_capacity(n * n),
            at: Vec::with_capacity(n * n),
            pivots: vec![Pivot::default(); n],
            below: Vec::with_capacity(triangle),
            updates: Vec::with_capacity(products),
            lower: 0,
            recorded: false,
        }
    }

    /// Whether (r, c) is in the pattern.
    pub(crate) fn in_pattern(&self, r: usize, c: usize) -> bool {
        self.pattern[r * self.n + c]
    }

    /// Forgets the recorded order (the next replay refreshes).
    pub(crate) fn forget(&mut self) {
        self.recorded = false;
    }

    /// Number of slots: the structural nonzeros of the recorded factors.
    #[cfg(test)]
    pub(crate) fn slots(&self) -> usize {
        self.src.len()
    }

    /// Number of off-diagonal factor entries a solve visits.
    #[cfg(test)]
    pub(crate) fn solve_entries(&self) -> usize {
        self.src.len() - self.n
    }

    /// Records and compiles the elimination of a pivoted factorization
    /// whose row k is row `perm[k]` of A.
    pub(crate) fn record(&mut self, perm: &[usize]) {
        let n = self.n;
        self.perm.copy_from_slice(perm);
        // The factors' pattern: A's rows permuted, the diagonal, fill-in.
        for (k, &p) in perm.iter().enumerate() {
            self.filled[k * n..k * n + n].copy_from_slice(&self.pattern[p * n..p * n + n]);
            self.filled[k * n + k] = true;
        }
        for k in 0..n {
            for i in k + 1..n {
                if self.filled[i * n + k] {
                    for j in k + 1..n {
                        if self.filled[k * n + j] {
                            self.filled[i * n + j] = true;
                        }
                    }
                }
            }
        }
        // Slots: L's strictly lower part row by row, the diagonal, U's
        // strictly upper part row by row; with where each starts from.
        self.src.clear();
        self.dense.clear();
        self.at.clear();
        for part in 0..3 {
            if part == 1 {
                self.lower = self.src.len();
            }
            for (i, &p) in perm.iter().enumerate() {
                let columns = match part {
                    0 => 0..i,
                    1 => i..i + 1,
                    _ => i + 1..n,
                };
                for j in columns {
                    if self.filled[i * n + j] {
                        self.slot_of[i * n + j] = self.src.len() as Ix;
                        let a = p * n + j;
                        self.src.push(if self.pattern[a] { a } else { n * n } as Ix);
                        self.dense.push((i * n + j) as Ix);
                        self.at.push((i as Ix, j as Ix));
                    }
                }
            }
        }
        // The elimination, pivot by pivot.
        self.below.clear();
        self.updates.clear();
        for k in 0..n {
            for i in k + 1..n {
                if !self.filled[i * n + k] {
                    continue;
                }
                let l = self.slot_of[i * n + k];
                self.below.push(l);
                for j in k + 1..n {
                    if self.filled[k * n + j] {
                        self.updates
                            .push([self.slot_of[i * n + j], l, self.slot_of[k * n + j]]);
                    }
                }
            }
            self.pivots[k] = Pivot {
                diag: self.slot_of[k * n + k],
                below_end: self.below.len() as Ix,
                update_end: self.updates.len() as Ix,
            };
        }
        self.recorded = true;
    }

    /// Copies row-major dense factors `lu`, made in the recorded order,
    /// into the slots of `factors`, and the reciprocals of their pivots
    /// into `inv_diag`.
    pub(crate) fn load(&self, lu: &[f64], factors: &mut [f64], inv_diag: &mut [f64]) {
        for (f, &d) in factors.iter_mut().zip(&self.dense) {
            *f = lu[d as usize];
        }
        for (inv, p) in inv_diag.iter_mut().zip(&self.pivots) {
            *inv = 1.0 / factors[p.diag as usize];
        }
        self.scale_upper(factors, inv_diag);
    }

    /// U_ij / U_ii in U's strictly upper slots (the solves' unit upper
    /// factor), once the elimination no longer reads them.
    fn scale_upper(&self, factors: &mut [f64], inv_diag: &[f64]) {
        let upper = self.lower + self.n..self.src.len();
        for (u, &(i, _)) in factors[upper.clone()].iter_mut().zip(&self.at[upper]) {
            *u *= inv_diag[i as usize];
        }
    }

    /// P A = L U of `a` (row-major, with a trailing zero at index n²) into
    /// the slots of `factors` with the recorded pivot order, the
    /// reciprocals of the pivots into `inv_diag`; returns the smallest
    /// pivot relative to the largest |a_rc| over the pattern, or
    /// [`Refresh`] when there is no recorded order or a pivot fails the
    /// threshold or singular test (`factors` is then meaningless).
    pub(crate) fn replay(
        &self,
        a: &[f64],
        factors: &mut [f64],
        inv_diag: &mut [f64],
        singular: f64,
    ) -> Result<f64, Refresh> {
        if !self.recorded {
            return Err(Refresh);
        }
        let f = &mut factors[..self.src.len()];
        let mut scale = f64::MIN_POSITIVE;
        for (v, &s) in f.iter_mut().zip(&self.src) {
            let x = a[s as usize];
            *v = x;
            if x.abs() > scale {
                scale = x.abs();
            }
        }
        let mut min_pivot = f64::INFINITY;
        let (mut below_start, mut update_start) = (0, 0);
        for (p, inv_k) in self.pivots.iter().zip(inv_diag.iter_mut()) {
            let pivot = f[p.diag as usize];
            let below = &self.below[below_start..p.below_end as usize];
            let updates = &self.updates[update_start..p.update_end as usize];
            below_start = p.below_end as usize;
            update_start = p.update_end as usize;
            let mut big = 0.0f64;
            for &s in below {
                if f[s as usize].abs() > big {
                    big = f[s as usize].abs();
                }
            }
            let ratio = pivot.abs() / scale;
            // Written so that a NaN fails.
            if !(pivot.abs() >= THRESHOLD * big && ratio > singular) {
                return Err(Refresh);
            }
            if ratio < min_pivot {
                min_pivot = ratio;
            }
            let inv = 1.0 / pivot;
            *inv_k = inv;
            for &s in below {
                f[s as usize] *= inv;
            }
            for &[t, l, u] in updates {
                let (t, l, u) = (t as usize, l as usize, u as usize);
                debug_assert!(t < f.len() && l < f.len() && u < f.len());
                // SAFETY: `record` makes every slot below the number of
                // slots, the length of `f`.
                unsafe {
                    let product = *f.get_unchecked(l) * *f.get_unchecked(u);
                    *f.get_unchecked_mut(t) -= product;
                }
            }
        }
        self.scale_upper(factors, inv_diag);
        Ok(min_pivot)
    }

    /// Row k of the factors is row `perm()[k]` of A.
    pub(crate) fn perm(&self) -> &[usize] {
        &self.perm
    }

    /// Gathers the numerical nonzeros of `factors` (in the recorded
    /// slots, as a factorization left them) as (row, column, value): L's
    /// strictly lower part, then the scaled upper part; returns the number
    /// of L's. Every entry is written and the end advances past nonzeros
    /// only, without a branch on the value.
    pub(crate) fn gather(&self, factors: &[f64], nonzeros: &mut [(Ix, Ix, f64)]) -> (usize, usize) {
        let mut len = 0;
        let mut lower = 0;
        let diag = self.lower..self.lower + self.n;
        for (s, (&v, &(i, j))) in factors.iter().zip(&self.at).enumerate() {
            if s == diag.start {
                lower = len;
            }
            if diag.contains(&s) {
                continue;
            }
            nonzeros[len] = (i, j, v);
            len += usize::from(v != 0.0);
        }
        (lower, len)
    }

    /// Solves A x = b in place with factors in the recorded slots
    /// (`factors`, `inv_diag` as [`replay`](Self::replay) or
    /// [`load`](Self::load) left them); `work` holds n values.
    pub(crate) fn solve(&self, factors: &[f64], inv_diag: &[f64], b: &mut [f64], work: &mut [f64]) {
        let (lower, upper) = (..self.lower, self.lower + self.n..self.src.len());
        let entries =
            |range: std::ops::Range<usize>| factors[range.clone()].iter().zip(&self.at[range]);
        let n = self.n;
        let (b, work) = (&mut b[..n], &mut work[..n]);
        for (w, &p) in work.iter_mut().zip(&self.perm) {
            *w = b[p];
        }
        // L y = P b (unit diagonal): row by row, each entry's y_j is final.
        for (&l, &(i, j)) in entries(0..lower.end) {
            sub_product(work, i, j, l);
        }
        // U x = y as D (I + D⁻¹U') x = y, rows from the last.
        for ((x, &y), &inv) in b.iter_mut().zip(work.iter()).zip(inv_diag) {
            *x = y * inv;
        }
        for (&u, &(i, j)) in entries(upper).rev() {
            sub_product(b, i, j, u);
        }
    }
}

/// The solve of [`Elimination::solve`] over gathered nonzeros
/// ([`Elimination::gather`]: L's entries up to `lower`, then the scaled
/// upper ones) with the row order `perm`.
///
/// # Safety
/// Every row and column in `nonzeros` is below `perm.len()`: they are
/// gathered by [`Elimination::gather`] of the elimination whose
/// [`Elimination::perm`] is `perm`. The triangular solves index `b` and
/// `work` with them unchecked.
pub(crate) unsafe fn solve_gathered(
    nonzeros: &[(Ix, Ix, f64)],
    lower: usize,
    perm: &[usize],
    inv_diag: &[f64],
    b: &mut [f64],
    work: &mut [f64],
) {
    let n = perm.len();
    let (b, work) = (&mut b[..n], &mut work[..n]);
    for (w, &p) in work.iter_mut().zip(perm) {
        *w = b[p];
    }
    for &(i, j, l) in &nonzeros[..lower] {
        sub_product(work, i, j, l);
    }
    for ((x, &y), &inv) in b.iter_mut().zip(work.iter()).zip(inv_diag) {
        *x = y * inv;
    }
    for &(i, j, u) in nonzeros[lower..].iter().rev() {
        sub_product(b, i, j, u);
    }
}

/// `v[i] −= a v[j]`, the step of the triangular solves, for the row and
/// column of a factor entry ([`Elimination`]'s `at`, or the entries
/// [`Elimination::gather`] takes from it).
///
/// The solves spend most of their time here, and a bounds check on both
/// indices about doubles its cost; the indices are checked in debug
/// builds only.
#[inline(always)]
fn sub_product(v: &mut [f64], i: Ix, j: Ix, a: f64) {
    let (i, j) = (i as usize, j as usize);
    debug_assert!(i < v.len() && j < v.len());
    // SAFETY: the solves pass vectors of n values, and every row and
    // column in `at` is below n: `record` makes them from 0..n only, and
    // an elimination keeps its n for life; `gather` takes its entries from
    // `at`, and `solve_gathered`'s caller passes them with that
    // elimination's permutation of n.
    unsafe {
        let x = *v.get_unchecked(j);
        *v.get_unchecked_mut(i) -= a * x;
    }
}

#[cfg(test)]
mod tests {
    /// A pivot that falls under the threshold is refused: a 2 × 2 whose
    /// rows swap their sizes.
    #[test]
    fn a_small_pivot_asks_for_a_refresh() {
        let mut e = super::Elimination::new(2, [(0, 0), (0, 1), (1, 0), (1, 1)]);
        e.record(&[0, 1]);
        let (mut f, mut inv) = ([0.0; 4], [0.0; 2]);
        assert!(e
            .replay(&[1.0, 1.0, 0.5, 2.0, 0.0], &mut f, &mut inv, 1e-12)
            .is_ok());
        // Slots: L_10, U_00, U_11, U_01.
        assert_eq!(f, [0.5, 1.0, 1.5, 1.0]); // U_01 / U_00 = 1
        assert_eq!(
            e.replay(&[0.01, 1.0, 1.0, 2.0, 0.0], &mut f, &mut inv, 1e-12),
            Err(super::Refresh)
        );
        e.forget();
        assert_eq!(
            e.replay(&[1.0, 1.0, 0.5, 2.0, 0.0], &mut f, &mut inv, 1e-12),
            Err(super::Refresh)
        );
    }

    /// The compiled lists hold the factors' structure with fill-in: a
    /// tridiagonal matrix in its natural order has none, the same matrix
    /// with its first row moved last fills the rows below the moved one.
    #[test]
    fn fill_in_follows_the_pivot_order() {
        let n: usize = 5;
        let band = (0..n).flat_map(|i| (i.saturating_sub(1)..(i + 2).min(n)).map(move |j| (i, j)));
        let mut e = super::Elimination::new(n, band);
        e.record(&[0, 1, 2, 3, 4]);
        assert_eq!(e.slots(), 3 * n - 2);
        assert_eq!(e.solve_entries(), 2 * n - 2);
        // Rows 1, 2, 3, 4, 0: an upper Hessenberg-like order whose last
        // row (A's row 0: columns 0, 1) fills towards the end.
        e.record(&[1, 2, 3, 4, 0]);
        assert!(e.slots() > 3 * n - 2, "{} slots", e.slots());
    }
}
