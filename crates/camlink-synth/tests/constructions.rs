//! Function generation and Burmester curves against classical graphical
//! constructions, computed here independently of the crate's equations:
//!
//! - Freudenstein's three-point solution against the inversion
//!   construction (the rocker held still, the crank pin's positions
//!   rotated back about O₄: the rocker pin B₁ is the centre of the circle
//!   through them);
//! - the centre-point curve of four poses against Burmester's
//!   opposite-pole quadrilateral: from every centre point M the opposite
//!   sides P₁₂P₂₃ and P₁₄P₃₄ of the quadrilateral P₁₂P₂₃P₃₄P₁₄ are seen
//!   under equal angles (mod π).
//!
//! No worked textbook example with published numbers could be checked
//! here (the books were not at hand, and numbers recalled from memory are
//! not evidence); these constructions stand in for one.

use camlink_synth::burmester::Equations;
use camlink_synth::fourbar::P2;
use camlink_synth::motion::Pose;
use camlink_synth::{solve_path, solve_str};
use serde_json::Value;

use crate::burmester::{assert_line_roots_on_curve, examples, known_poses};
use crate::slider_crank::Rng;

fn dist(p: P2, q: P2) -> f64 {
    (p[0] - q[0]).hypot(p[1] - q[1])
}

/// The centre of the circle through three points.
fn circumcentre(a: P2, b: P2, c: P2) -> P2 {
    let d = 2.0 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]));
    let s = |p: P2| p[0] * p[0] + p[1] * p[1];
    [
        (s(a) * (b[1] - c[1]) + s(b) * (c[1] - a[1]) + s(c) * (a[1] - b[1])) / d,
        (s(a) * (c[0] - b[0]) + s(b) * (a[0] - c[0]) + s(c) * (b[0] - a[0])) / d,
    ]
}

fn rotate_about(o: P2, p: P2, t: f64) -> P2 {
    let (s, c) = t.sin_cos();
    let d = [p[0] - o[0], p[1] - o[1]];
    [o[0] + c * d[0] - s * d[1], o[1] + s * d[0] + c * d[1]]
}

