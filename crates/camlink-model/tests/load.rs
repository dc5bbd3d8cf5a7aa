//! Valid model files load into the expected core model.

use std::path::{Path, PathBuf};

use camlink_core::constraint::relative::RelCoord;
use camlink_core::{Constraint, Equations, TimeFn};
use camlink_model::{load_path, load_str, AnalysisSpec, Format};

fn models() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/models")
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-12
}

#[test]
fn four_bar_toml_and_json_agree() {
    let t = load_path(&models().join("four_bar.toml")).unwrap();
    let j = load_path(&models().join("four_bar.json")).unwrap();
    assert_eq!(t.model.bodies, j.model.bodies);
    assert_eq!(t.analysis, j.analysis);
    let names = |m: &camlink_core::Model| {
        m.joints
            .iter()
            .map(|j| (j.name.clone(), j.constraint.kind(), j.driver))
            .collect::<Vec<_>>()
    };
    assert_eq!(names(&t.model), names(&j.model));
}

#[test]
fn four_bar_contents() {
    let l = load_path(&models().join("four_bar.toml")).unwrap();
    let m = &l.model;
    assert_eq!(m.name, "four_bar");
    assert_eq!(m.bodies.len(), 4);
    assert_eq!(m.bodies[0].name, "ground");
    assert_eq!(m.bodies[0].point("C"), Some([3.0, 0.0]));
    let crank = &m.bodies[1];
    assert!(close(crank.q0[2], 60f64.to_radians()));
    assert!(close(crank.inertia, 1.0 / 12.0));
    assert_eq!(m.bodies[2].point("P"), Some([1.3, 0.5]));
    assert_eq!(m.joints.len(), 5);
    let motor = m.joint("motor").unwrap();
    assert!(motor.driver);
    match &motor.constraint {
        Constraint::RelativeCoord(c) => {
            assert_eq!(c.coord, RelCoord::Phi);
            assert_eq!((c.body_i.0, c.body_j.0), (0, 1));
            let [f, fd, ..] = c.f.jet(0.5);
            assert!(close(f, 60f64.to_radians() + std::f64::consts::PI));
            assert!(close(fd, 2.0 * std::f64::consts::PI));
        }
        other => panic!("motor is {other:?}"),
    }
    assert_eq!(
        l.analysis,
        AnalysisSpec {
            t_end: Some(1.0),
            step: Some(0.01),
            times: None,
            tol: 1e-10,
            max_iter: 25,
            points: vec!["coupler.P".into(), "crank.A".into()],
            ..AnalysisSpec::default()
        }
    );
}

const EVERY_TYPE: &str = r#"
[model]
name = "zoo"

[parameters]
R = 0.5

[ground]
points = { O = [0, 0], Q = [2, 1] }

[[bodies]]
name = "a"
position = [1, 0]
angle = 0.3
points = { P = [0.5, 0] }

[[bodies]]
name = "b"
position = [2, 1]
angle = 0.7

[[bodies]]
name = "c"
position = [0, 3]

[[joints]]
name = "rev"
type = "revolute"
body_i = "ground"
body_j = "a"
point_j = [-1, 0]

[[joints]]
name = "slide"
type = "translational"
body_i = "a"
point_i = "P"
axis = [2, 0]
body_j = "b"

[[joints]]
type = "revolute_revolute"
body_i = "a"
point_i = "P"
body_j = "c"

[[joints]]
type = "revolute_translational"
body_i = "c"
body_j = "ground"
point_j = "O"
axis = [1, 0]

[[joints]]
type = "absolute_x"
body = "c"

[[joints]]
type = "absolute_y"
body = "c"
value = 3

[[joints]]
type = "absolute_phi"
body = "b"

[[joints]]
type = "absolute_distance"
body = "a"
point = "P"
ground_point = "Q"

[[joints]]
type = "relative_x"
body_i = "a"
body_j = "b"

[[joints]]
type = "relative_y"
body_i = "a"
body_j = "b"

[[joints]]
type = "relative_phi"
body_i = "a"
body_j = "c"

[[joints]]
type = "relative_distance"
body_i = "b"
body_j = "c"

[[joints]]
type = "gear"
body_i = "a"
radius_i = "R"
body_j = "b"
radius_j = "2*R"
kind = "internal"

[[joints]]
type = "rack_pinion"
body_i = "b"
radius = "R"
body_j = "c"
axis = [1, 1]

