//! The exports' geometry: a circle fits to arcs with its exact centre and
//! radius, chordal angles keep an exact profile within the tolerance, and
//! the bounds of steps and tolerances are held.

use std::f64::consts::TAU;
use std::path::Path;

use camlink_cam::export::{
    angles_by_chord, angles_by_step, check_tolerance, chord_angles, circle, fit_arcs, fit_run,
};
use camlink_cam::limits::{MAX_CSV_ROWS, MIN_RELATIVE_TOLERANCE};

const CENTRE: [f64; 2] = [0.3, -0.2];
const RADIUS: f64 = 0.05;

fn on_circle(t: f64) -> [f64; 2] {
    [CENTRE[0] + RADIUS * t.cos(), CENTRE[1] + RADIUS * t.sin()]
}

#[test]
fn a_circle_fits_to_one_arc_with_its_exact_centre_and_radius() {
    // 101 points over 120° counterclockwise, their edges 2.7e-6 m from the
    // circle at most: one arc within 1e-5 m.
    let run: Vec<[f64; 2]> = (0..=100)
        .map(|k| on_circle(0.3 + k as f64 * TAU / 3.0 / 100.0))
        .collect();
    let a = fit_run(&run, 1e-5).unwrap();
    assert!((a.centre[0] - CENTRE[0]).abs() < 1e-14, "{a:?}");
    assert!((a.centre[1] - CENTRE[1]).abs() < 1e-14, "{a:?}");
    assert!((a.radius - RADIUS).abs() < 1e-14, "{a:?}");
    assert!((a.start - 0.3f64.to_degrees()).abs() < 1e-10, "{a:?}");
    assert!(
        (a.end - (0.3 + TAU / 3.0).to_degrees()).abs() < 1e-10,
        "{a:?}"
    );
    assert_eq!((a.p0, a.p1), (run[0], run[100]));
    // Run clockwise, the same arc: its ends swap so that it runs
    // counterclockwise.
    let back: Vec<[f64; 2]> = run.iter().rev().copied().collect();
    let b = fit_run(&back, 1e-5).unwrap();
    assert!((b.start - a.start).abs() < 1e-10 && (b.end - a.end).abs() < 1e-10);
    // Three points: the circle through them.
    let (c, r) = circle(on_circle(0.1), on_circle(2.0), on_circle(4.0)).unwrap();
    assert!((c[0] - CENTRE[0]).abs() < 1e-15 && (c[1] - CENTRE[1]).abs() < 1e-15);
    assert!((r - RADIUS).abs() < 1e-15);
    assert!(circle([0.0, 0.0], [1.0, 1.0], [2.0, 2.0]).is_none());
    // Collinear points are a line.
    let line: Vec<[f64; 2]> = (0..10).map(|k| [k as f64 * 0.01, 0.5]).collect();
    assert!(fit_run(&line, 1e-9).unwrap().radius.is_infinite());
}

#[test]
fn a_closed_circle_is_covered_by_arcs_of_its_centre_and_radius() {
    let n = 360;
    let points: Vec<[f64; 2]> = (0..n)
        .map(|k| on_circle(k as f64 * TAU / n as f64))
        .collect();
    // Edges 1.9e-6 m from the circle at most. A run cannot end on its own
    // start (its ends and middle fix the circle): one arc through all the
    // points, then the closing edge as its own chord.
    let arcs = fit_arcs(&points, 1e-5, 0.0).unwrap();
    assert_eq!(arcs.len(), 2);
    assert_eq!((arcs[0].p0, arcs[0].p1), (points[0], points[n - 1]));
    assert!(arcs[1].radius.is_infinite());
    for a in &arcs[..1] {
        assert!((a.centre[0] - CENTRE[0]).abs() < 1e-12, "{a:?}");
        assert!((a.centre[1] - CENTRE[1]).abs() < 1e-12, "{a:?}");
        assert!((a.radius - RADIUS).abs() < 1e-12, "{a:?}");
    }
    // The pieces share their ends and close the polygon.
    for w in arcs.windows(2) {
        assert_eq!(w[0].p1, w[1].p0);
    }
    assert_eq!(arcs[0].p0, points[0]);
    assert_eq!(arcs[arcs.len() - 1].p1, points[0]);
    // A point that is not finite is named.
    let mut bad = points.clone();
    bad[7] = [f64::NAN, 0.0];
    assert_eq!(
        fit_arcs(&bad, 1e-5, 0.0).unwrap_err(),
        "the profile's point 7 is not finite"
    );
    // A tolerance that the polygon's own distance from the curve uses up.
    let e = fit_arcs(&points, 1e-5, 1e-5).unwrap_err();
    assert!(e.contains("must be above"), "{e}");
}

