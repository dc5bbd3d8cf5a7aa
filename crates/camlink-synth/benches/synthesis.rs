//! Synthesis speed: each method on the examples' problems.
//!
//! `cargo bench -p camlink-synth --bench synthesis`. `solve_*` time the
//! whole problem file (parsing, synthesis, checks, model file and report);
//! the others the mathematics and checks alone.

use std::path::Path;

use camlink_expr::Expr;
use camlink_synth::fourbar::Requirements;
use camlink_synth::function::{chebyshev, synthesise, Fit, FunctionSpec};
use camlink_synth::motion::{three_positions, Pivot, Pose};

fn main() {
    divan::main();
}

fn example(name: &str) -> String {
    std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples")
            .join(name),
    )
    .unwrap()
}

#[divan::bench]
fn motion_three_positions() {
    let poses = [
        Pose {
            x: 0.0,
            y: 0.0,
            theta: 0.0,
        },
        Pose {
            x: 0.08,
            y: 0.03,
            theta: (-25f64).to_radians(),
        },
        Pose {
            x: 0.15,
            y: 0.02,
            theta: (-50f64).to_radians(),
        },
    ];
    divan::black_box(
        three_positions(
            divan::black_box(&poses),
            Pivot::Moving([0.08, -0.18]),
            Pivot::Moving([0.12, -0.18]),
            &Requirements::default(),
            ["poses", "crank", "rocker"],
        )
        .unwrap(),
    );
}

fn log_spec() -> FunctionSpec {
    FunctionSpec {
        f: Expr::parse("log(x)/log(10)", "x").unwrap(),
        source: "log(x)/log(10)".into(),
        x: [1.0, 10.0],
        input: [135f64.to_radians(), 225f64.to_radians()],
        output: [75f64.to_radians(), 135f64.to_radians()],
        ground: 0.1,
    }
}

/// Three precision points, the structural error over 201 samples.
#[divan::bench]
fn function_three_point(bencher: divan::Bencher) {
    let spec = log_spec();
    let fit = Fit::ThreePoint(chebyshev(3, 1.0, 10.0));
    bencher.bench(|| synthesise(&spec, &fit, 201, &Requirements::default(), "f").unwrap());
}

/// Least squares over 20 points, the structural error over 201 samples.
#[divan::bench]
fn function_least_squares_20(bencher: divan::Bencher) {
    let spec = log_spec();
    let fit = Fit::LeastSquares(chebyshev(20, 1.0, 10.0));
    bencher.bench(|| synthesise(&spec, &fit, 201, &Requirements::default(), "f").unwrap());
}

#[divan::bench]
fn solve_three_positions_file(bencher: divan::Bencher) {
    let text = example("synthesis_three_positions.toml");
    bencher.bench(|| camlink_synth::solve_str(&text, "p.toml", "p").unwrap());
}

#[divan::bench]
fn solve_function_file(bencher: divan::Bencher) {
    let text = example("synthesis_function.toml");
    bencher.bench(|| camlink_synth::solve_str(&text, "p.toml", "p").unwrap());
}
