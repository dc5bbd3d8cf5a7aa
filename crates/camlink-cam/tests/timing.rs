//! Timing files: a good file gives the values the Python reader gave, every
//! bad field is refused naming the file, the line and the field, and a
//! clearance matches its closed form.

use std::f64::consts::{PI, TAU};
use std::path::{Path, PathBuf};

use camlink_cam::timing::{is_timing_path, load_path, load_toml, SAMPLES};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn files() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/files")
}

fn example() -> String {
    std::fs::read_to_string(root().join("examples/cam_design_timing.toml")).unwrap()
}

#[test]
fn the_example_loads_to_its_recorded_values() {
    let path = root().join("examples/cam_design_timing.toml");
    assert!(is_timing_path(&path));
    assert!(!is_timing_path(
        &root().join("examples/cam_design_timing_gate.toml")
    ));
    let t = load_path(&path).unwrap().timing;
    // Recorded figures (6.283185307179586 and 3.141592653589793 are 2π
    // and π): a change in how the file is read or analysed shows here.
    assert_eq!(t.name, "pusher and gate");
    assert_eq!(t.speed, TAU);
    assert_eq!(t.resolution, 0.008726646259971648);
    assert_eq!(t.units, "mm");
    assert_eq!(t.diagram.as_deref(), Some("cam_design_timing_timing.png"));
    assert!(t.tables);
    let axes: Vec<_> = t
        .axes
        .iter()
        .map(|a| (a.name.as_str(), a.phase, a.origin, a.direction))
        .collect();
    assert_eq!(
        axes,
        [
            ("pusher", 0.0, [0.0, 0.0], 0.0),
            ("gate", 3.490658503988659, [0.1, 0.0], PI),
        ]
    );
    assert!(t.axes[1]
        .design
        .source
        .ends_with("cam_design_timing_gate.toml"));
    assert_eq!(t.clearances.len(), 1);
    let c = &t.clearances[0];
    assert_eq!((c.a, c.b, c.min_distance), (0, 1, 0.015));
    // The clearance, the cam table and the gate's rise, recorded bit for
    // bit.
    let r = &t.clearances()[0];
    assert_eq!(r.least, 0.020012372787609613);
    assert_eq!(r.at_deg, 136.09816828283957);
    assert!(r.ok);
    let table = t.table(1, "mm").unwrap();
    assert_eq!(table.len(), 721);
    assert_eq!(table[720][0], 360.0);
    let rise = &t.segments(1, "mm").unwrap()[1];
    assert_eq!(rise.law, "cycloidal");
    assert_eq!(
        (rise.start_deg, rise.end_deg, rise.lift),
        (350.0, 60.0, 60.0)
    );
    assert_eq!((rise.continuity_start, rise.continuity_end), (2, 2));
    assert_eq!(rise.peak_velocity, (617.1428571428572, 25.0));
    assert_eq!(rise.max_acceleration, (9971.030397679277, 7.5));
    assert_eq!(rise.min_acceleration, (-9971.030397679277, 42.5));
    assert!(t.table(1, "in").is_none());
}

#[test]
fn an_axis_runs_its_program_at_the_master_angle_less_its_phase() {
    let t = load_path(&root().join("examples/cam_design_timing.toml"))
        .unwrap()
        .timing;
    let gate = &t.axes[1];
    for master in [0.0, 1.0, 3.5, 6.0, -0.5, 7.0] {
        let theta = (master - gate.phase).rem_euclid(TAU);
        let m = gate.program.eval(theta);
        assert_eq!(gate.motion(master), [m[0], m[1], m[2], m[3]]);
    }
    // The gate moves towards −x from x = 100 mm.
    let tip = gate.tip(0.02);
    assert!(
        (tip[0] - 0.08).abs() < 1e-15 && tip[1].abs() < 1e-15,
        "{tip:?}"
    );
    // Its table in metres is its table in millimetres / 1000.
    let (m, mm) = (t.table(1, "m").unwrap(), t.table(1, "mm").unwrap());
    for (a, b) in m.iter().zip(&mm) {
        assert!((a[1] * 1000.0 - b[1]).abs() < 1e-9);
    }
}

