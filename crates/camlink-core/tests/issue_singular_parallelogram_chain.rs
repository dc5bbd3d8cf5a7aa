//! Forward dynamics through singular positions: a chain of parallelogram
//! four-bars falls under gravity from the flat position (every crank at
//! 0°, where Φ_q loses one rank per four-bar) and swings to the other flat
//! position (−180°) and back, against the exact one-degree-of-freedom
//! motion θ̈ = −κ cos θ.

mod mechanisms;

use camlink_core::dynamics::integrator::{run, Settings};
use camlink_core::kinematics::{time_grid, Table};
use mechanisms::{parallelogram_chain, parallelogram_kappa, parallelogram_reference};

const G: f64 = 9.81;

/// Largest |θ − θ_exact| (rad) of crank 0 over [0, t_end], and the largest
/// spread of the crank angles (rad).
fn crank_error(n: usize, fused: bool, h: f64, tol: f64, t_end: f64) -> Result<(f64, f64), String> {
    let model = parallelogram_chain(n, 0.0, fused);
    let times = time_grid(t_end, 0.01).unwrap();
    let settings = Settings {
        step: h,
        tol,
        ..Settings::default()
    };
    let mut table = Table::default();
    run(&model, &times, &settings, &[], &mut table).map_err(|e| e.to_string())?;
    let want = parallelogram_reference(parallelogram_kappa(n, G), 0.0, &table.t);
    let th0 = table.channel("crank0.phi").unwrap();
    if std::env::var("CL_TRACE").is_ok() {
        for k in (0..th0.len()).step_by(5) {
            eprintln!("{:.3} {:.6} {:.6}", table.t[k], th0[k], want[k]);
        }
    }
    let err = th0.iter().zip(&want).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    let mut spread = 0.0f64;
    for k in 1..=n {
        let thk = table.channel(&format!("crank{k}.phi")).unwrap();
        spread = spread.max(thk.iter().zip(&th0).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max));
    }
    Ok((err, spread))
}

#[test]
fn reproduce() {
    let hs: Vec<f64> = std::env::var("CL_H").map(|v| vec![v.parse().unwrap()]).unwrap_or(vec![1e-3, 1e-4]);
    let tols: Vec<f64> = std::env::var("CL_TOL").map(|v| vec![v.parse().unwrap()]).unwrap_or(vec![1e-6, 1e-8, 1e-10]);
    for &h in &hs {
        for &tol in &tols {
            let r = crank_error(2, false, h, tol, 1.2);
            eprintln!("h {h:e} tol {tol:e}: {r:?}");
        }
    }
}

#[test]
fn reproduce_fused() {
    for n in [2usize, 40] {
        for th in [-0.5, 0.0] {
            let model = parallelogram_chain(n, th, true);
            let times = time_grid(1.2, 0.01).unwrap();
            let settings = Settings { step: 1e-3, tol: 1e-8, ..Settings::default() };
            let mut table = Table::default();
            let r = run(&model, &times, &settings, &[], &mut table);
            match r {
                Err(e) => eprintln!("fused n {n} th {th}: {e}"),
                Ok(_) => {
                    let want = parallelogram_reference(parallelogram_kappa(n, G), th, &table.t);
                    let th0 = table.channel("crank0.phi").unwrap();
                    let err = th0.iter().zip(&want).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
                    eprintln!("fused n {n} th {th}: err {err:e}");
                }
            }
        }
    }
}
