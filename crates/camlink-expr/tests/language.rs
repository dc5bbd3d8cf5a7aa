//! The expression language: precedence, logic, branches, names, constants.

use crate::common;

use camlink_expr::{eval_constant, Expr};
use common::expr;
use std::collections::HashMap;
use std::f64::consts::{E, PI};

fn value(src: &str) -> f64 {
    expr(src).eval(f64::NAN)
}

fn params(list: &[(&str, f64)]) -> HashMap<String, f64> {
    list.iter().map(|&(k, v)| (k.to_owned(), v)).collect()
}

#[test]
fn precedence_and_associativity() {
    assert_eq!(value("1 + 2 * 3"), 7.0);
    assert_eq!(value("(1 + 2) * 3"), 9.0);
    assert_eq!(value("1 - 2 - 3"), -4.0);
    assert_eq!(value("8 / 4 / 2"), 1.0);
    assert_eq!(value("-2^2"), -4.0);
    assert_eq!(value("(-2)^2"), 4.0);
    assert_eq!(value("2^3^2"), 512.0);
    assert_eq!(value("2**3**2"), 512.0);
    assert_eq!(value("2^-1"), 0.5);
    assert_eq!(value("2^-1*4"), 2.0);
    assert_eq!(value("- -3"), 3.0);
    assert_eq!(value("+3"), 3.0);
    assert_eq!(value("1 + 2 < 4"), 1.0);
    assert_eq!(value("not 1 == 2"), 1.0);
    assert_eq!(value("!0"), 1.0);
    assert_eq!(value("1 or 0 and 0"), 1.0);
    assert_eq!(value("(1 or 0) and 0"), 0.0);
    assert_eq!(value(".5 + 1e-3 + 2. + 1.5E+2"), 152.501);
}

#[test]
fn comparisons_and_logic_give_one_or_zero() {
    let e = expr("(t > 1) + 2*(t >= 1) + 4*(t < 1) + 8*(t <= 1) + 16*(t == 1) + 32*(t != 1)");
    assert_eq!(e.eval(0.0), 4.0 + 8.0 + 32.0);
    assert_eq!(e.eval(1.0), 2.0 + 8.0 + 16.0);
    assert_eq!(e.eval(2.0), 1.0 + 2.0 + 32.0);
    assert_eq!(e.jet(1.0)[1..], [0.0, 0.0, 0.0]);
    assert_eq!(expr("t and 5").eval(3.0), 1.0);
    assert_eq!(expr("t && 5").eval(0.0), 0.0);
    assert_eq!(expr("t or 0").eval(-2.0), 1.0);
    assert_eq!(expr("t || 0").eval(0.0), 0.0);
    assert_eq!(expr("not t").eval(0.0), 1.0);
}

#[test]
fn if_evaluates_only_the_chosen_branch() {
    // log(t) at t = -1 would be NaN; the branch is not taken.
    let e = expr("if(t > 0, log(t), -t)");
    assert_eq!(e.jet(-1.0), [1.0, -1.0, 0.0, 0.0]);
    assert!(e.check(-1.0).is_ok());
    assert_eq!(e.jet(1.0), [0.0, 1.0, -1.0, 2.0]);
    // Logic short-circuits the same way.
    assert!(expr("t > 0 and log(t) > 1").check(-1.0).is_ok());
    assert!(expr("t < 0 or log(t) > 1").check(-1.0).is_ok());
    // Nested branches.
    let e = expr("if(t < 0, -1, if(t < 1, t^2, 2*t - 1))");
    assert_eq!(e.jet(-3.0), [-1.0, 0.0, 0.0, 0.0]);
    assert_eq!(e.jet(0.5), [0.25, 1.0, 2.0, 0.0]);
    assert_eq!(e.jet(2.0), [3.0, 2.0, 0.0, 0.0]);
}

#[test]
fn constant_conditions_keep_one_branch() {
    let e = expr("if(1 < 2, 3, t)");
    assert!(e.is_constant());
    assert_eq!(e.eval(7.0), 3.0);
    let e = expr("if(pi > 4, 3, t)");
    assert!(!e.is_constant());
    assert_eq!(e.eval(7.0), 7.0);
}

