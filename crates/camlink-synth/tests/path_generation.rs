//! Path generation: fits recover known four-bars from their own coupler
//! curves; the examples give defect-free mechanisms whose models, run by
//! camlink's kinematics, pass their points.

use std::f64::consts::TAU;

use camlink_synth::fourbar::{FourBar, Requirements};
use camlink_synth::path::{fit, CouplerLinkage, FitSpec, Timing};

pub(crate) fn known() -> CouplerLinkage {
    CouplerLinkage {
        linkage: FourBar {
            o2: [0.0, 0.0],
            o4: [0.4, 0.0],
            crank: 0.12,
            coupler: 0.38,
            rocker: 0.3,
        },
        point: [0.15, 0.12],
        sigma: 1.0,
    }
}

#[test]
fn issue31_path_fit_recovers_a_known_four_bar() {
    let m = known();
    let n = 20;
    let targets: Vec<[f64; 2]> = (0..n)
        .map(|j| m.trace(0.3 + TAU * j as f64 / n as f64).unwrap().2)
        .collect();
    for timing in [Timing::Uniform, Timing::Free] {
        let spec = FitSpec {
            targets: targets.clone(),
            timing: timing.clone(),
            closed: true,
            ordered: true,
            starts: 128,
            keep: 3,
            requirements: Requirements::default(),
        };
        let t0 = std::time::Instant::now();
        let (cands, found) = fit(&spec);
        let best = &cands[0];
        eprintln!(
            "{:?}: {} found, rms {:e} max {:e}, {:?} {:?} {:?}",
            timing,
            found,
            best.rms,
            best.max,
            best.mechanism.linkage.lengths(),
            best.checks.defects,
            t0.elapsed()
        );
        assert!(best.rms < 1e-9, "rms {}", best.rms);
    }
}

use std::path::{Path, PathBuf};

use camlink_core::kinematics;
use camlink_core::run::{PointOutput, Settings, Table};
use camlink_model::{load_str, Format};
use camlink_synth::{solve_path, solve_str, Solution};
use serde_json::Value;

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// Runs `s`'s model at 0, 0.005, …, 1 s with `extra` times added; returns
/// the table and the times.
pub(crate) fn run_with_p(s: &Solution, extra: &[f64]) -> Table {
    let loaded = load_str(&s.model, Format::Toml, &format!("{}.toml", s.name))
        .unwrap_or_else(|e| panic!("the model does not load: {e}\n{}", s.model));
    let mut times: Vec<f64> = (0..=200).map(|k| k as f64 / 200.0).collect();
    times.extend_from_slice(extra);
    times.sort_by(f64::total_cmp);
    times.dedup();
    let settings = Settings {
        tol: 1e-12,
        max_iter: 25,
        jerk: false,
    };
    // The coupler point P as an output channel (coupler.P.x, coupler.P.y).
    let body = loaded.model.body_id("coupler").unwrap();
    let points = [PointOutput {
        body,
        name: "coupler.P".into(),
        s: loaded.model.body(body).point("P").unwrap(),
    }];
    let mut table = Table::default();
    kinematics::run(&loaded.model, &times, &settings, &points, &mut table)
        .unwrap_or_else(|e| panic!("the model does not run: {e}\n{}", s.model));
    table
}

pub(crate) fn at(table: &Table, name: &str, t: f64) -> f64 {
    let k = table.t.iter().position(|&s| s == t).expect("a run time");
    table.channel(name).unwrap()[k]
}

pub(crate) fn defects(s: &Solution) -> usize {
    s.report["checks"]["defects"].as_array().unwrap().len()
}

/// The coupler point of the model, run by camlink's kinematics, is at the
/// report's distance from each target at the report's time.
pub(crate) fn assert_reaches_targets(s: &Solution, tol_of_error: f64) {
    let r = &s.report;
    let times = floats(&r["point_times"]);
    let table = run_with_p(s, &times);
    let errors = floats(&r["error"]["points"]);
    for (j, (t, target)) in times
        .iter()
        .zip(r["targets"].as_array().unwrap())
        .enumerate()
    {
        let target = floats(target);
        let (x, y) = (at(&table, "coupler.P.x", *t), at(&table, "coupler.P.y", *t));
        let e = (x - target[0]).hypot(y - target[1]);
        assert!(
            (e - errors[j]).abs() < tol_of_error,
            "point {}: the model is {e} m from the target, the report says {}",
            j + 1,
            errors[j]
        );
    }
}

/// The freehand example: the best candidate has no defect, its model runs
/// a full crank turn, and its coupler point is where the report says at
/// every target (to 1e-9 m).
#[test]
fn issue31_path_example_gives_a_defect_free_mechanism() {
    let out = solve_path(&examples().join("synthesis_path.toml")).unwrap();
    assert_eq!(out.kind, "path");
    let best = &out.solutions[0];
    assert_eq!(defects(best), 0, "{}", best.report["checks"]);
    assert_eq!(best.report["checks"]["grashof"], "crank-rocker");
    let rms = best.report["error"]["rms"].as_f64().unwrap();
    // The target spans about 170 mm; the fit is within a few mm.
    assert!(rms < 0.005, "rms {rms} m");
    for s in &out.solutions {
        assert_reaches_targets(s, 1e-9);
    }
}

