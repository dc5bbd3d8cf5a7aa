//! Levenberg–Marquardt least squares for the small dense problems of path
//! synthesis: minimise ½|r(x)|² over x ∈ ℝⁿ, r: ℝⁿ → ℝᵐ.
//!
//! Each step solves (JᵀJ + λ·diag(JᵀJ)) h = −Jᵀr by Cholesky (Marquardt's
//! scaling), accepts it if |r| decreases (λ ← λ/3) and otherwise raises λ
//! (λ ← 4λ). The Jacobian J (m × n, row-major) is filled by the caller.

/// What a residual function provides.
pub trait Residual {
    /// Number of residuals m.
    fn count(&self) -> usize;
    /// r(x) into `r` (length m).
    fn eval(&self, x: &[f64], r: &mut [f64]);
    /// J(x) into `jac` (m × n, row-major), given r = r(x).
    fn jacobian(&self, x: &[f64], r: &[f64], jac: &mut [f64]);
}

/// Stopping rules.
#[derive(Clone, Copy, Debug)]
pub struct Settings {
    pub max_iter: usize,
    /// Stop when a step changes |r|² by less than this fraction.
    pub rel_tol: f64,
    /// Stop when |r|² falls below this.
    pub abs_tol: f64,
    /// (k, c): give up after k iterations if |r|² is still above c (a
    /// start of a global search that is going nowhere).
    pub give_up: Option<(usize, f64)>,
}

/// The result: the last accepted x, |r(x)|² and the iterations taken.
#[derive(Clone, Debug)]
pub struct Fit {
    pub x: Vec<f64>,
    pub cost: f64,
    pub iterations: usize,
}

/// Forward-difference Jacobian of columns `cols` (the others left as they
/// are): J[:, k] = (r(x + h e_k) − r(x)) / h, h = 1e-7·max(1, |x_k|).
pub fn forward_columns<R: Residual + ?Sized>(
    f: &R,
    x: &[f64],
    r: &[f64],
    cols: std::ops::Range<usize>,
    jac: &mut [f64],
) {
    let n = x.len();
    let m = r.len();
    let mut xp = x.to_vec();
    let mut rp = vec![0.0; m];
    for k in cols {
        let h = 1e-7 * x[k].abs().max(1.0);
        xp[k] = x[k] + h;
        f.eval(&xp, &mut rp);
        for i in 0..m {
            jac[i * n + k] = (rp[i] - r[i]) / h;
        }
        xp[k] = x[k];
    }
}

fn sq(r: &[f64]) -> f64 {
    r.iter().map(|v| v * v).sum()
}

/// Solves the symmetric positive definite `a` (n × n, row-major) x = b in
/// place of `b`; false if `a` is not positive definite.
fn cholesky_solve(a: &mut [f64], b: &mut [f64], n: usize) -> bool {
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        if d.is_nan() || d <= 0.0 || !d.is_finite() {
            return false;
        }
        let d = d.sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = s / d;
        }
    }
    // L y = b, then Lᵀ x = y.
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= a[i * n + k] * b[k];
        }
        b[i] = s / a[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= a[k * n + i] * b[k];
        }
        b[i] = s / a[i * n + i];
    }
    true
}

/// Minimises ½|r(x)|² from `x0`.
pub fn minimise<R: Residual + ?Sized>(f: &R, x0: &[f64], s: &Settings) -> Fit {
    let n = x0.len();
    let m = f.count();
    let mut x = x0.to_vec();
    let mut r = vec![0.0; m];
    f.eval(&x, &mut r);
    let mut cost = sq(&r);
    if !cost.is_finite() {
        return Fit {
            x,
            cost: f64::INFINITY,
            iterations: 0,
        };
    }
    let mut jac = vec![0.0; m * n];
    let mut jtj = vec![0.0; n * n];
    let mut g = vec![0.0; n];
    let mut a = vec![0.0; n * n];
    let mut h = vec![0.0; n];
    let mut xt = vec![0.0; n];
    let mut rt = vec![0.0; m];
    let mut lambda = 1e-3;
    let mut it = 0;
    'outer: while it < s.max_iter && cost > s.abs_tol {
        if s.give_up.is_some_and(|(k, c)| it >= k && cost > c) {
            break;
        }
        it += 1;
        f.jacobian(&x, &r, &mut jac);
        // JᵀJ and Jᵀr.
        jtj.iter_mut().for_each(|v| *v = 0.0);
        g.iter_mut().for_each(|v| *v = 0.0);
        for i in 0..m {
            let row = &jac[i * n..(i + 1) * n];
            for p in 0..n {
                let v = row[p];
                if v == 0.0 {
                    continue;
                }
                g[p] += v * r[i];
                for q in p..n {
                    jtj[p * n + q] += v * row[q];
                }
            }
        }
        for p in 0..n {
            for q in 0..p {
                jtj[p * n + q] = jtj[q * n + p];
            }
        }
        // Raise λ until a step lowers the cost.
        loop {
            a.copy_from_slice(&jtj);
            for p in 0..n {
                a[p * n + p] += lambda * jtj[p * n + p].max(1e-12);
            }
            for p in 0..n {
                h[p] = -g[p];
            }
            if cholesky_solve(&mut a, &mut h, n) {
                for p in 0..n {
                    xt[p] = x[p] + h[p];
                }
                f.eval(&xt, &mut rt);
                let ct = sq(&rt);
                if ct.is_finite() && ct < cost {
                    let drop = cost - ct;
                    x.copy_from_slice(&xt);
                    r.copy_from_slice(&rt);
                    cost = ct;
                    lambda = (lambda / 3.0).max(1e-12);
                    if drop <= s.rel_tol * cost {
                        break 'outer;
                    }
                    break;
                }
            }
            lambda *= 4.0;
            if lambda > 1e12 {
                break 'outer;
            }
        }
    }
    Fit {
        x,
        cost,
        iterations: it,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rosenbrock as least squares: r = (10(x₁ − x₀²), 1 − x₀), minimum at (1, 1).
    struct Rosen;
    impl Residual for Rosen {
        fn count(&self) -> usize {
            2
        }
        fn eval(&self, x: &[f64], r: &mut [f64]) {
            r[0] = 10.0 * (x[1] - x[0] * x[0]);
            r[1] = 1.0 - x[0];
        }
        fn jacobian(&self, x: &[f64], r: &[f64], jac: &mut [f64]) {
            forward_columns(self, x, r, 0..2, jac);
        }
    }

    #[test]
    fn rosenbrock_minimum() {
        let s = Settings {
            max_iter: 200,
            rel_tol: 0.0,
            abs_tol: 1e-28,
            give_up: None,
        };
        let fit = minimise(&Rosen, &[-1.2, 1.0], &s);
        assert!((fit.x[0] - 1.0).abs() < 1e-7 && (fit.x[1] - 1.0).abs() < 1e-7);
    }
}
