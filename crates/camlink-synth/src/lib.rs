//! camlink linkage synthesis: from the motion a mechanism must make to a
//! four-bar that makes it, written as a camlink model file.
//!
//! Methods, one module each:
//! - [`motion`]: three-position motion generation (rigid-body guidance),
//!   closed form, the moving or the ground pivots chosen by the user;
//! - [`function`]: function generation with Freudenstein's equation,
//!   through three precision points or in the least-squares sense;
//! - [`two_positions`]: two-position motion generation, closed form, the
//!   pivots on the perpendicular bisectors at the user's distances;
//! - [`burmester`]: four- and five-pose motion generation (centre-point
//!   and circle-point curves, Burmester points), dyads paired into
//!   four-bars, checked and ranked;
//! - [`slider_crank`]: slider-cranks, motion generation through two or
//!   three poses and function generation (crank angle to slider position);
//! - [`path`]: path generation, a fit of a target curve or precision
//!   points by a global search, and [`precision`]: three precision points
//!   at prescribed crank rotations in closed form;
//! - [`ball`]: a four-bar coupler's velocity pole, inflection circle and
//!   Ball's point at a crank angle;
//!
//! and what they share: [`fourbar`] (the linkage, its closed-form position
//! analysis and the checks of every candidate: Grashof class, transmission
//! angle, branch, order, dead positions), [`model_file`] (the model file a
//! solution is written as) and [`problem`] (problem files and reports).
//! Lengths in m, angles in rad, counter-clockwise from +x.

pub mod burmester;
mod complex;
pub mod error;
pub mod fourbar;
pub mod function;
pub mod model_file;
pub mod motion;
pub mod problem;
pub mod slider_crank;
pub mod two_positions;

// Path generation and the classical constructions.
pub mod ball;
pub mod cognates;
pub mod dead_centre;
pub mod lm;
pub mod marks;
pub mod path;
pub mod precision;
pub mod properties;

pub use error::{ErrorKind, SynthError};
pub use problem::{path_starts, solve_path, solve_str, solve_str_from_starts, Outcome, Solution};
