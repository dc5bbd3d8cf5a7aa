//! A `near_singular` warning names the joints whose equations lose rank:
//! the joints of the weakest combination of equations of Φ_q, in its
//! `joints` field and its text, in kinematics and in forward dynamics.

use crate::common;
use crate::mechanisms;

use camlink_core::constraint::absolute::{AbsoluteCoord, Coord};
use camlink_core::dynamics::integrator::{self, Settings as DynSettings};
use camlink_core::kinematics;
use camlink_core::run::{time_grid, Kind, Settings, Table, Warning};
use camlink_core::TimeFn;
use mechanisms::{parallelogram_chain, CrankMass};

fn near_singular(warnings: &[Warning]) -> Vec<&Warning> {
    warnings
        .iter()
        .filter(|w| w.kind == Kind::NearSingular)
        .collect()
}

/// A slider pushed towards the dead centre of a slider-crank (crank 0.1 m,
/// rod 0.3 m, the dead centre at x = 0.4 m): near it the crank and the rod
/// line up with the slide, and the only self-stressed set of equations is
/// the line of force O → crank → A → rod → B → slider → push (the slide
/// carries no force along its axis).
#[test]
fn slider_crank_near_dead_centre_names_the_line_of_force() {
    let mut model = common::slider_crank(0.1, 0.3, 1.0);
    let slider = model.body_id("slider").unwrap();
    let x0 = model.body(slider).q0[0];
    // Reaches 1e-9 m short of the dead centre at t = 1 s (the crank 1.2e-4
    // rad from the line).
    let rate = 0.4 - 1e-9 - x0;
    model.add_driver(
        "push",
        AbsoluteCoord {
            body: slider,
            s: [0.0, 0.0],
            coord: Coord::X,
            f: TimeFn::Linear { value: x0, rate },
        },
    );
    let times = time_grid(1.0, 1e-3).unwrap();
    let mut table = Table::default();
    let summary = kinematics::run(&model, &times, &Settings::default(), &[], &mut table).unwrap();
    let found = near_singular(&summary.warnings);
    assert_eq!(found.len(), 1, "{:?}", summary.warnings);
    assert_eq!(found[0].joints, ["O", "A", "B", "push"], "{:?}", found[0]);
    assert!(
        found[0].message.contains("at joints O, A, B, push"),
        "{}",
        found[0].message
    );
}

/// The parallelogram four-bar through its change point: all four
/// revolutes carry the self-stress along the line, the motor does not.
#[test]
fn parallelogram_change_point_names_its_four_revolutes() {
    let model = common::four_bar_with([0.5, 0.2, 0.5, 0.2], 2.0, 2.0);
    let mut model = model;
    let coupler = model.body_id("coupler").unwrap();
    let rocker = model.body_id("rocker").unwrap();
    model.bodies[coupler.0].q0[2] = 0.0;
    model.bodies[rocker.0].q0[2] = 2.0;
    let times = time_grid(1.0, 1e-3).unwrap();
    let mut table = Table::default();
    let summary = kinematics::run(&model, &times, &Settings::default(), &[], &mut table).unwrap();
    let found = near_singular(&summary.warnings);
    assert!(!found.is_empty(), "{:?}", summary.warnings);
    assert_eq!(found[0].joints, ["O2", "B", "C", "O4"], "{:?}", found[0]);
}

/// Forward dynamics of a parallelogram four-bar released at its flat
/// position: the warning at t = 0 names the four revolutes that carry the
/// self-stress along the line (the one lost direction).
#[test]
fn dynamics_at_the_flat_position_names_the_joints() {
    let model = parallelogram_chain(1, 0.0, false, CrankMass::AtPin);
    let times = time_grid(0.02, 0.01).unwrap();
    let mut table = Table::default();
    let settings = DynSettings::default();
    let summary = integrator::run(&model, &times, &settings, &[], &mut table).unwrap();
    let found = near_singular(&summary.warnings);
    assert_eq!(found.len(), 1, "{:?}", summary.warnings);
    assert_eq!(found[0].time, 0.0);
    assert_eq!(found[0].joints, ["O0", "O1", "L0", "R0"], "{:?}", found[0]);
    assert!(
        found[0].message.contains("at joints O0, O1, L0, R0"),
        "{}",
        found[0].message
    );
}
