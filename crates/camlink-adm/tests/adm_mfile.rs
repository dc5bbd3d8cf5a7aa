//! Issue 27: a `PointForceFile`'s MATLAB force function is translated into
//! a point force of state (`adm/mfile.rs`), never run.
//!
//! `adm/mfile/piston_force.m` and `adm/mfile/Models/piston.adm` are our own
//! files in the layout and shape of the course repository's
//! `pistonForce.m` and `Models/project2.adm` (that repository carries no
//! licence, so its files are not copied; `adm_course.rs` checks them when
//! `CAMLINK_COURSE_MODELS` names their folder).

use std::collections::HashMap;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use camlink_adm::mfile::translate;
use camlink_adm::{describe, describe_str, load_adm};
use camlink_core::dynamics::integrator;
use camlink_core::run::{time_grid, Table};
use camlink_expr::Expr;
use camlink_model::Format;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/adm/mfile")
}

/// `piston_force.m` evaluated by hand, as MATLAB runs it (`~(t < 0.05)`
/// is written as MATLAB reads it).
#[allow(clippy::neg_cmp_op_on_partial_ord)]
fn piston_force(t: f64, q: [f64; 3], qd: [f64; 3]) -> [f64; 2] {
    let (x, v) = (q[0], qd[0]);
    let mut f = [0.0, 0.0];
    if v > 0.0 {
        f[0] = if x > 4.5 {
            0.0
        } else if x > 4.0 {
            -2500.0 * (1.0 - (2.0 * PI * (x - 4.25)).sin())
        } else if x >= 1.5 {
            2000.0 - 7000.0 / (5.0 - x)
        } else {
            0.0
        };
    }
    let side = 0.01 * f[0] * q[2].cos() + 2.0 * qd[2] - 0.0 * q[1].powi(2);
    if (!(t < 0.05) && v.abs() != 0.0) || t == 1e9 {
        f[1] = side;
    } else if t <= 0.01 {
        f[1] = -side.powi(2) / 1e4 + (1.0 + t).ln().exp().sqrt() - 1.0 + (0.0 * qd[1]).tan();
    }
    f
}

/// The translated expressions of body `b`, as functions of (t, q, q̇).
pub fn compiled(fx: &str, fy: &str, b: &str) -> impl Fn(f64, [f64; 3], [f64; 3]) -> [f64; 2] {
    let names: Vec<String> = ["x", "y", "phi", "vx", "vy", "omega"]
        .iter()
        .map(|c| format!("{b}_{c}"))
        .chain(["t".to_string()])
        .collect();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    let none = HashMap::new();
    let ex = Expr::parse_inputs(fx, &names, &none).unwrap_or_else(|e| panic!("{fx}: {e}"));
    let ey = Expr::parse_inputs(fy, &names, &none).unwrap_or_else(|e| panic!("{fy}: {e}"));
    move |t, q, qd| {
        let u = [q[0], q[1], q[2], qd[0], qd[1], qd[2], t];
        [ex.eval_inputs(&u), ey.eval_inputs(&u)]
    }
}

/// Compares `f` with `reference` at points in every branch, to 1e-12
/// relative to max(1, |F|); the number of points.
pub fn compare_on_branches(
    f: impl Fn(f64, [f64; 3], [f64; 3]) -> [f64; 2],
    reference: impl Fn(f64, [f64; 3], [f64; 3]) -> [f64; 2],
    xs: &[f64],
    ts: &[f64],
) -> usize {
    let mut n = 0;
    for &t in ts {
        for &x in xs {
            for v in [-1.3, 0.0, 2.0] {
                let (q, qd) = ([x, 0.2, 0.3], [v, -0.4, -0.7]);
                let (a, b) = (f(t, q, qd), reference(t, q, qd));
                for k in 0..2 {
                    let err = (a[k] - b[k]).abs() / b[k].abs().max(1.0);
                    assert!(
                        err <= 1e-12,
                        "F({}) at t={t} x={x} v={v}: {} vs {}",
                        k + 1,
                        a[k],
                        b[k]
                    );
                }
                n += 1;
            }
        }
    }
    n
}

#[test]
fn issue27_mfile_translation_equals_the_matlab_function() {
    let src = std::fs::read_to_string(dir().join("piston_force.m")).unwrap();
    let f = translate(&src, "piston_force.m", "piston").unwrap();
    assert!(
        f.fx.starts_with("if(piston_vx > 0, if(piston_x > 4.5, 0, "),
        "{}",
        f.fx
    );
    let n = compare_on_branches(
        compiled(&f.fx, &f.fy, "piston"),
        piston_force,
        &[1.0, 1.5, 3.0, 4.0, 4.2, 4.5, 4.8],
        &[0.005, 0.02, 0.3, 1e9],
    );
    assert_eq!(n, 4 * 7 * 3);
}

