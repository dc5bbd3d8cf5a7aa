//! Motion laws called from expressions: end values, smoothness, jets.

use crate::common;

use camlink_expr::Law;
use common::{assert_close, assert_jet_matches_differences, expr};
use std::f64::consts::PI;

/// (name, law, highest continuous derivative at the ends).
const LAWS: [(&str, Law, usize); 6] = [
    ("ramp", Law::Ramp, 0),
    ("step", Law::Step, 1),
    ("step5", Law::Poly345, 2),
    ("poly345", Law::Poly345, 2),
    ("harmonic", Law::Harmonic, 1),
    ("cycloidal", Law::Cycloidal, 2),
];

const X0: f64 = 0.2;
const H0: f64 = 0.1;
const X1: f64 = 1.7;
const H1: f64 = 0.3;

fn call(name: &str) -> String {
    format!("{name}(t, {X0}, {H0}, {X1}, {H1})")
}

#[test]
fn end_values_are_exact_and_constant_outside() {
    for (name, _, _) in LAWS {
        let e = expr(&call(name));
        assert_eq!(e.jet(X0), [H0, 0.0, 0.0, 0.0], "{name}");
        assert_eq!(e.jet(X1), [H1, 0.0, 0.0, 0.0], "{name}");
        assert_eq!(e.jet(-3.0), [H0, 0.0, 0.0, 0.0], "{name}");
        assert_eq!(e.jet(9.0), [H1, 0.0, 0.0, 0.0], "{name}");
        let mid = e.eval(0.5 * (X0 + X1));
        assert_close(mid, 0.5 * (H0 + H1), 1e-15, name);
    }
}

#[test]
fn derivatives_are_continuous_exactly_to_the_documented_order() {
    let d = 1e-7;
    for (name, law, c) in LAWS {
        assert_eq!(law.continuity(), c, "{name}");
        let e = expr(&call(name));
        for x in [X0, X1] {
            let (l, r) = (e.jet(x - d), e.jet(x + d));
            for k in 0..=c {
                assert!(
                    (l[k] - r[k]).abs() < 1e-5,
                    "{name} order {k} at {x}: {} vs {}",
                    l[k],
                    r[k]
                );
            }
            assert!(
                (l[c + 1] - r[c + 1]).abs() > 1e-2,
                "{name} order {} is continuous at {x}",
                c + 1
            );
        }
    }
}

#[test]
fn peak_velocities_at_mid_rise() {
    // f'(mid) = v·(h1 − h0)/(x1 − x0) with v the shape's s'(1/2).
    let slope = (H1 - H0) / (X1 - X0);
    for (name, v) in [
        ("ramp", 1.0),
        ("step", 1.5),
        ("poly345", 1.875),
        ("harmonic", PI / 2.0),
        ("cycloidal", 2.0),
    ] {
        let j = expr(&call(name)).jet(0.5 * (X0 + X1));
        assert_close(j[1], v * slope, 1e-14, name);
    }
}

#[test]
fn jets_against_differences_inside_the_rise() {
    for (name, _, _) in LAWS {
        let e = expr(&call(name));
        for x in [0.35, 0.7, 0.95, 1.3, 1.6] {
            assert_jet_matches_differences(&e, x, 1e-3, 1e-8);
        }
    }
}

#[test]
fn laws_of_expressions_follow_the_chain_rule() {
    for (name, _, _) in LAWS {
        // x, h1 and x1 all depend on t.
        let e = expr(&format!("{name}(sin(t), -0.5, 1, 0.8 + 0.1*t, 3*t^2)"));
        for t in [-0.3, 0.1, 0.5] {
            assert_jet_matches_differences(&e, t, 1e-3, 1e-8);
        }
    }
}

#[test]
fn reversed_laws_run_towards_decreasing_x() {
    // From (2, 7) back to (1, 3): 7 for x ≥ 2, 3 for x ≤ 1.
    for (name, _, _) in LAWS {
        let e = expr(&format!("{name}(t, 2, 7, 1, 3)"));
        assert_eq!(e.eval(2.5), 7.0);
        assert_eq!(e.eval(0.5), 3.0);
        assert_close(e.eval(1.5), 5.0, 1e-15, name);
        assert!(e.jet(1.5)[1] > 0.0, "{name} rises with x");
        assert_jet_matches_differences(&e, 1.3, 1e-3, 1e-8);
    }
}

#[test]
fn adams_step_matches_its_definition() {
    // STEP(x, x0, h0, x1, h1) = h0 + (h1 − h0) Δ²(3 − 2Δ), Δ = (x − x0)/(x1 − x0).
    let e = expr("step(t, 1, -2, 3, 4)");
    for x in [1.2, 1.9, 2.5, 2.99] {
        let dl: f64 = (x - 1.0) / 2.0;
        let want = -2.0 + 6.0 * dl * dl * (3.0 - 2.0 * dl);
        assert_close(e.eval(x), want, 1e-15, "step");
    }
}
