//! The cam and slot examples (`examples/cam_*.toml`, `examples/slot_*.toml`)
//! load, run, and agree with an independent answer: a closed form, the same
//! mechanism built from other joints, or a brute-force contact computed by
//! dense sampling and refinement, without the contact joints' equations.

use std::f64::consts::{PI, TAU};
use std::path::{Path, PathBuf};

use camlink_core::constraint::Constraint;
use camlink_core::design::{self, Severity};
use camlink_core::kinematics;
use camlink_core::run::{AnalysisError, Kind, PointOutput, Settings, Table};
use camlink_model::{load_path, load_str, Format, Loaded};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn load(name: &str) -> Loaded {
    load_path(&examples().join(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// The example's text with `from` replaced by `to` (which must occur once).
fn variant(name: &str, from: &str, to: &str) -> Loaded {
    let text = std::fs::read_to_string(examples().join(name)).unwrap();
    assert_eq!(text.matches(from).count(), 1, "{from:?} in {name}");
    let source = examples().join(name).display().to_string();
    load_str(&text.replace(from, to), Format::Toml, &source).unwrap_or_else(|e| panic!("{e}"))
}

/// Runs the `[analysis]` of a loaded model.
fn try_run(l: &Loaded) -> (Table, Result<camlink_core::run::Summary, AnalysisError>) {
    let a = &l.analysis;
    let times = match &a.times {
        Some(t) => t.clone(),
        None => camlink_core::run::time_grid(a.t_end.unwrap(), a.step.unwrap()).unwrap(),
    };
    let points: Vec<PointOutput> = a
        .points
        .iter()
        .map(|p| {
            let (b, pt) = p.split_once('.').unwrap();
            let body = l.model.body_id(b).unwrap();
            PointOutput {
                body,
                name: p.clone(),
                s: l.model.body(body).point(pt).unwrap(),
            }
        })
        .collect();
    let settings = Settings {
        tol: a.tol,
        max_iter: a.max_iter,
        ..Settings::default()
    };
    let mut table = Table::default();
    let r = kinematics::run(&l.model, &times, &settings, &points, &mut table);
    (table, r)
}

fn run(l: &Loaded) -> Table {
    let (table, r) = try_run(l);
    r.unwrap_or_else(|e| panic!("{e}"));
    table
}

fn ch(t: &Table, name: &str) -> Vec<f64> {
    t.channel(name)
        .unwrap_or_else(|| panic!("no channel {name} in {:?}", t.channels))
}

/// Largest |a − b| over a series, printed for the record.
fn worst(what: &str, a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let w = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    eprintln!("{what}: worst error {w:.3e}");
    w
}

/// Angle difference folded into (−π, π].
fn wrap(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if w > PI {
        w - TAU
    } else {
        w
    }
}

/// The maximum of f on [lo, hi): the best of `n` samples refined by golden
/// section on its neighbourhood. Returns (argmax, max).
fn argmax(f: impl Fn(f64) -> f64, lo: f64, hi: f64, n: usize) -> (f64, f64) {
    let h = (hi - lo) / n as f64;
    let best = (0..n).map(|k| lo + k as f64 * h).map(|x| (x, f(x))).fold(
        (lo, f64::NEG_INFINITY),
        |a, b| if b.1 > a.1 { b } else { a },
    );
    let (mut a, mut b) = (best.0 - h, best.0 + h);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..120 {
        if fc > fd {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    let x = 0.5 * (a + b);
    (x, f(x).max(best.1))
}

/// A root of f in [a, b] by bisection; f(a) and f(b) must differ in sign.
fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let fa = f(a);
    assert!(fa * f(b) <= 0.0, "no sign change in [{a}, {b}]");
    for _ in 0..64 {
        let m = 0.5 * (a + b);
        if (f(m) > 0.0) == (fa > 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

fn rot(phi: f64, p: [f64; 2]) -> [f64; 2] {
    let (s, c) = phi.sin_cos();
    [c * p[0] - s * p[1], s * p[0] + c * p[1]]
}

/// The seed's Example 3.4.3 cam ρ₁(α).
fn rho_seed(a: f64) -> f64 {
    let a = a.rem_euclid(TAU);
    if a <= TAU / 3.0 {
        1.25 - (3.0 * a).cos() / 4.0
    } else {
        1.0
    }
}

#[test]
fn seed_example_3_4_3_roller_follower() {
    let l = load("cam_seed_example_3_4_3.toml");
    assert!(design::check(&l.model).is_empty());
    let t = run(&l);
    let r = 0.25;
    // Brute force: the roller centre C = (0, h) on the guide sits as low as
    // it can without entering the cam, h = max over cam points P with
    // |x_P| ≤ r of y_P + √(r² − x_P²); the maximiser is the contact point.
    let (mut h, mut cx, mut cy, mut pa, mut alpha) = (vec![], vec![], vec![], vec![], vec![]);
    for &time in &t.t {
        let phi = TAU * time;
        let cam = |a: f64| rot(phi, [rho_seed(a) * a.cos(), rho_seed(a) * a.sin()]);
        let g = |a: f64| {
            let p = cam(a);
            if p[0].abs() >= r {
                f64::NEG_INFINITY
            } else {
                p[1] + (r * r - p[0] * p[0]).sqrt()
            }
        };
        let (a, top) = argmax(g, 0.0, TAU, 4000);
        let p = cam(a);
        h.push(top);
        cx.push(p[0]);
        cy.push(p[1]);
        alpha.push(a);
        // Normal along C − P; the follower moves along y.
        pa.push(p[0].abs().atan2(top - p[1]));
    }
    let y = ch(&t, "follower.y");
    assert!(worst("seed 3.4.3 follower height", &y, &h) < 1e-9);
    assert!(worst("seed 3.4.3 contact x", &ch(&t, "contact.cx"), &cx) < 1e-7);
    assert!(worst("seed 3.4.3 contact y", &ch(&t, "contact.cy"), &cy) < 1e-7);
    let pressure = ch(&t, "contact.pressure_angle");
    assert!(worst("seed 3.4.3 pressure angle", &pressure, &pa) < 1e-6);
    let a: Vec<f64> = ch(&t, "contact.alpha_i")
        .iter()
        .zip(&alpha)
        .map(|(x, y)| y + wrap(x - y))
        .collect();
    assert!(worst("seed 3.4.3 alpha_i", &a, &alpha) < 1e-6);
    // The lobe lifts the roller by half a unit.
    let (lo, hi) = y
        .iter()
        .fold((f64::MAX, f64::MIN), |m, &v| (m.0.min(v), m.1.max(v)));
    assert!(
        (lo - 1.25).abs() < 1e-9 && hi <= 1.75 + 1e-9 && hi > 1.7499,
        "{lo} {hi}"
    );
}

#[test]
fn seed_example_with_a_too_large_roller_is_undercut() {
    // The lobe's flanks are concave with radius of curvature 0.8 at their
    // roots (κ = (ρ² + 2ρ′² − ρρ″)/(ρ² + ρ′²)^{3/2} = −1.25 at α = 0).
    let l = variant(
        "cam_seed_example_3_4_3.toml",
        "r_roller = 0.25",
        "r_roller = 0.85",
    );
    let f = design::check(&l.model);
    assert_eq!(f.len(), 1, "{f:?}");
    assert_eq!(f[0].severity, Severity::Warning);
    let text = f[0].to_string();
    assert!(
        text.contains("joint 'contact'") && text.contains("undercut"),
        "{text}"
    );
    assert!(
        text.contains("radius 0.85 m") && text.contains("0.8 m"),
        "{text}"
    );
}

#[test]
fn flat_follower_on_the_seed_cam_warns_then_stops_in_a_hollow() {
    let l = variant(
        "cam_seed_example_3_4_3.toml",
        "type = \"cam_follower\"\nname = \"contact\"\ncurve_i = \"lobe\"\ncurve_j = \"roller\"",
        "type = \"flat_follower\"\nname = \"contact\"\ncurve_i = \"lobe\"\nbody_j = \"follower\"\naxis = [1, 0]",
    );
    let f = design::check(&l.model);
    assert_eq!(f.len(), 1, "{f:?}");
    let text = f[0].to_string();
    assert!(
        text.contains("concave") && text.contains("α_i in"),
        "{text}"
    );
    assert!(text.contains('°'), "{text}");
    // The face rides on the lobe, then on the round part; where a convex
    // part meets a concave flank (an inflection) the contact equations
    // lose their solution (the real follower would jump), the run stops,
    // and the error names the concave ranges.
    let (table, r) = try_run(&l);
    let e = r.unwrap_err();
    assert!(e.joints == ["contact"], "{e:?}");
    // Newton stops at the edge; the design finding explains why.
    assert_eq!(e.kind, Kind::NotConverged, "{e:?}");
    assert!(
        e.to_string().contains("possible cause: joint 'contact'"),
        "{e}"
    );
    assert!(e.to_string().contains("concave for α_i in"), "{e}");
    assert!(e.time > 0.0 && table.t.len() > 1 && *table.t.last().unwrap() < e.time);
    eprintln!("flat follower on the seed cam: {e}");
}

#[test]
fn eccentric_cam_flat_follower_lift() {
    let l = load("cam_eccentric_flat.toml");
    assert!(design::check(&l.model).is_empty());
    let t = run(&l);
    let (r, e, w) = (0.04, 0.01, TAU * 10.0);
    let phi: Vec<f64> = t.t.iter().map(|&s| w * s).collect();
    let map = |f: &dyn Fn(f64) -> f64| phi.iter().map(|&p| f(p)).collect::<Vec<_>>();
    assert!(
        worst(
            "eccentric lift",
            &ch(&t, "tappet.y"),
            &map(&|p| e * p.sin() + r)
        ) < 1e-9
    );
    assert!(
        worst(
            "eccentric velocity",
            &ch(&t, "tappet.vy"),
            &map(&|p| e * w * p.cos())
        ) < 1e-9
    );
    let acc = ch(&t, "tappet.ay");
    assert!(
        worst(
            "eccentric acceleration",
            &acc,
            &map(&|p| -e * w * w * p.sin())
        ) < 1e-8
    );
    assert!(
        worst(
            "eccentric contact x",
            &ch(&t, "face.cx"),
            &map(&|p| e * p.cos())
        ) < 1e-9
    );
    assert!(
        worst(
            "eccentric contact y",
            &ch(&t, "face.cy"),
            &map(&|p| e * p.sin() + r)
        ) < 1e-9
    );
    let zero = vec![0.0; phi.len()];
    assert!(
        worst(
            "eccentric pressure angle",
            &ch(&t, "face.pressure_angle"),
            &zero
        ) < 1e-12
    );
    // The contact is the top of the disc: α_i = π/2 − φ.
    let a: Vec<f64> = ch(&t, "face.alpha_i")
        .iter()
        .zip(&phi)
        .map(|(a, p)| wrap(a - (PI / 2.0 - p)))
        .collect();
    assert!(worst("eccentric alpha_i", &a, &zero) < 1e-9);
}

#[test]
fn circular_cam_and_roller_equal_a_coupler_between_centres() {
    let l = load("cam_circle_roller.toml");
    assert!(design::check(&l.model).is_empty());
    let t = run(&l);
    let twin = run(&variant(
        "cam_circle_roller.toml",
        "type = \"cam_follower\"\nname = \"contact\"\ncurve_i = \"disc\"\ncurve_j = \"roller\"",
        "type = \"relative_distance\"\nname = \"contact\"\nbody_i = \"cam\"\npoint_i = [\"e\", 0]\nbody_j = \"arm\"\npoint_j = \"roller_centre\"\nvalue = \"R + r\"",
    ));
    assert!(
        worst(
            "circle/roller arm angle vs four-bar",
            &ch(&t, "arm.phi"),
            &ch(&twin, "arm.phi")
        ) < 1e-9
    );
    assert!(
        worst(
            "circle/roller arm rate vs four-bar",
            &ch(&t, "arm.omega"),
            &ch(&twin, "arm.omega")
        ) < 1e-9
    );
    let acc = ch(&t, "arm.alpha");
    assert!(
        worst(
            "circle/roller arm acceleration vs four-bar",
            &acc,
            &ch(&twin, "arm.alpha")
        ) < 1e-8
    );
    // Pressure angle: between the centre line and the roller centre's path.
    let (cx, cy) = (ch(&t, "arm.roller_centre.x"), ch(&t, "arm.roller_centre.y"));
    let want: Vec<f64> = (0..t.t.len())
        .map(|k| {
            let q = rot(TAU * t.t[k], [0.2, 0.0]);
            let n = [cx[k] - q[0], cy[k] - q[1]];
            let d = [-(cy[k] - 0.8), cx[k] - 0.6];
            (n[0] * d[1] - n[1] * d[0])
                .abs()
                .atan2((n[0] * d[0] + n[1] * d[1]).abs())
        })
        .collect();
    assert!(
        worst(
            "circle/roller pressure angle",
            &ch(&t, "contact.pressure_angle"),
            &want
        ) < 1e-9
    );
}

#[test]
fn oscillating_roller_follower_against_brute_force() {
    let l = load("cam_oscillating_roller.toml");
    assert!(design::check(&l.model).is_empty());
    let t = run(&l);
    let (o, arm, r) = ([0.6, 0.8], 0.8, 0.1);
    let rho = |a: f64| 0.5 + 0.08 * a.cos() + 0.03 * (2.0 * a).sin();
    let theta = ch(&t, "arm.phi");
    let (mut want, mut pa) = (vec![], vec![]);
    for (k, &time) in t.t.iter().enumerate() {
        let phi = -TAU * time;
        let cam = |a: f64| rot(phi, [rho(a) * a.cos(), rho(a) * a.sin()]);
        let centre = |th: f64| [o[0] + arm * th.cos(), o[1] + arm * th.sin()];
        // Gap between the roller and the cam at arm angle θ: the distance
        // from the roller centre to the nearest cam point, less r.
        let nearest = |c: [f64; 2]| {
            argmax(
                |a| {
                    let p = cam(a);
                    -((c[0] - p[0]).powi(2) + (c[1] - p[1]).powi(2))
                },
                0.0,
                TAU,
                720,
            )
        };
        let gap = |th: f64| (-nearest(centre(th)).1).sqrt() - r;
        let th = bisect(gap, theta[k] - 0.02, theta[k] + 0.02);
        want.push(th);
        let c = centre(th);
        let p = cam(nearest(c).0);
        let n = [c[0] - p[0], c[1] - p[1]];
        let d = [-(c[1] - o[1]), c[0] - o[0]];
        pa.push(
            (n[0] * d[1] - n[1] * d[0])
                .abs()
                .atan2((n[0] * d[0] + n[1] * d[1]).abs()),
        );
    }
    assert!(worst("oscillating roller arm angle", &theta, &want) < 1e-9);
    assert!(
        worst(
            "oscillating roller pressure angle",
            &ch(&t, "contact.pressure_angle"),
            &pa
        ) < 1e-6
    );
}

#[test]
fn valve_train_lift_is_the_cam_support_function() {
    let l = load("cam_valve_train.toml");
    assert!(design::check(&l.model).is_empty());
    let t = run(&l);
    let rho = |a: f64| 0.021 + 0.004 * a.cos() + 0.001 * (2.0 * a).cos();
    // A flat face perpendicular to the motion rides on the cam's highest
    // point: lift = max over α of the cam point's height.
    let lift: Vec<f64> =
        t.t.iter()
            .map(|&time| {
                let phi = -TAU * 25.0 * time;
                argmax(|a| rho(a) * (a + phi).sin(), 0.0, TAU, 4000).1
            })
            .collect();
    assert!(worst("valve train lift", &ch(&t, "valve.y"), &lift) < 1e-9);
    let offset = vec![0.005; lift.len()];
    assert!(worst("valve train axis", &ch(&t, "valve.x"), &offset) < 1e-12);
    let head: Vec<f64> = lift.iter().map(|y| y - 0.09).collect();
    assert!(worst("valve head", &ch(&t, "valve.head.y"), &head) < 1e-9);
    let zero = vec![0.0; lift.len()];
    assert!(
        worst(
            "valve pressure angle",
            &ch(&t, "bucket.pressure_angle"),
            &zero
        ) < 1e-12
    );
    // camlink's valve rises from the base, ρ(π) = 0.018, to the nose,
    // ρ(0) = 0.026: 8 mm of lift. The lift lies between the cam's least and
    // largest radius, ρ(π) and ρ(0), and reaches each where it points along
    // the valve axis (the profile's normal is radial there): the base at
    // φ = −π/2 (t = 0.01 s), the nose at φ = −3π/2 (t = 0.03 s), both output
    // times, so these radii are the extremes of the lift on the grid. Newton
    // stops once the contact residual (m, along the valve axis: the pressure
    // angle is zero) is within `tol` and then applies that correction, so
    // camlink's lift is within `tol` of them.
    let tol = l.analysis.tol;
    let step = l.analysis.step.unwrap();
    for at in [0.01, 0.03] {
        assert!(
            t.t.iter().any(|&x| (x - at).abs() < 1e-9 * step),
            "no output at {at} s"
        );
    }
    let y = ch(&t, "valve.y");
    let (lo, hi) = y
        .iter()
        .fold((f64::MAX, f64::MIN), |m, &v| (m.0.min(v), m.1.max(v)));
    assert!(
        (hi - rho(0.0)).abs() <= tol && (lo - rho(PI)).abs() <= tol,
        "camlink's lift runs from {lo} to {hi} m, want {} to {} m within {tol:.0e} m",
        rho(PI),
        rho(0.0)
    );
}

#[test]
fn pin_in_a_circular_slot_equals_a_coupler_to_the_slot_centre() {
    let l = load("slot_circular_pin.toml");
    let t = run(&l);
    let twin = run(&variant(
        "slot_circular_pin.toml",
        "type = \"point_follower\"\nname = \"pin_in_slot\"\nbody_i = \"crank\"\npoint_i = \"pin\"\ncurve_j = \"slot\"",
        "type = \"relative_distance\"\nname = \"pin_in_slot\"\nbody_i = \"crank\"\npoint_i = \"pin\"\nbody_j = \"rocker\"\npoint_j = \"K\"\nvalue = 0.9",
    ));
    assert!(
        worst(
            "slot rocker angle vs four-bar",
            &ch(&t, "rocker.phi"),
            &ch(&twin, "rocker.phi")
        ) < 1e-9
    );
    assert!(
        worst(
            "slot rocker rate vs four-bar",
            &ch(&t, "rocker.omega"),
            &ch(&twin, "rocker.omega")
        ) < 1e-9
    );
    // The pin stays inside the slot's 85° of arc, and the contact point is the pin.
    let s = ch(&t, "pin_in_slot.alpha_j");
    assert!(
        s.iter().all(|&v| v > 0.0 && v < 0.9 * 85f64.to_radians()),
        "{s:?}"
    );
    assert!(
        worst(
            "slot contact point",
            &ch(&t, "pin_in_slot.cx"),
            &ch(&t, "crank.pin.x")
        ) < 1e-12
    );
}

#[test]
fn pin_driven_along_a_curved_slot() {
    let l = load("slot_curved_driven.toml");
    let t = run(&l);
    let s: Vec<f64> = t.t.iter().map(|&x| 1.0 + 0.3 * (TAU * x).sin()).collect();
    assert!(worst("driven slot travel", &ch(&t, "slider.alpha_j"), &s) < 1e-12);
    assert!(worst("driven pin x", &ch(&t, "rod.P.x"), &s) < 1e-9);
    let y: Vec<f64> = s.iter().map(|s| 0.1 * (3.0 * s).sin()).collect();
    assert!(worst("driven pin y", &ch(&t, "rod.P.y"), &y) < 1e-9);
    // Crank angle in closed form: A on circles |A| = 0.4 and |A − P| = 1,
    // on the upper branch (left of O→P).
    let want: Vec<f64> = s
        .iter()
        .zip(&y)
        .map(|(&px, &py)| {
            let d = px.hypot(py);
            let a = (0.16 - 1.0 + d * d) / (2.0 * d);
            let h = (0.16 - a * a).sqrt();
            let (ux, uy) = (px / d, py / d);
            (a * uy + h * ux).atan2(a * ux - h * uy)
        })
        .collect();
    let got: Vec<f64> = ch(&t, "crank.phi")
        .iter()
        .zip(&want)
        .map(|(g, w)| w + wrap(g - w))
        .collect();
    assert!(worst("driven slot crank angle", &got, &want) < 1e-9);
    // The driver's own rate: α̇_j = f′(t) reaches the pin's velocity along x.
    let vx: Vec<f64> = t.t.iter().map(|&x| 0.3 * TAU * (TAU * x).cos()).collect();
    assert!(worst("driven pin vx", &ch(&t, "rod.P.vx"), &vx) < 1e-9);
}

#[test]
fn a_pin_driven_off_the_end_of_its_slot_stops_the_run() {
    // Slot shortened to end at x = 1.2; the drive reaches 1.3.
    let l = variant(
        "slot_curved_driven.toml",
        "range = [0.2, 1.6]",
        "range = [0.2, 1.2]",
    );
    let (table, r) = try_run(&l);
    let e = r.unwrap_err();
    // s = 1 + 0.3 sin 2πt passes 1.2 at t = asin(2/3)/2π = 0.1161 s.
    assert!((e.time - 0.12).abs() < 1e-12, "{e}");
    assert_eq!(e.joints, ["slider"]);
    assert_eq!(e.kind, Kind::OffCurve, "{e}");
    let text = e.to_string();
    assert!(
        text.contains("ran off the upper end (1.2)") && text.contains("α_j = 1.2"),
        "{text}"
    );
    assert_eq!(table.t.len(), 24, "the steps before the error are kept");
}

#[test]
fn a_pin_driven_off_the_start_of_its_slot_names_the_lower_end() {
    // Slot starting at x = 0.75; the drive comes down to 0.7.
    let l = variant(
        "slot_curved_driven.toml",
        "range = [0.2, 1.6]",
        "range = [0.75, 1.6]",
    );
    let (_, r) = try_run(&l);
    let e = r.unwrap_err();
    // s = 1 + 0.3 sin 2πt falls below 0.75 at t = 1/2 + asin(5/6)/2π = 0.6568 s, first
    // seen at the next output time.
    assert!((e.time - 0.66).abs() < 1e-12, "{e}");
    let text = e.to_string();
    assert!(
        text.contains("ran off the lower end (0.75)") && text.contains("α_j = 0.7"),
        "{text}"
    );
}

#[test]
fn cam_from_csv_points() {
    let l = load("cam_csv_profile.toml");
    assert!(design::check(&l.model).is_empty());
    let cam = match &l.model.joint("face").unwrap().constraint {
        Constraint::FlatFollower(f) => f.curve_i.clone(),
        other => panic!("{other:?}"),
    };
    // The spline passes through every measured point.
    let csv = std::fs::read_to_string(examples().join("data/cam_profile.csv")).unwrap();
    let rows: Vec<(f64, f64)> = csv
        .lines()
        .filter_map(|l| {
            let (a, r) = l.split_once(',')?;
            Some((a.parse().ok()?, r.parse().ok()?))
        })
        .collect();
    assert_eq!(rows.len(), 36);
    for &(a, r) in &rows {
        let p = cam.jet(a).p;
        assert!((p[0].hypot(p[1]) - r).abs() < 1e-12 && (p[1].atan2(p[0]) - wrap(a)).abs() < 1e-12);
    }
    let t = run(&l);
    // Lift = the spline profile's support function (brute force on the
    // curve's points), and close to the function the table sampled.
    let (mut spline, mut exact) = (vec![], vec![]);
    for &time in &t.t {
        let phi = TAU * time;
        spline.push(argmax(|a| rot(phi, cam.jet(a).p)[1], 0.0, TAU, 4000).1);
        let rho = |a: f64| 0.03 + 0.005 * a.cos() + 0.001 * (2.0 * a).sin();
        exact.push(argmax(|a| rho(a) * (a + phi).sin(), 0.0, TAU, 4000).1);
    }
    let y = ch(&t, "follower.y");
    assert!(worst("CSV cam lift vs spline support", &y, &spline) < 1e-9);
    assert!(worst("CSV cam lift vs sampled function", &y, &exact) < 1e-6);
}

#[test]
fn every_cam_and_slot_example_has_a_test() {
    // The cam examples' dynamics are tested in cam_dynamics.rs and
    // unilateral.rs.
    let this = [
        include_str!("cam_examples.rs"),
        include_str!("cam_dynamics.rs"),
        include_str!("unilateral.rs"),
    ]
    .concat();
    let mut found = 0;
    for entry in std::fs::read_dir(examples()).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        // Cam design files are not models: tests/python/test_cam_design.py runs them.
        if name.starts_with("cam_design_") {
            continue;
        }
        if (name.starts_with("cam_") || name.starts_with("slot_")) && name.ends_with(".toml") {
            assert!(this.contains(&format!("\"{name}\"")), "{name} has no test");
            found += 1;
        }
    }
    assert!(found >= 9, "only {found} cam and slot examples found");
}

/// A small cam model with `curves` and `joint` spliced in, loaded as
/// `source`.
fn cam_model(curves: &str, joint: &str, source: &str) -> Result<Loaded, String> {
    let text = format!(
        r#"
[[bodies]]
name = "cam"

[[bodies]]
name = "follower"
position = [0, 2]

{curves}

[[joints]]
type = "revolute"
name = "pivot"
body_i = "ground"
body_j = "cam"

{joint}
"#
    );
    load_str(&text, Format::Toml, source).map_err(|e| e.to_string())
}

const ROLLER: &str =
    "[[curves]]\nname = \"roller\"\nbody = \"follower\"\nsource = \"circle\"\nradius = 0.2";

#[test]
fn curve_errors_name_the_field() {
    let e = cam_model(
        &format!("{ROLLER}\n[[curves]]\nname = \"lobe\"\nbody = \"cam\"\nsource = \"circle\"\nradius = 1"),
        "[[joints]]\ntype = \"cam_follower\"\ncurve_i = \"lobb\"\ncurve_j = \"roller\"",
        "m.toml",
    )
    .unwrap_err();
    assert!(
        e.contains("joints[1].curve_i: no curve named 'lobb' (did you mean 'lobe'?)"),
        "{e}"
    );

    let e = cam_model(
        "[[curves]]\nname = \"c\"\nbody = \"cam\"\nsource = \"expression\"\nrho = \"1\"\nx = \"s\"",
        "",
        "m.toml",
    )
    .unwrap_err();
    assert!(e.contains("curves[0].rho: give either `rho`"), "{e}");

    let e = cam_model(
        "[[curves]]\nname = \"c\"\nbody = \"cam\"\nsource = \"expression\"\nrho = \"0.5 + cos(a)\"",
        "",
        "m.toml",
    )
    .unwrap_err();
    assert!(
        e.contains("curves[0]: curve 'c': the polar profile has ρ = "),
        "{e}"
    );

    let e = cam_model(
        "[[curves]]\nname = \"c\"\nbody = \"cam\"\nsource = \"expression\"\nrho = \"1 + cos(b)\"",
        "",
        "m.toml",
    )
    .unwrap_err();
    assert!(e.contains("curves[0].rho: invalid expression"), "{e}");
    // The line and column of the faulty value come first.
    assert!(e.starts_with("m.toml:13:7: "), "{e}");

    let e = cam_model(
        "[[curves]]\nname = \"c\"\nbody = \"cam\"\nsource = \"circle\"\nradius = 1\nstart = 0.3",
        "",
        "m.toml",
    )
    .unwrap_err();
    assert!(
        e.contains("curves[0].start: `start` applies to a parametric circle"),
        "{e}"
    );

    let e = cam_model(
        "[[curves]]\nname = \"c\"\nbody = \"cam\"\nsource = \"circle\"\nradius = 1\nradus = 2",
        "",
        "m.toml",
    )
    .unwrap_err();
    assert!(e.contains("unknown field `radus`"), "{e}");
}

#[test]
fn csv_errors_name_the_csv_file_and_line() {
    let dir = std::env::temp_dir().join(format!("camlink_cam_csv_{}", std::process::id()));
    std::fs::create_dir_all(dir.join("data")).unwrap();
    std::fs::write(dir.join("data/bad.csv"), "alpha,rho\n0,1\n1,1.1\n2 1.2 7\n").unwrap();
    let source = dir.join("m.toml").display().to_string();
    let spline = |file: &str| {
        format!("[[curves]]\nname = \"c\"\nbody = \"cam\"\nsource = \"spline\"\nkind = \"polar\"\nfile = \"{file}\"")
    };
    let e = cam_model(&spline("data/bad.csv"), "", &source).unwrap_err();
    assert!(
        e.contains("curves[0].file: ") && e.contains("bad.csv:4: expected 2 columns"),
        "{e}"
    );
    let e = cam_model(&spline("data/missing.csv"), "", &source).unwrap_err();
    assert!(
        e.contains("curves[0].file: ") && e.contains("missing.csv"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn curve_travel_needs_a_point_follower() {
    let e = cam_model(
        ROLLER,
        "[[drivers]]\ntype = \"curve_travel\"\njoint = \"pivot\"\nf = \"t\"",
        "m.toml",
    )
    .unwrap_err();
    assert!(
        e.contains("drivers[0].joint: joint 'pivot' is a revolute joint, but a curve_travel driver needs a point_follower joint"),
        "{e}"
    );
}

#[test]
fn one_given_contact_parameter_seeds_the_other() {
    // Cam circle about the origin (radius 1), roller of 0.2 centred at
    // (0, 2) on the follower: α_i = π/2 on the cam is (0, 1), nearest to
    // the roller's point straight below its centre, at α_j = 3π/2.
    let l = cam_model(
        &format!("{ROLLER}\n[[curves]]\nname = \"disc\"\nbody = \"cam\"\nsource = \"circle\"\nradius = 1"),
        "[[joints]]\ntype = \"cam_follower\"\nname = \"c\"\ncurve_i = \"disc\"\ncurve_j = \"roller\"\nalpha_i = \"pi/2\"",
        "m.toml",
    )
    .unwrap();
    let own = l.model.joint("c").unwrap().own0.unwrap();
    assert!(
        (own[0] - PI / 2.0).abs() < 1e-15 && (own[1] - 1.5 * PI).abs() < 1e-9,
        "{own:?}"
    );
}

/// `examples/cam_motion_roller.toml`: a `motion` curve drives its offset
/// roller through the program; the follower height against the closed
/// forms of the cycloidal rise and the 3-4-5 return, y = y₀ + s(θ).
#[test]
fn motion_curve_reproduces_its_program() {
    let l = load("cam_motion_roller.toml");
    let t = run(&l);
    let (rb, rr, e, h): (f64, f64, f64, f64) = (0.03, 0.01, 0.005, 0.012);
    let y0 = ((rb + rr) * (rb + rr) - e * e).sqrt();
    let s = |th: f64| {
        let b = 2.0 * PI / 3.0;
        if th < PI / 3.0 {
            0.0
        } else if th < PI {
            let u = (th - PI / 3.0) / b;
            h * (u - (TAU * u).sin() / TAU)
        } else if th < 4.0 * PI / 3.0 {
            h
        } else {
            let u = (th - 4.0 * PI / 3.0) / b;
            h * (1.0 - u * u * u * (10.0 - 15.0 * u + 6.0 * u * u))
        }
    };
    let want: Vec<f64> = t.t.iter().map(|&tt| y0 + s((TAU * tt) % TAU)).collect();
    let err = worst("follower.y", &ch(&t, "follower.y"), &want);
    assert!(err < 1e-9 * h, "follower height off by {err} m");
    // The follower stays on its stem at x = e.
    assert!(ch(&t, "follower.x").iter().all(|x| (x - e).abs() < 1e-12));
}

/// A `motion` curve's mistakes name the field.
#[test]
fn motion_curve_errors_name_the_field() {
    for (from, to, want) in [
        (
            "law = \"cycloidal\"",
            "law = \"cycloid\"",
            "curves[0].segments[1].law",
        ),
        (
            "span = \"pi/3\" },\n    { law = \"3-4-5\"",
            "span = \"pi/4\" },\n    { law = \"3-4-5\"",
            "curves[0].segments",
        ),
        ("offset = \"e\"", "arm_length = 0.1", "curves[0].arm_length"),
        (
            "follower = \"translating-roller\"",
            "follower = \"rolling\"",
            "curves[0].follower",
        ),
    ] {
        let text = std::fs::read_to_string(examples().join("cam_motion_roller.toml")).unwrap();
        assert_eq!(text.matches(from).count(), 1, "{from}");
        let e = load_str(&text.replace(from, to), Format::Toml, "m.toml").unwrap_err();
        assert!(e.to_string().contains(want), "{want}: {e}");
    }
}
