//! Three precision points at prescribed crank rotations in closed form,
//! and Ball's point: the models, run by camlink's kinematics, pass the
//! points (1e-9 m) and put the coupler point on a path with zero curvature
//! and zero rate of curvature; Ball's point is checked against finite
//! differences of the coupler curve traced in closed form.

use camlink_core::kinematics;
use camlink_core::run::{PointOutput, Settings, Table};
use camlink_model::{load_str, Format};
use camlink_synth::ball::instant;
use camlink_synth::fourbar::{wrap_pi, FourBar, P2};
use camlink_synth::path::CouplerLinkage;
use camlink_synth::precision::{three_points, ThreePoints};
use camlink_synth::{solve_path, solve_str, Solution};

use crate::burmester::examples;
use crate::path_generation::{assert_reaches_targets, defects, known};
use crate::slider_crank::Rng;

fn fmt(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:?}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The problem file of three points with the crank's, the coupler's and
/// the rocker's rotations from point 1.
fn problem(points: &[P2; 3], beta: [f64; 2], alpha: [f64; 2], gamma: [f64; 2]) -> String {
    format!(
        "[synthesis]\ntype = \"path\"\nmethod = \"precision_points\"\ntargets = [{}]\n\
         crank_rotations = [{}]\ncoupler_rotations = [{}]\nrocker_rotations = [{}]\n",
        points
            .iter()
            .map(|p| format!("[{:?}, {:?}]", p[0], p[1]))
            .collect::<Vec<_>>()
            .join(", "),
        fmt(&beta),
        fmt(&alpha),
        fmt(&gamma)
    )
}

/// The coupler's angle (A→B) and the rocker's (O₄→B) of `m` at crank angle `phi`.
fn angles(m: &CouplerLinkage, phi: f64) -> (f64, f64) {
    let (a, b, _) = m.trace(phi).unwrap();
    let o4 = m.linkage.o4;
    (
        (b[1] - a[1]).atan2(b[0] - a[0]),
        (b[1] - o4[1]).atan2(b[0] - o4[0]),
    )
}

/// Three points of a known four-bar's coupler curve, with its own
/// coupler and rocker rotations as the free choices: the closed form gives
/// that four-bar back (1e-12 m), and its model passes the points at the
/// prescribed crank angles (1e-9 m).
#[test]
fn issue31_precision_closed_form_recovers_a_known_four_bar() {
    let m = known();
    let (phi1, beta) = (0.4, [0.7, 1.5]);
    let phis = [phi1, phi1 + beta[0], phi1 + beta[1]];
    let points = phis.map(|f| m.trace(f).unwrap().2);
    let (t1, r1) = angles(&m, phis[0]);
    let alpha = [1, 2].map(|j| wrap_pi(angles(&m, phis[j]).0 - t1));
    let gamma = [1, 2].map(|j| wrap_pi(angles(&m, phis[j]).1 - r1));
    let spec = ThreePoints {
        points,
        crank: beta,
        coupler: alpha,
        rocker: gamma,
    };
    let (got, crank_angles) = three_points(&spec, ["t", "b", "a", "g"]).unwrap();
    let (l, k) = (got.linkage, m.linkage);
    for (x, y) in [
        (l.o2[0], k.o2[0]),
        (l.o2[1], k.o2[1]),
        (l.o4[0], k.o4[0]),
        (l.o4[1], k.o4[1]),
        (l.crank, k.crank),
        (l.coupler, k.coupler),
        (l.rocker, k.rocker),
        (got.point[0], m.point[0]),
        (got.point[1], m.point[1]),
    ] {
        assert!((x - y).abs() < 1e-12, "{got:?} is not {m:?}");
    }
    for (f, g) in crank_angles.iter().zip(phis) {
        assert!(wrap_pi(f - g).abs() < 1e-12);
    }
    let out = solve_str(&problem(&points, beta, alpha, gamma), "cf.toml", "cf").unwrap();
    let s = &out.solutions[0];
    assert_eq!(s.report["method"], "precision_points_closed_form");
    assert_eq!(defects(s), 0, "{}", s.report["checks"]);
    assert!(s.report["error"]["max"].as_f64().unwrap() < 1e-12);
    assert_reaches_targets(s, 1e-9);
}

