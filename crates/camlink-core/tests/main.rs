//! The crate's integration tests, one module per file, in one test binary
//! (one link instead of one per file). camlink-core's `test_layout` checks
//! that every file in `tests/` is listed here or built on its own.

use camlink_testkit::{common, mechanisms};

mod andrews;
mod assembly;
mod cam_contact_force;
mod cam_round_trip;
mod dynamics_forward;
mod dynamics_inverse;
mod dynamics_mass_check;
mod dynamics_statics;
mod dynamics_stiff_spring;
mod force_failed_and_interrupt;
mod four_bar;
mod issue27_a02;
mod issue27_global_error;
mod issue29_start_branch;
mod issue32_machine;
mod issue32_shaking;
mod issue_dynamics_contact_channels;
mod issue_near_singular_joints;
mod issue_neutral_equilibrium;
mod issue_projection_own_rates;
mod issue_redundant_kinematics;
mod issue_redundant_parallelogram_chain;
mod issue_singular_benchmark_a02;
mod issue_singular_parallelogram_chain;
mod issue_singular_uniform_crank_chain;
mod layers;
mod misbehave;
mod sink_stop;
mod sparse_singular;
mod test_layout;
