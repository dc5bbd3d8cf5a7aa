//! The geometry of a cam's exports: the cam angles of a CSV (a fixed
//! step, or a chordal tolerance), and lines and arcs fitted to the profile
//! within a tolerance for a DXF.
//!
//! Points are in the cam frame (m), the cam centre at the origin; cam
//! angles θ in rad over one turn [0, 2π). A chordal tolerance bounds how
//! far the curve strays from the chord between two neighbouring points.

use std::f64::consts::TAU;

use camlink_core::cam::Cam;
use camlink_core::cam_limits;
use camlink_core::fmt_num::{self, num};

use crate::limits::{MAX_CSV_ROWS, MIN_RELATIVE_TOLERANCE};

/// Most points [`chord_angles`] gives.
pub const MAX_POINTS: usize = 2_000_000;

/// Intervals over a turn that [`chord_angles`] starts from (5° each).
const START_INTERVALS: usize = 72;

/// Shortest interval (rad) [`chord_angles`] halves.
const LEAST_INTERVAL: f64 = 1e-9;

/// Cam angles θ (rad) over one turn at `step` (rad), the end excluded: at
/// least 3 and at most [`MAX_CSV_ROWS`]; an error for a step that is not
/// positive or makes more rows.
pub fn angles_by_step(step: f64) -> Result<Vec<f64>, String> {
    if !(step > 0.0 && step.is_finite()) {
        return Err(format!("the step must be positive, got {} rad", num(step)));
    }
    // Counted as a float: a tiny step's count does not fit a usize.
    let rows = (TAU / step - 1e-9).ceil().max(3.0);
    if rows > MAX_CSV_ROWS as f64 {
        return Err(format!(
            "a step of {}° makes {} rows; at most {MAX_CSV_ROWS} (a step of at least {}°)",
            num(step.to_degrees()),
            fmt_num::count(rows),
            num(360.0 / MAX_CSV_ROWS as f64)
        ));
    }
    let n = rows as usize;
    let h = TAU / n as f64;
    Ok((0..n).map(|k| k as f64 * h).collect())
}

/// An error when `tolerance` (m) is not positive or is finer than
/// [`MIN_RELATIVE_TOLERANCE`] of the size of the curve `offset` (m)
/// outside `cam`'s surface (its largest distance from the cam centre).
pub fn check_tolerance(cam: &Cam, tolerance: f64, offset: f64) -> Result<(), String> {
    if !(tolerance > 0.0 && tolerance.is_finite()) {
        return Err(format!(
            "the tolerance must be positive, got {} m",
            num(tolerance)
        ));
    }
    let size = cam_limits::geometry(cam).max_radius + offset.abs();
    let least = MIN_RELATIVE_TOLERANCE * size;
    if tolerance < least {
        return Err(format!(
            "a tolerance of {} m is finer than {} of the profile's size ({} m); use at least {} m",
            num(tolerance),
            num(MIN_RELATIVE_TOLERANCE),
            num(size),
            num(least)
        ));
    }
    Ok(())
}

/// Cam angles θ (rad) of `cam`'s surface, or of the curve `offset` (m)
/// outside it, within the chordal `tolerance` (m): [`check_tolerance`],
/// then [`chord_angles`].
pub fn angles_by_chord(cam: &Cam, tolerance: f64, offset: f64) -> Result<Vec<f64>, String> {
    check_tolerance(cam, tolerance, offset)?;
    chord_angles(|t| cam.offset_point(t, offset), tolerance)
}

