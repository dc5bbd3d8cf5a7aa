//! Forward-dynamics benchmarks (generalized-α, fixed step).
//!
//! `cargo bench -p camlink-bench --bench dynamics`

use camlink_testkit::mechanisms;

use camlink_bench::shared;

fn main() {
    divan::main();
}

/// Slider-crank (crank 0.1 m, rod 0.3 m) with gravity, started at 10 rad/s:
/// 1,000 steps of 1 ms (divide by 1,000 for the cost per step).
#[divan::bench(sample_count = 50)]
fn slider_crank_1000_steps(bencher: divan::Bencher) {
    let model = mechanisms::slider_crank(0.3, 10.0, false);
    shared::fixed_steps(bencher, &model, 1000);
}

/// A chain of N links falling from the horizontal: 100 steps of 1 ms
/// (divide by 100 N for the cost per body per step).
#[divan::bench(args = [10, 100, 1000], sample_count = 10)]
fn chain_100_steps(bencher: divan::Bencher, n: usize) {
    shared::fixed_steps(bencher, &mechanisms::chain(n, 0.1), 100);
}
