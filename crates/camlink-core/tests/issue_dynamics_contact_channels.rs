//! Dynamic analyses fill the contact channels (`<joint>.cx`, `.cy`) that
//! the kinematic channel list includes; they were once left at zero, which
//! shifted nothing but reported a contact point at the origin.

use camlink_core::constraint::absolute::{AbsoluteCoord, Coord};
use camlink_core::constraint::point_follower::PointFollower;
use camlink_core::curve::{Curve, Polar};
use camlink_core::dynamics::{integrator, statics};
use camlink_core::run::Table;
use camlink_core::{Body, BodyId, Model, TimeFn};

/// A bead (mass 1 kg) in a circular slot of radius 0.5 m on the ground,
/// released from about 29° below horizontal: a pendulum without a rod.
fn bead_in_slot() -> Model {
    let mut m = Model::new("bead");
    let th: f64 = -0.5;
    let mut bead = Body::new("bead", [0.5 * th.cos(), 0.5 * th.sin(), 0.0]);
    bead.mass = 1.0;
    bead.inertia = 1e-3;
    let bead = m.add_body(bead);
    let slot = Curve::Polar(Polar::circle([0.0, 0.0], 0.5).unwrap());
    m.add_joint(
        "slot",
        PointFollower::new(bead, [0.0, 0.0], BodyId::GROUND, slot),
    );
    // The bead slides without turning, so that its equilibrium is unique.
    m.add_joint(
        "no_spin",
        AbsoluteCoord {
            body: bead,
            s: [0.0, 0.0],
            coord: Coord::Phi,
            f: TimeFn::Const(0.0),
        },
    );
    m
}

fn check_contact_is_the_bead(table: &Table) {
    let (x, y) = (
        table.channel("bead.x").unwrap(),
        table.channel("bead.y").unwrap(),
    );
    let (cx, cy) = (
        table.channel("slot.cx").unwrap(),
        table.channel("slot.cy").unwrap(),
    );
    for k in 0..x.len() {
        assert!(
            (x[k] - cx[k]).abs() < 1e-9 && (y[k] - cy[k]).abs() < 1e-9,
            "step {k}"
        );
    }
}

#[test]
fn forward_dynamics_fills_contact_channels() {
    let model = bead_in_slot();
    let times: Vec<f64> = (0..50).map(|k| k as f64 * 1e-3).collect();
    let mut table = Table::default();
    integrator::run(&model, &times, &Default::default(), &[], &mut table).unwrap();
    check_contact_is_the_bead(&table);
}

#[test]
fn equilibrium_fills_contact_channels() {
    let model = bead_in_slot();
    let mut table = Table::default();
    statics::run(&model, 0.0, &Default::default(), &[], &mut table).unwrap();
    check_contact_is_the_bead(&table);
    // The bead rests at the bottom of the slot.
    assert!((table.channel("slot.cy").unwrap()[0] + 0.5).abs() < 1e-9);
}
