//! The crate's integration tests, one module per file, in one test binary
//! (one link instead of one per file). A test of this file checks that
//! every file in `tests/` is listed here or built on its own.

#[path = "../../camlink-core/tests/mechanisms/mod.rs"]
mod mechanisms;
#[path = "../../../fuzz/src/lib.rs"]
mod targets;

mod adm;
mod adm_course;
mod analysis;
mod bad_models;
mod cam_dynamics;
mod cam_examples;
mod check_contacts;
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
mod issue_newton_rounding_level;
mod jerk;
mod load;
mod load_scale;
mod outline;
mod predictor;
mod schema;
mod time_messages;
mod unilateral;

/// Test files built as binaries of their own (see Cargo.toml).
const APART: &[&str] = &["no_alloc"];

#[test]
fn every_test_file_is_a_module() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let this = std::fs::read_to_string(dir.join("main.rs")).unwrap();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "rs") {
            let stem = path.file_stem().unwrap().to_str().unwrap();
            if stem == "main" || APART.contains(&stem) {
                continue;
            }
            assert!(
                this.contains(&format!("\nmod {stem};\n")),
                "tests/{stem}.rs is not a module of tests/main.rs, so it never runs"
            );
        }
    }
}
