//! Equilibrium: pendulums held by a torque, a mass hanging on a spring.

use crate::mechanisms;

use camlink_core::constraint::translational::Translational;
use camlink_core::dynamics::statics::{run, solve, Settings};
use camlink_core::force::point::Torque;
use camlink_core::force::tsda::Tsda;
use camlink_core::force::Force;
use camlink_core::run::Table;
use camlink_core::{BodyId, Model, TimeFn};
use mechanisms::{body, pendulum};

/// m g l sin θ = T, whichever frame the body has; the pivot carries the
/// weight.
#[test]
fn pendulum_held_by_a_torque() {
    let (l, mass, torque): (f64, f64, f64) = (0.5, 2.0, 4.0);
    let want = (torque / (mass * 9.81 * l)).asin();
    for at_pivot in [false, true] {
        let mut model = pendulum(l, mass, 0.02, 0.0, at_pivot);
        let bob = model.body_id("bob").unwrap();
        model.add_force(Force::new(
            "hold",
            Torque {
                body: bob,
                t: TimeFn::Const(torque),
            },
        ));
        let mut table = Table::default();
        run(&model, 0.0, &Settings::default(), &[], &mut table).unwrap();
        let v = |n: &str| table.channel(n).unwrap()[0];
        assert!(
            (v("bob.phi") - want).abs() < 1e-10,
            "{} vs {want}",
            v("bob.phi")
        );
        // The pivot holds the weight up; a revolute carries no torque.
        assert!(v("pivot.fx_j").abs() < 1e-9);
        assert!((v("pivot.fy_j") - mass * 9.81).abs() < 1e-9);
        assert!(v("pivot.torque_j").abs() < 1e-9);
        let e = solve(&model, 0.0, &Settings::default()).unwrap();
        assert!(e.iterations <= 10, "{} Newton iterations", e.iterations);
    }
}

/// A block on a vertical slide hanging from a spring: stretch m g / k, and
/// the slide carries no force along its axis.
#[test]
fn mass_on_a_spring() {
    let (mass, k, l0) = (3.0, 1200.0, 0.4);
    let mut model = Model::new("spring-mass");
    let block = model.add_body(body("block", [0.0, -0.3, 0.0], mass, 0.01, [0.0, 0.0]));
    model.add_joint(
        "slide",
        Translational {
            body_i: BodyId::GROUND,
            s_i: [0.0, 0.0],
            v_i: [0.0, 1.0],
            body_j: block,
            s_j: [0.0, 0.0],
            angle: 0.0,
        },
    );
    model.add_force(Force::new(
        "spring",
        Tsda {
            body_i: BodyId::GROUND,
            s_i: [0.0, 0.0],
            body_j: block,
            s_j: [0.0, 0.0],
            stiffness: k,
            free_length: l0,
            damping: 0.0,
            actuator: TimeFn::Const(0.0),
        },
    ));
    let mut table = Table::default();
    run(&model, 0.0, &Settings::default(), &[], &mut table).unwrap();
    let v = |n: &str| table.channel(n).unwrap()[0];
    let want = -(l0 + mass * 9.81 / k);
    assert!(
        (v("block.y") - want).abs() < 1e-10,
        "{} vs {want}",
        v("block.y")
    );
    assert!(v("slide.fy_j").abs() < 1e-9, "no force along the slide");
    assert!(v("slide.fx_j").abs() < 1e-9);
}
