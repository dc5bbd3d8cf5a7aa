//! Inverse dynamics: driver torque against power balance, reactions of a
//! static two-bar truss against hand statics.

use crate::mechanisms;

use camlink_core::dynamics::inverse::run;
use camlink_core::force::point::PointForce;
use camlink_core::force::tsda::Tsda;
use camlink_core::force::Force;
use camlink_core::run::{time_grid, Settings, Table};
use camlink_core::{BodyId, Model, TimeFn};
use mechanisms::{body, rev, slider_crank};

/// The slider-crank driven at constant speed, with gravity and a spring on
/// the slider: the motor's power must equal d(T + V)/dt.
#[test]
fn slider_crank_driver_torque_matches_power_balance() {
    let omega = 2.0 * std::f64::consts::PI * 3.0;
    let mut model = slider_crank(0.3, omega, true);
    let slider = model.body_id("slider").unwrap();
    model.add_force(Force::new(
        "spring",
        Tsda {
            body_i: BodyId::GROUND,
            s_i: [0.6, 0.1],
            body_j: slider,
            s_j: [0.0, 0.0],
            stiffness: 500.0,
            free_length: 0.3,
            damping: 0.0,
            actuator: TimeFn::Const(0.0),
        },
    ));
    let h = 1e-4;
    let times = time_grid(0.4, h).unwrap();
    let mut table = Table::default();
    run(&model, &times, &Settings::default(), &[], &mut table).unwrap();
    let ch = |n: &str| table.channel(n).unwrap();
    let (effort, power, energy) = (ch("motor.effort"), ch("motor.power"), ch("energy.total"));
    let peak = power.iter().fold(0.0f64, |a, p| a.max(p.abs()));
    assert!(peak > 1.0, "the motor does work: {peak} W");
    let mut worst = 0.0f64;
    for k in 1..times.len() - 1 {
        // P = E ω, and P = d(T + V)/dt (central difference, O(h²)).
        assert!((power[k] - effort[k] * omega).abs() <= 1e-9 * peak);
        let de = (energy[k + 1] - energy[k - 1]) / (2.0 * h);
        worst = worst.max((power[k] - de).abs());
    }
    assert!(
        worst <= 1e-5 * peak,
        "power balance off by {worst} W (peak {peak} W)"
    );
}

/// Two massless bars pinned to the ground at A and C and to each other at
/// B, loaded by W downwards at B: two-force members whose axial forces
/// follow from the equilibrium of pin B.
#[test]
fn truss_reactions_match_hand_statics() {
    let (a, b, c) = ([0.0, 0.0], [0.4, 0.6], [1.2, 0.0]);
    let w = 1000.0;
    let bar = |p: [f64; 2], q: [f64; 2]| {
        let d = [q[0] - p[0], q[1] - p[1]];
        let l = d[0].hypot(d[1]);
        (
            l,
            [d[0] / l, d[1] / l],
            d[1].atan2(d[0]),
            [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])],
        )
    };
    let (l1, e1, phi1, m1) = bar(a, b);
    let (l2, e2, phi2, m2) = bar(c, b);
    let mut model = Model::new("truss");
    model.gravity = [0.0, -9.81];
    let b1 = model.add_body(body("bar1", [m1[0], m1[1], phi1], 0.0, 0.0, [0.0, 0.0]));
    let b2 = model.add_body(body("bar2", [m2[0], m2[1], phi2], 0.0, 0.0, [0.0, 0.0]));
    let g = BodyId::GROUND;
    model.add_joint("A", rev(g, a, b1, [-l1 / 2.0, 0.0]));
    model.add_joint("B", rev(b1, [l1 / 2.0, 0.0], b2, [l2 / 2.0, 0.0]));
    model.add_joint("C", rev(g, c, b2, [-l2 / 2.0, 0.0]));
    model.add_force(Force::new(
        "load",
        PointForce {
            body: b1,
            s: [l1 / 2.0, 0.0],
            f: [TimeFn::Const(0.0), TimeFn::Const(-w)],
            local: false,
        },
    ));
    let mut table = Table::default();
    run(&model, &[0.0], &Settings::default(), &[], &mut table).unwrap();
    let v = |n: &str| table.channel(n).unwrap()[0];

    // Pin B: N₁ e₁ + N₂ e₂ = (0, W), N > 0 in compression (Cramer).
    let det = e1[0] * e2[1] - e1[1] * e2[0];
    let n1 = (0.0 * e2[1] - w * e2[0]) / det;
    let n2 = (e1[0] * w - e1[1] * 0.0) / det;
    assert!(n1 > 0.0 && n2 > 0.0, "both bars in compression");
    let close = |got: f64, want: f64, what: &str| {
        assert!((got - want).abs() <= 1e-9 * w, "{what}: {got} vs {want}");
    };
    // The ground pushes bar 1 at A along the bar: N₁ e₁; the ground feels −N₁ e₁.
    close(v("A.fx_j"), n1 * e1[0], "A on bar1, x");
    close(v("A.fy_j"), n1 * e1[1], "A on bar1, y");
    close(v("A.fx"), -n1 * e1[0], "A on ground, x");
    close(v("A.fy"), -n1 * e1[1], "A on ground, y");
    // In bar 1's frame the force is axial: (N₁, 0).
    close(v("A.fx_local_j"), n1, "A on bar1, axial");
    close(v("A.fy_local_j"), 0.0, "A on bar1, transverse");
    close(v("C.fx_j"), n2 * e2[0], "C on bar2, x");
    close(v("C.fy_j"), n2 * e2[1], "C on bar2, y");
    close(v("C.fx_local_j"), n2, "C on bar2, axial");
    // Pin B on bar 1 balances N₁ e₁ and the load; on bar 2 the opposite.
    close(v("B.fx"), -n1 * e1[0], "B on bar1, x");
    close(v("B.fy"), -n1 * e1[1] + w, "B on bar1, y");
    close(v("B.fx_j"), n1 * e1[0], "B on bar2, x");
    close(v("B.fy_j"), n1 * e1[1] - w, "B on bar2, y");
    // A revolute joint carries no torque.
    for j in ["A", "B", "C"] {
        close(v(&format!("{j}.torque")), 0.0, "torque on i");
        close(v(&format!("{j}.torque_j")), 0.0, "torque on j");
    }
}

/// A crank held horizontal by its motor against gravity needs the torque
/// m g d (counter-clockwise) — the sign convention of efforts.
#[test]
fn motor_holding_a_crank_against_gravity() {
    let mut model = slider_crank(0.0, 0.0, true);
    // Only the crank has weight.
    for b in &mut model.bodies[2..] {
        b.mass = 0.0;
        b.inertia = 0.0;
    }
    let mut table = Table::default();
    run(&model, &[0.0], &Settings::default(), &[], &mut table).unwrap();
    let torque = table.channel("motor.effort").unwrap()[0];
    let want = mechanisms::MASS[0] * 9.81 * mechanisms::CRANK_CENTROID[0];
    assert!((torque - want).abs() < 1e-9, "{torque} vs {want}");
}
