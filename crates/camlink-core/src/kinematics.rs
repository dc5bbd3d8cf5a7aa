//! Kinematic analysis of a fully driven model.
//!
//! At each time t_k:
//! 1. predict q from the previous steps: q̈ over the step extrapolated by
//!    the quadratic through the last three accelerations (a line through
//!    two, a constant from one), integrated twice from q and q̇;
//! 2. Newton–Raphson on Φ(q, t_k) = 0, reusing the last factorization of
//!    Φ_q while it keeps converging fast, refreshing it when it does not;
//! 3. factor Φ_q at the solution, solve Φ_q q̇ = ν and Φ_q q̈ = γ;
//! 4. when the jerk is asked for ([`Settings::jerk`]), solve Φ_q q⃛ = η with
//!    the same factorization (η from [`Equations::eta`]).
//!
//! The factorization of step 3 is the one step 2 reuses at the next time,
//! so a smooth run factors the Jacobian once per step.
//!
//! A step whose Newton iterations fail, or whose solution lands far from
//! the prediction (a jump to another assembly branch), is retried as two
//! half steps, down to 1/2^[`MAX_HALVINGS`] of the output step; past that
//! the run stops with an error naming the time, the joints involved, the
//! largest residual and the condition of Φ_q. Near-singular configurations
//! that the mechanism passes through (toggle, dead centre) are reported as
//! warnings.

use crate::assembly::{Assembly, JacobianPlan};
use crate::constraint::{Equations, Local};
use crate::contact::Contacts;
use crate::design::StepGuard;
use crate::diagnose::{levenberg_marquardt, KeptRows, DENSE_MAX};
use crate::fmt_num::num;
use crate::limits::LimitWatch;
use crate::linsolve::{Singular, SystemMatrix};
use crate::math::rot_d;
use crate::model::{BodyId, Model};
use crate::motion;
use crate::newton::{self, Failure};
use crate::run::{
    channels, fill_outputs, jerk_channels, worst_joints, AnalysisError, Kind, PointOutput,
    Settings, Sink, StateView, Summary, Warning,
};

/// Times an output step may be halved when Newton fails or a jump is seen.
pub(crate) const MAX_HALVINGS: u32 = 8;
/// Relative pivot of Φ_q under which a configuration is reported as near
/// singular (a healthy four-bar stays near 0.25; a parallelogram sampled
/// 1 mrad from its change point gives about 1e-4).
pub(crate) const NEAR_SINGULAR: f64 = 1e-3;
/// Largest correction of an angle (rad) from the predicted position that
/// still counts as continuous motion; a larger one is treated as a jump.
pub(crate) const JUMP_ANGLE: f64 = 0.2;

/// What `check` reports about a model.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    pub bodies: usize,
    pub coordinates: usize,
    pub equations: usize,
    /// Coordinates minus equations.
    pub dof: i64,
    /// (name, kind, equations, driver) of each joint.
    pub joints: Vec<(String, String, usize, bool)>,
}

/// The names of the model's coordinates in the order of q: `<body>.x`,
/// `.y`, `.phi` for every moving body, then `<joint>.<own>` for every own
/// coordinate of a joint (the run's channels of the same names).
pub fn coordinate_names(model: &Model) -> Vec<String> {
    let asm = Assembly::new(model);
    (0..asm.n).map(|k| asm.coordinate_name(model, k)).collect()
}

/// Counts bodies, coordinates and equations.
pub fn check(model: &Model) -> Report {
    let asm = Assembly::new(model);
    Report {
        bodies: model.bodies.len() - 1,
        coordinates: asm.n,
        equations: asm.m,
        dof: asm.n as i64 - asm.m as i64,
        joints: model
            .joints
            .iter()
            .map(|j| {
                (
                    j.name.clone(),
                    j.constraint.kind().to_string(),
                    j.constraint.rows(),
                    j.driver,
                )
            })
            .collect(),
    }
}

/// Position, velocity and acceleration analysis over `times`.
///
/// Rows reach `sink` as each step completes, so a run that fails keeps every
/// step before the failure.
/// After each step the curve contacts are checked
/// ([`StepGuard`](crate::design::StepGuard)): a contact that runs off an
/// open curve, or reaches a part of a cam its follower cannot touch, stops
/// the run; a failed step's error names the design findings of its joints.
pub fn run(
    model: &Model,
    times: &[f64],
    settings: &Settings,
    points: &[PointOutput],
    sink: &mut dyn Sink,
) -> Result<Summary, AnalysisError> {
    run_from(model, times, settings, points, sink, None)
}

