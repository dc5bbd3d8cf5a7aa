//! Composite joints that replace a massless link.
//!
//! Revolute–revolute (coupler of length L between P_i and P_j):
//! Φ = dᵀd − L², d = r_j^P − r_i^P.
//!
//! Revolute–translational (pin P_i of body i runs on the line through Q_j
//! along v'_j of body j, at a signed offset c to the left of v_j):
//! Φ = (A_j v'_j)⊥ᵀ (r_i^P − r_j^Q) − c.

use crate::math::V2;
use crate::model::BodyId;

#[derive(Clone, Debug)]
pub struct RevoluteRevolute {
    pub body_i: BodyId,
    pub s_i: V2,
    pub body_j: BodyId,
    pub s_j: V2,
    /// L (m).
    pub length: f64,
}

#[derive(Clone, Debug)]
pub struct RevoluteTranslational {
    /// Body carrying the pin P_i.
    pub body_i: BodyId,
    pub s_i: V2,
    /// Body carrying the line.
    pub body_j: BodyId,
    /// Q_j, a point of the line (m).
    pub s_j: V2,
    /// v'_j, the line direction (unit vector).
    pub v_j: V2,
    /// c, the signed offset of the pin from the line (m).
    pub offset: f64,
}
