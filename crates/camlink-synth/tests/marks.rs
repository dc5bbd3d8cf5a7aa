//! Dead-centre and toggle marks on a four-bar's motion against the closed
//! form: the crank and the coupler in line at |O₂B| = a + b and b − a.

use camlink_synth::fourbar::FourBar;
use camlink_synth::marks::{marks, LoopPins, Mark, MarkKind, ROW};
use std::f64::consts::{PI, TAU};

/// The studio example's crank-rocker (m): d = 0.4, a = 0.12, b = 0.38,
/// c = 0.3, O₂ at the origin, O₄ at (d, 0).
const D: f64 = 0.4;
const A: f64 = 0.12;
const B: f64 = 0.38;
const C: f64 = 0.3;

fn linkage() -> FourBar {
    FourBar {
        o2: [0.0, 0.0],
        o4: [D, 0.0],
        crank: A,
        coupler: B,
        rocker: C,
    }
}

/// The rocker angle ψ (rad) at crank angle φ, on the branch of ψ > 0 at
/// φ = 0.
fn psi(phi: f64) -> f64 {
    let four = linkage();
    let sigma = {
        let p = four.position(0.0, 1.0).unwrap();
        if p.psi > 0.0 {
            1.0
        } else {
            -1.0
        }
    };
    four.position(phi, sigma).unwrap().psi
}

/// Rows of the crank turning at ω (rad/s) over `turns` turns in steps of
/// `step` (rad): crank body at O₂ with angle φ = ωt, rocker body at O₄
/// with angle ψ; ψ̇ and ψ̈ by central differences. With `swap`, the
/// crank and the rocker trade places in each row.
fn motion(omega: f64, step: f64, turns: f64, swap: bool) -> (Vec<f64>, Vec<f64>) {
    let n = (turns * TAU / step).round() as usize;
    let dt = 1e-4;
    let (mut t, mut rows) = (Vec::new(), Vec::new());
    for k in 0..=n {
        let tk = k as f64 * step / omega;
        let f = |t: f64| psi(omega * t);
        let (p, pp, pm) = (f(tk), f(tk + dt), f(tk - dt));
        let (pd, pdd) = ((pp - pm) / (2.0 * dt), (pp - 2.0 * p + pm) / (dt * dt));
        let crank = [[0.0, 0.0, omega * tk], [0.0, 0.0, omega], [0.0; 3]];
        let rocker = [[D, 0.0, p], [0.0, 0.0, pd], [0.0, 0.0, pdd]];
        let (first, second) = if swap {
            (rocker, crank)
        } else {
            (crank, rocker)
        };
        for block in 0..3 {
            rows.extend(first[block]);
            rows.extend(second[block]);
        }
        t.push(tk);
    }
    assert_eq!(rows.len(), t.len() * ROW);
    (t, rows)
}

fn wrap(x: f64) -> f64 {
    (x + PI).rem_euclid(TAU) - PI
}

/// The crank angles of the dead centres (rad): extended and folded.
fn dead_centres() -> [f64; 2] {
    let out = (((A + B).powi(2) + D * D - C * C) / (2.0 * (A + B) * D)).acos();
    let fold = PI + (((B - A).powi(2) + D * D - C * C) / (2.0 * (B - A) * D)).acos();
    [out, fold]
}

#[test]
fn dead_centres_of_a_crank_rocker_at_their_closed_form_angles() {
    let pins = LoopPins {
        o2: [0.0, 0.0],
        o4: [D, 0.0],
        a_on_crank: [A, 0.0],
        b_on_rocker: [C, 0.0],
    };
    let omega = 3.0;
    let (t, rows) = motion(omega, 1f64.to_radians(), 2.0, false);
    let found = marks(&pins, &t, &rows, &vec![true; t.len()]);
    assert_eq!(found.len(), 4, "{found:?}");
    let want = dead_centres();
    for (i, m) in found.iter().enumerate() {
        assert_eq!(m.kind, MarkKind::DeadCentre);
        let w = want[i % 2];
        assert!(
            wrap(m.crank - w).abs() < 1e-9,
            "{i}: {} against {w}",
            m.crank
        );
        assert!((m.t * omega - m.crank).abs() < 1e-12);
        // B where the rocker puts it, on the line O₂A extended or folded.
        let b = linkage().position(m.crank, 1.0).unwrap().b;
        let b = if (b[1] > 0.0) == (psi(m.crank) > 0.0) {
            b
        } else {
            linkage().position(m.crank, -1.0).unwrap().b
        };
        assert!(
            (m.at[0] - b[0]).hypot(m.at[1] - b[1]) < 1e-9,
            "{:?} against {b:?}",
            m.at
        );
        let r = m.at[0].hypot(m.at[1]);
        let reach = if i % 2 == 0 { A + B } else { B - A };
        assert!((r - reach).abs() < 1e-9, "|O₂B| {r} against {reach}");
    }
}

