//! What the dynamics benchmarks share: timing fixed steps of a model.

use camlink_core::dynamics::integrator::{Integrator, Settings};
use camlink_core::Model;

/// Times `steps` fixed steps of 1 ms of `model` from its start; laying the
/// model out and the consistent initial conditions are outside the timing.
pub fn fixed_steps(bencher: divan::Bencher, model: &Model, steps: usize) {
    let settings = Settings {
        step: 1e-3,
        ..Settings::default()
    };
    bencher
        .with_inputs(|| Integrator::new(model, settings.clone()).unwrap())
        .bench_local_values(|mut it| {
            let mut h = 1e-3;
            it.advance_to(steps as f64 * 1e-3, &mut h).unwrap();
            assert_eq!(it.diagnostics().summary.steps, steps);
            it.state().q[0]
        });
}