/// Angles θ over [0, 2π) of the closed curve `point(θ)` such that no curve
/// point between two neighbours lies farther than `tolerance` from their
/// chord, checked at the quarter, middle and three-quarter points of every
/// interval and halving where it fails (not below 1e-9 rad). Starts from
/// 72 intervals; θ = 0 first, the angles increasing. An error when more
/// than [`MAX_POINTS`] are needed.
pub fn chord_angles(point: impl Fn(f64) -> [f64; 2], tolerance: f64) -> Result<Vec<f64>, String> {
    let h = TAU / START_INTERVALS as f64;
    let mut a: Vec<f64> = (0..START_INTERVALS).map(|k| k as f64 * h).collect();
    let mut b: Vec<f64> = (1..=START_INTERVALS)
        .map(|k| {
            if k == START_INTERVALS {
                TAU
            } else {
                k as f64 * h
            }
        })
        .collect();
    let mut done: Vec<f64> = Vec::new();
    // Breadth first: each level's intervals, then their halves.
    while !a.is_empty() {
        let mut split = Vec::with_capacity(a.len());
        for (&a, &b) in a.iter().zip(&b) {
            let at = |u: f64| point(a + (b - a) * u);
            let (p0, p1) = (at(0.0), at(1.0));
            let d = [p1[0] - p0[0], p1[1] - p0[1]];
            let ln = d[0].hypot(d[1]);
            // The largest distance of the probes from the chord (NaN if any is).
            let mut dev = f64::NEG_INFINITY;
            for u in [0.25, 0.5, 0.75] {
                let p = at(u);
                let r = [p[0] - p0[0], p[1] - p0[1]];
                let e = if ln > 0.0 {
                    (d[0] * r[1] - d[1] * r[0]).abs() / ln
                } else {
                    r[0].hypot(r[1])
                };
                dev = if dev.is_nan() || e.is_nan() {
                    f64::NAN
                } else {
                    dev.max(e)
                };
            }
            let s = dev > tolerance && b - a > LEAST_INTERVAL;
            if !s {
                done.push(b);
            }
            split.push(s);
        }
        let halves = split.iter().filter(|&&s| s).count();
        if done.len() + 2 * halves > MAX_POINTS {
            return Err(format!(
                "more than {MAX_POINTS} points are needed to follow the curve within {} m",
                num(tolerance)
            ));
        }
        let (mut na, mut nb) = (
            Vec::with_capacity(2 * halves),
            Vec::with_capacity(2 * halves),
        );
        let mids: Vec<f64> = (0..a.len())
            .filter(|&k| split[k])
            .map(|k| 0.5 * (a[k] + b[k]))
            .collect();
        na.extend((0..a.len()).filter(|&k| split[k]).map(|k| a[k]));
        na.extend(&mids);
        nb.extend(&mids);
        nb.extend((0..b.len()).filter(|&k| split[k]).map(|k| b[k]));
        (a, b) = (na, nb);
    }
    done.sort_by(f64::total_cmp);
    done.pop();
    done.insert(0, 0.0);
    Ok(done)
}

/// A fitted piece of a profile: an arc about `centre` (m) of `radius` (m)
/// running counterclockwise from `start` to `end` (deg), or a line when
/// `radius` is infinite (its centre NaN); `p0`, `p1` are the ends of the
/// run of points it covers, in their order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arc {
    pub centre: [f64; 2],
    pub radius: f64,
    pub start: f64,
    pub end: f64,
    pub p0: [f64; 2],
    pub p1: [f64; 2],
}

/// The circle through three points (centre (m), radius (m)); `None` when
/// they are collinear.
pub fn circle(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> Option<([f64; 2], f64)> {
    let d = 2.0 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]));
    if d.abs() < 1e-300 {
        return None;
    }
    let (aa, bb, cc) = (dot(a, a), dot(b, b), dot(c, c));
    let ux = (aa * (b[1] - c[1]) + bb * (c[1] - a[1]) + cc * (a[1] - b[1])) / d;
    let uy = (aa * (c[0] - b[0]) + bb * (a[0] - c[0]) + cc * (b[0] - a[0])) / d;
    let centre = [ux, uy];
    Some((centre, distance(a, centre)))
}

/// a · b, as a₁ b₁ + (a₀ b₀), the sum rounded once (a fused
/// multiply-add): the order the exports' recorded figures are made in.
fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[1].mul_add(b[1], a[0] * b[0])
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = [a[0] - b[0], a[1] - b[1]];
    dot(d, d).sqrt()
}

/// The largest of `x` (NaN when any is).
fn largest(x: impl Iterator<Item = f64>) -> f64 {
    x.fold(f64::NEG_INFINITY, |m, v| {
        if m.is_nan() || v.is_nan() {
            f64::NAN
        } else {
            m.max(v)
        }
    })
}

