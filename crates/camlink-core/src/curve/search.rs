//! Finding contact parameters on curves: the starting values of the
//! curve-contact joints' own coordinates.
//!
//! Each search samples the curve (one period of a closed curve, the range
//! of an open one, ends included), takes the best sample and refines it by
//! a few safeguarded Newton iterations. Given a guess, the search refines
//! the guess instead, so that a model can pick one of several contacts. On
//! an open curve results stay inside the range; on a closed one a result
//! found from samples lies in the range, a refined guess stays near the
//! guess (not wrapped).

use super::{Carried, Curve, CurveJet};
use crate::math::{cross, dot, norm, sub, V2};

/// Samples per curve in the searches.
const SAMPLES: usize = 256;
/// Samples per curve in the two-curve search.
const PAIR_SAMPLES: usize = 128;
/// Most Newton iterations.
const ITERATIONS: usize = 50;

/// The parameter of the point of `curve` nearest to `target` (body frame,
/// m): the minimum of |p(s) − target|².
pub fn closest(curve: &Curve, target: V2, guess: Option<f64>) -> f64 {
    minimize(
        curve,
        |j| {
            let d = sub(j.p, target);
            (
                0.5 * dot(d, d),
                dot(j.d1, d),
                dot(j.d1, j.d1) + dot(j.d2, d),
            )
        },
        guess,
    )
}

/// The parameter of the point of `curve` farthest in direction `dir` (body
/// frame): the maximum of dirᵀ p(s). On a convex profile this is where the
/// tangent is perpendicular to `dir`.
pub fn support(curve: &Curve, dir: V2, guess: Option<f64>) -> f64 {
    minimize(
        curve,
        |j| (-dot(dir, j.p), -dot(dir, j.d1), -dot(dir, j.d2)),
        guess,
    )
}

/// The sample parameters: `n` over one period of a closed curve, `n + 1`
/// over an open one (both ends).
fn samples(curve: &Curve, n: usize) -> impl Iterator<Item = f64> {
    let (s0, s1) = curve.range();
    let m = if curve.closed() { n } else { n + 1 };
    (0..m).map(move |k| s0 + (s1 - s0) * k as f64 / n as f64)
}

/// Bounds on the parameter: the range of an open curve, none on a closed one.
fn bounds(curve: &Curve) -> (f64, f64) {
    if curve.closed() {
        (f64::NEG_INFINITY, f64::INFINITY)
    } else {
        curve.range()
    }
}

/// Minimizes f(s) given as (f, f′, f″) of the curve jet: from the best
/// sample, or from `guess`.
fn minimize(curve: &Curve, f: impl Fn(&CurveJet) -> (f64, f64, f64), guess: Option<f64>) -> f64 {
    let (lo, hi) = bounds(curve);
    let mut s = match guess {
        Some(g) => g.clamp(lo, hi),
        None => {
            samples(curve, SAMPLES)
                .map(|s| (f(&curve.jet(s)).0, s))
                .fold((f64::INFINITY, 0.0), |a, b| if b.0 < a.0 { b } else { a })
                .1
        }
    };
    let (s0, s1) = curve.range();
    let max_step = (s1 - s0) / 8.0;
    let (mut val, mut d1, mut d2) = f(&curve.jet(s));
    for _ in 0..ITERATIONS {
        // Newton where f is convex, otherwise a bounded descent step;
        // halved until f decreases.
        let mut step = if d2 > 0.0 {
            -d1 / d2
        } else {
            -d1.signum() * max_step
        };
        step = step.clamp(-max_step, max_step);
        let mut moved = None;
        for _ in 0..40 {
            let t = (s + step).clamp(lo, hi);
            let (v, e1, e2) = f(&curve.jet(t));
            if v <= val {
                moved = Some((t, v, e1, e2));
                break;
            }
            step *= 0.5;
        }
        let Some((t, v, e1, e2)) = moved else { break };
        let done = (t - s).abs() <= 1e-14 * (s1 - s0).max(s.abs());
        (s, val, d1, d2) = (t, v, e1, e2);
        if done {
            break;
        }
    }
    s
}

