//! A polyline through a curve, fine enough to draw it.
//!
//! [`Curve::sample`] returns points p(s) on the curve (body frame, m) such
//! that the curve between two consecutive points stays within `tol` (m) of
//! the chord joining them: each chord is split until its quarter, middle and
//! three-quarter points lie within `tol` of it.

use crate::curve::Curve;
use crate::math::V2;

/// Chords a curve's parameter range is first split into.
const START_SEGMENTS: usize = 64;
/// Deepest halving of one starting chord (2¹⁶ pieces).
const MAX_DEPTH: u32 = 16;

impl Curve {
    /// Points (s, p(s)) along the curve's range, in increasing s, whose
    /// polyline lies within `tol` (m) of the curve. A closed curve's last
    /// point repeats its first (s₁ = s₀ + period).
    pub fn sample(&self, tol: f64) -> Vec<(f64, V2)> {
        let tol = if tol.is_finite() && tol > 0.0 {
            tol
        } else {
            1e-6
        };
        let (s0, s1) = self.range();
        let at = |s: f64| self.jet(s).p;
        let mut out = vec![(s0, at(s0))];
        for k in 0..START_SEGMENTS {
            let a = s0 + (s1 - s0) * k as f64 / START_SEGMENTS as f64;
            let b = s0 + (s1 - s0) * (k + 1) as f64 / START_SEGMENTS as f64;
            split(&at, (a, at(a)), (b, at(b)), tol, MAX_DEPTH, &mut out);
        }
        out
    }
}

/// Appends the points after `a` up to and including `b`, halving the chord
/// while the curve strays more than `tol` from it.
fn split(
    at: &impl Fn(f64) -> V2,
    a: (f64, V2),
    b: (f64, V2),
    tol: f64,
    depth: u32,
    out: &mut Vec<(f64, V2)>,
) {
    let far = [0.25, 0.5, 0.75].iter().any(|f| {
        let s = a.0 + (b.0 - a.0) * f;
        distance_to_chord(at(s), a.1, b.1) > tol
    });
    if far && depth > 0 {
        let m = 0.5 * (a.0 + b.0);
        let mid = (m, at(m));
        split(at, a, mid, tol, depth - 1, out);
        split(at, mid, b, tol, depth - 1, out);
    } else {
        out.push(b);
    }
}

/// Distance (m) from `p` to the segment a–b.
fn distance_to_chord(p: V2, a: V2, b: V2) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    let w = [p[0] - a[0], p[1] - a[1]];
    let u = if len2 > 0.0 {
        ((w[0] * d[0] + w[1] * d[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let e = [w[0] - u * d[0], w[1] - u * d[1]];
    (e[0] * e[0] + e[1] * e[1]).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::Polar;

    /// The polyline through a circle of radius r stays within tol of it:
    /// each chord's sagitta r(1 − cos(Δ/2)) is at most tol, and every point
    /// is on the circle.
    #[test]
    fn circle_chords_within_tolerance() {
        let r = 0.25;
        let curve: Curve = Polar::circle([0.0, 0.0], r).unwrap().into();
        for tol in [1e-3, 1e-5] {
            let pts = curve.sample(tol);
            for w in pts.windows(2) {
                let a = w[0].1;
                let half = 0.5 * (w[1].0 - w[0].0);
                assert!(r * (1.0 - half.cos()) <= tol, "sagitta over {tol}");
                assert!((a[0].hypot(a[1]) - r).abs() < 1e-12);
            }
            // Not more points than needed: twice the least uniform count.
            let least = std::f64::consts::PI / (1.0 - tol / r).acos();
            assert!((pts.len() as f64) < 2.0 * least + START_SEGMENTS as f64);
            let (first, last) = (pts[0].1, pts[pts.len() - 1].1);
            assert!((first[0] - last[0]).abs() < 1e-12 && (first[1] - last[1]).abs() < 1e-12);
        }
    }
}
