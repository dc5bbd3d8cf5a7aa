//! A body's `outline` in the model file: a polyline or a closed curve of the
//! body, resolved for drawings; wrong ones are named by their field.

use camlink_model::{load_str, Format, OutlineShape};

const BASE: &str = r#"
[parameters]
w = 0.02

[[bodies]]
name = "plate"
points = { O = [0, 0], A = [0.1, 0] }
OUTLINE

[[bodies]]
name = "other"
position = [0.3, 0]

[[curves]]
name = "disc"
body = "plate"
source = "circle"
radius = 0.05

[[curves]]
name = "bar"
body = "other"
source = "circle"
radius = 0.01

[[curves]]
name = "edge"
body = "plate"
source = "line"
from = [0, 0]
to = [0.1, 0]

[[joints]]
name = "pivot"
type = "revolute"
body_i = "ground"
body_j = "plate"

[[joints]]
name = "p2"
type = "revolute"
body_i = "ground"
point_i = [0.3, 0]
body_j = "other"
"#;

fn with(outline: &str) -> Result<camlink_model::Loaded, String> {
    load_str(
        &BASE.replace("OUTLINE", outline),
        Format::Toml,
        "plate.toml",
    )
    .map_err(|e| e.to_string())
}

#[test]
fn polyline_outline_is_evaluated() {
    let l = with(r#"outline = [[0, "-w"], [0.1, "-w"], [0.1, "w"], [0, "w"]]"#).unwrap();
    assert_eq!(l.outlines.len(), 1);
    assert_eq!(l.outlines[0].body, "plate");
    match &l.outlines[0].shape {
        OutlineShape::Polyline(p) => assert_eq!(
            p,
            &vec![[0.0, -0.02], [0.1, -0.02], [0.1, 0.02], [0.0, 0.02]]
        ),
        OutlineShape::Curve(_) => panic!("expected a polyline"),
    }
}

#[test]
fn curve_outline_is_the_bodys_closed_curve() {
    let l = with(r#"outline = "disc""#).unwrap();
    assert!(matches!(&l.outlines[0].shape, OutlineShape::Curve(c) if c.closed()));
    assert!(with("").unwrap().outlines.is_empty());
}

#[test]
fn bad_outlines_name_the_field() {
    let e = with(r#"outline = [[0, 0], [1, 0]]"#).unwrap_err();
    assert!(
        e.contains("bodies[0].outline") && e.contains("at least three corners, got 2"),
        "{e}"
    );
    let e = with(r#"outline = "dics""#).unwrap_err();
    assert!(
        e.contains("no curve named 'dics'") && e.contains("disc"),
        "{e}"
    );
    let e = with(r#"outline = "bar""#).unwrap_err();
    assert!(
        e.contains("curve 'bar' is on body 'other', not on 'plate'"),
        "{e}"
    );
    let e = with(r#"outline = "edge""#).unwrap_err();
    assert!(e.contains("curve 'edge' is open"), "{e}");
}