#[test]
fn the_same_positions_as_toggles_with_the_links_named_the_other_way() {
    // Crank and rocker trade places: the crank's line with the coupler is
    // now the coupler's with the "rocker", a toggle, marked at "A".
    let pins = LoopPins {
        o2: [D, 0.0],
        o4: [0.0, 0.0],
        a_on_crank: [C, 0.0],
        b_on_rocker: [A, 0.0],
    };
    let omega = 3.0;
    let (t, rows) = motion(omega, 1f64.to_radians(), 1.0, true);
    let found = marks(&pins, &t, &rows, &vec![true; t.len()]);
    let toggles: Vec<_> = found
        .iter()
        .filter(|m| m.kind == MarkKind::Toggle)
        .collect();
    assert_eq!(toggles.len(), 2, "{found:?}");
    for (m, w) in toggles.iter().zip(dead_centres()) {
        assert!(
            wrap(m.t * omega - w).abs() < 1e-9,
            "{} against {w}",
            m.t * omega
        );
    }
}

#[test]
fn rows_not_solved_hide_the_marks_between_them() {
    let pins = LoopPins {
        o2: [0.0, 0.0],
        o4: [D, 0.0],
        a_on_crank: [A, 0.0],
        b_on_rocker: [C, 0.0],
    };
    let (t, mut rows) = motion(3.0, 1f64.to_radians(), 1.0, false);
    let all = marks(&pins, &t, &rows, &vec![true; t.len()]);
    assert_eq!(all.len(), 2);
    // The row after the first mark flagged unsolved, the row after the
    // second not a number: neither mark is found.
    let mut solved = vec![true; t.len()];
    let after = |m: f64| t.iter().position(|&tk| tk > m).unwrap();
    solved[after(all[0].t)] = false;
    rows[after(all[1].t) * ROW + 4] = f64::NAN;
    assert!(marks(&pins, &t, &rows, &solved).is_empty());
}

/// Rows of a crank turning at 1 rad/s through the angles `phi` (rad), A
/// at (a, 0) on it, and a "rocker" body held at (L, 0) with B at its
/// origin: the dead-centre cross product is −a L sin φ, exactly 0 at
/// φ = 0 (and the toggle's, with O₄ at (2L, 0), a sin φ).
fn dead(found: Vec<Mark>) -> Vec<Mark> {
    found
        .into_iter()
        .filter(|m| m.kind == MarkKind::DeadCentre)
        .collect()
}

fn straight(phi: &[f64], rate: &[f64]) -> (LoopPins, Vec<f64>, Vec<f64>) {
    let pins = LoopPins {
        o2: [0.0, 0.0],
        o4: [2.0, 0.0],
        a_on_crank: [0.2, 0.0],
        b_on_rocker: [0.0, 0.0],
    };
    let t: Vec<f64> = (0..phi.len()).map(|k| k as f64).collect();
    let mut rows = Vec::new();
    for (&p, &w) in phi.iter().zip(rate) {
        rows.extend([0.0, 0.0, p, 1.0, 0.0, 0.0]);
        rows.extend([0.0, 0.0, w, 0.0, 0.0, 0.0]);
        rows.extend([0.0; 6]);
    }
    (pins, t, rows)
}

#[test]
fn a_zero_on_a_row_is_one_mark_where_the_sign_changes_across_it() {
    let d = 0.1;
    // Through φ = 0 at the middle row: one mark, at that row's time.
    let (pins, t, rows) = straight(&[-2.0 * d, -d, 0.0, d, 2.0 * d], &[d; 5]);
    let found = dead(marks(&pins, &t, &rows, &[true; 5]));
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!((found[0].t, found[0].crank), (2.0, 0.0));
    assert_eq!(found[0].at, [1.0, 0.0]);
    // Reaching φ = 0 at the last row: a mark there.
    let (pins, t, rows) = straight(&[-2.0 * d, -d, 0.0], &[d; 3]);
    let found = dead(marks(&pins, &t, &rows, &[true; 3]));
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].t, 2.0);
    // Down to φ = 0 and back: the links come into line and part the way
    // they came; no mark.
    let (pins, t, rows) = straight(&[2.0 * d, d, 0.0, d, 2.0 * d], &[-d, -d, 0.0, d, d]);
    assert!(marks(&pins, &t, &rows, &[true; 5]).is_empty());
}

#[test]
fn tiny_cross_products_of_one_sign_are_no_mark() {
    // Both products of the same sign and so small that their product
    // underflows to 0.
    let (pins, t, mut rows) = straight(&[1e-170, 2e-170], &[0.0; 2]);
    rows[3] = 1e-150;
    rows[ROW + 3] = 1e-150;
    assert!(marks(&pins, &t, &rows, &[true; 2]).is_empty());
}

#[test]
fn a_row_at_a_time_that_is_not_finite_is_not_solved() {
    let d = 0.1;
    let (pins, mut t, rows) = straight(&[-d, d], &[2.0 * d; 2]);
    assert_eq!(dead(marks(&pins, &t, &rows, &[true; 2])).len(), 1);
    t[1] = f64::NAN;
    assert!(marks(&pins, &t, &rows, &[true; 2]).is_empty());
}
