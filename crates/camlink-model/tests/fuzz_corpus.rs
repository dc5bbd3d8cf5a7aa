//! The fuzz targets on stable Rust: every seed in `fuzz/corpus/<target>/`,
//! every crash kept in `fuzz/regressions/<target>/` and every model under
//! `tests/models/` goes through the same code as the cargo-fuzz targets
//! (`camlink-fuzz-targets`), then a deterministic mutation loop (bit flips,
//! truncations, splices, token insertions) runs a few thousand cases.
//!
//! The long run: `CAMLINK_FUZZ_ITERS=1000000 cargo test --release -p
//! camlink-model --test integration fuzz_corpus::` (and `CAMLINK_FUZZ_SEED=<n>` for other
//! cases); coverage-guided fuzzing with cargo-fuzz is in `fuzz/README.md`.
//! A failing case is written to `target/fuzz-failures/` so it can be added
//! to the regressions.

use crate::targets;

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Files directly in `dir` (none when it does not exist), sorted.
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_file() && p.file_name().is_some_and(|n| n != "README.md"))
        .collect();
    out.sort();
    out
}

/// A fuzz target: its name, its logic, its extra seeds from `tests/models`.
struct Target {
    name: &'static str,
    run: fn(&[u8]),
    extension: Option<&'static str>,
    tokens: &'static [&'static str],
}

const MODEL_TOKENS: &[&str] = &[
    "\"",
    "'",
    "[",
    "]",
    "{",
    "}",
    ",",
    "=",
    ":",
    "\n",
    "\r\n",
    "-",
    "0",
    "1e308",
    "-1e400",
    "nan",
    "inf",
    "-inf",
    "1e-320",
    "\"1/0\"",
    "\"log(-1)\"",
    "\"deg(\"",
    "\"t\"",
    "\"ground\"",
    "\"crank\"",
    "\"crank.A\"",
    "\"\"",
    "null",
    "true",
    "[0, 0]",
    "[1e300, -1e300]",
    "\u{feff}",
    "\u{e9}",
    "\u{1F600}",
    "\0",
    "#",
    "//",
    "\\u0000",
    "type = \"gear\"\n",
    "type = \"revolute\"\n",
    "type = \"translational\"\n",
    "type = \"rack_pinion\"\n",
    "\"revolute_angle\"",
    "\"absolute_phi\"",
    "\"relative_distance\"",
    "\"translational_travel\"",
    "[[bodies]]\nname = \"k\"\n",
    "[[joints]]\n",
    "[[drivers]]\n",
    "[analysis]\n",
    "[parameters]\n",
    "\"bodies\": [{\"name\": \"k\"}]",
    "\"f\": \"1/(t-0.01)\"",
    "step = 1e-300\n",
    "t_end = 1e300\n",
    "times = [0, 0, -1]\n",
    "max_iter = 0\n",
    "tol = 0\n",
    "\"sqrt(t - 0.01)\"",
];

const EXPR_TOKENS: &[&str] = &[
    "t",
    "a",
    "r",
    "(",
    ")",
    ",",
    "+",
    "-",
    "*",
    "/",
    "^",
    "**",
    "<",
    "<=",
    "==",
    "!=",
    "and",
    "or",
    "not",
    "!",
    "&&",
    "||",
    "if(",
    "sin(",
    "log(",
    "sqrt(",
    "asin(",
    "atan2(",
    "mod(",
    "min(",
    "max(",
    "step(",
    "cycloidal(",
    "hypot(",
    "deg(",
    "pi",
    "π",
    "e",
    "1e308",
    "0",
    ".",
    "1e",
    "1e-400",
    "α",
    " ",
    "\u{feff}",
    "é",
    "((((((((((",
    "))))))))))",
];

const TARGETS: [Target; 3] = [
    Target {
        name: "load_toml",
        run: targets::load_toml,
        extension: Some("toml"),
        tokens: MODEL_TOKENS,
    },
    Target {
        name: "load_json",
        run: targets::load_json,
        extension: Some("json"),
        tokens: MODEL_TOKENS,
    },
    Target {
        name: "expr",
        run: targets::expr,
        extension: None,
        tokens: EXPR_TOKENS,
    },
];

