//! Motion programs: the follower's motion over one cam revolution.
//!
//! A program is a list of segments over the cam angle θ (rad), starting at
//! θ = 0, each with a span β, a lift h (m for a translating follower, rad of
//! swing for an oscillating one) and a law ([`LawKind`]). The follower
//! displacement s(θ) starts at 0 and each segment adds its lift:
//! s(θ) = s₀ + h S((θ − θ₀)/β) on [θ₀, θ₀ + β). Derivatives are with respect
//! to θ: s′ (m/rad), s″ (m/rad²), s‴ (m/rad³), s⁗; at angular speed ω the
//! time derivatives are ṡ = ω s′, s̈ = ω² s″, and the jerk ω³ s‴.
//!
//! A program closes when its spans add up to 2π and its lifts to zero.
//! Each boundary (including the one at 0 = 2π) is classified by the
//! highest derivative that is continuous there: C0 (position only) to C3
//! (jerk too), with the jumps of s′, s″, s‴ named.
//!
//! A fitted polynomial segment takes boundary conditions
//! s(θ₀) = s₀, s(θ₀ + β) = s₀ + h and any of s′, s″, s‴ at either end, and
//! is the polynomial of least degree that meets them (MechDesigner's
//! "flexible polynomial"; Norton ch. 3).

use std::f64::consts::TAU;
use std::fmt;

use super::law::{peaks, poly_eval, LawKind, Shape, Shape5};

/// Boundary conditions of a fitted polynomial: `[s′, s″, s‴]` at an end,
/// each optional (m/rad^k or rad/rad^k).
pub type EndConditions = [Option<f64>; 3];

/// One segment of a motion program, as the user gives it.
#[derive(Clone, Debug, PartialEq)]
pub struct SegmentSpec {
    pub law: LawKind,
    /// Span β (rad).
    pub span: f64,
    /// Lift h: the change of s over the segment (m or rad).
    pub lift: f64,
    /// Fitted polynomial: derivatives at the start and end.
    pub start: EndConditions,
    pub end: EndConditions,
}

impl SegmentSpec {
    /// A segment of a named law with no extra conditions.
    pub fn new(law: LawKind, span: f64, lift: f64) -> Self {
        SegmentSpec {
            law,
            span,
            lift,
            start: [None; 3],
            end: [None; 3],
        }
    }
}

/// A segment ready to evaluate.
#[derive(Clone, Debug)]
struct Segment {
    spec: SegmentSpec,
    /// θ₀ (rad) and s₀.
    theta0: f64,
    s0: f64,
    shape: Option<Shape>,
}

/// Why a program is not valid.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MotionError {
    #[error("segment {segment}: {message}")]
    Segment { segment: usize, message: String },
    #[error("the program does not close: {0}")]
    NotClosed(String),
}

/// A motion program over one revolution.
#[derive(Clone, Debug)]
pub struct Program {
    segments: Vec<Segment>,
}

/// How smoothly the motion passes a segment boundary.
#[derive(Clone, Debug, PartialEq)]
pub struct Boundary {
    /// The cam angle θ (rad).
    pub theta: f64,
    /// Segments on either side (indices; the last meets the first at 2π).
    pub before: usize,
    pub after: usize,
    /// Highest continuous derivative: 0 (position) … 3 (jerk).
    pub continuity: usize,
    /// Jumps (after − before) of s′, s″, s‴.
    pub jumps: [f64; 3],
}

impl fmt::Display for Boundary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "C{} at {}°",
            self.continuity,
            crate::fmt_num::num(self.theta.to_degrees())
        )?;
        let names = ["velocity", "acceleration", "jerk"];
        if self.continuity < 3 {
            let k = self.continuity;
            write!(
                f,
                ": {} jumps by {}",
                names[k],
                crate::fmt_num::num(self.jumps[k])
            )?;
            if k + 1 < 3 {
                write!(f, " (infinite {} there)", names[k + 1])?;
            }
        }
        Ok(())
    }
}

