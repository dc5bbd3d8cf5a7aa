//! `Expr::check`: the first failing operation, named and quoted.

use crate::common;

use camlink_expr::{eval_constant, EvalError, Expr};
use common::expr;
use std::collections::HashMap;

fn message(src: &str, t: f64) -> String {
    match expr(src).check(t) {
        Ok(()) => panic!("`{src}` passed the check at t = {t}"),
        Err(EvalError { message, x }) => {
            assert_eq!(x.to_bits(), t.to_bits());
            message
        }
    }
}

#[test]
fn domain_errors_name_the_operation_and_quote_it() {
    assert_eq!(
        message("log(t - 1)", 0.5),
        "log of a negative number (-0.5) in `log(t - 1)` at t = 0.5"
    );
    assert_eq!(message("1 + ln(t)", 0.0), "log of zero in `ln(t)` at t = 0");
    assert_eq!(
        message("2 + 1/(t - 2)", 2.0),
        "division by zero in `1/(t - 2)` at t = 2"
    );
    assert_eq!(message("t/0", 1.0), "division by zero in `t/0` at t = 1");
    assert_eq!(message("t/-0", 1.0), "division by zero in `t/-0` at t = 1");
    assert_eq!(
        message("(1 + t)/t", 0.0),
        "division by zero in `(1 + t)/t` at t = 0"
    );
    assert_eq!(
        message("sqrt(t)", -1.0),
        "square root of a negative number (-1) in `sqrt(t)` at t = -1"
    );
    assert_eq!(
        message("asin(2*t)", 1.0),
        "asin of 2, outside [-1, 1] in `asin(2*t)` at t = 1"
    );
    assert_eq!(
        message("acos(t)", -1.5),
        "acos of -1.5, outside [-1, 1] in `acos(t)` at t = -1.5"
    );
    assert_eq!(
        message("mod(1, t)", 0.0),
        "mod by zero in `mod(1, t)` at t = 0"
    );
    assert_eq!(
        message("t^0.5", -4.0),
        "negative number (-4) raised to the non-integer power 0.5 in `t^0.5` at t = -4"
    );
    assert_eq!(
        message("t^-2", 0.0),
        "zero raised to a negative power (-2) in `t^-2` at t = 0"
    );
    assert_eq!(
        message("atan2(t, t)", 0.0),
        "atan2(0, 0) is undefined in `atan2(t, t)` at t = 0"
    );
    assert_eq!(
        message("step(t, 1, 0, 1, 2)", 0.0),
        "motion law with x0 = x1 (= 1) in `step(t, 1, 0, 1, 2)` at t = 0"
    );
}

#[test]
fn values_and_derivatives_that_are_not_finite() {
    assert_eq!(
        message("exp(t)", 1000.0),
        "result is not finite (inf) in `exp(t)` at t = 1000"
    );
    // √t is 0 at t = 0 but its slope is infinite.
    assert_eq!(
        message("1 + sqrt(t)", 0.0),
        "first derivative is not finite (inf) in `sqrt(t)` at t = 0"
    );
    assert_eq!(
        message("asin(t)", 1.0),
        "first derivative is not finite (inf) in `asin(t)` at t = 1"
    );
    assert_eq!(
        message("t", f64::NAN),
        "the variable is not finite (NaN) in `t` at t = NaN"
    );
}

#[test]
fn the_quote_is_one_line_and_short() {
    let src = "1 +\n  log(t\n   - 1 + 0*t + 0*t + 0*t + 0*t + 0*t + 0*t + 0*t + 0*t + 0*t)";
    assert_eq!(
        message(src, 0.0),
        "log of a negative number (-1) in `log(t - 1 + 0*t + 0*t + 0*t + 0*t + 0*t + 0*t + 0*t + 0*t...` at t = 0"
    );
}

#[test]
fn healthy_points_pass() {
    for (src, t) in [
        ("if(t <= 2*pi/3, 5/4 - cos(3*t)/4, 1)", 1.0),
        ("log(t - 1)", 2.0),
        ("sqrt(t)", 0.25),
        ("1/(t - 2)", 1.0),
        ("cycloidal(t, 0, 0, 1, 2)", 0.5),
        ("pi/6 + 2*pi*t", 0.0),
    ] {
        assert_eq!(expr(src).check(t), Ok(()), "`{src}` at {t}");
    }
}

#[test]
fn constant_expressions_report_without_a_variable() {
    let e = Expr::parse_with("1 + log(-2)", None, &HashMap::new()).unwrap();
    assert_eq!(
        e.check(0.0).unwrap_err().message,
        "log of a negative number (-2) in `log(-2)`"
    );
    assert!(e.eval(0.0).is_nan());
    let err = eval_constant("3 + 1/(2 - 2)", &HashMap::new()).unwrap_err();
    assert_eq!(err.message, "division by zero");
    assert_eq!((err.offset, err.len), (4, 9));
    assert_eq!(
        err.render("3 + 1/(2 - 2)"),
        "3 + 1/(2 - 2)\n    ^^^^^^^^^\ndivision by zero"
    );
}

#[test]
fn unchecked_evaluation_gives_nan_or_infinity() {
    assert!(expr("log(t)").eval(-1.0).is_nan());
    assert_eq!(expr("1/t").eval(0.0), f64::INFINITY);
    let j = expr("sqrt(t)").jet(0.0);
    assert_eq!(j[0], 0.0);
    assert_eq!(j[1], f64::INFINITY);
    assert!(expr("asin(t)").jet(2.0).iter().all(|v| v.is_nan()));
}

/// Issue 27: a time in an evaluation error is written short: `1e-300`, not
/// 298 digits; `1e-7`, not `0.00000010000000000000001`. A value just past a
/// limit keeps the digits that tell it from the limit.
#[test]
fn issue27_times_and_values_in_errors_are_readable() {
    assert_eq!(
        message("log(-t)", 1e-300),
        "log of a negative number (-1e-300) in `log(-t)` at t = 1e-300"
    );
    assert_eq!(
        message("sqrt(-t)", 1.0000000000000001e-7),
        "square root of a negative number (-1e-7) in `sqrt(-t)` at t = 1e-7"
    );
    assert_eq!(
        message("asin(1 + t)", 2.220446049250313e-16),
        "asin of 1.0000000000000002, outside [-1, 1] in `asin(1 + t)` at t = 2.22045e-16"
    );
}
