//! A free motion with nothing acting on it balances everywhere: equilibrium
//! analysis reports it as neutral instead of returning the placement.

use camlink_core::constraint::revolute::Revolute;
use camlink_core::dynamics::statics;
use camlink_core::run::Kind;
use camlink_core::{Body, BodyId, Model};

fn pendulum(gravity: [f64; 2]) -> Model {
    let mut m = Model::new("pendulum");
    m.gravity = gravity;
    let mut arm = Body::new("arm", [0.5, 0.0, 0.0]);
    arm.mass = 1.0;
    arm.inertia = 0.02;
    let arm = m.add_body(arm);
    m.add_joint(
        "pivot",
        Revolute {
            body_i: BodyId::GROUND,
            s_i: [0.0, 0.0],
            body_j: arm,
            s_j: [-0.5, 0.0],
        },
    );
    m
}

#[test]
fn a_pendulum_without_gravity_is_neutral() {
    let err = statics::solve(&pendulum([0.0, 0.0]), 0.0, &Default::default()).unwrap_err();
    assert_eq!(err.kind, Kind::LockUp, "{err}");
    assert!(err.message.contains("neutral equilibrium"), "{err}");
}

#[test]
fn a_pendulum_with_gravity_hangs_down() {
    let e = statics::solve(&pendulum([0.0, -9.81]), 0.0, &Default::default()).unwrap();
    // The arm hangs straight down: φ = −π/2 (its frame at the centroid).
    let phi = e.q[2].rem_euclid(2.0 * std::f64::consts::PI);
    assert!((phi - 1.5 * std::f64::consts::PI).abs() < 1e-9, "{phi}");
}
