//! Planar vector helpers of the Cartesian formulation.
//!
//! A body point with local vector s' is at r + A(φ) s' in the global frame,
//! where A(φ) is the rotation matrix and B(φ) = dA/dφ = A(φ) R, R being the
//! rotation by +π/2. Vectors are `[x, y]` in metres unless stated otherwise.

/// A planar vector `[x, y]`.
pub type V2 = [f64; 2];

/// A(φ) s: rotate `s` by `phi` (radians).
#[inline]
pub fn rot(phi: f64, s: V2) -> V2 {
    let (sn, cs) = phi.sin_cos();
    [cs * s[0] - sn * s[1], sn * s[0] + cs * s[1]]
}

/// B(φ) s = dA/dφ s = A(φ) s⊥.
#[inline]
pub fn rot_d(phi: f64, s: V2) -> V2 {
    let (sn, cs) = phi.sin_cos();
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

/// Euclidean norm ‖v‖₂ of a vector of any length.
pub fn norm2(v: &[f64]) -> f64 {
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
pub fn point_vel(q: [f64; 3], qd: [f64; 3], s: V2) -> V2 {
    add([qd[0], qd[1]], scale(qd[2], rot_d(q[2], s)))
}

#[cfg(test)]
mod tests {
    use super::*;

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
