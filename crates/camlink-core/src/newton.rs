//! Newton's method: one damped Newton iteration shared by the analyses,
//! and the stopping test at the rounding level.
//!
//! [`solve`] finds x with r(x) = 0 for a [`Problem`] that evaluates the
//! residual r and gives the Newton direction Δx (x + Δx is the full step).
//! How each analysis ends is an explicit [`Options`] field: the cap on the
//! iterations, a backtracking line search on the merit ‖r‖₂ (and what to do
//! when it stalls), a limit on the change of angle coordinates per step,
//! and a last correction applied once the residual has converged. The
//! residual of an accepted trial point is the residual of the next
//! iteration, so a full step costs one residual evaluation whether or not
//! the line search is on. Nothing is allocated: the vectors live in a
//! [`Workspace`] made once.
//!
//! A correction Δx of a value x can be no smaller than the rounding of x
//! itself, about ε_mach |x|: asking for less makes Newton iterate on
//! rounding noise and fail. A value has converged when its last correction
//! is within the tolerance or within [`ULPS`] units of rounding of its
//! value, whichever is larger:
//!
//! |Δx| ≤ max(tol, ULPS · ε_mach · |x|).

/// Units of rounding (ε_mach |x|) a converged correction may keep.
pub(crate) const ULPS: f64 = 8.0;

/// The rounding level of a value `x`: ULPS · ε_mach · |x|.
#[inline]
pub(crate) fn rounding(x: f64) -> f64 {
    ULPS * f64::EPSILON * x.abs()
}

/// True when the correction `dx` of the value `x` is within `tol` or
/// within the rounding level of `x`, whichever is larger.
#[inline]
pub(crate) fn settled(dx: f64, x: f64, tol: f64) -> bool {
    dx.abs() <= tol.max(rounding(x))
}

/// What a residual evaluation reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Measure {
    /// Whether r(x) passes the problem's stopping test.
    pub converged: bool,
    /// The merit the line search decreases, normally ‖r‖₂.
    pub merit: f64,
    /// The size of the residual reported in errors (normally max |r|);
    /// not finite when r is not.
    pub size: f64,
}

impl Measure {
    /// The usual measure of a residual `r`: size max |r|, merit ‖r‖₂,
    /// converged when max |r| ≤ `tol`.
    pub(crate) fn max_abs(r: &[f64], tol: f64) -> Self {
        let size = crate::math::max_abs(r);
        Measure {
            converged: size <= tol,
            merit: crate::math::norm2(r),
            size,
        }
    }
}

/// Where the iteration is when a direction is asked for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Progress {
    /// Iterations done before this one.
    pub iteration: usize,
    /// [`Measure::size`] now and at the previous iterate (∞ at the first).
    pub size: f64,
    pub previous: f64,
}

/// A system of equations r(x) = 0 solved by [`solve`].
pub(crate) trait Problem {
    /// Why a direction could not be found (a singular matrix).
    type Error;
    /// Writes r(x) into `r` and measures it.
    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Measure;
    /// Writes the Newton direction Δx at `x` with residual `r` into `dx`.
    fn direction(
        &mut self,
        x: &[f64],
        r: &[f64],
        dx: &mut [f64],
        progress: Progress,
    ) -> Result<(), Self::Error>;
    /// The last correction applied after convergence ([`Options::polish`]):
    /// writes Δx for the converged residual `r` into `dx` and returns true,
    /// or returns false when it has none to give (the default).
    fn correction(&mut self, r: &[f64], dx: &mut [f64]) -> bool {
        let _ = (r, dx);
        false
    }
}

/// What the line search does when the step falls below its minimum.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Stall {
    /// Stop with [`Failure::NoDescent`].
    Fail,
    /// Take the short step and go on.
    Accept,
}

/// A backtracking line search: a step s (from 1, halved) is accepted when
/// merit(x + s Δx) ≤ (1 − 10⁻⁴ s) merit(x).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LineSearch {
    /// Smallest step s tried.
    pub min_step: f64,
    /// What happens below it.
    pub stall: Stall,
}

