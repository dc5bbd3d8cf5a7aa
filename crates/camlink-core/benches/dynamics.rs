//! Forward-dynamics benchmarks (generalized-α, fixed step).
//!
//! `cargo bench -p camlink-core --bench dynamics`

#[path = "../tests/mechanisms/mod.rs"]
mod mechanisms;

use camlink_core::dynamics::integrator::{Integrator, Settings};

fn main() {
    divan::main();
}

/// Slider-crank (crank 0.1 m, rod 0.3 m) with gravity, started at 10 rad/s:
/// 1,000 steps of 1 ms (divide by 1,000 for the cost per step).
#[divan::bench(sample_count = 50)]
fn slider_crank_1000_steps(bencher: divan::Bencher) {
    let model = mechanisms::slider_crank(0.3, 10.0, false);
    let settings = Settings {
        step: 1e-3,
        ..Settings::default()
    };
    bencher
        .with_inputs(|| Integrator::new(&model, settings.clone()).unwrap())
        .bench_local_values(|mut it| {
            let mut h = 1e-3;
            it.advance_to(1.0, &mut h).unwrap();
            assert_eq!(it.summary.steps, 1000);
            it.q[6]
        });
}

/// A chain of N links falling from the horizontal: 100 steps of 1 ms
/// (divide by 100 N for the cost per body per step).
#[divan::bench(args = [10, 100, 1000], sample_count = 10)]
fn chain_100_steps(bencher: divan::Bencher, n: usize) {
    let model = mechanisms::chain(n, 0.1);
    let settings = Settings {
        step: 1e-3,
        ..Settings::default()
    };
    bencher
        .with_inputs(|| Integrator::new(&model, settings.clone()).unwrap())
        .bench_local_values(|mut it| {
            let mut h = 1e-3;
            it.advance_to(0.1, &mut h).unwrap();
            assert_eq!(it.summary.steps, 100);
            it.q[0]
        });
}
