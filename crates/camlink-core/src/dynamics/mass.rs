//! Mass matrix, gravity and velocity-quadratic forces of a body whose frame
//! need not sit at its centroid.
//!
//! Body k has mass m (kg), polar moment of inertia J' about its centroid
//! (kg·m²) and its centroid at s'_c in the body frame (m). Its coordinates
//! q = (r, φ) are those of the body frame, so the centroid is at
//! r_c = r + A s'_c and ṙ_c = ṙ + B s'_c φ̇. The kinetic energy
//!
//! T = ½ m ṙ_cᵀṙ_c + ½ J' φ̇² = ½ q̇ᵀ M(φ) q̇
//!
//! gives the full mass matrix with the offset terms (Haug's
//! M = diag(m, m, J') is the case s'_c = 0):
//!
//! M = [ m I        m B s'_c
//!       m (B s'_c)ᵀ  J' + m s'_cᵀs'_c ].
//!
//! M depends on φ, so Lagrange's equations add a velocity-quadratic force
//! Q_v = [m A s'_c φ̇² ; 0] (the centripetal force of the centroid about the
//! frame origin; the φ row cancels). Gravity g (m/s², global) acts at the
//! centroid: Q_g = [m g ; m (B s'_c)ᵀ g], with potential V = −m gᵀ r_c.
//!
//! The body's equation of motion is M q̈ = Q_g + Q_v + (applied) + (reaction).
//! For Newton iteration matrices, R = M q̈ − Q_g − Q_v has the derivatives
//! (non-zero only in the φ and φ̇ columns):
//! - ∂R/∂φ = [−m A s'_c φ̈ − m B s'_c φ̇² ; −m (A s'_c)ᵀ(r̈ − g)],
//! - ∂R/∂φ̇ = [−2 m A s'_c φ̇ ; 0].

use crate::math::{dot, perp, rot, V2};
use crate::model::Body;

/// The inertia of one body.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Inertia {
    /// m (kg).
    pub mass: f64,
    /// J' about the centroid (kg·m²).
    pub inertia: f64,
    /// s'_c in the body frame (m).
    pub centroid: V2,
}

impl From<&Body> for Inertia {
    fn from(b: &Body) -> Self {
        Inertia {
            mass: b.mass,
            inertia: b.inertia,
            centroid: b.centroid,
        }
    }
}

impl Inertia {
    /// Whether the body frame is at the centroid (s'_c = 0): M is then
    /// constant and diagonal, and no term below needs φ.
    #[inline]
    pub fn centred(&self) -> bool {
        self.centroid == [0.0, 0.0]
    }

    /// A(φ) s'_c and B(φ) s'_c = (A(φ) s'_c)⊥ (m), without trigonometry for
    /// a centred body.
    #[inline]
    fn arm(&self, phi: f64) -> (V2, V2) {
        if self.centred() {
            return ([0.0; 2], [0.0; 2]);
        }
        let a = rot(phi, self.centroid);
        (a, perp(a))
    }

    /// M(φ) (3 × 3, row-major).
    #[inline]
    pub fn matrix(&self, phi: f64) -> [[f64; 3]; 3] {
        let m = self.mass;
        let (_, b) = self.arm(phi);
        let j = self.inertia + m * dot(self.centroid, self.centroid);
        [
            [m, 0.0, m * b[0]],
            [0.0, m, m * b[1]],
            [m * b[0], m * b[1], j],
        ]
    }

    /// Q_g + Q_v: gravity and the velocity-quadratic force (N, N, N·m).
    #[inline]
    pub fn loads(&self, q: [f64; 3], qd: [f64; 3], g: V2) -> [f64; 3] {
        let m = self.mass;
        let (a, b) = self.arm(q[2]);
        let w2 = qd[2] * qd[2];
        [
            m * (g[0] + a[0] * w2),
            m * (g[1] + a[1] * w2),
            m * dot(b, g),
        ]
    }

    /// The φ column of ∂R/∂q and the φ̇ column of ∂R/∂q̇, where
    /// R = M q̈ − Q_g − Q_v.
    #[inline]
    pub fn derivatives(
        &self,
        q: [f64; 3],
        qd: [f64; 3],
        qdd: [f64; 3],
        g: V2,
    ) -> ([f64; 3], [f64; 3]) {
        let m = self.mass;
        let (a, b) = self.arm(q[2]);
        let (w, al) = (qd[2], qdd[2]);
        let dphi = [
            -m * (a[0] * al + b[0] * w * w),
            -m * (a[1] * al + b[1] * w * w),
            -m * (a[0] * (qdd[0] - g[0]) + a[1] * (qdd[1] - g[1])),
        ];
        let domega = [-2.0 * m * a[0] * w, -2.0 * m * a[1] * w, 0.0];
        (dphi, domega)
    }

