//! The crate's integration tests, one module per file, in one test binary
//! (one link instead of one per file). camlink-core's `test_layout` checks
//! that every file in `tests/` is listed here or built on its own.

mod burmester;
mod closed_forms;
mod constructions;
mod marks;
mod path_generation;
mod problem_files;
mod published;
mod slider_crank;
mod two_positions;
mod verify;
