//! Newton's stopping test at the rounding level: forward dynamics with
//! steps so small that a tolerance on the velocity corrections γ'|Δq|
//! asks for position corrections below the rounding of the coordinates.
//! `camlink run examples/dyn_slider_crank.toml -a dynamics --t-end 0.0005
//! --step 0.0005 --h 1e-7 --tol 1e-10` is the command of the report.

use std::path::Path;

use camlink_core::dynamics::integrator::{run, Adaptive, Settings};
use camlink_core::run::{Summary, Table};
use camlink_model::load_path;

/// Forward dynamics of `examples/dyn_slider_crank.toml` from 0 to `t_end`
/// (s) with `settings`; checks that the constraints hold (max |Φ| < 1e-12)
/// and returns the summary.
fn run_slider_crank(settings: &Settings, t_end: f64) -> Summary {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/dyn_slider_crank.toml");
    let l = load_path(&path).unwrap_or_else(|e| panic!("{e}"));
    let mut table = Table::default();
    let summary =
        run(&l.model, &[0.0, t_end], settings, &[], &mut table).unwrap_or_else(|e| panic!("{e}"));
    let phi = table.channel("constraint.residual").unwrap();
    assert!(phi.iter().all(|v| *v < 1e-12), "{phi:?}");
    summary
}

/// h = 1e-7 s, tol = 1e-10: γ' ≈ 2e7 /s, so a velocity tolerance of 1e-10
/// m/s asks for |Δq| ≤ 5e-18 m, below the rounding of coordinates of
/// 0.1 m (about 1e-17 m). The run completes.
#[test]
fn tiny_steps_with_a_tight_tolerance_converge() {
    let settings = Settings {
        step: 1e-7,
        tol: 1e-10,
        ..Settings::default()
    };
    let summary = run_slider_crank(&settings, 5e-4);
    assert_eq!(summary.steps, 5000);
    // About one Newton iteration a step: the predictor is already within
    // rounding at this step.
    let per_step = summary.newton_iterations as f64 / summary.steps as f64;
    eprintln!("{per_step:.2} Newton iterations a step");
    assert!(per_step < 3.0, "{per_step}");
}

/// The error-controlled mode with a tight atol shrinks its step towards
/// h_min = 1e-8 s; it must not shrink into a Newton failure (with a
/// velocity test that ignores rounding it failed at h ≈ 2.4e-7 s).
#[test]
fn adaptive_steps_with_a_tight_atol_run() {
    let settings = Settings {
        step: 1e-3,
        tol: 1e-10,
        adaptive: Some(Adaptive {
            atol: 1e-16,
            rtol: 0.0,
            h_min: 1e-8,
        }),
        ..Settings::default()
    };
    let summary = run_slider_crank(&settings, 5e-5);
    eprintln!("adaptive, atol 1e-16: {} steps", summary.steps);
}