/// Varied points and free choices (both senses of the crank): every
/// solution without defects runs through its points to 1e-9 m, and the
/// coupler and the rocker turn by the chosen rotations between them.
#[test]
fn issue31_precision_closed_form_varied_free_choices() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut passed = 0;
    for _ in 0..60 {
        let points = [
            [0.0, 0.0],
            [rng.range(0.05, 0.2), rng.range(-0.05, 0.1)],
            [rng.range(0.1, 0.3), rng.range(-0.1, 0.05)],
        ];
        let s = if rng.range(0.0, 1.0) < 0.5 { 1.0 } else { -1.0 };
        let b2 = s * rng.range(0.3, 1.2);
        let beta = [b2, b2 + s * rng.range(0.3, 1.2)];
        let alpha = [rng.range(-0.6, 0.6), rng.range(-0.8, 0.8)];
        let gamma = [s * rng.range(0.1, 0.8), s * rng.range(0.3, 1.4)];
        let text = problem(&points, beta, alpha, gamma);
        let Ok(out) = solve_str(&text, "cf.toml", "cf") else {
            continue;
        };
        let sol = &out.solutions[0];
        // Off the points only with a branch defect: the exact solution
        // reaches some point on the other assembly branch.
        let off = sol.report["error"]["max"].as_f64().unwrap() >= 1e-12;
        let branch = sol.report["checks"]["defects"]
            .as_array()
            .unwrap()
            .iter()
            .any(|d| d["kind"] == "branch");
        assert!(!off || branch, "{text}");
        if defects(sol) > 0 {
            continue;
        }
        assert_reaches_targets(sol, 1e-9);
        // The coupler's and the rocker's rotations are the ones chosen.
        let l = &sol.report["links"];
        let o4 = [l["O4"][0].as_f64().unwrap(), l["O4"][1].as_f64().unwrap()];
        let c = sol.report["crank_angles"].as_array().unwrap();
        let m = mechanism(sol);
        let at: Vec<(P2, P2)> = c
            .iter()
            .map(|f| {
                let (a, b, _) = m.trace(f.as_f64().unwrap()).unwrap();
                (a, b)
            })
            .collect();
        let ang = |p: P2, q: P2| (q[1] - p[1]).atan2(q[0] - p[0]);
        for j in 1..3 {
            let da = wrap_pi(ang(at[j].0, at[j].1) - ang(at[0].0, at[0].1) - alpha[j - 1]);
            let dg = wrap_pi(ang(o4, at[j].1) - ang(o4, at[0].1) - gamma[j - 1]);
            assert!(da.abs() < 1e-9 && dg.abs() < 1e-9, "{text}: {da:e} {dg:e}");
        }
        passed += 1;
    }
    assert!(passed >= 5, "{passed} defect-free solutions");
}

/// The mechanism of a path solution's report.
fn mechanism(s: &Solution) -> CouplerLinkage {
    let r = &s.report;
    let f = |v: &serde_json::Value| v.as_f64().unwrap();
    CouplerLinkage {
        linkage: FourBar {
            o2: [f(&r["links"]["O2"][0]), f(&r["links"]["O2"][1])],
            o4: [f(&r["links"]["O4"][0]), f(&r["links"]["O4"][1])],
            crank: f(&r["signed"]["crank"]),
            coupler: f(&r["links"]["coupler"]),
            rocker: f(&r["signed"]["rocker"]),
        },
        point: [f(&r["coupler_point"][0]), f(&r["coupler_point"][1])],
        sigma: f(&r["branch"]),
    }
}

#[test]
fn issue31_precision_closed_form_bad_choices_named() {
    let m = known();
    let points = [0.4, 1.1, 1.9].map(|f| m.trace(f).unwrap().2);
    let beta = [0.7, 1.5];
    let err = |text: &str| match solve_str(text, "cf.toml", "cf") {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    };
    // The coupler turning with the crank: the crank side is singular.
    let e = err(&problem(&points, beta, beta, [0.2, 0.5]));
    assert!(
        e.contains("synthesis.coupler_rotations") && e.contains("singular"),
        "{e}"
    );
    // The rocker turning as the crank does: one dyad twice.
    let e = err(&problem(&points, beta, [0.1, 0.3], beta));
    assert!(
        e.contains("synthesis.rocker_rotations") && e.contains("the crank's"),
        "{e}"
    );
    // Only one of the two free choices.
    let text = problem(&points, beta, [0.1, 0.3], [0.2, 0.5]);
    let e = err(&text.replace("rocker_rotations = [0.2, 0.5]\n", ""));
    assert!(e.contains("synthesis.rocker_rotations: missing"), "{e}");
    // Four points: the closed form is for three.
    let e = err(
        "[synthesis]\ntype = \"path\"\nmethod = \"precision_points\"\n\
         targets = [[0, 0], [0.1, 0.02], [0.2, 0.0], [0.3, -0.05]]\n\
         crank_rotations = [0.5, 1.0, 1.5]\ncoupler_rotations = [0.1, 0.2]\n\
         rocker_rotations = [0.2, 0.4]\n",
    );
    assert!(
        e.contains("synthesis.coupler_rotations") && e.contains("4 points"),
        "{e}"
    );
}

