//! Issue 32: balancing, flywheel and motor sizing of `camlink_core::machine`.

use crate::common::four_bar_with;
use crate::mechanisms;

use camlink_core::dynamics::inverse::run;
use camlink_core::machine::{self, balance, flywheel, motor, Motor, Spec};
use camlink_core::run::{Settings, Table};
use camlink_core::Model;

/// max |F_s| (N) of an inverse-dynamics run of `model` over `times`.
fn peak_shaking(model: &Model, times: &[f64]) -> f64 {
    let mut t = Table::default();
    run(model, times, &Settings::default(), &[], &mut t).unwrap();
    let (x, y) = (
        t.channel("shaking.fx").unwrap(),
        t.channel("shaking.fy").unwrap(),
    );
    x.iter()
        .zip(&y)
        .fold(0.0f64, |a, (x, y)| a.max(x.hypot(*y)))
}

fn cycle(omega: f64, n: usize) -> Vec<f64> {
    let period = 2.0 * std::f64::consts::PI / omega;
    (0..=n).map(|i| period * i as f64 / n as f64).collect()
}

/// A crank-rocker with masses whose centroids sit off the link lines: the
/// counterweights of the Berkof–Lowen conditions leave a shaking force of
/// rounding size over the whole cycle (gravity off, so the frame carries
/// only the inertia forces).
#[test]
fn issue32_balanced_four_bar_shakes_nothing() {
    let omega = 2.0 * std::f64::consts::PI * 4.0;
    let mut model = four_bar_with([0.4, 0.12, 0.38, 0.3], 0.3, omega);
    model.gravity = [0.0, 0.0];
    for (b, (m, j, c)) in model.bodies.iter_mut().skip(1).zip([
        (0.6, 1e-3, [0.05, 0.01]),
        (1.5, 2e-2, [0.2, 0.04]),
        (1.1, 9e-3, [0.14, -0.02]),
    ]) {
        (b.mass, b.inertia, b.centroid) = (m, j, c);
    }
    let crank = model.body_id("crank").unwrap();
    let b = balance::full_force_balance(&model, crank).unwrap();
    assert_eq!(b.linkage, "four_bar");
    let bodies: Vec<&str> = b.counterweights.iter().map(|c| c.body.as_str()).collect();
    assert_eq!(bodies, ["crank", "rocker"]);
    let times = cycle(omega, 180);
    let before = peak_shaking(&model, &times);
    let after = peak_shaking(&balance::apply(&model, &b), &times);
    eprintln!("four-bar shaking force {before:.3} N, balanced {after:.2e} N");
    assert!(before > 50.0, "an unbalanced four-bar shakes: {before} N");
    assert!(
        after <= 1e-10 * before,
        "balanced four-bar shakes {after} N"
    );
}

/// The slider-crank of `mechanisms`: a counterweight on the rod and one on
/// the crank balance the shaking force, the slider's included.
#[test]
fn issue32_balanced_slider_crank_shakes_nothing() {
    let omega = 2.0 * std::f64::consts::PI * 5.0;
    let mut model = mechanisms::slider_crank(0.3, omega, true);
    model.gravity = [0.0, 0.0];
    let crank = model.body_id("crank").unwrap();
    let b = balance::full_force_balance(&model, crank).unwrap();
    assert_eq!(b.linkage, "slider_crank");
    assert_eq!(b.counterweights.len(), 2);
    let times = cycle(omega, 180);
    let before = peak_shaking(&model, &times);
    let after = peak_shaking(&balance::apply(&model, &b), &times);
    eprintln!("slider-crank shaking force {before:.3} N, balanced {after:.2e} N");
    assert!(
        after <= 1e-10 * before,
        "balanced slider-crank shakes {after} N"
    );
}

