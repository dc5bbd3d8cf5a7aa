//! Cam contact forces and follower lift-off: the spring-loaded valve
//! follower (`examples/cam_valve_spring.toml`) against its closed form, the
//! speed where it starts to jump, the same in forward dynamics, and a
//! roller follower's force balance.

use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::path::{Path, PathBuf};

use camlink_core::dynamics::contact_force::lift_off;
use camlink_core::dynamics::{integrator, inverse};
use camlink_core::run::{Kind, LiftOff, Settings, Summary, Table};
use camlink_model::{load_path, load_str, Format, Loaded};

const EXAMPLE: &str = "cam_valve_spring.toml";

// The example's parameters.
const R: f64 = 0.02;
const E: f64 = 0.004;
const M: f64 = 0.1;
const K: f64 = 5000.0;
const PRELOAD: f64 = 50.0;
const G: f64 = 9.81;
/// Height where the spring is free (m).
const Y_FREE: f64 = R - E - PRELOAD / K;

fn path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(EXAMPLE)
}

/// The example with each (from, to) replaced (each `from` occurs once).
fn variant(edits: &[(&str, &str)]) -> Loaded {
    let mut text = std::fs::read_to_string(path()).unwrap();
    for (from, to) in edits {
        assert_eq!(text.matches(from).count(), 1, "{from:?}");
        text = text.replace(from, to);
    }
    load_str(&text, Format::Toml, &path().display().to_string()).unwrap_or_else(|e| panic!("{e}"))
}

fn at_rpm(rpm: f64) -> Loaded {
    variant(&[("rpm = 3000 ", &format!("rpm = {rpm:.17} "))])
}

/// ω (rad/s) of a camshaft speed in rpm.
fn omega(rpm: f64) -> f64 {
    rpm * TAU / 60.0
}

/// The closed form of the normal force at cam angle θ:
/// N = k (y − y_free) + m g + m ÿ + c ẏ, y = R + e sin θ.
fn n_closed(w: f64, c: f64, th: f64) -> f64 {
    let y = R + E * th.sin();
    K * (y - Y_FREE) + M * G - M * E * w * w * th.sin() + c * E * w * th.cos()
}

/// ω where min N = 0 without friction: N(90°) = 0.
fn omega_jump() -> f64 {
    ((K * (R + E - Y_FREE) + M * G) / (M * E)).sqrt()
}

/// Inverse dynamics over one camshaft turn, 720 steps (θ on every ½°).
fn inverse_turn(l: &Loaded, rpm: f64) -> (Table, Summary) {
    let period = 60.0 / rpm;
    let times: Vec<f64> = (0..=720).map(|k| period * k as f64 / 720.0).collect();
    let mut table = Table::default();
    let s = inverse::run(&l.model, &times, &Settings::default(), &[], &mut table)
        .unwrap_or_else(|e| panic!("{e}"));
    (table, s)
}

fn ch(t: &Table, name: &str) -> Vec<f64> {
    t.channel(name)
        .unwrap_or_else(|| panic!("no channel {name} in {:?}", t.channels))
}

fn lift_off_warnings(s: &Summary) -> Vec<&String> {
    s.warnings
        .iter()
        .filter(|w| w.kind == Kind::LiftOff)
        .map(|w| &w.message)
        .collect()
}

/// The run's lift-off records are the intervals in its table, and its
/// lift-off warnings are their messages at their start times, in order.
fn assert_lift_off_data_matches_warnings(l: &Loaded, t: &Table, s: &Summary) {
    assert_eq!(s.lift_off, lift_off(&l.model, t));
    let warnings: Vec<(f64, String)> = s
        .warnings
        .iter()
        .filter(|w| w.kind == Kind::LiftOff)
        .map(|w| (w.time, w.message.clone()))
        .collect();
    let records: Vec<(f64, String)> = s
        .lift_off
        .iter()
        .map(|r| (r.start.time, r.message()))
        .collect();
    assert_eq!(warnings, records);
}

