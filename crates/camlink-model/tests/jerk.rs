//! The jerk channels of kinematic analysis (`jerk = true`) against closed
//! forms: the four-bar's rocker from Freudenstein's equation, differentiated
//! exactly by the expression jets of `camlink-expr`.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use camlink_core::kinematics::run;
use camlink_core::run::{time_grid, Settings, Table};
use camlink_expr::Expr;
use camlink_model::{load_path, load_str, Format, Loaded};

fn examples_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// Runs the file's kinematic analysis with the jerk.
fn run_with_jerk(loaded: &Loaded) -> Table {
    let a = &loaded.analysis;
    let times = time_grid(a.t_end.unwrap(), a.step.unwrap()).unwrap();
    let settings = Settings {
        tol: a.tol,
        max_iter: a.max_iter,
        jerk: true,
    };
    let points = loaded.point_outputs().unwrap();
    let mut table = Table::default();
    run(&loaded.model, &times, &settings, &points, &mut table).unwrap();
    table
}

fn channel(t: &Table, name: &str) -> Vec<f64> {
    t.channel(name)
        .unwrap_or_else(|| panic!("no channel {name} in {:?}", t.channels))
}

/// Freudenstein's closed form of the rocker angle θ4 (open branch) as an
/// expression in t, for a crank angle θ2(t) given as an expression:
/// with K1 = d/a, K2 = d/c, K3 = (a² − b² + c² + d²)/(2ac),
/// A = cos θ2 − K1 − K2 cos θ2 + K3, B = −2 sin θ2,
/// C = K1 − (K2 + 1) cos θ2 + K3: θ4 = 2 atan2(−B − √(B² − 4AC), 2A).
fn freudenstein_theta4(theta2: &str) -> String {
    let k1 = "(d/a)";
    let k2 = "(d/c)";
    let k3 = "((a^2 - b^2 + c^2 + d^2)/(2*a*c))";
    let th = format!("({theta2})");
    let a = format!("(cos({th}) - {k1} - {k2}*cos({th}) + {k3})");
    let b = format!("(-2*sin({th}))");
    let c = format!("({k1} - ({k2} + 1)*cos({th}) + {k3})");
    format!("2*atan2(-{b} - sqrt({b}^2 - 4*{a}*{c}), 2*{a})")
}