/// How [`solve`] iterates and ends.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Options<'a> {
    /// Newton iterations allowed; the residual is tested once more after
    /// the last.
    pub max_iter: usize,
    /// Damping by backtracking; `None` takes full steps.
    pub line_search: Option<LineSearch>,
    /// (largest change in one step, which coordinates it applies to): the
    /// step is scaled so that no flagged coordinate (an angle, rad) moves
    /// more, which keeps the iteration on the branch nearest the start.
    pub angle_limit: Option<(f64, &'a [bool])>,
    /// Once converged, apply [`Problem::correction`] of the converged
    /// residual (one more solve, no residual evaluation).
    pub polish: bool,
}

/// A converged solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Solved {
    /// Newton directions taken.
    pub iterations: usize,
    /// [`Measure::size`] of the converged residual.
    pub size: f64,
}

/// Why [`solve`] stopped without converging.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Failure<E> {
    /// The residual is not a finite number.
    NotFinite,
    /// The line search found no step that decreases the merit.
    NoDescent,
    /// [`Options::max_iter`] iterations did not converge.
    Iterations,
    /// The problem gave no direction.
    Direction(E),
}

/// A failed solve: why, and the residual size at the last accepted x
/// (which `solve` leaves in place).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Failed<E> {
    pub why: Failure<E>,
    pub size: f64,
    pub iterations: usize,
}

/// The vectors of one [`solve`]: residuals at x and at a trial point, the
/// direction and the trial point. Made once per analysis.
#[derive(Clone, Debug, Default)]
pub(crate) struct Workspace {
    r: Vec<f64>,
    r_trial: Vec<f64>,
    dx: Vec<f64>,
    trial: Vec<f64>,
}

impl Workspace {
    /// For `unknowns` values of x and `equations` residuals.
    pub(crate) fn new(unknowns: usize, equations: usize) -> Self {
        Workspace {
            r: vec![0.0; equations],
            r_trial: vec![0.0; equations],
            dx: vec![0.0; unknowns],
            trial: vec![0.0; unknowns],
        }
    }
}

