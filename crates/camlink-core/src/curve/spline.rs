//! Interpolating cubic splines.
//!
//! [`Spline`] is a scalar cubic spline y(x) through points (x_k, y_k); on
//! interval k, with t = x − x_k, y = a + b t + c t² + d t³. It is C²:
//! value, slope and second derivative are continuous; the third derivative
//! 6d is constant on each interval and jumps at the knots. So a cam profile
//! from a spline has continuous curvature and a piecewise-constant ρ‴.
//!
//! - Periodic (closed profiles): y, y′ and y″ match across the wrap
//!   x_n = x₀ + P; at least 3 points.
//! - Open: "not-a-knot" ends (the third derivative is continuous at the
//!   second and the next-to-last knot), which keeps the end curvature of the
//!   data instead of forcing it to zero; 3 points give the parabola, 2 the
//!   line. Past the ends the end cubic continues.
//!
//! The second derivatives M_k at the knots solve a sparse (cyclic)
//! tridiagonal system, factored by faer's sparse LU.
//!
//! [`PlanarSpline`] interpolates points P_k of the plane by x(s), y(s),
//! parametrised by cumulative chord length s (m), open or closed.

use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::Mat;

use super::{CurveError, CurveJet, CurveJet4};
use crate::math::{norm, sub, V2};

/// A cubic spline y(x) through given points, periodic or open.
#[derive(Clone, Debug, PartialEq)]
pub struct Spline {
    /// Knots x₀ < … < x_n (periodic: x_n = x₀ + P).
    x: Vec<f64>,
    /// Coefficients (a, b, c, d) of each of the n intervals.
    c: Vec<[f64; 4]>,
    periodic: bool,
}

impl Spline {
    /// The periodic spline of period `period` through `(x_k, y_k)`, x
    /// strictly increasing with x_last − x₀ < period. A last point at
    /// x₀ + period repeating the first value is accepted and dropped.
    pub fn periodic(points: &[V2], period: f64) -> Result<Self, CurveError> {
        let mut pts = points.to_vec();
        check_points(&pts)?;
        if !(period > 0.0 && period.is_finite()) {
            return Err(CurveError::Invalid(format!(
                "the period must be positive, got {period}"
            )));
        }
        if let (Some(first), Some(last)) = (pts.first().copied(), pts.last().copied()) {
            let span = last[0] - first[0];
            let tol = 1e-9 * period;
            if (span - period).abs() <= tol && pts.len() > 1 {
                if (last[1] - first[1]).abs() > 1e-9 * (1.0 + first[1].abs()) {
                    return Err(CurveError::Invalid(format!(
                        "the last point (x = {}) closes the period but its value {} differs from the first value {}",
                        last[0], last[1], first[1]
                    )));
                }
                pts.pop();
            } else if span >= period {
                return Err(CurveError::Invalid(format!(
                    "the points span {span}, more than one period {period}"
                )));
            }
        }
        if pts.len() < 3 {
            return Err(CurveError::Invalid(format!(
                "a periodic spline needs at least 3 distinct points, got {}",
                pts.len()
            )));
        }
        let n = pts.len();
        let mut x: Vec<f64> = pts.iter().map(|p| p[0]).collect();
        let mut y: Vec<f64> = pts.iter().map(|p| p[1]).collect();
        x.push(x[0] + period);
        y.push(y[0]);
        let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let del: Vec<f64> = (0..n).map(|k| (y[k + 1] - y[k]) / h[k]).collect();
        // Row k: h_{k−1} M_{k−1} + 2(h_{k−1} + h_k) M_k + h_k M_{k+1}
        //        = 6(δ_k − δ_{k−1}), indices cyclic.
        let mut t = Vec::with_capacity(3 * n);
        let mut rhs = vec![0.0; n];
        for k in 0..n {
            let km = (k + n - 1) % n;
            t.push(Triplet::new(k, km, h[km]));
            t.push(Triplet::new(k, k, 2.0 * (h[km] + h[k])));
            t.push(Triplet::new(k, (k + 1) % n, h[k]));
            rhs[k] = 6.0 * (del[k] - del[km]);
        }
        let mut m = solve(n, &t, &rhs)?;
        m.push(m[0]);
        Ok(Spline {
            c: coefficients(&x, &y, &m),
            x,
            periodic: true,
        })
    }

