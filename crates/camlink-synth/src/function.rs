//! Function generation with Freudenstein's equation.
//!
//! A four-bar with O₂ at the origin and O₄ = (d, 0) (the ground line along
//! +x), crank angle φ (input) and rocker angle ψ (output), both measured
//! counter-clockwise from the ground line O₂→O₄ (rad), closes its loop
//! a·u(φ) + b·u(θ₃) = (d, 0) + c·u(ψ) when (eliminating θ₃)
//!
//!   K₁ cos ψ − K₂ cos φ + K₃ = cos(φ − ψ),
//!   K₁ = d/a,  K₂ = d/c,  K₃ = (a² − b² + c² + d²)/(2ac)
//!
//! (Norton's form; Freudenstein's R₁ cos φ − R₂ cos ψ + R₃ = cos(φ − ψ) is
//! the same equation with the names of the two angles exchanged). The
//! equation is linear in K: three pairs (φ_j, ψ_j) fix K exactly (three
//! precision points); more pairs fix it in the least-squares sense of the
//! equation's residual. Given d, a = d/K₁, c = d/K₂ (signed: a negative
//! link points against its body axis, see [`crate::fourbar`]) and
//! b² = a² + c² + d² − 2ac·K₃.
//!
//! A function y = f(x), x ∈ [x_s, x_e], maps to angles linearly:
//! φ = φ_s + (x − x_s)/(x_e − x_s)·(φ_e − φ_s) and
//! ψ = ψ_s + (y − y_s)/(y_e − y_s)·(ψ_e − ψ_s), y_s = f(x_s), y_e = f(x_e).
//! The structural error is the mechanism's ψ minus the ψ asked for (rad).

use std::f64::consts::PI;

use camlink_expr::Expr;

use crate::error::{ErrorKind, SynthError};
use crate::fourbar::{unit, wrap_pi, Checks, FourBar, Requirements, P2};

/// The function to generate and its mapping to angles.
#[derive(Clone, Debug)]
pub struct FunctionSpec {
    /// y = f(x).
    pub f: Expr,
    /// The source text of `f`, for reports.
    pub source: String,
    /// x_s, x_e.
    pub x: [f64; 2],
    /// φ_s, φ_e (rad).
    pub input: [f64; 2],
    /// ψ_s, ψ_e (rad).
    pub output: [f64; 2],
    /// d (m).
    pub ground: f64,
}

impl FunctionSpec {
    /// (φ, ψ) asked for at `x` (rad).
    pub fn angles(&self, x: f64) -> (f64, f64) {
        let [xs, xe] = self.x;
        let (ys, ye) = (self.f.eval(xs), self.f.eval(xe));
        let phi = self.input[0] + (x - xs) / (xe - xs) * (self.input[1] - self.input[0]);
        let psi =
            self.output[0] + (self.f.eval(x) - ys) / (ye - ys) * (self.output[1] - self.output[0]);
        (phi, psi)
    }
}

/// The `n` Chebyshev points of [lo, hi]:
/// x_j = (lo + hi)/2 − (hi − lo)/2 · cos((2j − 1)π/(2n)), j = 1..n (increasing).
pub fn chebyshev(n: usize, lo: f64, hi: f64) -> Vec<f64> {
    (1..=n)
        .map(|j| {
            0.5 * (lo + hi) - 0.5 * (hi - lo) * ((2 * j - 1) as f64 * PI / (2 * n) as f64).cos()
        })
        .collect()
}

