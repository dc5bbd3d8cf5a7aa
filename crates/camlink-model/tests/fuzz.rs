//! Mutated valid model files never panic the loader: every input either
//! loads or gives a `LoadError`. The generator is a fixed-seed xorshift, so
//! a failure reproduces.

use std::path::Path;

use camlink_model::{load_str, Format};

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Fragments that tend to reach deep code paths when spliced in.
const PIECES: &[&str] = &[
    "\"",
    "[",
    "]",
    "{",
    "}",
    ",",
    "=",
    ":",
    "\n",
    "-",
    "0",
    "1e308",
    "-1e400",
    "nan",
    "inf",
    "\"1/0\"",
    "\"deg(\"",
    "\"x\"",
    "\"ground\"",
    "[[joints]]\ntype = \"gear\"\n",
    "[[bodies]]\nname = \"k\"\n",
    "\u{e9}",
    "\"t*t\"",
    "\"\"",
    "null",
    "true",
    "[0, 0]",
    "\"a.b\"",
    "\"crank.A\"",
];

fn mutate(rng: &mut Rng, text: &str) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for _ in 0..1 + rng.below(3) {
        let k = rng.below(chars.len() + 1);
        match rng.below(5) {
            0 if k < chars.len() => {
                chars.remove(k);
            }
            1 => {
                let piece = PIECES[rng.below(PIECES.len())];
                for (n, c) in piece.chars().enumerate() {
                    chars.insert(k + n, c);
                }
            }
            2 if k < chars.len() => {
                let end = (k + 1 + rng.below(40)).min(chars.len());
                chars.drain(k..end);
            }
            3 if k < chars.len() => {
                chars[k] = (b' ' + rng.below(95) as u8) as char;
            }
            _ => chars.truncate(k),
        }
    }
    chars.into_iter().collect()
}

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

/// Mutated simEngine2D models never panic the `.adm` reader, and every one
/// that loads converts to a TOML file that loads too.
#[test]
fn mutated_adm_never_panics_and_converts_when_it_loads() {
    use camlink_model::adm::describe_str;
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files = [
        dir.join("../../examples/simengine2d/slider_crank.adm"),
        dir.join("tests/adm/rack_pinion.adm"),
        dir.join("tests/adm/forces.adm"),
    ];
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    let mut loaded = 0;
    for path in files {
        let base = std::fs::read_to_string(path).unwrap();
        for _ in 0..500 {
            let text = mutate(&mut rng, &base);
            let Ok(described) = describe_str(&text, "m.adm", None) else {
                continue;
            };
            if described.resolve().is_err() {
                continue;
            }
            loaded += 1;
            let toml = described.write(Format::Toml).unwrap();
            if let Err(e) = load_str(&toml, Format::Toml, "m.toml") {
                panic!("{e}\nfrom the .adm\n{text}\nconverted to\n{toml}");
            }
        }
    }
    assert!(loaded > 0);
}
