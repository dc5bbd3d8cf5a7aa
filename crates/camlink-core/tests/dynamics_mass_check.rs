//! Forward dynamics refuses a body without mass or inertia, naming it,
//! instead of failing on a singular mass matrix.

use camlink_core::constraint::revolute::Revolute;
use camlink_core::dynamics::integrator;
use camlink_core::kinematics::Table;
use camlink_core::{Body, BodyId, Model};

#[test]
fn massless_body_is_named_before_integrating() {
    let mut m = Model::new("pendulum");
    let mut arm = Body::new("arm", [0.5, 0.0, 0.0]);
    arm.mass = 1.0; // inertia left at zero
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
    let err = integrator::run(
        &m,
        &[0.0, 0.1],
        &Default::default(),
        &[],
        &mut Table::default(),
    )
    .unwrap_err();
    assert!(
        err.message.contains("'arm'") && err.message.contains("inertia"),
        "{err}"
    );
}
