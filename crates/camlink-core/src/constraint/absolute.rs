//! Absolute constraints of one body against the ground, and their drivers.
//!
//! With r_i^P = r_i + A_i s'_i:
//! - coordinate x: Φ = x_i^P − f(t); y: Φ = y_i^P − f(t); φ: Φ = φ_i − f(t);
//! - distance: Φ = (r_i^P − C)ᵀ(r_i^P − C) − f(t)², C a ground point.
//!
//! A constant f makes a joint; an expression of t makes a driver.

use crate::function::TimeFn;
use crate::math::V2;
use crate::model::BodyId;

/// Which coordinate a coordinate constraint holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coord {
    X,
    Y,
    Phi,
}

/// x, y (of point P) or φ of one body equals f(t).
#[derive(Clone, Debug)]
pub struct AbsoluteCoord {
    pub body: BodyId,
    /// s'_P: the point in the body frame (m); unused for φ.
    pub s: V2,
    pub coord: Coord,
    /// f(t) in m or rad.
    pub f: TimeFn,
}

/// Distance from body point P to ground point C equals f(t) (m).
#[derive(Clone, Debug)]
pub struct AbsoluteDistance {
    pub body: BodyId,
    /// s'_P (m).
    pub s: V2,
    /// C in the global frame (m).
    pub ground_point: V2,
    pub f: TimeFn,
}