fn params() -> HashMap<String, f64> {
    [
        ("d", 0.4),
        ("a", 0.12),
        ("b", 0.38),
        ("c", 0.3),
        ("w", 2.0 * std::f64::consts::PI),
        ("theta0", 0.3),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect()
}

/// Compares the rocker's φ and its third derivative, and the jerk of the
/// rocker point B = O4 + c(cos θ4, sin θ4), with the closed form at every
/// step. `scale` is the size of the jerks over the run (rad/s³, m/s³).
fn check_four_bar(table: &Table, theta2: &str, scale: f64) {
    let p = params();
    let theta4 = Expr::parse_with(&freudenstein_theta4(theta2), Some("t"), &p).unwrap();
    let bx = Expr::parse_with(
        &format!("d + c*cos({})", freudenstein_theta4(theta2)),
        Some("t"),
        &p,
    )
    .unwrap();
    let by = Expr::parse_with(
        &format!("c*sin({})", freudenstein_theta4(theta2)),
        Some("t"),
        &p,
    )
    .unwrap();
    let crank = Expr::parse_with(theta2, Some("t"), &p).unwrap();
    let phi = channel(table, "rocker.phi");
    let jphi = channel(table, "rocker.jphi");
    let (jx, jy) = (channel(table, "rocker.B.jx"), channel(table, "rocker.B.jy"));
    let crank_j = channel(table, "crank.jphi");
    let mut worst = 0.0f64;
    for (k, &t) in table.t.iter().enumerate() {
        let want = theta4.jet(t);
        // Same angle up to whole turns.
        let turns = ((phi[k] - want[0]) / std::f64::consts::TAU).round();
        assert!(
            (phi[k] - want[0] - turns * std::f64::consts::TAU).abs() < 1e-9,
            "θ4 at t = {t}: {} vs {}",
            phi[k],
            want[0]
        );
        for (got, want, what) in [
            (jphi[k], want[3], "rocker.jphi"),
            (jx[k], bx.jet(t)[3], "rocker.B.jx"),
            (jy[k], by.jet(t)[3], "rocker.B.jy"),
            (crank_j[k], crank.jet(t)[3], "crank.jphi"),
        ] {
            let err = (got - want).abs();
            worst = worst.max(err / scale);
            assert!(
                err <= 1e-7 * want.abs().max(scale),
                "{what} at t = {t}: {got} vs closed form {want}"
            );
        }
    }
    assert!(worst > 0.0 || scale > 0.0);
}

/// The example file at constant crank speed: 401 crank angles over two
/// turns.
#[test]
fn four_bar_rocker_jerk_matches_freudenstein() {
    let mut loaded = load_path(&examples_dir().join("four_bar.toml")).unwrap();
    loaded.analysis.jerk = true;
    let table = run_with_jerk(&loaded);
    assert_eq!(table.t.len(), 401);
    let jphi = channel(&table, "rocker.jphi");
    let big = jphi.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    // The rocker's jerk is of order ω³ ≈ 250 rad/s³ times the link ratios.
    assert!(big > 10.0, "{big}");
    check_four_bar(&table, "theta0 + w*t", big);
}

/// A crank that speeds up and slows down: the crank's own jerk is not zero,
/// so every term of η enters.
#[test]
fn four_bar_with_a_varying_crank_speed() {
    let text = std::fs::read_to_string(examples_dir().join("four_bar.toml")).unwrap();
    let crank = "theta0 + w*t + 0.4*sin(3*t)";
    let text = text
        .replace("f = \"theta0 + w*t\"", &format!("f = \"{crank}\""))
        .replace("t_end = 2.0 ", "t_end = 1.5 ")
        .replace("step = 0.005", "step = 0.005\njerk = true");
    let loaded = load_str(&text, Format::Toml, "four_bar_varying.toml").unwrap();
    assert!(loaded.analysis.jerk);
    let table = run_with_jerk(&loaded);
    let big = channel(&table, "rocker.jphi")
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    check_four_bar(&table, crank, big);
}

/// Without the option the run has no jerk channels; with it, the jerk
/// channels follow all the others.
#[test]
fn jerk_channels_only_when_asked_for() {
    let loaded = load_path(&examples_dir().join("four_bar.toml")).unwrap();
    let times = time_grid(0.1, 0.05).unwrap();
    let points = loaded.point_outputs().unwrap();
    let mut plain = Table::default();
    run(
        &loaded.model,
        &times,
        &Settings::default(),
        &points,
        &mut plain,
    )
    .unwrap();
    assert!(!plain.channels.iter().any(|c| c.ends_with(".jx")));
    let mut with = Table::default();
    let settings = Settings {
        jerk: true,
        ..Settings::default()
    };
    run(&loaded.model, &times, &settings, &points, &mut with).unwrap();
    let n = plain.channels.len();
    assert_eq!(with.channels[..n], plain.channels[..]);
    assert_eq!(
        with.channels[n..],
        [
            "crank.jx",
            "crank.jy",
            "crank.jphi",
            "coupler.jx",
            "coupler.jy",
            "coupler.jphi",
            "rocker.jx",
            "rocker.jy",
            "rocker.jphi",
            "coupler.P.jx",
            "coupler.P.jy",
            "rocker.B.jx",
            "rocker.B.jy",
        ]
    );
}

#[test]
fn jerk_is_refused_outside_kinematics() {
    let text = std::fs::read_to_string(examples_dir().join("four_bar.toml")).unwrap();
    let text = text.replace(
        "step = 0.005",
        "step = 0.005\njerk = true\ntype = \"inverse_dynamics\"",
    );
    let e = load_str(&text, Format::Toml, "bad.toml")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("analysis.jerk") && e.contains("kinematic"),
        "{e}"
    );
}

/// Runs a model given as TOML text with the jerk and returns the table.
fn run_text(text: &str) -> Table {
    let loaded = load_str(text, Format::Toml, "test.toml").unwrap_or_else(|e| panic!("{e}"));
    assert!(loaded.analysis.jerk);
    run_with_jerk(&loaded)
}

/// Compares `got` with `want(t)` at every step, to 1e-7 of the larger of
/// |want| and `scale`.
fn compare(table: &Table, name: &str, want: impl Fn(f64) -> f64, scale: f64) {
    let got = channel(table, name);
    for (k, &t) in table.t.iter().enumerate() {
        let w = want(t);
        assert!(
            (got[k] - w).abs() <= 1e-7 * w.abs().max(scale),
            "{name} at t = {t}: {} vs closed form {w}",
            got[k]
        );
    }
}

