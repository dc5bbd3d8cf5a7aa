//! Defaults marked *initial* are measured where the bodies are written, and
//! one that differs in the assembled placement is reported with both values
//! (issue 30, finding 2).

use camlink_core::constraint::composite::{RevoluteRevolute, RevoluteTranslational};
use camlink_core::kinematics::run;
use camlink_core::run::{time_grid, Settings, Table};
use camlink_core::Constraint;
use camlink_model::{load_str, Format, Loaded};

/// A quick-return: crank O2–A turning about O2 = (0.3, 0), its pin A in the
/// slot of a lever rocking about O4 = (0, 0), the lever's tip T in a
/// vertical slot of a ram that slides along the x axis. The lever is
/// written at `lever_x` (its pivot is at the origin: 0 is exact) and the
/// ram's slot joint gives `ram_offset` (a TOML line, or nothing).
fn quick_return(lever_x: f64, ram_offset: &str) -> String {
    format!(
        r#"
[parameters]
d = 0.3
r = 0.1
L = 0.5

[ground]
points = {{ O4 = [0, 0], O2 = ["d", 0] }}

[[bodies]]
name = "crank"
position = ["d", 0]
points = {{ O2 = [0, 0], A = ["r", 0] }}

[[bodies]]
name = "lever"
position = [{lever_x}, 0]
points = {{ O4 = [0, 0], T = ["L", 0] }}

[[bodies]]
name = "ram"
position = ["L", 0]
points = {{ P = [0, 0] }}

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
name = "guide"
type = "translational"
body_i = "ground"
point_i = [0, 0]
axis = [1, 0]
body_j = "ram"
point_j = "P"

[[joints]]
name = "ram_slot"
type = "revolute_translational"
body_i = "lever"
point_i = "T"
body_j = "ram"
point_j = "P"
axis = [0, 1]
{ram_offset}

[[drivers]]
name = "motor"
type = "revolute_angle"
joint = "O2"
f = "2*pi*t"

[analysis]
t_end = 1
step = 0.01
points = ["ram.P", "lever.T"]
"#
    )
}

fn load(text: &str) -> Loaded {
    load_str(text, Format::Toml, "quick_return.toml").unwrap_or_else(|e| panic!("{e}"))
}

fn offset(l: &Loaded, joint: &str) -> f64 {
    let j = l.model.joints.iter().find(|j| j.name == joint).unwrap();
    match &j.constraint {
        Constraint::RevoluteTranslational(RevoluteTranslational { offset, .. }) => *offset,
        other => panic!("{other:?}"),
    }
}

fn kinematics(l: &Loaded) -> Table {
    let times = time_grid(1.0, 0.01).unwrap();
    let mut table = Table::default();
    run(
        &l.model,
        &times,
        &Settings::default(),
        &l.point_outputs().unwrap(),
        &mut table,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    table
}

fn largest_difference(a: &Table, b: &Table, channel: &str) -> f64 {
    let (a, b) = (a.channel(channel).unwrap(), b.channel(channel).unwrap());
    a.iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn issue30_default_from_assembled_placement_quick_return() {
    // The lever written 1 mm off its pivot: measured there, the ram's slot
    // sits 1 mm beside the lever's tip (the value used, as written), while
    // the assembled placement puts it on the tip. The warning names the
    // joint, the field and both values.
    let rough = load(&quick_return(0.001, ""));
    assert!((offset(&rough, "ram_slot") + 0.001).abs() < 1e-15);
    let w = &rough.model.warnings;
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].kind, "default_unassembled");
    assert_eq!(w[0].field, "joints[4].offset");
    let m = &w[0].message;
    assert!(m.contains("joint 'ram_slot'"), "{m}");
    assert!(m.contains("`offset` is left out"), "{m}");
    assert!(m.contains("-0.001 m (used)"), "{m}");
    assert!(m.contains(" 0 m (assembled)"), "{m}");
    // The mechanism used is the one measured where the bodies are written:
    // the ram runs 1 mm beside the one the assembled value describes.
    let assembled = load(&quick_return(0.001, "offset = 0"));
    assert!(assembled.model.warnings.is_empty());
    let d = largest_difference(&kinematics(&rough), &kinematics(&assembled), "ram.x");
    assert!((d - 1e-3).abs() < 1e-9, "{d}");
    // The value that the warning calls assembled gives the mechanism meant,
    // that of the exact drawing.
    let meant = load(&quick_return(0.0, ""));
    let (a, b) = (kinematics(&assembled), kinematics(&meant));
    for channel in ["ram.x", "ram.P.x", "lever.T.x", "lever.T.y"] {
        let d = largest_difference(&a, &b, channel);
        assert!(d < 1e-12, "{channel}: {d}");
    }
}

#[test]
fn issue30_default_from_assembled_placement_exact_drawing_unchanged() {
    // A placement that satisfies the joints: defaults as measured there,
    // bit for bit, and nothing to report.
    let exact = load(&quick_return(0.0, ""));
    assert_eq!(offset(&exact, "ram_slot"), 0.0);
    assert!(
        exact.model.warnings.is_empty(),
        "{:?}",
        exact.model.warnings
    );
}

