//! Every crate of the workspace builds its integration tests as one binary,
//! `tests/main.rs`, with a module per file (Cargo's `autotests = false`), so
//! a file in `tests/` that is neither a module of `main.rs` nor a `[[test]]`
//! of its own in the crate's `Cargo.toml` would never run. This checks that
//! none is.

use std::fs;
use std::path::Path;

#[test]
fn every_test_file_of_every_crate_runs() {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut checked = 0;
    for entry in fs::read_dir(&crates).unwrap() {
        let dir = entry.unwrap().path();
        let main = dir.join("tests").join("main.rs");
        let Ok(modules) = fs::read_to_string(&main) else {
            continue;
        };
        let manifest = fs::read_to_string(dir.join("Cargo.toml")).unwrap();
        let krate = dir.file_name().unwrap().to_string_lossy().into_owned();
        assert!(
            manifest.contains("autotests = false"),
            "{krate}: tests/main.rs without `autotests = false` builds every file twice"
        );
        for file in fs::read_dir(dir.join("tests")).unwrap() {
            let path = file.unwrap().path();
            if path.extension().and_then(|e| e.to_str()) != Some("rs") {
                continue;
            }
            let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
            let listed = stem == "main"
                || modules.contains(&format!("\nmod {stem};\n"))
                || manifest.contains(&format!("path = \"tests/{stem}.rs\""));
            assert!(
                listed,
                "{krate}/tests/{stem}.rs is neither a module of tests/main.rs nor a [[test]] \
                 of Cargo.toml, so it never runs"
            );
            checked += 1;
        }
    }
    // camlink-core, -expr, -model and -synth hold their tests this way.
    assert!(checked >= 60, "only {checked} test files found");
}
