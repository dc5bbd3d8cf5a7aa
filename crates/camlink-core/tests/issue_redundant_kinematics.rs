//! Redundant constraints in kinematics and inverse dynamics: the fused
//! parallelogram chain (n + 1 cranks on one rigid bar, n − 1 redundant
//! equations) with a motor on crank 0 turning at constant speed is fully
//! driven. Kinematics solves it with the dependent rows left out; inverse
//! dynamics reports the minimum-norm multipliers, a motor torque equal
//! to the gravity torque of the exact one-degree-of-freedom model, and a
//! `redundant` warning naming the equations and joints.

use crate::common;
use crate::mechanisms;

use camlink_core::diagnose::dense_jacobian;
use camlink_core::dynamics::inverse;
use camlink_core::kinematics;
use camlink_core::run::{time_grid, Kind, Settings, Table, Warning};
use camlink_core::Model;
use mechanisms::{parallelogram_chain, CrankMass, PAR_COUPLER_MASS, PAR_CRANK, PAR_CRANK_MASS};

const G: f64 = 9.81;
const TH0: f64 = -0.5;
const OMEGA: f64 = -1.0;

/// The fused chain of `n` four-bars (uniform cranks) with crank 0 driven
/// at θ = θ₀ + ω t: from −0.5 to −1.5 rad over 1 s, clear of the flat
/// positions (θ = 0, −π), where Φ_q loses rank.
fn driven_chain(n: usize) -> Model {
    let mut m = parallelogram_chain(n, TH0, true, CrankMass::Uniform);
    let crank = m.body_id("crank0").unwrap();
    m.add_driver("motor", common::crank_motor(crank, TH0, OMEGA));
    m
}

fn redundant_warning(warnings: &[Warning]) -> &Warning {
    warnings
        .iter()
        .find(|w| w.kind == Kind::Redundant)
        .unwrap_or_else(|| panic!("no redundancy warning in {warnings:?}"))
}

/// Every crank and the bar follow θ = θ₀ + ω t exactly (the bar
/// translates on a circle of radius a).
#[test]
fn kinematics_of_a_redundant_chain_follows_the_driver() {
    for n in [2, 5] {
        let model = driven_chain(n);
        let times = time_grid(1.0, 0.01).unwrap();
        let mut table = Table::default();
        let summary =
            kinematics::run(&model, &times, &Settings::default(), &[], &mut table).unwrap();
        let w = redundant_warning(&summary.warnings);
        assert!(
            w.message.starts_with(&format!("{} redundant", n - 1)),
            "{}",
            w.message
        );
        for k in 0..=n {
            let th = table.channel(&format!("crank{k}.phi")).unwrap();
            let om = table.channel(&format!("crank{k}.omega")).unwrap();
            for (i, t) in table.t.iter().enumerate() {
                assert!((th[i] - (TH0 + OMEGA * t)).abs() < 1e-9, "crank{k} t {t}");
                assert!((om[i] - OMEGA).abs() < 1e-9, "crank{k} t {t}");
            }
        }
        let y = table.channel("coupler.y").unwrap();
        let ydd = table.channel("coupler.ay").unwrap();
        for (i, t) in table.t.iter().enumerate() {
            let th = TH0 + OMEGA * t;
            assert!((y[i] - PAR_CRANK * th.sin()).abs() < 1e-9);
            assert!((ydd[i] + PAR_CRANK * OMEGA * OMEGA * th.sin()).abs() < 1e-7);
        }
    }
}

/// The motor holds the chain against gravity at constant speed:
/// E = g (n_c m_c c + n m_b a) cos θ (the kinetic energy is constant),
/// and the multipliers are the minimum-norm ones (no component in the
/// null space of Φ_qᵀ beyond rounding).
#[test]
fn inverse_dynamics_of_a_redundant_chain_gives_minimum_norm_reactions() {
    let n = 3;
    let model = driven_chain(n);
    let times = time_grid(1.0, 0.05).unwrap();
    let mut table = Table::default();
    let summary = inverse::run(&model, &times, &Settings::default(), &[], &mut table).unwrap();
    let w = redundant_warning(&summary.warnings);
    assert!(w.message.contains("minimum-norm"), "{}", w.message);
    assert!(w.joints.contains(&"P3".to_string()), "{w:?}");
    let (_, c) = CrankMass::Uniform.inertia();
    let first = G * ((n + 1) as f64 * PAR_CRANK_MASS * c + n as f64 * PAR_COUPLER_MASS * PAR_CRANK);
    let effort = table.channel("motor.effort").unwrap();
    for (i, t) in table.t.iter().enumerate() {
        let want = first * (TH0 + OMEGA * t).cos();
        assert!(
            (effort[i] - want).abs() < 1e-8 * first,
            "t {t}: effort {} vs {want}",
            effort[i]
        );
    }
    // λ at t = 0.3 against the null space of Φ_qᵀ.
    let mut s = inverse::InverseSolver::new(&model, Settings::default()).unwrap();
    s.step(0.0, None).unwrap();
    s.step(0.3, Some(0.0)).unwrap();
    let j = dense_jacobian(&model, s.kin.assembly(), &s.kin.q, 0.3);
    let (m, nq) = (j.nrows(), j.ncols());
    let svd = j.svd().unwrap();
    let u = svd.U();
    let sv = svd.S().column_vector();
    let smax = (0..sv.nrows()).fold(0.0f64, |a, k| a.max(sv[k]));
    let rank = (0..sv.nrows()).filter(|&k| sv[k] > 1e-9 * smax).count();
    assert_eq!(rank, nq);
    assert_eq!(m - rank, n - 1);
    let lam_norm = s.lambda.iter().map(|v| v * v).sum::<f64>().sqrt();
    for col in rank..m {
        let dot: f64 = (0..m).map(|r| u[(r, col)] * s.lambda[r]).sum();
        // The regularised solve leaves rounding amplified by 1/EPS_REL:
        // ε_mach / 1e-8 ≈ 2.2e-8 of |λ|.
        assert!(
            dot.abs() < 5e-8 * lam_norm,
            "null-space component {dot} of |λ| {lam_norm}"
        );
    }
}