/// Peak dimensionless factors of one segment beside its law's textbook
/// values.
#[derive(Clone, Debug, PartialEq)]
pub struct Factors {
    pub segment: usize,
    pub law: LawKind,
    /// max |S′|, |S″|, |S‴| over the segment, S = (s − s₀)/h, u = (θ − θ₀)/β.
    pub computed: [f64; 3],
    pub textbook: Option<[f64; 3]>,
}

/// Relative size under which a jump counts as continuous.
const CONTINUOUS: f64 = 1e-9;

impl Program {
    /// Builds and checks a program: positive finite spans adding up to 2π
    /// (to 1e-9 rad), lifts adding up to zero, dwells with no lift, fitted
    /// polynomials with consistent conditions.
    pub fn new(specs: &[SegmentSpec]) -> Result<Program, MotionError> {
        if specs.is_empty() {
            return Err(MotionError::NotClosed("it has no segments".into()));
        }
        let mut segments = Vec::with_capacity(specs.len());
        let (mut theta, mut s) = (0.0, 0.0);
        let mut scale = 0.0f64;
        for (k, spec) in specs.iter().enumerate() {
            let bad = |m: String| MotionError::Segment {
                segment: k,
                message: m,
            };
            if !(spec.span > 0.0 && spec.span.is_finite()) {
                return Err(bad(format!("span must be positive, got {} rad", spec.span)));
            }
            if !spec.lift.is_finite() {
                return Err(bad(format!("lift must be finite, got {}", spec.lift)));
            }
            if spec.law == LawKind::Dwell && spec.lift != 0.0 {
                return Err(bad(format!("a dwell has no lift, got {}", spec.lift)));
            }
            let shape = if spec.law == LawKind::Polynomial {
                Some(fit(spec).map_err(bad)?)
            } else {
                if spec.start.iter().chain(&spec.end).any(Option::is_some) {
                    return Err(bad(format!(
                        "end conditions belong to a 'polynomial' segment, not '{}'",
                        spec.law.name()
                    )));
                }
                Shape::of(spec.law)
            };
            segments.push(Segment {
                spec: spec.clone(),
                theta0: theta,
                s0: s,
                shape,
            });
            theta += spec.span;
            s += spec.lift;
            scale = scale.max(s.abs()).max(spec.lift.abs());
        }
        if (theta - TAU).abs() > 1e-9 {
            return Err(MotionError::NotClosed(format!(
                "the spans add up to {}° instead of 360°",
                crate::fmt_num::num(theta.to_degrees())
            )));
        }
        if s.abs() > 1e-12 * scale.max(1e-300) {
            return Err(MotionError::NotClosed(format!(
                "the lifts add up to {s} instead of 0 (the follower must return)"
            )));
        }
        Ok(Program { segments })
    }

    /// Number of segments.
    pub fn len(&self) -> usize {
        self.segments.len()
    }