/// As [`run`], the first time assembled by Newton from `start` instead of
/// the model's placement: q laid out as the model's coordinates
/// ([`coordinate_names`]: every moving body's x, y (m), φ (rad), then the
/// joints' own coordinates). A model re-solved from an earlier solution of
/// the same instant stays on that solution's assembly branch.
pub fn run_from(
    model: &Model,
    times: &[f64],
    settings: &Settings,
    points: &[PointOutput],
    sink: &mut dyn Sink,
    start: Option<&[f64]>,
) -> Result<Summary, AnalysisError> {
    let mut solver = Solver::new(model, settings.clone())?;
    if let Some(q) = start {
        solver.start_from(q)?;
    }
    let mut names = channels(model, points);
    let plain = names.len();
    if settings.jerk {
        names.extend(jerk_channels(model, points));
    }
    let mut run = KinematicRun {
        model,
        points,
        plain,
        jerk: settings.jerk,
        guard: StepGuard::new(model),
        limits: LimitWatch::new(model),
        solver,
    };
    crate::run::output_loop(&mut run, times, &names, sink)?;
    let mut summary = run.solver.summary.clone();
    summary.warnings.extend(run.limits.warnings(model));
    Ok(summary)
}

/// A kinematic run as the output loop drives it: the solver, the check
/// of the curve contacts after each step and the watch on joint limits.
struct KinematicRun<'a, 'm> {
    model: &'m Model,
    points: &'a [PointOutput],
    /// The number of channels before the jerk's.
    plain: usize,
    jerk: bool,
    guard: StepGuard,
    limits: LimitWatch,
    solver: Solver<'m>,
}

impl crate::run::Analysis for KinematicRun<'_, '_> {
    fn reach(
        &mut self,
        t: f64,
        prev: Option<f64>,
        _tick: &mut crate::run::Tick,
    ) -> Result<(), AnalysisError> {
        let (model, solver) = (self.model, &mut self.solver);
        match prev {
            None => solver.step(t, None).map(|_| ()),
            Some(p) => solver.advance(p, t, 0),
        }
        .map_err(|e| self.guard.explain(model, e))?;
        self.guard.check(model, solver.assembly(), &solver.q, t)?;
        self.limits.observe(model, solver.assembly(), &solver.q, t);
        Ok(())
    }

    fn fill(&mut self, t: f64, values: &mut [f64]) -> Result<(), AnalysisError> {
        let (solver, plain) = (&mut self.solver, self.plain);
        solver.outputs(self.points, &mut values[..plain]);
        if self.jerk {
            solver.jerk(t)?;
            solver.jerk_outputs(self.points, &mut values[plain..]);
        }
        Ok(())
    }
}

/// The state and scratch of a kinematic run; allocated once.
pub struct Solver<'m> {
    model: &'m Model,
    asm: Assembly,
    settings: Settings,
    /// Φ_q and its factorization.
    jac: SystemMatrix,
    /// Where each entry of Φ_q goes in `jac`'s storage.
    plan: JacobianPlan,
    /// Each joint's view of the state, gathered once per factorization and
    /// read for Φ_q, ν and γ.
    locals: Vec<Local>,
    pub q: Vec<f64>,
    pub qd: Vec<f64>,
    pub qdd: Vec<f64>,
    /// q⃛, solved by [`jerk`](Self::jerk) only.
    pub qddd: Vec<f64>,
    /// The predicted q of the current step.
    predicted: Vec<f64>,
    /// q̈ of the step before the last, and the time from it to the last
    /// step (s); `None` until two steps are solved.
    qdd_prev: Vec<f64>,
    h_prev: Option<f64>,
    /// q̈ of the step before that, and the time from it to the step after
    /// it (s); `None` until three steps are solved.
    qdd_prev2: Vec<f64>,
    h_prev2: Option<f64>,
    /// The state at the start of a step, to retry it.
    saved: Saved,
    /// True for angle coordinates (bodies' φ, joints' own coordinates).
    angles: Vec<bool>,
    /// A length that sizes the model (m), for the jump test.
    size: f64,
    /// Whether the last factorization was near singular.
    near_singular: bool,
    /// The rows solved for in a model with redundant equations (None: all).
    kept: Option<KeptRows>,
    pub summary: Summary,
    /// Contact points and pressure angles of the curve-contact joints.
    contacts: Contacts,
    /// The vectors of the Newton iterations.
    newton: newton::Workspace,
}

