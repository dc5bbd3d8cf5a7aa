//! The crate's integration tests, one module per file, in one test binary
//! (one link instead of one per file). camlink-core's `test_layout` checks
//! that every file in `tests/` is listed here or built on its own.

mod adm;
mod adm_course;
mod adm_mfile;
mod fuzz;
mod joint_kinds;
