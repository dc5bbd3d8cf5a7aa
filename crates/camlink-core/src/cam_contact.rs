//! Contact stress, camshaft torque and roller-bearing life of a
//! synthesised cam ([`crate::cam`]) over one turn at constant speed.
//!
//! At each of the [`crate::cam_limits::SAMPLES`] cam angles θ the normal
//! contact force F (N) is that of [`crate::cam_limits::force`] (the rigid
//! follower train held on by its spring), and the surfaces are two
//! cylinders ([`crate::cam::hertz`]): the cam's radius of curvature ρ
//! against the roller radius R_r, or against a flat face (1/R₂ = 0), over
//! the contact width L; the largest peak pressure p_max is refined by
//! golden-section search.
//!
//! **Camshaft torque.** With no friction the cam's power is the follower's:
//! T ω = Q ṡ, so T = Q s′ (N·m), Q the generalised force the cam supplies
//! (N or N·m) and s′ = ds/dθ (m/rad or rad/rad). Positive T resists the
//! cam's rotation (the cam does work).
//!
//! **Roller bearing.** The roller turns on its pin at
//! |t · (v_cam − v_follower)|/R_r at the contact P (ground frame, t the
//! contact tangent): v_cam = σω ẑ × P, and the follower's material velocity
//! at P is ω s′ ŷ for a translating follower or −ω s′ ẑ × (P − pivot) for an
//! oscillating one (ψ = ψ₀ − s). The equivalent load P_eq is the mean of F^a
//! weighted by these revolutions ([`crate::cam::hertz::equivalent_load`]),
//! and L₁₀ = (C/P_eq)^a million roller revolutions.

use std::f64::consts::TAU;

use crate::cam::hertz::{equivalent_load, l10, line_contact, point_contact};
use crate::cam::law::golden_max;
use crate::cam::{Cam, CamError, Follower};
use crate::cam_limits::{force, Extreme, Train, SAMPLES};
use crate::math::{dot, sub};

/// The contact's width and the materials' contact modulus.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactSpec {
    /// Contact length L along the cam's axis (m): the narrower of the cam
    /// and the roller or face.
    pub width: f64,
    /// Contact modulus E* (Pa), [`crate::cam::hertz::contact_modulus`].
    pub modulus: f64,
    /// A crowned roller's crown radius R_c (m): the contact is then the
    /// ellipse of [`crate::cam::hertz::point_contact`] with curvature sums
    /// ½(1/ρ + 1/R_r) along the profile and ½(1/R_c) across it, and
    /// `half_width` is the ellipse's semi-axis b, `pressure` its p₀.
    pub crown: Option<f64>,
}

/// A roller's bearing: its dynamic rating and life exponent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BearingSpec {
    /// Dynamic load rating C (N).
    pub rating: f64,
    /// Life exponent a: 3 for ball, 10/3 for roller bearings.
    pub exponent: f64,
}

/// The bearing's load and life.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BearingLife {
    /// Equivalent load P_eq (N).
    pub equivalent_load: f64,
    /// Roller revolutions per cam turn.
    pub roller_turns: f64,
    /// L₁₀ in roller revolutions.
    pub l10_revolutions: f64,
    /// L₁₀ in cam turns.
    pub l10_turns: f64,
}

/// Contact stress and torque over a turn.
#[derive(Clone, Debug, PartialEq)]
pub struct Stress {
    pub omega: f64,
    /// Cam angles θ (rad).
    pub theta: Vec<f64>,
    /// Normal contact force F (N).
    pub force: Vec<f64>,
    /// Cam's radius of curvature ρ at the contact (m).
    pub rho: Vec<f64>,
    /// Contact half-width b (m); NaN where there is no Hertz contact
    /// (F ≤ 0 or conforming surfaces).
    pub half_width: Vec<f64>,
    /// Peak contact pressure p_max (Pa); 0 where there is no contact.
    pub pressure: Vec<f64>,
    /// Largest p_max over the turn (Pa) and where.
    pub max_pressure: Extreme,
    /// The contact half-width there (m).
    pub half_width_at_max: f64,
    /// Camshaft torque T = Q s′ (N·m).
    pub torque: Vec<f64>,
    /// Largest |T| (signed, N·m) and where.
    pub peak_torque: Extreme,
    /// RMS of T over the turn (N·m).
    pub rms_torque: f64,
    /// With a bearing rating: its life.
    pub bearing: Option<BearingLife>,
}