/// The line over `run` (when every point lies within `tolerance` (m) of
/// the chord between its ends), or else the arc through its ends and its
/// middle point (when every point lies within `tolerance` of it, less the
/// arc's largest sagitta over the edges between neighbouring points, so
/// that the edges stay within `tolerance` too); `None` when neither does.
/// `run` holds at least two points.
pub fn fit_run(run: &[[f64; 2]], tolerance: f64) -> Option<Arc> {
    let (first, last) = (run[0], run[run.len() - 1]);
    let d = [last[0] - first[0], last[1] - first[1]];
    let ln = d[0].hypot(d[1]);
    let rel = run.iter().map(|p| [p[0] - first[0], p[1] - first[1]]);
    let off = if ln > 0.0 {
        largest(rel.map(|r| (d[0] * r[1] - d[1] * r[0]).abs())) / ln
    } else {
        largest(rel.map(|r| r[0].hypot(r[1])))
    };
    if off <= tolerance {
        return Some(Arc {
            centre: [f64::NAN, f64::NAN],
            radius: f64::INFINITY,
            start: 0.0,
            end: 0.0,
            p0: first,
            p1: last,
        });
    }
    let mid = run[run.len() / 2];
    let (centre, radius) = circle(first, mid, last)?;
    let half = largest(
        run.windows(2)
            .map(|w| 0.5 * (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1])),
    );
    let sagitta = radius - (radius * radius - half * half).max(0.0).sqrt();
    let within = run
        .iter()
        .all(|&p| (distance(p, centre) - radius).abs() <= tolerance - sagitta);
    if !within {
        return None;
    }
    let angle = |p: [f64; 2]| (p[1] - centre[1]).atan2(p[0] - centre[0]).to_degrees();
    let (mut a0, mut a1) = (angle(first), angle(last));
    // A clockwise run: swap its ends (an arc runs counterclockwise).
    let cross =
        (mid[0] - first[0]) * (last[1] - first[1]) - (mid[1] - first[1]) * (last[0] - first[0]);
    if cross < 0.0 {
        (a0, a1) = (a1, a0);
    }
    Some(Arc {
        centre,
        radius,
        start: a0,
        end: a1,
        p0: first,
        p1: last,
    })
}

/// Lines and arcs ([`fit_run`]) covering the closed polygon `points`, each
/// run as long as every point and every edge of it stays within
/// `tolerance` − `slack` (m) of its line or arc (run lengths found by
/// doubling, then bisection). A curve that leaves each edge of the polygon
/// by at most `slack` stays within `tolerance` of the pieces. Neighbouring
/// pieces share their end points. An error when `tolerance` is not above
/// `slack` or a point is not finite (naming the first).
pub fn fit_arcs(points: &[[f64; 2]], tolerance: f64, slack: f64) -> Result<Vec<Arc>, String> {
    let margin = tolerance - slack;
    if margin.is_nan() || margin <= 0.0 {
        return Err(format!(
            "the tolerance ({} m) must be above the polygon's distance from the curve ({} m)",
            num(tolerance),
            num(slack)
        ));
    }
    if let Some(k) = points
        .iter()
        .position(|p| !(p[0].is_finite() && p[1].is_finite()))
    {
        return Err(format!("the profile's point {k} is not finite"));
    }
    let n = points.len();
    let mut pts = points.to_vec();
    if let Some(&p) = points.first() {
        pts.push(p);
    }
    let tol = tolerance - slack;
    let mut arcs = Vec::new();
    let mut i = 0;
    while i < n {
        // A run of two points is its own chord. The run ends at `lo`, which
        // fits; `hi` is the least end known not to (n + 1 until one fails).
        let (mut lo, mut hi, mut step) = (i + 1, n + 1, 1);
        let mut fit = fit_run(&pts[i..i + 2], tol);
        while lo + 1 < hi {
            let j = if hi > n {
                (lo + step).min(n)
            } else {
                (lo + hi) / 2
            };
            match fit_run(&pts[i..=j], tol) {
                None => hi = j,
                Some(f) => {
                    (lo, fit, step) = (j, Some(f), 2 * step);
                }
            }
        }
        // Two finite points always fit as their chord.
        let Some(fit) = fit else {
            return Err(format!(
                "no line or arc fits the profile's points {i} and {}",
                i + 1
            ));
        };
        arcs.push(fit);
        i = lo;
    }
    Ok(arcs)
}
