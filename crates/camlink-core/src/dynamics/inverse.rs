//! Inverse dynamics of a kinematically driven model (zero degrees of
//! freedom): the forces that make the prescribed motion happen.
//!
//! At each time t_k, kinematic analysis gives q, q̇, q̈
//! ([`crate::kinematics::Solver`]); with as many equations as coordinates
//! Φ_q is square, and the equations of motion give the multipliers from
//!
//! Φ_qᵀ λ = Q(q, q̇, t) − M(q) q̈,
//!
//! one solve with the transposed Jacobian (Haug §6.5). With joint
//! friction Q_f(q, q̇, λ) on the right, λ is found by fixed-point
//! iteration from the frictionless λ ([`super::friction`]), so a driver's
//! effort includes the friction it overcomes. A model with
//! redundant equations (m > n, Φ_q of rank n; kinematics leaves the
//! dependent rows out) has a family of multipliers λ + w, Φ_qᵀw = 0: the
//! one reported is the minimum-norm λ, from
//! [I Φ_qᵀ; Φ_q 0][x; λ] = [Q − M q̈; 0] (x = 0 as Φ_q has full column
//! rank), solved by [`Augmented::solve_refined`]. Joint reactions and
//! driver efforts follow from λ ([`super::reaction`]), and so do the curve
//! contacts' normal forces, whose negative intervals (lift-off) become
//! warnings and `lift_off` records of the run summary
//! ([`super::contact_force`]).

use super::contact_force::LiftOffWatch;

use super::output::{self, Scratch};
use super::project::IDENTITY;
use super::system::{Augmented, System};
use crate::kinematics;
use crate::limits::LimitWatch;
use crate::linsolve::SystemMatrix;
use crate::model::Model;
use crate::run::{self, AnalysisError, Kind, PointOutput, Settings, Sink, Summary};

/// The state and scratch of an inverse-dynamics run; allocated once.
pub struct InverseSolver<'m> {
    pub kin: kinematics::Solver<'m>,
    pub sys: System<'m>,
    /// Φ_qᵀ and its factorization, or the augmented matrix of the
    /// minimum-norm multipliers of a model with redundant equations.
    solve: Multipliers,
    /// λ at the last step (one per equation, in assembly order).
    pub lambda: Vec<f64>,
    /// Q − M q̈ (length n; n + m for the augmented matrix).
    rhs: Vec<f64>,
    /// n zeros: the rates the augmented matrix D = I is filled at.
    zeros: Vec<f64>,
}

/// How λ is found from Φ_qᵀλ = Q − M q̈.
enum Multipliers {
    /// Φ_q square: its transpose, factored.
    Square(Box<SystemMatrix>),
    /// Redundant equations (m > n): the minimum-norm λ.
    MinNorm(Box<Augmented>),
}

impl<'m> InverseSolver<'m> {
    /// Checks that the model is fully driven and lays it out.
    pub fn new(model: &'m Model, settings: Settings) -> Result<Self, AnalysisError> {
        let kin = kinematics::Solver::new(model, settings)?;
        let sys = System::new(model);
        let (n, m) = (sys.n(), sys.m());
        let internal =
            |e: crate::linsolve::SetupError| AnalysisError::new(Kind::Internal, 0.0, e.to_string());
        let solve = if m > n {
            let mut aug = Augmented::new(&sys, &kin.q).map_err(internal)?;
            aug.set_regularised(true);
            Multipliers::MinNorm(Box::new(aug))
        } else {
            let mut pattern = Vec::new();
            sys.asm
                .jacobian(model, &kin.q, 0.0, |r, c, _| pattern.push((c, r)));
            Multipliers::Square(Box::new(
                SystemMatrix::try_new(n, &pattern).map_err(internal)?,
            ))
        };
        Ok(InverseSolver {
            solve,
            lambda: vec![0.0; m],
            rhs: vec![0.0; if m > n { n + m } else { n }],
            zeros: vec![0.0; n],
            kin,
            sys,
        })
    }

