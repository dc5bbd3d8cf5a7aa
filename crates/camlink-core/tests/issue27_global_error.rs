//! Issue 27 item 3: the global error of error-controlled runs falls with
//! `atol`, on IFToMM A01 (simple pendulum), IFToMM A02 (N-four-bar, N = 40),
//! Andrews' squeezing mechanism ([`super::andrews`]) and the free
//! slider-crank of [`super::dynamics_forward`], each against an independent
//! minimal-coordinate solution (Andrews': the IVP test set's reference). The table of
//! docs/validation.md:
//! `cargo test --release -p camlink-core --test integration issue27_global_error -- --ignored --nocapture`.

use crate::andrews::{andrews, angles, Y_REF};
use crate::dynamics_forward::{free_slider_crank, reference, TH0, W0};
use crate::issue27_a02::a02_errors;
use crate::mechanisms;

use camlink_core::dynamics::integrator::{run, Adaptive, Integrator, Settings};
use camlink_core::run::{time_grid, Table};

/// Default settings, error-controlled at `atol` (m or rad), `rtol` = 0,
/// largest step `h_max` (s).
fn adaptive(h_max: f64, atol: f64) -> Settings {
    Settings {
        step: h_max,
        adaptive: Some(Adaptive {
            atol,
            rtol: 0.0,
            h_min: 1e-9,
        }),
        ..Settings::default()
    }
}

/// IFToMM A01: a mass of 1 kg on a massless 1 m rod, released at rest from
/// the horizontal, 10 s; the point mass is a small bob of J' = 1e-4 kg·m²
/// (dynamics needs a body's inertia). (The bob's distance (m) from its
/// exact place at 10 s, the largest over the 0.01 s outputs, steps);
/// exact: θ̈ = −κ sin θ from the downward vertical, κ = m g l/(J' + m l²),
/// by RK4.
fn a01_errors(settings: &Settings) -> (f64, f64, usize) {
    let j = 1e-4;
    let model = mechanisms::pendulum(1.0, 1.0, j, std::f64::consts::FRAC_PI_2, true);
    let times = time_grid(10.0, 0.01).unwrap();
    let mut table = Table::default();
    let summary = run(&model, &times, settings, &[], &mut table).unwrap();
    // ψ = θ − π/2 obeys ψ̈ = −κ cos ψ from ψ = 0 at rest.
    let kappa = 9.81 / (j + 1.0);
    let want = mechanisms::pendulum_like_reference(kappa, 0.0, 0.0, &table.t);
    let th = table.channel("bob.phi").unwrap();
    let dist = |d: f64| 2.0 * (0.5 * d).sin().abs();
    let errs: Vec<f64> = th
        .iter()
        .zip(&want)
        .map(|(a, b)| dist(a - std::f64::consts::FRAC_PI_2 - b))
        .collect();
    let max = errs.iter().copied().fold(0.0, f64::max);
    (errs[errs.len() - 1], max, summary.steps)
}

/// The free slider-crank, θ₀ = 0.3 rad, ω₀ = 10 rad/s, 1 s: (|x − x_exact|
/// of the slider at 1 s (m), steps).
fn slider_crank_error(settings: &Settings) -> (f64, usize) {
    let model = free_slider_crank(TH0, W0);
    let (_, x_ref) = reference(TH0, W0, 1.0, 1e-5);
    let mut it = Integrator::new(&model, settings.clone()).unwrap();
    let mut h = settings.step.min(1e-4);
    it.advance_to(1.0, &mut h).unwrap();
    (
        (it.state().q[6] - x_ref).abs(),
        it.diagnostics().summary.steps,
    )
}

/// Andrews' mechanism to 0.03 s: (the largest error of its seven angles
/// there against the IVP test set (rad), steps).
pub fn andrews_error(settings: &Settings) -> (f64, usize) {
    let mut table = Table::default();
    let summary = run(&andrews(), &[0.0, 0.03], settings, &[], &mut table).unwrap();
    let phi: [f64; 7] =
        std::array::from_fn(|k| table.channel(&format!("K{}.phi", k + 1)).unwrap()[1]);
    let got = angles(phi);
    let err = got
        .iter()
        .zip(&Y_REF)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    (err, summary.steps)
}

#[test]
#[ignore = "the validation table, 3 minutes in release: cargo test --release -- --ignored issue27_global_error"]
fn issue27_global_error_falls_with_atol() {
    let atols = [1e-4, 1e-6, 1e-8];
    let mut failures = Vec::new();
    let mut rows = Vec::new();
    let mut row = |r: String| {
        eprintln!("{r}");
        rows.push(r);
    };
    for &h_max in &[1e-2, 1e-3] {
        let mut a01 = Vec::new();
        let mut a02 = Vec::new();
        let mut sc = Vec::new();
        let mut an = Vec::new();
        for &atol in &atols {
            let s = adaptive(h_max, atol);
            let (fin, steps) = andrews_error(&s);
            row(format!(
                "| Andrews, 0.03 s | {h_max:e} | {atol:e} | {fin:.1e} rad | | {steps} |"
            ));
            an.push(fin);
            let (fin, max, steps) = a01_errors(&s);
            row(format!(
                "| A01 pendulum, 10 s | {h_max:e} | {atol:e} | {fin:.1e} | {max:.1e} | {steps} |"
            ));
            a01.push(max);
            let (fin, max, steps, _) = a02_errors(40, &s, 20.0).unwrap();
            row(format!(
                "| A02 N = 40, 20 s | {h_max:e} | {atol:e} | {fin:.1e} | {max:.1e} | {steps} |"
            ));
            a02.push(max);
            let (fin, steps) = slider_crank_error(&s);
            row(format!(
                "| slider-crank, 1 s | {h_max:e} | {atol:e} | {fin:.1e} | | {steps} |"
            ));
            sc.push(fin);
        }
        // Falling with atol: at the largest step 0.01 s, every tighter
        // atol gives a smaller error, and 1e-8 one at least 10 times
        // smaller than 1e-4.
        if h_max == 1e-2 {
            let all = [
                ("A01", &a01),
                ("A02", &a02),
                ("Andrews", &an),
                ("slider-crank", &sc),
            ];
            for (name, e) in all {
                let falls = e.windows(2).all(|w| w[1] < w[0]) && e[2] * 10.0 <= e[0];
                failures.push((falls, format!("{name}: errors {e:?} at atol {atols:?}")));
            }
        }
    }
    eprintln!("| model | largest step (s) | atol | final error (m) | max error (m) | steps |");
    eprintln!("|---|---|---|---|---|---|");
    for r in rows {
        eprintln!("{r}");
    }
    let failed: Vec<_> = failures
        .iter()
        .filter(|(ok, _)| !ok)
        .map(|(_, m)| m)
        .collect();
    assert!(failed.is_empty(), "{failed:#?}");
}

/// One Andrews run from the environment, for measurements: `AN_H` (largest
/// or fixed step, s), `AN_ATOL` (error control when set), `AN_TOL`.
#[test]
#[ignore = "a probe: AN_ATOL=1e-8 cargo test --release -- --ignored issue27_andrews_probe"]
fn issue27_andrews_probe() {
    let get = |k: &str| std::env::var(k).ok().map(|v| v.parse::<f64>().unwrap());
    let mut s = Settings {
        step: get("AN_H").unwrap_or(1e-5),
        ..Settings::default()
    };
    if let Some(tol) = get("AN_TOL") {
        s.tol = tol;
    }
    if let Some(atol) = get("AN_ATOL") {
        s = adaptive(s.step, atol);
    }
    eprintln!("Andrews {s:?}: {:?}", andrews_error(&s));
}
