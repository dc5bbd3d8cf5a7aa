//! The batch runner on the example four-bar: outcomes in order, a failing
//! variant recorded among good ones, the same numbers on any thread count,
//! and the swing against Freudenstein's closed form.

use std::path::Path;

use camlink_study::{run_batch, BatchSettings, Reduction, Status};

fn four_bar() -> camlink_model::Loaded {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/four_bar.toml");
    camlink_model::load_path(&path).unwrap()
}

fn swing() -> Vec<(String, Reduction)> {
    vec![(
        "swing".into(),
        Reduction::Range {
            channel: "rocker.phi".into(),
        },
    )]
}

/// The rocker's swing of the example four-bar with crank `a` (rad), from
/// its extreme positions where crank and coupler line up.
fn freudenstein_swing(a: f64) -> f64 {
    let (b, c, d) = (0.38, 0.3, 0.4);
    let at = |l: f64| ((l * l - d * d - c * c) / (2.0 * d * c)).acos();
    at(b - a) - at(b + a)
}

#[test]
fn a_failing_variant_is_recorded_and_the_others_run() {
    let variants: Vec<Vec<(String, f64)>> = [0.1, 0.3, f64::NAN, 0.12]
        .iter()
        .map(|&a| vec![("a".to_string(), a)])
        .collect();
    let out = run_batch(&four_bar(), &variants, &swing(), &BatchSettings::default()).unwrap();
    let status: Vec<Status> = out.iter().map(|o| o.status).collect();
    assert_eq!(
        status,
        [
            Status::Ok,
            Status::AnalysisError,
            Status::ModelError,
            Status::Ok
        ]
    );
    assert!(out[1].values[0].is_nan() && !out[1].error.is_empty());
    assert!(out[2].error.contains("parameters.a"), "{}", out[2].error);
    for (k, a) in [(0, 0.1), (3, 0.12)] {
        // Sampled every 1.8° of crank: within 5e-5 rad of the closed form.
        assert!(
            (out[k].values[0] - freudenstein_swing(a)).abs() < 5e-5,
            "{a}: {:?}",
            out[k]
        );
    }
}

#[test]
fn one_thread_and_two_give_the_same_bits() {
    let variants: Vec<Vec<(String, f64)>> = (0..6)
        .map(|k| vec![("a".to_string(), 0.08 + 0.01 * k as f64)])
        .collect();
    let run = |threads| {
        let settings = BatchSettings {
            threads: Some(threads),
            time_limit: None,
            stop: None,
        };
        run_batch(&four_bar(), &variants, &swing(), &settings).unwrap()
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one, two);
    assert!(one.iter().all(|o| o.status == Status::Ok));
}
