//! Kinematics of example models loaded from their files, per 10,000 steps.
//!
//! `cargo bench -p camlink-bench --bench examples` (divide the times by
//! 10,000 for the cost per step; the model is loaded outside the timing).

use std::path::Path;

use camlink_core::kinematics::run;
use camlink_core::run::{time_grid, Channel, Settings, Sink, Stop};
use camlink_expr::Expr;

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

fn bench_file(bencher: divan::Bencher, name: &str) {
    bench_file_with(bencher, name, false);
}

/// As `bench_file`, with the jerk solved and output when `jerk`.
fn bench_file_with(bencher: divan::Bencher, name: &str, jerk: bool) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    let loaded = camlink_model::load_path(&path).unwrap();
    let times = time_grid(9.999, 1e-3).unwrap();
    assert_eq!(times.len(), 10_000);
    let settings = Settings {
        tol: loaded.analysis.tol,
        max_iter: loaded.analysis.max_iter,
        jerk,
    };
    bencher.bench_local(|| run(&loaded.model, &times, &settings, &[], &mut Discard).unwrap());
}

/// Four-bar crank-rocker (9 coordinates).
#[divan::bench(sample_count = 20)]
fn four_bar_10k_steps(bencher: divan::Bencher) {
    bench_file(bencher, "four_bar.toml");
}

/// The lecture's Example 3.4.3 cam with its ρ₂ = 1/4 roller follower.
#[divan::bench(sample_count = 20)]
fn cam_roller_10k_steps(bencher: divan::Bencher) {
    bench_file(bencher, "cam_seed_example_3_4_3.toml");
}

/// The same cam with the jerk (`jerk = true`): one more solve and the
/// fourth-order profile jet per step.
#[divan::bench(sample_count = 20)]
fn cam_roller_jerk_10k_steps(bencher: divan::Bencher) {
    bench_file_with(bencher, "cam_seed_example_3_4_3.toml", true);
}

/// The four-bar with the jerk.
#[divan::bench(sample_count = 20)]
fn four_bar_jerk_10k_steps(bencher: divan::Bencher) {
    bench_file_with(bencher, "four_bar.toml", true);
}

/// Eccentric cam with a flat-faced translating follower.
#[divan::bench(sample_count = 20)]
fn cam_flat_10k_steps(bencher: divan::Bencher) {
    bench_file(bencher, "cam_eccentric_flat.toml");
}

/// The lecture's piecewise profile ρ₁ with four derivatives (the jerk path).
#[divan::bench]
fn seed_profile_jet4(bencher: divan::Bencher) {
    let e = Expr::parse("if(a <= 2*pi/3, 5/4 - cos(3*a)/4, 1)", "a").unwrap();
    let mut a = 0.0;
    bencher.bench_local(|| {
        a = (a + 0.1) % 6.2;
        divan::black_box(e.jet4(divan::black_box(a)))
    });
}

/// The lecture's piecewise profile ρ₁ with three derivatives.
#[divan::bench]
fn seed_profile_jet(bencher: divan::Bencher) {
    let e = Expr::parse("if(a <= 2*pi/3, 5/4 - cos(3*a)/4, 1)", "a").unwrap();
    let mut a = 0.0;
    bencher.bench_local(|| {
        a = (a + 0.1) % 6.2;
        divan::black_box(e.jet(divan::black_box(a)))
    });
}