    /// Kinematics at `t`, then λ.
    pub fn step(&mut self, t: f64, prev: Option<f64>) -> Result<(), AnalysisError> {
        self.kin.step(t, prev)?;
        let (q, qd, qdd) = (&self.kin.q, &self.kin.qd, &self.kin.qdd);
        // Φ_qᵀ λ = Q − M q̈.
        let n = self.sys.n();
        let f = &mut self.rhs[..n];
        self.sys.forces(q, qd, t, f)?;
        for v in f.iter_mut() {
            *v = -*v;
        }
        self.sys.add_mass_times(q, qdd, f);
        for v in f.iter_mut() {
            *v = -*v;
        }
        let singular = || {
            AnalysisError::new(
                Kind::LockUp,
                t,
                "the constraint Jacobian is singular: reactions are not determined",
            )
        };
        match &mut self.solve {
            Multipliers::Square(jt) => {
                let mut k = 0;
                self.sys.asm.jacobian(self.sys.model, q, t, |r, c, v| {
                    jt.put(k, c, r, v);
                    k += 1;
                });
                if jt.factor().is_err() {
                    return Err(singular());
                }
                self.lambda.copy_from_slice(&self.rhs);
                jt.solve(&mut self.lambda);
                if !self.sys.friction.is_empty() {
                    let mut solve = |f: &mut [f64], out: &mut [f64]| {
                        jt.solve(f);
                        out.copy_from_slice(f);
                    };
                    let lambda = &mut self.lambda;
                    self.sys.friction.inverse(
                        self.sys.model,
                        &self.sys.asm,
                        t,
                        q,
                        qd,
                        &self.rhs,
                        lambda,
                        &mut solve,
                    )?;
                }
            }
            Multipliers::MinNorm(aug) => {
                let zeros = &self.zeros;
                if aug
                    .refactor(&self.sys, q, zeros, zeros, None, t, IDENTITY)
                    .is_err()
                {
                    return Err(singular());
                }
                self.rhs[n..].fill(0.0);
                let base = (!self.sys.friction.is_empty()).then(|| self.rhs.clone());
                aug.solve_refined(&mut self.rhs);
                self.lambda.copy_from_slice(&self.rhs[n..]);
                if let Some(base) = base {
                    let mut solve = |f: &mut [f64], out: &mut [f64]| {
                        aug.solve_refined(f);
                        out.copy_from_slice(&f[n..]);
                    };
                    let lambda = &mut self.lambda;
                    self.sys.friction.inverse(
                        self.sys.model,
                        &self.sys.asm,
                        t,
                        q,
                        qd,
                        &base,
                        lambda,
                        &mut solve,
                    )?;
                }
            }
        }
        if self.lambda.iter().any(|v| !v.is_finite()) {
            return Err(AnalysisError::new(
                Kind::NotFinite,
                t,
                "the Lagrange multipliers are not finite numbers",
            ));
        }
        Ok(())
    }
}

/// Inverse dynamics over `times`: the kinematic channels, then reactions,
/// efforts and energy ([`super::output`]). Rows reach `sink` as each step
/// completes.
pub fn run(
    model: &Model,
    times: &[f64],
    settings: &Settings,
    points: &[PointOutput],
    sink: &mut dyn Sink,
) -> Result<Summary, AnalysisError> {
    let s = InverseSolver::new(model, settings.clone())?;
    let mut names = run::channels(model, points);
    let nk = names.len();
    names.extend(output::channels(model));
    let mut r = InverseRun {
        model,
        points,
        nk,
        lift_off: LiftOffWatch::new(model, &names),
        scratch: Scratch::new(&s.sys),
        limits: LimitWatch::new(model),
        s,
    };
    run::output_loop(&mut r, times, &names, sink)?;
    let mut summary = r.s.kin.summary.clone();
    r.lift_off.report(&mut summary);
    summary.warnings.extend(r.limits.warnings(model));
    Ok(summary)
}

/// An inverse-dynamics run as the output loop drives it.
struct InverseRun<'a, 'm> {
    model: &'m Model,
    points: &'a [PointOutput],
    /// The number of kinematic channels, before the dynamic ones.
    nk: usize,
    lift_off: LiftOffWatch,
    scratch: Scratch,
    limits: LimitWatch,
    s: InverseSolver<'m>,
}

impl run::Analysis for InverseRun<'_, '_> {
    fn reach(
        &mut self,
        t: f64,
        prev: Option<f64>,
        _tick: &mut run::Tick,
    ) -> Result<(), AnalysisError> {
        let s = &mut self.s;
        s.step(t, prev)?;
        self.limits
            .observe(self.model, s.kin.assembly(), &s.kin.q, t);
        Ok(())
    }

    fn fill(&mut self, t: f64, values: &mut [f64]) -> Result<(), AnalysisError> {
        let (s, nk) = (&mut self.s, self.nk);
        s.kin.outputs(self.points, &mut values[..nk]);
        output::fill(
            &s.sys,
            &mut self.scratch,
            &s.kin.q,
            &s.kin.qd,
            &s.lambda,
            t,
            &mut values[nk..],
        );
        Ok(())
    }

    fn observe(&mut self, t: f64, values: &[f64]) {
        self.lift_off.observe(t, values);
    }
}