    /// The open spline through `(x_k, y_k)`, x strictly increasing, with
    /// not-a-knot ends; at least 2 points.
    pub fn open(points: &[V2]) -> Result<Self, CurveError> {
        check_points(points)?;
        let n = points.len();
        if n < 2 {
            return Err(CurveError::Invalid(format!(
                "a spline needs at least 2 points, got {n}"
            )));
        }
        let x: Vec<f64> = points.iter().map(|p| p[0]).collect();
        let y: Vec<f64> = points.iter().map(|p| p[1]).collect();
        let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let del: Vec<f64> = (0..n - 1).map(|k| (y[k + 1] - y[k]) / h[k]).collect();
        let mut t = Vec::with_capacity(3 * n);
        let mut rhs = vec![0.0; n];
        // Interior rows: the standard continuity of y′.
        for k in 1..n - 1 {
            t.push(Triplet::new(k, k - 1, h[k - 1]));
            t.push(Triplet::new(k, k, 2.0 * (h[k - 1] + h[k])));
            t.push(Triplet::new(k, k + 1, h[k]));
            rhs[k] = 6.0 * (del[k] - del[k - 1]);
        }
        // End rows.
        match n {
            2 => {
                // A line: M₀ = M₁ = 0.
                t.push(Triplet::new(0, 0, 1.0));
                t.push(Triplet::new(1, 1, 1.0));
            }
            3 => {
                // A parabola: M₀ = M₁ = M₂.
                t.push(Triplet::new(0, 0, 1.0));
                t.push(Triplet::new(0, 1, -1.0));
                t.push(Triplet::new(2, 2, 1.0));
                t.push(Triplet::new(2, 1, -1.0));
            }
            _ => {
                // Not-a-knot: (M₁ − M₀)/h₀ = (M₂ − M₁)/h₁, and likewise at
                // the other end.
                t.push(Triplet::new(0, 0, -h[1]));
                t.push(Triplet::new(0, 1, h[0] + h[1]));
                t.push(Triplet::new(0, 2, -h[0]));
                let (a, b) = (h[n - 3], h[n - 2]);
                t.push(Triplet::new(n - 1, n - 3, -b));
                t.push(Triplet::new(n - 1, n - 2, a + b));
                t.push(Triplet::new(n - 1, n - 1, -a));
            }
        }
        let m = solve(n, &t, &rhs)?;
        Ok(Spline {
            c: coefficients(&x, &y, &m),
            x,
            periodic: false,
        })
    }

    /// True for a periodic spline.
    pub(crate) fn is_periodic(&self) -> bool {
        self.periodic
    }

    /// The knots x₀ … x_n (periodic: x_n = x₀ + P).
    pub fn knots(&self) -> &[f64] {
        &self.x
    }

    /// (x₀, x_n): the data range, one period for a periodic spline.
    pub fn range(&self) -> (f64, f64) {
        (self.x[0], self.x[self.x.len() - 1])
    }

    /// `[y, y′, y″, y‴]` at `x` (wrapped into one period when periodic).
    #[inline]
    pub fn jet(&self, x: f64) -> [f64; 4] {
        let (x0, xn) = self.range();
        let x = if self.periodic {
            x0 + (x - x0).rem_euclid(xn - x0)
        } else {
            x
        };
        let k = self
            .x
            .partition_point(|&xk| xk <= x)
            .saturating_sub(1)
            .min(self.c.len() - 1);
        let [a, b, c, d] = self.c[k];
        let t = x - self.x[k];
        [
            a + t * (b + t * (c + t * d)),
            b + t * (2.0 * c + 3.0 * t * d),
            2.0 * c + 6.0 * t * d,
            6.0 * d,
        ]
    }

