//! The design report (`camlink_cam::report`): each check against a figure
//! computed here from the closed form of a cycloidal program, the spring
//! and Hertz formulas; limits passed and exceeded with their margins; the
//! report in millimetres and back.

use std::f64::consts::{PI, TAU};
use std::path::Path;

use camlink_cam::report::{analyse, tool_undercut, Check, Report};
use camlink_cam::{load_path, load_toml, Design};

/// Rise h (m) over β = 120°, dwell 60°, return over 120°, dwell 60°, all
/// cycloidal.
const H: f64 = 0.01;
const BETA_DEG: f64 = 120.0;
const RB: f64 = 0.03;

fn program() -> String {
    format!(
        r#"[[segments]]
law = "cycloidal"
span_deg = {BETA_DEG}
lift = {H}
[[segments]]
law = "dwell"
span_deg = 60
[[segments]]
law = "cycloidal"
span_deg = {BETA_DEG}
lift = -{H}
[[segments]]
law = "dwell"
span_deg = 60
"#
    )
}

fn design(follower: &str, rest: &str) -> Design {
    let text = format!(
        "name = \"t\"\n[cam]\nbase_radius = {RB}\n[follower]\n{follower}\n{}{rest}",
        program()
    );
    load_toml(&text, "t.toml").expect("a good design").design
}

/// s, s′, s″ (per rad) of the program at θ (rad), from the cycloidal law's
/// closed form s = h (u − sin 2πu / 2π), u = (θ − θ₀)/β.
fn motion(theta: f64) -> [f64; 3] {
    let beta = BETA_DEG.to_radians();
    let cyc = |t: f64, h: f64| {
        let u = t / beta;
        [
            h * (u - (TAU * u).sin() / TAU),
            h / beta * (1.0 - (TAU * u).cos()),
            h * TAU / (beta * beta) * (TAU * u).sin(),
        ]
    };
    let t = theta.rem_euclid(TAU);
    let (rise_end, ret) = (beta, beta + PI / 3.0);
    if t < rise_end {
        cyc(t, H)
    } else if t < ret {
        [H, 0.0, 0.0]
    } else if t < ret + beta {
        let [s, v, a] = cyc(t - ret, -H);
        [H + s, v, a]
    } else {
        [0.0; 3]
    }
}

/// The extreme of `f` over a turn sampled at n angles, with its angle.
fn dense(f: impl Fn(f64) -> f64, least: bool) -> (f64, f64) {
    let n = 720_000;
    (0..n)
        .map(|k| TAU * k as f64 / n as f64)
        .map(|t| (f(t), t))
        .fold((f64::NAN, 0.0), |best, (v, t)| {
            let better = if least { v < best.0 } else { v > best.0 };
            if best.0.is_nan() || better {
                (v, t)
            } else {
                best
            }
        })
}

fn check<'a>(r: &'a Report, name: &str) -> &'a Check {
    r.checks
        .iter()
        .find(|c| c.name.starts_with(name))
        .unwrap_or_else(|| panic!("no check '{name}' in {:?}", r.checks))
}

fn close(got: f64, want: f64, rel: f64) {
    assert!(
        (got - want).abs() <= rel * want.abs().max(1e-300),
        "{got} vs {want} (relative {rel})"
    );
}

/// A centred translating roller: tan φ = s′/(R_b + r + s); the report
/// gives the largest φ of the rise in degrees, its margin under the
/// limit, and fails past it.
#[test]
fn pressure_angle_of_a_centred_roller_is_the_closed_form() {
    let roller = 0.01;
    let follower = format!("type = \"translating-roller\"\nroller_radius = {roller}");
    let phi = |t: f64| {
        let [s, v, _] = motion(t);
        (v / (RB + roller + s)).atan()
    };
    let (rise, at) = dense(phi, false);
    let (ret, _) = dense(phi, true);
    let limit_deg = 25.0;
    let d = design(
        &follower,
        &format!("[limits]\nmax_pressure_angle_deg = {limit_deg}\n"),
    );
    let r = analyse(&d).unwrap();
    let c = check(&r, "pressure angle, rise");
    close(c.value, rise.to_degrees(), 1e-7);
    assert!((c.at_deg.unwrap() - at.to_degrees()).abs() < 0.2);
    assert_eq!((c.unit.as_str(), c.limit), ("deg", Some(limit_deg)));
    close(c.margin.unwrap(), limit_deg - rise.to_degrees(), 1e-6);
    assert_eq!(c.ok, rise.to_degrees() <= limit_deg);
    close(
        check(&r, "pressure angle, return").value,
        ret.to_degrees(),
        1e-7,
    );

    // A limit under the largest angle fails by the difference.
    let tight = rise.to_degrees() - 2.0;
    let d = design(
        &follower,
        &format!("[limits]\nmax_pressure_angle_deg = {tight}\n"),
    );
    let r = analyse(&d).unwrap();
    let c = check(&r, "pressure angle, rise");
    assert!(!c.ok && !r.ok());
    close(c.margin.unwrap(), -2.0, 1e-5);
}

