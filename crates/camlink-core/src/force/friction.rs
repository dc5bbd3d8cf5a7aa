//! Coulomb friction in joints: the regularised law and the loads it puts
//! on a joint's two bodies at a given normal force (`docs/friction.md`).
//!
//! The law is the smooth Coulomb law of the expression function
//! `coulomb(v, fc, vs)` ([`camlink_expr::coulomb`]): with the slip speed v
//! (m/s) and the transition speed v_s (m/s),
//!
//! f(v) = μ s(v / v_s),  s(u) = (3u − u³)/2 for |u| ≤ 1, sign(u) beyond,
//!
//! so the friction is μ N sign(v) once |v| ≥ v_s and a cubic through 0
//! inside: a joint that sticks creeps at a speed below v_s at which the
//! friction balances the load (the creep bound of `docs/friction.md`).
//!
//! Two forms of load, each an [`Applied`] force at a fixed normal force N
//! (N, ≥ 0) that the dynamics layer computes from the joint's multipliers:
//!
//! - [`PinFriction`], a revolute joint of pin radius r (m): the slip speed
//!   at the pin's surface is v = r θ̇, θ̇ = φ̇_j − φ̇_i, and the friction
//!   torque T = −r N f(v) acts on body j, −T on body i;
//! - [`SlideFriction`], a sliding contact (translational joint, pin in a
//!   slot, cam contacts): with the contact points P_i, P_j (body frames,
//!   s'_i and s'_j) and the unit tangent t = A_k t'_k fixed in body k, the
//!   slip speed is v = tᵀ(ṙ_j^P − ṙ_i^P), ṙ^P = ṙ + B s' φ̇, and the
//!   friction force F = −N f(v) t acts on body j at P_j, −F on body i at
//!   P_i.
//!
//! The derivatives ∂Q/∂q, ∂Q/∂q̇ are exact at fixed N and fixed contact
//! geometry (s'_i, s'_j, t'_k).

use super::{Applied, BodyJac, BodyQ, ForceError};
use crate::constraint::{BodyId, Local};
use crate::math::{dot, perp, rot, rot_d, V2};

/// The transition speed v_s (m/s) when a model gives none.
pub const DEFAULT_TRANSITION_SPEED: f64 = 1e-4;

/// Coulomb friction of one joint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Friction {
    /// Friction coefficient μ ≥ 0.
    pub mu: f64,
    /// Pin radius r (m) ≥ 0 of a revolute joint; 0 for the other kinds.
    pub radius: f64,
    /// Transition speed v_s (m/s) > 0 of the regularised law.
    pub transition_speed: f64,
}

impl Friction {
    /// Friction μ of a sliding contact, with the default transition speed.
    pub fn sliding(mu: f64) -> Self {
        Friction {
            mu,
            radius: 0.0,
            transition_speed: DEFAULT_TRANSITION_SPEED,
        }
    }

    /// Friction μ in a revolute joint of pin radius r (m), with the
    /// default transition speed.
    pub fn pin(mu: f64, radius: f64) -> Self {
        Friction {
            radius,
            ..Friction::sliding(mu)
        }
    }

    /// Checks the numbers: μ ≥ 0, r ≥ 0, v_s > 0, all finite.
    pub fn validate(&self) -> Result<(), String> {
        let bad = |what: &str, v: f64, rule: &str| {
            Err(format!(
                "friction {what} must be {rule} ({})",
                crate::fmt_num::num(v)
            ))
        };
        if !(self.mu.is_finite() && self.mu >= 0.0) {
            return bad("coefficient mu", self.mu, "zero or positive");
        }
        if !(self.radius.is_finite() && self.radius >= 0.0) {
            return bad("radius (m)", self.radius, "zero or positive");
        }
        if !(self.transition_speed.is_finite() && self.transition_speed > 0.0) {
            return bad("transition_speed (m/s)", self.transition_speed, "positive");
        }
        Ok(())
    }

    /// [f(v), f′(v)]: the friction per newton of normal force at slip
    /// speed v (m/s), μ s(v/v_s), and its slope (s/m).
    #[inline]
    pub fn law(&self, v: f64) -> [f64; 2] {
        camlink_expr::coulomb(v, self.mu, self.transition_speed)
    }

