//! Loading cam design files: a good file gives the values the Python
//! loader gave; every field's bad value is refused naming the file, the
//! line and the field.

use std::path::Path;

use camlink_cam::{load_json, load_path, load_toml, DxfMode};
use camlink_core::cam::LawKind;

/// A design touching every table; line numbers are those of the cases
/// below.
const GOOD: &str = r#"name = "t"
[cam]
base_radius = 0.03
rotation = "ccw"
[follower]
type = "translating-roller"
offset = 0.0
roller_radius = 0.01
[[segments]]
law = "cycloidal"
span_deg = 120
lift = 0.01
[[segments]]
law = "dwell"
span_deg = 60
[[segments]]
law = "polynomial"
span_deg = 120
lift = -0.01
start = { velocity = 0.0, acceleration = 0.0 }
end = { velocity = 0.0, acceleration = 0.0 }
[[segments]]
law = "dwell"
span_deg = 60
[limits]
max_pressure_angle_deg = 30
min_radius = 0.005
base_radius_search = [0.01, 0.1]
[dynamics]
mass = 0.5
spring_rate = 2000
preload = 20
speed_rpm = 300
[contact]
width = 0.01
cam_material = "steel"
[vibration]
stiffness = [1e6]
[export]
csv = "t.csv"
units = "mm"
"#;

/// `GOOD` with line `line` (from 1) replaced by `text`.
fn with_line(line: usize, text: &str) -> String {
    GOOD.lines()
        .enumerate()
        .map(|(k, l)| if k + 1 == line { text } else { l })
        .collect::<Vec<_>>()
        .join("\n")
}

fn examples() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

#[test]
fn a_good_design_loads_in_si_units_and_radians() {
    let d = load_toml(GOOD, "dir/t.toml").unwrap().design;
    assert_eq!(d.name, "t");
    assert_eq!(
        (d.follower, d.dims.as_slice()),
        ("translating-roller", &[0.0, 0.01][..])
    );
    assert_eq!(d.segments.len(), 4);
    assert_eq!(d.segments[2].law, LawKind::Polynomial);
    assert_eq!(d.segments[0].span, 120f64.to_radians());
    assert_eq!(d.segments[2].start, [Some(0.0), Some(0.0), None]);
    assert_eq!(d.limits.max_pressure_angle, Some(30f64.to_radians()));
    assert_eq!(d.limits.base_radius_range, Some((0.01, 0.1)));
    assert_eq!(d.limits.min_surge_ratio, 13.0);
    let dy = d.dynamics.as_ref().unwrap();
    assert_eq!(dy.speed, 300.0 * std::f64::consts::TAU / 60.0);
    // The defaults: steel on steel, a ball bearing, one mass undamped.
    let c = d.contact.as_ref().unwrap();
    assert_eq!(c.materials, ("steel".into(), "steel".into()));
    assert_eq!(c.exponent, 3.0);
    let v = d.vibration.as_ref().unwrap();
    assert_eq!(
        (v.masses.as_slice(), v.damping.as_slice()),
        (&[0.5][..], &[0.0][..])
    );
    assert_eq!((v.steps, v.turns, v.polydyne), (7200, 3, false));
    // Exports: given names kept, the others named after the file's stem.
    let e = &d.export;
    assert_eq!(e.csv.as_deref(), Some("t.csv"));
    assert_eq!(e.dxf.as_deref(), Some("t.dxf"));
    assert_eq!(e.svaj_time.as_deref(), Some("t_svaj_time.png"));
    assert_eq!(e.vibration.as_deref(), Some("t_vibration.png"));
    assert_eq!(e.given, ["csv"]);
    assert_eq!((e.units.as_str(), e.dxf_mode), ("mm", DxfMode::Polyline));
    assert!(d.cam().is_ok());
}