/// The pitch curve of a centred translating roller is the polar curve
/// r = R_b + r_r + s(θ), of radius of curvature
/// (r² + r′²)^{3/2} / (r² + 2r′² − r r″); the report holds its least
/// convex value against the roller's radius.
#[test]
fn pitch_curve_radius_is_the_polar_curve_formula() {
    let roller = 0.01;
    let d = design(
        &format!("type = \"translating-roller\"\nroller_radius = {roller}"),
        "",
    );
    let (least, _) = dense(
        |t| {
            let [s, v, a] = motion(t);
            let r = RB + roller + s;
            let rho = (r * r + v * v).powf(1.5) / (r * r + 2.0 * v * v - r * a);
            if rho > 0.0 {
                rho
            } else {
                f64::INFINITY
            }
        },
        true,
    );
    let r = analyse(&d).unwrap();
    let c = check(&r, "least convex pitch-curve radius vs roller radius");
    close(c.value, least, 1e-6);
    assert_eq!((c.limit, c.unit.as_str(), c.ok), (Some(roller), "m", true));
    close(c.margin.unwrap(), least - roller, 1e-6);
}

/// The smallest base circle for a pressure angle limit φ_max under a
/// centred translating roller: tan φ = |s′|/(R_b + r_r + s) ≤ tan φ_max
/// everywhere gives R_b ≥ max(|s′|/tan φ_max − r_r − s); the report's
/// search finds it (to its 1e-6 bisection) and holds the file's R_b to it.
#[test]
fn smallest_base_circle_is_the_pressure_angle_bound() {
    let (roller, phi_deg) = (0.01, 25.0);
    let tan = f64::to_radians(phi_deg).tan();
    let (want, _) = dense(
        |t| {
            let [s, v, _] = motion(t);
            v.abs() / tan - roller - s
        },
        false,
    );
    let d = design(
        &format!("type = \"translating-roller\"\nroller_radius = {roller}"),
        &format!(
            "[limits]\nmax_pressure_angle_deg = {phi_deg}\nbase_radius_search = [0.005, 0.2]\n"
        ),
    );
    let r = analyse(&d).unwrap();
    let got = r.smallest_base_radius.unwrap();
    close(got, want, 2e-6);
    let c = check(&r, "smallest base circle meeting the limits");
    assert_eq!((c.value, c.limit), (got, Some(RB)));
    close(c.margin.unwrap(), RB - got, 1e-12);
    assert_eq!(c.ok, got <= RB);
}

/// A translating flat face: the surface's radius of curvature is
/// R_b + s + s″, the contact runs along the face at x = s′ (width
/// 4h/β), and the face has no pressure angle.
#[test]
fn flat_face_radius_and_width_are_the_closed_form() {
    let (rho, _) = dense(
        |t| {
            let [s, _, a] = motion(t);
            RB + s + a
        },
        true,
    );
    let width = 4.0 * H / BETA_DEG.to_radians();
    let min_radius = rho + 0.001;
    let d = design(
        "type = \"translating-flat\"",
        &format!("[limits]\nmin_radius = {min_radius}\nmax_face_width = 0.05\n"),
    );
    let r = analyse(&d).unwrap();
    assert!(r.checks.iter().all(|c| !c.name.starts_with("pressure")));
    let c = check(&r, "least radius of curvature");
    close(c.value, rho, 1e-6);
    // Past the limit: fails by value − limit.
    assert!(!c.ok);
    close(c.margin.unwrap(), c.value - min_radius, 1e-12);
    let w = check(&r, "face width needed");
    close(w.value, width, 1e-6);
    assert!(w.ok);
    close(w.margin.unwrap(), 0.05 - w.value, 1e-12);
    let t = r.face_travel.as_ref().unwrap();
    close(t.hi, 2.0 * H / BETA_DEG.to_radians(), 1e-6);
    assert_eq!(
        w.note,
        format!(
            "contact travels from {} to {} m along the face",
            g6(t.lo),
            g6(t.hi)
        )
    );
    assert!(check(&r, "undercut ranges").ok);
}

