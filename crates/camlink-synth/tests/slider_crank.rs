//! Slider-cranks: function generation puts the slider at the prescribed
//! positions at the precision points (to 1e-9 m in camlink's kinematics),
//! recovers a known slider-crank, and reports the structural error camlink
//! measures; motion generation passes its poses; bad input is named.

use camlink_core::kinematics;
use camlink_core::run::{Settings, Table};
use camlink_model::load_path;
use camlink_synth::slider_crank::{linkage_of, solve_k};
use camlink_synth::{solve_path, solve_str};
use serde_json::Value;

use crate::burmester::{assert_passes_poses, at, examples, floats, run, TOL};

#[test]
fn issue31_slider_function_example_reproduces_its_precision_points() {
    let out = solve_path(&examples().join("synthesis_slider_crank.toml")).unwrap();
    let s = &out.solutions[0];
    let r = &s.report;
    assert_eq!(r["method"], "slider_three_point");
    assert_eq!(r["checks"]["defects"], Value::Array(vec![]));
    let times = floats(&r["point_times"]);
    let table = run(s, &times);
    for (j, (pair, &t)) in r["pairs"]
        .as_array()
        .unwrap()
        .iter()
        .zip(&times)
        .enumerate()
    {
        let [phi, sj] = [floats(pair)[0], floats(pair)[1]];
        let e_phi = at(&table, "crank.phi", t) - phi;
        let e_s = at(&table, "slider.x", t) - sj;
        assert!(
            e_phi.abs() < TOL && e_s.abs() < TOL,
            "point {j}: ({e_phi:e} rad, {e_s:e} m)"
        );
    }
}

/// Three (φ, s) pairs computed by camlink's kinematics for
/// examples/slider_crank.toml (r = 0.05, l = 0.2, e = 0.01 m) give that
/// slider-crank back.
#[test]
fn issue31_slider_function_recovers_the_slider_crank_example() {
    let loaded = load_path(&examples().join("slider_crank.toml")).unwrap();
    let times = [0.0, 0.01, 0.035, 0.06];
    let settings = Settings {
        tol: 1e-12,
        max_iter: 25,
        jerk: false,
    };
    let mut table = Table::default();
    kinematics::run(&loaded.model, &times, &settings, &[], &mut table).unwrap();
    let phi = table.channel("crank.phi").unwrap();
    let s = table.channel("slider.x").unwrap();
    let pairs: Vec<(f64, f64)> = (1..4).map(|k| (phi[k], s[k])).collect();
    let l = linkage_of(solve_k(&pairs, "f").unwrap(), "f").unwrap();
    for (got, want, name) in [
        (l.crank, 0.05, "a"),
        (l.coupler, 0.2, "b"),
        (l.line[1], 0.01, "e"),
    ] {
        assert!(
            (got - want).abs() < 1e-10,
            "{name} = {got}, expected {want}"
        );
    }
}

/// Least squares: K solves the normal equations, and the structural error
/// reported equals the one camlink's kinematics measures over the same
/// samples.
#[test]
fn issue31_slider_function_least_squares_error_matches_kinematics() {
    let text = std::fs::read_to_string(examples().join("synthesis_slider_crank.toml"))
        .unwrap()
        .replace(
            "method = \"three_point\"",
            "method = \"least_squares\"\ncount = 15",
        );
    let out = solve_str(&text, "ls.toml", "ls").unwrap();
    let s = &out.solutions[0];
    let r = &s.report;
    assert_eq!(r["checks"]["defects"], Value::Array(vec![]));
    let k = floats(&r["k"]);
    let mut g = [0.0; 3];
    for p in r["pairs"].as_array().unwrap() {
        let [phi, sv] = [floats(p)[0], floats(p)[1]];
        let row = [sv * phi.cos(), phi.sin(), -1.0];
        let res = row[0] * k[0] + row[1] * k[1] + row[2] * k[2] - sv * sv;
        for j in 0..3 {
            g[j] += row[j] * res;
        }
    }
    assert!(g.iter().all(|v| v.abs() < 1e-15), "Aᵀr = {g:?}");
    let se = &r["structural_error"];
    let n = se["samples"].as_u64().unwrap() as usize;
    let times: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
    let table = run(s, &times);
    let mut worst = 0.0f64;
    for &t in &times {
        // x = t; s asked = 0.20 − 0.07 x².
        let want = 0.20 - 0.07 * t * t;
        worst = worst.max((at(&table, "slider.x", t) - want).abs());
    }
    let reported = se["max"].as_f64().unwrap();
    assert!(
        (reported - worst).abs() < TOL,
        "reported {reported}, measured {worst}"
    );
}