/// Precision points with prescribed crank rotations: four points of a
/// known four-bar's coupler curve, and their mirror image (the crank turning
/// clockwise); the models pass them to 1e-9 m.
#[test]
fn issue31_precision_points_pass_through_the_points() {
    let m = known();
    let betas = [0.0, 0.6, 1.3, 2.1];
    for mirror in [1.0, -1.0] {
        let pts: Vec<[f64; 2]> = betas
            .iter()
            .map(|b| {
                let p = m.trace(0.4 + b).unwrap().2;
                [p[0], mirror * p[1]]
            })
            .collect();
        let text = format!(
            "[synthesis]\ntype = \"path\"\nmethod = \"precision_points\"\ntargets = [{}]\ncrank_rotations = [{:?}, {:?}, {:?}]\n",
            pts.iter()
                .map(|p| format!("[{:?}, {:?}]", p[0], p[1]))
                .collect::<Vec<_>>()
                .join(", "),
            mirror * betas[1],
            mirror * betas[2],
            mirror * betas[3]
        );
        let out = solve_str(&text, "pp.toml", "pp").unwrap();
        for s in &out.solutions {
            assert!(s.report["error"]["max"].as_f64().unwrap() < 1e-10);
            if defects(s) == 0 {
                assert_reaches_targets(s, 1e-9);
            }
        }
        assert!(
            out.solutions.iter().any(|s| defects(s) == 0),
            "mirror {mirror}: {:?}",
            out.solutions
                .iter()
                .map(|s| &s.report["checks"]["defects"])
                .collect::<Vec<_>>()
        );
    }
}

/// Dead-centre example: run by the kinematics, the rocker's angle at the
/// two extremes differs by the swing, stays between them over the turn,
/// and the crank's time from one to the other over the time back is the
/// time ratio, all to 1e-9.
#[test]
fn issue31_dead_centre_swing_and_time_ratio() {
    let path = examples().join("synthesis_dead_centre.toml");
    let out = solve_path(&path).unwrap();
    // The ground link chosen: the locus meets its circle at up to two points.
    let d = out.solutions[0].report["links"]["ground"].as_f64().unwrap();
    let text = std::fs::read_to_string(&path).unwrap() + &format!("ground = {d:?}\n");
    let chosen = solve_str(&text, "dc.toml", "dc").unwrap();
    let crank = out.solutions[0].report["links"]["crank"].as_f64().unwrap();
    assert!(chosen
        .solutions
        .iter()
        .any(|s| (s.report["links"]["crank"].as_f64().unwrap() - crank).abs() < 1e-9));
    assert!(chosen.solutions.len() >= 2);
    // The example's solution has no defect; the other point of the locus
    // may fall short of the transmission angle asked, and says so.
    assert_eq!(defects(&out.solutions[0]), 0);
    for s in out.solutions.iter().chain(&chosen.solutions) {
        for d in s.report["checks"]["defects"].as_array().unwrap() {
            assert_eq!(d["kind"], "transmission", "{d}");
        }
        let r = &s.report;
        let times = floats(&r["extremes"]["times"]);
        let table = run_with_p(s, &times);
        let (psi1, psi2) = (
            at(&table, "rocker.phi", times[0]),
            at(&table, "rocker.phi", times[1]),
        );
        let swing = 45f64.to_radians();
        assert!(
            ((psi2 - psi1) - swing).abs() < 1e-9,
            "swing {}",
            psi2 - psi1
        );
        // Every sampled angle lies within the two extremes.
        for v in table.channel("rocker.phi").unwrap() {
            assert!(
                v >= psi1 - 1e-12 && v <= psi2 + 1e-12,
                "{v} outside [{psi1}, {psi2}]"
            );
        }
        // The rocker is at rest at the extremes.
        for t in [times[0], times[1]] {
            assert!(at(&table, "rocker.omega", t).abs() < 1e-9);
        }
        let q = (times[1] - times[0]) / (1.0 - times[1]);
        assert!((q - 1.25).abs() < 1e-9, "time ratio {q}");
    }
}

/// Cognates example: the three models, each run by the kinematics over a
/// full turn, put P at the same place at every instant (1e-9 m).
#[test]
fn issue31_cognates_trace_the_same_curve() {
    let out = solve_path(&examples().join("synthesis_cognates.toml")).unwrap();
    assert_eq!(out.solutions.len(), 3);
    let tables: Vec<Table> = out.solutions.iter().map(|s| run_with_p(s, &[])).collect();
    let px = tables[0].channel("coupler.P.x").unwrap();
    let py = tables[0].channel("coupler.P.y").unwrap();
    let mut worst = 0.0f64;
    for t in &tables[1..] {
        let (x, y) = (
            t.channel("coupler.P.x").unwrap(),
            t.channel("coupler.P.y").unwrap(),
        );
        assert_eq!(x.len(), px.len());
        for k in 0..x.len() {
            worst = worst.max((x[k] - px[k]).hypot(y[k] - py[k]));
        }
    }
    assert!(worst < 1e-9, "the cognates' P differ by up to {worst} m");
    // The given crank turns once: P comes back to its start.
    let n = px.len() - 1;
    assert!((px[n] - px[0]).hypot(py[n] - py[0]) < 1e-9);
}
