//! A body without mass makes forward dynamics singular; the error names it.
//! (A body without inertia is fine where joints fix its rotation, or where
//! it hangs as a point mass, so neither is refused up front.)

use camlink_core::constraint::revolute::Revolute;
use camlink_core::dynamics::integrator;
use camlink_core::run::{Kind, Table};
use camlink_core::{Body, BodyId, Model};

#[test]
fn massless_body_is_named_when_the_mass_matrix_is_singular() {
    let mut m = Model::new("pendulum");
    // No mass, no inertia: the pendulum's acceleration is undetermined.
    let arm = m.add_body(Body::new("arm", [0.5, 0.0, 0.0]));
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
    assert_eq!(err.kind, Kind::SingularMass, "{err}");
    assert!(
        err.message.contains("'arm'") && err.message.contains("inertia"),
        "{err}"
    );
}
