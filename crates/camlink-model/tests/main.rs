//! The crate's integration tests, one module per file, in one test binary
//! (one link instead of one per file). camlink-core's `test_layout` checks
//! that every file in `tests/` is listed here or built on its own.

use camlink_fuzz_targets as targets;
use camlink_testkit::mechanisms;

mod analysis;
mod bad_models;
mod cam_dynamics;
mod cam_examples;
mod check_contacts;
mod convert;
mod examples;
mod fast_path;
mod forces;
mod friction;
mod fuzz;
mod fuzz_corpus;
mod global_points;
mod hostile;
mod initial_defaults;
mod issue27_output_time;
mod issue27_unilateral;
mod issue32_machine;
mod issue_newton_rounding_level;
mod jerk;
mod joint_friction;
mod joint_kinds;
mod joint_limits;
mod load;
mod load_scale;
mod outline;
mod predictor;
mod schema;
mod state_forces;
mod time_messages;
mod unilateral;
mod units;