#[test]
fn valve_spring_example_runs_in_contact() {
    let l = load_path(&path()).unwrap_or_else(|e| panic!("{e}"));
    let (t, s) = inverse_turn(&l, 3000.0);
    let n = ch(&t, "bucket.normal_force");
    let least = n.iter().copied().fold(f64::INFINITY, f64::min);
    eprintln!("3000 rpm: least normal force {least:.4} N");
    assert!(least > 20.0, "{least}");
    assert!(lift_off_warnings(&s).is_empty(), "{:?}", s.warnings);
    assert!(lift_off(&l.model, &t).is_empty());
    assert!(s.lift_off.is_empty());
}

/// camlink's normal force is the closed form to 1e-8 of its largest value,
/// with and without viscous friction in the guide; the tangential force is
/// zero; the lift is R + e sin θ.
#[test]
fn valve_spring_normal_force_matches_the_closed_form() {
    let mut worst: f64 = 0.0;
    for (rpm, c) in [
        (1000.0, 0.0),
        (3000.0, 0.0),
        (4800.0, 0.0),
        (6000.0, 0.0),
        (3000.0, 5.0),
    ] {
        let l = variant(&[
            ("rpm = 3000 ", &format!("rpm = {rpm} ")),
            ("damping = 0 ", &format!("damping = {c} ")),
        ]);
        let (t, _) = inverse_turn(&l, rpm);
        let (th, y) = (ch(&t, "cam.phi"), ch(&t, "tappet.y"));
        let (n, tan) = (
            ch(&t, "bucket.normal_force"),
            ch(&t, "bucket.tangential_force"),
        );
        let w = omega(rpm);
        let want: Vec<f64> = th.iter().map(|&a| n_closed(w, c, a)).collect();
        let scale = want.iter().map(|v| v.abs()).fold(0.0, f64::max);
        let err = n
            .iter()
            .zip(&want)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / scale;
        let lift = th
            .iter()
            .zip(&y)
            .map(|(a, y)| (y - (R + E * a.sin())).abs())
            .fold(0.0, f64::max);
        let tmax = tan.iter().map(|v| v.abs()).fold(0.0, f64::max);
        eprintln!(
            "{rpm} rpm, c = {c}: normal force relative error {err:.2e}, lift error {lift:.1e} m, \
             |tangential| ≤ {tmax:.1e} N"
        );
        assert!(err < 1e-8, "{err}");
        assert!(lift < 1e-12, "{lift}");
        assert!(tmax < 1e-9 * scale, "{tmax}");
        worst = worst.max(err);
    }
    eprintln!("worst relative error of the normal force: {worst:.2e}");
}

/// The least normal force over a turn (at θ = 90° on the ½° grid).
fn least_force(rpm: f64) -> (f64, Summary, Table) {
    let (t, s) = inverse_turn(&at_rpm(rpm), rpm);
    let least = ch(&t, "bucket.normal_force")
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    (least, s, t)
}