#[test]
fn issue31_slider_motion_example_passes_its_poses() {
    let out = solve_path(&examples().join("synthesis_slider_motion.toml")).unwrap();
    let s = &out.solutions[0];
    assert_eq!(s.report["checks"]["defects"], Value::Array(vec![]));
    assert_passes_poses(s);
}

/// Two poses: any coupler point is a slider point (its two positions fix
/// the slide); the model passes the poses.
#[test]
fn issue31_slider_motion_two_poses_pass() {
    let text = r#"[synthesis]
type = "slider_motion"
poses = [[0, 0, 0], [0.1, 0.02, "deg(20)"]]
crank = { moving = [-0.02, -0.1] }
along = 0.05
slider = { moving = [0.12, 0.0] }
"#
    .replace("along = 0.05", "along = [0.05]");
    let s = &solve_str(&text, "p.toml", "p").unwrap().solutions[0];
    let defects = s.report["checks"]["defects"].as_array().unwrap();
    assert!(defects.is_empty(), "{defects:?}");
    assert_passes_poses(s);
}

#[test]
fn issue31_slider_bad_input_named() {
    let base = std::fs::read_to_string(examples().join("synthesis_slider_motion.toml")).unwrap();
    // A point not on a slider line.
    let off = base.replace(
        "slider = { angle = \"deg(10)\" }",
        "slider = { moving = [0.1, 0.1] }",
    );
    let e = solve_str(&off, "p.toml", "p").unwrap_err().to_string();
    assert!(
        e.contains("synthesis.slider: the slider's pin at pose"),
        "{e}"
    );
    assert!(e.contains("not a slider point"), "{e}");
    let both = base.replace(
        "slider = { angle = \"deg(10)\" }",
        "slider = { angle = 0, moving = [0, 0] }",
    );
    let e = solve_str(&both, "p.toml", "p").unwrap_err().to_string();
    assert!(e.contains("give exactly one of"), "{e}");
    let f = std::fs::read_to_string(examples().join("synthesis_slider_crank.toml")).unwrap();
    let same = f.replace("output = [0.20, 0.13]", "output = [0.20, 0.20]");
    let e = solve_str(&same, "p.toml", "p").unwrap_err().to_string();
    assert!(e.contains("synthesis.output: s_start equals s_end"), "{e}");
    let ground = f.replace("method =", "ground = 0.1\nmethod =");
    let e = solve_str(&ground, "p.toml", "p").unwrap_err().to_string();
    assert!(
        e.contains("synthesis.ground: not a field of a slider_function problem"),
        "{e}"
    );
}

/// A small deterministic generator (xorshift) for varied problems.
pub(crate) struct Rng(pub u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    pub(crate) fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// Random three-pose problems with a random crank pivot and slide
/// direction: every defect-free slider-crank passes its poses in camlink's
/// kinematics (μ ≥ 10°, away from the dead positions where the solver's
/// first steps may change branch).
#[test]
fn issue31_slider_motion_varied_problems_pass_their_poses() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let mut checked = 0;
    for _ in 0..300 {
        let poses: Vec<String> = (0..3)
            .map(|_| {
                format!(
                    "[{:?}, {:?}, {:?}]",
                    rng.range(-0.2, 0.2),
                    rng.range(-0.2, 0.2),
                    rng.range(-1.0, 1.0)
                )
            })
            .collect();
        let text = format!(
            "[synthesis]\ntype = \"slider_motion\"\nposes = [{}]\ncrank = {{ moving = [{:?}, {:?}] }}\nslider = {{ angle = {:?} }}\nmin_transmission = \"deg(10)\"\n",
            poses.join(", "),
            rng.range(-0.3, 0.3),
            rng.range(-0.3, 0.3),
            rng.range(-3.0, 3.0)
        );
        let Ok(out) = solve_str(&text, "case.toml", "case") else {
            continue;
        };
        let s = &out.solutions[0];
        if !s.report["checks"]["defects"].as_array().unwrap().is_empty() {
            continue;
        }
        assert_passes_poses(s);
        checked += 1;
    }
    assert!(checked >= 20, "only {checked} defect-free cases checked");
}