/// The inversion construction of a three-point function generator's
/// report: with O₂ = (0, 0), O₄ = (d, 0) and the crank a (signed) of the
/// solution, the crank pins A_j = a·u(φ_j) rotated about O₄ by −(ψ_j − ψ₁)
/// lie on the circle about the solution's rocker pin B₁ with the coupler's
/// radius (1e-12 relative), and, when they make a triangle (area at least
/// 1e-3 of the scale squared), its circumcentre is B₁ (1e-9 relative).
/// Returns whether they made one.
fn assert_inversion_agrees(r: &Value) -> bool {
    let f = |v: &Value| v.as_f64().unwrap();
    let d = f(&r["links"]["ground"]);
    let a = f(&r["signed"]["crank"]);
    let pairs: Vec<(f64, f64)> = r["angles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (f(&p[0]), f(&p[1])))
        .collect();
    assert_eq!(pairs.len(), 3);
    let o4 = [d, 0.0];
    let inverted: Vec<P2> = pairs
        .iter()
        .map(|&(phi, psi)| {
            let pin = [a * phi.cos(), a * phi.sin()];
            rotate_about(o4, pin, -(psi - pairs[0].1))
        })
        .collect();
    let scale = d.max(a.abs());
    let rocker = f(&r["signed"]["rocker"]);
    let coupler = f(&r["links"]["coupler"]);
    // The synthesised B₁ = O₄ + c·u(ψ₁) is at the coupler's length from
    // every inverted crank pin.
    let psi1 = pairs[0].1;
    let b1 = [d + rocker * psi1.cos(), rocker * psi1.sin()];
    for (j, p) in inverted.iter().enumerate() {
        assert!(
            (dist(b1, *p) - coupler).abs() < 1e-12 * scale,
            "inverted pin {} is {} from B₁; the coupler is {coupler}",
            j + 1,
            dist(b1, *p)
        );
    }
    // Three distinct inverted pins fix B₁ as their circumcentre; two that
    // coincide (the crank pin back where it was relative to the rocker)
    // leave it on a line, and the construction says no more.
    let [p, q, w] = [inverted[0], inverted[1], inverted[2]];
    let area = ((q[0] - p[0]) * (w[1] - p[1]) - (q[1] - p[1]) * (w[0] - p[0])).abs();
    if area < 1e-3 * scale * scale {
        return false;
    }
    // The circumcentre's error grows as scale²/area (at most 1e3 here).
    let centre = circumcentre(p, q, w);
    assert!(
        dist(centre, b1) < 1e-9 * scale,
        "B₁ {centre:?} by inversion, {b1:?} synthesised"
    );
    assert!((dist(centre, o4) - rocker.abs()).abs() < 1e-9 * scale);
    true
}

/// Freudenstein's three-point solutions (the example, and varied
/// functions, ranges and precision points) agree with the inversion
/// construction.
#[test]
fn issue31_freudenstein_agrees_with_the_inversion_construction() {
    let out = solve_path(&examples().join("synthesis_function.toml")).unwrap();
    assert_eq!(out.solutions[0].report["method"], "three_point");
    // The example's first and third inverted pins coincide (its crank
    // angles are symmetric about the ground line).
    assert!(!assert_inversion_agrees(&out.solutions[0].report));
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let mut checked = 0;
    for k in 0..80 {
        let function = ["log(x)", "x^2", "sin(x)", "exp(x/2)", "1/x"][k % 5];
        let x0 = rng.range(0.5, 1.0);
        let x1 = x0 + rng.range(0.5, 1.5);
        let phi0 = rng.range(-1.0, 1.0);
        let psi0 = rng.range(0.5, 2.5);
        let text = format!(
            "[synthesis]\ntype = \"function\"\nfunction = \"{function}\"\nx = [{x0:?}, {x1:?}]\n\
             input = [{phi0:?}, {:?}]\noutput = [{psi0:?}, {:?}]\nground = {:?}\n",
            phi0 + rng.range(0.6, 2.0),
            psi0 + rng.range(-1.2, 1.2),
            rng.range(0.05, 0.5),
        );
        if let Ok(out) = solve_str(&text, "f.toml", "f") {
            if assert_inversion_agrees(&out.solutions[0].report) {
                checked += 1;
            }
        }
    }
    assert!(checked >= 30, "{checked} problems checked");
}

/// The pole P_ij of poses i and j: the point with the same coordinates in
/// the coupler frame at both.
pub(crate) fn pole(p: &Pose, q: &Pose) -> P2 {
    let m = |p: &Pose| {
        let (s, c) = p.theta.sin_cos();
        [[c, s], [-s, c]]
    };
    let (mi, mj) = (m(p), m(q));
    let a = [
        [mi[0][0] - mj[0][0], mi[0][1] - mj[0][1]],
        [mi[1][0] - mj[1][0], mi[1][1] - mj[1][1]],
    ];
    let ri = [
        mi[0][0] * p.x + mi[0][1] * p.y,
        mi[1][0] * p.x + mi[1][1] * p.y,
    ];
    let rj = [
        mj[0][0] * q.x + mj[0][1] * q.y,
        mj[1][0] * q.x + mj[1][1] * q.y,
    ];
    let b = [ri[0] - rj[0], ri[1] - rj[1]];
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    [
        (b[0] * a[1][1] - b[1] * a[0][1]) / det,
        (a[0][0] * b[1] - a[1][0] * b[0]) / det,
    ]
}

/// The signed angle at `m` from `x` to `y` (rad).
fn seen(m: P2, x: P2, y: P2) -> f64 {
    let (u, v) = ([x[0] - m[0], x[1] - m[1]], [y[0] - m[0], y[1] - m[1]]);
    (u[0] * v[1] - u[1] * v[0]).atan2(u[0] * v[0] + u[1] * v[1])
}

/// sin(∠P₁₂MP₂₃ − ∠P₁₄MP₃₄): zero where M sees the opposite sides under
/// equal angles mod π.
fn opposite_sides(poles: &[P2; 4], m: P2) -> f64 {
    let [p12, p23, p34, p14] = *poles;
    (seen(m, p12, p23) - seen(m, p14, p34)).sin()
}

/// Every sampled centre point of the Burmester curve sees the opposite
/// sides of the opposite-pole quadrilateral under equal angles (1e-9),
/// and on horizontal lines every point that does (a sign change of the
/// construction's function) is on the curve, with its circle point from
/// the three-position inversion (1e-8 m).
#[test]
fn issue31_burmester_curve_agrees_with_the_opposite_pole_quadrilateral() {
    let (poses, _, _) = known_poses(&[20.0, 60.0, 100.0, 140.0]);
    let eq = Equations::new(&poses, "poses").unwrap();
    let poles = [
        pole(&poses[0], &poses[1]),
        pole(&poses[1], &poses[2]),
        pole(&poses[2], &poses[3]),
        pole(&poses[0], &poses[3]),
    ];
    let near_pole = |m: P2| poles.iter().any(|p| dist(*p, m) < 1e-3);
    let mut n = 0;
    for line in eq.curves(360) {
        for d in line {
            if near_pole(d.centre) || dist(d.centre, [0.0, 0.0]) > 50.0 {
                continue;
            }
            let g = opposite_sides(&poles, d.centre);
            assert!(g.abs() < 1e-9, "{:?}: {g:e}", d.centre);
            n += 1;
        }
    }
    assert!(n > 500, "{n} centre points");
    // A root next to a pole, or where the angles jump, is not a root of
    // the construction.
    let roots = assert_line_roots_on_curve(
        &poses,
        &eq,
        &|m| opposite_sides(&poles, m),
        &|m, f_lo, f_hi| near_pole(m) || f_lo.abs() > 1e-6 || f_hi.abs() > 1e-6,
    );
    assert!(roots >= 9, "{roots} roots");
}