/// A sweep of camshaft speeds shows where the follower starts to jump; the
/// speed found by bisection on camlink's least normal force is the closed
/// form's; lift-off is reported just above it and not just below.
#[test]
fn valve_spring_jump_speed() {
    let wj = omega_jump();
    let rpm_j = wj * 60.0 / TAU;
    // The sweep.
    let mut first = None;
    for rpm in (1..=12).map(|k| 500.0 * k as f64) {
        let (least, s, _) = least_force(rpm);
        let jumps = !lift_off_warnings(&s).is_empty();
        eprintln!(
            "{rpm:6.0} rpm: least normal force {least:9.3} N{}",
            if jumps { "  jump" } else { "" }
        );
        assert_eq!(jumps, least < 0.0);
        if jumps && first.is_none() {
            first = Some(rpm);
        }
    }
    assert_eq!(first, Some(5000.0), "jump begins between 4500 and 5000 rpm");
    // Bisection on camlink's own least force.
    let (mut lo, mut hi) = (4500.0, 5000.0);
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if least_force(mid).0 < 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let found = 0.5 * (lo + hi);
    let rel = (found - rpm_j).abs() / rpm_j;
    eprintln!(
        "jump begins at {found:.6} rpm ({:.4} rad/s); closed form {rpm_j:.6} rpm, relative difference {rel:.1e}",
        omega(found)
    );
    assert!(rel < 1e-8, "{found} vs {rpm_j}");
    // Just below: in contact all the way round.
    let (least, s, t) = least_force(rpm_j * (1.0 - 1e-4));
    assert!(
        least > 0.0 && lift_off_warnings(&s).is_empty(),
        "{least} {:?}",
        s.warnings
    );
    assert!(lift_off(&at_rpm(rpm_j).model, &t).is_empty());
    assert!(s.lift_off.is_empty());
    // Just above: one interval around full lift.
    for eps in [1e-4, 1e-2] {
        let rpm = rpm_j * (1.0 + eps);
        let l = at_rpm(rpm);
        let (t, s) = inverse_turn(&l, rpm);
        let warnings = lift_off_warnings(&s);
        assert_eq!(warnings.len(), 1, "{:?}", s.warnings);
        eprintln!("{rpm:.3} rpm: {}", warnings[0]);
        let found = lift_off(&l.model, &t);
        assert_eq!(found.len(), 1);
        assert_lift_off_data_matches_warnings(&l, &t, &s);
        let LiftOff {
            joint,
            cam,
            start,
            end,
            least,
            least_at,
        } = &found[0];
        assert_eq!((joint.as_str(), cam.as_str()), ("bucket", "cam"));
        assert_eq!(warnings[0], &found[0].message());
        let end = end.expect("the contact comes back");
        // Closed form: N(θ) = 0 at sin θ = A / (m e ω² − k e).
        let w = omega(rpm);
        let a = K * (R - Y_FREE) + M * G;
        let th0 = (a / (M * E * w * w - K * E)).asin();
        let (th1, period) = (PI - th0, 60.0 / rpm);
        let half_step = PI / 720.0;
        eprintln!(
            "  cam angles {:.5} to {:.5} rad, closed form {th0:.5} to {th1:.5}",
            start.cam_angle, end.cam_angle
        );
        assert!(
            (start.cam_angle - th0).abs() < half_step,
            "{start:?} vs {th0}"
        );
        assert!((end.cam_angle - th1).abs() < half_step, "{end:?} vs {th1}");
        assert!((start.time - th0 / w).abs() < period / 1440.0);
        assert!((end.time - th1 / w).abs() < period / 1440.0);
        assert!((least_at.cam_angle - FRAC_PI_2).abs() < 1e-12);
        let n90 = n_closed(w, 0.0, FRAC_PI_2);
        assert!((least - n90).abs() < 1e-8 * K * E, "{least} vs {n90}");
    }
}

