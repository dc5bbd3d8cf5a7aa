//! Issue 27: times in messages are written by the one number formatter:
//! `1e-300`, not 298 digits; `1e-7`, not `0.00000010000000000000001`.

use camlink_core::kinematics;
use camlink_core::run::{Settings, Table};
use camlink_model::{load_str, Format};

/// The error of a kinematic run of an arm driven by `f` at output `times`.
fn run_error(f: &str, times: &[f64]) -> String {
    let text = format!(
        r#"
[[bodies]]
name = "arm"
points = {{ tip = [1, 0] }}

[[joints]]
name = "pivot"
type = "revolute"
body_i = "ground"
body_j = "arm"

[[drivers]]
name = "motor"
type = "revolute_angle"
joint = "pivot"
f = "{f}"
"#
    );
    let l = load_str(&text, Format::Toml, "arm.toml").unwrap_or_else(|e| panic!("{e}"));
    let mut table = Table::default();
    kinematics::run(&l.model, times, &Settings::default(), &[], &mut table)
        .expect_err("the run fails")
        .to_string()
}

#[test]
fn issue27_time_messages_are_short() {
    let e = run_error("log(-t)", &[1e-300]);
    assert!(e.starts_with("at t = 1e-300 s: "), "{e}");
    assert!(
        e.contains("log of a negative number (-1e-300) in `log(-t)` at t = 1e-300;"),
        "{e}"
    );
    assert!(!e.contains("0.0000"), "{e}");

    let e = run_error("sqrt(-t)", &[1.0000000000000001e-7]);
    assert!(e.starts_with("at t = 1e-7 s: "), "{e}");
    assert!(
        e.contains("square root of a negative number (-1e-7) in `sqrt(-t)` at t = 1e-7;"),
        "{e}"
    );

    let e = run_error("t", &[0.5, 1e-300]);
    assert!(
        e.contains("times must increase, but 1e-300 follows 0.5"),
        "{e}"
    );
}