/// A knife-edge follower (a point follower: the tip rides the profile) on a
/// polar cam ρ(α) = R_b + s(α), translating on the vertical line through
/// the cam's pivot; the cam turns clockwise at ω, so the tip meets the
/// profile at α = π/2 + ωt and the follower's height is y = R_b + s(ωt)
/// over the rise. With the cycloidal rise of h over β,
/// s(θ) = h(θ/β − sin(2πθ/β)/2π), the jerk is y‴ = ω³ h (4π²/β³) cos(2πθ/β).
#[test]
fn knife_edge_on_a_cycloidal_cam_has_the_closed_form_jerk() {
    let (rb, h, beta, w) = (
        1.0,
        0.2,
        std::f64::consts::FRAC_PI_2,
        2.0 * std::f64::consts::PI,
    );
    let text = format!(
        r#"
[model]
name = "cycloidal knife edge"

[parameters]
Rb = {rb}
h = {h}
w = {w}

[[bodies]]
name = "cam"

[[bodies]]
name = "follower"
position = [0, {rb}]
points = {{ tip = [0, 0] }}

[[curves]]
name = "profile"
body = "cam"
source = "expression"
rho = "Rb + cycloidal(a, pi/2, 0, pi, h) - cycloidal(a, 3*pi/2, 0, 2*pi, h)"

[[joints]]
type = "revolute"
name = "shaft"
body_i = "ground"
body_j = "cam"

[[joints]]
type = "translational"
name = "guide"
body_i = "ground"
axis = [0, 1]
body_j = "follower"

[[joints]]
type = "point_follower"
name = "tip"
body_i = "follower"
point_i = "tip"
curve_j = "profile"

[[drivers]]
type = "revolute_angle"
name = "motor"
joint = "shaft"
f = "-w*t"

[analysis]
t_end = 0.24
step = 0.001
jerk = true
"#
    );
    let table = run_text(&text);
    let two_pi = 2.0 * std::f64::consts::PI;
    let s = |t: f64| {
        let th = w * t;
        rb + h * (th / beta - (two_pi * th / beta).sin() / two_pi)
    };
    // At t = 0 the rise starts: the cycloidal law's jerk jumps there, and
    // the law takes the dwell's value (0) at the start itself.
    let jerk = |t: f64| {
        if t == 0.0 {
            0.0
        } else {
            w.powi(3) * h * two_pi * two_pi / beta.powi(3) * (two_pi * w * t / beta).cos()
        }
    };
    let scale = w.powi(3) * h * two_pi * two_pi / beta.powi(3);
    compare(&table, "follower.y", s, 1.0);
    compare(&table, "follower.jy", jerk, scale);
    compare(&table, "follower.jx", |_| 0.0, scale);
    compare(&table, "cam.jphi", |_| 0.0, scale);
}

/// A roller of radius r on an eccentric circular cam (radius R, centre at e
/// from the pivot), the roller centre translating on the vertical line
/// through the pivot: |(0, y) − e(cos φ, sin φ)| = R + r gives
/// y = e sin φ + √((R + r)² − e² cos² φ), differentiated three times by the
/// expression jets (φ = ωt).
#[test]
fn roller_on_an_eccentric_cam_matches_the_closed_form() {
    let text = r#"
[model]
name = "eccentric cam, in-line roller"

[parameters]
R = 0.5
e = 0.2
r = 0.15

[[bodies]]
name = "cam"

[[bodies]]
name = "follower"
position = [0, 0.7]

[[curves]]
name = "disc"
body = "cam"
source = "circle"
centre = ["e", 0]
radius = "R"

[[curves]]
name = "roller"
body = "follower"
source = "circle"
radius = "r"

[[joints]]
type = "revolute"
name = "shaft"
body_i = "ground"
body_j = "cam"

[[joints]]
type = "translational"
name = "guide"
body_i = "ground"
axis = [0, 1]
body_j = "follower"

[[joints]]
type = "cam_follower"
name = "contact"
curve_i = "disc"
curve_j = "roller"

[[drivers]]
type = "revolute_angle"
name = "motor"
joint = "shaft"
f = "3*t + 0.5*t^2"

[analysis]
t_end = 2.5
step = 0.005
jerk = true
"#;
    let table = run_text(text);
    let p: HashMap<String, f64> = [("R", 0.5), ("e", 0.2), ("r", 0.15)]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
    let phi = "(3*t + 0.5*t^2)";
    let y = Expr::parse_with(
        &format!("e*sin({phi}) + sqrt((R + r)^2 - e^2*cos({phi})^2)"),
        Some("t"),
        &p,
    )
    .unwrap();
    let scale = channel(&table, "follower.jy")
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 1.0, "{scale}");
    compare(&table, "follower.y", |t| y.jet(t)[0], 1.0);
    compare(&table, "follower.jy", |t| y.jet(t)[3], scale);
    compare(&table, "cam.jphi", |_| 0.0, scale);
}

/// The flat-faced follower example: the face height over an eccentric
/// circle is y = e sin ωt + R, so y‴ = −e ω³ cos ωt.
#[test]
fn flat_follower_example_jerk_matches_the_closed_form() {
    let mut loaded = load_path(&examples_dir().join("cam_eccentric_flat.toml")).unwrap();
    loaded.analysis.jerk = true;
    let table = run_with_jerk(&loaded);
    let (e, r, w) = (0.01, 0.04, 2.0 * std::f64::consts::PI * 600.0 / 60.0);
    compare(&table, "tappet.y", |t| e * (w * t).sin() + r, 0.05);
    let scale = e * w.powi(3);
    compare(&table, "tappet.jy", |t| -scale * (w * t).cos(), scale);
    compare(&table, "tappet.jphi", |_| 0.0, scale);
}
