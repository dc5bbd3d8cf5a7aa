//! The dead-centre and toggle positions that a four-bar's solved motion
//! passes, for the studio's marks on the cycle.
//!
//! Symbols as in [`crate::fourbar`] (global frame, m, rad): ground pivots
//! O₂ (crank) and O₄ (rocker), the crank pin A (crank–coupler) and the
//! rocker pin B (coupler–rocker).
//! - A **dead centre**: the crank and the coupler in line, the rocker at a
//!   limit of its swing: (A − O₂) × (B − A) = 0.
//! - A **toggle**: the coupler and the rocker in line, μ = 0 or π:
//!   (B − A) × (O₄ − B) = 0.
//!
//! Each is found where its cross product changes sign between two solved
//! rows, on the quintic through each row's pose, velocity and acceleration
//! of the crank and the rocker, by regula falsi (the Illinois variant).

use crate::fourbar::{cross, rotate, sub, P2};

/// Values in each row of a motion: the crank's and the rocker's
/// (x, y, φ) (m, rad), then their velocities (ẋ, ẏ, φ̇) (m/s, rad/s),
/// then their accelerations (ẍ, ÿ, φ̈) (m/s², rad/s²), each block as
/// crank (x, y, φ) then rocker (x, y, φ).
pub const ROW: usize = 18;

/// The loop's pins (m): the ground pivots O₂ and O₄ (global), A on the
/// crank and B on the rocker (each in its body's frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopPins {
    pub o2: P2,
    pub o4: P2,
    pub a_on_crank: P2,
    pub b_on_rocker: P2,
}

/// Which links fall in line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MarkKind {
    /// The crank and the coupler.
    DeadCentre,
    /// The coupler and the rocker.
    Toggle,
}

impl MarkKind {
    /// `dead centre` or `toggle`.
    pub fn name(self) -> &'static str {
        match self {
            MarkKind::DeadCentre => "dead centre",
            MarkKind::Toggle => "toggle",
        }
    }

    /// Its cross product at the pins A and B.
    fn cross(self, pins: &LoopPins, a: P2, b: P2) -> f64 {
        match self {
            MarkKind::DeadCentre => cross(sub(a, pins.o2), sub(b, a)),
            MarkKind::Toggle => cross(sub(b, a), sub(pins.o4, b)),
        }
    }
}

/// A position passed: its time t (s), kind, the crank body's angle φ then
/// (rad) and the pin that marks it (B at a dead centre, A at a toggle;
/// global, m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mark {
    pub t: f64,
    pub kind: MarkKind,
    pub crank: f64,
    pub at: P2,
}

/// The quintic through (y, y′, y″) at both ends of a step of h, as powers
/// of the step's fraction s: row j holds the coefficients of s⁰…s⁵ of the
/// weight of y₀, h y′₀, h² y″₀, y₁, h y′₁, h² y″₁ in turn.
const HERMITE5: [[f64; 6]; 6] = [
    [1.0, 0.0, 0.0, -10.0, 15.0, -6.0],
    [0.0, 1.0, 0.0, -6.0, 8.0, -3.0],
    [0.0, 0.0, 0.5, -1.5, 1.5, -0.5],
    [0.0, 0.0, 0.0, 10.0, -15.0, 6.0],
    [0.0, 0.0, 0.0, -4.0, 7.0, -3.0],
    [0.0, 0.0, 0.0, 0.5, -1.0, 0.5],
];

/// Regula falsi's iterations at most, and the width of the bracket (as a
/// fraction of the step) at which it stops.
const ITERATIONS: usize = 80;
const BRACKET: f64 = 1e-14;

/// The pins A and B (global, m) and the crank angle (rad) of a pose
/// (crank x, y, φ, rocker x, y, φ).
fn pins_at(pins: &LoopPins, pose: &[f64]) -> (P2, P2, f64) {
    let ra = rotate(pose[2], pins.a_on_crank);
    let rb = rotate(pose[5], pins.b_on_rocker);
    (
        [pose[0] + ra[0], pose[1] + ra[1]],
        [pose[3] + rb[0], pose[4] + rb[1]],
        pose[2],
    )
}

/// The step from row k to row k + 1 as six quintics, one per pose value.
struct Step {
    coeffs: [[f64; 6]; 6],
}

impl Step {
    fn new(h: f64, r0: &[f64], r1: &[f64]) -> Step {
        let mut coeffs = [[0.0; 6]; 6];
        for (ch, c) in coeffs.iter_mut().enumerate() {
            let w = [
                r0[ch],
                h * r0[6 + ch],
                h * h * r0[12 + ch],
                r1[ch],
                h * r1[6 + ch],
                h * h * r1[12 + ch],
            ];
            for (p, cp) in c.iter_mut().enumerate() {
                *cp = (0..6).map(|j| w[j] * HERMITE5[j][p]).sum();
            }
        }
        Step { coeffs }
    }

    /// The pose at the fraction s of the step.
    fn pose(&self, s: f64) -> [f64; 6] {
        self.coeffs
            .map(|c| c.iter().rev().fold(0.0, |acc, &cp| acc * s + cp))
    }
}

