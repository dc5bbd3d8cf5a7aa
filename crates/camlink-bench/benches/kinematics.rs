//! Kinematics benchmarks: positions, velocities and accelerations per step.
//!
//! `cargo bench -p camlink-bench --bench kinematics`

use camlink_testkit::common;

use camlink_testkit::mechanisms;

use camlink_core::kinematics::run;
use camlink_core::run::{time_grid, Channel, Settings, Sink, Stop};

/// Discards rows; the benchmark measures the solver alone.
struct Discard;

impl Sink for Discard {
    fn begin(&mut self, _: &[Channel]) {}
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

/// A chain of N links with every joint driven: 100 steps of 1 ms (divide
/// by 100 N for the cost per body per step; N = 10,000 is in
/// `chain_large`).
#[divan::bench(args = [100, 1000], sample_count = 10)]
fn driven_chain_100_steps(bencher: divan::Bencher, n: usize) {
    let model = mechanisms::driven_chain(n, 0.1);
    let times = time_grid(0.099, 1e-3).unwrap();
    bencher.bench_local(|| run(&model, &times, &Settings::default(), &[], &mut Discard).unwrap());
}