/// A crank-rocker whose coupler point is at Ball's point at crank angle
/// φ₀ (the four-bar of examples/four_bar.toml).
fn ball_problem(phi0: f64) -> String {
    format!(
        "[synthesis]\ntype = \"ball_point\"\nfour_bar = {{ O2 = [0, 0], O4 = [0.4, 0], crank = 0.12, \
         coupler = 0.38, rocker = 0.3, branch = 1, crank_angle = {phi0:?} }}\n"
    )
}

/// The coupler point `p` (coupler frame) of the example linkage at crank
/// angle `phi`, traced in closed form.
fn traced(p: P2, phi: f64) -> P2 {
    let m = CouplerLinkage {
        point: p,
        ..known()
    };
    m.trace(phi).unwrap().2
}

/// Curvature κ of the curve through P(φ + k h), k = −3 … 3, at k = 0
/// (h = 2e-3 rad), and its derivative dκ/dφ from κ at φ₀ ± g, φ₀ ± 2g
/// (g = 5e-3 rad), by central differences (sixth- and fourth-order
/// accurate).
fn curvature_fd(p: P2, phi0: f64) -> (f64, f64) {
    let (h, g) = (2e-3, 5e-3);
    let kappa = |phi: f64| {
        let x: Vec<P2> = (-3..=3).map(|k| traced(p, phi + k as f64 * h)).collect();
        let d1 = |c: usize| {
            (-x[0][c] + 9.0 * x[1][c] - 45.0 * x[2][c] + 45.0 * x[4][c] - 9.0 * x[5][c] + x[6][c])
                / (60.0 * h)
        };
        let d2 = |c: usize| {
            (2.0 * x[0][c] - 27.0 * x[1][c] + 270.0 * x[2][c] - 490.0 * x[3][c] + 270.0 * x[4][c]
                - 27.0 * x[5][c]
                + 2.0 * x[6][c])
                / (180.0 * h * h)
        };
        let (v, a) = ([d1(0), d1(1)], [d2(0), d2(1)]);
        (v[0] * a[1] - v[1] * a[0]) / v[0].hypot(v[1]).powi(3)
    };
    let dk = (kappa(phi0 - 2.0 * g) - 8.0 * kappa(phi0 - g) + 8.0 * kappa(phi0 + g)
        - kappa(phi0 + 2.0 * g))
        / (12.0 * g);
    (kappa(phi0), dk)
}

/// Ball's point against finite differences of the coupler curve (traced
/// in closed form, independent of the derivatives of crate::ball): its
/// path's curvature and rate of curvature vanish (to the differences'
/// accuracy), while a point 10 mm away has both clearly non-zero; its
/// path leaves the tangent as the fourth power of the crank rotation.
#[test]
fn issue31_ball_point_has_zero_curvature_and_rate() {
    for phi0 in [0.3, 1.0, 2.0, 4.0] {
        let g = instant(&known().linkage, phi0, 1.0).unwrap();
        let p = g.ball_local.unwrap();
        let (k, dk) = curvature_fd(p, phi0);
        // κ in 1/m; the coupler is 0.38 m.
        assert!(k.abs() * 0.38 < 1e-7, "φ₀ {phi0}: κ = {k:e}");
        assert!(dk.abs() * 0.38 < 1e-5, "φ₀ {phi0}: dκ/dφ = {dk:e}");
        let (k2, dk2) = curvature_fd([p[0] + 0.01, p[1]], phi0);
        assert!(k2.abs() * 0.38 > 1e-3 || dk2.abs() * 0.38 > 1e-3);
        // The distance from the tangent at φ₀: about h⁴ (16 times less at
        // half the step), where a point of the inflection circle alone
        // leaves it as h³.
        let p0 = traced(p, phi0);
        let (d1, _) = (
            [
                traced(p, phi0 + 1e-6)[0] - traced(p, phi0 - 1e-6)[0],
                traced(p, phi0 + 1e-6)[1] - traced(p, phi0 - 1e-6)[1],
            ],
            (),
        );
        let tn = d1[0].hypot(d1[1]);
        let off = |h: f64| {
            let q = traced(p, phi0 + h);
            ((q[0] - p0[0]) * d1[1] - (q[1] - p0[1]) * d1[0]).abs() / tn
        };
        let ratio = off(0.02) / off(0.01);
        assert!((ratio - 16.0).abs() < 1.6, "φ₀ {phi0}: ratio {ratio}");
        // The pole, the instant centre on lines O₂A and O₄B; it and Ball's
        // point on the inflection circle.
        let l = known().linkage;
        let on = |p: P2, q: P2, x: P2| {
            let d = [q[0] - p[0], q[1] - p[1]];
            (d[0] * (x[1] - p[1]) - d[1] * (x[0] - p[0])) / d[0].hypot(d[1])
        };
        assert!(on(l.o2, g.a, g.pole).abs() < 1e-12 && on(l.o4, g.b, g.pole).abs() < 1e-12);
        let (c, r) = g.inflection.unwrap();
        let ball = g.ball.unwrap();
        assert!(((ball[0] - c[0]).hypot(ball[1] - c[1]) - r).abs() < 1e-12 * r.max(1.0));
        assert!(((g.pole[0] - c[0]).hypot(g.pole[1] - c[1]) - r).abs() < 1e-12 * r.max(1.0));
    }
}

