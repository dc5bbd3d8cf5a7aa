//! Equilibrium (static) analysis: the configuration where applied forces,
//! springs and gravity balance, and the reactions there.
//!
//! With q̇ = q̈ = 0 the equations of motion reduce to
//!
//! Φ_qᵀ λ − Q(q, 0, t) = 0,  Φ(q, t) = 0,
//!
//! n + m equations in (q, λ), solved by Newton's method with the matrix
//!
//! [ (Φ_qᵀλ)_q − Q_q   Φ_qᵀ ; Φ_q  0 ].
//!
//! The curvature term (Φ_qᵀλ)_q is what makes a pendulum hang (with its
//! frame at the centroid, gravity alone has no stiffness in φ); it is
//! formed joint by joint by central differences of the analytic Jacobian
//! blocks. Start: q projected onto the constraints, λ the least-squares
//! multipliers min ‖Φ_qᵀλ − Q‖. Steps are limited in angle and
//! backtracked on ‖residual‖₂, so the solver goes to an equilibrium near the
//! starting placement; it may be unstable (an inverted pendulum is in
//! equilibrium too). Drivers hold their coordinates at f(t) and report the
//! effort that does it.

use super::output::{self, Scratch};
use super::project;
use super::redundant::Redundant;
use super::system::{Augmented, Coefficients, System};
use crate::kinematics::MAX_ANGLE_STEP;
use crate::math::{max_abs, norm2};
use crate::model::Model;
use crate::newton::{self, Failure};
use crate::run::{self, AnalysisError, Kind, PointOutput, Sink, Summary};

/// Equilibrium solver settings.
#[derive(Clone, Debug)]
pub struct Settings {
    /// Stop when max |Φ| ≤ tol (m or rad) and max |Φ_qᵀλ − Q| ≤ tol·(1 + max |Q|).
    pub tol: f64,
    pub max_iter: usize,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            tol: 1e-10,
            max_iter: 100,
        }
    }
}

/// An equilibrium: coordinates, multipliers and the Newton iterations used.
#[derive(Clone, Debug, PartialEq)]
pub struct Equilibrium {
    pub q: Vec<f64>,
    pub lambda: Vec<f64>,
    pub iterations: usize,
}

/// The equilibrium at time `t` (drivers at f(t)) nearest the model's placement.
pub fn solve(model: &Model, t: f64, settings: &Settings) -> Result<Equilibrium, AnalysisError> {
    solve_watching(model, t, settings, &mut || Ok(()))
}