/// Contact force N = m ω² s″ + c ω s′ + F₀ + k s under a translating
/// flat face, and the jump speed ω² = min (F₀ + k s)/(m |s″|) where
/// s″ < 0, in rev/min; a redline above it fails.
#[test]
fn contact_force_and_jump_speed_are_the_closed_form() {
    let (m, k, f0, rpm) = (0.2, 2000.0, 20.0, 600.0);
    let omega = rpm * TAU / 60.0;
    let dynamics =
        format!("[dynamics]\nmass = {m}\nspring_rate = {k}\npreload = {f0}\nspeed_rpm = {rpm}\n");
    let d = design("type = \"translating-flat\"", &dynamics);
    let r = analyse(&d).unwrap();
    let (least, _) = dense(
        |t| {
            let [s, _, a] = motion(t);
            m * omega * omega * a + f0 + k * s
        },
        true,
    );
    let c = check(&r, "least contact force at 600 rpm");
    close(c.value, least, 1e-4);
    assert_eq!(
        (c.limit, c.margin, c.ok),
        (Some(0.0), Some(c.value), c.value > 0.0)
    );
    let (jump2, _) = dense(
        |t| {
            let [s, _, a] = motion(t);
            if a < 0.0 {
                (f0 + k * s) / (m * -a)
            } else {
                f64::INFINITY
            }
        },
        true,
    );
    let jump_rpm = jump2.sqrt() * 60.0 / TAU;
    let j = check(&r, "jump speed");
    close(j.value, jump_rpm, 1e-6);
    assert!(j.ok && j.unit == "rpm");

    let red = (jump_rpm + 100.0).round();
    let d = design(
        "type = \"translating-flat\"",
        &format!("{dynamics}redline_rpm = {red}\n"),
    );
    let r = analyse(&d).unwrap();
    let j = check(&r, "jump speed vs redline");
    assert!(!j.ok);
    close(j.limit.unwrap(), red, 1e-15);
    close(j.margin.unwrap(), jump_rpm - red, 1e-4);
}

/// A helical spring: k = G d⁴/(8 D³ N_a), solid height N_t d, the
/// clash margin L_i − h − N_t d, the surge frequency ½√(k/m_s) with
/// m_s = ρ π² d² D N_a / 4, over the forcing frequency.
#[test]
fn spring_checks_are_the_spring_formulas() {
    let (wire, dm, na, nt, free, inst): (f64, f64, f64, f64, f64, f64) =
        (0.003, 0.02, 6.0, 8.0, 0.06, 0.05);
    let (g, rho) = (79.3e9, 7800.0);
    let text = format!(
        "[dynamics]\nmass = 0.1\nspeed_rpm = 1200\n[spring]\nwire_diameter = {wire}\n\
         mean_diameter = {dm}\nactive_coils = {na}\ntotal_coils = {nt}\nfree_length = {free}\n\
         installed_length = {inst}\nshear_modulus = {g}\ndensity = {rho}\n\
         [limits]\nmin_coil_clearance = 0.02\n"
    );
    let r = analyse(&design("type = \"translating-flat\"", &text)).unwrap();
    let k = g * wire.powi(4) / (8.0 * dm.powi(3) * na);
    let spring = r.sizing.spring.as_ref().unwrap();
    close(spring.installed.rate, k, 1e-12);
    close(spring.installed.preload, k * (free - inst), 1e-12);
    let clash = inst - H - nt * wire;
    let c = check(&r, "spring coil-clash margin");
    close(c.value, clash, 1e-9);
    // The clearance asked for is more than there is: fails by the rest.
    assert!(!c.ok);
    close(c.margin.unwrap(), clash - 0.02, 1e-9);
    let ms = rho * PI * PI * wire * wire * dm * na / 4.0;
    let ratio = 0.5 * (k / ms).sqrt() / (1200.0 / 60.0);
    let s = check(&r, "spring surge / forcing frequency at 1200 rpm");
    close(s.value, ratio, 1e-9);
    assert_eq!(s.limit, Some(13.0));
    close(s.margin.unwrap(), ratio - 13.0, 1e-9);
    assert_eq!(s.ok, ratio >= 13.0);
}

