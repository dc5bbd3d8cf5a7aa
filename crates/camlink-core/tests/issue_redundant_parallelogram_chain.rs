//! Redundant constraints: the parallelogram chain with its couplers fused
//! into one rigid bar (n + 1 cranks on one bar: n − 1 redundant
//! equations, one degree of freedom) runs in forward dynamics and
//! equilibrium, names its redundant equations, and reports the
//! minimum-norm multipliers.

use crate::mechanisms;

use camlink_core::assembly::Assembly;
use camlink_core::diagnose::dense_jacobian;
use camlink_core::dynamics::integrator::{run, Integrator, Settings};
use camlink_core::dynamics::statics;
use camlink_core::run::{time_grid, Kind, Table, Warning};
use mechanisms::{parallelogram_chain, parallelogram_error, CrankMass};

const G: f64 = 9.81;
const CRANK: CrankMass = CrankMass::Uniform;

/// Largest |θ − θ_exact| of crank 0 (rad) released at rest from `th0`,
/// and the run's warnings.
fn fused_error(n: usize, th0: f64, h: f64, t_end: f64) -> (f64, Vec<Warning>) {
    let model = parallelogram_chain(n, th0, true, CRANK);
    let times = time_grid(t_end, 0.01).unwrap();
    let settings = Settings {
        step: h,
        tol: 1e-10,
        ..Settings::default()
    };
    let mut table = Table::default();
    let summary = run(&model, &times, &settings, &[], &mut table).unwrap();
    let err = parallelogram_error(&table, n, CRANK, th0, G);
    (err, summary.warnings)
}

/// Two cranks on one bar are not redundant; three or more are. The
/// motion matches θ̈ = −κ cos θ at second order.
#[test]
fn fused_chain_of_three_cranks_runs_and_names_its_redundant_equation() {
    let (e1, warnings) = fused_error(2, -0.5, 1e-3, 0.6);
    let (e2, _) = fused_error(2, -0.5, 5e-4, 0.6);
    eprintln!(
        "fused chain N = 2: max |θ − θ_exact| {e1:.2e} rad (h = 1e-3 s), {e2:.2e} rad (h = 5e-4 s)"
    );
    assert!(e1 < 2e-4, "{e1}");
    assert!(e1 / e2 > 3.0, "{e1} / {e2}: not second order");
    let w = warnings
        .iter()
        .find(|w| w.kind == Kind::Redundant)
        .unwrap_or_else(|| panic!("no redundancy warning in {warnings:?}"));
    assert_eq!(w.joints, ["O0", "O1", "O2", "P0", "P1", "P2"], "{w:?}");
    let m = &w.message;
    assert!(m.starts_with("1 redundant constraint equation"), "{m}");
    assert!(
        m.contains("minimum-norm") && m.contains("not unique"),
        "{m}"
    );
    assert!(m.contains("P2."), "{m}");
}

/// N = 40: 39 redundant equations, a sparse augmented matrix.
#[test]
fn fused_chain_of_forty_one_cranks_runs() {
    let (err, warnings) = fused_error(40, -0.5, 1e-3, 0.3);
    eprintln!("fused chain N = 40: max |θ − θ_exact| {err:.2e} rad");
    assert!(err < 1e-4, "{err}");
    assert!(
        warnings
            .iter()
            .any(|w| w.kind == Kind::Redundant && w.message.starts_with("39 redundant")),
        "{warnings:?}"
    );
}

/// The reported multipliers give the same generalized constraint forces
/// Φ_qᵀλ as the integrator's own, and have no component in the null
/// space of Φ_qᵀ (the minimum-norm split) beyond the rounding that the
/// regularisation amplifies, ε_mach / EPS_REL ≈ 2e-8 of |λ| (checked at 1e-5).
#[test]
fn reactions_of_a_redundant_chain_are_the_minimum_norm_split() {
    let model = parallelogram_chain(3, -0.5, true, CRANK);
    let mut it = Integrator::new(&model, Settings::default()).unwrap();
    for _ in 0..50 {
        it.step(1e-3).unwrap();
    }
    let m = it.sys.m();
    let mut lam = vec![0.0; m];
    it.min_norm_multipliers(&mut lam).unwrap();
    let asm = Assembly::new(&model);
    let j = dense_jacobian(&model, &asm, &it.state().q, it.state().t);
    let n = j.ncols();
    let force = |l: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|c| (0..m).map(|r| j[(r, c)] * l[r]).sum())
            .collect()
    };
    let (f_int, f_min) = (force(&it.state().lambda), force(&lam));
    let scale = f_int.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    for c in 0..n {
        assert!(
            (f_int[c] - f_min[c]).abs() < 1e-8 * scale,
            "{c}: {} vs {}",
            f_int[c],
            f_min[c]
        );
    }
    assert_eq!(null_component(&j, &lam), (2, true));
}

/// (number of redundant equations, whether λ has no component in the
/// left null space of Φ_q = `j` beyond 1e-5 |λ|).
fn null_component(j: &faer::Mat<f64>, lam: &[f64]) -> (usize, bool) {
    let m = j.nrows();
    let svd = j.svd().unwrap();
    let s = svd.S().column_vector();
    let rank = (0..s.nrows()).filter(|&k| s[k] > 1e-9 * s[0]).count();
    let u = svd.U();
    let norm = lam.iter().map(|v| v * v).sum::<f64>().sqrt();
    let small = (rank..m).all(|k| {
        let w: f64 = (0..m).map(|r| u[(r, k)] * lam[r]).sum();
        eprintln!("null-space component {w:.2e} of |λ| {norm:.3e}");
        w.abs() < 1e-5 * norm
    });
    (m - rank, small)
}

/// Equilibrium of the fused chain: every crank hangs straight down, with
/// the minimum-norm multipliers.
#[test]
fn fused_chain_equilibrium_hangs_down() {
    for n in [2, 40] {
        let model = parallelogram_chain(n, -1.2, true, CRANK);
        let e = statics::solve(&model, 0.0, &statics::Settings::default())
            .unwrap_or_else(|e| panic!("N = {n}: {e:?}"));
        let asm = Assembly::new(&model);
        let j = dense_jacobian(&model, &asm, &e.q, 0.0);
        assert_eq!(null_component(&j, &e.lambda), (n - 1, true), "N = {n}");
        for k in 0..=n {
            let c = asm.body_col(k + 1).unwrap();
            let th = e.q[c + 2];
            assert!(
                (th + std::f64::consts::FRAC_PI_2).abs() < 1e-9,
                "N = {n}: crank {k} at {th}"
            );
        }
    }
}