/// The ball_point problem's model, run by camlink's kinematics with the
/// jerk: at t = 0 the coupler point's velocity is parallel to its
/// acceleration and to its jerk (zero curvature and zero rate of
/// curvature), to 1e-9 relative, and it is at the reported Ball's point.
#[test]
fn issue31_ball_point_model_runs_straight_there() {
    for phi0 in [0.3, 2.0] {
        let out = solve_str(&ball_problem(phi0), "ball.toml", "ball").unwrap();
        assert_eq!(out.kind, "ball_point");
        let s = &out.solutions[0];
        let loaded = load_str(&s.model, Format::Toml, "ball.toml").unwrap();
        let body = loaded.model.body_id("coupler").unwrap();
        let points = [PointOutput {
            body,
            name: "coupler.P".into(),
            s: loaded.model.body(body).point("P").unwrap(),
        }];
        let settings = Settings {
            tol: 1e-12,
            max_iter: 25,
            jerk: true,
        };
        let mut table = Table::default();
        kinematics::run(&loaded.model, &[0.0, 0.5], &settings, &points, &mut table).unwrap();
        let c = |n: &str| table.channel(&format!("coupler.P.{n}")).unwrap()[0];
        let (v, a, j) = ([c("vx"), c("vy")], [c("ax"), c("ay")], [c("jx"), c("jy")]);
        let cross = |p: [f64; 2], q: [f64; 2]| p[0] * q[1] - p[1] * q[0];
        let size = |p: [f64; 2]| p[0].hypot(p[1]);
        // ω = 2π rad/s: scales of |a| and |j| for a point 0.38 m out.
        let w = std::f64::consts::TAU;
        assert!(
            cross(v, a).abs() < 1e-9 * size(v) * w * w * 0.38,
            "v × a = {:e}",
            cross(v, a)
        );
        assert!(
            cross(v, j).abs() < 1e-9 * size(v) * w * w * w * 0.38,
            "v × j = {:e}",
            cross(v, j)
        );
        let ball = &s.report["instant"]["ball"];
        assert!((c("x") - ball[0].as_f64().unwrap()).abs() < 1e-9);
        assert!((c("y") - ball[1].as_f64().unwrap()).abs() < 1e-9);
    }
}

#[test]
fn issue31_ball_point_bad_input_named() {
    let err = |text: &str| match solve_str(text, "ball.toml", "ball") {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    };
    let e = err(&ball_problem(0.3).replace("branch = 1", "branch = 1, point = [0.1, 0.1]"));
    assert!(
        e.contains("synthesis.four_bar.point") && e.contains("leave point out"),
        "{e}"
    );
    let e = err(&format!("{}keep = 2\n", ball_problem(0.3)));
    assert!(
        e.contains("synthesis.keep: not a field of a ball_point problem"),
        "{e}"
    );
    // A triple-rocker: its crank does not turn fully.
    let e = err(&ball_problem(0.3).replace("crank = 0.12", "crank = 0.35"));
    assert!(e.contains("does not turn fully"), "{e}");
}

#[test]
fn issue31_precision_closed_form_example_passes_its_points() {
    let out = solve_path(&examples().join("synthesis_precision_points.toml")).unwrap();
    let s = &out.solutions[0];
    assert_eq!(s.report["method"], "precision_points_closed_form");
    assert_eq!(defects(s), 0, "{}", s.report["checks"]);
    assert!(s.report["error"]["max"].as_f64().unwrap() < 1e-12);
    assert_reaches_targets(s, 1e-9);
}
