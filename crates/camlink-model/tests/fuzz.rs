//! Mutated valid model files never panic the loader: every input either
//! loads or gives a `LoadError`. The generator is a fixed-seed xorshift, so
//! a failure reproduces.

use std::path::Path;

use camlink_model::{load_str, Format};
use camlink_testkit::mutate::{mutate, Rng};

fn fuzz(file: &str, format: Format, seed: u64) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/models")
        .join(file);
    let base = std::fs::read_to_string(path).unwrap();
    let mut rng = Rng(seed);
    let mut loaded = 0;
    for _ in 0..1500 {
        let text = mutate(&mut rng, &base);
        match load_str(&text, format, file) {
            Ok(_) => loaded += 1,
            Err(e) => assert!(!e.to_string().is_empty()),
        }
    }
    // Some mutations (inside comments, whitespace) leave the file valid.
    assert!(loaded > 0);
}

#[test]
fn mutated_toml_never_panics() {
    fuzz("four_bar.toml", Format::Toml, 0x9E37_79B9_7F4A_7C15);
}

#[test]
fn mutated_json_never_panics() {
    fuzz("four_bar.json", Format::Json, 0xD1B5_4A32_D192_ED03);
}

#[test]
fn mutated_every_bad_file_never_panics() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/models/bad");
    let mut rng = Rng(42);
    let mut mutated = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        // Files that are not UTF-8 on purpose are fuzzed as bytes elsewhere.
        let Ok(base) = std::fs::read_to_string(&path) else {
            continue;
        };
        mutated += 1;
        let format = if path.extension().is_some_and(|e| e == "json") {
            Format::Json
        } else {
            Format::Toml
        };
        for _ in 0..100 {
            let _ = load_str(&mutate(&mut rng, &base), format, "bad");
        }
    }
    assert!(mutated >= 15, "only {mutated} bad files found to mutate");
}

#[test]
fn deep_nesting_is_an_error_not_a_crash() {
    let depth = 100_000;
    let toml = format!("x = {}{}", "[".repeat(depth), "]".repeat(depth));
    assert!(load_str(&toml, Format::Toml, "deep.toml").is_err());
    let json = format!("{{\"x\": {}{}}}", "[".repeat(depth), "]".repeat(depth));
    assert!(load_str(&json, Format::Json, "deep.json").is_err());
}