/// K from (φ_j, ψ_j) pairs (rad): exact for three, least squares for more.
///
/// Householder QR of the rows [cos ψ_j, −cos φ_j, 1] against cos(φ_j − ψ_j);
/// a column that is (nearly) a combination of the others, 1e-12 relative,
/// means the pairs do not determine K.
pub fn solve_k(pairs: &[(f64, f64)], field: &str) -> Result<[f64; 3], SynthError> {
    let m = pairs.len();
    if m < 3 {
        return Err(SynthError::new(
            ErrorKind::Invalid,
            field,
            format!("{m} points; Freudenstein's equation needs at least three"),
        ));
    }
    let mut a: Vec<[f64; 3]> = pairs
        .iter()
        .map(|&(phi, psi)| [psi.cos(), -phi.cos(), 1.0])
        .collect();
    let mut r: Vec<f64> = pairs.iter().map(|&(phi, psi)| (phi - psi).cos()).collect();
    let col_norm: Vec<f64> = (0..3)
        .map(|j| a.iter().map(|row| row[j] * row[j]).sum::<f64>().sqrt())
        .collect();
    for j in 0..3 {
        // Householder reflection zeroing column j below the diagonal.
        let norm = a[j..].iter().map(|row| row[j] * row[j]).sum::<f64>().sqrt();
        if norm <= 1e-12 * col_norm[j].max(1.0) {
            return Err(SynthError::new(
                ErrorKind::NoSolution,
                field,
                "the points do not determine Freudenstein's K₁, K₂, K₃ (two of them share an \
                 input or an output angle, or all lie on one linkage family); spread them out",
            ));
        }
        let alpha = if a[j][j] > 0.0 { -norm } else { norm };
        let mut v: Vec<f64> = a[j..].iter().map(|row| row[j]).collect();
        v[0] -= alpha;
        let vv: f64 = v.iter().map(|x| x * x).sum();
        for k in j..3 {
            let dot: f64 = v.iter().zip(&a[j..]).map(|(vi, row)| vi * row[k]).sum();
            for (vi, row) in v.iter().zip(a[j..].iter_mut()) {
                row[k] -= 2.0 * dot / vv * vi;
            }
        }
        let dot: f64 = v.iter().zip(&r[j..]).map(|(vi, ri)| vi * ri).sum();
        for (vi, ri) in v.iter().zip(r[j..].iter_mut()) {
            *ri -= 2.0 * dot / vv * vi;
        }
    }
    // Back substitution on R.
    let mut k = [0.0; 3];
    for j in (0..3).rev() {
        let s: f64 = (j + 1..3).map(|i| a[j][i] * k[i]).sum();
        k[j] = (r[j] - s) / a[j][j];
    }
    Ok(k)
}

/// The linkage of K for ground link d (m): O₂ = (0, 0), O₄ = (d, 0).
pub fn linkage_of(k: [f64; 3], d: f64, field: &str) -> Result<FourBar, SynthError> {
    // A link longer than 1e9 d is a slider, not a crank.
    for (kv, name) in [(k[0], "crank"), (k[1], "rocker")] {
        if kv.is_nan() || kv.abs() < 1e-9 {
            return Err(SynthError::new(
                ErrorKind::NoSolution,
                field,
                format!(
                    "the {name} would be infinitely long (K = {kv:e}): the points ask for a slider"
                ),
            ));
        }
    }
    let (a, c) = (d / k[0], d / k[1]);
    let b2 = a * a + c * c + d * d - 2.0 * a * c * k[2];
    if b2.is_nan() || b2 <= 0.0 {
        return Err(SynthError::new(
            ErrorKind::NoSolution,
            field,
            format!("no real coupler: b² = a² + c² + d² − 2ac·K₃ = {b2:.6e} m² is not positive"),
        ));
    }
    Ok(FourBar {
        o2: [0.0, 0.0],
        o4: [d, 0.0],
        crank: a,
        coupler: b2.sqrt(),
        rocker: c,
    })
}

/// How the K are fitted.
#[derive(Clone, Debug, PartialEq)]
pub enum Fit {
    /// Exactly through three precision points x_j.
    ThreePoint(Vec<f64>),
    /// Least squares over the points x_j (at least three).
    LeastSquares(Vec<f64>),
}

/// The structural error over a dense evaluation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StructuralError {
    /// Largest |ψ_mechanism − ψ_asked| (rad), and the x where it occurs.
    pub max: f64,
    pub at_x: f64,
    /// Root mean square over the samples (rad).
    pub rms: f64,
    pub samples: usize,
    /// The first x where the linkage does not assemble, if any.
    pub unassembled_at: Option<f64>,
}

/// A synthesised function generator.
#[derive(Clone, Debug)]
pub struct FunctionSolution {
    pub k: [f64; 3],
    pub linkage: FourBar,
    /// The x of the points fitted.
    pub x: Vec<f64>,
    /// (φ_j, ψ_j) asked for at those points (rad).
    pub pairs: Vec<(f64, f64)>,
    /// σ the mechanism runs on (that of the first point).
    pub sigma: f64,
    pub checks: Checks,
    pub error: StructuralError,
}