#[test]
fn issue27_mfile_model_runs_in_dynamics() {
    let adm = dir().join("Models/piston.adm");
    let l = load_adm(&adm, None).unwrap_or_else(|e| panic!("{e}"));
    // The m-file is found in the model's parent folder, and named.
    assert_eq!(l.warnings.len(), 1, "{:?}", l.warnings);
    let w = &l.warnings[0];
    assert!(
        w.contains(
            "forces[0].mfile: force 'gas' (id 1): the force is translated from the MATLAB file"
        ) && w.contains("piston_force.m"),
        "{w}"
    );
    let a = &l.analysis;
    let grid = time_grid(a.t_end.unwrap(), a.step.unwrap()).unwrap();
    let mut table = Table::default();
    integrator::run(&l.model, &grid, &a.integrator_settings(), &[], &mut table)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(table.t.len(), 501);
    // The converted model carries the translated force.
    let toml = describe(&adm, None).unwrap().write(Format::Toml).unwrap();
    let src = std::fs::read_to_string(dir().join("piston_force.m")).unwrap();
    let f = translate(&src, "x", "piston").unwrap();
    assert!(toml.contains(&format!("fx = {:?}", f.fx)), "{toml}");
    assert!(toml.contains("local = false"), "{toml}");

    // The same model with the gas force written by hand in camlink's
    // language moves the same; without it, the piston moves otherwise.
    let line = format!("fx = {:?}", f.fx);
    let hand = "if(piston_vx <= 0, 0, if(piston_x > 4.5, 0, if(piston_x > 4, \
                -2500 + 2500*sin(2*pi*piston_x - 8.5*pi), if(piston_x < 1.5, 0, 2000 - 7000/(5 - piston_x)))))";
    let by_hand = toml.replace(&line, &format!("fx = {hand:?}"));
    let fy = format!("fy = {:?}", f.fy);
    let by_hand = by_hand
        .replace(
            &fy,
            "fy = \"if(t >= 0.05 && piston_vx != 0, 0.01*FX*cos(piston_phi) + 2*piston_omega, 0)\"",
        )
        .replace("FX", hand);
    assert_ne!(by_hand, toml);
    let without = toml.replace(&line, "fx = 0").replace(&fy, "fy = 0");
    let x = |text: &str| {
        let l = camlink_model::load_str(text, Format::Toml, "piston.toml")
            .unwrap_or_else(|e| panic!("{e}"));
        let mut table = Table::default();
        integrator::run(&l.model, &grid, &a.integrator_settings(), &[], &mut table).unwrap();
        table.channel("piston.x").unwrap()
    };
    let (ours, hand, none) = (table.channel("piston.x").unwrap(), x(&by_hand), x(&without));
    let most = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(p, q)| (p - q).abs())
            .fold(0.0, f64::max)
    };
    assert!(most(&ours, &hand) <= 1e-9, "{}", most(&ours, &hand));
    assert!(most(&ours, &none) > 1e-2, "{}", most(&ours, &none));
}

/// A model beside `m` (the m-file text, or none), with a force on `slider`
/// in `frame` computed by `mfile`; the error or the described TOML.
fn with_mfile(tag: &str, mfile: &str, m: Option<&str>, frame: &str) -> Result<String, String> {
    let root = std::env::temp_dir().join(format!("camlink-mfile-{}-{tag}", std::process::id()));
    let models = root.join("Models");
    std::fs::create_dir_all(&models).unwrap();
    if let Some(m) = m {
        std::fs::write(models.join("force.m"), m).unwrap();
    }
    let adm = format!(
        r#"{{"name": "m", "bodies": [{{"name": "slider", "id": 1, "mass": 1, "jbar": 1, "q0": [0, 0, 0]}}],
  "forces": [{{"name": "push", "id": 4, "type": "PointForceFile", "body1": 1, "sP1": [0.5, 0],
              "frame": "{frame}", "mfile": "{mfile}"}}]}}"#
    );
    let path = models.join("m.adm");
    let r = describe_str(&adm, path.to_str().unwrap(), None)
        .map_err(|e| e.to_string())
        .and_then(|d| d.write(Format::Toml).map_err(|e| e.to_string()));
    std::fs::remove_dir_all(&root).unwrap();
    r
}

#[test]
fn issue27_mfile_frames_and_points() {
    let m = "function F = force(t, qi, qdi)\nF = [qi(3); -2*qdi(3)];\n";
    let lrf = with_mfile("lrf", "force", Some(m), "LRF").unwrap();
    assert!(lrf.contains("fx = \"slider_phi\""), "{lrf}");
    assert!(lrf.contains("fy = \"-2*slider_omega\""), "{lrf}");
    assert!(lrf.contains("local = true"), "{lrf}");
    assert!(lrf.contains("push = [0.5, 0.0]"), "{lrf}");
    let grf = with_mfile("grf", "force", Some(m), "GRF").unwrap();
    assert!(grf.contains("local = false"), "{grf}");
}

#[test]
fn issue27_mfile_outside_the_subset_is_refused() {
    let head = "function F = force(t, qi, qdi)\nF = [0; 0];\n";
    let cases = [
        (
            "for",
            format!("{head}for k = 1:3\n  F(1) = F(1) + k;\nend\n"),
            "force.m:3: a `for` loop is not in the subset",
        ),
        (
            "call",
            format!("{head}F(1) = besselj(0, t);\n"),
            "force.m:3: a call to 'besselj' is not in the subset",
        ),
        (
            "eval",
            format!("{head}% read the law\nF(2) = eval('t');\n"),
            "force.m:4: `eval` is not in the subset",
        ),
        (
            "undefined",
            format!("{head}if t > 1\n  k = 2;\nend\nF(1) = k;\n"),
            "force.m:6: 'k' is read but is assigned only on some paths",
        ),
    ];
    for (tag, m, want) in cases {
        let e = with_mfile(tag, "force", Some(&m), "GRF").unwrap_err();
        assert!(e.contains(want), "{e}");
        assert!(
            e.contains("forces[0].mfile: force 'push' (id 4): cannot translate"),
            "{e}"
        );
    }
    for name in ["../force", "force.m", "my force", "2force", ""] {
        let e = with_mfile("name", name, Some(head), "GRF").unwrap_err();
        assert!(e.contains("forces[0].mfile: force 'push' (id 4)"), "{e}");
        if !name.is_empty() {
            assert!(
                e.contains(&format!("mfile '{name}' is not a MATLAB function name")),
                "{e}"
            );
        }
    }
    let e = with_mfile("missing", "other", Some(head), "GRF").unwrap_err();
    assert!(
        e.contains("there is no file other.m in the model's folder"),
        "{e}"
    );
}
