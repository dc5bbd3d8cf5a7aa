//! Assembly from rough placements: converge, and stay on the branch nearest
//! the guess.

use crate::common;

use camlink_core::kinematics::run;
use camlink_core::run::{Settings, Table};
use common::{four_bar_with, freudenstein};

const L: [f64; 4] = [0.4, 0.1, 0.35, 0.3];

/// Assembles the four-bar at t = 0 after moving the coupler and rocker by
/// (dφ, dx, dy) from the open branch, and returns (θ₃, θ₄).
fn assemble_from(
    dphi: f64,
    dx: f64,
    dy: f64,
    rocker_phi: Option<f64>,
) -> (f64, f64, Vec<(String, [f64; 3])>) {
    let mut m = four_bar_with(L, 0.5, 1.0);
    for name in ["coupler", "rocker"] {
        let b = m.body_id(name).unwrap();
        let q = &mut m.bodies[b.0].q0;
        q[0] += dx;
        q[1] += dy;
        q[2] += dphi;
    }
    if let Some(phi) = rocker_phi {
        let b = m.body_id("rocker").unwrap();
        m.bodies[b.0].q0[2] = phi;
    }
    let mut table = Table::default();
    let s = run(&m, &[0.0], &Settings::default(), &[], &mut table).unwrap();
    (
        table.channel("coupler.phi").unwrap()[0],
        table.channel("rocker.phi").unwrap()[0],
        s.assembly_moves,
    )
}

fn same_angle(a: f64, b: f64) -> bool {
    let d = (a - b).rem_euclid(2.0 * std::f64::consts::PI);
    d.min(2.0 * std::f64::consts::PI - d) < 1e-9
}

#[test]
fn thirty_degrees_and_ten_percent_off_assembles_on_the_open_branch() {
    let (open, _, _) = freudenstein(L, 0.5, 1.0, -1.0);
    for (dphi, dx, dy) in [(0.5, 0.03, -0.02), (-0.5, -0.03, 0.02), (0.3, 0.0, 0.04)] {
        let (th3, th4, moves) = assemble_from(dphi, dx, dy, None);
        assert!(
            same_angle(th3, open[0]) && same_angle(th4, open[1]),
            "{dphi} {dx} {dy}: {th3} {th4} vs {open:?}"
        );
        // Assembly says what it moved: the coupler and rocker, by about the offsets.
        let rocker = moves.iter().find(|(b, _)| b == "rocker").unwrap().1;
        assert!((rocker[2] + dphi).abs() < 0.2, "{moves:?}");
    }
}

#[test]
fn a_guess_near_the_crossed_branch_stays_crossed() {
    let (crossed, _, _) = freudenstein(L, 0.5, 1.0, 1.0);
    let (_, th4, _) = assemble_from(0.0, 0.0, 0.0, Some(crossed[1] + 0.3));
    assert!(same_angle(th4, crossed[1]), "{th4} vs {crossed:?}");
}
