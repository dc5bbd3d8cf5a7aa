//! Fourier series of one angle: f(α) = a₀ + Σₖ (aₖ cos kα + bₖ sin kα),
//! k = 1…n, with exact derivatives. Used as a cam radius ρ(α) (m).

use super::CurveError;

/// f(α) = a₀ + Σₖ (aₖ cos kα + bₖ sin kα); `a[k−1]` holds aₖ, `b[k−1]`
/// holds bₖ.
#[derive(Clone, Debug, PartialEq)]
pub struct Fourier {
    pub a0: f64,
    a: Vec<f64>,
    b: Vec<f64>,
}

impl Fourier {
    /// A series with cosine coefficients `a` and sine coefficients `b`
    /// (k = 1, 2, …); the shorter list is padded with zeros.
    pub fn new(a0: f64, a: &[f64], b: &[f64]) -> Result<Self, CurveError> {
        let n = a.len().max(b.len());
        let pad = |v: &[f64]| {
            let mut w = v.to_vec();
            w.resize(n, 0.0);
            w
        };
        let f = Fourier {
            a0,
            a: pad(a),
            b: pad(b),
        };
        if !a0.is_finite() || f.a.iter().chain(&f.b).any(|c| !c.is_finite()) {
            return Err(CurveError::Invalid(
                "a Fourier coefficient is not a finite number".into(),
            ));
        }
        Ok(f)
    }

    /// Cosine coefficients a₁…aₙ.
    pub fn a(&self) -> &[f64] {
        &self.a
    }

    /// Sine coefficients b₁…bₙ.
    pub fn b(&self) -> &[f64] {
        &self.b
    }

    /// `[f, f′, f″, f‴]` at α (rad).
    #[inline]
    pub fn jet(&self, alpha: f64) -> [f64; 4] {
        let mut out = [self.a0, 0.0, 0.0, 0.0];
        // cos kα and sin kα by the angle-addition recurrence.
        let (s1, c1) = alpha.sin_cos();
        let (mut s, mut c) = (s1, c1);
        for (k, (&ak, &bk)) in self.a.iter().zip(&self.b).enumerate() {
            let w = (k + 1) as f64;
            // Term t = a cos + b sin; t′ = w(−a sin + b cos); t″ = −w² t;
            // t‴ = −w² t′.
            let t = ak * c + bk * s;
            let td = w * (bk * c - ak * s);
            out[0] += t;
            out[1] += td;
            out[2] -= w * w * t;
            out[3] -= w * w * td;
            (s, c) = (s * c1 + c * s1, c * c1 - s * s1);
        }
        out
    }

    /// `[f, f′, f″, f‴, f⁗]` at α (rad); a term's t⁗ = w⁴ t.
    pub fn jet4(&self, alpha: f64) -> [f64; 5] {
        let [f0, f1, f2, f3] = self.jet(alpha);
        let (s1, c1) = alpha.sin_cos();
        let (mut s, mut c) = (s1, c1);
        let mut f4 = 0.0;
        for (k, (&ak, &bk)) in self.a.iter().zip(&self.b).enumerate() {
            let w2 = ((k + 1) * (k + 1)) as f64;
            f4 += w2 * w2 * (ak * c + bk * s);
            (s, c) = (s * c1 + c * s1, c * c1 - s * s1);
        }
        [f0, f1, f2, f3, f4]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jet_matches_closed_form() {
        let f = Fourier::new(1.0, &[0.2, 0.0, 0.05], &[0.0, -0.1]).unwrap();
        for &x in &[0.0, 0.4, 2.5, -1.3, 7.0] {
            let j = f.jet(x);
            let want = [
                1.0 + 0.2 * x.cos() - 0.1 * (2.0 * x).sin() + 0.05 * (3.0 * x).cos(),
                -0.2 * x.sin() - 0.2 * (2.0 * x).cos() - 0.15 * (3.0 * x).sin(),
                -0.2 * x.cos() + 0.4 * (2.0 * x).sin() - 0.45 * (3.0 * x).cos(),
                0.2 * x.sin() + 0.8 * (2.0 * x).cos() + 1.35 * (3.0 * x).sin(),
            ];
            for k in 0..4 {
                assert!((j[k] - want[k]).abs() < 1e-13, "{k}: {j:?} {want:?}");
            }
        }
    }

    #[test]
    fn rejects_non_finite_coefficients() {
        assert!(Fourier::new(1.0, &[f64::NAN], &[]).is_err());
    }
}
