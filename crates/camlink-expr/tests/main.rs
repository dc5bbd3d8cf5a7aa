//! The crate's integration tests, one module per file, in one test binary
//! (one link instead of one per file). camlink-core's `test_layout` checks
//! that every file in `tests/` is listed here or built on its own.

mod common;

mod docs_expressions;
mod eval_errors;
mod jets;
mod jets4;
mod language;
mod motion_laws;
mod no_panic;
mod parse_errors;
mod state_inputs;
