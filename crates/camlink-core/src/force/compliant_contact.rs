//! Compliant (Hunt–Crossley) contact of a unilateral cam contact: a normal
//! force from the overlap of the two features instead of an impact.
//!
//! With the gap g (m) and its rate ġ (m/s) of the features
//! ([`Features`]: witness points P_i, P_j and unit normal N from body i's
//! side to body j's), the overlap δ = −g and its rate δ̇ = −ġ, the normal
//! force is (Hunt & Crossley 1975)
//!
//! F = k δⁿ (1 + c δ̇)   for δ > 0, clamped at F ≥ 0; F = 0 apart,
//!
//! k the stiffness (N/mⁿ), n the exponent (3/2 for Hertz's contact of
//! elastic bodies), c the damping factor (s/m; Hunt and Crossley's
//! c ≈ 3 (1 − e) / (2 v⁻) for a restitution e at approach speed v⁻). F
//! pushes body j along N at P_j and body i against N at P_i:
//!
//! Q_j = [F N ; (P_j − r_j) × F N],  Q_i = −[F N ; (P_i − r_i) × F N].
//!
//! The force rises from zero as δⁿ (continuous, with its derivative for
//! n > 1), so the integrator steps through contact without events. ∂Q/∂q
//! and ∂Q/∂q̇ are central differences of Q (the witness points move with
//! the bodies); the potential of the elastic part is V = k δⁿ⁺¹/(n + 1).

use super::{central_derivatives, Applied, BodyJac, BodyQ, ForceError};
use crate::constraint::BodyId;
use crate::constraint::Local;
use crate::curve::distance::Features;
use crate::math::{cross, scale, sub};

/// Hunt–Crossley law of a compliant contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HuntCrossley {
    /// k (N/mⁿ).
    pub stiffness: f64,
    /// n, dimensionless (3/2: Hertz).
    pub exponent: f64,
    /// c (s/m).
    pub damping: f64,
}

impl HuntCrossley {
    /// F (N) at overlap δ (m) and overlap rate δ̇ (m/s).
    pub fn force(&self, delta: f64, rate: f64) -> f64 {
        if delta <= 0.0 {
            return 0.0;
        }
        (self.stiffness * delta.powf(self.exponent) * (1.0 + self.damping * rate)).max(0.0)
    }

    /// The elastic part's potential V = k δⁿ⁺¹/(n + 1) (J) at overlap δ (m).
    pub(crate) fn potential(&self, delta: f64) -> f64 {
        if delta <= 0.0 {
            return 0.0;
        }
        let n = self.exponent;
        self.stiffness * delta.powf(n + 1.0) / (n + 1.0)
    }
}

#[derive(Clone, Debug)]
pub struct CompliantContact {
    pub bodies: [BodyId; 2],
    pub features: Features,
    pub law: HuntCrossley,
}

/// Step of the central differences of Q (m, rad; m/s, rad/s).
const H: f64 = 1e-7;

impl CompliantContact {
    /// The normal force F (N) at the local state.
    pub fn normal_force(&self, x: &Local) -> f64 {
        let g = self.features.gap(x.q, x.qd, None);
        self.law.force(-g.gap, -g.rate)
    }

    /// Q_i and Q_j of the contact force at the local state (zero while
    /// the gap is open).
    fn contact_force(&self, x: &Local, out: &mut BodyQ) {
        *out = BodyQ::default();
        let g = self.features.gap(x.q, x.qd, None);
        let f = self.law.force(-g.gap, -g.rate);
        if f == 0.0 {
            return;
        }
        let fv = scale(f, g.normal);
        for (k, sign) in [(0, -1.0), (1, 1.0)] {
            let arm = sub(g.points[k], [x.q[k][0], x.q[k][1]]);
            out[k] = [sign * fv[0], sign * fv[1], sign * cross(arm, fv)];
        }
    }
}

impl Applied for CompliantContact {
    fn kind(&self) -> &'static str {
        "compliant_contact"
    }

    fn bodies(&self) -> [BodyId; 2] {
        self.bodies
    }

    fn generalized(&self, x: &Local, out: &mut BodyQ) -> Result<(), ForceError> {
        self.contact_force(x, out);
        Ok(())
    }

    fn derivatives(&self, x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac) {
        central_derivatives(x, H, |x, out| self.contact_force(x, out), dq, dqd);
    }

    fn potential(&self, x: &Local) -> f64 {
        self.law.potential(-self.features.gap(x.q, x.qd, None).gap)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::Polar;

    /// A disc of radius 0.1 m on body i over the ground's face y = 0.
    fn disc_on_floor(damping: f64) -> CompliantContact {
        CompliantContact {
            bodies: [BodyId(1), BodyId(0)],
            features: Features::Face {
                curve: Polar::circle([0.0, 0.0], 0.1).expect("circle").into(),
                point: [0.0, 0.0],
                m: [0.0, 1.0],
            },
            law: HuntCrossley {
                stiffness: 1e6,
                exponent: 1.5,
                damping,
            },
        }
    }

    fn at(y: f64, vy: f64) -> Local {
        let mut x = Local::default();
        x.q[0] = [0.2, y, 0.3];
        x.qd[0] = [0.5, vy, 1.0];
        x
    }

    #[test]
    fn force_is_k_delta_to_the_n_along_the_normal() {
        // Overlap 1 mm, approaching at 0.2 m/s, c = 0.5 s/m:
        // F = 1e6 · 1e-3^1.5 · (1 + 0.5 · 0.2) on the disc, upwards, through
        // its centre (no moment about the body origin at the centre).
        let c = disc_on_floor(0.5);
        let mut q = BodyQ::default();
        c.generalized(&at(0.099, -0.2), &mut q).unwrap();
        let f = 1e6 * 1e-3f64.powf(1.5) * 1.1;
        assert!((q[0][1] - f).abs() < 1e-9 * f, "{q:?}");
        assert!(q[0][0].abs() < 1e-12 && q[0][2].abs() < 1e-12 * f, "{q:?}");
        // Apart, or separating fast enough: no force.
        c.generalized(&at(0.1001, -0.2), &mut q).unwrap();
        assert_eq!(q, BodyQ::default());
        c.generalized(&at(0.099, 3.0), &mut q).unwrap();
        assert_eq!(q, BodyQ::default());
    }

    #[test]
    fn potential_is_the_work_of_the_elastic_force() {
        // −dV/dy = Q_y without damping.
        let c = disc_on_floor(0.0);
        let h = 1e-7;
        let mut q = BodyQ::default();
        c.generalized(&at(0.0985, 0.0), &mut q).unwrap();
        let dv =
            (c.potential(&at(0.0985 + h, 0.0)) - c.potential(&at(0.0985 - h, 0.0))) / (2.0 * h);
        assert!(
            (q[0][1] + dv).abs() < 1e-6 * q[0][1],
            "{} vs {}",
            q[0][1],
            -dv
        );
    }
}