/// Hertz line contact of the cam (radius R_b + s + s″) on the flat face:
/// p_max = √(F E*/(π L ρ)) with E* of two steels, at the angle the report
/// names; over the allowable it fails by the difference in MPa.
#[test]
fn contact_stress_is_the_hertz_formula() {
    let (m, k, f0, rpm, width) = (0.2, 2000.0, 20.0, 600.0, 0.01);
    let text = format!(
        "[dynamics]\nmass = {m}\nspring_rate = {k}\npreload = {f0}\nspeed_rpm = {rpm}\n\
         [contact]\nwidth = {width}\n"
    );
    let r = analyse(&design("type = \"translating-flat\"", &text)).unwrap();
    let (e, nu) = (207e9, 0.292);
    let modulus = 1.0 / (2.0 * (1.0 - nu * nu) / e);
    let c = check(&r, "Hertz contact stress at 600 rpm");
    let at = c.at_deg.unwrap().to_radians();
    let omega = rpm * TAU / 60.0;
    let [s, _, a] = motion(at);
    let force = m * omega * omega * a + f0 + k * s;
    let p = (force * modulus / (PI * width * (RB + s + a))).sqrt();
    close(r.sizing.contact.as_ref().unwrap().modulus, modulus, 1e-12);
    close(c.value, p / 1e6, 1e-9);
    assert_eq!(
        (c.unit.as_str(), c.limit, c.margin, c.ok),
        ("MPa", None, None, true)
    );

    // An allowable of half the stress fails by the other half.
    let allowable = 0.5 * p;
    let text = format!("{text}[limits]\nmax_contact_stress = {allowable}\n");
    let r = analyse(&design("type = \"translating-flat\"", &text)).unwrap();
    let c = check(&r, "Hertz contact stress");
    assert!(!c.ok && !r.ok());
    close(c.limit.unwrap(), allowable / 1e6, 1e-12);
    close(c.margin.unwrap(), -0.5 * p / 1e6, 1e-9);
}

/// A tool rounder than the tightest concave part of the indexing
/// example's cam cannot cut it; a sharper one can.
#[test]
fn tool_undercut_where_concave_tighter_than_the_tool() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/cam_design_indexing.toml");
    let d = load_path(&path).unwrap().design;
    let cam = d.cam().unwrap();
    let tightest = (0..3600)
        .map(|k| cam.contact(TAU * k as f64 / 3600.0).rho)
        .filter(|r| *r < 0.0)
        .map(|r| -r)
        .fold(f64::INFINITY, f64::min);
    assert!(tightest.is_finite(), "the cam has a concave part");
    assert!(tool_undercut(&cam, 0.9 * tightest, 3600).is_empty());
    let bad = tool_undercut(&cam, 1.1 * tightest, 3600);
    assert!(!bad.is_empty());
    for (a, b) in &bad {
        assert!(a < b && *b <= TAU);
        let mid = 0.5 * (a + b);
        let rho = cam.contact(mid).rho;
        assert!(rho < 0.0 && -rho < 1.1 * tightest, "{rho} at {mid}");
    }
}