    /// R = M q̈ − Q_g − Q_v.
    #[inline]
    pub fn residual(&self, q: [f64; 3], qd: [f64; 3], qdd: [f64; 3], g: V2) -> [f64; 3] {
        let m = self.mass;
        let (a, b) = self.arm(q[2]);
        let c = self.centroid;
        let j = self.inertia + m * dot(c, c);
        let w2 = qd[2] * qd[2];
        [
            m * (qdd[0] + b[0] * qdd[2] - g[0] - a[0] * w2),
            m * (qdd[1] + b[1] * qdd[2] - g[1] - a[1] * w2),
            m * (b[0] * (qdd[0] - g[0]) + b[1] * (qdd[1] - g[1])) + j * qdd[2],
        ]
    }

    /// Kinetic energy T = ½ q̇ᵀ M q̇ (J).
    #[inline]
    pub fn kinetic(&self, q: [f64; 3], qd: [f64; 3]) -> f64 {
        let mm = self.matrix(q[2]);
        let mut t = 0.0;
        for r in 0..3 {
            for c in 0..3 {
                t += qd[r] * mm[r][c] * qd[c];
            }
        }
        0.5 * t
    }

    /// Gravitational potential V = −m gᵀ r_c (J).
    #[inline]
    pub fn potential(&self, q: [f64; 3], g: V2) -> f64 {
        let (a, _) = self.arm(q[2]);
        -self.mass * (g[0] * (q[0] + a[0]) + g[1] * (q[1] + a[1]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body() -> Inertia {
        Inertia {
            mass: 2.5,
            inertia: 0.3,
            centroid: [0.4, -0.15],
        }
    }

    /// A body whose frame is at its centroid.
    fn centred() -> Inertia {
        Inertia {
            centroid: [0.0, 0.0],
            ..body()
        }
    }

    /// Lagrange's equations by finite differences of T and V:
    /// d/dt(∂T/∂q̇) − ∂T/∂q + ∂V/∂q = M q̈ − Q_g − Q_v.
    #[test]
    fn loads_follow_from_lagrange() {
        for b in [body(), centred()] {
            loads_follow_from_lagrange_for(b);
        }
    }

    fn loads_follow_from_lagrange_for(b: Inertia) {
        let g = [0.3, -9.81];
        let q = [0.1, 0.2, 0.7];
        let qd = [0.5, -0.4, 1.3];
        let qdd = [0.2, 0.9, -2.0];
        let h = 1e-5;
        // ∂T/∂q̇ = M q̇; its time derivative by the chain rule, numerically.
        let p = |q: [f64; 3], qd: [f64; 3]| -> [f64; 3] {
            let mm = b.matrix(q[2]);
            [0, 1, 2].map(|r| (0..3).map(|c| mm[r][c] * qd[c]).sum())
        };
        let shift = |v: [f64; 3], d: [f64; 3], s: f64| [0, 1, 2].map(|k| v[k] + s * d[k]);
        let pp = p(shift(q, qd, h), shift(qd, qdd, h));
        let pm = p(shift(q, qd, -h), shift(qd, qdd, -h));
        let mm = b.matrix(q[2]);
        let loads = b.loads(q, qd, g);
        for k in 0..3 {
            let mut e = [0.0; 3];
            e[k] = h;
            let dt_dq =
                (b.kinetic(shift(q, e, 1.0), qd) - b.kinetic(shift(q, e, -1.0), qd)) / (2.0 * h);
            let dv_dq =
                (b.potential(shift(q, e, 1.0), g) - b.potential(shift(q, e, -1.0), g)) / (2.0 * h);
            let lagrange = (pp[k] - pm[k]) / (2.0 * h) - dt_dq + dv_dq;
            let ours: f64 = (0..3).map(|c| mm[k][c] * qdd[c]).sum::<f64>() - loads[k];
            assert!(
                (lagrange - ours).abs() < 1e-7,
                "row {k}: {lagrange} vs {ours}"
            );
            assert!((b.residual(q, qd, qdd, g)[k] - ours).abs() < 1e-12);
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        for b in [body(), centred()] {
            derivatives_match_finite_differences_for(b);
        }
    }

    fn derivatives_match_finite_differences_for(b: Inertia) {
        let g = [0.3, -9.81];
        let q = [0.1, 0.2, 0.7];
        let qd = [0.5, -0.4, 1.3];
        let qdd = [0.2, 0.9, -2.0];
        let r = |q: [f64; 3], qd: [f64; 3]| -> [f64; 3] {
            let mm = b.matrix(q[2]);
            let l = b.loads(q, qd, g);
            [0, 1, 2].map(|k| (0..3).map(|c| mm[k][c] * qdd[c]).sum::<f64>() - l[k])
        };
        let (dphi, domega) = b.derivatives(q, qd, qdd, g);
        let h = 1e-6;
        let (mut qp, mut qm) = (q, q);
        qp[2] += h;
        qm[2] -= h;
        let (mut vp, mut vm) = (qd, qd);
        vp[2] += h;
        vm[2] -= h;
        for k in 0..3 {
            let fd = (r(qp, qd)[k] - r(qm, qd)[k]) / (2.0 * h);
            assert!((fd - dphi[k]).abs() < 1e-7, "dR/dφ[{k}]");
            let fd = (r(q, vp)[k] - r(q, vm)[k]) / (2.0 * h);
            assert!((fd - domega[k]).abs() < 1e-7, "dR/dω[{k}]");
        }
    }
}