/// T = T₀ + A sin 2θ: T̄ = T₀, E(θ) = A (1 − cos 2θ)/2, ΔE = A exactly,
/// E largest at θ = π/2; I = ΔE/(C_s ω²). RMS √(T₀² + A²/2), peak T₀ + A.
#[test]
fn issue32_flywheel_closed_form() {
    let (t0, a, n) = (12.0, 30.0, 720);
    let theta: Vec<f64> = (0..=n)
        .map(|i| 2.0 * std::f64::consts::PI * i as f64 / n as f64)
        .collect();
    let torque: Vec<f64> = theta.iter().map(|t| t0 + a * (2.0 * t).sin()).collect();
    let f = flywheel::fluctuation(&theta, &torque);
    assert!((f.mean_torque - t0).abs() <= 1e-12 * t0);
    // The grid holds the extremes θ = π/4·k exactly: ΔE to the trapezoidal
    // rule's O(h²) error, A h²/12 · 4 relative at worst.
    let h = theta[1];
    assert!(
        (f.delta_e - a).abs() <= a * h * h,
        "ΔE {} against {a}",
        f.delta_e
    );
    assert!((f.theta_max - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    let (cs, w) = (0.02, 100.0);
    assert_eq!(flywheel::inertia(a, cs, w), a / (cs * w * w));
    assert!((flywheel::band(a, flywheel::inertia(a, cs, w), w) - cs * w).abs() < 1e-12);
    let speed = vec![w; theta.len()];
    let d = motor::duty(2.0, &theta, &speed, &torque);
    let rms = (t0 * t0 + a * a / 2.0).sqrt() / 2.0;
    assert!(
        (d.rms_torque - rms).abs() <= 1e-12 * rms,
        "rms {} against {rms}",
        d.rms_torque
    );
    assert!((d.peak_torque - (t0 + a) / 2.0).abs() < 1e-12);
    assert!((d.peak_power - (t0 + a) * w).abs() < 1e-9);
}

/// The motor curve is linear between its points and ends at its last.
#[test]
fn issue32_motor_curve() {
    let m = Motor {
        curve: vec![(0.0, 10.0), (100.0, 8.0), (200.0, 2.0)],
        gear_ratio: 1.0,
        rated_torque: None,
        rated_power: None,
    };
    assert_eq!(m.available(50.0), Some(9.0));
    assert_eq!(m.available(150.0), Some(5.0));
    assert_eq!(m.available(200.0), Some(2.0));
    assert_eq!(m.available(200.1), None);
}

/// The whole analysis of the slider-crank: the flywheel sized for
/// C_s = 0.02 keeps the forward run's speed in that band (to the first
/// order in C_s that the formula neglects: the link's own varying inertia).
#[test]
fn issue32_flywheel_forward_run_keeps_the_band() {
    let omega = 2.0 * std::f64::consts::PI * 5.0;
    let model = mechanisms::slider_crank(0.3, omega, true);
    let spec = Spec {
        driver: "motor".into(),
        speed: omega,
        speed_band: Some(0.02),
        steps: 360,
        point: [0.0, 0.0],
        balance: true,
        motor: Some(Motor {
            curve: vec![(0.0, 40.0), (100.0, 30.0)],
            gear_ratio: 3.0,
            rated_torque: Some(5.0),
            rated_power: None,
        }),
    };
    let r = machine::analyse(&model, &spec).unwrap();
    let f = r.flywheel.as_ref().unwrap();
    eprintln!(
        "T̄ {:.4} N·m, ΔE {:.4} J, I {:.5} kg·m², run: ω {:.4}..{:.4} rad/s, Cs {:.5}; balanced peak {:?}; checks {:?}",
        f.mean_torque, f.delta_e, f.inertia, f.omega_min, f.omega_max, f.cs_run, r.balanced_peak_force, r.checks
    );
    assert!(
        (f.cs_run - f.cs).abs() <= 0.05 * f.cs,
        "Cs {} against {}",
        f.cs_run,
        f.cs
    );
    // Balanced, only the weight of the links and counterweights is left.
    let shaking = r.balanced_peak_force.unwrap();
    assert!(
        shaking <= 1e-10 * r.shaking.peak_dynamic,
        "balanced: {shaking} N"
    );
    let mid = 0.5 * (f.omega_max + f.omega_min);
    assert!(
        (mid - omega).abs() <= 0.05 * f.cs * omega,
        "band centred at {mid}, not {omega}"
    );
}