/// The solver's state at the start of a step, to retry it
/// ([`Solver::advance`]): q, q̇, q̈ and the predictor's history (q̈ of the
/// two steps before and their intervals, s).
struct Saved {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    qdd_prev: Vec<f64>,
    h_prev: Option<f64>,
    qdd_prev2: Vec<f64>,
    h_prev2: Option<f64>,
}

impl<'m> Solver<'m> {
    /// Checks the counts and lays out the model.
    pub fn new(model: &'m Model, settings: Settings) -> Result<Self, AnalysisError> {
        let asm = Assembly::new(model);
        let (n, m) = (asm.n, asm.m);
        if n == 0 {
            return Err(fail(Kind::InvalidInput, "the model has no moving bodies"));
        }
        model
            .check_grounded()
            .map_err(|e| fail(Kind::InvalidInput, &e.to_string()))?;
        if m < n {
            return Err(fail(
                Kind::NotDriven,
                &format!(
                    "{n} coordinates but {m} equations: {} degree(s) of freedom are not driven; \
                     add as many drivers (or run a dynamic analysis)",
                    n - m
                ),
            ));
        }
        // Redundant equations are left out of the solve.
        let kept = if m > n {
            Some(
                KeptRows::find(model, &asm, 0.0, settings.tol)
                    .map_err(|e| fail(Kind::Redundant, &e))?,
            )
        } else {
            None
        };
        let mut summary = Summary::default();
        if let Some(k) = &kept {
            summary.warnings.push(k.warning(0.0));
        }
        let q = asm.initial_q(model);
        let mut pattern = Vec::new();
        asm.jacobian(model, &q, 0.0, |r, c, _| {
            if let Some(r) = reduced(kept.as_ref(), r) {
                pattern.push((r, c));
            }
        });
        let jac =
            SystemMatrix::try_new(n, &pattern).map_err(|e| fail(Kind::Internal, &e.to_string()))?;
        let mut k = 0;
        let plan = asm.jacobian_plan(model, |r, c| {
            let r = reduced(kept.as_ref(), r)?;
            k += 1;
            Some(jac.slot(k - 1, r, c))
        });
        Ok(Solver {
            model,
            settings,
            jac,
            plan,
            locals: vec![Local::default(); model.joints.len()],
            qd: vec![0.0; n],
            qdd: vec![0.0; n],
            qddd: vec![0.0; n],
            predicted: vec![0.0; n],
            qdd_prev: vec![0.0; n],
            h_prev: None,
            qdd_prev2: vec![0.0; n],
            h_prev2: None,
            saved: Saved {
                q: vec![0.0; n],
                qd: vec![0.0; n],
                qdd: vec![0.0; n],
                qdd_prev: vec![0.0; n],
                h_prev: None,
                qdd_prev2: vec![0.0; n],
                h_prev2: None,
            },
            angles: asm.angle_mask(model),
            size: model_size(model),
            near_singular: false,
            kept,
            q,
            asm,
            summary,
            contacts: Contacts::new(model),
            newton: newton::Workspace::new(n, n),
        })
    }

    /// Sets q, from which the first [`step`](Self::step) assembles, to
    /// `start` (laid out as [`coordinate_names`]).
    pub(crate) fn start_from(&mut self, start: &[f64]) -> Result<(), AnalysisError> {
        if start.len() != self.q.len() {
            return Err(fail(
                Kind::InvalidInput,
                &format!(
                    "the starting coordinates have {} values, the model has {} coordinates",
                    start.len(),
                    self.q.len()
                ),
            ));
        }
        if let Some(k) = start.iter().position(|v| !v.is_finite()) {
            return Err(fail(
                Kind::InvalidInput,
                &format!(
                    "the starting value of {} is not a finite number",
                    self.asm.coordinate_name(self.model, k)
                ),
            ));
        }
        self.q.copy_from_slice(start);
        Ok(())
    }