/// Runs the target on `data`; a panic fails the test after saving the input.
fn run_case(target: &Target, data: &[u8], label: &str) {
    let outcome = catch_unwind(AssertUnwindSafe(|| (target.run)(data)));
    if let Err(panic) = outcome {
        let dir = root().join("target/fuzz-failures");
        let _ = std::fs::create_dir_all(&dir);
        let saved = dir.join(format!("{}-{}", target.name, label.replace('/', "_")));
        let _ = std::fs::write(&saved, data);
        let what = panic
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        panic!(
            "{} panicked on {label} (input saved as {}): {what}",
            target.name,
            saved.display()
        );
    }
}

/// The seeds of a target: its corpus, its regressions and the model files
/// of its format under `tests/models/`.
fn seeds(target: &Target) -> Vec<(String, Vec<u8>)> {
    let mut paths = files(&root().join("fuzz/corpus").join(target.name));
    paths.extend(files(&root().join("fuzz/regressions").join(target.name)));
    if let Some(ext) = target.extension {
        for dir in ["tests/models", "tests/models/bad", "examples"] {
            paths.extend(
                files(&root().join(dir))
                    .into_iter()
                    .filter(|p| p.extension().is_some_and(|e| e == ext)),
            );
        }
    }
    paths
        .into_iter()
        .map(|p| {
            let name = p.strip_prefix(root()).unwrap_or(&p).display().to_string();
            (name, std::fs::read(&p).unwrap())
        })
        .collect()
}

#[test]
fn corpus_and_regressions_replay() {
    for target in &TARGETS {
        let seeds = seeds(target);
        assert!(
            seeds.len() >= 8,
            "{}: only {} seeds",
            target.name,
            seeds.len()
        );
        for (name, data) in &seeds {
            run_case(target, data, name);
        }
    }
}

/// xorshift64*: a small deterministic generator.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// One to four mutations of a seed: bit flips, truncations, splices with
/// another seed, token insertions, deletions and repeats of a chunk.
fn mutate(rng: &mut Rng, seed: &[u8], other: &[u8], tokens: &[&str]) -> Vec<u8> {
    let mut data = seed.to_vec();
    for _ in 0..1 + rng.below(4) {
        let k = rng.below(data.len() + 1);
        match rng.below(6) {
            0 if k < data.len() => data[k] ^= 1 << rng.below(7),
            1 => data.truncate(k),
            2 => {
                let from = rng.below(other.len() + 1);
                data.truncate(k);
                data.extend_from_slice(&other[from..]);
            }
            3 => {
                let token = tokens[rng.below(tokens.len())].as_bytes();
                data.splice(k..k, token.iter().copied());
            }
            4 if k < data.len() => {
                let end = (k + 1 + rng.below(32)).min(data.len());
                data.drain(k..end);
            }
            _ => {
                let end = (k + rng.below(64)).min(data.len());
                let chunk = data[k..end].to_vec();
                for _ in 0..1 + rng.below(8) {
                    data.splice(k..k, chunk.iter().copied());
                }
            }
        }
    }
    data
}

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

#[test]
fn mutated_seeds_never_panic() {
    let iters = env_number("CAMLINK_FUZZ_ITERS", 1500);
    let seed = env_number("CAMLINK_FUZZ_SEED", 0x5EED_CA11_1B4D_F00D);
    for (t, target) in TARGETS.iter().enumerate() {
        let seeds = seeds(target);
        let mut rng = Rng(seed ^ (t as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
        for case in 0..iters {
            let a = &seeds[rng.below(seeds.len())].1;
            let b = &seeds[rng.below(seeds.len())].1;
            let data = mutate(&mut rng, a, b, target.tokens);
            run_case(target, &data, &format!("case-{case}-seed-{seed:x}"));
        }
    }
}