#[test]
fn a_clearance_matches_its_closed_form() {
    // Two harmonic cams facing each other on the x axis, 100 mm apart:
    // s(θ) = h/2 (1 − cos θ), phases 0 and φ, so the tips are
    // d(Θ) = 0.1 − h + h cos(φ/2) cos(Θ − φ/2) apart, least
    // 0.1 − h (1 + cos(φ/2)) at Θ = φ/2 + 180°. φ = 70.003° puts the
    // least between two samples, so the parabola refines it.
    let h = 0.02;
    let phi: f64 = 70.003;
    let text = std::fs::read_to_string(files().join("timing_unknown_axis.toml"))
        .unwrap()
        .replace("\"rigth\"", "\"right\"")
        .replace("phase_deg = 70", "phase_deg = 70.003");
    let t = load_toml(&text, "t.toml", &files()).unwrap().timing;
    let r = &t.clearances()[0];
    let least = 0.1 - h * (1.0 + (phi.to_radians() / 2.0).cos());
    assert!((r.least - least).abs() < 1e-12, "{} {least}", r.least);
    let at = phi / 2.0 + 180.0;
    assert!((r.at_deg - at).abs() < 1e-6, "{} {at}", r.at_deg);
    // Between two samples, 0.0015° from the nearer.
    let nearest = (at / (360.0 / SAMPLES as f64)).round() * (360.0 / SAMPLES as f64);
    assert!((nearest - at).abs() > 1e-3);
    assert_eq!(r.limit, 0.01);
    assert!(r.ok);
    // A limit above the least fails.
    let tight = text.replace("min_distance = 0.01", "min_distance = 0.07");
    let t = load_toml(&tight, "t.toml", &files()).unwrap().timing;
    let r = &t.clearances()[0];
    assert!(!r.ok && r.least < r.limit);
}