[[drivers]]
type = "absolute_x"
body = "a"
f = "t"

[[drivers]]
type = "absolute_y"
body = "a"
point = "P"
f = 1

[[drivers]]
type = "absolute_phi"
body = "a"
f = "sin(t)"

[[drivers]]
type = "absolute_distance"
body = "a"
ground_point = [1, 1]
f = "1 + t"

[[drivers]]
type = "relative_x"
body_i = "a"
body_j = "b"
f = "t"

[[drivers]]
type = "relative_y"
body_i = "a"
body_j = "b"
f = "t"

[[drivers]]
type = "relative_phi"
body_i = "a"
body_j = "b"
f = "t"

[[drivers]]
type = "relative_distance"
body_i = "a"
body_j = "b"
f = "2 + t"

[[drivers]]
type = "revolute_angle"
joint = "rev"
f = "R*t"

[[drivers]]
type = "translational_travel"
joint = "slide"
f = "0.1*t"

[analysis]
times = [0, 0.5, "2*R"]
tol = 1e-8
max_iter = 10
"#;

#[test]
fn every_joint_and_driver_type_loads() {
    let l = load_str(EVERY_TYPE, Format::Toml, "zoo.toml").unwrap();
    let m = &l.model;
    assert_eq!(m.joints.len(), 24);
    assert_eq!(m.joints.iter().filter(|j| j.driver).count(), 10);
    assert_eq!(l.analysis.times, Some(vec![0.0, 0.5, 1.0]));
    assert_eq!((l.analysis.tol, l.analysis.max_iter), (1e-8, 10));

    // Default names and defaults from the initial configuration.
    let slide = m.joint("slide").unwrap();
    match &slide.constraint {
        Constraint::Translational(c) => {
            assert_eq!(c.v_i, [1.0, 0.0]);
            assert!(close(c.angle, 0.4));
        }
        other => panic!("{other:?}"),
    }
    match &m.joint("revolute_revolute_2").unwrap().constraint {
        // P of a at (1 + 0.5 cos 0.3, 0.5 sin 0.3); c at (0, 3).
        Constraint::RevoluteRevolute(c) => {
            let p = [1.0 + 0.5 * 0.3f64.cos(), 0.5 * 0.3f64.sin()];
            assert!(close(
                c.length,
                (p[0].powi(2) + (p[1] - 3.0).powi(2)).sqrt()
            ));
        }
        other => panic!("{other:?}"),
    }
    match &m.joint("revolute_translational_3").unwrap().constraint {
        Constraint::RevoluteTranslational(c) => assert!(close(c.offset, 3.0)),
        other => panic!("{other:?}"),
    }
    match &m.joint("absolute_x_4").unwrap().constraint {
        Constraint::AbsoluteCoord(c) => assert!(matches!(c.f, TimeFn::Const(v) if v == 0.0)),
        other => panic!("{other:?}"),
    }
    match &m.joint("gear_12").unwrap().constraint {
        Constraint::Gear(c) => assert_eq!((c.radius_i, c.radius_j), (0.5, 1.0)),
        other => panic!("{other:?}"),
    }
    match &m.joint("translational_travel_driver_9").unwrap().constraint {
        Constraint::RelativeCoord(c) => assert_eq!(c.coord, RelCoord::Along([1.0, 0.0])),
        other => panic!("{other:?}"),
    }
}

#[test]
fn defaults_of_a_minimal_file() {
    let l = load_str(
        "[[bodies]]\nname = \"arm\"\n",
        Format::Toml,
        "dir/pendulum.toml",
    )
    .unwrap();
    assert_eq!(l.model.name, "pendulum");
    assert_eq!(l.model.gravity, [0.0, -9.81]);
    assert_eq!(l.analysis, AnalysisSpec::default());
    let b = &l.model.bodies[1];
    assert_eq!(
        (b.mass, b.inertia, b.q0, b.qd0),
        (0.0, 0.0, [0.0; 3], [0.0; 3])
    );
}

#[test]
fn json_errors_without_a_span_still_name_the_field() {
    let text = r#"{"bodies": [{"name": "arm"}], "analysis": {"points": ["arm"]}}"#;
    let err = load_str(text, Format::Json, "m.json").unwrap_err();
    assert_eq!(err.field.as_deref(), Some("analysis.points[0]"));
    assert_eq!(err.line, Some(1));
    assert!(err.message.contains("\"body.point\""), "{err}");
}
