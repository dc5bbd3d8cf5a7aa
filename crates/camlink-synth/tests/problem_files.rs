//! Problem files: every example solves; bad input gets an error naming the
//! file, the line and the field, never a panic or a wrong mechanism.

use std::path::Path;

use camlink_synth::solve_str;

fn err(text: &str) -> String {
    match solve_str(text, "p.toml", "p") {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

const MOTION: &str = r#"[synthesis]
type = "motion"
poses = [[0, 0, 0], [0.08, 0.03, "deg(-25)"], [0.15, 0.02, "deg(-50)"]]
crank = { moving = [0.08, -0.18] }
rocker = { moving = [0.12, -0.18] }
"#;

#[test]
fn every_synthesis_example_solves() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_str().unwrap().to_string();
        if name.starts_with("synthesis_") && name.ends_with(".toml") {
            let out = camlink_synth::solve_path(&path).unwrap_or_else(|e| panic!("{e}"));
            for (k, s) in out.solutions.iter().enumerate() {
                let d = &s.report["checks"]["defects"];
                // A path fit keeps candidates with defects for inspection,
                // ranked after the defect-free ones.
                if out.kind != "path" || k == 0 {
                    assert_eq!(d.as_array().unwrap().len(), 0, "{name}: {d}");
                }
                camlink_model::load_str(&s.model, camlink_model::Format::Toml, "m.toml")
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
            }
            n += 1;
        }
    }
    assert!(n >= 2);
}

#[test]
fn coincident_poses_named_with_line_and_field() {
    let text = MOTION.replace("[0.15, 0.02, \"deg(-50)\"]", "[0, 0, 0]");
    assert_eq!(
        err(&text),
        "p.toml:3:9: synthesis.poses: poses 1 and 3 coincide; three distinct poses are needed"
    );
}

#[test]
fn collinear_pivot_positions_named() {
    // A pure translation along x: every point moves on a line.
    let text = r#"[synthesis]
type = "motion"
poses = [[0, 0, 0.3], [0.1, 0, 0.3], [0.25, 0, 0.3]]
crank = { moving = [0.0, 0.1] }
rocker = { moving = [0.1, 0.0] }
"#;
    let e = err(text);
    assert!(
        e.starts_with("p.toml:4:9: synthesis.crank: the positions of moving pivot A at the three poses lie on a line"),
        "{e}"
    );
}

#[test]
fn pivot_at_a_pole_named() {
    // The origin of the coupler frame does not move between poses 1 and 2.
    let text = MOTION
        .replace("[0.08, 0.03, \"deg(-25)\"]", "[0, 0, \"deg(-25)\"]")
        .replace(
            "crank = { moving = [0.08, -0.18] }",
            "crank = { moving = [0, 0] }",
        );
    let e = err(&text);
    assert!(
        e.contains("synthesis.crank: the positions of moving pivot A at poses 1 and 2 coincide"),
        "{e}"
    );
}

#[test]
fn unknown_field_named() {
    let e = err(&MOTION.replace("crank =", "crnak ="));
    assert!(
        e.starts_with("p.toml:4:1: synthesis.crnak: unknown field `crnak`"),
        "{e}"
    );
}

#[test]
fn wrong_number_of_poses_named() {
    let text = MOTION.replace(
        "[0.15, 0.02, \"deg(-50)\"]",
        "[0.15, 0.02, \"deg(-50)\"], [0.2, 0.1, 0]",
    );
    let e = err(&text);
    assert!(
        e.contains(
            "synthesis.poses: 4 poses given; this version synthesises motion through exactly three"
        ),
        "{e}"
    );
}

#[test]
fn bad_expression_named() {
    let e = err(&MOTION.replace("\"deg(-25)\"", "\"deg(-25\""));
    assert!(
        e.starts_with("p.toml:3:34: synthesis.poses[1][2]: deg(-25\n"),
        "{e}"
    );
}

#[test]
fn both_pivot_choices_refused() {
    let e = err(&MOTION.replace(
        "crank = { moving = [0.08, -0.18] }",
        "crank = { moving = [0.08, -0.18], fixed = [0, 0] }",
    ));
    assert!(
        e.contains("synthesis.crank: give exactly one of moving"),
        "{e}"
    );
}

#[test]
fn function_field_in_a_motion_problem_refused() {
    let e = err(&format!("{MOTION}ground = 0.1\n"));
    assert!(
        e.contains("synthesis.ground: not a field of a motion problem"),
        "{e}"
    );
}

const FUNCTION: &str = r#"[synthesis]
type = "function"
function = "log(x)/log(10)"
x = [1, 10]
input = ["deg(135)", "deg(225)"]
output = ["deg(75)", "deg(135)"]
ground = 0.1
"#;

#[test]
fn function_outside_its_domain_named() {
    let e = err(&FUNCTION.replace("x = [1, 10]", "x = [-1, 10]"));
    assert!(
        e.starts_with("p.toml:3:12: synthesis.function: log of a negative number (-1)"),
        "{e}"
    );
}

#[test]
fn function_equal_at_both_ends_refused() {
    let e = err(&FUNCTION
        .replace("log(x)/log(10)", "sin(x)")
        .replace("x = [1, 10]", "x = [0, \"pi\"]"));
    assert!(
        e.contains("synthesis.function: f(x_start) equals f(x_end)"),
        "{e}"
    );
}

#[test]
fn repeated_precision_points_refused() {
    let e = err(&format!("{FUNCTION}points = [2, 2, 5]\n"));
    assert!(
        e.contains("synthesis.points: two points have the same x"),
        "{e}"
    );
}

