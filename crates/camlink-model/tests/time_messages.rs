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

/// The error of a forward dynamics run of `model` at output `times` with
/// fixed step `h` (s).
fn dynamics_error(model: &camlink_core::Model, times: &[f64], h: f64) -> String {
    use camlink_core::dynamics::integrator::{run, Settings};
    let settings = Settings {
        step: h,
        ..Settings::default()
    };
    let mut table = Table::default();
    run(model, times, &settings, &[], &mut table)
        .expect_err("the run fails")
        .to_string()
}

/// `tests/no_alloc/ball_over_floor.toml` (a ball falling 10 m onto a
/// unilateral floor) with the text `from` replaced by `to` in each pair.
fn ball_over_floor(edits: &[(&str, &str)]) -> camlink_core::Model {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/no_alloc/ball_over_floor.toml");
    let mut text = std::fs::read_to_string(path).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "no {from:?} in the ball model");
        text = text.replace(from, to);
    }
    load_str(&text, Format::Toml, "ball_over_floor.toml")
        .unwrap_or_else(|e| panic!("{e}"))
        .model
}

/// Forward dynamics: the time step, the output times of a run with a
/// unilateral contact and the accumulation of its events.
#[test]
fn issue27_dynamics_messages_are_short() {
    let pendulum = crate::mechanisms::pendulum(0.5, 1.0, 0.02, 0.3, true);
    let e = dynamics_error(&pendulum, &[0.0, 0.01], -1.0000000000000001e-7);
    assert!(
        e.contains("the time step must be a positive number, not -1e-7"),
        "{e}"
    );

    let ball = ball_over_floor(&[]);
    let e = dynamics_error(&ball, &[0.0, 0.01, 1.0000000000000001e-7], 1e-3);
    assert!(
        e.contains("times must increase, but 1e-7 follows 0.01"),
        "{e}"
    );
    assert!(!e.contains("0.0000"), "{e}");

    // No impact closes the contact (rest_speed = 0): the ball comes to
    // rest through ever shorter flights, events closer than 100 event_tol
    // = 1e-7 s apart.
    let ball = ball_over_floor(&[
        ("position = [0, 10]", "position = [0, 0.2]"),
        ("restitution = 0.5", "restitution = 0.5\nrest_speed = 0"),
    ]);
    let e = dynamics_error(&ball, &[0.0, 2.0], 1e-3);
    assert!(e.contains("an accumulation of events"), "{e}");
    assert!(e.contains("within 1e-7 s each"), "{e}");
}

/// A fixed step that is not a number is refused, not replaced by the
/// longest output interval.
#[test]
fn issue27_dynamics_nan_step_is_refused() {
    let pendulum = crate::mechanisms::pendulum(0.5, 1.0, 0.02, 0.3, true);
    let e = dynamics_error(&pendulum, &[0.0, 0.01], f64::NAN);
    assert!(
        e.contains("the time step must be a positive number, not NaN"),
        "{e}"
    );
}
