//! Kinematics benchmarks: positions, velocities and accelerations per step.
//!
//! `cargo bench -p camlink-core --bench kinematics`

#[path = "../tests/common/mod.rs"]
mod common;

use camlink_core::kinematics::run;
use camlink_core::run::{time_grid, Settings, Sink, Stop};

/// Discards rows; the benchmark measures the solver alone.
struct Discard;

impl Sink for Discard {
    fn begin(&mut self, _: &[String]) {}
    fn row(&mut self, _: f64, values: &[f64]) -> Result<(), Stop> {
        divan::black_box(values);
        Ok(())
    }
}

fn main() {
    divan::main();
}

/// Four-bar crank-rocker, 10,000 steps of 1 ms (divide the time by 10,000
/// for the cost per step).
#[divan::bench(sample_count = 20)]
fn four_bar_10k_steps(bencher: divan::Bencher) {
    let model = common::four_bar();
    let times = time_grid(9.999, 1e-3).unwrap();
    assert_eq!(times.len(), 10_000);
    bencher.bench_local(|| run(&model, &times, &Settings::default(), &[], &mut Discard).unwrap());
}
