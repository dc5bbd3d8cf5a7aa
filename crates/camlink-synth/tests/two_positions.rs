//! Two-position motion generation: the example's model, run by camlink's
//! kinematics, passes its poses to 1e-9; every choice along the bisectors
//! keeps both pivots' distances; bad input is named.

use camlink_synth::{solve_path, solve_str};
use serde_json::Value;

use crate::burmester::{assert_passes_poses, examples, floats};

#[test]
fn issue31_two_positions_example_passes_its_poses() {
    let out = solve_path(&examples().join("synthesis_two_positions.toml")).unwrap();
    let s = &out.solutions[0];
    assert_eq!(s.report["method"], "two_positions");
    assert_eq!(s.report["checks"]["defects"], Value::Array(vec![]));
    assert_passes_poses(s);
}

/// Across the free parameters (the distances along the bisectors, and a
/// ground pivot chosen instead of a moving one), every defect-free
/// solution passes its poses in camlink's kinematics.
#[test]
fn issue31_two_positions_free_choices_pass_their_poses() {
    let base = std::fs::read_to_string(examples().join("synthesis_two_positions.toml")).unwrap();
    let mut checked = 0;
    for (tc, tr) in [
        (0.02, -0.15),
        (-0.1, -0.3),
        (0.3, 0.1),
        (0.0, 0.0),
        (-0.2, 0.25),
    ] {
        for fixed in [false, true] {
            let mut text = base.replace(
                "along = [0.02, -0.15]",
                &format!("along = [{tc:?}, {tr:?}]"),
            );
            if fixed {
                text = text
                    .replace(
                        "crank = { moving = [-0.05, -0.08] }",
                        "crank = { fixed = [-0.05, -0.2] }",
                    )
                    .replace(
                        "rocker = { moving = [0.08, -0.06] }",
                        "rocker = { fixed = [0.2, -0.1] }",
                    );
            }
            let s = &solve_str(&text, "t.toml", "t").unwrap().solutions[0];
            let r = &s.report;
            // Both pivots keep their distance at the two poses.
            let links = &r["links"];
            let o2 = floats(&links["O2"]);
            let a = floats(&r["moving_pivots"]["A"]);
            let poses = crate::burmester::poses_of(r);
            let d: Vec<f64> = poses
                .iter()
                .map(|p| {
                    let q = p.place([a[0], a[1]]);
                    (q[0] - o2[0]).hypot(q[1] - o2[1])
                })
                .collect();
            assert!((d[0] - d[1]).abs() < 1e-14);
            if r["checks"]["defects"].as_array().unwrap().is_empty() {
                assert_passes_poses(s);
                checked += 1;
            }
        }
    }
    assert!(checked >= 4, "{checked}");
}

#[test]
fn issue31_two_positions_bad_input_named() {
    let base = std::fs::read_to_string(examples().join("synthesis_two_positions.toml")).unwrap();
    let same = base.replace("[0.1, 0.04, \"deg(30)\"]", "[0.0, 0.0, 0.0]");
    let e = solve_str(&same, "p.toml", "p").unwrap_err().to_string();
    assert!(
        e.starts_with("p.toml:16:9: synthesis.poses: poses 1 and 2 coincide"),
        "{e}"
    );
    let three = base.replace(
        "[0.1, 0.04, \"deg(30)\"],",
        "[0.1, 0.04, \"deg(30)\"], [0.2, 0.0, 1],",
    );
    let e = solve_str(&three, "p.toml", "p").unwrap_err().to_string();
    assert!(
        e.contains("3 poses given; a two_positions problem takes 2"),
        "{e}"
    );
    let slider = base.replace("along =", "slider = { angle = 0 }\nalong =");
    let e = solve_str(&slider, "p.toml", "p").unwrap_err().to_string();
    assert!(
        e.contains("synthesis.slider: not a field of a two_positions problem"),
        "{e}"
    );
}

/// The fields of these kinds are refused in the other kinds' problems.
#[test]
fn issue31_guidance_fields_refused_elsewhere() {
    let three = std::fs::read_to_string(examples().join("synthesis_three_positions.toml")).unwrap();
    let text = three.replace("turning =", "along = [0.1, 0.2]\nturning =");
    let e = solve_str(&text, "p.toml", "p").unwrap_err().to_string();
    assert!(
        e.contains("synthesis.along: not a field of a motion problem"),
        "{e}"
    );
}
