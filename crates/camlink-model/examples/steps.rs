//! Runs one benchmark model for a given number of steps, for instruction
//! counts (`bench/callgrind.py` runs it under callgrind at two step counts
//! and divides the difference, so set-up cancels out).
//!
//! `cargo run --release -p camlink-model --example steps -- <benchmark> <steps>`
//!
//! Benchmarks: `four_bar` and `cam_roller` (kinematics of
//! `examples/four_bar.toml` and `examples/cam_seed_example_3_4_3.toml`,
//! steps of 1 ms), `slider_crank` (forward dynamics, generalized-α, h = 1 ms,
//! the `camlink-core` dynamics benchmark's model), `chain<N>` (a chain of
//! N pendulum links, h = 1 ms) and `driven_chain<N>` (kinematics of the
//! same chain with every joint driven, steps of 1 ms).

use std::path::Path;
use std::process::ExitCode;

use camlink_core::dynamics::integrator::{Integrator, Settings as DynSettings};
use camlink_core::kinematics::run;
use camlink_core::run::{time_grid, Channel, Settings, Sink, Stop};

use camlink_testkit::mechanisms;

/// Keeps the last row so that the solver's work cannot be optimised away.
struct Last(f64);

impl Sink for Last {
    fn begin(&mut self, _: &[Channel]) {}
    fn row(&mut self, _: f64, values: &[f64]) -> Result<(), Stop> {
        self.0 = values.first().copied().unwrap_or(0.0);
        Ok(())
    }
}

/// Kinematics of an example file for `steps` steps of 1 ms.
fn kinematics(file: &str, steps: usize) -> Result<f64, String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(file);
    let loaded = camlink_model::load_path(&path).map_err(|e| e.to_string())?;
    let times = time_grid((steps - 1) as f64 * 1e-3, 1e-3).map_err(|e| e.to_string())?;
    let settings = Settings {
        tol: loaded.analysis.tol,
        max_iter: loaded.analysis.max_iter,
        jerk: false,
    };
    let mut sink = Last(0.0);
    run(&loaded.model, &times, &settings, &[], &mut sink).map_err(|e| e.to_string())?;
    Ok(sink.0)
}

/// Kinematics of a model built in code for `steps` steps of 1 ms.
fn kinematics_of(model: &camlink_core::Model, steps: usize) -> Result<f64, String> {
    let times = time_grid((steps - 1) as f64 * 1e-3, 1e-3).map_err(|e| e.to_string())?;
    let mut sink = Last(0.0);
    run(model, &times, &Settings::default(), &[], &mut sink).map_err(|e| e.to_string())?;
    Ok(sink.0)
}

/// Forward dynamics of `model` for `steps` fixed steps of 1 ms.
fn dynamics(model: &camlink_core::Model, steps: usize) -> Result<f64, String> {
    let settings = DynSettings {
        step: 1e-3,
        ..DynSettings::default()
    };
    let mut it = Integrator::new(model, settings).map_err(|e| e.to_string())?;
    let mut h = 1e-3;
    it.advance_to(steps as f64 * 1e-3, &mut h)
        .map_err(|e| e.to_string())?;
    Ok(it.state().q[0])
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(name), Some(steps)) = (args.first(), args.get(1).and_then(|s| s.parse().ok())) else {
        eprintln!("usage: steps <four_bar|cam_roller|slider_crank|chainN|driven_chainN> <steps>");
        return ExitCode::FAILURE;
    };
    let steps: usize = steps;
    let out = match name.as_str() {
        "four_bar" => kinematics("four_bar.toml", steps),
        "cam_roller" => kinematics("cam_seed_example_3_4_3.toml", steps),
        "slider_crank" => dynamics(&mechanisms::slider_crank(0.3, 10.0, false), steps),
        other => {
            let size = |prefix: &str| other.strip_prefix(prefix).and_then(|n| n.parse().ok());
            match (size("chain"), size("driven_chain")) {
                (Some(n), _) => dynamics(&mechanisms::chain(n, 0.1), steps),
                (_, Some(n)) => kinematics_of(&mechanisms::driven_chain(n, 0.1), steps),
                _ => Err(format!("unknown benchmark '{other}'")),
            }
        }
    };
    match out {
        Ok(v) => {
            println!("{v}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("{e}");
            ExitCode::FAILURE
        }
    }
}