/// The dead-centre and toggle positions passed between consecutive rows
/// that are both solved, or on a solved row where the sign changes across
/// it (or at either end of the solved rows), in time order. `t` holds the
/// rows' times (s), `motion` each row's [`ROW`] values, row after row, and
/// `solved` whether each row was solved (a row whose time or values are
/// not finite counts as not solved).
///
/// # Panics
/// When `motion` does not hold [`ROW`] values for each time, or `solved`
/// one flag for each.
pub fn marks(pins: &LoopPins, t: &[f64], motion: &[f64], solved: &[bool]) -> Vec<Mark> {
    let rows = t.len();
    assert_eq!(motion.len(), rows * ROW, "{ROW} motion values a row");
    assert_eq!(solved.len(), rows, "one solved flag a row");
    let row = |k: usize| &motion[k * ROW..(k + 1) * ROW];
    let ok: Vec<bool> = (0..rows)
        .map(|k| solved[k] && t[k].is_finite() && row(k).iter().all(|v| v.is_finite()))
        .collect();
    let mut out = Vec::new();
    for kind in [MarkKind::DeadCentre, MarkKind::Toggle] {
        let g: Vec<f64> = (0..rows)
            .map(|k| {
                let (a, b, _) = pins_at(pins, &row(k)[..6]);
                kind.cross(pins, a, b)
            })
            .collect();
        let mark = |k: usize, s: f64, pose: &[f64]| {
            let (a, b, crank) = pins_at(pins, pose);
            let t = if s == 0.0 {
                t[k]
            } else {
                t[k] + s * (t[k + 1] - t[k])
            };
            Mark {
                t,
                kind,
                crank,
                at: match kind {
                    MarkKind::DeadCentre => b,
                    MarkKind::Toggle => a,
                },
            }
        };
        for k in 0..rows {
            if !ok[k] {
                continue;
            }
            // Within the step to the next row: the signs differ.
            if k + 1 < rows && ok[k + 1] && opposite(g[k], g[k + 1]) {
                let step = Step::new(t[k + 1] - t[k], row(k), row(k + 1));
                let f = |s: f64| {
                    let (a, b, _) = pins_at(pins, &step.pose(s));
                    kind.cross(pins, a, b)
                };
                let s = illinois(f, g[k], g[k + 1]);
                out.push(mark(k, s, &step.pose(s)));
            }
            // On the row itself: a sign change across it, or a zero at
            // either end of the solved rows; not where the links only come
            // into line and go back.
            if g[k] == 0.0 {
                let before = (k > 0 && ok[k - 1]).then(|| g[k - 1]);
                let after = (k + 1 < rows && ok[k + 1]).then(|| g[k + 1]);
                let passed = match (before, after) {
                    (Some(b), Some(a)) => opposite(b, a),
                    (Some(x), None) | (None, Some(x)) => x != 0.0,
                    (None, None) => false,
                };
                if passed {
                    out.push(mark(k, 0.0, &row(k)[..6]));
                }
            }
        }
    }
    out.sort_by(|x, y| x.t.total_cmp(&y.t));
    out
}

/// True when `a` and `b` are of strictly opposite signs (compared, not
/// multiplied: a product of two small values can underflow to 0).
fn opposite(a: f64, b: f64) -> bool {
    (a < 0.0 && b > 0.0) || (a > 0.0 && b < 0.0)
}

/// A root in [0, 1] of `f`, whose values at the ends `fa` and `fb` are of
/// opposite signs, by regula falsi with the Illinois halving.
fn illinois(f: impl Fn(f64) -> f64, fa: f64, fb: f64) -> f64 {
    let (mut a, mut b, mut fa, mut fb) = (0.0, 1.0, fa, fb);
    // Which end moved last: -1 the right, 1 the left.
    let mut side = 0;
    let mut s = 0.0;
    for _ in 0..ITERATIONS {
        s = (a * fb - b * fa) / (fb - fa);
        let fs = f(s);
        if fs == 0.0 || b - a < BRACKET {
            break;
        }
        if (fs > 0.0) == (fb > 0.0) {
            (b, fb) = (s, fs);
            if side == -1 {
                fa /= 2.0;
            }
            side = -1;
        } else {
            (a, fa) = (s, fs);
            if side == 1 {
                fb /= 2.0;
            }
            side = 1;
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cubic_root_by_illinois() {
        let s = illinois(|s| s * s * s - 0.2, -0.2, 0.8);
        assert!((s - 0.2f64.cbrt()).abs() < 1e-13, "{s}");
    }

    #[test]
    fn the_quintic_meets_its_end_values_and_rates() {
        let h = 0.3;
        let r0: Vec<f64> = (0..ROW).map(|i| 0.1 * i as f64 - 0.4).collect();
        let r1: Vec<f64> = (0..ROW).map(|i| 0.05 * (i * i) as f64 - 0.2).collect();
        let step = Step::new(h, &r0, &r1);
        let (p0, p1) = (step.pose(0.0), step.pose(1.0));
        for ch in 0..6 {
            assert!((p0[ch] - r0[ch]).abs() < 1e-15);
            assert!((p1[ch] - r1[ch]).abs() < 1e-13);
            // The rate at the ends: d/dt = (1/h) d/ds.
            let ds = 1e-4;
            let y = |s: f64| step.pose(s)[ch];
            for (s, r) in [(0.0, &r0), (1.0, &r1)] {
                // d/dt = (1/h) d/ds, d²/dt² = (1/h²) d²/ds².
                let v = (y(s + ds) - y(s - ds)) / (2.0 * ds * h);
                let a = (y(s + ds) - 2.0 * y(s) + y(s - ds)) / (ds * ds * h * h);
                assert!((v - r[6 + ch]).abs() < 1e-6, "{ch} at {s}: {v}");
                assert!((a - r[12 + ch]).abs() < 1e-4, "{ch} at {s}: {a}");
            }
        }
    }
}