/// The valve example: the values the Python loader of design files gave
/// (its dataclasses' repr, which prints each double exactly).
#[test]
fn the_valve_example_loads_to_the_values_python_had() {
    let d = load_path(&examples().join("cam_design_valve.toml"))
        .unwrap()
        .design;
    assert_eq!(d.name, "valve cam");
    assert_eq!(d.follower, "translating-flat");
    assert_eq!(d.base_radius, 0.018);
    let spans: Vec<f64> = d.segments.iter().map(|s| s.span).collect();
    assert_eq!(
        spans,
        [
            2.6179938779914944,
            1.7453292519943295,
            0.17453292519943295,
            1.7453292519943295
        ]
    );
    let dy = d.dynamics.as_ref().unwrap();
    assert_eq!(
        (dy.speed, dy.redline),
        (314.1592653589793, Some(366.51914291880917))
    );
    // [spring] sets the rate and preload of [dynamics].
    assert_eq!(
        (dy.spring_rate, dy.preload),
        (41622.98399999999, 249.73790399999987)
    );
    let s = d.spring.as_ref().unwrap();
    assert_eq!(s.density, 7800.829029281152);
    assert_eq!(s.figures.clash_margin, 0.003799999999999998);
    assert_eq!(s.figures.surge, 645.8681266229053);
    let c = d.contact.as_ref().unwrap();
    assert_eq!(c.modulus, 71562472519.10306);
    assert_eq!(c.materials, ("cast-iron".into(), "steel".into()));
    assert_eq!(d.limits.min_surge_ratio, 10.0);
    assert_eq!(d.limits.max_contact_stress, Some(1.2e9));
    assert_eq!(d.export.dxf_mode, DxfMode::Arcs);
    assert_eq!(d.export.tool_radius, Some(0.05));
    assert!(d.export.given.is_empty());
    let v = d.vibration.as_ref().unwrap();
    assert_eq!((v.stiffness.as_slice(), v.polydyne), (&[2.5e6][..], true));
}

/// Every example design file loads, and as JSON data (as the studio holds
/// it) to the same design.
#[test]
fn every_example_design_loads_alike_from_toml_and_json() {
    let mut n = 0;
    for entry in std::fs::read_dir(examples()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("toml") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let doc: toml::Table = text.parse().unwrap();
        if !camlink_cam::is_design(&doc) {
            continue;
        }
        let source = path.display().to_string();
        let a = load_toml(&text, &source).unwrap().design;
        let json = serde_json::to_string(&doc).unwrap();
        let b = load_json(&json, &source).unwrap().design;
        assert_eq!(a, b, "{source}");
        n += 1;
    }
    assert!(n >= 4, "{n} design files");
}