    /// The slope (s/m) that Newton's iteration matrix takes for the law:
    /// inside the transition band the secant f(v)/v, which is at least the
    /// tangent f′(v) there (the law is concave for v > 0) and keeps the
    /// iteration from overshooting where f′ falls towards the band's
    /// edges; outside it the tangent, 0. (An iterate that would jump from
    /// outside the band across it is stopped at v = 0 by the dynamics,
    /// [`crate::dynamics::friction`].)
    #[inline]
    pub(crate) fn newton_slope(&self, v: f64) -> f64 {
        let [f, fd] = self.law(v);
        let inside = v.abs() < self.transition_speed;
        if inside && v.abs() > 1e-6 * self.transition_speed {
            fd.max(f / v)
        } else {
            fd
        }
    }
}

/// Friction torque in a revolute joint at normal force `normal` (N).
#[derive(Clone, Copy, Debug)]
pub struct PinFriction {
    pub bodies: [BodyId; 2],
    pub law: Friction,
    /// Normal force N (N): the magnitude of the pin's reaction force.
    pub normal: f64,
}

impl PinFriction {
    /// (T, v): the torque on body j (N·m) and the slip speed (m/s).
    pub fn torque(&self, x: &Local) -> (f64, f64) {
        let v = self.slip(x);
        (-self.law.radius * self.normal * self.law.law(v)[0], v)
    }

    /// The slip speed at the pin's surface v = r θ̇ (m/s).
    pub fn slip(&self, x: &Local) -> f64 {
        self.law.radius * (x.qd[1][2] - x.qd[0][2])
    }
}

impl Applied for PinFriction {
    fn kind(&self) -> &'static str {
        "pin_friction"
    }

    fn bodies(&self) -> [BodyId; 2] {
        self.bodies
    }

    fn generalized(&self, x: &Local, out: &mut BodyQ) -> Result<(), ForceError> {
        let (t, _) = self.torque(x);
        *out = [[0.0, 0.0, -t], [0.0, 0.0, t]];
        Ok(())
    }

    fn derivatives(&self, x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac) {
        self.derivatives_with(x, dq, dqd, |f, v| f.law(v)[1]);
    }
}

impl PinFriction {
    /// The derivatives with the law's slope f′ replaced by
    /// [`Friction::newton_slope`], for Newton's iteration matrix.
    pub(crate) fn newton_derivatives(&self, x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac) {
        self.derivatives_with(x, dq, dqd, Friction::newton_slope);
    }

    fn derivatives_with(
        &self,
        x: &Local,
        dq: &mut BodyJac,
        dqd: &mut BodyJac,
        slope: fn(&Friction, f64) -> f64,
    ) {
        *dq = BodyJac::default();
        *dqd = BodyJac::default();
        let r = self.law.radius;
        let v = r * (x.qd[1][2] - x.qd[0][2]);
        // ∂T/∂φ̇_j = −r² N f′(v) = −∂T/∂φ̇_i.
        let k = -r * r * self.normal * slope(&self.law, v);
        for (a, sa) in [(0, -1.0), (1, 1.0)] {
            for (b, sb) in [(0, -1.0), (1, 1.0)] {
                dqd[a][b][2][2] = sa * sb * k;
            }
        }
    }
}

/// Friction force at a sliding contact at normal force `normal` (N).
#[derive(Clone, Copy, Debug)]
pub struct SlideFriction {
    pub bodies: [BodyId; 2],
    pub law: Friction,
    /// Normal force N (N).
    pub normal: f64,
    /// Contact points s'_i, s'_j in the frames of bodies i and j (m).
    pub points: [V2; 2],
    /// The tangent t'_k (unit) in the frame of body k = `frame` (0: i, 1: j).
    pub tangent: V2,
    pub frame: usize,
}

impl SlideFriction {
    /// (F, v): the friction force on body j (N, global) and the slip
    /// speed (m/s).
    pub fn force(&self, x: &Local) -> (V2, f64) {
        let t = rot(x.q[self.frame][2], self.tangent);
        let v = dot(t, self.relative_velocity(x));
        let f = -self.normal * self.law.law(v)[0];
        ([f * t[0], f * t[1]], v)
    }

    /// The slip speed v = tᵀ(ṙ_j^P − ṙ_i^P) (m/s).
    pub fn slip(&self, x: &Local) -> f64 {
        dot(
            rot(x.q[self.frame][2], self.tangent),
            self.relative_velocity(x),
        )
    }