#[test]
fn builtin_constants_and_parameters() {
    assert_eq!(value("pi"), PI);
    assert_eq!(value("π"), PI);
    assert_eq!(value("e"), E);
    let p = params(&[("r", 0.25), ("e", 0.01), ("omega", 2.0)]);
    let f = Expr::parse_with("r + e*cos(omega*t)", Some("t"), &p).unwrap();
    assert_eq!(f.eval(0.0), 0.26);
    assert_eq!(f.jet(0.0)[2], -0.01 * 4.0);
    assert_eq!(eval_constant("2*r", &p), Ok(0.5));
    assert_eq!(eval_constant("deg(30)", &HashMap::new()), Ok(PI / 6.0));
    assert_eq!(eval_constant("deg(180)", &HashMap::new()), Ok(PI));
}

#[test]
fn the_variable_may_be_any_name() {
    let e = Expr::parse("α^2", "α").unwrap();
    assert_eq!(e.jet(3.0), [9.0, 6.0, 2.0, 0.0]);
    assert_eq!(e.var(), Some("α"));
    let e = Expr::parse("2*angle", "angle").unwrap();
    assert_eq!(e.eval(1.5), 3.0);
    assert!(Expr::parse("1", "if").is_err());
    assert!(Expr::parse("1", "2x").is_err());
    assert!(Expr::parse("1", "").is_err());
}

#[test]
fn is_constant() {
    assert!(expr("2*pi + sin(1)").is_constant());
    assert!(!expr("2*pi + sin(t)").is_constant());
    assert!(!expr("0*t").is_constant());
    let c = Expr::parse_with("3 + r", None, &params(&[("r", 1.0)])).unwrap();
    assert!(c.is_constant());
    assert_eq!(c.var(), None);
    assert_eq!(c.jet(5.0), [4.0, 0.0, 0.0, 0.0]);
}

#[test]
fn source_and_display() {
    let e = expr("pi/6 + 2*pi*t");
    assert_eq!(e.source(), "pi/6 + 2*pi*t");
    assert_eq!(e.to_string(), "pi/6 + 2*pi*t");
}

#[test]
fn whitespace_and_newlines() {
    assert_eq!(expr(" \t1 +\n  t\r\n").eval(2.0), 3.0);
}

#[test]
fn min_and_max_take_several_arguments() {
    let e = expr("min(3, t, 2*t, 1)");
    assert_eq!(e.jet(0.4), [0.4, 1.0, 0.0, 0.0]);
    assert_eq!(e.jet(2.0), [1.0, 0.0, 0.0, 0.0]);
    assert_eq!(expr("max(-t, t^2, -5)").jet(-3.0), [9.0, -6.0, 2.0, 0.0]);
}

#[test]
fn expr_is_shareable() {
    fn shareable<T: Clone + std::fmt::Debug + Send + Sync>() {}
    shareable::<Expr>();
    let e = expr("sin(t)");
    let handles: Vec<_> = (0..2)
        .map(|i| {
            let e = e.clone();
            std::thread::spawn(move || e.eval(i as f64))
        })
        .collect();
    for (i, h) in handles.into_iter().enumerate() {
        assert_eq!(h.join().unwrap(), (i as f64).sin());
    }
}

#[test]
fn long_flat_expressions_compile() {
    // 20 000 terms: left-associative chains do not recurse.
    let src = vec!["t"; 20_000].join(" + ");
    let e = expr(&src);
    assert_eq!(e.jet(0.5), [10_000.0, 20_000.0, 0.0, 0.0]);
    // A Horner polynomial nests one level deeper per coefficient.
    let mut horner = String::from("1");
    for _ in 0..20 {
        horner = format!("1 + t*({horner})");
    }
    let e = expr(&horner);
    assert_eq!(e.eval(1.0), 21.0);
    assert_eq!(e.jet(0.0)[1], 1.0);
}

#[test]
fn names_lists_what_an_expression_reads_not_what_it_calls() {
    assert_eq!(
        camlink_expr::names("a*sin(w*t) + a + max(b, 2e3) - pi").unwrap(),
        vec!["a", "w", "t", "b", "pi"]
    );
    assert_eq!(camlink_expr::names("1 + 2").unwrap(), Vec::<&str>::new());
    assert!(camlink_expr::names("a $ b").is_err());
}

#[test]
fn names_leave_out_the_word_operators() {
    // `and`, `or` and `not` are operators: a force of state written with
    // them reads only its channels.
    assert_eq!(
        camlink_expr::names("ram_vx > 0 and not ram_x > 1 or t < 2").unwrap(),
        vec!["ram_vx", "ram_x", "t"]
    );
}
