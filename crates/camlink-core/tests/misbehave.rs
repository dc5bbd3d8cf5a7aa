//! Mechanisms that misbehave: drivers past reach, singular and change-point
//! configurations. The solver must explain itself and keep what it computed.

use crate::common;

use camlink_core::constraint::absolute::{AbsoluteCoord, Coord};
use camlink_core::constraint::relative::{RelCoord, RelativeCoord};
use camlink_core::kinematics::run;
use camlink_core::run::{time_grid, Kind, Settings, Table};
use camlink_core::{BodyId, TimeFn};
use common::{four_bar_with, slider_crank};

#[test]
fn crank_driven_past_its_reach_stops_at_the_limit() {
    // Non-Grashof (s + l > p + q): the input link rocks between limits where
    // the coupler and rocker stretch out, |O4 − B| = b + c.
    let l = [0.5, 0.3, 0.3, 0.35];
    let [d, a, b, c] = l;
    let omega = 1.0;
    let model = four_bar_with(l, 0.2, omega);
    let limit = ((a * a + d * d - (b + c) * (b + c)) / (2.0 * a * d)).acos();
    let times = time_grid(2.0, 1e-3).unwrap();
    let mut table = Table::default();
    let err = run(&model, &times, &Settings::default(), &[], &mut table).unwrap_err();
    let t_limit = limit - 0.2;
    // The run stops just past the limit, and keeps every step before it.
    assert!(
        err.time > t_limit - 1e-3 && err.time < t_limit + 2e-3,
        "{err:?} vs {t_limit}"
    );
    assert_eq!(
        table.t.len(),
        times.iter().filter(|&&t| t < err.time).count()
    );
    assert!(!err.joints.is_empty(), "{err}");
    assert!(err.residual > 0.0, "{err}");
    let msg = err.to_string();
    assert!(msg.contains("condition"), "{msg}");
}

#[test]
fn slider_driven_past_dead_centre_names_the_joints() {
    // Crank 0.1, rod 0.3: the slider cannot go beyond x = 0.4.
    let mut model = slider_crank(0.1, 0.3, 1.0);
    let slider = model.body_id("slider").unwrap();
    let x0 = model.body(slider).q0[0];
    model.add_driver(
        "push",
        AbsoluteCoord {
            body: slider,
            s: [0.0, 0.0],
            coord: Coord::X,
            f: TimeFn::Linear {
                value: x0,
                rate: 0.1,
            },
        },
    );
    let times = time_grid(2.0, 1e-3).unwrap();
    let mut table = Table::default();
    let err = run(&model, &times, &Settings::default(), &[], &mut table).unwrap_err();
    let t_reach = (0.4 - x0) / 0.1;
    assert!(
        err.time > t_reach - 0.01 && err.time < t_reach + 2e-3,
        "{err:?} vs {t_reach}"
    );
    assert!(table.t.len() > 100);
    assert!(
        err.joints
            .iter()
            .any(|j| ["A", "B", "push", "slide", "O"].contains(&j.as_str())),
        "{err}"
    );
}

#[test]
fn parallelogram_passes_its_change_point_without_flipping() {
    // A parallelogram four-bar: at θ₂ = π all links are collinear, Φ_q is
    // singular, and the antiparallelogram branch crosses this one. The
    // rocker must stay parallel to the crank, and a warning names the time.
    let l = [0.5, 0.2, 0.5, 0.2];
    let omega = 2.0;
    let th0 = 2.0;
    let mut model = four_bar_with(l, th0, omega);
    // Place the coupler and rocker exactly on the parallelogram branch.
    let coupler = model.body_id("coupler").unwrap();
    let rocker = model.body_id("rocker").unwrap();
    model.bodies[coupler.0].q0[2] = 0.0;
    model.bodies[rocker.0].q0[2] = th0;
    let times = time_grid(1.0, 1e-3).unwrap();
    let mut table = Table::default();
    let summary = run(&model, &times, &Settings::default(), &[], &mut table).unwrap();
    let (crank, rock) = (
        table.channel("crank.phi").unwrap(),
        table.channel("rocker.phi").unwrap(),
    );
    for k in 0..crank.len() {
        assert!(
            (crank[k] - rock[k]).abs() < 1e-8,
            "t = {}: {} vs {}",
            table.t[k],
            crank[k],
            rock[k]
        );
    }
    let t_change = (std::f64::consts::PI - th0) / omega;
    assert!(
        summary
            .warnings
            .iter()
            .any(|w| (w.time - t_change).abs() < 0.05 && w.kind == Kind::NearSingular),
        "{:?}",
        summary.warnings
    );
}

#[test]
fn log_of_a_negative_number_in_a_driver_is_named() {
    let mut model = slider_crank(0.1, 0.3, 1.0);
    let crank = model.body_id("crank").unwrap();
    let f = camlink_expr::Expr::parse("if(t < 0.5, 1, log(0.4 - t))", "t").unwrap();
    model.add_driver(
        "motor",
        RelativeCoord {
            body_i: BodyId::GROUND,
            s_i: [0.0, 0.0],
            body_j: crank,
            s_j: [0.0, 0.0],
            coord: RelCoord::Phi,
            f: TimeFn::from(f),
        },
    );
    let times = time_grid(1.0, 0.1).unwrap();
    let err = run(
        &model,
        &times,
        &Settings::default(),
        &[],
        &mut Table::default(),
    )
    .unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("'motor'") && msg.contains("log of a negative number"),
        "{msg}"
    );
    assert!((0.5..=0.6).contains(&err.time), "{err:?}");
}
