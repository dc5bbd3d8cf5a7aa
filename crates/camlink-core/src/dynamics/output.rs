//! Output channels of the dynamic analyses.
//!
//! After the kinematic channels of every body, point and own coordinate
//! ([`crate::run::channels`]):
//! - per joint (not driver), the reaction on body i:
//!   `<joint>.fx .fy .torque .fx_local .fy_local`, and on body j:
//!   `<joint>.fx_j .fy_j .torque_j .fx_local_j .fy_local_j`
//!   (see [`super::reaction`] for the conventions), then, for a curve
//!   contact, `<joint>.normal_force .tangential_force` (see
//!   [`super::contact_force`]), then, for a joint with friction,
//!   `<joint>.friction_torque` (N·m) or `<joint>.friction_force` (N), and
//!   `<joint>.friction_power` (W) (see [`super::friction`]);
//! - per driver: `<driver>.effort .power`;
//! - the shaking force and moment ([`SHAKING`]): `shaking.fx`,
//!   `shaking.fy` (N), the sum of the forces the mechanism exerts on the
//!   ground through its joints and drivers and their friction, and through
//!   the forces with a reaction on the ground (springs, dampers and
//!   contacts joining a body to the ground, forces of state without another
//!   reaction body; see [`Applied::frame_load`]), in the global frame, and
//!   `shaking.moment` (N·m, counter-clockwise positive), their moment about
//!   the global origin O plus the torques on the ground (a motor's reaction
//!   torque among them);
//! - `energy.kinetic`, `energy.potential` (gravity and springs) and
//!   `energy.total` (J);
//! - `constraint.residual`, max |Φ| (m or rad), and
//!   `constraint.velocity`, max |Φ_q q̇ − ν| (m/s or rad/s): the drift.

use super::contact_force::ContactForces;
use super::friction::JointFrictions;
use super::reaction::{effort, reactions, Reaction};
use super::system::System;
use crate::constraint::Equations;
use crate::force::Applied;
use crate::math::cross;
use crate::model::Model;
use crate::quantity::{Channel, Quantity};

/// The shaking channels, after the joints' and drivers' channels.
pub use crate::model::SHAKING;

/// The shaking force F_s = Σ F_k (N) and moment M_O = Σ (T_k + r_k × F_k)
/// (N·m, about the global origin) of the loads `(body, reaction)` that
/// joints exert on their bodies, summed over those on the ground (body 0):
/// the loads the mechanism puts on its frame.
pub fn shaking<'a>(loads: impl IntoIterator<Item = (usize, &'a Reaction)>) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (_, r) in loads.into_iter().filter(|(b, _)| *b == 0) {
        out[0] += r.force[0];
        out[1] += r.force[1];
        out[2] += r.torque + cross(r.point, r.force);
    }
    out
}

/// The dynamic channels (after the kinematic ones). A driver's effort is
/// the generalized force conjugate to the coordinate it drives
/// ([`effort_quantity`]).
pub fn channels(model: &Model) -> Vec<Channel> {
    use Quantity::*;
    let contacts = ContactForces::new(model);
    let mut out = Vec::new();
    for (k, j) in model.joints.iter().enumerate() {
        if j.driver {
            let effort = effort_quantity(j.constraint.driven_quantity());
            out.push(Channel::new(format!("{}.effort", j.name), effort));
            out.push(Channel::new(format!("{}.power", j.name), Power));
        } else {
            for side in ["", "_j"] {
                for (c, q) in [
                    ("fx", Force),
                    ("fy", Force),
                    ("torque", Torque),
                    ("fx_local", Force),
                    ("fy_local", Force),
                ] {
                    out.push(Channel::new(format!("{}.{c}{side}", j.name), q));
                }
            }
            out.extend(contacts.channels(model, k));
            out.extend(JointFrictions::channels_of(model, k));
        }
    }
    for (name, q) in SHAKING.iter().zip([Force, Force, Torque]) {
        out.push(Channel::new(*name, q));
    }
    for (name, q) in ENERGY_AND_DRIFT {
        out.push(Channel::new(name, q));
    }
    out
}

/// The last dynamic channels, in the order [`energy_and_drift`] writes
/// them.
pub const ENERGY_AND_DRIFT: [(&str, Quantity); 5] = [
    ("energy.kinetic", Quantity::Energy),
    ("energy.potential", Quantity::Energy),
    ("energy.total", Quantity::Energy),
    ("constraint.residual", Quantity::Residual),
    ("constraint.velocity", Quantity::ResidualRate),
];

/// The quantity of the generalized force conjugate to a coordinate that
/// measures `driven`: N for a length, N·m for an angle, J (N·m per unit)
/// for a pure number (the parameter of a curve written as expressions).
pub fn effort_quantity(driven: Quantity) -> Quantity {
    match driven {
        Quantity::Angle => Quantity::Torque,
        Quantity::Length => Quantity::Force,
        _ => Quantity::Energy,
    }
}

/// Scratch for [`fill`], allocated once. [`fill_forces`] leaves ν at
/// (q, t) in `drift.nu`, where [`fill`] turns it into the drift.
pub struct Scratch {
    drift: DriftScratch,
    contacts: ContactForces,
}

impl Scratch {
    pub fn new(s: &System) -> Self {
        Scratch {
            drift: DriftScratch::new(s.m()),
            contacts: ContactForces::new(s.model),
        }
    }
}