/// Forward dynamics: the cam as a heavy flywheel spun up, not driven. The
/// tappet's force balance k (y − y_free) + m g + m ÿ = N holds along the
/// run; lift-off is reported when the flywheel runs faster than ω_jump and
/// not when it runs slower. (The initial velocity projection spreads the
/// given ω over the contact's own coordinate too, so the flywheel's speed
/// is read from the run.)
#[test]
fn valve_spring_forward_dynamics_reports_lift_off() {
    for rpm in [3000.0, 12000.0] {
        let l = variant(&[
            ("rpm = 3000 ", &format!("rpm = {rpm} ")),
            (
                "[[drivers]]\ntype = \"revolute_angle\"\nname = \"motor\"\njoint = \"shaft\"\nf = \"2*pi*rpm/60*t\"\n",
                "",
            ),
            ("inertia = 1e-4", "inertia = 10\nomega = \"2*pi*rpm/60\""),
        ]);
        // A turn at half the given speed.
        let period = 120.0 / rpm;
        let times = camlink_core::run::time_grid(period, period / 360.0).unwrap();
        let settings = integrator::Settings {
            step: period / 2880.0,
            tol: 1e-8,
            ..integrator::Settings::default()
        };
        let mut t = Table::default();
        let s = integrator::run(&l.model, &times, &settings, &[], &mut t)
            .unwrap_or_else(|e| panic!("{e}"));
        let (y, ay, n) = (
            ch(&t, "tappet.y"),
            ch(&t, "tappet.ay"),
            ch(&t, "bucket.normal_force"),
        );
        let w = ch(&t, "cam.omega");
        let err = (0..n.len())
            .map(|k| (n[k] - (K * (y[k] - Y_FREE) + M * G + M * ay[k])).abs())
            .fold(0.0, f64::max);
        let least = n.iter().copied().fold(f64::INFINITY, f64::min);
        let warnings = lift_off_warnings(&s);
        eprintln!(
            "forward, ω₀ from {rpm} rpm (ω {:.2} to {:.2} rad/s): least N {least:.3} N, force balance error {err:.1e} N; {warnings:?}",
            w[0],
            w[w.len() - 1]
        );
        assert!(err < 1e-6, "{err}");
        let jumps = w[0] > omega_jump();
        assert!(w.iter().all(|&v| (v > omega_jump()) == jumps));
        assert_eq!(!warnings.is_empty(), jumps, "{:?}", s.warnings);
        assert_eq!(least < 0.0, jumps);
        assert_lift_off_data_matches_warnings(&l, &t, &s);
        assert_eq!(s.lift_off.is_empty(), !jumps);
        if jumps {
            // Around full lift, θ = 90°.
            let l0 = &lift_off(&l.model, &t)[0];
            let e = l0.end.expect("the contact comes back");
            assert!(
                l0.start.cam_angle < FRAC_PI_2 && FRAC_PI_2 < e.cam_angle,
                "{l0:?}"
            );
        }
    }
}

/// A roller follower (cam–follower joint) instead of the flat face: the
/// normal force pushes along the line of centres, its vertical part
/// balances the tappet, and the tangential force is zero.
#[test]
fn roller_follower_normal_force_balances_the_tappet() {
    let r = 0.008;
    let l = variant(&[
        (
            "[[joints]]\ntype = \"flat_follower\"\nname = \"bucket\"\ncurve_i = \"disc\"\nbody_j = \"tappet\"\npoint_j = [0, 0]\naxis = [1, 0]\n",
            &format!(
                "[[curves]]\nname = \"roller\"\nbody = \"tappet\"\nsource = \"circle\"\nradius = {r}\n\n\
                 [[joints]]\ntype = \"cam_follower\"\nname = \"bucket\"\ncurve_i = \"disc\"\ncurve_j = \"roller\"\n"
            ),
        ),
        ("position = [0, \"R\"]", "position = [0, \"sqrt((R + 0.008)^2 - e^2)\"]"),
        ("free_length = \"H - (R - e - preload/k)\"", "free_length = 0.1"),
    ]);
    let (t, _) = inverse_turn(&l, 3000.0);
    let (th, y, ay) = (ch(&t, "cam.phi"), ch(&t, "tappet.y"), ch(&t, "tappet.ay"));
    let (n, tan) = (
        ch(&t, "bucket.normal_force"),
        ch(&t, "bucket.tangential_force"),
    );
    let mut worst: f64 = 0.0;
    let scale = n.iter().map(|v| v.abs()).fold(0.0, f64::max);
    for k in 0..n.len() {
        // Unit normal from the disc's centre to the roller's.
        let c = [E * th[k].cos(), E * th[k].sin()];
        let d = [-c[0], y[k] - c[1]];
        let ny = d[1] / (d[0] * d[0] + d[1] * d[1]).sqrt();
        // The spring is free at y = H − 0.1 = 0: it pushes down k y.
        let want = K * y[k] + M * G + M * ay[k];
        worst = worst.max((n[k] * ny - want).abs());
        assert!(n[k] > 0.0);
        assert!(tan[k].abs() < 1e-9 * scale, "{}", tan[k]);
    }
    eprintln!("roller: vertical balance error {worst:.1e} N of {scale:.1} N");
    assert!(worst < 1e-8 * scale, "{worst}");
}
