//! A recorded elimination for the small dense LU ([`crate::linsolve::SmallLu`]):
//! refactor with the pivot order of the last pivoted factorization.
//!
//! A mechanism's Φ_q keeps its sparsity pattern, and from one step to the
//! next its values change little, so the rows that partial pivoting picks
//! rarely change. After a pivoted factorization P A = L U, the elimination
//! is recorded symbolically over A's pattern (with fill-in): for each pivot
//! k, the rows i > k with L_ik structurally nonzero and the columns j > k
//! with U_kj structurally nonzero. The next factorization replays only
//! those updates, in the same order, with no pivot search.
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
pub const THRESHOLD: f64 = 0.1;

/// The recorded elimination of an n × n matrix with a fixed pattern.
#[derive(Clone, Debug)]
pub struct Elimination {
    n: usize,
    /// The structural nonzeros of A, row-major.
    pattern: Vec<bool>,
    /// Scratch: the pattern of the factors being recorded, row-major.
    filled: Vec<bool>,
    /// Row k of the factors is row `perm[k]` of A.
    perm: Vec<usize>,
    /// For pivot k, rows `below[below_start[k]..below_start[k + 1]]`
    /// (indices in the permuted order) have L_ik ≠ 0.
    below: Vec<usize>,
    below_start: Vec<usize>,
    /// For pivot k, columns `right[right_start[k]..right_start[k + 1]]`
    /// have U_kj ≠ 0 (j > k).
    right: Vec<usize>,
    right_start: Vec<usize>,
    /// The entries of A in the pattern, as indices into the row-major matrix.
    entries: Vec<usize>,
    /// The structural nonzeros of the factors, row by row, for
    /// [`gather`](Self::gather): (column, index into the row-major factors) of L's strictly lower
    /// part, rows starting at `lower_start`, and of U's strictly upper part.
    lower: Vec<(usize, usize)>,
    lower_start: Vec<usize>,
    upper: Vec<(usize, usize)>,
    upper_start: Vec<usize>,
    recorded: bool,
}

/// Why a replay stopped: the caller factors with pivoting instead.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Refresh;

impl Elimination {
    /// For an n × n matrix whose nonzeros are at `pattern` (row, col);
    /// all storage is made here, so recording and replaying allocate nothing.
    pub fn new(n: usize, pattern: impl IntoIterator<Item = (usize, usize)>) -> Self {
        let mut p = vec![false; n * n];
        for (r, c) in pattern {
            p[r * n + c] = true;
        }
        let entries = (0..n * n).filter(|&k| p[k]).collect();
        Elimination {
            n,
            pattern: p,
            filled: vec![false; n * n],
            perm: (0..n).collect(),
            below: Vec::with_capacity(n * n),
            below_start: vec![0; n + 1],
            right: Vec::with_capacity(n * n),
            right_start: vec![0; n + 1],
            entries,
            lower: Vec::with_capacity(n * n),
            lower_start: vec![0; n + 1],
            upper: Vec::with_capacity(n * n),
            upper_start: vec![0; n + 1],
            recorded: false,
        }
    }

    /// Whether (r, c) is in the pattern.
    pub fn in_pattern(&self, r: usize, c: usize) -> bool {
        self.pattern[r * self.n + c]
    }

    /// Forgets the recorded order (the next replay refreshes).
    pub fn forget(&mut self) {
        self.recorded = false;
    }

    /// The largest |a_rc| over the pattern (at least the smallest normal number).
    pub fn scale(&self, a: &[f64]) -> f64 {
        self.entries
            .iter()
            .fold(f64::MIN_POSITIVE, |s, &k| s.max(a[k].abs()))
    }