#[test]
fn each_bad_field_is_refused_naming_file_line_and_field() {
    let good = example();
    let dir = root().join("examples");
    // (text replaced, its replacement, field, line, the message's end)
    let cases: &[(&str, &str, &str, Option<usize>, &str)] = &[
        ("speed_rpm = 60", "speed_rpm = '60'", "speed_rpm", Some(9), "must be a number, got '60'"),
        ("speed_rpm = 60", "speed_rpm = -6", "speed_rpm", Some(9), "must be positive, got -6"),
        ("speed_rpm = 60", "", "speed_rpm", None, "is required"),
        ("speed_rpm = 60", "speed_rpm = 60\nsped = 1", "sped", Some(10), "unknown key; the keys here are axes, clearances, export, name, speed_rpm"),
        ("name = \"pusher and gate\"", "name = 3", "name", Some(8), "must be a string, got 3"),
        ("name = \"gate\"", "name = \"pusher\"", "axes[1].name", Some(19), "'pusher' names two axes"),
        ("\"cam_design_timing_gate.toml\"", "\"nope.toml\"", "axes[1].design", Some(20), "'nope.toml': no such file beside t.toml"),
        ("\"cam_design_timing_gate.toml\"", "\"sub/x.toml\"", "axes[1].design", Some(20), "'sub/x.toml' holds a path separator; name a design file beside t.toml"),
        ("origin = [0.10, 0.0]", "origin = [0.1]", "axes[1].origin", Some(22), "must be [x, y] (m), got [0.1]"),
        ("origin = [0.10, 0.0]", "origin = [1e4, 0]", "axes[1].origin", Some(22), "must be [x, y] (m), got [10000, 0]"),
        ("phase_deg = 200", "phase_deg = 400", "axes[1].phase_deg", Some(21), "must be at most 360° in size, got 400"),
        ("direction_deg = 180", "direction_deg = true", "axes[1].direction_deg", Some(23), "must be a number, got true"),
        ("direction_deg = 180", "direction_deg = 180\ndirection = 1", "axes[1].direction", Some(24), "unknown key (did you mean 'direction_deg'?); the keys here are design, direction_deg, name, origin, phase_deg"),
        ("[[clearances]]", "[clearances]", "clearances", Some(25), "must be an array of tables ([[clearances]])"),
        ("between = [\"pusher\", \"gate\"]", "between = [\"pusher\"]", "clearances[0].between", Some(26), "must name two axes, got ['pusher']"),
        ("between = [\"pusher\", \"gate\"]", "between = [\"pusher\", \"door\"]", "clearances[0].between", Some(26), "'door' is not an axis; the axes are pusher, gate"),
        ("between = [\"pusher\", \"gate\"]", "between = [\"gate\", \"gate\"]", "clearances[0].between", Some(26), "names one axis twice"),
        ("min_distance = 0.015", "min_distance = 0", "clearances[0].min_distance", Some(27), "must be positive, got 0"),
        ("resolution_deg = 0.5", "resolution_deg = 91", "export.resolution_deg", Some(30), "must be at most 90° in size, got 91"),
        ("resolution_deg = 0.5", "resolution_deg = 0.0001", "export.resolution_deg", Some(30), "0.0001° makes more than 1000000 rows (a step of at least 0.00036°)"),
        ("units = \"mm\"", "units = \"cm\"", "export.units", Some(31), "'cm' is not one of m, mm (did you mean 'm'?)"),
        ("units = \"mm\"", "units = \"mm\"\ndiagram = \"a/b.png\"", "export.diagram", Some(32), "must be a plain file name or false, got 'a/b.png'"),
        ("units = \"mm\"", "units = \"mm\"\ntables = \"no\"", "export.tables", Some(32), "must be true or false, got 'no'"),
    ];
    for &(from, to, field, line, message) in cases {
        assert!(good.contains(from), "{from}");
        let text = good.replacen(from, to, 1);
        let e = load_toml(&text, "t.toml", &dir).unwrap_err();
        assert_eq!(e.field.as_deref(), Some(field), "{to}: {e}");
        assert_eq!(e.line, line, "{to}: {e}");
        assert_eq!(e.message, message, "{to}: {e}");
        assert_eq!(e.source, "t.toml");
    }
    // No axes at all.
    let text = format!("{}axes = []\n", good.split("[[axes]]").next().unwrap());
    let e = load_toml(&text, "t.toml", &dir).unwrap_err();
    assert_eq!(
        e.to_string(),
        "t.toml:11:8: axes: a timing diagram needs at least one axis"
    );
    // A clearance needs translating followers.
    let text = good.replace(
        "\"cam_design_timing_gate.toml\"",
        "\"cam_design_indexing.toml\"",
    );
    let e = load_toml(&text, "t.toml", &dir).unwrap_err();
    assert_eq!(
        e.to_string(),
        "t.toml:26:11: clearances[0].between: 'gate' has an oscillating follower; a clearance \
         needs translating followers"
    );
    // The timing file is not its own design file.
    let text = good.replace(
        "\"cam_design_timing_gate.toml\"",
        "\"cam_design_timing.toml\"",
    );
    let e = load_toml(&text, "cam_design_timing.toml", &dir).unwrap_err();
    assert_eq!(e.message, "names the timing file itself");
    // A syntax error names its line and column.
    let e = load_toml(
        &good.replace("speed_rpm = 60", "speed_rpm = = 60"),
        "t.toml",
        &dir,
    )
    .unwrap_err();
    assert_eq!((e.line, e.column), (Some(9), Some(13)), "{e}");
    assert!(e.message.starts_with("syntax error"), "{e}");
}

#[test]
fn a_bad_design_file_is_named_with_its_own_line_and_field() {
    let tmp = std::env::temp_dir().join(format!("camlink-timing-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let gate = std::fs::read_to_string(root().join("examples/cam_design_timing_gate.toml"))
        .unwrap()
        .replacen("law = \"cycloidal\"", "law = \"cycloidl\"", 1);
    std::fs::write(tmp.join("cam_design_timing_gate.toml"), gate).unwrap();
    std::fs::copy(
        root().join("examples/cam_design_packaging.toml"),
        tmp.join("cam_design_packaging.toml"),
    )
    .unwrap();
    let e = load_toml(&example(), "t.toml", &tmp).unwrap_err();
    let _ = std::fs::remove_dir_all(&tmp);
    assert!(e.source.ends_with("cam_design_timing_gate.toml"), "{e}");
    assert_eq!(e.field.as_deref(), Some("segments[1].law"), "{e}");
    assert_eq!(e.line, Some(20), "{e}");
}