    /// Advances from the solved state at `prev` to `t`, halving the step
    /// (up to [`MAX_HALVINGS`] times) where Newton fails or the solution
    /// jumps away from the prediction.
    pub fn advance(&mut self, prev: f64, t: f64, depth: u32) -> Result<(), AnalysisError> {
        let s = &mut self.saved;
        s.q.copy_from_slice(&self.q);
        s.qd.copy_from_slice(&self.qd);
        s.qdd.copy_from_slice(&self.qdd);
        s.qdd_prev.copy_from_slice(&self.qdd_prev);
        s.h_prev = self.h_prev;
        s.qdd_prev2.copy_from_slice(&self.qdd_prev2);
        s.h_prev2 = self.h_prev2;
        let outcome = self.step(t, Some(prev)).and_then(|jump| match jump {
            Some(what) => Err(self.failure(Kind::BranchJump, t, &what)),
            None => Ok(()),
        });
        match outcome {
            Ok(()) => Ok(()),
            Err(e) if depth >= MAX_HALVINGS => Err(e),
            Err(_) => {
                let s = &self.saved;
                self.q.copy_from_slice(&s.q);
                self.qd.copy_from_slice(&s.qd);
                self.qdd.copy_from_slice(&s.qdd);
                self.qdd_prev.copy_from_slice(&s.qdd_prev);
                self.h_prev = s.h_prev;
                self.qdd_prev2.copy_from_slice(&s.qdd_prev2);
                self.h_prev2 = s.h_prev2;
                self.jac.invalidate();
                self.summary.halvings += 1;
                let mid = 0.5 * (prev + t);
                self.advance(prev, mid, depth + 1)?;
                self.advance(mid, t, depth + 1)
            }
        }
    }

    /// Whether small Jacobians are refactored with the pivot order of the
    /// last pivoted factorization ([`crate::lu_program`]; on by default).
    /// Off, every factorization searches for pivots: the general path the
    /// fast one is tested against.
    pub fn set_fixed_pivots(&mut self, on: bool) {
        self.jac.set_fixed_pivots(on);
    }

    /// (replayed, pivoted) factorizations of Φ_q so far, for Jacobians
    /// small enough for the recorded pivot order; None for larger ones.
    pub fn factorization_counts(&self) -> Option<(usize, usize)> {
        self.jac.factorization_counts()
    }

    pub fn assembly(&self) -> &Assembly {
        &self.asm
    }

    /// Solves positions, velocities and accelerations at `t`; `prev` is the
    /// previous time (None for the first step, which assembles from the
    /// model's placement). Returns a description of a jump away from the
    /// predicted position, if there was one.
    pub fn step(&mut self, t: f64, prev: Option<f64>) -> Result<Option<String>, AnalysisError> {
        let mut jump = None;
        if let Some(p) = prev {
            let h = t - p;
            // q̈(τ) = a + b τ + c τ² through the last accelerations (τ ≤ 0 in
            // the past; b = d₁ + c h₁ with d₁ the last divided difference),
            // so q(h) = q + h q̇ + h²/2 a + h³/6 b + h⁴/12 c.
            let (inv1, inv2, inv12, h1) = match (self.h_prev, self.h_prev2) {
                (Some(h1), Some(h2)) => (1.0 / h1, 1.0 / h2, 1.0 / (h1 + h2), h1),
                (Some(h1), None) => (1.0 / h1, 0.0, 0.0, h1),
                _ => (0.0, 0.0, 0.0, 0.0),
            };
            let (w2, w3) = (0.5 * h * h, h * h * h / 6.0);
            let w4 = w3 * h1 + 0.5 * w3 * h;
            for k in 0..self.q.len() {
                let d1 = (self.qdd[k] - self.qdd_prev[k]) * inv1;
                let c = (d1 - (self.qdd_prev[k] - self.qdd_prev2[k]) * inv2) * inv12;
                self.q[k] += h * self.qd[k] + w2 * self.qdd[k] + w3 * d1 + w4 * c;
            }
            self.predicted.copy_from_slice(&self.q);
            self.positions(t)?;
            jump = self.jump_from(t);
        } else {
            self.assemble(t)?;
            self.record_assembly_moves();
        }

        // Velocity and acceleration share one factorization at the solution;
        // ν is evaluated in the same pass over the joints as Φ_q.
        std::mem::swap(&mut self.qdd_prev2, &mut self.qdd_prev);
        self.qdd_prev.copy_from_slice(&self.qdd);
        self.h_prev2 = self.h_prev;
        self.h_prev = prev.map(|p| t - p);
        let (asm, model) = (&self.asm, self.model);
        let mut fit = Fit {
            model,
            asm,
            plan: &self.plan,
            jac: &mut self.jac,
            locals: &mut self.locals,
        };
        match &mut self.kept {
            None => fit.refactor(&self.q, t, Some(&mut self.qd), &mut self.summary),
            Some(k) => {
                k.gather(|f| asm.nu(model, &self.q, t, f), &mut self.qd);
                fit.refactor(&self.q, t, None, &mut self.summary)
            }
        }
        .map_err(|s| self.singular(t, s))?;
        self.jac.solve(&mut self.qd);
        let (asm, model, locals) = (&self.asm, self.model, &mut self.locals);
        match &mut self.kept {
            None => asm.gamma_at(model, locals, &self.qd, &mut self.qdd),
            Some(k) => k.gather(|f| asm.gamma_at(model, locals, &self.qd, f), &mut self.qdd),
        }
        self.jac.solve(&mut self.qdd);
        if self.qdd.iter().any(|v| !v.is_finite()) || self.qd.iter().any(|v| !v.is_finite()) {
            return Err(self.failure(
                Kind::NotFinite,
                t,
                "velocities or accelerations are not finite numbers",
            ));
        }
        self.watch_singularity(t);
        self.summary.steps += 1;
        Ok(jump)
    }

