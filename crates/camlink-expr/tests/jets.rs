//! Jets of every function against closed-form derivatives and against
//! Richardson-extrapolated finite differences.

use crate::common;

use camlink_expr::Expr;
use common::{assert_close, assert_jet, assert_jet_matches_differences, expr};
use std::f64::consts::PI;

type Closed = fn(f64) -> [f64; 4];

/// g and g', g'', g''' written independently of the crate's formulas.
fn closed_forms() -> Vec<(&'static str, Closed, &'static [f64])> {
    const ANY: &[f64] = &[-2.0, -0.7, 0.0, 0.4, 1.3, 2.9];
    const UNIT: &[f64] = &[-0.9, -0.3, 0.0, 0.5, 0.8];
    const POS: &[f64] = &[0.2, 0.9, 1.7, 4.0];
    vec![
        ("sin", |u| [u.sin(), u.cos(), -u.sin(), -u.cos()], ANY),
        ("cos", |u| [u.cos(), -u.sin(), -u.cos(), u.sin()], ANY),
        (
            "tan",
            |u| {
                let (t, s2) = (u.tan(), 1.0 / (u.cos() * u.cos()));
                [t, s2, 2.0 * s2 * t, 2.0 * s2 * s2 + 4.0 * s2 * t * t]
            },
            &[-1.2, -0.5, 0.0, 0.7, 1.4],
        ),
        (
            "asin",
            |u| {
                let w = 1.0 - u * u;
                [
                    u.asin(),
                    w.powf(-0.5),
                    u * w.powf(-1.5),
                    (1.0 + 2.0 * u * u) * w.powf(-2.5),
                ]
            },
            UNIT,
        ),
        (
            "acos",
            |u| {
                let w = 1.0 - u * u;
                [
                    u.acos(),
                    -w.powf(-0.5),
                    -u * w.powf(-1.5),
                    -(1.0 + 2.0 * u * u) * w.powf(-2.5),
                ]
            },
            UNIT,
        ),
        (
            "atan",
            |u| {
                let w = 1.0 + u * u;
                [
                    u.atan(),
                    1.0 / w,
                    -2.0 * u / (w * w),
                    (6.0 * u * u - 2.0) / (w * w * w),
                ]
            },
            ANY,
        ),
        ("sinh", |u| [u.sinh(), u.cosh(), u.sinh(), u.cosh()], ANY),
        ("cosh", |u| [u.cosh(), u.sinh(), u.cosh(), u.sinh()], ANY),
        (
            "tanh",
            |u| {
                let (t, s2) = (u.tanh(), 1.0 / (u.cosh() * u.cosh()));
                [t, s2, -2.0 * s2 * t, 4.0 * s2 * t * t - 2.0 * s2 * s2]
            },
            ANY,
        ),
        ("exp", |u| [u.exp(); 4], ANY),
        (
            "log",
            |u| [u.ln(), 1.0 / u, -1.0 / (u * u), 2.0 / (u * u * u)],
            POS,
        ),
        (
            "ln",
            |u| [u.ln(), 1.0 / u, -1.0 / (u * u), 2.0 / (u * u * u)],
            POS,
        ),
        (
            "sqrt",
            |u| {
                [
                    u.sqrt(),
                    0.5 * u.powf(-0.5),
                    -0.25 * u.powf(-1.5),
                    0.375 * u.powf(-2.5),
                ]
            },
            POS,
        ),
        (
            "abs",
            |u| [u.abs(), u.signum(), 0.0, 0.0],
            &[-2.0, -0.3, 0.4, 2.0],
        ),
        (
            "sign",
            |u| [u.signum(), 0.0, 0.0, 0.0],
            &[-2.0, -0.3, 0.4, 2.0],
        ),
        (
            "floor",
            |u| [u.floor(), 0.0, 0.0, 0.0],
            &[-1.5, -0.3, 0.4, 2.5],
        ),
        (
            "ceil",
            |u| [u.ceil(), 0.0, 0.0, 0.0],
            &[-1.5, -0.3, 0.4, 2.5],
        ),
        ("deg", |u| [u * PI / 180.0, PI / 180.0, 0.0, 0.0], ANY),
    ]
}