/// Contact stress, torque and bearing life of `cam` at `omega` (rad/s).
pub fn stress(
    cam: &Cam,
    train: &Train,
    omega: f64,
    contact: &ContactSpec,
    bearing: Option<&BearingSpec>,
) -> Result<Stress, CamError> {
    for (what, v) in [
        ("contact width", contact.width),
        ("contact modulus", contact.modulus),
    ] {
        if !(v > 0.0 && v.is_finite()) {
            return Err(CamError(format!("the {what} must be positive, got {v}")));
        }
    }
    if let Some(rc) = contact.crown {
        if cam.follower.roller().is_none() {
            return Err(CamError(
                "a crown radius needs a roller follower".to_string(),
            ));
        }
        if !(rc > 0.0 && rc.is_finite()) {
            return Err(CamError(format!(
                "the crown radius must be positive, got {rc}"
            )));
        }
    }
    let f = force(cam, train, omega)?;
    let r2 = cam.follower.roller().unwrap_or(f64::INFINITY);
    let p_at = |rho: f64, fo: f64| match contact.crown {
        Some(rc) => point_contact(0.5 / rc, 0.5 * (1.0 / rho + 1.0 / r2), fo, contact.modulus)
            .map_or((f64::NAN, 0.0), |c| (c.semi_minor, c.max_pressure)),
        None => line_contact(rho, r2, fo, contact.width, contact.modulus)
            .map_or((f64::NAN, 0.0), |c| (c.half_width, c.max_pressure)),
    };
    let n = f.theta.len();
    let (mut rho, mut bw, mut pr, mut torque) = (
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    );
    for (k, &t) in f.theta.iter().enumerate() {
        let c = cam.contact(t);
        let (b, p) = p_at(c.rho, f.normal[k]);
        rho.push(c.rho);
        bw.push(b);
        pr.push(p);
        torque.push(f.generalised[k] * c.motion[1]);
    }
    // The normal force at any θ, as cam_limits computes it at its samples.
    let normal_at = |t: f64| {
        let g = force_at(cam, train, omega, t);
        g.0
    };
    let h = TAU / SAMPLES as f64;
    let argmax = |v: &[f64]| {
        (0..v.len())
            .max_by(|&a, &b| v[a].abs().total_cmp(&v[b].abs()))
            .unwrap_or(0)
    };
    let kp = argmax(&pr);
    let pressure_at = |t: f64| p_at(cam.contact(t).rho, normal_at(t)).1;
    let tp = golden_max(pressure_at, f.theta[kp] - h, f.theta[kp] + h);
    let (tp, pmax) = if pressure_at(tp) >= pr[kp] {
        (tp.rem_euclid(TAU), pressure_at(tp))
    } else {
        (f.theta[kp], pr[kp])
    };
    let b_at_max = p_at(cam.contact(tp).rho, normal_at(tp)).0;
    let kt = argmax(&torque);
    let torque_at = |t: f64| {
        let (_, q) = force_at(cam, train, omega, t);
        q * cam.program.eval(t)[1]
    };
    let sign = torque[kt].signum();
    let tt = golden_max(|t| sign * torque_at(t), f.theta[kt] - h, f.theta[kt] + h);
    let peak_torque = if (torque_at(tt)).abs() >= torque[kt].abs() {
        Extreme {
            value: torque_at(tt),
            theta: tt.rem_euclid(TAU),
        }
    } else {
        Extreme {
            value: torque[kt],
            theta: f.theta[kt],
        }
    };
    let rms_torque = (torque.iter().map(|t| t * t).sum::<f64>() / n as f64).sqrt();
    let bearing = match (bearing, cam.follower.roller()) {
        (Some(b), Some(rr)) => {
            if !(b.exponent > 0.0 && b.exponent.is_finite()) {
                return Err(CamError(format!(
                    "the life exponent must be positive, got {}",
                    b.exponent
                )));
            }
            // Roller revolutions per unit θ at each sample.
            let spin: Vec<f64> = f
                .theta
                .iter()
                .map(|&t| roller_spin(cam, t) / (TAU * rr))
                .collect();
            let p = equivalent_load(&f.normal, &spin, b.exponent);
            let turns = spin.iter().sum::<f64>() * h;
            let revs = l10(b.rating, p, b.exponent)?;
            Some(BearingLife {
                equivalent_load: p,
                roller_turns: turns,
                l10_revolutions: revs,
                l10_turns: revs / turns,
            })
        }
        (Some(_), None) => {
            return Err(CamError(
                "a bearing rating needs a roller follower".to_string(),
            ))
        }
        _ => None,
    };
    Ok(Stress {
        omega,
        theta: f.theta,
        force: f.normal,
        rho,
        half_width: bw,
        pressure: pr,
        max_pressure: Extreme {
            value: pmax,
            theta: tp,
        },
        half_width_at_max: b_at_max,
        torque,
        peak_torque,
        rms_torque,
        bearing,
    })
}