    /// Lists the bodies that assembly moved away from the model's placement.
    fn record_assembly_moves(&mut self) {
        let size = self.size;
        self.summary.assembly_moves = self
            .model
            .moving_bodies()
            .filter_map(|(id, b)| {
                let c = self.asm.body_col(id.0)?;
                let d = [0, 1, 2].map(|k| self.q[c + k] - b.q0[k]);
                let moved = d[0].hypot(d[1]) > 1e-9 * size || d[2].abs() > 1e-9;
                moved.then(|| (b.name.clone(), d))
            })
            .collect();
    }

    /// Compares the solution with the prediction made by `step`.
    fn jump_from(&self, t: f64) -> Option<String> {
        let mut worst: Option<(f64, usize)> = None;
        for k in 0..self.q.len() {
            let d = (self.q[k] - self.predicted[k]).abs();
            let limit = if self.angles[k] {
                JUMP_ANGLE
            } else {
                JUMP_ANGLE * self.size
            };
            if d > limit && worst.is_none_or(|(w, _)| d / limit > w) {
                worst = Some((d / limit, k));
            }
        }
        worst.map(|(_, k)| {
            format!(
                "the solution jumped away from continuous motion ({} moved {} from its \
                 predicted value at t = {} s): the mechanism passed a singular position \
                 or changed assembly branch; a smaller step or a different driver may help",
                self.asm.coordinate_name(self.model, k),
                num(self.q[k] - self.predicted[k]),
                num(t),
            )
        })
    }

    /// Records a warning when Φ_q becomes, or stops being, near singular.
    fn watch_singularity(&mut self, t: f64) {
        let Some(pivot) = self.jac.min_pivot() else {
            return;
        };
        let near = pivot < NEAR_SINGULAR;
        if near && !self.near_singular {
            let joints = crate::diagnose::weakest_joints(self.model, &self.asm, &self.q, t);
            self.summary.warnings.push(Warning {
                kind: Kind::NearSingular,
                time: t,
                message: format!(
                    "near-singular configuration (relative pivot {}, \
                     condition about {}){}: a toggle or dead-centre position; \
                     accuracy of velocities and accelerations may suffer here",
                    num(pivot),
                    num(1.0 / pivot),
                    crate::diagnose::losing_rank(&joints)
                ),
                joints,
            });
        }
        self.near_singular = near;
    }