#[test]
fn precision_point_outside_the_range_named() {
    let e = err(&format!("{FUNCTION}points = [2, 5, 11]\n"));
    assert!(
        e.contains("synthesis.points[2]: x = 11 lies outside the range [1, 10]"),
        "{e}"
    );
}

#[test]
fn missing_ground_named() {
    let e = err(&FUNCTION.replace("ground = 0.1\n", ""));
    assert!(
        e.contains("synthesis.ground: missing; give the ground link d (m)"),
        "{e}"
    );
}

#[test]
fn unknown_type_named() {
    let e = err("[synthesis]\ntype = \"gears\"\n");
    assert_eq!(
        e,
        "p.toml:2:8: synthesis.type: unknown synthesis type 'gears'; expected \"motion\", \"function\", \
         \"two_positions\", \"burmester\", \"slider_motion\", \"slider_function\", \"path\", \
         \"dead_centre\", \"cognates\" or \"ball_point\""
    );
}

#[test]
fn syntax_error_located() {
    let e = err("[synthesis\ntype = 1\n");
    assert!(e.starts_with("p.toml:1:"), "{e}");
}

/// A solution's name becomes a file name in the output folder: a name
/// that would leave it (or hide the file) is refused.
#[test]
fn issue31_name_cannot_leave_the_output_folder() {
    for bad in ["../evil", "/abs", ".hidden", "a/b", "a\\b", ""] {
        let e = err(&format!("{MOTION}name = \"{bad}\"\n"));
        assert!(e.starts_with("p.toml:6:8: synthesis.name: '"), "{bad}: {e}");
    }
    let e = match solve_str(MOTION, ".x.toml", ".x") {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    };
    assert!(e.contains("give [synthesis] name"), "{e}");
    let ok = solve_str(&format!("{MOTION}name = \"arm-2.b\"\n"), "p.toml", "p").unwrap();
    assert_eq!(ok.solutions[0].name, "arm-2.b");
}

/// Poses far beyond a machine's size overflow to non-finite pivots: an
/// error, never a model file holding NaN.
#[test]
fn issue31_overflowing_poses_refused() {
    let text = r#"[synthesis]
type = "motion"
poses = [[-1.5e308, 0, 0], [1.5e308, 0, 0.5], [0, 1e308, 1.0]]
crank = { moving = [0.1, 0] }
rocker = { moving = [0, 0.1] }
"#;
    let e = err(text);
    assert!(
        e.contains("synthesis.poses: the poses and pivots are out of the range"),
        "{e}"
    );
}

/// Precision points may be listed in any order: they are taken in the
/// order the crank reaches them, so no order defect arises from the list.
#[test]
fn issue31_precision_points_in_any_order() {
    let sorted = solve_str(&format!("{FUNCTION}points = [2, 5, 9]\n"), "p.toml", "p").unwrap();
    let shuffled = solve_str(&format!("{FUNCTION}points = [9, 2, 5]\n"), "p.toml", "p").unwrap();
    let (a, b) = (&sorted.solutions[0].report, &shuffled.solutions[0].report);
    assert_eq!(a["x"], b["x"]);
    assert_eq!(a["k"], b["k"]);
    assert_eq!(b["checks"]["defects"], serde_json::json!([]));
}

/// One table says which fields each type takes: fields another type uses
/// are refused by name, not ignored (a path problem once took the
/// dead-centre fields silently, a dead-centre problem the search's, a
/// cognates problem the requirements).
#[test]
fn issue31_each_type_refuses_the_fields_it_does_not_take() {
    let path =
        "[synthesis]\ntype = \"path\"\ntargets = [[0, 0], [0.1, 0.02], [0.2, 0], [0.3, -0.05]]\n";
    let dead =
        "[synthesis]\ntype = \"dead_centre\"\nrocker_length = 0.1\nswing = 0.7\ntime_ratio = 1.2\n";
    let four = "four_bar = { O2 = [0, 0], O4 = [0.4, 0], crank = 0.12, coupler = 0.38, rocker = 0.3, point = [0.1, 0.1] }\n";
    let cognates = format!("[synthesis]\ntype = \"cognates\"\n{four}");
    let cases: Vec<(String, &str, &str)> = vec![
        (path.into(), "rocker_length = 0.2", "path"),
        (path.into(), "rocker_pivot = [0, 0]", "path"),
        (path.into(), "rocker_start = 0.1", "path"),
        (dead.into(), "starts = 4", "dead_centre"),
        (dead.into(), "units = \"mm\"", "dead_centre"),
        (dead.into(), "timing = \"free\"", "dead_centre"),
        (dead.into(), "method = \"fit\"", "dead_centre"),
        (dead.into(), "x = [0, 1]", "dead_centre"),
        (dead.into(), "turning = \"cw\"", "dead_centre"),
        (cognates.clone(), "turning = \"cw\"", "cognates"),
        (cognates.clone(), "min_transmission = 0.3", "cognates"),
        (cognates.clone(), "full_turn = true", "cognates"),
        (cognates, "keep = 2", "cognates"),
    ];
    for (base, line, kind) in cases {
        let field = line.split(' ').next().unwrap();
        let e = err(&format!("{base}{line}\n"));
        assert!(
            e.contains(&format!(
                "synthesis.{field}: not a field of a {kind} problem"
            )),
            "{line} in {kind}: {e}"
        );
    }
}