#[test]
fn chord_angles_keep_an_exact_profile_within_the_tolerance() {
    // On a circle the chord strays most at an interval's middle, by the
    // sagitta R (1 − cos(Δθ/2)): each interval within the tolerance, and
    // none shorter than half the longest interval that would be.
    let tol = 1e-6;
    let th = chord_angles(on_circle, tol).unwrap();
    assert_eq!(th[0], 0.0);
    let longest = 2.0 * (1.0 - tol / RADIUS).acos();
    let mut ends = th.clone();
    ends.push(TAU);
    for w in ends.windows(2) {
        let span = w[1] - w[0];
        assert!(span > 0.0);
        let sagitta = RADIUS * (1.0 - (span / 2.0).cos());
        assert!(sagitta <= tol, "{span} rad strays {sagitta} m");
        assert!(span > 0.5 * longest, "{span} rad, longest {longest}");
    }
    // The chords of the valve cam's exported profile, probed at 16 points
    // per interval: within the tolerance.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let design = camlink_cam::load_path(&root.join("examples/cam_design_valve.toml"))
        .unwrap()
        .design;
    let cam = design.cam().unwrap();
    let tol = 1e-5;
    let th = angles_by_chord(&cam, tol, 0.0).unwrap();
    let mut ends = th.clone();
    ends.push(TAU);
    let mut worst: f64 = 0.0;
    for w in ends.windows(2) {
        let (p0, p1) = (cam.offset_point(w[0], 0.0), cam.offset_point(w[1], 0.0));
        let d = [p1[0] - p0[0], p1[1] - p0[1]];
        let ln = d[0].hypot(d[1]);
        for k in 1..16 {
            let p = cam.offset_point(w[0] + (w[1] - w[0]) * k as f64 / 16.0, 0.0);
            let e = (d[0] * (p[1] - p0[1]) - d[1] * (p[0] - p0[0])).abs() / ln;
            worst = worst.max(e);
        }
    }
    assert!(worst <= tol, "{worst}");
}

#[test]
fn steps_and_tolerances_are_bounded() {
    let th = angles_by_step(1f64.to_radians()).unwrap();
    assert_eq!(th.len(), 360);
    assert_eq!(th[1], TAU / 360.0);
    assert_eq!(angles_by_step(TAU).unwrap().len(), 3);
    let finest = (360.0 / MAX_CSV_ROWS as f64).to_radians();
    assert_eq!(angles_by_step(finest).unwrap().len(), MAX_CSV_ROWS);
    assert!(angles_by_step(1e-7f64.to_radians())
        .unwrap_err()
        .contains("rows"));
    // A step so small that its count of rows is no integer's.
    let e = angles_by_step(1e-300).unwrap_err();
    assert!(e.contains("makes 6.28319e+300 rows"), "{e}");
    assert!(angles_by_step(0.0).unwrap_err().contains("positive"));
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let design = camlink_cam::load_path(&root.join("examples/cam_design_valve.toml"))
        .unwrap()
        .design;
    let cam = design.cam().unwrap();
    let size = camlink_core::cam_limits::geometry(&cam).max_radius;
    assert!(check_tolerance(&cam, MIN_RELATIVE_TOLERANCE * size, 0.0).is_ok());
    let e = check_tolerance(&cam, 0.5 * MIN_RELATIVE_TOLERANCE * size, 0.0).unwrap_err();
    assert!(e.contains("finer than"), "{e}");
    assert!(angles_by_chord(&cam, 1e-300, 0.0).is_err());
    assert!(check_tolerance(&cam, f64::NAN, 0.0).is_err());
}