    /// Assembles the mechanism at `t` from the model's rough placement:
    /// damped Newton ([`newton::solve`]) with a backtracking line search on
    /// ‖Φ‖₂, with angle steps limited to [`MAX_ANGLE_STEP`] so that it stays
    /// on the branch nearest the guess, and Levenberg–Marquardt steps where
    /// Φ_q is singular (for models of at most [`DENSE_MAX`] coordinates; a
    /// larger one stops with the singular joint named).
    pub fn assemble(&mut self, t: f64) -> Result<(), AnalysisError> {
        self.solve_positions(t, true).map_err(|e| match e.why {
            Failure::NotFinite => self.failure(
                Kind::NotFinite,
                t,
                "the constraint equations are not finite numbers",
            ),
            Failure::NoDescent => self.failure(
                Kind::NotAssembled,
                t,
                "the mechanism cannot be assembled from the given placement: \
                 no step reduces the constraint residual (check the joints \
                 named here, or place the bodies closer to a valid configuration)",
            ),
            Failure::Iterations => self.failure(
                Kind::NotAssembled,
                t,
                &format!("the mechanism did not assemble in {ASSEMBLY_ITER} iterations"),
            ),
            Failure::Direction(s) => self.singular(t, s),
        })
    }

    /// Newton–Raphson on Φ(q, t) = 0 from the predicted q ([`newton::solve`]
    /// with full steps), reusing the last factorization of Φ_q while the
    /// residual falls fast and refreshing it when it does not. Once
    /// max |Φ| ≤ tol, the correction that residual gives is applied too, so
    /// positions are accurate well beyond what the residual test alone
    /// guarantees.
    fn positions(&mut self, t: f64) -> Result<(), AnalysisError> {
        self.solve_positions(t, false).map_err(|e| match e.why {
            Failure::NotFinite => self.failure(
                Kind::NotFinite,
                t,
                "the constraint equations are not finite numbers",
            ),
            Failure::Iterations | Failure::NoDescent => self.failure(
                Kind::NotConverged,
                t,
                &format!(
                    "positions did not converge in {} Newton iterations: the drivers may ask \
                     for a position the mechanism cannot reach (past a limit or dead-centre \
                     position)",
                    self.settings.max_iter
                ),
            ),
            Failure::Direction(s) => self.singular(t, s),
        })
    }

    /// [`newton::solve`] on Φ(q, t) = 0 from the current q ([`Positions`]):
    /// for assembly, up to [`ASSEMBLY_ITER`] iterations with a line search
    /// that fails where it stalls and angle steps limited to
    /// [`MAX_ANGLE_STEP`]; for a time step, up to `max_iter` full steps and
    /// the converged correction.
    fn solve_positions(
        &mut self,
        t: f64,
        assembling: bool,
    ) -> Result<(), newton::Failed<Singular>> {
        let options = if assembling {
            newton::Options {
                max_iter: ASSEMBLY_ITER,
                line_search: Some(newton::LineSearch {
                    min_step: 1e-6,
                    stall: newton::Stall::Fail,
                }),
                angle_limit: Some((MAX_ANGLE_STEP, &self.angles)),
                polish: false,
            }
        } else {
            newton::Options {
                max_iter: self.settings.max_iter,
                line_search: None,
                angle_limit: None,
                polish: true,
            }
        };
        let mut problem = Positions {
            fit: Fit {
                model: self.model,
                asm: &self.asm,
                plan: &self.plan,
                jac: &mut self.jac,
                locals: &mut self.locals,
            },
            kept: self.kept.as_mut(),
            summary: &mut self.summary,
            t,
            tol: self.settings.tol,
            assembling,
        };
        newton::solve(&mut problem, &mut self.q, &mut self.newton, &options).map(|_| ())
    }

    fn singular(&self, t: f64, s: Singular) -> AnalysisError {
        let row = self.kept.as_ref().map_or(s.row, |k| k.full_row(s.row));
        let (j, _) = self.asm.joint_of_row(row);
        let mut e = self.failure(
            Kind::LockUp,
            t,
            &format!(
                "the constraint Jacobian is singular (relative pivot {}): \
                 the mechanism is locked, at a singular configuration, or over-constrained",
                num(s.pivot)
            ),
        );
        let name = self.model.joints[j].name.clone();
        if !e.joints.contains(&name) {
            e.joints.insert(0, name);
        }
        e
    }