    /// ṙ_j^P − ṙ_i^P (m/s, global).
    fn relative_velocity(&self, x: &Local) -> V2 {
        let vel = |b: usize| {
            let bs = rot_d(x.q[b][2], self.points[b]);
            [
                x.qd[b][0] + bs[0] * x.qd[b][2],
                x.qd[b][1] + bs[1] * x.qd[b][2],
            ]
        };
        let (vi, vj) = (vel(0), vel(1));
        [vj[0] - vi[0], vj[1] - vi[1]]
    }
}

impl Applied for SlideFriction {
    fn kind(&self) -> &'static str {
        "slide_friction"
    }

    fn bodies(&self) -> [BodyId; 2] {
        self.bodies
    }

    fn generalized(&self, x: &Local, out: &mut BodyQ) -> Result<(), ForceError> {
        let (f, _) = self.force(x);
        for (b, sign) in [(0, -1.0), (1, 1.0)] {
            let bs = rot_d(x.q[b][2], self.points[b]);
            out[b] = [sign * f[0], sign * f[1], sign * dot(bs, f)];
        }
        Ok(())
    }

    fn derivatives(&self, x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac) {
        self.derivatives_with(x, dq, dqd, |f, v| f.law(v)[1]);
    }
}

impl SlideFriction {
    /// The derivatives with the law's slope f′ replaced by
    /// [`Friction::newton_slope`], for Newton's iteration matrix.
    pub(crate) fn newton_derivatives(&self, x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac) {
        self.derivatives_with(x, dq, dqd, Friction::newton_slope);
    }