/// [`solve`], calling `tick` before every Newton iteration; an error from
/// `tick` (an interrupt) stops the search.
pub fn solve_watching(
    model: &Model,
    t: f64,
    settings: &Settings,
    tick: &mut dyn FnMut() -> Result<(), AnalysisError>,
) -> Result<Equilibrium, AnalysisError> {
    let s = System::new(model);
    let (n, m) = (s.n(), s.m());
    let err = |kind: Kind, message: String, residual: f64| {
        AnalysisError::new(kind, t, message).at_joints(Vec::new(), residual)
    };
    if n == 0 {
        return Err(err(
            Kind::InvalidInput,
            "the model has no moving bodies".into(),
            0.0,
        ));
    }
    let mut q = s.asm.initial_q(model);
    let mut aug = Augmented::new(&s, &q).map_err(|e| err(Kind::Internal, e.to_string(), 0.0))?;
    if Redundant::detect(&s, &mut aug, &q, t).is_some() {
        aug.set_regularised(true);
    }
    project::positions(&s, &mut aug, &mut q, t, settings.tol, settings.max_iter)
        .map_err(|e| err(e.kind, e.message, e.residual))?;
    let zeros = vec![0.0; n];
    let mut qf = vec![0.0; n];
    // Least-squares multipliers: [I Φ_qᵀ; Φ_q 0][x; λ] = [Q; 0].
    let mut rhs = vec![0.0; n + m];
    s.forces(&q, &zeros, t, &mut qf)?;
    rhs[..n].copy_from_slice(&qf);
    let least_squares = Coefficients {
        identity: 1.0,
        scale: 1.0,
        ..Default::default()
    };
    aug.refactor(&s, &q, &zeros, &zeros, None, t, least_squares)
        .map_err(|_| {
            err(
                Kind::Redundant,
                "the constraint Jacobian is rank deficient".into(),
                0.0,
            )
        })?;
    aug.solve_refined(&mut rhs);
    let mut lambda = rhs[n..].to_vec();

    let angles = s.asm.angle_mask(model);
    // Newton in x = (q, λ), damped by a line search that takes a short
    // step rather than stop where the residual does not fall.
    let mut x = [q.as_slice(), lambda.as_slice()].concat();
    let mut balance = Balance {
        s: &s,
        aug: &mut aug,
        t,
        tol: settings.tol,
        zeros: &zeros,
        qf,
        force_residual: 0.0,
        tick,
        failure: None,
    };
    let options = newton::Options {
        max_iter: settings.max_iter,
        line_search: Some(newton::LineSearch {
            min_step: 1e-3,
            stall: newton::Stall::Accept,
        }),
        angle_limit: Some((MAX_ANGLE_STEP, &angles)),
        polish: false,
    };
    let mut work = newton::Workspace::new(n + m, n + m);
    let neutral = |rp: f64| {
        err(
            Kind::LockUp,
            "the equilibrium equations are singular: a degree of freedom is neither \
             restrained by a spring or gravity nor driven (neutral equilibrium)"
                .into(),
            rp,
        )
    };
    let solved = match newton::solve(&mut balance, &mut x, &mut work, &options) {
        Ok(solved) => solved,
        Err(e) => {
            if let Some(failure) = balance.failure.take() {
                return Err(failure);
            }
            return Err(match e.why {
                Failure::NotFinite => err(
                    Kind::NotFinite,
                    "the equations are not finite numbers".into(),
                    e.size,
                ),
                Failure::Iterations | Failure::NoDescent => err(
                    Kind::NotConverged,
                    format!(
                        "no equilibrium found in {} iterations (force residual {}, relative)",
                        settings.max_iter,
                        crate::fmt_num::num(balance.force_residual)
                    ),
                    e.size,
                ),
                Failure::Direction(()) => neutral(e.size),
            });
        }
    };
    // A force that failed at a trial point of the line search is an error
    // even where the search went on from elsewhere.
    if let Some(failure) = balance.failure.take() {
        return Err(failure);
    }
    let rp = solved.size;
    q.copy_from_slice(&x[..n]);
    lambda.copy_from_slice(&x[n..]);
    // A balance is an equilibrium only where the tangent stiffness holds
    // every free motion (a free motion with no force on it balances
    // everywhere).
    aug.refactor(&s, &q, &zeros, &zeros, Some(&lambda), t, TANGENT)
        .map_err(|_| neutral(rp))?;
    // The multipliers of minimum norm with the same forces Φ_qᵀλ (they
    // differ from λ only with redundant equations):
    // [I Φ_qᵀ; Φ_q 0][x; μ] = [Φ_qᵀλ; 0].
    aug.refactor(&s, &q, &zeros, &zeros, None, t, least_squares)
        .map_err(|_| {
            err(
                Kind::Redundant,
                "the constraint Jacobian is rank deficient".into(),
                rp,
            )
        })?;
    let mut res = vec![0.0; n + m];
    s.add_jt_lambda(&q, t, &lambda, &mut res[..n]);
    aug.solve_refined(&mut res);
    lambda.copy_from_slice(&res[n..]);
    Ok(Equilibrium {
        q,
        lambda,
        iterations: solved.iterations,
    })
}

/// The Newton matrix of equilibrium, [ (Φ_qᵀλ)_q − Q_q  Φ_qᵀ ; Φ_q  0 ].
const TANGENT: Coefficients = Coefficients {
    mass: 0.0,
    damping: 0.0,
    stiffness: 1.0,
    identity: 0.0,
    scale: 1.0,
};

/// The equilibrium equations Φ_qᵀλ − Q(q, 0, t) = 0, Φ(q, t) = 0 as a
/// [`newton::Problem`] in x = (q, λ), converged when the force residual
/// relative to 1 + max |Q| and max |Φ| are both ≤ tol.
struct Balance<'a> {
    s: &'a System<'a>,
    aug: &'a mut Augmented,
    t: f64,
    tol: f64,
    /// Zero velocities and accelerations (length n).
    zeros: &'a [f64],
    /// Q at the last residual's q.
    qf: Vec<f64>,
    /// The relative force residual at the last residual's x.
    force_residual: f64,
    /// Called before every Newton direction; an error (an interrupt) stops
    /// the search.
    tick: &'a mut dyn FnMut() -> Result<(), AnalysisError>,
    /// The error that stopped the search from inside the problem (a force
    /// that failed, an interrupt), returned in place of Newton's failure.
    failure: Option<AnalysisError>,
}

