//! The fast paths of kinematics give the general path's results: every
//! kinematic example run with the recorded pivot order
//! ([`camlink_core::lu_program`]) and with a pivot search at every
//! factorization agrees to 1e-12 in q, q̇ and q̈ at every step (relative to
//! each quantity's largest size over the run, at least 1).

use std::path::Path;

use camlink_core::kinematics::Solver;
use camlink_core::run::{time_grid, Settings};
use camlink_model::AnalysisType;

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

#[test]
fn fixed_pivots_agree_with_pivot_search_on_every_example() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        // Cam design and study files are not models.
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy();
            !name.starts_with("cam_design_") && !name.starts_with("study_")
        })
        .collect();
    files.sort();
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