#[test]
fn every_bad_field_is_refused_naming_file_line_and_field() {
    let cases: &[(usize, &str, &str, usize, &str)] = &[
        (1, "name = 5", "name", 1, "must be a string, got 5"),
        (
            1,
            "nmae = 't'",
            "nmae",
            1,
            "unknown key (did you mean 'name'?)",
        ),
        (
            3,
            "base_radius = -1",
            "cam.base_radius",
            3,
            "must be positive, got -1",
        ),
        (
            3,
            "base_radius = 2000",
            "cam.base_radius",
            3,
            "must be at most 1000 m in size",
        ),
        (
            3,
            "base_radius = nan",
            "cam.base_radius",
            3,
            "must be a number, got NaN",
        ),
        (3, "radius = 0.03", "cam.base_radius", 2, "is required"),
        (
            4,
            "rotation = 'cc'",
            "cam.rotation",
            4,
            "(did you mean 'ccw'?)",
        ),
        (
            6,
            "type = 'knife'",
            "follower.type",
            6,
            "'knife' is not one of translating-roller",
        ),
        (
            7,
            "offset = 'x'",
            "follower.offset",
            7,
            "must be a number, got 'x'",
        ),
        (
            7,
            "arm_length = 0.1",
            "follower.arm_length",
            7,
            "unknown key",
        ),
        (
            8,
            "roller_radius = 0",
            "follower.roller_radius",
            8,
            "must be positive",
        ),
        (
            10,
            "law = 'cycloidl'",
            "segments[0].law",
            10,
            "(did you mean 'cycloidal'?)",
        ),
        (
            11,
            "span_deg = 0",
            "segments[0].span_deg",
            11,
            "must be positive",
        ),
        (
            11,
            "span_deg = 1e-4",
            "segments[0].span_deg",
            11,
            "must be at least 0.001°",
        ),
        (
            11,
            "span_deg = 400",
            "segments[0].span_deg",
            11,
            "must be at most 360° in size",
        ),
        (
            12,
            "lift = true",
            "segments[0].lift",
            12,
            "must be a number, got true",
        ),
        (
            12,
            "swing_deg = 10",
            "segments[0].swing_deg",
            12,
            "unknown key",
        ),
        (
            19,
            "lift = -0.02",
            "segments",
            9,
            "the program does not close",
        ),
        (20, "start = 1", "segments[2].start", 20, "must be a table"),
        (
            20,
            "start = { speed = 0.0 }",
            "segments[2].start.speed",
            20,
            "unknown key",
        ),
        (
            21,
            "end = { jerk = 'a' }",
            "segments[2].end.jerk",
            21,
            "must be a number",
        ),
        (
            26,
            "max_pressure_angle_deg = 95",
            "limits.max_pressure_angle_deg",
            26,
            "at most 90°",
        ),
        (
            27,
            "min_radius = -1",
            "limits.min_radius",
            27,
            "must be positive",
        ),
        (
            28,
            "base_radius_search = [0.1, 0.01]",
            "limits.base_radius_search",
            28,
            "0 < lo < hi",
        ),
        (
            28,
            "min_surge_ratio = 0",
            "limits.min_surge_ratio",
            28,
            "must be positive",
        ),
        (30, "mass = 0", "dynamics.mass", 30, "must be positive"),
        (
            31,
            "spring_rate = -1",
            "dynamics.spring_rate",
            31,
            "must not be negative",
        ),
        (
            33,
            "speed_rpm = 2e6",
            "dynamics.speed_rpm",
            33,
            "at most 1e+6 rpm in size",
        ),
        (35, "width = 0", "contact.width", 35, "must be positive"),
        (
            36,
            "cam_material = 'cheese'",
            "contact.cam_material",
            36,
            "not in the materials table",
        ),
        (
            36,
            "cam_material = { young_modulus = 2e11, poisson_ratio = 0.7 }",
            "contact.cam_material.poisson_ratio",
            36,
            "must be in [0, 0.5)",
        ),
        (
            36,
            "bearing_type = 'needle'",
            "contact.bearing_type",
            36,
            "is not one of ball, roller",
        ),
        (
            38,
            "stiffness = [0]",
            "vibration.stiffness",
            38,
            "a list of positive numbers",
        ),
        (
            38,
            "stiffness = [1e6, 1e6]",
            "vibration.stiffness",
            38,
            "gives 2 values for 1 masses",
        ),
        (
            38,
            "stiffness = [1e6]\nsteps_per_turn = 0.5",
            "vibration.steps_per_turn",
            39,
            "is 0.5: a whole number is needed",
        ),
        (
            38,
            "stiffness = [1e6]\nturns = 2.5",
            "vibration.turns",
            39,
            "is 2.5: a whole number is needed",
        ),
        (
            38,
            "stiffness = [1e6]\npolydyne = 1",
            "vibration.polydyne",
            39,
            "must be true or false",
        ),
        (
            40,
            "csv = '../t.csv'",
            "export.csv",
            40,
            "holds a path separator",
        ),
        (
            40,
            "csv = 't.toml'",
            "export.csv",
            40,
            "the design file's name",
        ),
        (
            40,
            "csv = 't.dxf'",
            "export.dxf",
            39,
            "'t.dxf' is also export.csv",
        ),
        (
            41,
            "units = 'in'",
            "export.units",
            41,
            "'in' is not one of m, mm",
        ),
        (
            41,
            "csv_step_deg = 1e-7",
            "export.csv_step_deg",
            41,
            "the CSV holds at most",
        ),
        (
            41,
            "tolerance = 1e-300",
            "export.tolerance",
            41,
            "is finer than 1e-9 of the profile",
        ),
        (
            41,
            "bore_diameter = 0.07",
            "export.bore_diameter",
            41,
            "beyond the profile's least",
        ),
        (
            41,
            "keyway_width = 0.002",
            "export.keyway_width",
            41,
            "needs export.bore_diameter",
        ),
        (
            41,
            "timing_mark = 'yes'",
            "export.timing_mark",
            41,
            "must be true or false",
        ),
    ];
    for &(line, text, field, at, message) in cases {
        let e = load_toml(&with_line(line, text), "dir/t.toml").unwrap_err();
        let shown = e.to_string();
        assert_eq!(e.source, "dir/t.toml", "{shown}");
        assert_eq!(e.field.as_deref(), Some(field), "{text}: {shown}");
        assert_eq!(e.line, Some(at), "{text}: {shown}");
        assert!(e.message.contains(message), "{text}: {shown}");
        assert!(shown.starts_with(&format!("dir/t.toml:{at}:")), "{shown}");
    }
}

#[test]
fn sizing_tables_need_dynamics_and_a_spring_a_translating_follower() {
    let no_dynamics: String = GOOD.replace(
        "[dynamics]\nmass = 0.5\nspring_rate = 2000\npreload = 20\nspeed_rpm = 300\n",
        "",
    );
    let e = load_toml(&no_dynamics, "t.toml").unwrap_err();
    assert_eq!(e.field.as_deref(), Some("contact"), "{e}");
    assert!(e.message.contains("[contact] needs [dynamics]"), "{e}");
    let spring = format!(
        "{}[spring]\nwire_diameter = 0.003\nmean_diameter = 0.02\nactive_coils = 5\n\
         total_coils = 7\nfree_length = 0.05\ninstalled_length = 0.045\n",
        GOOD
    );
    let e = load_toml(&spring, "t.toml").unwrap_err();
    assert_eq!(e.field.as_deref(), Some("dynamics.spring_rate"), "{e}");
    let e = load_toml(
        &spring.replace("spring_rate = 2000\npreload = 20\n", ""),
        "t.toml",
    );
    let d = e.unwrap().design;
    let s = d.spring.unwrap();
    // k = G d⁴ / (8 D³ N_a), steel's G.
    let g = camlink_core::cam::hertz::material("steel").unwrap().shear;
    let k = g * 0.003f64.powi(4) / (8.0 * 0.02f64.powi(3) * 5.0);
    assert!(
        (s.figures.rate - k).abs() <= 1e-12 * k,
        "{} {k}",
        s.figures.rate
    );
    assert_eq!(d.dynamics.unwrap().spring_rate, s.figures.rate);
}

