//! The analysis a model file's `[analysis]` table asks for, run into a sink.

use camlink_core::dynamics::{integrator, inverse, statics};
use camlink_core::kinematics;
use camlink_core::run::{self, Settings, Sink, Summary};
use camlink_model::{AnalysisSpec, AnalysisType, Loaded};

/// Runs `[analysis] type` with the file's settings (as `model.run()` in
/// Python does): output times `times`, else 0, `step`, … `t_end` with
/// `step = t_end / 100` when none is given; the file's output points.
/// The error is one line: the analysis error with its time and joints, or
/// what is missing from the settings.
pub fn run_file_analysis(model: &Loaded, sink: &mut dyn Sink) -> Result<Summary, String> {
    let a = &model.analysis;
    let points = model.point_outputs()?;
    let kind = a.kind;
    let tol = a.tol_for(kind);
    let max_iter = a.max_iter_for(kind);
    let times = || -> Result<Vec<f64>, String> {
        if let Some(t) = &a.times {
            return Ok(t.clone());
        }
        let t_end = a.t_end.ok_or_else(|| {
            format!(
                "model '{}' gives no end time ([analysis] t_end)",
                model.model.name
            )
        })?;
        let step = a.step.unwrap_or(AnalysisSpec::default_step(t_end));
        run::time_grid(t_end, step)
    };
    let m = &model.model;
    let result = match kind {
        AnalysisType::Kinematics => {
            let s = Settings {
                tol,
                max_iter,
                jerk: a.jerk,
            };
            kinematics::run(m, &times()?, &s, &points, sink)
        }
        AnalysisType::InverseDynamics => {
            let s = Settings {
                tol,
                max_iter,
                jerk: false,
            };
            inverse::run(m, &times()?, &s, &points, sink)
        }
        AnalysisType::Equilibrium => {
            let s = statics::Settings { tol, max_iter };
            statics::run(m, a.time, &s, &points, sink)
        }
        AnalysisType::Dynamics => {
            let s = a.integrator_settings();
            integrator::run(m, &times()?, &s, &points, sink)
        }
    };
    result.map_err(|e| e.to_string())
}