/// Contact parameters (s_i, s_j) of curve `ci` on a body at `qi` and curve
/// `cj` on a body at `qj`: the points coincide or, apart, face each other
/// along a common normal with collinear tangents. Solves
/// F = [dᵀ g_i, g_i × g_j] = 0, d = r_i^P − r_j^P, by Newton from the
/// nearest pair of samples (or from `guess`). Without a guess, a Newton
/// result that fails to converge or lands farther apart than the samples
/// by a tenth of the smaller curve's size is dropped for the nearest
/// samples.
pub(crate) fn contact_pair(
    ci: &Curve,
    qi: [f64; 3],
    cj: &Curve,
    qj: [f64; 3],
    guess: Option<[f64; 2]>,
) -> [f64; 2] {
    let at = |c: &Curve, q: [f64; 3], s: f64| Carried::new(q, [0.0; 3], &c.jet(s), 0.0);
    let start = match guess {
        Some(g) => g,
        None => {
            let pj: Vec<(f64, V2)> = samples(cj, PAIR_SAMPLES)
                .map(|s| (s, at(cj, qj, s).p))
                .collect();
            let mut best = (f64::INFINITY, [0.0; 2]);
            for si in samples(ci, PAIR_SAMPLES) {
                let p = at(ci, qi, si).p;
                for &(sj, q) in &pj {
                    let d = sub(p, q);
                    let dd = dot(d, d);
                    if dd < best.0 {
                        best = (dd, [si, sj]);
                    }
                }
            }
            best.1
        }
    };
    let (bi, bj) = (bounds(ci), bounds(cj));
    let span = |c: &Curve| {
        let (a, b) = c.range();
        b - a
    };
    let (max_i, max_j) = (span(ci) / 8.0, span(cj) / 8.0);
    let mut s = start;
    let mut converged = false;
    for _ in 0..ITERATIONS {
        let (a, b) = (at(ci, qi, s[0]), at(cj, qj, s[1]));
        let d = sub(a.p, b.p);
        let f = [dot(d, a.g), cross(a.g, b.g)];
        let jac = [
            [dot(a.g, a.g) + dot(d, a.g_s), -dot(b.g, a.g)],
            [cross(a.g_s, b.g), cross(a.g, b.g_s)],
        ];
        let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
        if det == 0.0 || !det.is_finite() {
            break;
        }
        let di = -(f[0] * jac[1][1] - f[1] * jac[0][1]) / det;
        let dj = -(jac[0][0] * f[1] - jac[1][0] * f[0]) / det;
        let next = [
            (s[0] + di.clamp(-max_i, max_i)).clamp(bi.0, bi.1),
            (s[1] + dj.clamp(-max_j, max_j)).clamp(bj.0, bj.1),
        ];
        let small = (next[0] - s[0]).abs() <= 1e-12 * span(ci).max(s[0].abs())
            && (next[1] - s[1]).abs() <= 1e-12 * span(cj).max(s[1].abs());
        s = next;
        if small {
            converged = true;
            break;
        }
    }
    if !(converged && s.iter().all(|v| v.is_finite())) {
        return start;
    }
    if guess.is_none() {
        let gap = |s: [f64; 2]| norm(sub(at(ci, qi, s[0]).p, at(cj, qj, s[1]).p));
        let size = size(ci).min(size(cj));
        if gap(s) > gap(start) + 0.1 * size {
            return start;
        }
        return [ci.wrap(s[0]), cj.wrap(s[1])];
    }
    s
}

/// Diagonal of the sampled bounding box of a curve (m).
fn size(c: &Curve) -> f64 {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for s in samples(c, 64) {
        let p = c.jet(s).p;
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    norm(sub(hi, lo))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::{Parametric, Polar};
    use std::f64::consts::{FRAC_PI_2, PI, TAU};

    #[test]
    fn closest_point_on_circle_and_line() {
        let c = Curve::from(Polar::circle([1.0, 0.0], 0.5).unwrap());
        let s = closest(&c, [1.0, 3.0], None);
        assert!((s - FRAC_PI_2).abs() < 1e-10, "{s}");
        // A guess is refined, not wrapped.
        let s = closest(&c, [1.0, 3.0], Some(FRAC_PI_2 + TAU + 0.3));
        assert!((s - FRAC_PI_2 - TAU).abs() < 1e-10, "{s}");
        let l = Curve::from(Parametric::line([0.0, 0.0], [2.0, 0.0]).unwrap());
        assert!((closest(&l, [0.7, 1.0], None) - 0.7).abs() < 1e-12);
        // Beyond the end: the end.
        assert_eq!(closest(&l, [3.0, 1.0], None), 2.0);
    }

    #[test]
    fn support_point_of_fourier_cam() {
        let c = Curve::from(Polar::fourier([0.0, 0.0], 1.0, &[0.0, 0.2], &[]).unwrap());
        // ρ = 1 + 0.2 cos 2α is largest at α = 0 and π; the support point
        // in direction (0, 1) is at α = π/2 where ρ is smallest and flat.
        let s = support(&c, [1.0, 0.0], None);
        assert!(s.abs() < 1e-9 || (s - TAU).abs() < 1e-9, "{s}");
        let s = support(&c, [0.0, -1.0], None);
        assert!((s - 1.5 * PI).abs() < 1e-9, "{s}");
    }

    #[test]
    fn circle_on_circle_touches_on_the_centre_line() {
        // Cam circle R = 1 about (0.2, 0) on body i at (0.5, 0.5, 0.3);
        // roller r = 0.25 about its origin on body j, touching.
        let cam = Curve::from(Polar::circle([0.2, 0.0], 1.0).unwrap());
        let roller = Curve::from(Polar::circle([0.0, 0.0], 0.25).unwrap());
        let qi = [0.5, 0.5, 0.3];
        let centre = crate::math::point(qi, [0.2, 0.0]);
        let dir: f64 = 2.0;
        let cj = [centre[0] + 1.25 * dir.cos(), centre[1] + 1.25 * dir.sin()];
        let qj = [cj[0], cj[1], -0.4];
        let [ai, aj] = contact_pair(&cam, qi, &roller, qj, None);
        assert!((ai - (dir - 0.3)).abs() < 1e-9, "{ai}");
        assert!((aj - (dir + PI + 0.4)).abs() < 1e-9, "{aj}");
        // Apart by a gap, still the centre-line points.
        let qj = [
            centre[0] + 1.4 * dir.cos(),
            centre[1] + 1.4 * dir.sin(),
            -0.4,
        ];
        let [ai, aj] = contact_pair(&cam, qi, &roller, qj, None);
        assert!((ai - (dir - 0.3)).abs() < 1e-9 && (aj - (dir + PI + 0.4)).abs() < 1e-9);
        // Overlapping slightly: the deepest points, again on the centre line.
        let qj = [
            centre[0] + 1.2 * dir.cos(),
            centre[1] + 1.2 * dir.sin(),
            -0.4,
        ];
        let [ai, aj] = contact_pair(&cam, qi, &roller, qj, None);
        assert!((ai - (dir - 0.3)).abs() < 1e-9 && (aj - (dir + PI + 0.4)).abs() < 1e-9);
    }
}