/// A four-bar whose coupler is a massless link (`revolute_revolute`) of
/// left-out length, with the rocker written `rocker_dy` above its pivot.
fn four_bar(rocker_dy: f64) -> String {
    format!(
        r#"
[ground]
points = {{ A = [0, 0], D = [0.4, 0] }}

[[bodies]]
name = "crank"
points = {{ A = [0, 0], B = [0, 0.1] }}

[[bodies]]
name = "rocker"
position = [0.4, {rocker_dy}]
points = {{ D = [0, 0], C = [0, 0.3] }}

[[joints]]
name = "A"
type = "revolute"
body_i = "ground"
point_i = "A"
body_j = "crank"
point_j = "A"

[[joints]]
name = "D"
type = "revolute"
body_i = "ground"
point_i = "D"
body_j = "rocker"
point_j = "D"

[[joints]]
name = "coupler"
type = "revolute_revolute"
body_i = "crank"
point_i = "B"
body_j = "rocker"
point_j = "C"

[[forces]]
name = "spring"
type = "tsda"
body_i = "crank"
point_i = "B"
body_j = "rocker"
point_j = "C"
stiffness = 10
"#
    )
}

#[test]
fn issue30_default_from_assembled_placement_length_and_free_length() {
    // The rocker written 5 mm above its pivot: the coupler's length and the
    // spring's free length are measured there; the nearest assembly moves
    // the rocker down, where they differ, so both are reported.
    let l = load(&four_bar(0.005));
    let length = match &l.model.joints[2].constraint {
        Constraint::RevoluteRevolute(RevoluteRevolute { length, .. }) => *length,
        other => panic!("{other:?}"),
    };
    let want = (0.4f64.powi(2) + 0.205f64.powi(2)).sqrt();
    assert!((length - want).abs() < 1e-13, "{length} vs {want}");
    let free = match &l.model.forces[0].kind {
        camlink_core::ForceKind::Tsda(s) => s.free_length,
        other => panic!("{other:?}"),
    };
    assert!((free - want).abs() < 1e-13, "{free} vs {want}");
    let fields: Vec<&str> = l.model.warnings.iter().map(|w| w.field.as_str()).collect();
    assert_eq!(fields, ["joints[2].length", "forces[0].free_length"]);
    assert!(l
        .model
        .warnings
        .iter()
        .all(|w| w.kind == "default_unassembled"));
    let assembled = (0.4f64.powi(2) + 0.2f64.powi(2)).sqrt();
    let m = &l.model.warnings[1].message;
    assert!(m.contains("force 'spring'"), "{m}");
    assert!(
        m.contains(&format!(
            "{} m (assembled)",
            camlink_core::fmt_num::num(assembled)
        )),
        "{m}"
    );
    // Written exactly: nothing moves, nothing is reported.
    assert!(load(&four_bar(0.0)).model.warnings.is_empty());
}

#[test]
fn issue30_default_from_assembled_placement_unassembled_is_reported() {
    // The rocker pinned to the ground twice, 1 cm from where its points
    // put it: the joints given in full cannot be satisfied together, so
    // the coupler's length is measured where the bodies are written and
    // the warning says so.
    let text = four_bar(0.0).replace(
        "[[forces]]",
        r#"[[joints]]
name = "D2"
type = "revolute"
body_i = "ground"
point_i = [0.41, 0.3]
body_j = "rocker"
point_j = "C"

[[forces]]"#,
    );
    let l = load(&text);
    let w: Vec<_> = l
        .model
        .warnings
        .iter()
        .filter(|w| w.field == "joints[2].length")
        .collect();
    assert_eq!(w.len(), 1, "{:?}", l.model.warnings);
    assert_eq!(w[0].kind, "default_unassembled");
    assert!(w[0].message.contains("joint 'coupler'"), "{}", w[0].message);
    assert!(w[0].message.contains("do not assemble"), "{}", w[0].message);
}

#[test]
fn issue30_default_from_assembled_placement_examples_say_what_they_mean() {
    // No shipped example leaves a value to a placement that the assembly
    // would change.
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        // Study and cam design files are other formats (tests/examples.rs
        // checks that each file loads as what it is).
        if path.extension().is_some_and(|e| e == "toml") {
            let Ok(l) = camlink_model::load_path(&path) else {
                continue;
            };
            assert!(
                l.model.warnings.is_empty(),
                "{}: {:?}",
                path.display(),
                l.model.warnings
            );
            seen += 1;
        }
    }
    assert!(seen > 10, "{seen}");
}

#[test]
fn issue30_length_scale_names_the_outlier() {
    // The quick-return with the lever tip written in mm (500 for 0.5).
    let text = quick_return(0.0, "offset = 0")
        .replace("T = [\"L\", 0]", "T = [500, 0]")
        .replace("position = [\"L\", 0]", "position = [500, 0]");
    let l = load(&text);
    let w: Vec<_> = l
        .model
        .warnings
        .iter()
        .filter(|w| w.kind == "length_scale")
        .collect();
    assert_eq!(w.len(), 1, "{:?}", l.model.warnings);
    assert_eq!(w[0].field, "bodies[1].points");
    assert!(
        w[0].message.contains("body 'lever' spans 500 m"),
        "{}",
        w[0].message
    );
    // In one unit throughout: nothing to say.
    assert!(load(&quick_return(0.0, "offset = 0"))
        .model
        .warnings
        .is_empty());
}
