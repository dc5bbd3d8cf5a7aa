//! Gear pair and rack-and-pinion: rolling of pitch circles without slip.
//!
//! Gear pair (own coordinate θ, the angle of the centre line from P_i to P_j
//! in the global frame, so that it stays continuous when a carrier turns):
//! Φ₁ = u(θ)⊥ᵀ (r_j^P − r_i^P)                         (centre line along u(θ))
//! Φ₂ = R_i(φ_i − θ) + R_j(φ_j − θ) − c                 (external)
//! Φ₂ = R_i(φ_i − θ) − R_j(φ_j − θ) − c                 (internal; j is the ring)
//! The centre distance itself is held by other joints (pivots, a carrier).
//!
//! Rack and pinion (pinion centre P_i, radius R; rack pitch line through Q_j
//! along u'_j; the pinion lies to the left of u_j):
//! Φ = (A_j u'_j)ᵀ (r_i^P − r_j^Q) + R(φ_i − φ_j) − c.

use crate::math::V2;
use crate::model::BodyId;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GearKind {
    External,
    Internal,
}

#[derive(Clone, Debug)]
pub struct Gear {
    pub body_i: BodyId,
    /// Centre P_i of gear i in body i (m).
    pub s_i: V2,
    /// Pitch radius R_i (m).
    pub radius_i: f64,
    pub body_j: BodyId,
    pub s_j: V2,
    pub radius_j: f64,
    pub kind: GearKind,
    /// Phase constant c (m), so the initial placement satisfies Φ₂.
    pub phase: f64,
}

#[derive(Clone, Debug)]
pub struct RackPinion {
    /// The pinion.
    pub body_i: BodyId,
    pub s_i: V2,
    /// Pitch radius R (m).
    pub radius: f64,
    /// The rack.
    pub body_j: BodyId,
    /// Q_j on the pitch line (m).
    pub s_j: V2,
    /// u'_j along the rack (unit vector).
    pub u_j: V2,
    /// Phase constant c (m).
    pub phase: f64,
}
