//! The fast paths of kinematics give the general path's results: every
//! kinematic example run with the recorded pivot order
//! ([`camlink_core::lu_program`]) and with a pivot search at every
//! factorization agrees to 1e-12 in q, q̇ and q̈ at every step (relative to
//! each quantity's largest size over the run, at least 1); and on every
//! example model, Φ_q, ν and γ filled through a [`JacobianPlan`] from joint
//! views gathered once are, bit for bit, those of the general per-entry
//! and per-joint evaluations.

use std::path::Path;

use camlink_core::assembly::{Assembly, JacobianPlan};
use camlink_core::constraint::Local;
use camlink_core::kinematics::Solver;
use camlink_core::linsolve::SystemMatrix;
use camlink_core::run::{time_grid, Settings};
use camlink_model::AnalysisType;

use crate::mechanisms;

const TOL: f64 = 1e-12;

/// (q, q̇, q̈) at every time of the example's analysis.
type States = Vec<[Vec<f64>; 3]>;

/// The states, and the (replayed, pivoted) factorizations of Φ_q.
fn states(loaded: &camlink_model::Loaded, times: &[f64], fixed: bool) -> (States, (usize, usize)) {
    let settings = Settings {
        tol: loaded.analysis.tol,
        max_iter: loaded.analysis.max_iter,
        ..Settings::default()
    };
    let mut solver = Solver::new(&loaded.model, settings).unwrap();
    solver.set_fixed_pivots(fixed);
    let mut out = Vec::with_capacity(times.len());
    for (k, &t) in times.iter().enumerate() {
        if k == 0 {
            solver.step(t, None).unwrap();
        } else {
            solver.advance(times[k - 1], t, 0).unwrap();
        }
        out.push([solver.q.clone(), solver.qd.clone(), solver.qdd.clone()]);
    }
    let counts = solver
        .factorization_counts()
        .expect("the examples are small");
    (out, counts)
}

/// The example files that are models (cam design and study files are not).
fn model_files() -> Vec<std::path::PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        // Cam design, study and synthesis problem files are not models.
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy();
            !name.starts_with("cam_design_")
                && !name.starts_with("study_")
                && !name.starts_with("synthesis_")
        })
        .collect();
    files.sort();
    files
}

#[test]
fn fixed_pivots_agree_with_pivot_search_on_every_example() {
    let files = model_files();
    let mut compared = 0;
    for path in &files {
        let loaded = camlink_model::load_path(path).unwrap_or_else(|e| panic!("{e}"));
        let a = &loaded.analysis;
        if a.kind != AnalysisType::Kinematics {
            continue;
        }
        let times = match &a.times {
            Some(t) => t.clone(),
            None => time_grid(a.t_end.unwrap(), a.step.unwrap()).unwrap(),
        };
        let (fast, counts) = states(&loaded, &times, true);
        let (general, general_counts) = states(&loaded, &times, false);
        // The fast path replays most factorizations; the general one none.
        let name = path.display();
        println!("{name}: (replayed, pivoted) factorizations {counts:?}");
        assert!(
            counts.0 > counts.1,
            "{name}: (replayed, pivoted) {counts:?}"
        );
        assert_eq!(general_counts.0, 0, "{name}");
        for (d, what) in ["q", "q̇", "q̈"].iter().enumerate() {
            let size = general
                .iter()
                .flat_map(|s| s[d].iter())
                .fold(1.0f64, |m, v| m.max(v.abs()));
            for (k, (f, g)) in fast.iter().zip(&general).enumerate() {
                for (c, (x, y)) in f[d].iter().zip(&g[d]).enumerate() {
                    assert!(
                        (x - y).abs() <= TOL * size,
                        "{}: {what}[{c}] at t = {} differs by {:.1e} (size {size:.1e})",
                        path.display(),
                        times[k],
                        (x - y).abs()
                    );
                }
            }
        }
        compared += 1;
    }
    assert!(
        compared >= 15,
        "only {compared} kinematic examples compared"
    );
}

/// The model's starting coordinates, coordinate k moved by
/// 0.01 sin(k · `spread`) (m or rad).
fn off_placement(model: &camlink_core::Model, asm: &Assembly, spread: f64) -> Vec<f64> {
    let q0 = asm.initial_q(model);
    q0.iter()
        .enumerate()
        .map(|(k, v)| v + 0.01 * (k as f64 * spread).sin())
        .collect()
}