/// g(a t + b) has the jet [g, a g', a² g'', a³ g'''] with u = a t + b.
#[test]
fn every_unary_function_against_its_closed_form() {
    let (a, b) = (0.7, 0.1);
    for (name, g, points) in closed_forms() {
        let e = expr(&format!("{name}(0.7*t + 0.1)"));
        for &u in points {
            let t = (u - b) / a;
            let gu = g(a * t + b);
            let want = [gu[0], a * gu[1], a * a * gu[2], a * a * a * gu[3]];
            assert_jet(&e, t, want, 1e-12);
        }
    }
}

/// Nonlinear inner functions exercise every term of Faà di Bruno's formula.
#[test]
fn every_unary_function_of_a_nonlinear_argument_against_differences() {
    let u = "0.5 + 0.3*sin(t) + 0.1*t^2";
    for (name, _, _) in closed_forms() {
        let e = expr(&format!("{name}({u})"));
        for &t in &[-0.9, -0.2, 0.3, 0.8] {
            assert_jet_matches_differences(&e, t, 1e-2, 1e-9);
        }
    }
}

#[test]
fn powers_against_closed_forms() {
    // u^2.5, u^3, u^-2 at u = 0.7 t + 0.1 (PowC, PowI, PowI negative).
    let cases: [(&str, f64); 4] = [("2.5", 2.5), ("3", 3.0), ("-2", -2.0), ("0.5", 0.5)];
    for (src, c) in cases {
        let e = expr(&format!("(0.7*t + 0.1)^{src}"));
        for &t in &[0.3, 1.0, 2.2] {
            let u: f64 = 0.7 * t + 0.1;
            let a: f64 = 0.7;
            let want = [
                u.powf(c),
                a * c * u.powf(c - 1.0),
                a * a * c * (c - 1.0) * u.powf(c - 2.0),
                a * a * a * c * (c - 1.0) * (c - 2.0) * u.powf(c - 3.0),
            ];
            assert_jet(&e, t, want, 1e-12);
        }
    }
    // Integer powers at zero: t^2 has f''' = 0, not 0·∞.
    assert_eq!(expr("t^2").jet(0.0), [0.0, 0.0, 2.0, 0.0]);
    assert_eq!(expr("t^3").jet(0.0), [0.0, 0.0, 0.0, 6.0]);
    assert_eq!(expr("t**1").jet(0.0), [0.0, 1.0, 0.0, 0.0]);
}

#[test]
fn arithmetic_against_differences() {
    for src in [
        "(t^2 + 1) * sin(t)",
        "exp(t) / (2 + cos(3*t))",
        "3 / (1 + t^2)",
        "1 - t/(2 + t^2)",
        "(1 + t)^(2 + sin(t))",
        "t^t",
        "-t^3 + 2*t - 7",
    ] {
        let e = expr(src);
        for &t in &[0.4, 1.1, 1.9] {
            assert_jet_matches_differences(&e, t, 1e-2, 1e-9);
        }
    }
}

#[test]
fn sin_of_exp_of_a_square() {
    let e = expr("sin(exp(t^2))");
    for &t in &[-0.6f64, 0.0, 0.35, 0.8] {
        let w = (t * t).exp();
        let (w1, w2, w3) = (
            2.0 * t * w,
            (2.0 + 4.0 * t * t) * w,
            (12.0 * t + 8.0 * t * t * t) * w,
        );
        let (s, c) = w.sin_cos();
        let want = [
            s,
            c * w1,
            -s * w1 * w1 + c * w2,
            -c * w1 * w1 * w1 - 3.0 * s * w1 * w2 + c * w3,
        ];
        assert_jet(&e, t, want, 1e-11);
        assert_jet_matches_differences(&e, t, 1e-3, 1e-8);
    }
}

#[test]
fn t_to_the_t_by_pow_and_by_exp_log() {
    let pow = expr("t^t");
    let explog = expr("exp(t*log(t))");
    for &t in &[0.3f64, 1.0, 2.5] {
        let (l, p) = (t.ln() + 1.0, t.powf(t));
        let want = [
            p,
            p * l,
            p * (l * l + 1.0 / t),
            p * (l * l * l + 3.0 * l / t - 1.0 / (t * t)),
        ];
        assert_jet(&pow, t, want, 1e-12);
        assert_jet(&explog, t, want, 1e-12);
    }
}