    fn derivatives_with(
        &self,
        x: &Local,
        dq: &mut BodyJac,
        dqd: &mut BodyJac,
        slope: fn(&Friction, f64) -> f64,
    ) {
        let k = self.frame;
        let t = rot(x.q[k][2], self.tangent);
        let w = self.relative_velocity(x);
        let v = dot(t, w);
        let (f, fd) = (self.law.law(v)[0], slope(&self.law, v));
        let n = self.normal;
        let (f_j, _) = self.force(x);
        // ∂v/∂q̇ and ∂v/∂q per body b and coordinate c.
        let mut dv_dqd = [[0.0; 3]; 2];
        let mut dv_dq = [[0.0; 3]; 2];
        for (b, sign) in [(0, -1.0), (1, 1.0)] {
            let bs = rot_d(x.q[b][2], self.points[b]);
            let a_s = rot(x.q[b][2], self.points[b]);
            dv_dqd[b] = [sign * t[0], sign * t[1], sign * dot(t, bs)];
            // ∂(B s′ φ̇)/∂φ = −A s′ φ̇.
            dv_dq[b][2] = -sign * dot(t, a_s) * x.qd[b][2];
        }
        // ∂t/∂φ_k = B_k t′_k = t⊥.
        let tp = perp(t);
        dv_dq[k][2] += dot(tp, w);
        // ∂F/∂x = −N (f′ ∂v/∂x t + f ∂t/∂x), F on body j.
        let df = |dv: f64, turns_t: bool| -> V2 {
            let mut d = [-n * fd * dv * t[0], -n * fd * dv * t[1]];
            if turns_t {
                d[0] -= n * f * tp[0];
                d[1] -= n * f * tp[1];
            }
            d
        };
        for (a, sa) in [(0usize, -1.0), (1, 1.0)] {
            let bs = rot_d(x.q[a][2], self.points[a]);
            let a_s = rot(x.q[a][2], self.points[a]);
            for b in 0..2 {
                for c in 0..3 {
                    let dfq = df(dv_dq[b][c], b == k && c == 2);
                    let dfv = df(dv_dqd[b][c], false);
                    // Q_a = sa [F ; (B_a s′_a)ᵀF], ∂(B s′)/∂φ = −A s′.
                    let mut mq = dot(bs, dfq);
                    if b == a && c == 2 {
                        mq -= dot(a_s, f_j);
                    }
                    for r in 0..2 {
                        dq[a][b][r][c] = sa * dfq[r];
                        dqd[a][b][r][c] = sa * dfv[r];
                    }
                    dq[a][b][2][c] = sa * mq;
                    dqd[a][b][2][c] = sa * dot(bs, dfv);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::check;
    use super::*;

    fn law(vs: f64) -> Friction {
        Friction {
            mu: 0.3,
            radius: 0.02,
            transition_speed: vs,
        }
    }

    fn slide(frame: usize, vs: f64) -> SlideFriction {
        SlideFriction {
            bodies: [BodyId(1), BodyId(2)],
            law: law(vs),
            normal: 7.0,
            points: [[0.3, -0.1], [-0.2, 0.4]],
            tangent: [0.6, 0.8],
            frame,
        }
    }

    #[test]
    fn the_law_is_the_expression_coulomb() {
        let f = law(0.01);
        // s(u) = (3u − u³)/2 inside the band, ±1 outside.
        for (v, s) in [(0.005, (1.5 - 0.125) / 2.0), (-0.02, -1.0), (0.0, 0.0)] {
            assert!((f.law(v)[0] - 0.3 * s).abs() < 1e-15, "v = {v}");
        }
        assert!((f.law(0.0)[1] - 0.3 * 1.5 / 0.01).abs() < 1e-12);
    }

    #[test]
    fn the_newton_slope_is_the_secant_inside_the_band_and_the_tangent_outside() {
        let f = law(0.01);
        for v in [-0.0099, -0.004, 1e-7, 0.002, 0.0099] {
            let [value, slope] = f.law(v);
            let n = f.newton_slope(v);
            assert!(n >= slope && n > 0.0, "v = {v}");
            assert!(
                (n - value / v).abs() <= 1e-9 * n,
                "v = {v}: {n} vs {}",
                value / v
            );
        }
        for v in [-0.3, -0.01, 0.02, 5.0] {
            assert_eq!(f.newton_slope(v), f.law(v)[1], "v = {v}");
        }
        assert_eq!(f.newton_slope(0.0), f.law(0.0)[1]);
    }

    #[test]
    fn slide_derivatives_match_finite_differences() {
        // Slip speeds inside the transition band (vs = 5) and outside (vs = 0.05).
        for vs in [5.0, 0.05] {
            for frame in [0, 1] {
                for seed in 0..20 {
                    check::derivatives(&slide(frame, vs), &check::state(seed));
                }
            }
        }
    }

    #[test]
    fn pin_derivatives_match_finite_differences() {
        for vs in [5.0, 0.01] {
            let p = PinFriction {
                bodies: [BodyId(1), BodyId(2)],
                law: law(vs),
                normal: 12.0,
            };
            for seed in 0..20 {
                check::derivatives(&p, &check::state(seed));
            }
        }
    }

    #[test]
    fn friction_dissipates_and_opposes_the_slip() {
        let f = slide(0, 0.05);
        for seed in 0..20 {
            let x = check::state(seed);
            let (force, v) = f.force(&x);
            let mut q = BodyQ::default();
            f.generalized(&x, &mut q).unwrap();
            // Power Σ Q·q̇ = F·(ṙ_j^P − ṙ_i^P) = −N f(v) v ≤ 0.
            let power: f64 = (0..2)
                .map(|b| (0..3).map(|c| q[b][c] * x.qd[b][c]).sum::<f64>())
                .sum();
            let expect = -f.normal * f.law.law(v)[0] * v;
            assert!((power - expect).abs() < 1e-12, "{power} vs {expect}");
            assert!(power <= 0.0);
            // |F| = μ N outside the transition band.
            if v.abs() > 0.05 {
                let m = (force[0].powi(2) + force[1].powi(2)).sqrt();
                assert!((m - 0.3 * 7.0).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn pin_torque_is_mu_r_n_against_the_turning() {
        let p = PinFriction {
            bodies: [BodyId(1), BodyId::GROUND],
            law: law(1e-4),
            normal: 50.0,
        };
        let mut x = Local::default();
        x.qd[0][2] = 2.0; // body i turns; θ̇ = φ̇_j − φ̇_i = −2
        let mut q = BodyQ::default();
        p.generalized(&x, &mut q).unwrap();
        // The torque on body i opposes its turning: −μ r N.
        assert!((q[0][2] + 0.3 * 0.02 * 50.0).abs() < 1e-12);
        assert_eq!(q[1][2], -q[0][2]);
    }

    #[test]
    fn bad_numbers_are_refused() {
        let mut f = law(1e-4);
        assert!(f.validate().is_ok());
        f.mu = -0.1;
        assert!(f.validate().unwrap_err().contains("mu"));
        f.mu = 0.1;
        f.radius = -1.0;
        assert!(f.validate().unwrap_err().contains("radius"));
        f.radius = 0.0;
        f.transition_speed = 0.0;
        assert!(f.validate().unwrap_err().contains("transition_speed"));
    }
}