    pub fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }

    /// The segment specs.
    pub fn specs(&self) -> Vec<SegmentSpec> {
        self.segments.iter().map(|s| s.spec.clone()).collect()
    }

    /// Start angle θ₀ (rad) of each segment.
    pub fn starts(&self) -> Vec<f64> {
        self.segments.iter().map(|s| s.theta0).collect()
    }

    /// The segment that holds θ (wrapped into [0, 2π)), by bisection of
    /// the start angles.
    pub fn segment_at(&self, theta: f64) -> usize {
        let th = theta.rem_euclid(TAU);
        self.segments
            .partition_point(|s| s.theta0 <= th)
            .saturating_sub(1)
    }

    /// `[s, s′, s″, s‴, s⁗, s⁽⁵⁾]` at θ (rad, wrapped), from the segment
    /// that holds θ (a boundary belongs to the segment it starts).
    pub fn eval(&self, theta: f64) -> [f64; 6] {
        let k = self.segment_at(theta);
        self.eval_in(k, theta.rem_euclid(TAU))
    }

    /// `[s, s′, …, s⁽⁵⁾]` of segment k's formula at θ (not wrapped).
    pub fn eval_in(&self, k: usize, theta: f64) -> [f64; 6] {
        let seg = &self.segments[k];
        let (beta, h) = (seg.spec.span, seg.spec.lift);
        let d: Shape5 = match &seg.shape {
            Some(shape) => shape.eval((theta - seg.theta0) / beta),
            None => [0.0; 6],
        };
        let mut out = [0.0; 6];
        let mut bk = 1.0;
        for k in 0..6 {
            out[k] = h * d[k] / bk;
            bk *= beta;
        }
        out[0] += seg.s0;
        out
    }

    /// Every boundary, including the closing one at 0 = 2π (listed first).
    pub fn boundaries(&self) -> Vec<Boundary> {
        let n = self.segments.len();
        let mut out = Vec::with_capacity(n);
        // A size for each order, to tell a jump from rounding.
        let size = self.peak_derivatives();
        for after in 0..n {
            let before = (after + n - 1) % n;
            let seg_b = &self.segments[before];
            let l = self.eval_in(before, seg_b.theta0 + seg_b.spec.span);
            let r = self.eval_in(after, self.segments[after].theta0);
            let jumps = [r[1] - l[1], r[2] - l[2], r[3] - l[3]];
            let continuity = (0..3)
                .find(|&k| jumps[k].abs() > CONTINUOUS * size[k].max(1e-300))
                .unwrap_or(3);
            out.push(Boundary {
                theta: self.segments[after].theta0,
                before,
                after,
                continuity,
                jumps,
            });
        }
        out
    }

    /// Largest |s′|, |s″|, |s‴| over the segments (sampled).
    fn peak_derivatives(&self) -> [f64; 3] {
        let mut m = [0.0f64; 3];
        for (k, seg) in self.segments.iter().enumerate() {
            for i in 0..=64 {
                let d = self.eval_in(k, seg.theta0 + seg.spec.span * i as f64 / 64.0);
                for o in 0..3 {
                    m[o] = m[o].max(d[o + 1].abs());
                }
            }
        }
        m
    }

    /// Cv, Ca, Cj of each moving segment beside the textbook values.
    pub fn factors(&self) -> Vec<Factors> {
        self.segments
            .iter()
            .enumerate()
            .filter(|(_, s)| s.spec.lift != 0.0)
            .map(|(k, s)| {
                let shape = s.shape.as_ref().expect("a moving segment has a shape");
                Factors {
                    segment: k,
                    law: s.spec.law,
                    computed: peaks(|u| shape.eval(u), 1000),
                    textbook: s.spec.law.textbook(),
                }
            })
            .collect()
    }
}

/// The normalised polynomial of least degree meeting a segment's
/// conditions: S(0) = 0, S(1) = 1 and S⁽ᵏ⁾ = β^k s⁽ᵏ⁾/h at the ends.
fn fit(spec: &SegmentSpec) -> Result<Shape, String> {
    let (beta, h) = (spec.span, spec.lift);
    if h == 0.0 {
        return Err("a polynomial segment needs a nonzero lift (use a dwell)".into());
    }
    // Rows: (u, order, value).
    let mut rows: Vec<(f64, usize, f64)> = vec![(0.0, 0, 0.0), (1.0, 0, 1.0)];
    for (u, conds) in [(0.0, &spec.start), (1.0, &spec.end)] {
        for (k, c) in conds.iter().enumerate() {
            if let Some(v) = c {
                if !v.is_finite() {
                    return Err(format!("boundary condition {v} is not finite"));
                }
                rows.push((u, k + 1, v * beta.powi(k as i32 + 1) / h));
            }
        }
    }
    let n = rows.len();
    // A[r][i] = d^order/du^order of u^i at u.
    let mut a = vec![vec![0.0; n + 1]; n];
    for (r, &(u, order, value)) in rows.iter().enumerate() {
        for i in 0..n {
            let mut unit = vec![0.0; n];
            unit[i] = 1.0;
            a[r][i] = poly_eval(&unit, u)[order];
        }
        a[r][n] = value;
    }
    let c = solve(a).ok_or("the boundary conditions do not fix a polynomial")?;
    Ok(Shape::Poly(c))
}

