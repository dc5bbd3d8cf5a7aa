//! Linear solves with the constraint Jacobian.
//!
//! Dense LU with partial pivoting (faer), factored into a buffer allocated
//! once, so that refactoring inside the time loop allocates nothing.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::{Mat, MatMut, MatRef, Par};

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

/// P A = L U of a square matrix, with reusable storage.
pub struct DenseLu {
    lu: Mat<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    scratch: MemBuffer,
    valid: bool,
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
        for k in 0..n {
            let pivot = self.lu[(k, k)].abs() / scale;
            if !(pivot > SINGULAR_PIVOT) {
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
}
