//! camlink core: planar multibody kinematics and dynamics in Haug's
//! Cartesian formulation.
//!
//! Body i has coordinates q_i = (x_i, y_i, φ_i); joints that run along curves
//! own extra coordinates. The global vector is
//! q = [moving bodies' (x, y, φ)…, joints' own coordinates…].
//! Data flows down: [`model`] (immutable) → [`assembly`] (layout and
//! buffers) → analyses such as [`kinematics`].

pub mod constraint;
pub mod curve;
pub mod function;
pub mod math;
pub mod model;

pub use constraint::{Constraint, Equations};
pub use function::TimeFn;
pub use model::{Body, BodyId, Joint, Model, ModelError, Point};
pub mod assembly;
pub mod contact;
pub mod design;
pub mod diagnose;
pub mod dynamics;
pub mod kinematics;
pub mod linsolve;
pub mod newton;