    /// Records the elimination of a pivoted factorization whose row k is
    /// row `perm[k]` of A.
    pub fn record(&mut self, perm: &[usize]) {
        let n = self.n;
        self.perm.copy_from_slice(perm);
        for (k, &p) in perm.iter().enumerate() {
            self.filled[k * n..k * n + n].copy_from_slice(&self.pattern[p * n..p * n + n]);
        }
        self.below.clear();
        self.right.clear();
        for k in 0..n {
            self.below_start[k] = self.below.len();
            self.right_start[k] = self.right.len();
            for j in k + 1..n {
                if self.filled[k * n + j] {
                    self.right.push(j);
                }
            }
            for i in k + 1..n {
                if self.filled[i * n + k] {
                    self.below.push(i);
                    for &j in &self.right[self.right_start[k]..] {
                        self.filled[i * n + j] = true;
                    }
                }
            }
        }
        self.below_start[n] = self.below.len();
        self.right_start[n] = self.right.len();
        self.lower.clear();
        self.upper.clear();
        for i in 0..n {
            self.lower_start[i] = self.lower.len();
            self.upper_start[i] = self.upper.len();
            for j in 0..i {
                if self.filled[i * n + j] {
                    self.lower.push((j, i * n + j));
                }
            }
            for j in i + 1..n {
                if self.filled[i * n + j] {
                    self.upper.push((j, i * n + j));
                }
            }
        }
        self.lower_start[n] = self.lower.len();
        self.upper_start[n] = self.upper.len();
        self.recorded = true;
    }

    /// Gathers the nonzeros of factors `lu` made in the recorded order,
    /// visiting their structural nonzeros only: (column, value) of L's
    /// strictly lower part and of U's strictly upper part, row by row, with
    /// the start of each row in `starts` (L rows, then U rows), as
    /// [`crate::linsolve::SmallLu`]'s solves read them.
    pub fn gather(&self, lu: &[f64], nonzeros: &mut [(usize, f64)], starts: &mut [usize]) {
        let n = self.n;
        let mut len = 0;
        for (part, (list, first)) in [
            (&self.lower, &self.lower_start),
            (&self.upper, &self.upper_start),
        ]
        .into_iter()
        .enumerate()
        {
            for i in 0..n {
                starts[part * n + i] = len;
                for &(j, k) in &list[first[i]..first[i + 1]] {
                    nonzeros[len] = (j, lu[k]);
                    len += usize::from(lu[k] != 0.0);
                }
            }
        }
        starts[2 * n] = len;
    }

    /// P A = L U of `a` (row-major) into `lu` with the recorded pivot order,
    /// the reciprocals of the pivots into `inv_diag`; returns the smallest
    /// pivot relative to `scale`, or [`Refresh`] when
    /// there is no recorded order or a pivot fails the threshold or
    /// singular test (`lu` is then meaningless).
    pub fn replay(
        &self,
        a: &[f64],
        lu: &mut [f64],
        inv_diag: &mut [f64],
        scale: f64,
        singular: f64,
    ) -> Result<f64, Refresh> {
        if !self.recorded {
            return Err(Refresh);
        }
        let n = self.n;
        for (k, &p) in self.perm.iter().enumerate() {
            lu[k * n..k * n + n].copy_from_slice(&a[p * n..p * n + n]);
        }
        let mut min_pivot = f64::INFINITY;
        for k in 0..n {
            let pivot = lu[k * n + k];
            let below = &self.below[self.below_start[k]..self.below_start[k + 1]];
            let big = below
                .iter()
                .fold(0.0f64, |b, &i| b.max(lu[i * n + k].abs()));
            let ratio = pivot.abs() / scale;
            // Written so that a NaN fails.
            if !(pivot.abs() >= THRESHOLD * big && ratio > singular) {
                return Err(Refresh);
            }
            min_pivot = min_pivot.min(ratio);
            let inv = 1.0 / pivot;
            inv_diag[k] = inv;
            let right = &self.right[self.right_start[k]..self.right_start[k + 1]];
            let (top, rest) = lu.split_at_mut((k + 1) * n);
            let pivot_row = &top[k * n..k * n + n];
            for &i in below {
                let row = &mut rest[(i - k - 1) * n..(i - k) * n];
                let l = row[k] * inv;
                row[k] = l;
                for &j in right {
                    row[j] -= l * pivot_row[j];
                }
            }
        }
        Ok(min_pivot)
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
        let (mut lu, mut inv) = ([0.0; 4], [0.0; 2]);
        assert!(e
            .replay(&[1.0, 1.0, 0.5, 2.0], &mut lu, &mut inv, 2.0, 1e-12)
            .is_ok());
        assert_eq!(lu, [1.0, 1.0, 0.5, 1.5]);
        assert_eq!(
            e.replay(&[0.01, 1.0, 1.0, 2.0], &mut lu, &mut inv, 2.0, 1e-12),
            Err(super::Refresh)
        );
        e.forget();
        assert_eq!(
            e.replay(&[1.0, 1.0, 0.5, 2.0], &mut lu, &mut inv, 2.0, 1e-12),
            Err(super::Refresh)
        );
    }
}
