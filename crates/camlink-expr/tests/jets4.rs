//! Fourth-order jets (`Expr::jet4`) of every function against closed-form
//! derivatives, against Richardson-extrapolated finite differences of the
//! order below, and against the third-order jets.

use crate::common;

use camlink_expr::{Expr, Law};
use common::{assert_close, expr, richardson};
use std::f64::consts::PI;

type Closed = fn(f64) -> [f64; 5];

/// g and its first four derivatives, written independently of the crate's
/// formulas (the fourth by differentiating the third by hand).
fn closed_forms() -> Vec<(&'static str, Closed, &'static [f64])> {
    const ANY: &[f64] = &[-2.0, -0.7, 0.0, 0.4, 1.3, 2.9];
    const UNIT: &[f64] = &[-0.9, -0.3, 0.0, 0.5, 0.8];
    const POS: &[f64] = &[0.2, 0.9, 1.7, 4.0];
    vec![
        (
            "sin",
            |u| [u.sin(), u.cos(), -u.sin(), -u.cos(), u.sin()],
            ANY,
        ),
        (
            "cos",
            |u| [u.cos(), -u.sin(), -u.cos(), u.sin(), u.cos()],
            ANY,
        ),
        (
            "tan",
            |u| {
                let (t, s2) = (u.tan(), 1.0 / (u.cos() * u.cos()));
                [
                    t,
                    s2,
                    2.0 * s2 * t,
                    2.0 * s2 * s2 + 4.0 * s2 * t * t,
                    16.0 * s2 * s2 * t + 8.0 * s2 * t * t * t,
                ]
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
                    u * (9.0 + 6.0 * u * u) * w.powf(-3.5),
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
                    -u * (9.0 + 6.0 * u * u) * w.powf(-3.5),
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
                    24.0 * u * (1.0 - u * u) / (w * w * w * w),
                ]
            },
            ANY,
        ),
        (
            "sinh",
            |u| [u.sinh(), u.cosh(), u.sinh(), u.cosh(), u.sinh()],
            ANY,
        ),
        (
            "cosh",
            |u| [u.cosh(), u.sinh(), u.cosh(), u.sinh(), u.cosh()],
            ANY,
        ),
        (
            "tanh",
            |u| {
                let (t, s2) = (u.tanh(), 1.0 / (u.cosh() * u.cosh()));
                [
                    t,
                    s2,
                    -2.0 * s2 * t,
                    4.0 * s2 * t * t - 2.0 * s2 * s2,
                    16.0 * s2 * s2 * t - 8.0 * s2 * t * t * t,
                ]
            },
            ANY,
        ),
        ("exp", |u| [u.exp(); 5], ANY),
        (
            "log",
            |u| {
                [
                    u.ln(),
                    1.0 / u,
                    -1.0 / (u * u),
                    2.0 / (u * u * u),
                    -6.0 / (u * u * u * u),
                ]
            },
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
                    -0.9375 * u.powf(-3.5),
                ]
            },
            POS,
        ),
        (
            "abs",
            |u| [u.abs(), u.signum(), 0.0, 0.0, 0.0],
            &[-2.0, -0.3, 0.4, 2.0],
        ),
        (
            "sign",
            |u| [u.signum(), 0.0, 0.0, 0.0, 0.0],
            &[-2.0, -0.3, 0.4, 2.0],
        ),
        (
            "floor",
            |u| [u.floor(), 0.0, 0.0, 0.0, 0.0],
            &[-1.5, -0.3, 0.4, 2.5],
        ),
        ("deg", |u| [u * PI / 180.0, PI / 180.0, 0.0, 0.0, 0.0], ANY),
    ]
}

fn assert_jet4(e: &Expr, x: f64, want: [f64; 5], tol: f64) {
    let j = e.jet4(x);
    for k in 0..5 {
        assert_close(
            j[k],
            want[k],
            tol,
            &format!("`{}` order {k} at {x}", e.source()),
        );
    }
}

/// The fourth derivative against a Richardson difference of the third, and
/// the first four entries against the third-order jet.
fn assert_jet4_matches(e: &Expr, x: f64, h: f64, tol: f64) {
    let (j4, j3) = (e.jet4(x), e.jet(x));
    for k in 0..4 {
        assert_close(j4[k], j3[k], 1e-13, &format!("`{}` order {k}", e.source()));
    }
    let fd = richardson(|s| e.jet4(s)[3], x, h);
    assert_close(j4[4], fd, tol, &format!("`{}` order 4 at {x}", e.source()));
}

/// g(a t + b) has the jet [g, a g', a² g'', a³ g''', a⁴ g''''].
#[test]
fn every_unary_function_against_its_fourth_order_closed_form() {
    let (a, b) = (0.7, 0.1);
    for (name, g, points) in closed_forms() {
        let e = expr(&format!("{name}(0.7*t + 0.1)"));
        for &u in points {
            let t = (u - b) / a;
            let gu = g(a * t + b);
            let want = std::array::from_fn(|k| a.powi(k as i32) * gu[k]);
            assert_jet4(&e, t, want, 1e-12);
        }
    }
}