    /// An error at `t` naming the joints with the largest residuals.
    fn failure(&self, kind: Kind, t: f64, what: &str) -> AnalysisError {
        let mut phi = vec![0.0; self.asm.m];
        self.asm.phi(self.model, &self.q, t, &mut phi);
        let (joints, residual) = worst_joints(self.model, &self.asm, &phi, self.settings.tol);
        let mut message = what.to_string();
        // A function of time or of a curve parameter that cannot be evaluated.
        for (j, joint) in self.model.joints.iter().enumerate() {
            let x = self.asm.local(self.model, j, &self.q, &[], t);
            if let Err(e) = joint.constraint.check_functions(&x) {
                message.push_str(&format!("; in '{}': {e}", joint.name));
                break;
            }
        }
        if !joints.is_empty() {
            message.push_str(&format!(
                "; largest residual {} in {}",
                num(residual),
                joints
                    .iter()
                    .map(|j| format!("'{j}'"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        if self.asm.n <= DIAGNOSE_MAX && residual.is_finite() {
            let j = crate::diagnose::dense_jacobian(self.model, &self.asm, &self.q, t);
            if let Ok(s) = j.singular_values() {
                let (hi, lo) = (
                    s.first().copied().unwrap_or(0.0),
                    s.last().copied().unwrap_or(0.0),
                );
                message.push_str(&format!("; condition of Φ_q {}", num(hi / lo)));
            }
        }
        AnalysisError::new(kind, t, message).at_joints(joints, residual)
    }

    /// Fills the output channels for the current state.
    pub fn outputs(&self, points: &[PointOutput], out: &mut [f64]) {
        fill_outputs(
            self.model,
            &self.asm,
            &self.contacts,
            StateView {
                q: &self.q,
                qd: &self.qd,
                qdd: &self.qdd,
            },
            points,
            out,
        );
    }

    /// Solves Φ_q q⃛ = η at the solved state of time `t`, with the
    /// factorization of its acceleration step.
    pub fn jerk(&mut self, t: f64) -> Result<(), AnalysisError> {
        let (asm, model) = (&self.asm, self.model);
        let (q, qd, qdd) = (&self.q, &self.qd, &self.qdd);
        match &mut self.kept {
            None => asm.eta(model, q, qd, qdd, t, &mut self.qddd),
            Some(k) => k.gather(|f| asm.eta(model, q, qd, qdd, t, f), &mut self.qddd),
        }
        self.jac.solve(&mut self.qddd);
        if self.qddd.iter().any(|v| !v.is_finite()) {
            return Err(self.failure(Kind::NotFinite, t, "jerks are not finite numbers"));
        }
        Ok(())
    }

    /// Fills the channels of [`jerk_channels`] from the solved jerk.
    pub(crate) fn jerk_outputs(&self, points: &[PointOutput], out: &mut [f64]) {
        let body = |v: &[f64], id: BodyId| -> [f64; 3] {
            match self.asm.body_col(id.0) {
                Some(c) => [v[c], v[c + 1], v[c + 2]],
                None => [0.0; 3],
            }
        };
        let mut k = 0;
        for (id, _) in self.model.moving_bodies() {
            out[k..k + 3].copy_from_slice(&body(&self.qddd, id));
            k += 3;
        }
        for p in points {
            let [q, qd, qdd, qddd] =
                [&self.q, &self.qd, &self.qdd, &self.qddd].map(|v| body(v, p.body));
            // r⃛^P = r⃛ + B s' φ⃛ + (the terms without jerk).
            let rest = motion::body_point(q, qd, qdd, p.s)[3];
            let b = rot_d(q[2], p.s);
            out[k] = qddd[0] + b[0] * qddd[2] + rest[0];
            out[k + 1] = qddd[1] + b[1] * qddd[2] + rest[1];
            k += 2;
        }
    }

    /// (q, q̇, q̈) of one body; zeros for the ground.
    pub fn body_state(&self, body: BodyId) -> ([f64; 3], [f64; 3], [f64; 3]) {
        match self.asm.body_col(body.0) {
            Some(c) => (
                [self.q[c], self.q[c + 1], self.q[c + 2]],
                [self.qd[c], self.qd[c + 1], self.qd[c + 2]],
                [self.qdd[c], self.qdd[c + 1], self.qdd[c + 2]],
            ),
            None => ([0.0; 3], [0.0; 3], [0.0; 3]),
        }
    }
}

/// Φ_q written into a matrix by a plan, and its factorization.
struct Fit<'a> {
    model: &'a Model,
    asm: &'a Assembly,
    /// Where each entry of Φ_q (only the rows kept, when redundant
    /// equations are left out) goes in `jac`.
    plan: &'a JacobianPlan,
    jac: &'a mut SystemMatrix,
    locals: &'a mut [Local],
}

impl Fit<'_> {
    /// Gathers the joints' views at (q, t), fills Φ_q into `jac` and
    /// factors it; with `nu`, writes ν(q, t) there in the same pass over
    /// the joints (all rows: only without kept rows).
    fn refactor(
        &mut self,
        q: &[f64],
        t: f64,
        nu: Option<&mut [f64]>,
        summary: &mut Summary,
    ) -> Result<(), Singular> {
        self.asm.gather(self.model, q, t, self.locals);
        self.asm.fill_jacobian(
            self.model,
            self.plan,
            self.locals,
            self.jac.values_mut(),
            nu,
        );
        summary.factorizations += 1;
        self.jac.factor()
    }
}

/// Φ(q, t) = 0 as a [`newton::Problem`], in q: a time step's chord
/// iteration, or assembly from a placement.
struct Positions<'a> {
    /// Φ_q and its factorization.
    fit: Fit<'a>,
    /// The rows solved for when redundant equations are left out.
    kept: Option<&'a mut KeptRows>,
    summary: &'a mut Summary,
    t: f64,
    /// Converged when max |Φ| ≤ tol (m or rad).
    tol: f64,
    /// Assembly factors Φ_q at every iterate and takes a Levenberg–Marquardt
    /// step where it is singular; a time step reuses the factorization while
    /// the residual falls to a quarter per iteration.
    assembling: bool,
}

impl newton::Problem for Positions<'_> {
    type Error = Singular;

    fn residual(&mut self, q: &[f64], phi: &mut [f64]) -> newton::Measure {
        let (asm, model, t) = (self.fit.asm, self.fit.model, self.t);
        match &mut self.kept {
            None => asm.phi(model, q, t, phi),
            Some(k) => k.gather(|f| asm.phi(model, q, t, f), phi),
        }
        newton::Measure::max_abs(phi, self.tol)
    }

    fn direction(
        &mut self,
        q: &[f64],
        phi: &[f64],
        dq: &mut [f64],
        progress: newton::Progress,
    ) -> Result<(), Singular> {
        dq.copy_from_slice(phi);
        if self.assembling {
            match self.fit.refactor(q, self.t, None, self.summary) {
                Ok(()) => self.fit.jac.solve(dq),
                // Levenberg–Marquardt is dense: up to the diagnosis' size only.
                Err(e) if self.fit.asm.n > DENSE_MAX => return Err(e),
                Err(_) => levenberg_marquardt(&self.fit.jac.to_dense(), phi, 1e-6, dq),
            }
        } else {
            if !self.fit.jac.is_valid() || progress.size > 0.25 * progress.previous {
                self.fit.refactor(q, self.t, None, self.summary)?;
            }
            self.fit.jac.solve(dq);
        }
        self.summary.newton_iterations += 1;
        for d in dq.iter_mut() {
            *d = -*d;
        }
        Ok(())
    }

    fn correction(&mut self, phi: &[f64], dq: &mut [f64]) -> bool {
        if !self.fit.jac.is_valid() {
            return false;
        }
        dq.copy_from_slice(phi);
        self.fit.jac.solve(dq);
        for d in dq.iter_mut() {
            *d = -*d;
        }
        true
    }
}

/// Largest model (coordinates) whose Jacobian condition is computed for an
/// error message.
const DIAGNOSE_MAX: usize = 600;

/// The row of the solve that equation `r` fills: `r` itself, or its
/// reduced index when redundant equations are left out (None: left out).
#[inline]
fn reduced(kept: Option<&KeptRows>, r: usize) -> Option<usize> {
    match kept {
        None => Some(r),
        Some(k) => k.reduced(r),
    }
}

/// A length that sizes the model: the largest distance of a body or point
/// from the origin (m), at least 1 mm.
fn model_size(model: &Model) -> f64 {
    let mut size = 1e-3f64;
    for b in &model.bodies {
        size = size.max(b.q0[0].hypot(b.q0[1]));
        for p in &b.points {
            size = size.max(p.s[0].hypot(p.s[1]));
        }
    }
    size
}

/// Iterations allowed to assemble from the model's placement.
const ASSEMBLY_ITER: usize = 100;
/// Largest change of an angle (rad) in one assembly iteration.
pub(crate) const MAX_ANGLE_STEP: f64 = 0.5;

/// An error before the first step (t = 0).
fn fail(kind: Kind, message: &str) -> AnalysisError {
    AnalysisError::new(kind, 0.0, message)
}
