//! Translational (prismatic) joint: P_j slides on the line through P_i along
//! v'_i (body i), and the bodies do not rotate relative to each other.
//!
//! Φ₁ = (A_i v'_i)⊥ᵀ (r_j^P − r_i^P)
//! Φ₂ = φ_j − φ_i − θ₀

use crate::math::V2;
use crate::model::BodyId;

#[derive(Clone, Debug)]
pub struct Translational {
    pub body_i: BodyId,
    /// P_i in body i (m).
    pub s_i: V2,
    /// v'_i: the sliding axis in body i (unit vector).
    pub v_i: V2,
    pub body_j: BodyId,
    /// P_j in body j (m).
    pub s_j: V2,
    /// θ₀: the fixed relative angle φ_j − φ_i (rad).
    pub angle: f64,
}