/// Damped Newton on `problem` from `x`, which holds the solution on success
/// and the last accepted iterate on failure.
pub(crate) fn solve<P: Problem>(
    problem: &mut P,
    x: &mut [f64],
    w: &mut Workspace,
    options: &Options,
) -> Result<Solved, Failed<P::Error>> {
    let mut m = problem.residual(x, &mut w.r);
    let mut previous = f64::INFINITY;
    let failed = |why, m: Measure, iterations| Failed {
        why,
        size: m.size,
        iterations,
    };
    for it in 0..=options.max_iter {
        if !(m.size.is_finite() && m.merit.is_finite()) {
            return Err(failed(Failure::NotFinite, m, it));
        }
        if m.converged {
            if options.polish && problem.correction(&w.r, &mut w.dx) {
                for (x, d) in x.iter_mut().zip(&w.dx) {
                    *x += d;
                }
            }
            return Ok(Solved {
                iterations: it,
                size: m.size,
            });
        }
        if it == options.max_iter {
            break;
        }
        let progress = Progress {
            iteration: it,
            size: m.size,
            previous,
        };
        problem
            .direction(x, &w.r, &mut w.dx, progress)
            .map_err(|e| failed(Failure::Direction(e), m, it))?;
        previous = m.size;
        let mut s = match options.angle_limit {
            Some((limit, angles)) => {
                let big =
                    w.dx.iter()
                        .zip(angles)
                        .filter(|(_, &a)| a)
                        .fold(0.0f64, |b, (d, _)| b.max(d.abs()));
                if big > limit {
                    limit / big
                } else {
                    1.0
                }
            }
            None => 1.0,
        };
        let Some(search) = options.line_search else {
            for (x, d) in x.iter_mut().zip(&w.dx) {
                *x += s * d;
            }
            m = problem.residual(x, &mut w.r);
            continue;
        };
        loop {
            for ((t, x), d) in w.trial.iter_mut().zip(x.iter()).zip(&w.dx) {
                *t = x + s * d;
            }
            let trial = problem.residual(&w.trial, &mut w.r_trial);
            let descent = trial.merit <= (1.0 - 1e-4 * s) * m.merit;
            if descent || (search.stall == Stall::Accept && s < search.min_step) {
                m = trial;
                break;
            }
            s *= 0.5;
            if search.stall == Stall::Fail && s < search.min_step {
                return Err(failed(Failure::NoDescent, m, it + 1));
            }
        }
        x.copy_from_slice(&w.trial);
        std::mem::swap(&mut w.r, &mut w.r_trial);
    }
    Err(failed(Failure::Iterations, m, options.max_iter))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_correction_below_tolerance_is_settled() {
        assert!(settled(1e-9, 0.0, 1e-8));
        assert!(!settled(1e-7, 0.0, 1e-8));
    }

    /// A coordinate of 1e3 m cannot be corrected by less than ~1e-13 m:
    /// with tol = 1e-15 a correction of 1e-13 is settled, one of 1e-11 not.
    #[test]
    fn a_correction_at_the_rounding_of_the_value_is_settled() {
        assert!(settled(1e-13, 1e3, 1e-15));
        assert!(!settled(1e-11, 1e3, 1e-15));
        assert!(!settled(1e-13, 1.0, 1e-15));
    }

    /// r(x) = atan(x): full Newton steps from |x| > 1.39 grow without
    /// bound; a line search brings them back.
    struct Atan {
        directions: usize,
    }

    impl Problem for Atan {
        type Error = ();
        fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Measure {
            r[0] = x[0].atan();
            Measure {
                converged: r[0].abs() <= 1e-12,
                merit: r[0].abs(),
                size: r[0].abs(),
            }
        }
        fn direction(
            &mut self,
            x: &[f64],
            r: &[f64],
            dx: &mut [f64],
            _: Progress,
        ) -> Result<(), ()> {
            self.directions += 1;
            dx[0] = -r[0] * (1.0 + x[0] * x[0]);
            Ok(())
        }
    }

    fn options(line_search: Option<LineSearch>) -> Options<'static> {
        Options {
            max_iter: 50,
            line_search,
            angle_limit: None,
            polish: false,
        }
    }

    const SEARCH: LineSearch = LineSearch {
        min_step: 1e-6,
        stall: Stall::Fail,
    };

    #[test]
    fn full_steps_diverge_where_the_line_search_converges() {
        let mut w = Workspace::new(1, 1);
        let mut x = [2.0];
        let full = solve(&mut Atan { directions: 0 }, &mut x, &mut w, &options(None));
        assert!(full.is_err(), "{full:?}");
        let mut x = [2.0];
        let mut p = Atan { directions: 0 };
        let done = solve(&mut p, &mut x, &mut w, &options(Some(SEARCH))).unwrap();
        assert!(x[0].abs() < 1e-12, "{x:?}");
        assert_eq!(done.iterations, p.directions);
        assert!(done.size <= 1e-12);
    }

    /// Near the root the line search takes the full step, so damped and
    /// undamped Newton give the same iterates.
    #[test]
    fn near_the_root_damped_and_full_steps_agree() {
        let mut w = Workspace::new(1, 1);
        let (mut a, mut b) = ([0.5], [0.5]);
        let da = solve(&mut Atan { directions: 0 }, &mut a, &mut w, &options(None)).unwrap();
        let db = solve(
            &mut Atan { directions: 0 },
            &mut b,
            &mut w,
            &options(Some(SEARCH)),
        )
        .unwrap();
        assert_eq!(a, b);
        assert_eq!(da, db);
    }

    /// The angle limit caps each step: from x = 10 with a limit of 0.5 the
    /// first step moves x by exactly 0.5.
    #[test]
    fn the_angle_limit_caps_a_step() {
        let mut w = Workspace::new(1, 1);
        let mut x = [10.0];
        let angles = [true];
        let opts = Options {
            max_iter: 1,
            angle_limit: Some((0.5, &angles)),
            ..options(None)
        };
        let e = solve(&mut Atan { directions: 0 }, &mut x, &mut w, &opts).unwrap_err();
        assert_eq!(e.why, Failure::Iterations);
        assert!((x[0] - 9.5).abs() < 1e-15, "{x:?}");
    }

    /// r(x) = x² + 1 has no root: Newton stalls at x = 0 where the merit
    /// has its minimum. A stall that fails stops there; one that is
    /// accepted runs into the iteration cap.
    struct NoRoot;

    impl Problem for NoRoot {
        type Error = ();
        fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Measure {
            r[0] = x[0] * x[0] + 1.0;
            Measure {
                converged: false,
                merit: r[0],
                size: r[0],
            }
        }
        fn direction(
            &mut self,
            x: &[f64],
            r: &[f64],
            dx: &mut [f64],
            _: Progress,
        ) -> Result<(), ()> {
            if x[0] == 0.0 {
                return Err(());
            }
            dx[0] = -r[0] / (2.0 * x[0]);
            Ok(())
        }
    }

    #[test]
    fn a_stalled_line_search_ends_as_asked() {
        let mut w = Workspace::new(1, 1);
        let mut x = [1e-3];
        let e = solve(&mut NoRoot, &mut x, &mut w, &options(Some(SEARCH))).unwrap_err();
        assert_eq!(e.why, Failure::NoDescent);
        assert_eq!(e.size, x[0] * x[0] + 1.0);
        let accept = LineSearch {
            stall: Stall::Accept,
            ..SEARCH
        };
        let mut x = [1e-3];
        let e = solve(&mut NoRoot, &mut x, &mut w, &options(Some(accept))).unwrap_err();
        assert!(
            matches!(e.why, Failure::Iterations | Failure::Direction(())),
            "{e:?}"
        );
    }

    /// A problem whose residual is not finite stops at once.
    #[test]
    fn a_residual_that_is_not_finite_stops() {
        let mut w = Workspace::new(1, 1);
        let mut x = [f64::INFINITY];
        let e = solve(&mut NoRoot, &mut x, &mut w, &options(Some(SEARCH))).unwrap_err();
        assert_eq!((e.why, e.iterations), (Failure::NotFinite, 0));
    }

    /// r(x) = x − 1 converged loosely (|r| ≤ 0.1), with a correction that
    /// lands on the root: the polish applies it once, without evaluating.
    struct Loose;

    impl Problem for Loose {
        type Error = ();
        fn residual(&mut self, x: &[f64], r: &mut [f64]) -> Measure {
            r[0] = x[0] - 1.0;
            Measure {
                converged: r[0].abs() <= 0.1,
                merit: r[0].abs(),
                size: r[0].abs(),
            }
        }
        fn direction(
            &mut self,
            _: &[f64],
            r: &[f64],
            dx: &mut [f64],
            _: Progress,
        ) -> Result<(), ()> {
            dx[0] = -0.5 * r[0];
            Ok(())
        }
        fn correction(&mut self, r: &[f64], dx: &mut [f64]) -> bool {
            dx[0] = -r[0];
            true
        }
    }

    #[test]
    fn the_polish_applies_the_converged_correction() {
        let mut w = Workspace::new(1, 1);
        let mut x = [1.05];
        solve(&mut Loose, &mut x, &mut w, &options(None)).unwrap();
        assert_eq!(x[0], 1.05);
        let polish = Options {
            polish: true,
            ..options(None)
        };
        let done = solve(&mut Loose, &mut x, &mut w, &polish).unwrap();
        assert_eq!((x[0], done.iterations), (1.0, 0));
    }
}
