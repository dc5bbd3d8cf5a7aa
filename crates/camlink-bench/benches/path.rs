//! Path-generation speed: the least-squares fit of a 20-point target.
//!
//! `cargo bench -p camlink-bench --bench path`. Rayon runs the starts on
//! every local core (`RAYON_NUM_THREADS=2` for two).

use std::path::Path;

use camlink_synth::fourbar::{FourBar, Requirements};
use camlink_synth::path::{fit, CouplerLinkage, FitSpec, Timing};
use camlink_synth::solve_path;

fn main() {
    divan::main();
}

fn example(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

/// The freehand example (20 points from a CSV, closed, free timing, 96
/// starts): the whole problem file, with checks, models and reports.
#[divan::bench(sample_count = 10)]
fn solve_path_example_20_points() {
    divan::black_box(solve_path(&example("synthesis_path.toml")).unwrap());
}

/// 20 points of a known crank-rocker's coupler curve, free timing, 96
/// starts: the fit alone.
#[divan::bench(sample_count = 10)]
fn fit_known_curve_20_points() {
    let m = CouplerLinkage {
        linkage: FourBar {
            o2: [0.0, 0.0],
            o4: [0.4, 0.0],
            crank: 0.12,
            coupler: 0.38,
            rocker: 0.3,
        },
        point: [0.15, 0.12],
        sigma: 1.0,
    };
    let targets = (0..20)
        .map(|j| {
            m.trace(0.3 + std::f64::consts::TAU * j as f64 / 20.0)
                .unwrap()
                .2
        })
        .collect();
    let spec = FitSpec {
        targets,
        timing: Timing::Free,
        closed: true,
        ordered: true,
        starts: 96,
        keep: 3,
        requirements: Requirements::default(),
    };
    divan::black_box(fit(&spec));
}
