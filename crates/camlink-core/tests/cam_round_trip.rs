//! Round trip of cam synthesis: camlink's kinematic analysis of the
//! synthesised cam with its matching follower joint reproduces the motion
//! program over a full turn, for the four follower types, several laws
//! and both senses of rotation.

use std::f64::consts::TAU;
use std::sync::Arc;

use camlink_core::cam::{Cam, Follower, LawKind, Program, SegmentSpec};
use camlink_core::cam_mechanism::mechanism;
use camlink_core::kinematics::{run, Settings, Table};

/// Cam speed ω (rad/s): not 1, so that the time scaling is exercised.
const OMEGA: f64 = 3.0;

fn program(rise: LawKind, ret: LawKind, lift: f64) -> Program {
    let d = |x: f64| x.to_radians();
    Program::new(&[
        SegmentSpec::new(LawKind::Dwell, d(40.0), 0.0),
        SegmentSpec::new(rise, d(110.0), lift),
        SegmentSpec::new(LawKind::Dwell, d(50.0), 0.0),
        SegmentSpec::new(ret, d(160.0), -lift),
    ])
    .unwrap()
}

/// Runs a full turn and compares the follower's coordinate (y of a
/// translating follower, φ of an oscillating one) and its rates with
/// the program: position within 1e-9 of the lift, rates within 1e-7
/// of their scale.
fn round_trip(cam: Cam, lift: f64) {
    let cam = Arc::new(cam);
    let model = mechanism(&cam, OMEGA);
    let n = 720;
    // Times off the segment boundaries, so that a law's jump in a higher
    // derivative does not make the comparison ambiguous.
    let times: Vec<f64> = (0..=n)
        .map(|k| (k as f64 + 0.3) / n as f64 * TAU / OMEGA)
        .collect();
    let settings = Settings {
        tol: 1e-13,
        max_iter: 25,
    };
    let mut table = Table::default();
    run(&model, &times, &settings, &[], &mut table).unwrap_or_else(|e| panic!("{e}"));
    let c = if cam.follower.oscillating() { "phi" } else { "y" };
    let r = if cam.follower.oscillating() { ["omega", "alpha"] } else { ["vy", "ay"] };
    let x = table.channel(&format!("follower.{c}")).unwrap();
    let v = table.channel(&format!("follower.{}", r[0])).unwrap();
    let a = table.channel(&format!("follower.{}", r[1])).unwrap();
    let p = &cam.program;
    let scale_v = (0..3600)
        .map(|k| p.eval(k as f64 * TAU / 3600.0)[1].abs())
        .fold(0.0, f64::max)
        * OMEGA;
    let scale_a = (0..3600)
        .map(|k| p.eval(k as f64 * TAU / 3600.0)[2].abs())
        .fold(0.0, f64::max)
        * OMEGA
        * OMEGA;
    let (mut ex, mut ev, mut ea) = (0.0f64, 0.0f64, 0.0f64);
    for (k, &t) in times.iter().enumerate() {
        let want = cam.follower_coordinate(OMEGA * t);
        ex = ex.max((x[k] - want[0]).abs() / lift.abs());
        ev = ev.max((v[k] - OMEGA * want[1]).abs() / scale_v);
        ea = ea.max((a[k] - OMEGA * OMEGA * want[2]).abs() / scale_a);
    }
    let name = cam.follower.name();
    assert!(ex < 1e-9, "{name}: displacement error {ex:e} of the lift");
    assert!(ev < 1e-7, "{name}: velocity error {ev:e}");
    assert!(ea < 1e-7, "{name}: acceleration error {ea:e}");
}

#[test]
fn translating_roller_with_offset_reproduces_the_program() {
    for (rise, ret, ccw, offset) in [
        (LawKind::Cycloidal, LawKind::Poly345, true, 0.004),
        (LawKind::ModifiedSine, LawKind::ModifiedTrapezoid, false, -0.006),
        (LawKind::Poly4567, LawKind::SimpleHarmonic, true, 0.0),
    ] {
        let f = Follower::TranslatingRoller { offset, roller: 0.008 };
        round_trip(Cam::new(program(rise, ret, 0.012), f, 0.03, ccw).unwrap(), 0.012);
    }
}

#[test]
fn translating_flat_faced_reproduces_the_program() {
    for (rise, ret, ccw) in [
        (LawKind::Cycloidal, LawKind::Poly4567, true),
        (LawKind::ModifiedTrapezoid, LawKind::Poly345, false),
    ] {
        let f = Follower::TranslatingFlat;
        round_trip(Cam::new(program(rise, ret, 0.008), f, 0.03, ccw).unwrap(), 0.008);
    }
}

#[test]
fn oscillating_roller_reproduces_the_program() {
    for (rise, ret, ccw) in [
        (LawKind::Cycloidal, LawKind::ModifiedSine, true),
        (LawKind::Poly345, LawKind::Cycloidal, false),
    ] {
        let f = Follower::OscillatingRoller {
            pivot: 0.08,
            arm: 0.06,
            roller: 0.008,
        };
        let lift = 15f64.to_radians();
        round_trip(Cam::new(program(rise, ret, lift), f, 0.03, ccw).unwrap(), lift);
    }
}

#[test]
fn oscillating_flat_faced_reproduces_the_program() {
    for (rise, ret, ccw, e) in [
        (LawKind::Cycloidal, LawKind::Poly4567, true, 0.0),
        (LawKind::Poly345, LawKind::ModifiedSine, false, 0.01),
    ] {
        let f = Follower::OscillatingFlat {
            pivot: 0.1,
            face_offset: e,
        };
        let lift = 8f64.to_radians();
        round_trip(Cam::new(program(rise, ret, lift), f, 0.04, ccw).unwrap(), lift);
    }
}