/// Φ_q (m × n, row-major) through a plan that leaves out the rows `skip`
/// says, ν and γ, from views gathered once.
fn planned(
    model: &camlink_core::Model,
    asm: &Assembly,
    q: &[f64],
    qd: &[f64],
    t: f64,
    skip: impl Fn(usize) -> bool,
) -> [Vec<f64>; 3] {
    let n = asm.n;
    let plan: JacobianPlan = asm.jacobian_plan(model, |r, c| (!skip(r)).then_some(r * n + c));
    let mut locals = vec![Local::default(); model.joints.len()];
    let (mut jac, mut nu, mut gamma) = (vec![0.0; asm.m * n], vec![0.0; asm.m], vec![0.0; asm.m]);
    asm.gather(model, q, t, &mut locals);
    asm.fill_jacobian(model, &plan, &locals, &mut jac, Some(&mut nu));
    asm.gamma_at(model, &mut locals, qd, &mut gamma);
    [jac, nu, gamma]
}

#[test]
fn planned_jacobian_nu_and_gamma_match_the_general_evaluation_on_every_example() {
    let mut compared = 0;
    for path in model_files() {
        let loaded = camlink_model::load_path(&path).unwrap_or_else(|e| panic!("{e}"));
        let model = &loaded.model;
        let asm = Assembly::new(model);
        let (n, m) = (asm.n, asm.m);
        // A configuration off the placement and velocities of every size.
        let q = off_placement(model, &asm, 1.7);
        let qd: Vec<f64> = (0..n).map(|k| (k as f64 * 0.9 + 0.3).cos()).collect();
        let t = 0.37;
        let mut jac = vec![0.0; m * n];
        asm.jacobian(model, &q, t, |r, c, v| jac[r * n + c] = v);
        let (mut nu, mut gamma) = (vec![0.0; m], vec![0.0; m]);
        asm.nu(model, &q, t, &mut nu);
        asm.gamma(model, &q, &qd, t, &mut gamma);
        let name = path.display();
        let [jac_p, nu_p, gamma_p] = planned(model, &asm, &q, &qd, t, |_| false);
        assert_eq!(jac_p, jac, "{name}: Φ_q");
        assert_eq!(nu_p, nu, "{name}: ν");
        assert_eq!(gamma_p, gamma, "{name}: γ");
        // Rows left out (as redundant equations are) stay untouched.
        let [odd, ..] = planned(model, &asm, &q, &qd, t, |r| r % 2 == 1);
        for (k, (a, b)) in odd.iter().zip(&jac).enumerate() {
            let expected = if (k / n) % 2 == 1 { 0.0 } else { *b };
            assert_eq!(*a, expected, "{name}: Φ_q entry ({}, {})", k / n, k % n);
        }
        assert!(jac.iter().any(|v| *v != 0.0), "{name}");
        compared += 1;
    }
    assert!(compared >= 20, "only {compared} example models compared");
}

/// Φ_q of a square model at (q, t) put into a [`SystemMatrix`] entry by
/// entry, and written through a plan into its storage: the same matrix.
fn plan_fills_the_matrix_as_put_does(model: &camlink_core::Model, name: &str) -> bool {
    let asm = Assembly::new(model);
    let n = asm.n;
    if asm.m != n {
        return false;
    }
    let q = off_placement(model, &asm, 2.3);
    let t = 0.61;
    let mut pattern = Vec::new();
    asm.jacobian(model, &q, t, |r, c, _| pattern.push((r, c)));
    let mut put = SystemMatrix::try_new(n, &pattern).unwrap();
    let mut k = 0;
    asm.jacobian(model, &q, t, |r, c, v| {
        put.put(k, r, c, v);
        k += 1;
    });
    let mut planned = SystemMatrix::try_new(n, &pattern).unwrap();
    let mut k = 0;
    let plan = asm.jacobian_plan(model, |r, c| {
        k += 1;
        Some(planned.slot(k - 1, r, c))
    });
    let mut locals = vec![Local::default(); model.joints.len()];
    asm.gather(model, &q, t, &mut locals);
    asm.fill_jacobian(model, &plan, &locals, planned.values_mut(), None);
    assert_eq!(planned.to_dense(), put.to_dense(), "{name}");
    true
}

#[test]
fn plans_fill_small_and_sparse_matrices_as_entry_by_entry_puts_do() {
    let mut small = 0;
    for path in model_files() {
        let loaded = camlink_model::load_path(&path).unwrap_or_else(|e| panic!("{e}"));
        small += usize::from(plan_fills_the_matrix_as_put_does(
            &loaded.model,
            &path.display().to_string(),
        ));
    }
    assert!(small >= 15, "only {small} square example models");
    // 60 driven links, 180 unknowns: the sparse LU's storage.
    let chain = mechanisms::driven_chain(60, 0.1);
    assert!(plan_fills_the_matrix_as_put_does(&chain, "driven chain"));
}
