//! A model file converted between frame form and global form
//! (camlink_model::convert, `camlink convert --global/--frame`): every
//! example gives the same results in both forms, and a round trip gives
//! the original results back (issue 30).

use std::path::{Path, PathBuf};

use camlink_core::dynamics::{integrator, inverse, statics};
use camlink_core::kinematics;
use camlink_core::run::{time_grid, Settings, Table};
use camlink_model::convert::{convert, Form, POINT_KEYS};
use camlink_model::{load_path, load_str, AnalysisType, Format, LoadOptions, Loaded};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// Runs the file's `[analysis]` (kinematics at a Newton tolerance near
/// rounding, so that both forms land on the same positions) into a table.
fn run(l: &Loaded, name: &str) -> Table {
    let a = &l.analysis;
    let times = || match &a.times {
        Some(t) => t.clone(),
        None => time_grid(a.t_end.unwrap_or(0.0), a.step.unwrap_or(0.01)).unwrap(),
    };
    let points = l.point_outputs().unwrap();
    let mut table = Table::default();
    let tol = 1e-13;
    let m = &l.model;
    let done = match a.kind {
        AnalysisType::Kinematics => {
            let s = Settings {
                tol,
                max_iter: 50,
                jerk: a.jerk,
            };
            kinematics::run(m, &times(), &s, &points, &mut table)
        }
        AnalysisType::InverseDynamics => {
            let s = Settings {
                tol,
                max_iter: 50,
                jerk: false,
            };
            inverse::run(m, &times(), &s, &points, &mut table)
        }
        AnalysisType::Equilibrium => {
            let s = statics::Settings {
                tol: a.tol_for(a.kind),
                max_iter: a.max_iter_for(a.kind),
            };
            statics::run(m, a.time, &s, &points, &mut table)
        }
        AnalysisType::Dynamics => {
            integrator::run(m, &times(), &a.integrator_settings(), &points, &mut table)
        }
    };
    done.unwrap_or_else(|e| panic!("{name}: {e}"));
    table
}

/// The largest difference between two runs over every channel, relative
/// to the channel's largest magnitude (at least 1).
fn assert_same(a: &Table, b: &Table, what: &str) {
    assert_eq!(a.channels, b.channels, "{what}");
    assert_eq!(a.t.len(), b.t.len(), "{what}");
    for ch in &a.channels {
        let (x, y) = (a.channel(ch).unwrap(), b.channel(ch).unwrap());
        let scale = x.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let d = x
            .iter()
            .zip(&y)
            .map(|(u, v)| (u - v).abs())
            .fold(0.0, f64::max);
        assert!(d <= 1e-12 * scale, "{what}: {ch}: {d:e} (scale {scale})");
    }
}

