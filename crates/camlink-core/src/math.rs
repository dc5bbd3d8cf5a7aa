//! Planar vector helpers of the Cartesian formulation.
//!
//! A body point with local vector s' is at r + A(φ) s' in the global frame,
//! where A(φ) is the rotation matrix and B(φ) = dA/dφ = A(φ) R, R being the
//! rotation by +π/2. Vectors are `[x, y]` in metres unless stated otherwise.

/// A planar vector `[x, y]`.
pub type V2 = [f64; 2];

/// Entries of the [`sin_cos`] memo (a power of two).
const MEMO: usize = 8;

std::thread_local! {
    /// Recent (φ bits, sin φ, cos φ), by a hash of the bits; NaN entries
    /// to start with, which give NaN for a NaN angle as the functions do.
    static SIN_COS: [std::cell::Cell<(u64, f64, f64)>; MEMO] = const {
        [const { std::cell::Cell::new((f64::NAN.to_bits(), f64::NAN, f64::NAN)) }; MEMO]
    };
}

/// (sin φ, cos φ), remembered for the last few angles of this thread.
///
/// One pass over a mechanism's joints rotates the same few body angles
/// many times (each revolute joint turns two points, every equation and
/// its Jacobian at the same q); the memo answers the repeats without
/// evaluating the functions again. The values are exactly those of
/// `f64::sin_cos`.
#[inline]
pub fn sin_cos(phi: f64) -> (f64, f64) {
    let bits = phi.to_bits();
    let slot = ((bits ^ (bits >> 32)).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 61) as usize;
    SIN_COS.with(|memo| {
        let entry = &memo[slot % MEMO];
        let (b, sn, cs) = entry.get();
        if b == bits {
            return (sn, cs);
        }
        let (sn, cs) = phi.sin_cos();
        entry.set((bits, sn, cs));
        (sn, cs)
    })
}

/// A(φ) s: rotate `s` by `phi` (radians).
#[inline]
pub fn rot(phi: f64, s: V2) -> V2 {
    let (sn, cs) = sin_cos(phi);
    [cs * s[0] - sn * s[1], sn * s[0] + cs * s[1]]
}

/// B(φ) s = dA/dφ s = A(φ) s⊥.
#[inline]
pub(crate) fn rot_d(phi: f64, s: V2) -> V2 {
    let (sn, cs) = sin_cos(phi);
    [-sn * s[0] - cs * s[1], cs * s[0] - sn * s[1]]
}

/// Aᵀ(φ) v: express a global vector in a frame rotated by `phi`.
#[inline]
pub fn rot_t(phi: f64, v: V2) -> V2 {
    rot(-phi, v)
}

/// s⊥ = R s, the vector rotated by +π/2.
#[inline]
pub fn perp(s: V2) -> V2 {
    [-s[1], s[0]]
}

#[inline]
pub fn add(a: V2, b: V2) -> V2 {
    [a[0] + b[0], a[1] + b[1]]
}

#[inline]
pub fn sub(a: V2, b: V2) -> V2 {
    [a[0] - b[0], a[1] - b[1]]
}

#[inline]
pub fn scale(k: f64, a: V2) -> V2 {
    [k * a[0], k * a[1]]
}

#[inline]
pub fn dot(a: V2, b: V2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// The scalar cross product a × b = aᵀ(−b⊥)… written a₀b₁ − a₁b₀.
#[inline]
pub fn cross(a: V2, b: V2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

#[inline]
pub fn norm(a: V2) -> f64 {
    a[0].hypot(a[1])
}

/// aᵀb of two vectors of the same length.
pub fn inner(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Euclidean norm ‖v‖₂ of a vector of any length.
pub(crate) fn norm2(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// max |v_k| (the residual norm of the solvers), or NaN when any entry is
/// NaN, so that a failed evaluation is never taken for convergence.
pub fn max_abs(v: &[f64]) -> f64 {
    let mut m = 0.0f64;
    for &x in v {
        if x.is_nan() {
            return f64::NAN;
        }
        m = m.max(x.abs());
    }
    m
}

/// Position r + A(φ) s' of a body point, from body coordinates `q = (x, y, φ)`.
#[inline]
pub fn point(q: [f64; 3], s: V2) -> V2 {
    add([q[0], q[1]], rot(q[2], s))
}

/// Velocity ṙ + B(φ) s' φ̇ of a body point.
#[inline]
pub(crate) fn point_vel(q: [f64; 3], qd: [f64; 3], s: V2) -> V2 {
    add([qd[0], qd[1]], scale(qd[2], rot_d(q[2], s)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn remembered_sin_cos_is_exactly_the_function() {
        // More angles than memo entries, repeated, so entries are both
        // reused and evicted; signed zeros and NaN included.
        let mut angles: Vec<f64> = (0..40).map(|k| (k as f64 * 0.731).sin() * 7.0).collect();
        angles.extend([0.0, -0.0, f64::NAN, 1e-300, -3.5]);
        for _ in 0..3 {
            for &a in &angles {
                let (s, c) = sin_cos(a);
                let (s0, c0) = a.sin_cos();
                assert_eq!(s.to_bits(), s0.to_bits(), "sin {a}");
                assert_eq!(c.to_bits(), c0.to_bits(), "cos {a}");
            }
        }
    }

    #[test]
    fn b_is_derivative_of_a() {
        let (phi, s, h) = (0.7, [0.3, -1.2], 1e-6);
        let fd = scale(1.0 / (2.0 * h), sub(rot(phi + h, s), rot(phi - h, s)));
        let b = rot_d(phi, s);
        assert!((fd[0] - b[0]).abs() < 1e-9 && (fd[1] - b[1]).abs() < 1e-9);
        assert_eq!(rot_d(phi, s), rot(phi, perp(s)));
    }

    #[test]
    fn rot_t_inverts_rot() {
        let v = rot_t(1.1, rot(1.1, [2.0, 3.0]));
        assert!((v[0] - 2.0).abs() < 1e-14 && (v[1] - 3.0).abs() < 1e-14);
    }
}
