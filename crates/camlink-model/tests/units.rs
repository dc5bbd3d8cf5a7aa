//! Model files in millimetres and degrees (`[model] units`), and the
//! quantity every output channel carries from the core (issues 28 and 30).
//!
//! The files in `tests/units/` are examples written again in mm and deg;
//! loaded, they are converted to SI, so that their runs give the SI
//! example's channels to 1e-12 of each channel's magnitude (the
//! conversions round each number once, 1e-16 relative, and the solver
//! settles on the same solution).

use std::path::{Path, PathBuf};

use camlink_core::dynamics::inverse;
use camlink_core::kinematics::run;
use camlink_core::quantity::Quantity;
use camlink_core::run::{time_grid, Settings, Table};
use camlink_model::{load_path, load_str, Format, Loaded};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The kinematics of `loaded` over its `[analysis]` grid.
fn kinematics(loaded: &Loaded) -> Table {
    let a = &loaded.analysis;
    let times = time_grid(a.t_end.unwrap(), a.step.unwrap()).unwrap();
    let settings = Settings {
        tol: a.tol,
        max_iter: a.max_iter,
        ..Settings::default()
    };
    let mut table = Table::default();
    run(
        &loaded.model,
        &times,
        &settings,
        &loaded.point_outputs().unwrap(),
        &mut table,
    )
    .unwrap_or_else(|e| panic!("{}: {e}", loaded.model.name));
    table
}

