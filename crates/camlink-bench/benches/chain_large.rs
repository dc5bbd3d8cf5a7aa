//! The pendulum chain at N = 10,000 links, in forward dynamics and (every
//! joint driven) in kinematics: long scaling benchmarks, run
//! only when asked for with `CAMLINK_BENCH_LARGE=1 cargo bench -p
//! camlink-core --bench chain_large` (divide by 100 N for the cost per body
//! per step; `benches/dynamics.rs` has N = 10 … 1000).

use camlink_testkit::mechanisms;

use camlink_bench::shared;

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
    if std::env::var_os("CAMLINK_BENCH_LARGE").is_none() {
        println!("chain_large: skipped; set CAMLINK_BENCH_LARGE=1 to run it");
        return;
    }
    divan::main();
}

/// A chain of 10,000 links falling from the horizontal: 100 steps of 1 ms,
/// as for the smaller chains.
#[divan::bench(sample_count = 3)]
fn chain_10000_links_100_steps(bencher: divan::Bencher) {
    shared::fixed_steps(bencher, &mechanisms::chain(10_000, 0.1), 100);
}

/// Kinematics of the chain of 10,000 links with every joint driven: 100
/// steps of 1 ms.
#[divan::bench(sample_count = 3)]
fn driven_chain_10000_links_100_steps(bencher: divan::Bencher) {
    let model = mechanisms::driven_chain(10_000, 0.1);
    let times = time_grid(0.099, 1e-3).unwrap();
    bencher.bench_local(|| run(&model, &times, &Settings::default(), &[], &mut Discard).unwrap());
}