/// Scratch for [`energy_and_drift`]: Φ and Φ_q q̇ − ν, resized to the
/// system's m (no allocation for systems of at most the m it was made for).
pub struct DriftScratch {
    phi: Vec<f64>,
    nu: Vec<f64>,
}

impl DriftScratch {
    /// Scratch for systems of up to `m` equations.
    pub fn new(m: usize) -> Self {
        DriftScratch {
            phi: Vec::with_capacity(m),
            nu: Vec::with_capacity(m),
        }
    }
}

/// Fills the dynamic channels at (q, q̇, λ, t).
pub fn fill(
    s: &System,
    w: &mut Scratch,
    q: &[f64],
    qd: &[f64],
    lambda: &[f64],
    t: f64,
    out: &mut [f64],
) {
    // fill_forces leaves ν of the same (q, t) in w.drift.nu.
    let k = fill_forces(s, w, q, qd, lambda, t, out);
    out[k..k + ENERGY_AND_DRIFT.len()].copy_from_slice(&energy_and_drift_from_nu(
        s,
        &mut w.drift,
        q,
        qd,
        t,
    ));
}

/// Fills the channels of [`fill`] before the energy and drift: the
/// reactions, contact forces, joint friction, driver efforts and powers,
/// and the shaking force and moment. Returns how many
/// it wrote, and leaves ν at (q, t) in the scratch.
pub fn fill_forces(
    s: &System,
    w: &mut Scratch,
    q: &[f64],
    qd: &[f64],
    lambda: &[f64],
    t: f64,
    out: &mut [f64],
) -> usize {
    let (model, asm) = (s.model, &s.asm);
    let nu = &mut w.drift.nu;
    nu.resize(s.m(), 0.0);
    asm.nu(model, q, t, nu);
    let mut k = 0;
    let mut shake = [0.0; 3];
    let (sys, mut friction) = (s, 0);
    for (j, joint) in model.joints.iter().enumerate() {
        // The loads of every joint and driver on the ground.
        let rs = reactions(model, asm, j, q, lambda, t);
        let bodies = joint.constraint.bodies().map(|b| b.0);
        let s = shaking(bodies.into_iter().zip(&rs));
        for (a, b) in shake.iter_mut().zip(s) {
            *a += b;
        }
        if joint.driver {
            let r = asm.rows_of(j).start;
            let (e, p) = effort(model, j, lambda[r], w.drift.nu[r], t);
            out[k] = e;
            out[k + 1] = p;
            k += 2;
        } else {
            for r in rs {
                out[k..k + 5].copy_from_slice(&[
                    r.force[0],
                    r.force[1],
                    r.torque,
                    r.force_local[0],
                    r.force_local[1],
                ]);
                k += 5;
            }
            if w.contacts.has(j) {
                let nt = w.contacts.resolve(model, asm, j, q, &rs);
                out[k..k + 2].copy_from_slice(&nt);
                k += 2;
            }
            if joint.friction.is_some() {
                let (fp, ground) = sys
                    .friction
                    .channels(model, asm, friction, q, qd, lambda, t);
                out[k..k + 2].copy_from_slice(&fp);
                for (a, b) in shake.iter_mut().zip(ground) {
                    *a += b;
                }
                k += 2;
                friction += 1;
            }
        }
    }
    // The loads of the forces with a reaction on the ground; a force that
    // fails here failed the analysis first, so NaN only marks the row.
    for f in 0..model.forces.len() {
        let x = s.force_local(f, q, qd, t);
        match model.forces[f].kind.frame_load(&x) {
            Ok(Some(l)) => {
                for (a, b) in shake.iter_mut().zip(l) {
                    *a += b;
                }
            }
            Ok(None) => {}
            Err(_) => shake = [f64::NAN; 3],
        }
    }
    out[k..k + 3].copy_from_slice(&shake);
    k + 3
}

/// The channels `energy.kinetic` T, `energy.potential` V, `energy.total`
/// T + V (J), `constraint.residual` max |Φ| and `constraint.velocity`
/// max |Φ_q q̇ − ν| (m or rad, m/s or rad/s) of system `s` at (q, q̇, t).
pub fn energy_and_drift(
    s: &System,
    w: &mut DriftScratch,
    q: &[f64],
    qd: &[f64],
    t: f64,
) -> [f64; ENERGY_AND_DRIFT.len()] {
    w.nu.resize(s.m(), 0.0);
    s.asm.nu(s.model, q, t, &mut w.nu);
    energy_and_drift_from_nu(s, w, q, qd, t)
}

/// [`energy_and_drift`] with `w.nu` already holding ν at (q, t).
fn energy_and_drift_from_nu(
    s: &System,
    w: &mut DriftScratch,
    q: &[f64],
    qd: &[f64],
    t: f64,
) -> [f64; ENERGY_AND_DRIFT.len()] {
    let (model, asm, m) = (s.model, &s.asm, s.m());
    debug_assert_eq!(w.nu.len(), m, "ν of every equation");
    let kin = s.kinetic(q, qd);
    let pot = s.potential(q, t);
    w.phi.resize(m, 0.0);
    asm.phi(model, q, t, &mut w.phi);
    // Φ_q q̇ − ν, from −ν.
    for v in w.nu.iter_mut() {
        *v = -*v;
    }
    let nu = &mut w.nu;
    asm.jacobian(model, q, t, |r, c, v| nu[r] += v * qd[c]);
    let max = |v: &[f64]| v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    [kin, pot, kin + pot, max(&w.phi), max(&w.nu)]
}
