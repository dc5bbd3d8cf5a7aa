//! The `[analysis]` table: analysis types, their settings and defaults, and
//! the errors for keys that do not fit the chosen type.

use camlink_core::dynamics::integrator::Adaptive;
use camlink_model::{load_str, AnalysisSpec, AnalysisType, Format, LoadError, Loaded};

/// A pendulum with `analysis` as its `[analysis]` table.
fn with_analysis(analysis: &str) -> Result<Loaded, LoadError> {
    let text = format!(
        r#"
[[bodies]]
name = "arm"
mass = 1
inertia = 0.01
centroid = [0.5, 0]

[[joints]]
type = "revolute"
name = "pivot"
body_i = "ground"
body_j = "arm"

[analysis]
{analysis}
"#
    );
    load_str(&text, Format::Toml, "m.toml")
}

fn error(analysis: &str) -> String {
    with_analysis(analysis).unwrap_err().to_string()
}

#[test]
fn kinematics_is_the_default_type() {
    let a = with_analysis("t_end = 1").unwrap().analysis;
    assert_eq!(a.kind, AnalysisType::Kinematics);
    assert_eq!((a.tol, a.max_iter), (1e-10, 25));
    assert!(!a.tol_set && !a.max_iter_set);
}

#[test]
fn dynamics_settings_and_defaults() {
    let a = with_analysis("type = \"dynamics\"\nt_end = 2\nstep = 0.01")
        .unwrap()
        .analysis;
    assert_eq!(a.kind, AnalysisType::Dynamics);
    // The integrator's own defaults; h follows the output step, at most 1 ms.
    let s = a.integrator_settings();
    assert_eq!(
        (s.step, s.rho_inf, s.tol, s.max_iter),
        (1e-3, 0.8, 1e-6, 12)
    );
    assert_eq!(s.adaptive, None);
    assert_eq!((a.tol, a.max_iter), (1e-6, 12));

    let a = with_analysis(
        "type = \"dynamics\"\nt_end = 2\nstep = 0.0005\nrho_inf = 0.5\nadaptive = true\nrtol = 1e-4\ntol = 1e-8",
    )
    .unwrap()
    .analysis;
    let s = a.integrator_settings();
    assert_eq!((s.step, s.rho_inf, s.tol), (0.0005, 0.5, 1e-8));
    assert_eq!(
        s.adaptive,
        Some(Adaptive {
            atol: 1e-6,
            rtol: 1e-4,
            h_min: 1e-8
        })
    );

    let a = with_analysis("type = \"dynamics\"\nt_end = 1\nh = \"2e-4\"")
        .unwrap()
        .analysis;
    assert_eq!(a.integrator_settings().step, 2e-4);
}

#[test]
fn equilibrium_takes_a_time() {
    let a = with_analysis("type = \"equilibrium\"\ntime = 0.5")
        .unwrap()
        .analysis;
    assert_eq!((a.kind, a.time), (AnalysisType::Equilibrium, 0.5));
    assert_eq!((a.tol, a.max_iter), (1e-10, 100));
    assert_eq!(AnalysisSpec::default().time, 0.0);
}

#[test]
fn keys_that_do_not_fit_the_type_are_errors() {
    let e = error("t_end = 1\nrho_inf = 0.5");
    assert!(
        e.contains("analysis.rho_inf: `rho_inf` does not apply to type = \"kinematics\" (it is a setting of dynamics)"),
        "{e}"
    );
    assert!(e.starts_with("m.toml:16:11: "), "{e}");
    let e = error("type = \"equilibrium\"\nt_end = 1");
    assert!(
        e.contains("analysis.t_end: `t_end` does not apply to type = \"equilibrium\""),
        "{e}"
    );
    let e = error("type = \"inverse_dynamics\"\ntime = 1");
    assert!(e.contains("(it is a setting of equilibrium)"), "{e}");
    let e = error("type = \"dynamics\"\natol = 1e-6");
    assert!(
        e.contains("analysis.atol: `atol` sets the error control: it needs adaptive = true"),
        "{e}"
    );
    let e = error("type = \"statics\"");
    assert!(
        e.contains("analysis.type") && e.contains("equilibrium"),
        "{e}"
    );
}

#[test]
fn bad_dynamics_values_are_errors() {
    let e = error("type = \"dynamics\"\nrho_inf = 1.5");
    assert!(
        e.contains("analysis.rho_inf: rho_inf must be between 0 and 1 (1.5)"),
        "{e}"
    );
    let e = error("type = \"dynamics\"\nh = 0");
    assert!(
        e.contains("analysis.h: h must be a positive finite number (0)"),
        "{e}"
    );
    let e = error("type = \"dynamics\"\nadaptive = true\natol = 0");
    assert!(e.contains("atol and rtol are both 0"), "{e}");
    let e = error("type = \"dynamics\"\nadaptive = true\nh_min = -1");
    assert!(
        e.contains("analysis.h_min: h_min must be a positive"),
        "{e}"
    );
}