/// A nonlinear inner function exercises every term of the fourth-order
/// Faà di Bruno formula.
#[test]
fn every_unary_function_of_a_nonlinear_argument_against_differences() {
    let u = "0.5 + 0.3*sin(t) + 0.1*t^2";
    for (name, _, _) in closed_forms() {
        let e = expr(&format!("{name}({u})"));
        for &t in &[-0.9, -0.2, 0.3, 0.8] {
            assert_jet4_matches(&e, t, 1e-2, 1e-8);
        }
    }
}

#[test]
fn powers_and_arithmetic_against_differences() {
    for src in [
        "(0.7*t + 0.1)^2.5",
        "(0.7*t + 0.1)^3",
        "(0.7*t + 0.1)^-2",
        "(t^2 + 1) * sin(t)",
        "exp(t) / (2 + cos(3*t))",
        "3 / (1 + t^2)",
        "1 - t/(2 + t^2)",
        "(1 + t)^(2 + sin(t))",
        "t^t",
        "atan2(sin(t), 0.3 + cos(t))",
        "hypot(t, 1 + t^2)",
        "mod(t^2, 0.7)",
    ] {
        let e = expr(src);
        for &t in &[0.4, 1.1, 1.9] {
            assert_jet4_matches(&e, t, 1e-2, 1e-8);
        }
    }
}

#[test]
fn powers_against_closed_forms() {
    for c in [2.5, 3.0, -2.0, 0.5, 4.0] {
        let e = expr(&format!("(0.7*t + 0.1)^{c}"));
        for &t in &[0.3, 1.0, 2.2] {
            let u: f64 = 0.7 * t + 0.1;
            let mut want = [0.0; 5];
            let mut f = 1.0;
            for (k, w) in want.iter_mut().enumerate() {
                *w = f * 0.7f64.powi(k as i32) * u.powf(c - k as f64);
                f *= c - k as f64;
            }
            assert_jet4(&e, t, want, 1e-12);
        }
    }
    // Integer powers at zero: no 0·∞.
    assert_eq!(expr("t^4").jet4(0.0), [0.0, 0.0, 0.0, 0.0, 24.0]);
    assert_eq!(expr("t^2").jet4(0.0), [0.0, 0.0, 2.0, 0.0, 0.0]);
}

/// sin(t²): f'''' = (16t⁴ − 12) sin t² − 48t² cos t², by hand.
#[test]
fn sin_of_a_square_in_closed_form() {
    let e = expr("sin(t^2)");
    for &t in &[-0.8f64, 0.0, 0.45, 1.3] {
        let (s, c) = (t * t).sin_cos();
        let want4 = (16.0 * t.powi(4) - 12.0) * s - 48.0 * t * t * c;
        assert_close(e.jet4(t)[4], want4, 1e-12, "sin(t^2) order 4");
    }
}

/// Every motion law's fourth derivative against a difference of its third,
/// inside the transition; a cycloidal rise in closed form.
#[test]
fn motion_laws_to_fourth_order() {
    for law in [
        Law::Ramp,
        Law::Step,
        Law::Poly345,
        Law::Harmonic,
        Law::Cycloidal,
    ] {
        for &u in &[0.1, 0.35, 0.5, 0.77, 0.9] {
            let s = law.shape4(u);
            let fd = richardson(|v| law.shape4(v)[3], u, 1e-3);
            assert_close(s[4], fd, 1e-9, &format!("{law:?} at {u}"));
            assert_eq!(&s[..4], &law.shape(u)[..]);
        }
    }
    // cycloidal(t, 0, 0, 2, 0.5): s = h(u − sin 2πu/2π), u = t/2.
    let e = expr("cycloidal(t, 0, 0, 2, 0.5)");
    for &t in &[0.3, 0.9, 1.6] {
        let u = t / 2.0;
        let want4 = 0.5 * -8.0 * PI.powi(3) * (2.0 * PI * u).sin() / 16.0;
        assert_close(e.jet4(t)[4], want4, 1e-12, "cycloidal order 4");
        assert_jet4_matches(&e, t, 1e-2, 1e-8);
    }
}

/// The seed's cam profile on both branches of its `if`.
#[test]
fn seed_cam_profile_to_fourth_order() {
    let e = Expr::parse("if(a <= 2*pi/3, 5/4 - cos(3*a)/4, 1)", "a").unwrap();
    let j = e.jet4(0.5);
    assert_close(j[4], -81.0 / 4.0 * 1.5f64.cos(), 1e-13, "lobe");
    assert_eq!(e.jet4(3.0), [1.0, 0.0, 0.0, 0.0, 0.0]);
}
