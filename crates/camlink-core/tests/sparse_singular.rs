//! A large model (sparse path, over 120 unknowns) whose Jacobian is
//! singular at one joint that is not the first: the error names that joint.

use crate::mechanisms;

use camlink_core::constraint::absolute::{AbsoluteCoord, AbsoluteDistance, Coord};
use camlink_core::kinematics::run;
use camlink_core::run::{Kind, Settings, Table};
use camlink_core::TimeFn;
use mechanisms::chain;

#[test]
fn a_singular_joint_deep_in_a_large_chain_is_named() {
    // 50 links (150 coordinates): 50 pins, 49 angle drivers and, on link
    // 30, a zero-length distance from its end B to the ground point where
    // B is. That equation's Jacobian row 2 eᵀ[I B s′] vanishes at e = 0.
    let mut m = chain(50, 1.0);
    for k in 0..50 {
        let body = m.body_id(&format!("link{k}")).unwrap();
        if k == 30 {
            let tie = AbsoluteDistance {
                body,
                s: [0.5, 0.0],
                ground_point: [31.0, 0.0],
                f: TimeFn::Const(0.0),
            };
            m.add_joint("tie30", tie);
        } else {
            let drive = AbsoluteCoord {
                body,
                s: [0.0, 0.0],
                coord: Coord::Phi,
                f: TimeFn::Const(0.0),
            };
            m.add_joint(format!("drive{k}"), drive);
        }
    }
    let err = run(
        &m,
        &[0.0, 0.1],
        &Settings::default(),
        &[],
        &mut Table::default(),
    )
    .unwrap_err();
    assert_eq!(err.kind, Kind::LockUp, "{err}");
    assert_eq!(
        err.joints.first().map(String::as_str),
        Some("tie30"),
        "{err:?}"
    );
}
