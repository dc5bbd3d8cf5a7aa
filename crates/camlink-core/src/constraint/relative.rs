//! Relative constraints between two bodies, and their drivers.
//!
//! With d = r_j^P − r_i^P (global frame):
//! - x: Φ = d_x − f(t); y: Φ = d_y − f(t); φ: Φ = φ_j − φ_i − f(t)
//!   (a revolute joint's relative angle);
//! - along: Φ = (A_i v'_i)ᵀ d − f(t), travel of P_j relative to P_i along the
//!   unit vector v'_i fixed in body i (a translational joint's travel);
//! - distance: Φ = dᵀd − f(t)².

use crate::function::TimeFn;
use crate::math::V2;
use crate::model::BodyId;

/// Which relative coordinate a [`RelativeCoord`] holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RelCoord {
    X,
    Y,
    Phi,
    /// Travel along the unit vector v'_i (body i frame).
    Along(V2),
}

#[derive(Clone, Debug)]
pub struct RelativeCoord {
    pub body_i: BodyId,
    pub s_i: V2,
    pub body_j: BodyId,
    pub s_j: V2,
    pub coord: RelCoord,
    /// f(t) in m or rad.
    pub f: TimeFn,
}

#[derive(Clone, Debug)]
pub struct RelativeDistance {
    pub body_i: BodyId,
    pub s_i: V2,
    pub body_j: BodyId,
    pub s_j: V2,
    /// f(t) in m.
    pub f: TimeFn,
}
