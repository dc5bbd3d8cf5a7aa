//! What each fuzz target does with its input, shared by the cargo-fuzz
//! targets (`fuzz/fuzz_targets/`) and the stable test that replays the
//! corpus and the regressions (`crates/camlink-model/tests/fuzz_corpus.rs`).
//!
//! A target returns normally for every input; a panic is the bug. Beyond
//! "no panic", the targets assert properties that hold for every input:
//! a load error has a message, an expression error points inside its
//! source, and an expression whose `check` passes has finite jets.

use std::collections::HashMap;

use camlink_core::kinematics;
use camlink_core::run::{Settings, Table};
use camlink_core::Model;
use camlink_expr::{eval_constant, Expr};
use camlink_model::{load_str, Format};

/// Output times of the short run made on every model that loads (s).
pub const RUN_TIMES: [f64; 3] = [0.0, 0.01, 0.02];

/// Largest coordinate count for which `diagnose` (a dense SVD) is tried.
pub const DIAGNOSE_MAX: usize = 60;

/// Model file bytes as TOML.
pub fn load_toml(data: &[u8]) {
    load(data, Format::Toml, "fuzz.toml");
}

/// Model file bytes as JSON.
pub fn load_json(data: &[u8]) {
    load(data, Format::Json, "fuzz.json");
}

/// Loads `data`; a model that loads is checked and run for three steps.
pub fn load(data: &[u8], format: Format, source: &str) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match load_str(text, format, source) {
        Ok(loaded) => analyse(&loaded.model, loaded.analysis.tol),
        Err(e) => {
            let shown = e.to_string();
            assert!(
                shown.starts_with(source) && !e.message.trim().is_empty(),
                "load error without a message: {shown:?}"
            );
        }
    }
}

/// What `camlink check` and a short `camlink run` do with a loaded model,
/// with a tiny Newton budget so that a hard model fails fast.
pub fn analyse(model: &Model, tol: f64) {
    let _ = model.check_grounded();
    let _ = model.check_mass_properties();
    let report = kinematics::check(model);
    if report.coordinates <= DIAGNOSE_MAX {
        let d = camlink_core::diagnose::diagnose(model, 0.0, tol);
        assert!(d.rank <= d.coordinates.min(d.equations));
    }
    let settings = Settings {
        tol: tol.max(1e-12),
        max_iter: 4,
        ..Settings::default()
    };
    let mut table = Table::default();
    let result = kinematics::run(model, &RUN_TIMES, &settings, &[], &mut table);
    // A run keeps the steps it finished, and reports why it stopped.
    let finished = table.t.len();
    match result {
        Ok(_) => assert_eq!(finished, RUN_TIMES.len()),
        Err(e) => {
            assert!(finished < RUN_TIMES.len());
            assert!(!e.message.is_empty());
        }
    }
}

/// Points where the `expr` target evaluates an expression.
pub const POINTS: [f64; 9] = [
    0.0,
    -0.0,
    1.0,
    -1.5,
    0.5,
    2.0944,
    1e300,
    f64::INFINITY,
    f64::NAN,
];

/// Expression source bytes: parse as a function of `t`, of `a` with a
/// parameter `r`, and as a constant; evaluate, take jets and check.
pub fn expr(data: &[u8]) {
    let Ok(src) = std::str::from_utf8(data) else {
        return;
    };
    let params: HashMap<String, f64> = [("r".to_owned(), 0.5)].into();
    for parsed in [
        Expr::parse(src, "t"),
        Expr::parse_with(src, Some("a"), &params),
        Expr::parse_with(src, None, &params),
    ] {
        match parsed {
            Ok(e) => {
                for x in POINTS {
                    exercise(&e, x);
                }
            }
            Err(err) => {
                assert!(err.offset <= src.len(), "offset past the end of {src:?}");
                let shown = err.render(src);
                assert!(!shown.is_empty());
            }
        }
    }
    let _ = eval_constant(src, &params);
}

/// eval, jet and check at one point, and how they agree.
fn exercise(e: &Expr, x: f64) {
    let v = e.eval(x);
    let jet = e.jet(x);
    match e.check(x) {
        Ok(()) => {
            if x.is_finite() {
                assert!(
                    jet.iter().all(|d| d.is_finite()),
                    "check passed but the jet of `{e}` at {x} is {jet:?}"
                );
            }
        }
        Err(err) => assert!(!err.message.is_empty()),
    }
    // The value path and the jet path compute the same f(x).
    if v.is_finite() || jet[0].is_finite() {
        let scale = v.abs().max(jet[0].abs()).max(1.0);
        assert!(
            (v - jet[0]).abs() <= 1e-9 * scale,
            "eval and jet disagree for `{e}` at {x}: {v} vs {}",
            jet[0]
        );
    }
}