impl newton::Problem for Balance<'_> {
    type Error = ();

    fn residual(&mut self, x: &[f64], r: &mut [f64]) -> newton::Measure {
        let (s, zeros, n) = (self.s, self.zeros, self.zeros.len());
        let (q, lambda) = x.split_at(n);
        let evaluated = s
            .residual(q, zeros, zeros, lambda, self.t, &mut r[..n])
            .and_then(|_| s.forces(q, zeros, self.t, &mut self.qf));
        if let Err(e) = evaluated {
            // A NaN merit ends the search; `solve` returns this error.
            self.failure.get_or_insert(e);
            return newton::Measure {
                converged: false,
                merit: f64::NAN,
                size: f64::NAN,
            };
        }
        s.asm.phi(s.model, q, self.t, &mut r[n..]);
        self.force_residual = max_abs(&r[..n]) / (1.0 + max_abs(&self.qf));
        let rp = max_abs(&r[n..]);
        newton::Measure {
            converged: self.force_residual <= self.tol && rp <= self.tol,
            merit: if self.force_residual.is_finite() {
                norm2(r)
            } else {
                f64::NAN
            },
            size: rp,
        }
    }

    /// The Newton step of [ (Φ_qᵀλ)_q − Q_q  Φ_qᵀ ; Φ_q  0 ]; where the
    /// tangent stiffness is singular away from a balance (a pendulum lying
    /// horizontal), a regularised step K + μI leads on.
    fn direction(
        &mut self,
        x: &[f64],
        r: &[f64],
        dx: &mut [f64],
        _: newton::Progress,
    ) -> Result<(), ()> {
        if let Err(e) = (self.tick)() {
            self.failure = Some(e);
            return Err(());
        }
        let (s, zeros, n, t) = (self.s, self.zeros, self.zeros.len(), self.t);
        let (q, lambda) = x.split_at(n);
        if self
            .aug
            .refactor(s, q, zeros, zeros, Some(lambda), t, TANGENT)
            .is_err()
        {
            let regularised = Coefficients {
                identity: 1e-3 * (1.0 + max_abs(&self.qf)),
                ..TANGENT
            };
            self.aug
                .refactor(s, q, zeros, zeros, Some(lambda), t, regularised)
                .map_err(|_| ())?;
        }
        for (d, r) in dx.iter_mut().zip(r) {
            *d = -r;
        }
        self.aug.solve(dx);
        Ok(())
    }
}

/// Equilibrium at `t`, written as one row: the kinematic channels (zero
/// velocities and accelerations), then reactions, efforts and energy.
pub fn run(
    model: &Model,
    t: f64,
    settings: &Settings,
    points: &[PointOutput],
    sink: &mut dyn Sink,
) -> Result<Summary, AnalysisError> {
    let e = solve_watching(model, t, settings, &mut || sink.tick().map_err(|s| s.at(t)))?;
    let s = System::new(model);
    let contacts = crate::contact::Contacts::new(model);
    let mut names = run::channels(model, points);
    let nk = names.len();
    names.extend(output::channels(model));
    sink.begin(&names);
    let mut values = vec![0.0; names.len()];
    let zeros = vec![0.0; s.n()];
    run::fill_outputs(
        model,
        &s.asm,
        &contacts,
        run::StateView {
            q: &e.q,
            qd: &zeros,
            qdd: &zeros,
        },
        points,
        &mut values[..nk],
    );
    let mut scratch = Scratch::new(&s);
    output::fill(
        &s,
        &mut scratch,
        &e.q,
        &zeros,
        &e.lambda,
        t,
        &mut values[nk..],
    );
    sink.row(t, &values).map_err(|s| s.at(t))?;
    let mut aug = Augmented::new(&s, &e.q).map_err(|e| AnalysisError {
        kind: Kind::Internal,
        time: t,
        message: e.to_string(),
        joints: Vec::new(),
        residual: 0.0,
    })?;
    let warnings = Redundant::detect(&s, &mut aug, &e.q, t)
        .map(|r| vec![r.warning(t)])
        .unwrap_or_default();
    Ok(Summary {
        steps: 1,
        newton_iterations: e.iterations,
        factorizations: e.iterations,
        warnings,
        ..Summary::default()
    })
}
