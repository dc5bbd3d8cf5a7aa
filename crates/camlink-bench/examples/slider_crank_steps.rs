//! Forward dynamics of the slider-crank of the `dynamics` benchmark
//! (crank 0.1 m, rod 0.3 m, gravity, started at 10 rad/s): `runs` runs of
//! 1,000 fixed steps of 1 ms, for instruction counts of one step. Under
//! `valgrind --tool=callgrind` the difference between two runs and one is
//! the cost of 1,000 steps (and of one start), with loading cancelled out.
//!
//! `cargo run --release -p camlink-bench --example slider_crank_steps -- <runs>`

use camlink_core::dynamics::integrator::{Integrator, Settings};

use camlink_testkit::mechanisms;

fn main() {
    let runs: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let model = mechanisms::slider_crank(0.3, 10.0, false);
    let settings = Settings {
        step: 1e-3,
        ..Settings::default()
    };
    for _ in 0..runs {
        let mut it = Integrator::new(&model, settings.clone()).expect("consistent start");
        let mut h = 1e-3;
        it.advance_to(1.0, &mut h).expect("1,000 steps");
        let s = &it.diagnostics().summary;
        println!(
            "steps {} newton_iterations {} factorizations {}",
            s.steps, s.newton_iterations, s.factorizations
        );
        // The end state to the last bit, to compare builds.
        println!("q {:?}\nqd {:?}", it.state().q, it.state().qd);
    }
}