/// (normal force F, generalised force Q) at θ, as
/// [`crate::cam_limits::force`] computes them.
fn force_at(cam: &Cam, train: &Train, omega: f64, theta: f64) -> (f64, f64) {
    let c = cam.contact(theta);
    let [s, s1, s2, _] = c.motion;
    let q = train.mass * omega * omega * s2
        + train.damping * omega * s1
        + train.preload
        + train.spring_rate * s;
    let lever = match cam.follower {
        Follower::TranslatingRoller { .. } | Follower::TranslatingFlat => 1.0,
        Follower::OscillatingRoller { pivot, .. } => {
            let centre = cam.pitch(theta).expect("a roller has a pitch curve").p;
            let centre = crate::math::rot(cam.sigma * theta, centre);
            crate::math::norm(sub(centre, [pivot, 0.0]))
        }
        Follower::OscillatingFlat { pivot, .. } => crate::math::norm(sub(c.point, [pivot, 0.0])),
    };
    (q / (lever * c.pressure_angle.cos()), q)
}

/// |t · (v_cam − v_follower)| / ω at the contact (m/rad): the roller's
/// rolling speed per unit cam angle.
fn roller_spin(cam: &Cam, theta: f64) -> f64 {
    let c = cam.contact(theta);
    let p = c.point;
    let t = [-c.normal[1], c.normal[0]];
    let v_cam = [-cam.sigma * p[1], cam.sigma * p[0]];
    let s1 = c.motion[1];
    let v_fol = match cam.follower {
        Follower::OscillatingRoller { pivot, .. } | Follower::OscillatingFlat { pivot, .. } => {
            let r = sub(p, [pivot, 0.0]);
            [s1 * r[1], -s1 * r[0]]
        }
        _ => [0.0, s1],
    };
    dot(t, sub(v_cam, v_fol)).abs()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cam::hertz::{contact_modulus, material};
    use crate::cam::{LawKind, Program, SegmentSpec};

    /// A circular cam (eccentric, harmonic lift) under a centred roller at
    /// very low speed: F = F₀ + k s, ρ = the eccentric's radius, so
    /// p_max follows the two-cylinder closed form; on the base circle's
    /// dwell a centred roller spins at R_b/R_r per cam radian.
    #[test]
    fn issue32_stress_on_a_dwell_matches_two_cylinders() {
        let (rb, rr) = (0.03, 0.01);
        let p = Program::new(&[
            SegmentSpec::new(LawKind::Dwell, 2.0, 0.0),
            SegmentSpec::new(LawKind::Cycloidal, 1.5, 0.008),
            SegmentSpec::new(LawKind::Dwell, 1.0, 0.0),
            SegmentSpec::new(LawKind::Cycloidal, TAU - 4.5, -0.008),
        ])
        .unwrap();
        let f = Follower::TranslatingRoller {
            offset: 0.0,
            roller: rr,
        };
        let cam = Cam::new(p, f, rb, true).unwrap();
        let train = Train {
            mass: 0.1,
            spring_rate: 1e4,
            preload: 300.0,
            damping: 0.0,
        };
        let steel = material("steel").unwrap();
        let e = contact_modulus(&steel, &steel);
        let spec = ContactSpec {
            width: 0.012,
            modulus: e,
            crown: None,
        };
        let b = BearingSpec {
            rating: 5000.0,
            exponent: 3.0,
        };
        let s = stress(&cam, &train, 1.0, &spec, Some(&b)).unwrap();
        let k = 500; // θ = 0.87 rad, on the first dwell
        assert!((s.rho[k] - rb).abs() < 1e-12);
        let f = s.force[k];
        assert!((f - 300.0).abs() < 1e-9);
        let curv = 1.0 / rb + 1.0 / rr;
        let bw = (4.0 * f / (curv * std::f64::consts::PI * 0.012 * e)).sqrt();
        assert!((s.half_width[k] - bw).abs() < 1e-12 * bw);
        let pm = 2.0 * f / (std::f64::consts::PI * bw * 0.012);
        assert!((s.pressure[k] - pm).abs() < 1e-9 * pm);
        assert!(s.max_pressure.value >= s.pressure.iter().cloned().fold(0.0, f64::max));
        assert!((roller_spin(&cam, 0.87) - rb).abs() < 1e-12);
        // Torque: zero on the dwell, Q s′ on the rise.
        assert_eq!(s.torque[k], 0.0);
        let life = s.bearing.unwrap();
        assert!(life.equivalent_load > 300.0 && life.equivalent_load < 300.0 + 1e4 * 0.008);
        assert!((life.l10_revolutions - (5000.0 / life.equivalent_load).powi(3) * 1e6).abs() < 1.0);
    }

    /// A crowned roller on the dwell: the point contact of
    /// [`point_contact`] with sums ½(1/R_b + 1/R_r) and ½(1/R_c) under the
    /// spring's force, its p₀ above the line contact's.
    #[test]
    fn issue32_crowned_roller_on_a_dwell_is_the_point_contact() {
        let (rb, rr, rc) = (0.03, 0.01, 0.2);
        let p = Program::new(&[
            SegmentSpec::new(LawKind::Dwell, 2.0, 0.0),
            SegmentSpec::new(LawKind::Cycloidal, 1.5, 0.008),
            SegmentSpec::new(LawKind::Dwell, 1.0, 0.0),
            SegmentSpec::new(LawKind::Cycloidal, TAU - 4.5, -0.008),
        ])
        .unwrap();
        let f = Follower::TranslatingRoller {
            offset: 0.0,
            roller: rr,
        };
        let cam = Cam::new(p, f, rb, true).unwrap();
        let train = Train {
            mass: 0.1,
            spring_rate: 1e4,
            preload: 300.0,
            damping: 0.0,
        };
        let mut spec = ContactSpec {
            width: 0.012,
            modulus: 1.1e11,
            crown: Some(rc),
        };
        let s = stress(&cam, &train, 1.0, &spec, None).unwrap();
        let want = point_contact(0.5 / rc, 0.5 * (1.0 / rb + 1.0 / rr), 300.0, 1.1e11).unwrap();
        let k = 500;
        assert!((s.pressure[k] - want.max_pressure).abs() < 1e-9 * want.max_pressure);
        assert!((s.half_width[k] - want.semi_minor).abs() < 1e-12);
        spec.crown = None;
        let line = stress(&cam, &train, 1.0, &spec, None).unwrap();
        assert!(s.pressure[k] > line.pressure[k]);
        let flat = Cam::new(cam.program.clone(), Follower::TranslatingFlat, rb, true).unwrap();
        spec.crown = Some(rc);
        assert!(stress(&flat, &train, 1.0, &spec, None).is_err());
    }

    /// The torque is the rate of the follower's energy per cam radian:
    /// E(θ) = ½ m ω² s′² + ½ k s² + F₀ s, dE/dθ = s′ (m ω² s″ + k s + F₀)
    /// = T for an undamped train (checked against central differences of
    /// E), and its peak is at least every sample's.
    #[test]
    fn issue32_torque_is_the_rate_of_the_follower_energy() {
        let p = Program::new(&[
            SegmentSpec::new(LawKind::Poly345, 2.0, 0.01),
            SegmentSpec::new(LawKind::Dwell, 1.0, 0.0),
            SegmentSpec::new(LawKind::Poly345, 2.0, -0.01),
            SegmentSpec::new(LawKind::Dwell, TAU - 5.0, 0.0),
        ])
        .unwrap();
        let cam = Cam::new(p, Follower::TranslatingFlat, 0.03, true).unwrap();
        let (m, k, f0, w) = (0.3, 2e4, 100.0, 120.0);
        let train = Train {
            mass: m,
            spring_rate: k,
            preload: f0,
            damping: 0.0,
        };
        let spec = ContactSpec {
            width: 0.01,
            modulus: 1e11,
            crown: None,
        };
        let s = stress(&cam, &train, w, &spec, None).unwrap();
        let energy = |t: f64| {
            let d = cam.program.eval(t);
            0.5 * m * w * w * d[1] * d[1] + 0.5 * k * d[0] * d[0] + f0 * d[0]
        };
        let h = 1e-6;
        for i in (7..s.theta.len()).step_by(97) {
            let t = s.theta[i];
            let fd = (energy(t + h) - energy(t - h)) / (2.0 * h);
            assert!(
                (s.torque[i] - fd).abs() < 1e-6 * s.peak_torque.value.abs(),
                "{} vs {fd} at {t}",
                s.torque[i]
            );
        }
        let most = s.torque.iter().map(|t| t.abs()).fold(0.0, f64::max);
        assert!(s.peak_torque.value.abs() >= most);
    }
}
