//! Dynamics: inverse dynamics and reactions, equilibrium and forward
//! dynamics of the constrained equations of motion
//!
//! M(q) q̈ + Φ_qᵀ λ = Q(q, q̇, t),  Φ(q, t) = 0
//!
//! (Haug ch. 6; the theory and the sign conventions are in `docs/dynamics.md`).
//!
//! - the mass matrix of a body whose centroid is anywhere in its frame,
//!   gravity and the velocity-quadratic force, in [`mass`];
//! - applied forces (point forces and torques, TSDA, RSDA, user callbacks)
//!   are defined in [`crate::force`];
//! - assembly of M, Q and the augmented matrices, in [`system`];
//! - consistent initial conditions, in [`project`];
//! - redundant equations (detection, warning), in [`redundant`];
//! - joint reactions and driver efforts from λ, in [`reaction`], the
//!   normal force of curve contacts and follower lift-off, in
//!   [`contact_force`], the output channels, in [`output`], and the run's
//!   drift, in [`drift`];
//! - inverse dynamics of a driven (zero-DOF) model, in [`inverse`];
//! - equilibrium, in [`statics`];
//! - forward dynamics: the run with output, in [`integrator`]; the
//!   implicit index-3 generalized-α integrator, in [`generalized_alpha`],
//!   through bifurcation points with the branch rows of [`branch`], its
//!   retry policy in [`retry`]; the
//!   layer of unilateral cam contacts (lift-off, flight, impact) over it
//!   in [`unilateral`], joint limits as end stops in [`stops`] and the
//!   impact law in [`impact`].

pub(crate) mod branch;
pub mod contact_force;
pub mod drift;
pub mod friction;
pub mod generalized_alpha;
pub mod impact;
pub mod integrator;
pub mod inverse;
pub mod mass;
pub mod output;
pub mod project;
pub mod reaction;
pub mod redundant;
pub mod retry;
pub mod statics;
pub mod stops;
pub mod system;
pub mod unilateral;