/// Gaussian elimination with partial pivoting on an augmented matrix.
fn solve(mut a: Vec<Vec<f64>>) -> Option<Vec<f64>> {
    let n = a.len();
    for col in 0..n {
        let p = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[p][col].abs() < 1e-12 {
            return None;
        }
        a.swap(col, p);
        for r in 0..n {
            if r != col {
                let f = a[r][col] / a[col][col];
                let pivot = a[col].clone();
                for (x, p) in a[r].iter_mut().zip(&pivot).skip(col) {
                    *x -= f * p;
                }
            }
        }
    }
    Some((0..n).map(|i| a[i][n] / a[i][i]).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn deg(d: f64) -> f64 {
        d.to_radians()
    }

    /// Dwell–rise–dwell–return: cycloidal rise of 10 mm over 90°.
    fn drdr(rise: LawKind, ret: LawKind) -> Program {
        Program::new(&[
            SegmentSpec::new(LawKind::Dwell, deg(60.0), 0.0),
            SegmentSpec::new(rise, deg(90.0), 0.01),
            SegmentSpec::new(LawKind::Dwell, deg(60.0), 0.0),
            SegmentSpec::new(ret, deg(150.0), -0.01),
        ])
        .unwrap()
    }

    #[test]
    fn cycloidal_rise_matches_closed_form() {
        let p = drdr(LawKind::Cycloidal, LawKind::Cycloidal);
        let (b, h) = (deg(90.0), 0.01);
        for &th in &[deg(70.0), deg(100.0), deg(140.0)] {
            let x = th - deg(60.0);
            let w = 2.0 * PI / b;
            let want = [
                h * (x / b - (w * x).sin() / (2.0 * PI)),
                h / b * (1.0 - (w * x).cos()),
                h / b * w * (w * x).sin(),
                h / b * w * w * (w * x).cos(),
            ];
            let got = p.eval(th);
            for k in 0..4 {
                assert!(
                    (got[k] - want[k]).abs() < 1e-12 * (1.0 + want[k].abs()),
                    "order {k}"
                );
            }
        }
        assert!((p.eval(deg(200.0))[0] - h).abs() < 1e-15);
        assert!(p.eval(deg(359.0))[0].abs() < 1e-6);
    }

    #[test]
    fn boundaries_are_classified() {
        // Harmonic rise: velocity continuous, acceleration jumps: C1.
        let p = drdr(LawKind::SimpleHarmonic, LawKind::Cycloidal);
        let b = p.boundaries();
        assert_eq!(b.len(), 4);
        assert_eq!(b[1].continuity, 1, "{}", b[1]);
        assert_eq!(b[2].continuity, 1);
        // The harmonic acceleration at the start is (π²/2) h/β².
        let want = PI * PI / 2.0 * 0.01 / deg(90.0).powi(2);
        assert!((b[1].jumps[1] - want).abs() < 1e-12 * want);
        // Cycloidal: acceleration continuous, jerk jumps: C2.
        assert_eq!(b[3].continuity, 2);
        assert_eq!(b[0].continuity, 2);
        assert!(b[1].to_string().contains("infinite jerk"), "{}", b[1]);
        // Constant velocity: C0, velocity jumps by h/β.
        let p = drdr(LawKind::ConstantVelocity, LawKind::Poly4567);
        let b = p.boundaries();
        assert_eq!(b[1].continuity, 0);
        assert!((b[1].jumps[0] - 0.01 / deg(90.0)).abs() < 1e-15);
        // 4-5-6-7 has continuous jerk at its ends: C3.
        assert_eq!(b[3].continuity, 3);
        assert_eq!(b[0].continuity, 3);
    }

    #[test]
    fn program_must_close() {
        let e = Program::new(&[SegmentSpec::new(LawKind::Dwell, 3.0, 0.0)]).unwrap_err();
        assert!(e.to_string().contains("360"), "{e}");
        let e = Program::new(&[
            SegmentSpec::new(LawKind::Cycloidal, PI, 0.01),
            SegmentSpec::new(LawKind::Dwell, PI, 0.0),
        ])
        .unwrap_err();
        assert!(e.to_string().contains("return"), "{e}");
        let e = Program::new(&[SegmentSpec::new(LawKind::Dwell, TAU, 0.1)]).unwrap_err();
        assert!(e.to_string().contains("segment 0"), "{e}");
    }

    /// The fitted polynomial with zero end velocity and acceleration is the
    /// 3-4-5; with zero jerk too, the 4-5-6-7.
    #[test]
    fn fitted_polynomial_reproduces_the_standard_polynomials() {
        let z = Some(0.0);
        for (conds, law) in [
            ([z, z, None], LawKind::Poly345),
            ([z, z, z], LawKind::Poly4567),
        ] {
            let mut fitted = SegmentSpec::new(LawKind::Polynomial, deg(120.0), 0.02);
            fitted.start = conds;
            fitted.end = conds;
            let mut back = SegmentSpec::new(LawKind::Polynomial, deg(240.0), -0.02);
            back.start = conds;
            back.end = conds;
            let a = Program::new(&[fitted, back]).unwrap();
            let b = Program::new(&[
                SegmentSpec::new(law, deg(120.0), 0.02),
                SegmentSpec::new(law, deg(240.0), -0.02),
            ])
            .unwrap();
            for i in 0..50 {
                let th = i as f64 * 0.125;
                let (x, y) = (a.eval(th), b.eval(th));
                for k in 0..5 {
                    assert!(
                        (x[k] - y[k]).abs() < 1e-9 * (1.0 + y[k].abs()),
                        "{law:?} {k}"
                    );
                }
            }
        }
    }

    /// A fitted polynomial meets a nonzero end velocity it was given
    /// (a constant-velocity stretch joined smoothly).
    #[test]
    fn fitted_polynomial_meets_its_conditions() {
        let mut seg = SegmentSpec::new(LawKind::Polynomial, deg(100.0), 0.03);
        seg.start = [Some(0.0), Some(0.0), None];
        seg.end = [Some(0.02), Some(0.0), Some(0.0)];
        let mut back = SegmentSpec::new(LawKind::Polynomial, deg(260.0), -0.03);
        back.start = [Some(0.02), Some(0.0), Some(0.0)];
        back.end = [Some(0.0), Some(0.0), None];
        let p = Program::new(&[seg, back]).unwrap();
        let end = p.eval_in(0, deg(100.0));
        assert!((end[0] - 0.03).abs() < 1e-14);
        assert!((end[1] - 0.02).abs() < 1e-12);
        assert!(end[2].abs() < 1e-10 && end[3].abs() < 1e-9);
        // Both joins are at least C2; the join at 100° also C3.
        let b = p.boundaries();
        assert!(b[1].continuity == 3, "{}", b[1]);
        assert!(b[0].continuity >= 2, "{}", b[0]);
    }

    #[test]
    fn factors_sit_beside_the_textbook() {
        let p = drdr(LawKind::Cycloidal, LawKind::ModifiedSine);
        let f = p.factors();
        assert_eq!(f.len(), 2);
        assert!((f[0].computed[0] - 2.0).abs() < 1e-9);
        assert!((f[0].computed[2] - 4.0 * PI * PI).abs() < 1e-6);
        assert_eq!(f[1].law, LawKind::ModifiedSine);
        assert!((f[1].computed[1] - 5.528).abs() < 1e-3);
    }
}
