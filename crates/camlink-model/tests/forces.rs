//! `[[forces]]`: every force type loads; defaults and errors.

use camlink_core::force::ForceKind;
use camlink_model::{load_str, Format};

const MODEL: &str = r#"
[parameters]
k = 250

[[bodies]]
name = "arm"
position = [0.5, 0]
mass = 2
inertia = 0.05
centroid = [0.1, 0]
points = { tip = [0.5, 0] }

[[bodies]]
name = "block"
position = [1.5, 0]
mass = 1

[[joints]]
type = "revolute"
body_i = "ground"
body_j = "arm"
point_j = [-0.5, 0]

[[forces]]
type = "point_force"
name = "push"
body = "arm"
point = "tip"
fy = "-10*sin(2*pi*t)"
local = true

[[forces]]
type = "torque"
body = "arm"
torque = 3

[[forces]]
type = "tsda"
name = "spring"
body_i = "arm"
point_i = "tip"
body_j = "block"
stiffness = "k"
damping = 2

[[forces]]
type = "rsda"
body_i = "ground"
body_j = "arm"
damping = 0.1
"#;

#[test]
fn every_force_type_loads() {
    let m = load_str(MODEL, Format::Toml, "forces.toml").unwrap().model;
    assert_eq!(m.forces.len(), 4);
    let names: Vec<&str> = m.forces.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["push", "torque_1", "spring", "rsda_3"]);
    match &m.forces[0].kind {
        ForceKind::PointForce(p) => {
            assert_eq!(p.s, [0.5, 0.0]);
            assert!(p.local);
            assert_eq!(p.f[0].value(0.3), 0.0);
            assert!((p.f[1].value(0.25) + 10.0).abs() < 1e-12);
        }
        k => panic!("{k:?}"),
    }
    match &m.forces[2].kind {
        ForceKind::Tsda(s) => {
            assert_eq!(s.stiffness, 250.0);
            assert_eq!(s.damping, 2.0);
            // Free length: the initial distance from the tip (1, 0) to the block (1.5, 0).
            assert!((s.free_length - 0.5).abs() < 1e-12);
        }
        k => panic!("{k:?}"),
    }
    match &m.forces[3].kind {
        ForceKind::Rsda(r) => {
            assert_eq!((r.stiffness, r.damping, r.free_angle), (0.0, 0.1, 0.0));
        }
        k => panic!("{k:?}"),
    }
}

#[test]
fn bad_forces_name_the_field() {
    let bad = MODEL.replace("stiffness = \"k\"", "stiffness = -1");
    let e = load_str(&bad, Format::Toml, "f.toml")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("forces[2].stiffness") && e.contains("≥ 0"),
        "{e}"
    );
    let bad = MODEL.replace("body = \"arm\"\ntorque", "body = \"amr\"\ntorque");
    let e = load_str(&bad, Format::Toml, "f.toml")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("forces[1].body") && e.contains("did you mean 'arm'"),
        "{e}"
    );
    let bad = MODEL.replace("torque = 3", "torque = 3\nspeed = 1");
    let e = load_str(&bad, Format::Toml, "f.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("speed"), "{e}");
    let bad = MODEL.replace("name = \"spring\"", "name = \"push\"");
    let e = load_str(&bad, Format::Toml, "f.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("duplicate force name 'push'"), "{e}");
}