#[test]
fn json_data_is_refused_naming_the_field_without_a_line() {
    let doc: toml::Table = with_line(11, "span_deg = 0").parse().unwrap();
    let json = serde_json::to_string(&doc).unwrap();
    let e = load_json(&json, "t.toml").unwrap_err();
    assert_eq!(
        (e.line, e.field.as_deref()),
        (None, Some("segments[0].span_deg"))
    );
    assert_eq!(
        e.to_string(),
        "t.toml: segments[0].span_deg: must be positive, got 0"
    );
}

#[test]
fn a_metres_long_base_circle_is_questioned() {
    let text = with_line(3, "base_radius = 90").replace("base_radius_search = [0.01, 0.1]", "");
    let loaded = load_toml(&text, "t.toml");
    let w = match loaded {
        Ok(l) => l.warnings,
        Err(e) => panic!("{e}"),
    };
    assert_eq!(
        w,
        [
            "t.toml: [cam] base_radius: a base circle of radius 90 m: is it 90 mm (0.09 m)? \
          (design files are in metres)"
        ]
    );
}

#[test]
fn a_syntax_error_names_its_line() {
    let e = load_toml(&with_line(1, "name = = 't'"), "t.toml").unwrap_err();
    assert_eq!(e.line, Some(1), "{e}");
    assert!(e.message.starts_with("syntax error"), "{e}");
}

/// Each `<!-- cam-output: FILE -->` marker of docs/errors.md is followed by
/// a text block holding the message FILE (a design or a timing file, named
/// by its file name) gives.
#[test]
fn docs_errors_page_matches_real_output() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let page = std::fs::read_to_string(root.join("docs/errors.md")).unwrap();
    let lines: Vec<&str> = page.lines().collect();
    let mut checked = 0;
    for (k, line) in lines.iter().enumerate() {
        let Some(file) = line.trim().strip_prefix("<!-- cam-output:") else {
            continue;
        };
        let file = file.trim_end_matches("-->").trim();
        let path = root.join(file);
        let text = std::fs::read_to_string(&path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy();
        let doc: toml::Table = text.parse().unwrap();
        let got = if camlink_cam::timing::is_timing(&doc) {
            let dir = path.parent().unwrap();
            camlink_cam::timing::load_toml(&text, &name, dir)
                .unwrap_err()
                .to_string()
        } else {
            load_toml(&text, &name).unwrap_err().to_string()
        };
        assert!(
            lines[k + 1].starts_with("```text"),
            "no text block after {line}"
        );
        assert_eq!(lines[k + 2], got, "docs/errors.md, {file}");
        checked += 1;
    }
    assert!(checked >= 2);
}

/// Each law name loads as its own law (the loader carries the parsed
/// law; no name falls back to another), and so do the choices of
/// rotation, DXF mode and bearing type.
#[test]
fn every_law_name_loads_as_its_law() {
    for law in LawKind::ALL {
        let text = GOOD.replacen(
            "law = \"cycloidal\"",
            &format!("law = \"{}\"", law.name()),
            1,
        );
        match load_toml(&text, "t.toml") {
            Ok(l) => assert_eq!(l.design.segments[0].law, law),
            // A law that cannot make this segment is refused at it, never
            // read as another.
            Err(e) => assert_eq!(e.field.as_deref(), Some("segments[0]"), "{e}"),
        }
    }
    let text = GOOD
        .replace("rotation = \"ccw\"", "rotation = \"cw\"")
        .replace("units = \"mm\"", "units = \"mm\"\ndxf_mode = \"arcs\"")
        .replace("[contact]", "[contact]\nbearing_type = \"roller\"");
    let d = load_toml(&text, "t.toml").unwrap().design;
    assert!(!d.ccw);
    assert_eq!(d.export.dxf_mode, DxfMode::Arcs);
    assert_eq!(d.contact.unwrap().exponent, 10.0 / 3.0);
}
