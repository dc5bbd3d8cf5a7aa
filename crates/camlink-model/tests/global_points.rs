//! Bodies given by the global positions of their points (issue 30,
//! finding 1): the frame rule, and models equal to their frame-coordinate
//! versions.

use camlink_core::kinematics::run;
use camlink_core::run::{time_grid, Settings, Table};
use camlink_model::{load_path, load_str, Format, Loaded};

fn examples() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn kinematics(l: &Loaded) -> Table {
    let a = &l.analysis;
    let times = time_grid(a.t_end.unwrap(), a.step.unwrap()).unwrap();
    let mut table = Table::default();
    // Two descriptions of one mechanism take different Newton paths; a
    // tolerance near rounding makes both land on the same positions.
    let settings = Settings {
        tol: 1e-14,
        ..Settings::default()
    };
    run(
        &l.model,
        &times,
        &settings,
        &l.point_outputs().unwrap(),
        &mut table,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(table.t.len(), times.len());
    table
}

fn largest_difference(a: &Table, b: &Table, channel: &str) -> f64 {
    let (a, b) = (a.channel(channel).unwrap(), b.channel(channel).unwrap());
    a.iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The Whitworth quick-return of `examples/whitworth_global.toml` with each
/// body frame placed by hand at a joint, along the link.
const WHITWORTH_FRAMES: &str = r#"
[parameters]
d = 0.05
r = 0.1
R = 0.08
l = 0.3
w = "2*pi"
b0 = "atan2(d, r)"
Bx = "-R*cos(b0)"
By = "-R*sin(b0)"
Cx = "Bx - sqrt(l*l - By*By)"

[ground]
points = { O4 = [0, 0], O2 = [0, "d"] }

[[bodies]]
name = "crank"
position = [0, "d"]
points = { O2 = [0, 0], A = ["r", 0] }

[[bodies]]
name = "lever"
angle = "b0"
points = { O4 = [0, 0], A = ["hypot(r, d)", 0], B = ["-R", 0] }

[[bodies]]
name = "rod"
position = ["Bx", "By"]
angle = "atan2(-By, Cx - Bx)"
points = { B = [0, 0], C = ["l", 0] }

[[bodies]]
name = "ram"
position = ["Cx", 0]
points = { C = [0, 0] }

[[joints]]
name = "O2"
type = "revolute"
body_i = "ground"
point_i = "O2"
body_j = "crank"
point_j = "O2"

[[joints]]
name = "O4"
type = "revolute"
body_i = "ground"
point_i = "O4"
body_j = "lever"
point_j = "O4"

[[joints]]
name = "slot"
type = "revolute_translational"
body_i = "crank"
point_i = "A"
body_j = "lever"
point_j = "O4"
axis = [1, 0]
offset = 0

[[joints]]
name = "B"
type = "revolute"
body_i = "lever"
point_i = "B"
body_j = "rod"
point_j = "B"

[[joints]]
name = "C"
type = "revolute"
body_i = "rod"
point_i = "C"
body_j = "ram"
point_j = "C"

[[joints]]
name = "guide"
type = "translational"
body_i = "ground"
point_i = [0, 0]
axis = [1, 0]
body_j = "ram"
point_j = "C"
angle = 0

[[drivers]]
name = "motor"
type = "revolute_angle"
joint = "O2"
f = "w*t"

[analysis]
t_end = 1.0
step = 0.005
points = ["ram.C", "lever.B", "crank.A"]
"#;

#[test]
fn issue30_whitworth_global_matches_its_frame_version() {
    let global = load_path(&examples().join("whitworth_global.toml")).unwrap();
    assert!(
        global.model.warnings.is_empty(),
        "{:?}",
        global.model.warnings
    );
    let frames = load_str(WHITWORTH_FRAMES, Format::Toml, "whitworth_frames.toml").unwrap();
    let (a, b) = (kinematics(&global), kinematics(&frames));
    // Points do not depend on where the frames are; the crank's and the
    // ram's frames start with the same angle in both, so their channels
    // agree too.
    let mut checked = 0;
    for channel in &a.channels {
        let frame_free = [
            "ram.",
            "crank.phi",
            "crank.omega",
            "crank.alpha",
            "lever.B.",
            "crank.A.",
            "ram.C.",
        ]
        .iter()
        .any(|p| channel.starts_with(p));
        if channel == "t" || !frame_free {
            continue;
        }
        let d = largest_difference(&a, &b, channel);
        assert!(d < 1e-12, "{channel}: {d}");
        checked += 1;
    }
    assert!(
        checked >= 20,
        "{checked} channels compared: {:?}",
        a.channels
    );
    // Closed form: the lever angle β = atan2(d + r sin θ, r cos θ) with
    // θ = w t, B = −R (cos β, sin β), C_x = B_x − √(l² − B_y²).
    let (d, r, big_r, l) = (0.05f64, 0.1f64, 0.08f64, 0.3f64);
    let ram = a.channel("ram.C.x").unwrap();
    for (k, &t) in a.t.iter().enumerate() {
        let th = 2.0 * std::f64::consts::PI * t;
        let beta = (d + r * th.sin()).atan2(r * th.cos());
        let (bx, by) = (-big_r * beta.cos(), -big_r * beta.sin());
        let cx = bx - (l * l - by * by).sqrt();
        assert!((ram[k] - cx).abs() < 1e-12, "t = {t}: {} vs {cx}", ram[k]);
    }
    // The ram's stroke is 2R.
    let x = a.channel("ram.x").unwrap();
    let (lo, hi) = x
        .iter()
        .fold((f64::MAX, f64::MIN), |(l, h), &v| (l.min(v), h.max(v)));
    assert!((hi - lo - 0.16).abs() < 1e-4, "stroke {}", hi - lo);
}

/// A pendulum arm given by `body` (TOML lines of its [[bodies]] entry).
fn arm(body: &str) -> Loaded {
    let text = format!(
        r#"
[ground]
points = {{ O = [1, 2] }}

[[bodies]]
name = "arm"
{body}

[[joints]]
name = "pivot"
type = "revolute"
body_i = "ground"
point_i = "O"
body_j = "arm"
point_j = "O"
"#
    );
    load_str(&text, Format::Toml, "arm.toml").unwrap_or_else(|e| panic!("{e}"))
}

fn point(l: &Loaded, name: &str) -> [f64; 2] {
    l.model.bodies[1]
        .points
        .iter()
        .find(|p| p.name == name)
        .unwrap()
        .s
}

#[test]
fn issue30_global_points_frame_rule() {
    // Without position and angle: the frame at the mean of the points,
    // φ = 0; the centroid is global too.
    let l = arm("global_points = { O = [1, 2], P = [3, 2], Q = [2, 5] }\ncentroid = [2, 3]");
    let b = &l.model.bodies[1];
    assert_eq!(b.q0, [2.0, 3.0, 0.0]);
    assert_eq!(point(&l, "O"), [-1.0, -1.0]);
    assert_eq!(point(&l, "P"), [1.0, -1.0]);
    assert_eq!(point(&l, "Q"), [0.0, 2.0]);
    assert_eq!(b.centroid, [0.0, 0.0]);
    // With position and angle: that frame, the points converted into it.
    let l = arm("global_points = { O = [1, 2], P = [1, 4] }\nposition = [1, 2]\nangle = \"pi/2\"");
    assert_eq!(l.model.bodies[1].q0[..2], [1.0, 2.0]);
    let p = point(&l, "P");
    assert!((p[0] - 2.0).abs() < 1e-15 && p[1].abs() < 1e-15, "{p:?}");
}

#[test]
fn issue30_global_points_and_points_are_exclusive() {
    let text = r#"
[[bodies]]
name = "arm"
points = { O = [0, 0] }
global_points = { P = [1, 0] }
"#;
    let e = load_str(text, Format::Toml, "arm.toml").unwrap_err();
    assert_eq!(e.field.as_deref(), Some("bodies[0].global_points"), "{e}");
    assert!(e.message.contains("not both"), "{e}");
}