/// The report in millimetres: every length ×1000 (checks in m, the base
/// circles, the face travel and its note), nothing else changed; back in
/// metres it is the report again.
#[test]
fn in_units_millimetres_and_back() {
    let d = design(
        "type = \"translating-flat\"",
        "[limits]\nmin_radius = 0.001\nmax_face_width = 0.05\nbase_radius_search = [0.01, 0.05]\n\
         [dynamics]\nmass = 0.2\nspring_rate = 2000\npreload = 20\nspeed_rpm = 600\n",
    );
    let m = analyse(&d).unwrap();
    assert_eq!(m.units, "m");
    let mm = m.in_units("mm").unwrap();
    assert_eq!(mm.units, "mm");
    assert_eq!(mm.base_radius, RB * 1000.0);
    assert_eq!(
        mm.smallest_base_radius,
        m.smallest_base_radius.map(|r| r * 1000.0)
    );
    for (a, b) in m.checks.iter().zip(&mm.checks) {
        if a.unit == "m" {
            assert_eq!(b.unit, "mm");
            assert_eq!(b.value, a.value * 1000.0);
            assert_eq!(b.limit, a.limit.map(|v| v * 1000.0));
            assert_eq!(b.margin, a.margin.map(|v| v * 1000.0));
        } else {
            assert_eq!(a, b);
        }
    }
    let t = mm.face_travel.as_ref().unwrap();
    assert_eq!(t.hi, m.face_travel.as_ref().unwrap().hi * 1000.0);
    assert_eq!(
        check(&mm, "face width needed").note,
        format!(
            "contact travels from {} to {} mm along the face",
            g6(t.lo),
            g6(t.hi)
        )
    );
    assert_eq!(mm.sizing, m.sizing);
    assert_eq!(mm.in_units("mm").unwrap(), mm);

    // Back in metres: the same report, to rounding.
    let back = mm.in_units("m").unwrap();
    assert_eq!(back.units, "m");
    assert_eq!(back.checks.len(), m.checks.len());
    for (a, b) in m.checks.iter().zip(&back.checks) {
        assert_eq!(
            (&a.name, &a.unit, &a.note, a.ok),
            (&b.name, &b.unit, &b.note, b.ok)
        );
        close(b.value, a.value, 1e-15);
        if let (Some(x), Some(y)) = (a.margin, b.margin) {
            close(y, x, 1e-15);
        }
    }
    close(back.base_radius, RB, 1e-15);
    assert!(m.in_units("in").unwrap_err().contains("'in'"));
}

/// Python's `format(v, ".6g")`, for the notes compared here (fixed
/// notation for the figures of these tests).
fn g6(v: f64) -> String {
    let mag = if v == 0.0 {
        0
    } else {
        v.abs().log10().floor() as i32
    };
    let decimals = (5 - mag).max(0) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A one-mass train on a link far stiffer than the spring moves with the
/// program: its least dynamic contact force is the rigid follower's
/// m ω² s″ + F₀ + k s, its residual vibration nearly nothing; past the
/// residual limit it fails by the difference.
#[test]
fn stiff_train_vibration_is_the_rigid_follower() {
    let (m, k, f0, rpm) = (0.2, 2000.0, 20.0, 600.0);
    let omega = rpm * TAU / 60.0;
    let text = format!(
        "[dynamics]\nmass = {m}\nspring_rate = {k}\npreload = {f0}\nspeed_rpm = {rpm}\n\
         [vibration]\nstiffness = [1e9]\ndamping = [200.0]\n\
         [limits]\nmax_residual_vibration = 1e-12\n"
    );
    let r = analyse(&design("type = \"translating-flat\"", &text)).unwrap();
    let (least, _) = dense(
        |t| {
            let [s, _, a] = motion(t);
            m * omega * omega * a + f0 + k * s
        },
        true,
    );
    let c = check(&r, "least dynamic contact force at 600 rpm (1-mass train)");
    let v = r.sizing.vibration.as_ref().unwrap();
    // The link's force k₁ x differs from the rigid one by its ringing:
    // at most k₁ times the largest deviation.
    assert!(
        (c.value - least).abs() <= 1e9 * v.max_deviation,
        "{} vs {least}",
        c.value
    );
    assert_eq!(
        (c.limit, c.margin, c.ok),
        (Some(0.0), Some(c.value), c.value > 0.0)
    );
    assert_eq!(v.min_contact, c.value);
    // Deflection of the link under the largest force: |N|/k₁ at most.
    assert!(v.max_deviation < 1e-6, "{}", v.max_deviation);
    assert_eq!(v.residual.len(), 2);
    for x in &v.residual {
        let c = check(
            &r,
            &format!("residual vibration after segment {}", x.segment),
        );
        assert_eq!((c.value, c.unit.as_str()), (x.amplitude, "m"));
        assert!(c.value < 1e-6);
        assert_eq!(c.margin, Some(1e-12 - x.amplitude));
        assert_eq!(c.ok, x.amplitude <= 1e-12);
    }
}