    /// `[y, y′, y″, y‴, y⁗]` at `x`: a cubic's fourth derivative is zero.
    pub fn jet4(&self, x: f64) -> [f64; 5] {
        let [y0, y1, y2, y3] = self.jet(x);
        [y0, y1, y2, y3, 0.0]
    }
}

/// Finite values and strictly increasing x.
fn check_points(points: &[V2]) -> Result<(), CurveError> {
    for (k, p) in points.iter().enumerate() {
        if !p[0].is_finite() || !p[1].is_finite() {
            return Err(CurveError::Invalid(format!(
                "point {} ({}, {}) is not finite",
                k + 1,
                p[0],
                p[1]
            )));
        }
        if k > 0 && p[0] <= points[k - 1][0] {
            return Err(CurveError::Invalid(format!(
                "the points must be in strictly increasing order of their first coordinate: point {} ({}) does not follow point {} ({})",
                k + 1,
                p[0],
                k,
                points[k - 1][0]
            )));
        }
    }
    Ok(())
}

/// Solves the n×n sparse system given by triplets.
fn solve(n: usize, t: &[Triplet<usize, usize, f64>], rhs: &[f64]) -> Result<Vec<f64>, CurveError> {
    let fail = || CurveError::Invalid("the spline's equations are singular".into());
    let a = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, t).map_err(|_| fail())?;
    let lu = a.sp_lu().map_err(|_| fail())?;
    let mut b = Mat::from_fn(n, 1, |i, _| rhs[i]);
    lu.solve_in_place(b.as_mut());
    let m: Vec<f64> = (0..n).map(|i| b[(i, 0)]).collect();
    if m.iter().all(|v| v.is_finite()) {
        Ok(m)
    } else {
        Err(fail())
    }
}

/// Interval coefficients from knot values y_k and second derivatives M_k.
fn coefficients(x: &[f64], y: &[f64], m: &[f64]) -> Vec<[f64; 4]> {
    (0..x.len() - 1)
        .map(|k| {
            let h = x[k + 1] - x[k];
            let del = (y[k + 1] - y[k]) / h;
            [
                y[k],
                del - h * (2.0 * m[k] + m[k + 1]) / 6.0,
                m[k] / 2.0,
                (m[k + 1] - m[k]) / (6.0 * h),
            ]
        })
        .collect()
}

/// A planar cubic spline (x(s), y(s)) through points P_k, parametrised by
/// cumulative chord length s (m), open or closed.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanarSpline {
    x: Spline,
    y: Spline,
}

impl PlanarSpline {
    /// The spline through `points` (m). Closed: a periodic spline through
    /// the points and back to the first (a last point equal to the first is
    /// dropped), at least 3 points; open: not-a-knot ends, at least 2.
    /// Consecutive points must differ.
    pub fn new(points: &[V2], closed: bool) -> Result<Self, CurveError> {
        let mut pts = points.to_vec();
        if let Some(k) = pts
            .iter()
            .position(|p| !p[0].is_finite() || !p[1].is_finite())
        {
            return Err(CurveError::Invalid(format!(
                "point {} ({}, {}) is not finite",
                k + 1,
                pts[k][0],
                pts[k][1]
            )));
        }
        if closed && pts.len() > 1 && pts[0] == pts[pts.len() - 1] {
            pts.pop();
        }
        let mut s = Vec::with_capacity(pts.len());
        let mut len = 0.0;
        for (k, p) in pts.iter().enumerate() {
            if k > 0 {
                let h = norm(sub(*p, pts[k - 1]));
                if h == 0.0 {
                    return Err(CurveError::Invalid(format!(
                        "points {} and {} coincide at ({}, {})",
                        k,
                        k + 1,
                        p[0],
                        p[1]
                    )));
                }
                len += h;
            }
            s.push(len);
        }
        let xs: Vec<V2> = pts.iter().zip(&s).map(|(p, &s)| [s, p[0]]).collect();
        let ys: Vec<V2> = pts.iter().zip(&s).map(|(p, &s)| [s, p[1]]).collect();
        if closed {
            let close = pts
                .first()
                .zip(pts.last())
                .map_or(0.0, |(a, b)| norm(sub(*a, *b)));
            if pts.len() < 3 {
                return Err(CurveError::Invalid(format!(
                    "a closed spline needs at least 3 distinct points, got {}",
                    pts.len()
                )));
            }
            let period = len + close;
            Ok(PlanarSpline {
                x: Spline::periodic(&xs, period)?,
                y: Spline::periodic(&ys, period)?,
            })
        } else {
            Ok(PlanarSpline {
                x: Spline::open(&xs)?,
                y: Spline::open(&ys)?,
            })
        }
    }

