//! Synthesis speed: each method on the examples' problems.
//!
//! `cargo bench -p camlink-bench --bench synthesis`. `solve_*` time the
//! whole problem file (parsing, synthesis, checks, model file and report);
//! the others the mathematics and checks alone.

use std::path::Path;

use camlink_expr::Expr;
use camlink_synth::burmester::{pair, sample_dyads, Equations, Limits};
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

fn burmester_poses(n: usize) -> Vec<Pose> {
    let all = [
        (0.1545, 0.2164, 42.93),
        (0.1429, 0.2626, 32.03),
        (0.0878, 0.2775, 27.17),
        (0.0196, 0.2554, 26.92),
        (-0.0349, 0.2037, 30.74),
    ];
    let four = [
        (0.1545, 0.2164, 42.93),
        (0.1371, 0.2669, 31.0),
        (0.0683, 0.2749, 26.68),
        (-0.0066, 0.2359, 28.06),
    ];
    let list: &[(f64, f64, f64)] = if n == 4 { &four } else { &all };
    list.iter()
        .map(|&(x, y, d)| Pose {
            x,
            y,
            theta: d.to_radians(),
        })
        .collect()
}

/// Four poses: the centre-point and circle-point curves at 360 steps of
/// β₂ per branch (examples/synthesis_burmester_four.toml's poses).
#[divan::bench]
fn burmester_four_curves(bencher: divan::Bencher) {
    let poses = burmester_poses(4);
    bencher.bench(|| {
        let eq = Equations::new(divan::black_box(&poses), "poses").unwrap();
        eq.curves(360)
    });
}

/// Four poses: 36 dyads per branch sampled, every ordered pair checked and
/// ranked (the problem file's work without parsing and output).
#[divan::bench]
fn burmester_four_pairs(bencher: divan::Bencher) {
    let poses = burmester_poses(4);
    let req = Requirements {
        turning: None,
        min_transmission: Some(30f64.to_radians()),
        full_turn: true,
    };
    bencher.bench(|| {
        let eq = Equations::new(divan::black_box(&poses), "poses").unwrap();
        let dyads = sample_dyads(&eq, 36);
        pair(&poses, &dyads, &req, &Limits::default())
    });
}

/// Five poses: every real Burmester point (a scan of 4096 steps of β₂ per
/// branch, each root refined by bisection).
#[divan::bench]
fn burmester_five_points(bencher: divan::Bencher) {
    let poses = burmester_poses(5);
    bencher.bench(|| {
        let eq = Equations::new(divan::black_box(&poses), "poses").unwrap();
        eq.burmester_points(4096)
    });
}

#[divan::bench]
fn solve_burmester_four_file(bencher: divan::Bencher) {
    let text = example("synthesis_burmester_four.toml");
    bencher.bench(|| camlink_synth::solve_str(&text, "p.toml", "p").unwrap());
}

#[divan::bench]
fn solve_burmester_five_file(bencher: divan::Bencher) {
    let text = example("synthesis_burmester_five.toml");
    bencher.bench(|| camlink_synth::solve_str(&text, "p.toml", "p").unwrap());
}

#[divan::bench]
fn solve_two_positions_file(bencher: divan::Bencher) {
    let text = example("synthesis_two_positions.toml");
    bencher.bench(|| camlink_synth::solve_str(&text, "p.toml", "p").unwrap());
}

/// Slider-crank function generation, three points, error over 201 samples.
#[divan::bench]
fn solve_slider_function_file(bencher: divan::Bencher) {
    let text = example("synthesis_slider_crank.toml");
    bencher.bench(|| camlink_synth::solve_str(&text, "p.toml", "p").unwrap());
}

#[divan::bench]
fn solve_slider_motion_file(bencher: divan::Bencher) {
    let text = example("synthesis_slider_motion.toml");
    bencher.bench(|| camlink_synth::solve_str(&text, "p.toml", "p").unwrap());
}
