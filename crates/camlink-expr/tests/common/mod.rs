//! Helpers shared by the integration tests.

#![allow(dead_code)]

use camlink_expr::Expr;

/// Parses `src` in the variable `t`, panicking with the rendered error.
pub fn expr(src: &str) -> Expr {
    Expr::parse(src, "t").unwrap_or_else(|e| panic!("{}", e.render(src)))
}

/// g'(x) by central differences with two Richardson extrapolations:
/// D(h) = (g(x+h) − g(x−h))/2h is O(h²); R₁ = (4D(h/2) − D(h))/3 is O(h⁴);
/// R₂ = (16R₁(h/2) − R₁(h))/15 is O(h⁶).
pub fn richardson(g: impl Fn(f64) -> f64, x: f64, h: f64) -> f64 {
    let d = |h: f64| (g(x + h) - g(x - h)) / (2.0 * h);
    let (d1, d2, d4) = (d(h), d(h / 2.0), d(h / 4.0));
    let r1 = (4.0 * d2 - d1) / 3.0;
    let r2 = (4.0 * d4 - d2) / 3.0;
    (16.0 * r2 - r1) / 15.0
}

/// Asserts |a − b| ≤ tol·(1 + |b|).
pub fn assert_close(a: f64, b: f64, tol: f64, what: &str) {
    assert!(
        (a - b).abs() <= tol * (1.0 + b.abs()),
        "{what}: {a} vs {b} (difference {:e})",
        (a - b).abs()
    );
}

/// Each derivative of `e`'s jet at x against a Richardson difference of the
/// order below it: f' from f, f'' from f', f''' from f''.
pub fn assert_jet_matches_differences(e: &Expr, x: f64, h: f64, tol: f64) {
    let j = e.jet(x);
    for k in 0..3 {
        let fd = richardson(|s| e.jet(s)[k], x, h);
        assert_close(
            j[k + 1],
            fd,
            tol,
            &format!("`{}` order {} at {x}", e.source(), k + 1),
        );
    }
}

/// Asserts the jet equals `want` to a relative tolerance.
pub fn assert_jet(e: &Expr, x: f64, want: [f64; 4], tol: f64) {
    let j = e.jet(x);
    for k in 0..4 {
        assert_close(
            j[k],
            want[k],
            tol,
            &format!("`{}` order {k} at {x}", e.source()),
        );
    }
}
