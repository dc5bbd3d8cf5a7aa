//! Mechanisms built in code for camlink's tests and benchmarks: four-bars,
//! slider-cranks, pendulums, chains and the IFToMM A02 benchmark, with
//! their closed-form references (SI units: m, kg, kg·m², s, rad); and the
//! mutations of valid files that the loaders' fuzz tests read.
//!
//! A dev-dependency of the workspace's crates and the benchmarks; not
//! published.

pub mod common;
pub mod mechanisms;
pub mod mutate;
