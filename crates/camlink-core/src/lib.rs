//! camlink core: planar multibody kinematics and dynamics in Haug's
//! Cartesian formulation.
//!
//! Body i has coordinates q_i = (x_i, y_i, φ_i); joints that run along curves
//! own extra coordinates. The global vector is
//! q = [moving bodies' (x, y, φ)…, joints' own coordinates…].
//! Data flows down: [`model`] (immutable) → [`assembly`] (layout and
//! buffers) → analyses such as [`kinematics`].
//!
//! The modules are layered; each imports only modules of its own or an
//! earlier line, with no cycle (`tests/layers.rs` checks it):
//!
//! 1. [`math`], [`quantity`], [`names`], [`cam`], [`curve`], [`function`],
//!    [`motion`], [`newton`]: geometry (a synthesised cam's profile too),
//!    known names nearest a mistyped one, units of
//!    channels, functions of time, time derivatives of points along a
//!    motion, and Newton's stopping test;
//! 2. [`constraint`], [`force`]: Φ, Φ_q, ν, γ and applied forces Q;
//! 3. [`model`]: the validated, immutable description;
//! 4. [`assembly`], [`linsolve`]: layout, sparsity and factorisations;
//! 5. [`contact`]: the curve contacts;
//! 6. [`run`]: settings, sinks, tables, summaries, errors and warnings;
//!    [`limits`]: joint limits, their coordinates and stops;
//! 7. [`design`], [`diagnose`], [`cam_limits`], [`cam_contact`]: checks and reports;
//! 8. [`kinematics`], [`cam_mechanism`] (a synthesised cam run through it);
//! 9. [`dynamics`];
//! 10. [`machine`]: shaking, balancing, flywheel and motor sizing.

#![warn(unreachable_pub)]

pub mod cam;
pub mod curve;
pub mod fmt_num;
pub(crate) mod function;
pub mod math;
pub(crate) mod motion;
pub mod names;
pub(crate) mod newton;
pub mod quantity;

pub mod constraint;
pub mod force;

pub mod model;
pub mod setting;

pub mod assembly;
pub mod linsolve;
pub(crate) mod lu_program;

pub(crate) mod contact;

pub mod run;

pub mod limits;

pub mod cam_contact;
pub mod cam_limits;
pub mod design;
pub mod diagnose;

pub mod cam_mechanism;
pub mod kinematics;

pub mod dynamics;

pub mod machine;

pub use constraint::{Constraint, Equations};
pub use force::{Applied, Force, ForceKind};
pub use function::TimeFn;
pub use model::{Body, BodyId, Joint, Model, ModelError, ModelWarning, Point};