/// The examples that are mechanism models (study, cam design and
/// synthesis files are other formats), by name.
fn models() -> Vec<(String, Loaded)> {
    let mut out: Vec<(String, Loaded)> = Vec::new();
    for entry in std::fs::read_dir(examples()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        if let Ok(l) = load_path(&path) {
            out.push((path.file_name().unwrap().to_string_lossy().into(), l));
        }
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

fn reload(text: &str, l: &Loaded) -> Loaded {
    let r = l.recipe.as_ref().unwrap();
    load_str(text, r.format, &r.source).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

#[test]
fn issue30_every_example_in_global_form_gives_the_same_results() {
    let options = LoadOptions::default();
    let mut converted = 0;
    for (name, frames) in models() {
        let (text, bodies) = convert(&frames, Form::Global, &options).unwrap();
        let global = reload(&text, &frames);
        // Every body with points is in global form now.
        let file: toml::Table = text.parse().unwrap();
        for b in file
            .get("bodies")
            .and_then(|b| b.as_array())
            .into_iter()
            .flatten()
        {
            assert!(b.get("points").is_none(), "{name}: {b}");
        }
        assert_same(&run(&frames, &name), &run(&global, &name), &name);
        // And back: the same results again.
        let (back, _) = convert(&global, Form::Frame, &options).unwrap();
        let again = reload(&back, &frames);
        assert_same(&run(&frames, &name), &run(&again, &name), &name);
        converted += usize::from(!bodies.is_empty());
    }
    assert!(converted >= 17, "{converted}");
}

#[test]
fn issue30_whitworth_in_frame_form_gives_the_same_results() {
    let global = load_path(&examples().join("whitworth_global.toml")).unwrap();
    let (text, bodies) = convert(&global, Form::Frame, &LoadOptions::default()).unwrap();
    assert_eq!(bodies, ["crank", "lever", "rod", "ram"]);
    assert!(!text.contains("global_points ="), "{text}");
    // Comments and the other keys stay as written.
    assert!(text.contains("# Pin A runs in the lever's slot"), "{text}");
    assert!(text.contains("fx = \"step(ram_vx, 0, 0, 0.01, -F_cut)\""));
    let frames = reload(&text, &global);
    assert_same(
        &run(&global, "whitworth"),
        &run(&frames, "whitworth"),
        "whitworth",
    );
    // Dynamics too.
    let dynamics = |l: &Loaded| {
        let times = time_grid(0.3, 0.01).unwrap();
        let mut t = Table::default();
        // A Newton tolerance near rounding, as for kinematics.
        let s = integrator::Settings {
            step: 1e-3,
            tol: 1e-13,
            ..Default::default()
        };
        let mut free = l.model.clone();
        free.joints.retain(|j| !j.driver);
        integrator::run(&free, &times, &s, &[], &mut t).unwrap();
        t
    };
    assert_same(&dynamics(&global), &dynamics(&frames), "whitworth dynamics");
}

#[test]
fn issue30_unturned_frames_keep_expressions() {
    let text = r#"
[parameters]
d = 0.2
r = 0.1

[ground]
points = { O = [0, 0] }

[[bodies]]
name = "crank"   # the crank
position = ["d", 0]
points = { O = [0, 0], A = ["r", "r/2"] }
centroid = ["r/2", 0]

[[bodies]]
name = "arm"
angle = 0.5
points = { P = [1, 0] }

[[joints]]
type = "revolute"
body_i = "ground"
point_i = "O"
body_j = "crank"
point_j = [0, 0]
"#;
    let l = load_str(text, Format::Toml, "m.toml").unwrap();
    let (global, _) = convert(&l, Form::Global, &LoadOptions::default()).unwrap();
    assert!(
        global.contains(r#"global_points = { O = ["d", 0], A = ["d + r", "r/2"] }"#),
        "{global}"
    );
    assert!(
        global.contains(r#"centroid = ["d + (r/2)", 0]"#),
        "{global}"
    );
    assert!(global.contains(r#"point_j = ["d", 0]"#), "{global}");
    assert!(
        global.contains("name = \"crank\"   # the crank\n"),
        "{global}"
    );
    // A turned frame: numbers, the shortest within rounding; the body had
    // no position, so the frame origin is written.
    let arm = "name = \"arm\"\nposition = [0, 0]\nangle = 0.5\nglobal_points = { P = [";
    let k = global.find(arm).unwrap_or_else(|| panic!("{global}")) + arm.len();
    let p: Vec<f64> = global[k..global[k..].find(']').unwrap() + k]
        .split(", ")
        .map(|v| v.parse().unwrap())
        .collect();
    assert!((p[0] - 0.5f64.cos()).abs() < 1e-15 && (p[1] - 0.5f64.sin()).abs() < 1e-15);
    let (back, _) = convert(
        &load_str(&global, Format::Toml, "m.toml").unwrap(),
        Form::Frame,
        &LoadOptions::default(),
    )
    .unwrap();
    assert!(
        back.contains(r#"points = { O = [0, 0], A = ["r", "r/2"] }"#),
        "{back}"
    );
    assert!(back.contains(r#"centroid = ["r/2", 0]"#), "{back}");
    assert!(back.contains("points = { P = [1, 0] }"), "{back}");
}

#[test]
fn issue30_json_files_convert_too() {
    let text = r#"{
  "ground": {"points": {"O": [0, 0]}},
  "bodies": [{"name": "arm", "position": [0.5, 0], "points": {"O": [-0.5, 0], "P": [0.5, 0]}}],
  "joints": [{"type": "revolute", "body_i": "ground", "point_i": "O", "body_j": "arm", "point_j": "O"}]
}"#;
    let l = load_str(text, Format::Json, "m.json").unwrap();
    let (global, _) = convert(&l, Form::Global, &LoadOptions::default()).unwrap();
    assert!(
        global.contains(r#""global_points": {"O": [0, 0], "P": [1, 0]}"#),
        "{global}"
    );
    let (back, _) = convert(
        &load_str(&global, Format::Json, "m.json").unwrap(),
        Form::Frame,
        &LoadOptions::default(),
    )
    .unwrap();
    assert!(
        back.contains(r#""points": {"O": [-0.5, 0], "P": [0.5, 0]}"#),
        "{back}"
    );
}

/// Every key of the schema whose value is a point of a body is one the
/// converter rewrites.
#[test]
fn issue30_the_converter_knows_every_point_key() {
    let schema = camlink_model::json_schema();
    let mut keys = Vec::new();
    fn walk(v: &serde_json::Value, keys: &mut Vec<String>) {
        match v {
            serde_json::Value::Object(m) => {
                if let Some(serde_json::Value::Object(props)) = m.get("properties") {
                    for (k, p) in props {
                        if p.to_string().contains("#/$defs/PointRef") {
                            keys.push(k.clone());
                        }
                    }
                }
                m.values().for_each(|x| walk(x, keys));
            }
            serde_json::Value::Array(a) => a.iter().for_each(|x| walk(x, keys)),
            _ => {}
        }
    }
    walk(&schema, &mut keys);
    keys.sort();
    keys.dedup();
    assert!(keys.len() >= 6, "{keys:?}");
    for k in keys {
        // The ground's points are global in both forms.
        if k == "ground_point" {
            continue;
        }
        assert!(POINT_KEYS.iter().any(|(p, _)| *p == k), "{k}");
    }
}