    /// True for a closed spline.
    pub fn closed(&self) -> bool {
        self.x.is_periodic()
    }

    /// (0, L): L the total chord length (including the closing chord of a
    /// closed spline).
    pub fn range(&self) -> (f64, f64) {
        self.x.range()
    }

    /// The knots s_k (m).
    pub fn knots(&self) -> &[f64] {
        self.x.knots()
    }

    /// p(s), p′, p″, p‴ (closed splines wrap s).
    #[inline]
    pub fn jet(&self, s: f64) -> CurveJet {
        let (x, y) = (self.x.jet(s), self.y.jet(s));
        CurveJet {
            p: [x[0], y[0]],
            d1: [x[1], y[1]],
            d2: [x[2], y[2]],
            d3: [x[3], y[3]],
        }
    }

    /// p(s) … p⁗(s): p⁗ = 0 on every cubic piece.
    pub fn jet4(&self, s: f64) -> CurveJet4 {
        CurveJet4 {
            jet: self.jet(s),
            d4: [0.0; 2],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    /// Central differences of the jet entry `k` against entry `k + 1`.
    fn check_derivatives(f: impl Fn(f64) -> [f64; 4], xs: &[f64]) {
        let h = 1e-6;
        for &x in xs {
            let (p, m, j) = (f(x + h), f(x - h), f(x));
            for k in 0..3 {
                let fd = (p[k] - m[k]) / (2.0 * h);
                assert!(
                    (fd - j[k + 1]).abs() < 1e-6 * (1.0 + j[k + 1].abs()),
                    "derivative {} at {x}: {} vs {fd}",
                    k + 1,
                    j[k + 1]
                );
            }
        }
    }

    fn radius_points() -> Vec<V2> {
        (0..9)
            .map(|k| {
                let a = 0.1 + k as f64 * TAU / 9.0 + 0.05 * (k as f64).sin();
                [a, 1.0 + 0.2 * (2.0 * a).cos() + 0.05 * a.sin()]
            })
            .collect()
    }

    #[test]
    fn periodic_spline_interpolates() {
        let pts = radius_points();
        let s = Spline::periodic(&pts, TAU).unwrap();
        for p in &pts {
            assert!((s.jet(p[0])[0] - p[1]).abs() < 1e-13);
            assert!((s.jet(p[0] + TAU)[0] - p[1]).abs() < 1e-12);
            assert!((s.jet(p[0] - 3.0 * TAU)[0] - p[1]).abs() < 1e-12);
        }
    }

    #[test]
    fn periodic_spline_is_c2_across_the_wrap_and_at_knots() {
        let pts = radius_points();
        let s = Spline::periodic(&pts, TAU).unwrap();
        let e = 1e-9;
        let knots: Vec<f64> = s.knots().to_vec();
        for &x in &knots {
            let (l, r) = (s.jet(x - e), s.jet(x + e));
            for k in 0..3 {
                assert!(
                    (l[k] - r[k]).abs() < 1e-6,
                    "entry {k} jumps at {x}: {l:?} {r:?}"
                );
            }
        }
        // The wrap point seen from both sides of the period.
        let (x0, xn) = s.range();
        let (l, r) = (s.jet(xn - e), s.jet(x0 + e));
        for k in 0..3 {
            assert!(
                (l[k] - r[k]).abs() < 1e-6,
                "entry {k} jumps across the wrap"
            );
        }
    }

    #[test]
    fn spline_derivatives_match_finite_differences() {
        let s = Spline::periodic(&radius_points(), TAU).unwrap();
        // Away from knots, where y‴ is smooth.
        let xs: Vec<f64> = s
            .knots()
            .windows(2)
            .map(|w| 0.37 * w[0] + 0.63 * w[1])
            .collect();
        check_derivatives(|x| s.jet(x), &xs);
        let o =
            Spline::open(&[[0.0, 0.0], [0.5, 0.3], [1.2, 0.1], [2.0, 0.8], [2.5, 0.5]]).unwrap();
        check_derivatives(|x| o.jet(x), &[0.2, 0.9, 1.5, 2.3, -0.2, 2.7]);
    }

    #[test]
    fn open_spline_reproduces_a_cubic() {
        // Not-a-knot ends reproduce any cubic exactly.
        let f = |x: f64| 1.0 - 2.0 * x + 0.5 * x * x + 0.3 * x * x * x;
        let pts: Vec<V2> = [0.0, 0.3, 1.0, 1.4, 2.2, 3.0]
            .iter()
            .map(|&x| [x, f(x)])
            .collect();
        let s = Spline::open(&pts).unwrap();
        for &x in &[-0.5, 0.1, 0.7, 1.9, 2.8, 3.5] {
            let j = s.jet(x);
            assert!((j[0] - f(x)).abs() < 1e-11, "{x}: {} vs {}", j[0], f(x));
            assert!((j[3] - 1.8).abs() < 1e-9);
        }
    }

    #[test]
    fn small_open_splines_are_line_and_parabola() {
        let l = Spline::open(&[[0.0, 1.0], [2.0, 3.0]]).unwrap();
        assert_eq!(l.jet(1.0), [2.0, 1.0, 0.0, 0.0]);
        let p = Spline::open(&[[0.0, 0.0], [1.0, 1.0], [2.0, 4.0]]).unwrap();
        let j = p.jet(1.5);
        assert!((j[0] - 2.25).abs() < 1e-13 && (j[2] - 2.0).abs() < 1e-13 && j[3].abs() < 1e-13);
    }

    #[test]
    fn periodic_spline_accepts_a_closing_point_and_rejects_bad_data() {
        let mut pts = radius_points();
        pts.push([pts[0][0] + TAU, pts[0][1]]);
        assert!(Spline::periodic(&pts, TAU).is_ok());
        let last = pts.len() - 1;
        pts[last][1] += 0.1;
        assert!(Spline::periodic(&pts, TAU).is_err());
        assert!(Spline::periodic(&[[0.0, 1.0], [1.0, 1.0]], TAU).is_err());
        let err = Spline::open(&[[0.0, 1.0], [1.0, 1.0], [1.0, 2.0]]).unwrap_err();
        assert!(err.to_string().contains("point 3"), "{err}");
    }

    #[test]
    fn planar_spline_interpolates_and_closes_smoothly() {
        let pts: Vec<V2> = (0..7)
            .map(|k| {
                let a = k as f64 * TAU / 7.0;
                [2.0 * a.cos(), (1.0 + 0.1 * k as f64) * a.sin()]
            })
            .collect();
        let c = PlanarSpline::new(&pts, true).unwrap();
        assert!(c.closed());
        for (p, &s) in pts.iter().zip(c.knots()) {
            let j = c.jet(s);
            assert!((j.p[0] - p[0]).abs() < 1e-12 && (j.p[1] - p[1]).abs() < 1e-12);
        }
        let (s0, s1) = c.range();
        let (a, b) = (c.jet(s1 - 1e-9), c.jet(s0 + 1e-9));
        for (u, v) in [(a.p, b.p), (a.d1, b.d1), (a.d2, b.d2)] {
            assert!((u[0] - v[0]).abs() < 1e-6 && (u[1] - v[1]).abs() < 1e-6);
        }
        let o = PlanarSpline::new(&pts, false).unwrap();
        assert!(!o.closed());
        assert!(PlanarSpline::new(&[[0.0, 0.0], [0.0, 0.0]], false).is_err());
    }
}