/// ψ of `linkage` at crank angle `phi` on branch `sigma`, as close to
/// `near` as a multiple of 2π makes it (rad); `None` where it does not
/// assemble.
pub fn output_angle(linkage: &FourBar, phi: f64, sigma: f64, near: f64) -> Option<f64> {
    let p = linkage.position(phi, sigma)?;
    Some(near + wrap_pi(p.psi - near))
}

/// Synthesises the function generator of `spec` by `fit`; the structural
/// error is evaluated at `samples` evenly spaced x (at least 2).
pub fn synthesise(
    spec: &FunctionSpec,
    fit: &Fit,
    samples: usize,
    req: &Requirements,
    field: &str,
) -> Result<FunctionSolution, SynthError> {
    let xs = match fit {
        Fit::ThreePoint(x) | Fit::LeastSquares(x) => x.clone(),
    };
    let pairs: Vec<(f64, f64)> = xs.iter().map(|&x| spec.angles(x)).collect();
    let k = solve_k(&pairs, field)?;
    let linkage = linkage_of(k, spec.ground, field)?;
    let pins: Vec<P2> = pairs
        .iter()
        .map(|&(phi, _)| linkage.crank_pin(phi))
        .collect();
    let rockers: Vec<P2> = pairs
        .iter()
        .map(|&(_, psi)| {
            let u = unit(psi);
            [
                linkage.o4[0] + linkage.rocker * u[0],
                linkage.o4[1] + linkage.rocker * u[1],
            ]
        })
        .collect();
    let checks = Checks::of(
        &linkage,
        &pins,
        &rockers,
        req,
        Some((spec.input[0], spec.input[1])),
    );
    let sigma = if checks.branches[0] != 0.0 {
        checks.branches[0]
    } else {
        1.0
    };
    let error = structural_error(spec, &linkage, sigma, samples);
    Ok(FunctionSolution {
        k,
        linkage,
        x: xs,
        pairs,
        sigma,
        checks,
        error,
    })
}

/// The structural error of `linkage` on branch `sigma` at `samples` evenly
/// spaced x over the range.
pub fn structural_error(
    spec: &FunctionSpec,
    linkage: &FourBar,
    sigma: f64,
    samples: usize,
) -> StructuralError {
    let n = samples.max(2);
    let (mut max, mut at_x, mut sum2) = (0.0f64, spec.x[0], 0.0);
    let mut unassembled_at = None;
    for i in 0..n {
        let x = spec.x[0] + (spec.x[1] - spec.x[0]) * i as f64 / (n - 1) as f64;
        let (phi, psi) = spec.angles(x);
        match output_angle(linkage, phi, sigma, psi) {
            Some(got) => {
                let e = got - psi;
                sum2 += e * e;
                if e.abs() > max {
                    max = e.abs();
                    at_x = x;
                }
            }
            None => {
                unassembled_at.get_or_insert(x);
            }
        }
    }
    StructuralError {
        max,
        at_x,
        rms: (sum2 / n as f64).sqrt(),
        samples: n,
        unassembled_at,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chebyshev_points_of_three() {
        let x = chebyshev(3, 1.0, 3.0);
        let h = 3f64.sqrt() / 2.0;
        assert!((x[0] - (2.0 - h)).abs() < 1e-15);
        assert!((x[1] - 2.0).abs() < 1e-15);
        assert!((x[2] - (2.0 + h)).abs() < 1e-15);
    }

    #[test]
    fn k_of_a_known_linkage_is_recovered() {
        // examples/four_bar.toml's linkage on its open branch.
        let l = FourBar {
            o2: [0.0, 0.0],
            o4: [0.4, 0.0],
            crank: 0.12,
            coupler: 0.38,
            rocker: 0.3,
        };
        let pairs: Vec<(f64, f64)> = [0.4, 1.3, 2.2]
            .iter()
            .map(|&phi| (phi, l.position(phi, 1.0).unwrap().psi))
            .collect();
        let k = solve_k(&pairs, "f").unwrap();
        let m = linkage_of(k, 0.4, "f").unwrap();
        assert!((m.crank - 0.12).abs() < 1e-13);
        assert!((m.coupler - 0.38).abs() < 1e-13);
        assert!((m.rocker - 0.3).abs() < 1e-13);
    }

    #[test]
    fn repeated_points_are_refused() {
        let e = solve_k(&[(0.1, 0.5), (0.1, 0.5), (0.9, 1.2)], "synthesis.x").unwrap_err();
        assert_eq!(e.kind, ErrorKind::NoSolution);
    }
}
