//! Round trip of cam synthesis: camlink's kinematic analysis of the
//! synthesised cam with its matching follower joint reproduces the motion
//! program over a full turn, for the four follower types, several laws
//! and both senses of rotation.

use std::sync::Arc;

use camlink_core::cam::{Cam, Follower, LawKind, Program, SegmentSpec};

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

/// Runs a full turn in 720 steps and compares the follower's coordinate
/// (y of a translating follower, φ of an oscillating one) and its rates
/// with the program: position within 1e-9 of the lift, rates within 1e-7
/// of their peaks.
fn round_trip(cam: Cam, lift: f64) {
    let cam = Arc::new(cam);
    let r =
        camlink_core::cam_mechanism::round_trip(&cam, OMEGA, 720).unwrap_or_else(|e| panic!("{e}"));
    let name = cam.follower.name();
    assert_eq!(r.steps, 721);
    assert!(
        r.displacement < 1e-9,
        "{name}: displacement error {:e} of the lift {lift}",
        r.displacement
    );
    assert!(r.velocity < 1e-7, "{name}: velocity error {:e}", r.velocity);
    assert!(
        r.acceleration < 1e-7,
        "{name}: acceleration error {:e}",
        r.acceleration
    );
}

#[test]
fn translating_roller_with_offset_reproduces_the_program() {
    for (rise, ret, ccw, offset) in [
        (LawKind::Cycloidal, LawKind::Poly345, true, 0.004),
        (
            LawKind::ModifiedSine,
            LawKind::ModifiedTrapezoid,
            false,
            -0.006,
        ),
        (LawKind::Poly4567, LawKind::SimpleHarmonic, true, 0.0),
    ] {
        let f = Follower::TranslatingRoller {
            offset,
            roller: 0.008,
        };
        round_trip(
            Cam::new(program(rise, ret, 0.012), f, 0.03, ccw).unwrap(),
            0.012,
        );
    }
}

#[test]
fn translating_flat_faced_reproduces_the_program() {
    for (rise, ret, ccw) in [
        (LawKind::Cycloidal, LawKind::Poly4567, true),
        (LawKind::ModifiedTrapezoid, LawKind::Poly345, false),
    ] {
        let f = Follower::TranslatingFlat;
        round_trip(
            Cam::new(program(rise, ret, 0.008), f, 0.03, ccw).unwrap(),
            0.008,
        );
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
        round_trip(
            Cam::new(program(rise, ret, lift), f, 0.03, ccw).unwrap(),
            lift,
        );
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
        round_trip(
            Cam::new(program(rise, ret, lift), f, 0.04, ccw).unwrap(),
            lift,
        );
    }
}