#[test]
fn atan2_hypot_and_mod() {
    // atan2(sin t, cos t) = t on (−π, π); hypot(3t, 4t) = 5|t|.
    for &t in &[-2.5f64, -1.0, 0.3, 1.6, 3.0] {
        assert_jet(&expr("atan2(sin(t), cos(t))"), t, [t, 1.0, 0.0, 0.0], 1e-12);
        assert_jet(
            &expr("atan2(2*sin(t), -2*cos(t))"),
            t,
            {
                let v = (2.0 * t.sin()).atan2(-2.0 * t.cos());
                [v, -1.0, 0.0, 0.0]
            },
            1e-12,
        );
        assert_jet(
            &expr("hypot(3*t, 4*t)"),
            t,
            [5.0 * t.abs(), 5.0 * t.signum(), 0.0, 0.0],
            1e-12,
        );
    }
    for src in [
        "atan2(1 + t^2, 0.5 - t)",
        "atan2(0.2 + t, 3*t^2 - 1)",
        "hypot(sin(t), 1 + t^3)",
        "mod(3*t^2, 0.7 + 0.1*t)",
        "min(sin(t), cos(t)) + max(t^2, 2*t)",
    ] {
        let e = expr(src);
        for &t in &[-0.9, 0.4, 1.3] {
            assert_jet_matches_differences(&e, t, 1e-3, 1e-8);
        }
    }
    // mod is floored: the result has the sign of the divisor.
    assert_eq!(expr("mod(t, 3)").jet(-1.0), [2.0, 1.0, 0.0, 0.0]);
    assert_eq!(expr("mod(t, -3)").eval(1.0), -2.0);
    assert_close(expr("mod(t, 2*pi)").eval(7.0), 7.0 - 2.0 * PI, 1e-15, "mod");
}

#[test]
fn seed_cam_profile_on_both_branches() {
    let e = Expr::parse("if(a <= 2*pi/3, 5/4 - cos(3*a)/4, 1)", "a").unwrap();
    for &a in &[0.0f64, 0.5, 1.2, 2.0] {
        let (s, c) = (3.0 * a).sin_cos();
        let want = [1.25 - c / 4.0, 0.75 * s, 2.25 * c, -6.75 * s];
        assert_jet(&e, a, want, 1e-14);
        assert_jet_matches_differences(&e, a, 1e-3, 1e-9);
    }
    for &a in &[2.2, 3.0, 2.0 * PI] {
        assert_eq!(e.jet(a), [1.0, 0.0, 0.0, 0.0]);
    }
    // The two branches meet at 2π/3 with value 1.
    assert_close(e.eval(2.0 * PI / 3.0), 1.0, 1e-15, "value at 2π/3");
    assert!(e.check(1.0).is_ok());
}

#[test]
fn driver_is_affine() {
    let e = expr("pi/6 + 2*pi*t");
    for &t in &[0.0, 0.25, 3.0] {
        assert_jet(&e, t, [PI / 6.0 + 2.0 * PI * t, 2.0 * PI, 0.0, 0.0], 1e-15);
    }
}

/// Value-only evaluation and the jet's value come from the same `f64`
/// operations, so they agree exactly.
#[test]
fn eval_equals_the_value_of_the_jet_bit_for_bit() {
    for src in [
        "if(t <= 2*pi/3, 5/4 - cos(3*t)/4, 1)",
        "t^t + t^2.5 + t^-3 + 2^t",
        "atan2(t, 1 - t) + hypot(t, 2) + mod(t, 0.3)",
        "asin(t/4) * acos(t/5) / (1 + atan(t))",
        "sqrt(t) + log(t) + exp(-t) + sinh(t) - cosh(t) * tanh(t)",
        "step(t, 0, 1, 2, 3) + step5(t, 0, 1, 2, 3) + ramp(t, 0, 1, 2, 3)",
        "harmonic(t, 2, 0, 0, 1) + cycloidal(t, 0.5, -1, 1.5, 1) + poly345(t, 0, 0, 3, 1)",
        "min(t, 1, 2) + max(t, -1) + abs(t - 1) + sign(t - 1) + floor(t) + ceil(t)",
        "(t > 1) + (t >= 1) + (t < 1) + (t <= 1) + (t == 1) + (t != 1)",
        "(t > 1 and t < 2) + (t < 0.5 or not t < 3)",
        "tan(t) + deg(t)",
    ] {
        let e = expr(src);
        for &t in &[0.0, 0.25, 0.5, 1.0, 1.5, 2.0, 2.75, 4.0] {
            let (v, j) = (e.eval(t), e.jet(t)[0]);
            assert!(
                v.to_bits() == j.to_bits() || (v.is_nan() && j.is_nan()),
                "`{src}` at {t}: {v} vs {j}"
            );
        }
    }
}
