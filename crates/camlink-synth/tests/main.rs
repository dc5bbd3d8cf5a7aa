//! The crate's integration tests, one module per file, in one test binary
//! (one link instead of one per file). A test of this file checks that
//! every file in `tests/` is listed here or built on its own.

mod problem_files;
mod verify;

/// Test files built as binaries of their own (see Cargo.toml).
const APART: &[&str] = &[];

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