fn load(path: &Path) -> Loaded {
    load_path(path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn issue30_mm_deg_models_equal_their_si_versions() {
    for (si, mm) in [
        ("four_bar", "four_bar_mm_deg"),
        ("slider_crank", "slider_crank_mm_deg"),
        ("cam_motion_roller", "cam_motion_roller_mm_deg"),
    ] {
        let a = load(&root().join(format!("examples/{si}.toml")));
        let b = load(&root().join(format!("crates/camlink-model/tests/units/{mm}.toml")));
        assert!(
            a.model.warnings.is_empty() && b.model.warnings.is_empty(),
            "{mm}"
        );
        let (ta, tb) = (kinematics(&a), kinematics(&b));
        assert_eq!(ta.channels, tb.channels, "{mm}");
        assert_eq!(ta.quantities, tb.quantities, "{mm}");
        assert_eq!(ta.t, tb.t, "{mm}");
        for name in &ta.channels {
            let (x, y) = (ta.channel(name).unwrap(), tb.channel(name).unwrap());
            let scale = x.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
            let worst = x
                .iter()
                .zip(&y)
                .fold(0.0_f64, |m, (p, q)| m.max((p - q).abs()));
            assert!(
                worst <= 1e-12 * scale,
                "{mm}: {name} differs by {worst:e} (scale {scale:e})"
            );
        }
    }
}

#[test]
fn issue30_a_driver_in_degrees_gives_its_rates_in_degrees_per_second() {
    // θ = 90 + 360 t deg, read as rad: ω = 2π rad/s, α = 0.
    let text = r#"
[model]
units = { angle = "deg" }
[[bodies]]
name = "crank"
points = { A = [0.1, 0] }
[[joints]]
name = "O"
type = "revolute"
body_i = "ground"
body_j = "crank"
[[drivers]]
name = "motor"
type = "revolute_angle"
joint = "O"
f = "90 + 360*t"
[analysis]
t_end = 0.25
step = 0.125
"#;
    let loaded = load_str(text, Format::Toml, "deg.toml").unwrap();
    let t = kinematics(&loaded);
    let phi = t.channel("crank.phi").unwrap();
    let omega = t.channel("crank.omega").unwrap();
    let tau = std::f64::consts::TAU;
    for (k, time) in t.t.iter().enumerate() {
        assert!((phi[k] - (tau / 4.0 + tau * time)).abs() < 1e-12, "{phi:?}");
        assert!((omega[k] - tau).abs() < 1e-12, "{omega:?}");
    }
}

#[test]
fn issue30_units_that_camlink_does_not_know_are_refused_with_the_list() {
    let text = "[model]\nunits = { length = \"ft\" }\n";
    let e = load_str(text, Format::Toml, "ft.toml").unwrap_err();
    let shown = e.to_string();
    assert_eq!(e.field.as_deref(), Some("model.units.length"), "{shown}");
    assert!(shown.contains("`mm`") && shown.contains("`in`"), "{shown}");
}

#[test]
fn issue30_length_scale_names_the_lever_written_in_millimetres() {
    // The issue's quick-return: links of about 0.1 m, one written as 100
    // (millimetres meant), which turned a 1:2 quick-return into 1:1.
    let text = std::fs::read_to_string(root().join("examples/quick_return.toml")).unwrap();
    let (l, lever) = quick_return_lever(&text);
    let bad = text.replacen(&lever, &lever.replace(&l, "100"), 1);
    let loaded = load_str(&bad, Format::Toml, "quick_return.toml").unwrap();
    let w: Vec<_> = loaded
        .model
        .warnings
        .iter()
        .filter(|w| w.kind == "length_scale")
        .collect();
    assert_eq!(w.len(), 1, "{:?}", loaded.model.warnings);
    assert!(w[0].message.contains("spans 100 m"), "{}", w[0].message);
    assert!(load_str(&text, Format::Toml, "q.toml")
        .unwrap()
        .model
        .warnings
        .iter()
        .all(|w| w.kind != "length_scale"));
}

/// The value of the lever's length parameter in the quick-return example
/// and the line that sets it.
fn quick_return_lever(text: &str) -> (String, String) {
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with("L = "))
        .expect("examples/quick_return.toml sets the lever length L");
    let value = line["L = ".len()..]
        .split('#')
        .next()
        .unwrap()
        .trim()
        .to_string();
    (value, line.to_string())
}

#[test]
fn issue30_a_cam_base_circle_metres_long_is_questioned() {
    let text = std::fs::read_to_string(root().join("examples/cam_motion_roller.toml")).unwrap();
    let big = text.replace("rb = 0.03 ", "rb = 30 ");
    assert_ne!(big, text);
    let loaded = load_str(&big, Format::Toml, "cam.toml").unwrap();
    let w = loaded
        .model
        .warnings
        .iter()
        .find(|w| w.field == "curves[0].base_radius")
        .unwrap_or_else(|| panic!("{:?}", loaded.model.warnings));
    assert!(
        w.message.contains("radius 30 m: is it 30 mm (0.03 m)?"),
        "{}",
        w.message
    );
}

#[test]
fn issue28_channels_carry_their_quantities_from_where_they_are_named() {
    let q = |example: &str, inverse_dynamics: bool| -> Vec<(String, Quantity)> {
        let loaded = load(&root().join(format!("examples/{example}.toml")));
        let times = [0.0, 0.01];
        let mut table = Table::default();
        let points = loaded.point_outputs().unwrap();
        let settings = Settings::default();
        if inverse_dynamics {
            inverse::run(&loaded.model, &times, &settings, &points, &mut table).unwrap();
        } else {
            run(&loaded.model, &times, &settings, &points, &mut table).unwrap();
        }
        assert_eq!(table.channels.len(), table.quantities.len());
        table.channels.into_iter().zip(table.quantities).collect()
    };
    let of = |list: &[(String, Quantity)], name: &str| {
        list.iter()
            .find(|(n, _)| n == name)
            .unwrap_or_else(|| panic!("no {name} in {list:?}"))
            .1
    };
    let gears = q("gear_train", false);
    assert_eq!(of(&gears, "mesh12.theta"), Quantity::Angle);
    let cam = q("cam_circle_roller", true);
    assert_eq!(of(&cam, "contact.normal_force"), Quantity::Force);
    assert_eq!(of(&cam, "contact.alpha_i"), Quantity::Angle);
    assert_eq!(of(&cam, "motor.effort"), Quantity::Torque);
    assert_eq!(of(&cam, "motor.power"), Quantity::Power);
    let pushed = q("slider_crank_slider_driven", true);
    assert_eq!(of(&pushed, "stroke.effort"), Quantity::Force);
    assert_eq!(of(&pushed, "constraint.residual"), Quantity::Residual);
}
