//! Issue 27: `camlink check` (the diagnosis of Φ_q at the start) counts a
//! unilateral contact only when it is closed at the placement: a free disc
//! above a line has 3 degrees of freedom, not 2.

use camlink_core::diagnose::diagnose;
use camlink_model::{load_str, Format, Loaded};

/// A disc of radius 0.1 m with its centre at `y` (m) above a floor (a face
/// on the ground along x), the contact unilateral with `law`.
fn disc(y: f64, law: &str) -> Loaded {
    let text = format!(
        r#"
[model]
name = "disc"

[[bodies]]
name = "disc"
position = [0.3, {y}]
mass = 2
inertia = 0.01

[[curves]]
name = "rim"
body = "disc"
source = "circle"
centre = [0, 0]
radius = 0.1

[[joints]]
type = "flat_follower"
name = "floor"
curve_i = "rim"
body_j = "ground"
axis = [1, 0]
unilateral = true
{law}
"#
    );
    load_str(&text, Format::Toml, "disc.toml").unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn issue27_check_open_contact_is_not_counted() {
    // 0.5 m of air under the disc: the contact removes no freedom.
    let l = disc(0.6, "");
    let d = diagnose(&l.model, 0.0, l.analysis.tol);
    assert_eq!(d.dof, 3, "{d:#?}");
    assert_eq!(d.rank, 0);
    assert_eq!(d.coordinates, 3);
    assert_eq!(d.equations, 0);
    let [r] = d.released.as_slice() else {
        panic!("{d:#?}")
    };
    assert_eq!(r.joint, "floor");
    let gap = r.gap.expect("a gap");
    assert!((gap - 0.5).abs() < 1e-9, "{gap}");
    assert_eq!(
        r.text,
        "contact 'floor': open at t = 0 s (gap 0.5 m): its 2 equations and 1 own \
         coordinate are not counted"
    );

    // Resting on the floor: closed, counted as a bilateral contact.
    let l = disc(0.1, "");
    let d = diagnose(&l.model, 0.0, l.analysis.tol);
    assert!(d.released.is_empty(), "{d:#?}");
    assert_eq!(d.dof, 2);

    // A gap within OPEN_AT_START is closed by the assembly.
    let l = disc(0.1 + 5e-7, "");
    let d = diagnose(&l.model, 0.0, l.analysis.tol);
    assert!(d.released.is_empty(), "{d:#?}");
    assert_eq!(d.dof, 2);

    // A compliant contact is a force, never a constraint, even touching.
    let l = disc(0.1, "stiffness = 1e6\nexponent = 1.5");
    let d = diagnose(&l.model, 0.0, l.analysis.tol);
    let [r] = d.released.as_slice() else {
        panic!("{d:#?}")
    };
    assert_eq!(r.gap, None);
    assert!(
        r.text.starts_with("contact 'floor': compliant"),
        "{}",
        r.text
    );
    assert_eq!(d.dof, 3);
}

/// `check` and a forward dynamics run open the same contacts at the start:
/// the run's features and threshold are the diagnosis's own
/// (`diagnose::gap_features`, `diagnose::OPEN_AT_START`).
#[test]
fn issue27_check_and_dynamics_share_the_open_contact_rule() {
    use camlink_core::diagnose::OPEN_AT_START;
    use camlink_core::dynamics::integrator::{run, Settings};
    use camlink_core::run::Table;
    for y in [
        0.1,
        0.1 + 0.5 * OPEN_AT_START,
        0.1 + 2.0 * OPEN_AT_START,
        0.6,
    ] {
        let l = disc(y, "");
        let d = diagnose(&l.model, 0.0, l.analysis.tol);
        let mut table = Table::default();
        run(
            &l.model,
            &[0.0, 1e-3],
            &Settings::default(),
            &[],
            &mut table,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let state = table.channel("floor.state").expect("floor.state")[0];
        let open_in_check = !d.released.is_empty();
        assert_eq!(
            open_in_check,
            state == 0.0,
            "y = {y} m: check {d:#?}, the run's state {state}"
        );
        assert_eq!(open_in_check, y - 0.1 > OPEN_AT_START, "y = {y} m");
    }
}
