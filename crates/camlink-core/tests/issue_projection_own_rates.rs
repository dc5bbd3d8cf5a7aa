//! Initial velocities given for the bodies are kept when they already
//! satisfy the constraints: the contact parameters' rates are derived from
//! them, not shared with them by the projection (which once started a cam
//! given ω₀ at about ω₀/2).

use camlink_core::constraint::absolute::{AbsoluteCoord, Coord};
use camlink_core::constraint::point_follower::PointFollower;
use camlink_core::curve::{Curve, Polar};
use camlink_core::dynamics::integrator;
use camlink_core::run::Table;
use camlink_core::{Body, BodyId, Model, TimeFn};

#[test]
fn a_bead_launched_along_its_slot_keeps_its_speed() {
    let (r, th, v) = (0.5f64, -0.5f64, 2.0);
    let mut m = Model::new("bead");
    let mut bead = Body::new("bead", [r * th.cos(), r * th.sin(), 0.0]);
    bead.mass = 1.0;
    bead.inertia = 1e-3;
    // Tangent to the slot, counter-clockwise: consistent with the constraint.
    bead.qd0 = [-v * th.sin(), v * th.cos(), 0.0];
    let bead = m.add_body(bead);
    let slot = Curve::Polar(Polar::circle([0.0, 0.0], r).unwrap());
    m.add_joint(
        "slot",
        PointFollower::new(bead, [0.0, 0.0], BodyId::GROUND, slot),
    );
    m.add_joint(
        "no_spin",
        AbsoluteCoord {
            body: bead,
            s: [0.0, 0.0],
            coord: Coord::Phi,
            f: TimeFn::Const(0.0),
        },
    );
    let mut table = Table::default();
    integrator::run(&m, &[0.0, 1e-3], &Default::default(), &[], &mut table).unwrap();
    let (vx, vy) = (
        table.channel("bead.vx").unwrap()[0],
        table.channel("bead.vy").unwrap()[0],
    );
    assert!(
        (vx.hypot(vy) - v).abs() < 1e-12,
        "speed {} instead of {v}",
        vx.hypot(vy)
    );
}
