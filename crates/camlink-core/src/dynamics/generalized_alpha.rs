//! Forward dynamics: the implicit index-3 generalized-α method
//! (Chung & Hulbert 1993; Arnold & Brüls 2007) with Newton's method on the
//! discretised equations.
//!
//! The equations M(q) q̈ + Φ_qᵀλ = Q(q, q̇, t), Φ(q, t) = 0 are enforced at
//! every t_{n+1} = t_n + h. The pseudo-acceleration a carries the numerical
//! damping:
//!
//! (1 − α_m) a_{n+1} + α_m a_n = (1 − α_f) q̈_{n+1} + α_f q̈_n,
//! q_{n+1} = q_n + h q̇_n + h² (½ − β) a_n + h² β a_{n+1},
//! q̇_{n+1} = q̇_n + h (1 − γ) a_n + h γ a_{n+1},
//!
//! with, for a spectral radius at infinity ρ∞ ∈ [0, 1] (1: no numerical
//! damping, 0: the most), α_m = (2ρ∞ − 1)/(ρ∞ + 1), α_f = ρ∞/(ρ∞ + 1),
//! γ = ½ + α_f − α_m, β = ¼ (γ + ½)². Second-order accurate in q and q̇.
//!
//! Newton unknowns are q̈_{n+1} and λ_{n+1}; a change Δq of positions goes
//! with Δq̇ = γ' Δq and Δq̈ = β' Δq, β' = (1 − α_m)/(β h² (1 − α_f)),
//! γ' = γ/(β h). The iteration matrix is the augmented matrix
//!
//! [ s (β' M + γ' ∂R/∂q̇ + ∂R/∂q)  Φ_qᵀ ; Φ_q  0 ],  s = 1/β',
//!
//! whose first block row is the equations of motion scaled by s (so that
//! both block rows are O(1) for small h, Bottasso et al. 2007) and whose
//! unknowns are (Δq, s Δλ). ∂R/∂q includes the constraint curvature
//! (Φ_qᵀλ)_q and the derivatives of gravity, springs and dampers, so stiff
//! springs converge. The factorization is kept from step to step and
//! refreshed only when Newton converges slowly (chord iterations).
//!
//! Where Φ_q loses rank S is singular and S_ε, the regularised matrix of
//! the augmented Lagrangian formulation, is factored instead
//! ([`super::system::Augmented`]). Within a small window around a
//! bifurcation point, where two branches of Φ = 0 cross (the flat position
//! of a parallelogram), the lost equations are joined by branch rows that
//! hold the branch being followed ([`super::branch`]).
//!
//! Initial conditions are made consistent: positions and velocities
//! projected onto Φ = 0 and Φ_q q̇ = ν ([`super::project`]), then q̈₀ and λ₀
//! from [M Φ_qᵀ; Φ_q 0][q̈; λ] = [Q; γ], and a₀ = q̈₀.
//!
//! Steps keep to their own grid: an output time inside a step, short of
//! its end, is served by [`Integrator::dense_output`] (cubic Hermite
//! interpolants of q and q̇, projected onto the constraints, then the
//! consistent q̈ and λ), never by a step cut short to meet it.
//!
//! The error-controlled mode estimates the local error of a step as
//! h² |β − 1/6| |q̈_{n+1} − q̈_n| per coordinate, the leading term of the
//! Newmark truncation error (with q̈ for a, whose parasitic oscillation
//! after a change of step would trigger needless rejections), rejects steps
//! whose weighted norm exceeds 1 and changes h by a PI controller on the
//! errors of the last two accepted steps.

use super::branch::{self, BranchRows};
use super::project;
use super::redundant::Redundant;
use super::retry::{self, Way, SINGULAR_ITER};
use super::system::{Augmented, Coefficients, System};
use crate::linsolve::DenseLu;
use crate::math::{inner, max_abs};
use crate::model::Model;
use crate::newton;
use crate::run::{self, AnalysisError, Kind, StateView, Summary};

/// A Newton correction larger than this fraction of the one before means
/// the chord iteration has stalled: the next iteration refactors.
const STALL: f64 = 0.5;

/// A chord iteration whose correction is more than this fraction of the
/// one before, short of a stall ([`STALL`]), refactors for the next
/// iteration, while the correction is more than [`ABOVE_ROUNDING`] times
/// the rounding of the largest coordinate.
const SLOW: f64 = 0.2;

/// See [`SLOW`].
const ABOVE_ROUNDING: f64 = 1e3;

/// Newton stops on the error a correction leaves, estimated from the
/// contraction, while the correction is more than this many times the
/// rounding of the largest coordinate; below, on the correction itself
/// too (see `Integrator::converged`).
const ESTIMATE_ABOVE_ROUNDING: f64 = 1e2;

/// A correction within this many times the measured rounding noise of the
/// solve counts as converged.
const NOISE_SAFETY: f64 = 4.0;

/// A step whose largest multiplier grew by more than this factor makes
/// the next one start from the multipliers consistent with its predicted
/// state (see `Integrator::predict`).
const LAMBDA_JUMP: f64 = 1.5;

/// A growth of the largest multiplier by more than this factor in one
/// step triggers the same restart even when it is not accelerating.
const LAMBDA_LEAP: f64 = 3.0;

/// In the error-controlled mode Newton's tolerance is at most this
/// fraction of the local error allowed to a coordinate, atol + rtol |q_k|
/// (m or rad; the same number in m/s and m/s² for its velocity and
/// acceleration corrections), so that what Newton leaves stays well within
/// the error the step controller estimates.
const NEWTON_SHARE: f64 = 0.1;

/// The fixed-step mode stretches a step by up to this fraction of h rather
/// than leave a sliver before an output time.
const SLIVER: f64 = 1e-6;

/// A factorization whose smallest relative pivot falls below this makes
/// the step look for a lost rank of Φ_q ([`branch`]).
const PIVOT_WATCH: f64 = 1e-6;

/// The predictor extrapolates quadratically only while the smallest
/// relative pivot of the last factorization is at least this (1e-3 to
/// 5e-2 along the slider-crank's and the parallelogram chains' regular
/// positions; it falls as σ² towards a singular position).
const QUADRATIC_PIVOT: f64 = 1e-4;

/// The first plain step past a window of branch rows has kept to the
/// branch when its motion across the rows is within this fraction of it.
const GUARD: f64 = 0.1;

/// A step that moves a coordinate by this much (m or rad) or more passes a
/// bifurcation point at speed, without branch rows.
const SLOW_STEP: f64 = 1e-4;

/// How close to `t_end` (s) a run of steps of at most `h_max` (s) counts
/// as there: a few ulps of t_end, or a trillionth of the step (a step
/// larger than the interval counts as the interval, so a huge h still
/// steps).
pub(crate) fn arrived_within(t_end: f64, h_max: f64) -> f64 {
    let scale = h_max.min(t_end.abs()).max(f64::MIN_POSITIVE);
    (4.0 * f64::EPSILON * t_end.abs()).max(1e-12 * scale)
}

/// The next fixed step with `left` (s) to go: `h_max`, or the whole of
/// `left` when it is at most [`SLIVER`] longer than `h_max`. The rounding
/// of t accumulated over the steps of an output interval would otherwise
/// leave a sliver of a step (~1e-14 s at h = 1e-5 s), whose Newton matrix
/// (β' ∝ 1/h²) cannot be factored.
pub(crate) fn fixed_step(left: f64, h_max: f64) -> f64 {
    if left <= h_max * (1.0 + SLIVER) {
        left
    } else {
        h_max
    }
}

/// True when an output time `left` (s) ahead lies inside the next fixed
/// step of `h_max` (s), short of a whole step by more than [`SLIVER`]: the
/// step goes past it and the output is interpolated
/// ([`Integrator::dense_output`]).
pub(crate) fn steps_over(left: f64, h_max: f64) -> bool {
    left < h_max * (1.0 - SLIVER)
}

/// Error control of the variable-step mode: the weighted local error
/// |e_k| / (atol + rtol |q_k|) is kept ≤ 1.
#[derive(Clone, Debug, PartialEq)]
pub struct Adaptive {
    /// Absolute tolerance (m or rad).
    pub atol: f64,
    /// Relative tolerance.
    pub rtol: f64,
    /// Smallest step allowed (s).
    pub h_min: f64,
}

/// Integrator settings.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Time step h (s); the largest step in the error-controlled mode.
    pub step: f64,
    /// Spectral radius at infinity ρ∞ ∈ [0, 1].
    pub rho_inf: f64,
    /// Newton stops when every coordinate's last correction |Δq_k|, its
    /// velocity's |Δq̇_k| = γ' |Δq_k| and its acceleration's
    /// |Δq̈_k| = β' |Δq_k| are each ≤ tol (m or rad; m/s or rad/s; m/s² or
    /// rad/s²) or within the rounding of the value ([`crate::newton`]),
    /// whichever is larger. In the error-controlled mode tol is at most a
    /// tenth of atol + rtol |q_k|.
    pub tol: f64,
    /// Newton iterations per step.
    pub max_iter: usize,
    /// Tolerance of the initial position projection (m or rad).
    pub projection_tol: f64,
    /// `Some` for the error-controlled mode.
    pub adaptive: Option<Adaptive>,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            step: 1e-3,
            rho_inf: 0.8,
            tol: 1e-6,
            max_iter: 12,
            projection_tol: 1e-12,
            adaptive: None,
        }
    }
}

/// The method's coefficients for ρ∞.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coeffs {
    pub alpha_m: f64,
    pub alpha_f: f64,
    pub beta: f64,
    pub gamma: f64,
}

impl Coeffs {
    pub fn new(rho_inf: f64) -> Self {
        let r = rho_inf.clamp(0.0, 1.0);
        let alpha_m = (2.0 * r - 1.0) / (r + 1.0);
        let alpha_f = r / (r + 1.0);
        let gamma = 0.5 + alpha_f - alpha_m;
        Coeffs {
            alpha_m,
            alpha_f,
            beta: 0.25 * (gamma + 0.5) * (gamma + 0.5),
            gamma,
        }
    }

    /// The pseudo-acceleration a_{n+1} of the recurrence
    /// (1 − α_m) a_{n+1} + α_m a_n = (1 − α_f) q̈_{n+1} + α_f q̈_n, for
    /// one coordinate.
    #[inline]
    pub fn next_a(&self, qdd1: f64, qdd0: f64, a0: f64) -> f64 {
        ((1.0 - self.alpha_f) * qdd1 + self.alpha_f * qdd0 - self.alpha_m * a0)
            / (1.0 - self.alpha_m)
    }
}

/// The state of a forward-dynamics run at time t (s): positions q (m or
/// rad), velocities q̇ (m/s or rad/s), accelerations q̈ (m/s² or rad/s²),
/// multipliers λ (one per equation of Φ) and the pseudo-acceleration a
/// (m/s² or rad/s²) with the step h_a that made it. Vectors in the
/// layout of the integrator's assembly.
#[derive(Clone, Debug, Default)]
pub struct State {
    pub t: f64,
    pub q: Vec<f64>,
    pub qd: Vec<f64>,
    pub qdd: Vec<f64>,
    pub lambda: Vec<f64>,
    pub a: Vec<f64>,
    /// The step (s) that made `a`, a ≈ q̈(t + (α_m − α_f) h_a), or 0 when
    /// `a` is not known to lie so (it is q̈, or q̈ was solved afresh).
    pub h_a: f64,
}

impl State {
    /// The state at `t` (s) with positions `q` and velocities `qd`, the
    /// rest zero, for a system of `m` equations.
    fn at(t: f64, q: Vec<f64>, qd: Vec<f64>, m: usize) -> Self {
        let n = q.len();
        State {
            t,
            q,
            qd,
            qdd: vec![0.0; n],
            lambda: vec![0.0; m],
            a: vec![0.0; n],
            h_a: 0.0,
        }
    }

    /// Copies `from` into this state, reusing its vectors.
    fn copy_from(&mut self, from: &State) {
        self.t = from.t;
        self.q.clone_from(&from.q);
        self.qd.clone_from(&from.qd);
        self.qdd.clone_from(&from.qdd);
        self.lambda.clone_from(&from.lambda);
        self.a.clone_from(&from.a);
        self.h_a = from.h_a;
    }

    /// a = q̈, as at a start (h_a = 0).
    fn restart_a(&mut self) {
        self.a.copy_from_slice(&self.qdd);
        self.h_a = 0.0;
    }

    /// Its positions, velocities and accelerations.
    pub(crate) fn view(&self) -> StateView<'_> {
        StateView {
            q: &self.q,
            qd: &self.qd,
            qdd: &self.qdd,
        }
    }
}

/// The predictor's history ([`Integrator::predict`]): the length h (s)
/// of the last step (0: none, or not to extrapolate from) with q̈ and λ
/// at its start, and the same of the step before it; and of the step
/// before that, which the last [`push`](Self::push) dropped, so that a
/// step taken back ([`undo`](Self::undo)) leaves the history as it was.
#[derive(Clone, Debug, Default)]
struct History {
    h: f64,
    qdd: Vec<f64>,
    lambda: Vec<f64>,
    h2: f64,
    qdd2: Vec<f64>,
    lambda2: Vec<f64>,
    h3: f64,
    qdd3: Vec<f64>,
    lambda3: Vec<f64>,
}

impl History {
    fn new(n: usize, m: usize) -> Self {
        History {
            h: 0.0,
            qdd: vec![0.0; n],
            lambda: vec![0.0; m],
            h2: 0.0,
            qdd2: vec![0.0; n],
            lambda2: vec![0.0; m],
            h3: 0.0,
            qdd3: vec![0.0; n],
            lambda3: vec![0.0; m],
        }
    }

    /// Copies `from` into this history, reusing its vectors.
    fn copy_from(&mut self, from: &History) {
        self.h = from.h;
        self.qdd.clone_from(&from.qdd);
        self.lambda.clone_from(&from.lambda);
        self.h2 = from.h2;
        self.qdd2.clone_from(&from.qdd2);
        self.lambda2.clone_from(&from.lambda2);
        self.h3 = from.h3;
        self.qdd3.clone_from(&from.qdd3);
        self.lambda3.clone_from(&from.lambda3);
    }

    /// True when the last step, the one before it and a step of `h` (s)
    /// are equal, within [`SLIVER`] h.
    fn equal_steps(&self, h: f64) -> bool {
        let equal = |a: f64, b: f64| (a - b).abs() <= SLIVER * h;
        self.h > 0.0 && self.h2 > 0.0 && equal(h, self.h) && equal(self.h2, self.h)
    }

    /// q̈ and λ at the end of the next step, from `qdd` and `lambda` at
    /// its start, by the parabola through them and the values at the start
    /// of the last two steps (equal steps, [`equal_steps`](Self::equal_steps)):
    /// x₊ = 3 (x − x₁) + x₂.
    fn extrapolate_quadratic(&self, qdd: &mut [f64], lambda: &mut [f64]) {
        for (x, (x1, x2)) in qdd.iter_mut().zip(self.qdd.iter().zip(&self.qdd2)) {
            *x = 3.0 * (*x - x1) + x2;
        }
        for (x, (x1, x2)) in lambda.iter_mut().zip(self.lambda.iter().zip(&self.lambda2)) {
            *x = 3.0 * (*x - x1) + x2;
        }
    }

    /// q̈ and λ at the end of the next step, of `h` (s), from `qdd` and
    /// `lambda` at its start, by the line through them and the values at
    /// the start of the last step, x₊ = x + (h/h₁)(x − x₁); held constant
    /// when there is no last step (h₁ = 0).
    fn extrapolate_linear(&self, h: f64, qdd: &mut [f64], lambda: &mut [f64]) {
        let r = if self.h > 0.0 { h / self.h } else { 0.0 };
        for (x, x1) in qdd.iter_mut().zip(&self.qdd) {
            *x += r * (*x - x1);
        }
        for (x, x1) in lambda.iter_mut().zip(&self.lambda) {
            *x += r * (*x - x1);
        }
    }

    /// After a step of `h` (s) from a state with q̈ `qdd` and λ `lambda`:
    /// that step becomes the last one, the last the one before (the
    /// vectors rotate; only the new values are copied).
    fn push(&mut self, h: f64, qdd: &[f64], lambda: &[f64]) {
        std::mem::swap(&mut self.qdd2, &mut self.qdd3);
        std::mem::swap(&mut self.lambda2, &mut self.lambda3);
        std::mem::swap(&mut self.qdd, &mut self.qdd2);
        std::mem::swap(&mut self.lambda, &mut self.lambda2);
        self.qdd.copy_from_slice(qdd);
        self.lambda.copy_from_slice(lambda);
        self.h3 = self.h2;
        self.h2 = self.h;
        self.h = h;
    }

    /// Takes back the last [`push`](Self::push), of a step that is
    /// taken again: the history is the one that step started from (the
    /// step before the two then known is not: h₃ = 0).
    fn undo(&mut self) {
        std::mem::swap(&mut self.qdd, &mut self.qdd2);
        std::mem::swap(&mut self.lambda, &mut self.lambda2);
        std::mem::swap(&mut self.qdd2, &mut self.qdd3);
        std::mem::swap(&mut self.lambda2, &mut self.lambda3);
        self.h = self.h2;
        self.h2 = self.h3;
        self.h3 = 0.0;
    }
}

/// A copy of an integrator's [`State`] and the predictor's history, for
/// stepping again from the same start.
#[derive(Clone, Debug, Default)]
pub struct Snapshot {
    state: State,
    history: History,
}

impl Snapshot {
    /// Copies `s` into this snapshot, reusing its vectors.
    pub fn copy_from(&mut self, s: &Snapshot) {
        self.state.copy_from(&s.state);
        self.history.copy_from(&s.history);
    }

    /// Its time (s).
    pub fn t(&self) -> f64 {
        self.state.t
    }
}

/// How an attempt at a step ended.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Attempt {
    Converged,
    /// Newton did not converge.
    Failed,
    /// A slow step found S singular: to be taken along the branch.
    MetSingular,
}

/// The coefficients of one step of h from t: t₁ = t + h, β' and γ'
/// (Δq̈ = β' Δq, Δq̇ = γ' Δq) and the scale s = 1/β' of the equations
/// of motion in Newton's matrix.
#[derive(Clone, Copy, Debug)]
struct StepCoeffs {
    h: f64,
    t1: f64,
    bp: f64,
    gp: f64,
    s: f64,
}

impl StepCoeffs {
    fn new(c: &Coeffs, t: f64, h: f64) -> Self {
        let bp = (1.0 - c.alpha_m) / (c.beta * h * h * (1.0 - c.alpha_f));
        StepCoeffs {
            h,
            t1: t + h,
            bp,
            gp: c.gamma / (c.beta * h),
            s: 1.0 / bp,
        }
    }
}

/// One Newton correction applied: its largest |Δq_k| (m or rad), its
/// ratio θ to the one before, and whether the iteration has converged.
struct Correction {
    dmax: f64,
    theta: f64,
    converged: bool,
}

/// A forward-dynamics run, allocated once: the system, the settings, the
/// state at t, the start of the step being taken, the predictor's
/// history, Newton's matrix and scratch, the branch being followed, the
/// run's diagnostics and the dense output.
pub struct Integrator<'m> {
    pub sys: System<'m>,
    /// The model's redundant equations, if any.
    pub redundant: Option<Redundant>,
    settings: Settings,
    c: Coeffs,

    /// The state at t.
    state: State,
    /// The state at the start of the step, to retry it.
    start: State,

    /// The predictor's history.
    history: History,
    /// The weighted error of the last accepted error-controlled step.
    err_prev: Option<f64>,

    newton: Newton,

    /// Near a bifurcation point, the branch being followed.
    follow: Follow,

    diagnostics: Diagnostics,

    /// The state at an output time inside the last step
    /// ([`dense_output`](Self::dense_output)); made at its first use.
    pub dense: Option<Dense>,
}

/// Newton's matrix and scratch: the augmented matrix S (or S_ε) and the
/// step it was factored for, the right side, a vector of length n and the
/// rounding noise of a correction.
struct Newton {
    aug: Augmented,
    /// The step h the factorization was made for (0: none).
    h_factored: f64,
    /// Right side and correction, length n + m.
    rhs: Vec<f64>,
    /// Scratch of length n.
    work: Vec<f64>,
    /// The rounding noise of a Newton correction, the same level for
    /// every coordinate (zero until measured in an attempt at a step).
    noise: f64,
}

/// What a run reports beside its state.
#[derive(Clone, Debug, Default)]
pub struct Diagnostics {
    /// Steps, Newton iterations, factorizations and warnings.
    pub summary: Summary,
    /// Steps rejected by the error control.
    pub rejected: usize,
    /// Whether the last step ended at a singular position (warned once
    /// per visit).
    near_singular: bool,
}

/// Near a bifurcation point ([`branch`]): the branch rows in use, their
/// multipliers μ, and the bordered matrix [S_ε Bᵀ; B −ε I] (B = [A 0])
/// solved through S_ε's factorization: X = S_ε⁻¹ Bᵀ (`border`, k columns
/// of n + m) and the LU of the Schur complement C = −ε I − B X; `ext`
/// holds the k row corrections of a solve.
#[derive(Default)]
struct Follow {
    rows: Option<BranchRows>,
    /// At the last look for a lost rank after a plain step: the smallest
    /// pivot over σ_rel² there.
    seen: Option<f64>,
    /// The last rows of a window just left, to check the first plain step.
    guard: Option<BranchRows>,
    mu: Vec<f64>,
    border: Vec<f64>,
    schur: Option<DenseLu>,
    ext: Vec<f64>,
}

/// The state at an output time t inside a step [t₀, t₁]: q and q̇ from the
/// cubic Hermite interpolants of (q, q̇) and (q̇, q̈) at the step's ends,
/// projected onto Φ = 0 and Φ_q q̇ = ν, then q̈ and λ consistent with them,
/// [M Φ_qᵀ; Φ_q 0][q̈; λ] = [Q; γ]. Its own matrix leaves the step's
/// factorization alone.
pub struct Dense {
    /// Time (s).
    pub t: f64,
    /// Positions q (m or rad), in the layout of the integrator's assembly.
    pub q: Vec<f64>,
    /// Velocities q̇ (m/s or rad/s).
    pub qd: Vec<f64>,
    /// Accelerations q̈ (m/s² or rad/s²).
    pub qdd: Vec<f64>,
    /// Multipliers λ, one per equation of Φ.
    pub lambda: Vec<f64>,
    aug: Augmented,
    rhs: Vec<f64>,
    /// The projections' scratch.
    proj: project::Workspace,
}

impl Dense {
    /// Its positions, velocities and accelerations.
    pub(crate) fn view(&self) -> StateView<'_> {
        StateView {
            q: &self.q,
            qd: &self.qd,
            qdd: &self.qdd,
        }
    }
}

impl<'m> Integrator<'m> {
    /// Lays the model out and makes the initial conditions consistent at t = 0.
    pub fn new(model: &'m Model, settings: Settings) -> Result<Self, AnalysisError> {
        Self::starting_at(model, settings, 0.0)
    }

    /// As [`new`](Self::new), starting at `t0`.
    pub fn starting_at(
        model: &'m Model,
        settings: Settings,
        t0: f64,
    ) -> Result<Self, AnalysisError> {
        let fail = |kind: Kind, message: String, residual: f64| {
            AnalysisError::new(kind, t0, message).at_joints(Vec::new(), residual)
        };
        if !(settings.step.is_finite() && settings.step > 0.0) {
            return Err(fail(
                Kind::InvalidInput,
                format!(
                    "the time step must be a positive number, not {}",
                    crate::fmt_num::num(settings.step)
                ),
                0.0,
            ));
        }
        let sys = System::new(model);
        let (n, m) = (sys.n(), sys.m());
        if n == 0 {
            return Err(fail(
                Kind::InvalidInput,
                "the model has no moving bodies".into(),
                0.0,
            ));
        }
        let mut q = sys.asm.initial_q(model);
        let mut qd = vec![0.0; n];
        for (id, b) in model.moving_bodies() {
            let c = sys.asm.body_col(id.0).expect("moving body");
            qd[c..c + 3].copy_from_slice(&b.qd0);
        }
        let mut aug =
            Augmented::new(&sys, &q).map_err(|e| fail(Kind::Internal, e.to_string(), 0.0))?;
        let redundant = Redundant::detect(&sys, &mut aug, &q, t0);
        let mut summary = Summary::default();
        if let Some(r) = &redundant {
            aug.set_regularised(true);
            summary.warnings.push(r.warning(t0));
        }
        // The joints furthest from Φ = 0 at q when a projection fails.
        let named = |e: project::ProjectionError, q: &[f64]| {
            let mut phi = vec![0.0; m];
            sys.asm.phi(model, q, t0, &mut phi);
            let (joints, _) = run::worst_joints(model, &sys.asm, &phi, 0.0);
            fail(e.kind, e.message, e.residual).at_joints(joints, e.residual)
        };
        project::positions(&sys, &mut aug, &mut q, t0, settings.projection_tol, 100)
            .map_err(|e| named(e, &q))?;
        project::velocities(&sys, &mut aug, &q, &mut qd, t0).map_err(|e| named(e, &q))?;
        let state = State::at(t0, q, qd, m);
        let mut it = Integrator {
            c: Coeffs::new(settings.rho_inf),
            settings,
            start: state.clone(),
            state,
            history: History::new(n, m),
            err_prev: None,
            newton: Newton {
                aug,
                h_factored: 0.0,
                rhs: vec![0.0; n + m],
                work: vec![0.0; n],
                noise: 0.0,
            },
            follow: Follow::default(),
            diagnostics: Diagnostics {
                summary,
                ..Diagnostics::default()
            },
            dense: None,
            sys,
            redundant,
        };
        it.accelerations()?;
        it.state.restart_a();
        it.watch_singularity();
        Ok(it)
    }

    /// Restarts at an event of a unilateral contact ([`super::unilateral`])
    /// from (t, q, q̇): positions and velocities projected onto this
    /// model's constraints, q̈ and λ consistent, the predictor's history
    /// dropped.
    pub fn restart(&mut self, t: f64, q: &[f64], qd: &[f64]) -> Result<(), AnalysisError> {
        self.leave_branch();
        self.state.t = t;
        self.state.q.copy_from_slice(q);
        self.state.qd.copy_from_slice(qd);
        let tol = self.settings.projection_tol;
        let projected = project::positions(
            &self.sys,
            &mut self.newton.aug,
            &mut self.state.q,
            t,
            tol,
            100,
        )
        .and_then(|_| {
            project::velocities(
                &self.sys,
                &mut self.newton.aug,
                &self.state.q,
                &mut self.state.qd,
                t,
            )
        });
        if let Err(e) = projected {
            return Err(self.error(e.kind, &e.message));
        }
        self.accelerations()?;
        self.state.restart_a();
        self.history.h = 0.0;
        self.err_prev = None;
        Ok(())
    }

    /// The system and its augmented matrix, for a one-shot solve of the
    /// caller's (the impact's); the step's factorization is dropped.
    pub fn system_and_matrix(&mut self) -> (&System<'m>, &mut Augmented) {
        self.newton.h_factored = 0.0;
        (&self.sys, &mut self.newton.aug)
    }

    /// Copies the state into `s`, to [`resume`](Self::resume) from it.
    pub fn snapshot(&self, s: &mut Snapshot) {
        s.state.copy_from(&self.state);
        s.history.copy_from(&self.history);
    }

    /// Returns to the state of a [`snapshot`](Self::snapshot).
    pub fn resume(&mut self, s: &Snapshot) {
        self.leave_branch();
        self.state.copy_from(&s.state);
        self.history.copy_from(&s.history);
    }

    /// The state at t.
    pub fn state(&self) -> &State {
        &self.state
    }

    /// The run's counts, warnings and rejected steps so far.
    pub fn diagnostics(&self) -> &Diagnostics {
        &self.diagnostics
    }

    /// q̈ and λ at the current (t, q, q̇): [M Φ_qᵀ; Φ_q 0][q̈; λ] = [Q; γ].
    pub fn accelerations(&mut self) -> Result<(), AnalysisError> {
        self.consistent()?;
        let n = self.sys.n();
        self.state.qdd.copy_from_slice(&self.newton.rhs[..n]);
        self.state.lambda.copy_from_slice(&self.newton.rhs[n..]);
        self.state.h_a = 0.0;
        Ok(())
    }

    /// The multipliers μ of minimum norm with the same constraint forces
    /// Φ_qᵀμ = Φ_qᵀλ as the current λ, into `out` (length m): the
    /// reactions of a model with redundant equations. From
    /// [I Φ_qᵀ; Φ_q 0][x; μ] = [Φ_qᵀλ; 0] (x = 0), solved by
    /// [`Augmented::solve_refined`]; the integrator's state is unchanged.
    pub fn min_norm_multipliers(&mut self, out: &mut [f64]) -> Result<(), AnalysisError> {
        let (n, s) = (self.sys.n(), &self.sys);
        let k = Coefficients {
            identity: 1.0,
            scale: 1.0,
            ..Default::default()
        };
        self.newton.h_factored = 0.0;
        if self
            .newton
            .aug
            .refactor(
                s,
                &self.state.q,
                &self.state.qd,
                &self.state.qdd,
                None,
                self.state.t,
                k,
            )
            .is_err()
        {
            return Err(self.error(Kind::LockUp, "the constraint Jacobian is singular"));
        }
        self.newton.rhs.fill(0.0);
        s.add_jt_lambda(
            &self.state.q,
            self.state.t,
            &self.state.lambda,
            &mut self.newton.rhs[..n],
        );
        self.newton.aug.solve_refined(&mut self.newton.rhs);
        out.copy_from_slice(&self.newton.rhs[n..]);
        Ok(())
    }

    /// Solves [M Φ_qᵀ; Φ_q 0][q̈; λ] = [Q; γ] into `rhs`, λ of minimum norm.
    fn consistent(&mut self) -> Result<(), AnalysisError> {
        self.newton.h_factored = 0.0;
        let (t, q, qd, qdd) = (self.state.t, &self.state.q, &self.state.qd, &self.state.qdd);
        solve_consistent(
            &self.sys,
            &mut self.newton.aug,
            t,
            q,
            qd,
            qdd,
            &mut self.newton.rhs,
        )
    }

    /// [`consistent`](Self::consistent) at the current state with the
    /// caller's matrix `aug` (made for this system) into the caller's
    /// `rhs` (resized to n + m: q̈, then λ); the integrator and its
    /// factorization are unchanged.
    pub(crate) fn consistent_into(
        &self,
        aug: &mut Augmented,
        rhs: &mut Vec<f64>,
    ) -> Result<(), AnalysisError> {
        rhs.resize(self.sys.n() + self.sys.m(), 0.0);
        let (t, q, qd, qdd) = (self.state.t, &self.state.q, &self.state.qd, &self.state.qdd);
        solve_consistent(&self.sys, aug, t, q, qd, qdd, rhs)
    }

    /// The state at `t` (s) inside the last step, t₀ ≤ t ≤ t₁ = `self.state.t`,
    /// into [`dense`](Self::dense) ([`Dense`]). The accelerations and
    /// multipliers of a step scale like 1/h², so a step cut short to land
    /// on t would not give them; the integrator's state and factorization
    /// are unchanged.
    pub fn dense_output(&mut self, t: f64) -> Result<(), AnalysisError> {
        self.make_dense(t)?;
        // Projected, or where the projection fails, as interpolated.
        for project in [true, false] {
            let d = self.dense.as_mut().expect("dense output");
            hermite(d, t, &self.start, &self.state);
            let settled = self.settle_dense(project);
            if settled.is_ok() || !project {
                return settled;
            }
        }
        unreachable!("the unprojected state returns")
    }

    /// [`dense_output`](Self::dense_output) at `t` (s) between the states
    /// of two snapshots of this integrator, `start` and `end`, the ends of
    /// one step.
    pub fn dense_between(
        &mut self,
        start: &Snapshot,
        end: &Snapshot,
        t: f64,
    ) -> Result<(), AnalysisError> {
        self.make_dense(t)?;
        // Projected, or where the projection fails, as interpolated.
        for project in [true, false] {
            let d = self.dense.as_mut().expect("dense output");
            hermite(d, t, &start.state, &end.state);
            let settled = self.settle_dense(project);
            if settled.is_ok() || !project {
                return settled;
            }
        }
        unreachable!("the unprojected state returns")
    }

    /// Makes [`dense`](Self::dense) at its first use.
    fn make_dense(&mut self, t: f64) -> Result<(), AnalysisError> {
        if self.dense.is_none() {
            let (n, m) = (self.sys.n(), self.sys.m());
            let aug = Augmented::new(&self.sys, &self.state.q)
                .map_err(|e| AnalysisError::new(Kind::Internal, t, e.to_string()))?;
            self.dense = Some(Dense {
                t,
                q: vec![0.0; n],
                qd: vec![0.0; n],
                qdd: vec![0.0; n],
                lambda: vec![0.0; m],
                aug,
                rhs: vec![0.0; n + m],
                proj: project::Workspace::new(&self.sys),
            });
        }
        Ok(())
    }

    /// The interpolated (q, q̇) of [`dense`](Self::dense) projected onto
    /// Φ = 0 (to `projection_tol`) and Φ_q q̇ = ν when `project`, then q̈
    /// and λ (of minimum norm) from [M Φ_qᵀ; Φ_q 0][q̈; λ] = [Q; γ] there.
    /// (The interpolant is off the constraints by its O(h⁴) error only: at
    /// a singular position, where the projection can fail, it serves
    /// unprojected.)
    fn settle_dense(&mut self, project: bool) -> Result<(), AnalysisError> {
        let n = self.sys.n();
        let (sys, tol) = (&self.sys, self.settings.projection_tol);
        let Dense {
            t,
            q,
            qd,
            qdd,
            lambda,
            aug,
            rhs,
            proj,
        } = self.dense.as_mut().expect("dense output");
        let t = *t;
        aug.set_regularised(self.redundant.is_some());
        if project {
            let projected = project::positions_in(sys, aug, q, t, tol, 100, proj)
                .and_then(|_| project::velocities_in(sys, aug, q, qd, t, proj));
            if let Err(e) = projected {
                return Err(error_at(sys, t, q, e.kind, &e.message));
            }
        }
        solve_consistent(sys, aug, t, q, qd, qdd, rhs)?;
        qdd.copy_from_slice(&rhs[..n]);
        lambda.copy_from_slice(&rhs[n..]);
        Ok(())
    }

    /// An error at the current state, naming the joints furthest from
    /// Φ = 0 (at most five) and the largest |Φ|.
    fn error(&self, kind: Kind, what: &str) -> AnalysisError {
        error_at(&self.sys, self.state.t, &self.state.q, kind, what)
    }

    /// Advances one step of size `h`. The ways of taking it are tried in
    /// the order of the retry policy ([`retry`]), each from the state at
    /// the start of the step; when none converges the state is back there
    /// and the error says so. An error raised within an attempt (a Newton
    /// matrix that cannot be factored, a force that cannot be evaluated)
    /// stops at that attempt's state.
    pub fn step(&mut self, h: f64) -> Result<(), AnalysisError> {
        // At a singular position (S_ε factored last) the multipliers of the
        // lost direction are not determined, and the ones carried over can
        // be arbitrarily large: follow the branch with its rows, or start
        // from the consistent q̈ and the minimum-norm λ.
        if self.follow.rows.is_none()
            && self.at_singular_position()
            && !(self.slow(h) && self.enter_branch())
        {
            self.accelerations()?;
            self.history.h = 0.0;
        }
        self.save();
        let mut last = Attempt::Failed;
        for &way in retry::ladder(self.follow.rows.is_some()) {
            let Some(outcome) = self.take(way, h, last)? else {
                continue;
            };
            if outcome == Attempt::Converged {
                return if way.along_branch() {
                    self.after_branch_step()
                } else {
                    self.after_plain_step(h)
                };
            }
            self.restore();
            self.after_failed(way)?;
            last = outcome;
        }
        Err(self.error(
            Kind::NotConverged,
            &format!(
                "Newton did not converge in {} iterations at step {} s, nor in {} \
                 with a fresh matrix each iteration: near a singular position (a toggle, \
                 a dead centre, the flat position of a parallelogram) try another step h; \
                 with stiff springs or contacts, a smaller h",
                self.settings.max_iter,
                crate::fmt_num::num(h),
                SINGULAR_ITER * self.settings.max_iter
            ),
        ))
    }

    /// One attempt at a step of `h` the [`Way`] `way`, from the start of
    /// the step (`last`: how the attempt before ended); None when the way
    /// does not apply here.
    fn take(&mut self, way: Way, h: f64, last: Attempt) -> Result<Option<Attempt>, AnalysisError> {
        match way {
            Way::Chord => return self.attempt(h, false, true).map(Some),
            Way::BranchAtSingular => {
                if last != Attempt::MetSingular || !self.enter_branch() {
                    return Ok(None);
                }
            }
            Way::Fresh => self.history.h = 0.0,
            Way::BranchWhereLost => {
                if !self.enter_branch() {
                    return Ok(None);
                }
            }
            Way::AlongBranch => {}
            Way::LeaveBranch => {
                self.leave_branch();
                self.accelerations()?;
                self.save();
            }
        }
        self.attempt(h, true, false).map(Some)
    }

    /// After a failed attempt the [`Way`] `way`, back at the start of the
    /// step: what the next way starts from.
    fn after_failed(&mut self, way: Way) -> Result<(), AnalysisError> {
        match way {
            Way::BranchAtSingular => {
                self.leave_branch();
                self.accelerations()?;
                self.save();
            }
            Way::AlongBranch => self.history.h = 0.0,
            Way::Chord | Way::Fresh | Way::BranchWhereLost | Way::LeaveBranch => {}
        }
        Ok(())
    }

    /// After a step with Φ alone: the first one past a window of branch
    /// rows that crossed to the other branch is taken again along the
    /// branch; a step that ends near a singular position looks for a lost
    /// rank.
    fn after_plain_step(&mut self, h: f64) -> Result<(), AnalysisError> {
        if let Some(rows) = self.crossed_branch() {
            // Back to the start of the step.
            self.take_back();
            self.use_rows(rows);
            self.save();
            if !self.try_step(h, true)? {
                self.restore();
                return Err(self.error(
                    Kind::NotConverged,
                    "Newton did not converge along the branch past a singular position",
                ));
            }
            return self.after_branch_step();
        }
        if self.newton.aug.min_pivot().is_some_and(|p| p < PIVOT_WATCH) && self.slow(h) {
            self.watch_branch();
        } else {
            self.follow.seen = None;
        }
        self.watch_singularity();
        Ok(())
    }

    /// Starts following the branch with its rows ([`branch`]) when Φ_q
    /// has lost rank here; false when it has not (or the model has
    /// redundant equations, whose lost directions are exact).
    fn enter_branch(&mut self) -> bool {
        if self.redundant.is_some() {
            return false;
        }
        let Some(rows) = branch::analyse(&self.sys, &self.state.q, self.state.t, self.direction())
        else {
            return false;
        };
        self.use_rows(rows);
        true
    }

    /// Follows the branch with `rows` from the current state.
    fn use_rows(&mut self, rows: BranchRows) {
        let (n, m, k) = (self.sys.n(), self.sys.m(), rows.k);
        self.follow.mu = vec![0.0; k];
        self.follow.ext = vec![0.0; k];
        self.follow.border = vec![0.0; k * (n + m)];
        self.follow.schur = Some(DenseLu::new(k));
        self.follow.rows = Some(rows);
        self.newton.aug.set_regularised(true);
        self.newton.aug.invalidate();
        self.history.h = 0.0;
    }

    /// True when a step of `h` moves every coordinate by less than
    /// [`SLOW_STEP`]: the branch rows serve a mechanism that reaches a
    /// bifurcation point at rest or nearly; one that passes it at speed
    /// steps over it with Φ alone, whose roots are then a step's motion
    /// apart, while the rows' linearisation would err by the square of it.
    fn slow(&self, h: f64) -> bool {
        h * max_abs(&self.state.qd) < SLOW_STEP
    }

    /// The direction of motion: the velocity, or at rest the acceleration.
    fn direction(&self) -> &[f64] {
        if max_abs(&self.state.qd) > 0.0 {
            &self.state.qd
        } else {
            &self.state.qdd
        }
    }

    /// Stops following a branch (Φ alone from here); the rows that were
    /// in use.
    fn leave_branch(&mut self) -> Option<BranchRows> {
        self.follow.seen = None;
        self.follow.guard = None;
        let rows = self.follow.rows.take()?;
        self.follow.schur = None;
        self.newton.aug.set_regularised(false);
        self.newton.aug.invalidate();
        Some(rows)
    }

    /// After the first plain step past a window: the window's last rows
    /// A when the step crossed to the other branch, moving across them
    /// (|A Δq| > [`GUARD`] |Δq|; along the branch A Δq is of second order).
    fn crossed_branch(&mut self) -> Option<BranchRows> {
        let rows = self.follow.guard.take()?;
        let n = self.sys.n();
        for ((d, q), q0) in self
            .newton
            .work
            .iter_mut()
            .zip(&self.state.q)
            .zip(&self.start.q)
        {
            *d = q - q0;
        }
        let across = rows
            .a
            .chunks(n)
            .map(|row| inner(row, &self.newton.work).abs())
            .fold(0.0, f64::max);
        (across > GUARD * max_abs(&self.newton.work)).then_some(rows)
    }

    /// After a plain step that ended near a singular position: follows
    /// the branch with its rows from here when inside the window.
    fn watch_branch(&mut self) {
        if self.redundant.is_some() {
            return;
        }
        let Some(pivot) = self.newton.aug.min_pivot() else {
            return;
        };
        // The smallest pivot falls as σ² near the point: scaled by the
        // ratio found at the last look, it tells cheaply whether a new
        // look is due.
        if let Some(ratio) = self.follow.seen {
            let sigma = (pivot / ratio).sqrt();
            if sigma > 2.0 * branch::WINDOW {
                return;
            }
        }
        let Some(rows) = branch::analyse(&self.sys, &self.state.q, self.state.t, self.direction())
        else {
            self.follow.seen = None;
            return;
        };
        self.follow.seen = Some(pivot / (rows.sigma_rel * rows.sigma_rel));
        if rows.sigma_rel < branch::WINDOW {
            self.use_rows(rows);
        }
    }

    /// After a step along the branch: out of the window
    /// ([`branch::WINDOW_EXIT`]), back to Φ alone from the consistent q̈
    /// and λ.
    fn after_branch_step(&mut self) -> Result<(), AnalysisError> {
        let Some(old) = &self.follow.rows else {
            return Ok(());
        };
        let next = branch::analyse_from(&self.sys, &self.state.q, self.state.t, &old.tangent, old);
        match next {
            Some(rows) if rows.k == old.k && rows.sigma_rel < branch::WINDOW_EXIT => {
                // The same forces Aᵀμ on the new rows (orthonormal).
                let n = self.sys.n();
                let force = &mut self.newton.work;
                force.fill(0.0);
                for (row, mu) in old.a.chunks(n).zip(&self.follow.mu) {
                    for (f, x) in force.iter_mut().zip(row) {
                        *f += x * mu;
                    }
                }
                for (row, mu) in rows.a.chunks(n).zip(self.follow.mu.iter_mut()) {
                    *mu = inner(row, force);
                }
                self.follow.rows = Some(rows);
            }
            _ => {
                // The first plain step is checked against the last rows.
                self.follow.guard = self.leave_branch();
                self.accelerations()?;
                self.history.h = 0.0;
            }
        }
        self.watch_singularity();
        Ok(())
    }

    /// Keeps the state as the start of the step.
    fn save(&mut self) {
        self.start.copy_from(&self.state);
    }

    /// Back to the start of the step: its time and state.
    fn restore(&mut self) {
        self.state.copy_from(&self.start);
    }

    /// Takes back an accepted step, to take it again: the state at its
    /// start, the step count and the predictor's history as they were.
    fn take_back(&mut self) {
        self.restore();
        self.history.undo();
        self.diagnostics.summary.steps -= 1;
    }

    /// One step; Ok(false) when Newton did not converge.
    fn try_step(&mut self, h: f64, fresh: bool) -> Result<bool, AnalysisError> {
        Ok(self.attempt(h, fresh, false)? == Attempt::Converged)
    }

    /// One step, with a fresh matrix each iteration when `fresh`; with
    /// `stop_at_singular`, a slow step that finds S singular stops at once
    /// ([`Attempt::MetSingular`]).
    fn attempt(
        &mut self,
        h: f64,
        fresh: bool,
        stop_at_singular: bool,
    ) -> Result<Attempt, AnalysisError> {
        let k = StepCoeffs::new(&self.c, self.state.t, h);
        self.predict(h)?;
        let mut last = f64::INFINITY;
        self.newton.noise = 0.0;
        let mut noise_known = false;
        // Near a singular position Newton converges only linearly (the
        // root is singular); the retry with a fresh matrix each iteration
        // has [`SINGULAR_ITER`] times the iterations.
        let max_iter = if fresh {
            SINGULAR_ITER * self.settings.max_iter
        } else {
            self.settings.max_iter
        };
        for _ in 0..max_iter {
            self.newton_residual(&k)?;
            // The factorization serves steps within rounding of its own.
            let same_h = (h - self.newton.h_factored).abs() <= 1e-6 * h;
            if fresh || !self.newton.aug.is_valid() || !same_h || self.follow.rows.is_some() {
                self.newton_matrix(&k)?;
                // Near a bifurcation point S_ε's regularisation damps the
                // lost direction's correction while Φ barely sees it: a
                // slow mechanism's step would stop on a point off both
                // branches. It is taken along the branch instead
                // ([`Integrator::step`]).
                if stop_at_singular
                    && self.follow.rows.is_none()
                    && self.at_singular_position()
                    && self.slow(h)
                {
                    return Ok(Attempt::MetSingular);
                }
                self.border_matrix()?;
            }
            self.newton_correction(&k);
            self.diagnostics.summary.newton_iterations += 1;
            let Correction {
                dmax,
                theta,
                converged,
            } = self.apply_correction(&k, last);
            if !dmax.is_finite() {
                return Ok(Attempt::Failed);
            }
            if converged {
                self.accept(&k);
                return Ok(Attempt::Converged);
            }
            // A chord iteration that contracts slowly has an old matrix:
            // the next iteration refactors (Newton's quadratic rate
            // reaches the acceleration's bound in one or two iterations
            // where the chord needs several). Corrections near the
            // rounding of the coordinates, and the lost direction at a
            // singular position, converge slowly whatever the matrix.
            let lost = self.at_singular_position() || self.follow.rows.is_some();
            if !lost
                && theta > SLOW
                && dmax <= STALL * last
                && dmax > ABOVE_ROUNDING * newton::rounding(max_abs(&self.state.q))
            {
                self.newton.aug.invalidate();
            }
            // An iteration that stalls has reached the noise of the solve
            // (measured once per attempt; it applies from the next
            // iteration) or needs a fresh matrix: it gets both.
            if dmax > STALL * last {
                if !noise_known {
                    self.measure_noise(k.t1, k.s)?;
                    noise_known = true;
                }
                self.newton.aug.invalidate();
            }
            last = dmax;
        }
        self.newton.aug.invalidate();
        Ok(Attempt::Failed)
    }

    /// The predicted state at the end of a step of `h`: q̈ and λ
    /// extrapolated, a_{n+1}, q and q̇ from them.
    fn predict(&mut self, h: f64) -> Result<(), AnalysisError> {
        let (c, n) = (self.c, self.sys.n());
        let quadratic = self.history.equal_steps(h) && self.regular();
        let s = &mut self.state;
        // a_n ≈ q̈(t_n + (α_m − α_f) h_a) + O(h²) (Arnold & Brüls 2007) for
        // the step h_a that made it; a step of another length h needs
        // q̈(t_n + (α_m − α_f) h), q̈_n + (h/h_a)(a_n − q̈_n) to that order.
        // Left as it is, a change of step costs an error of order
        // |h − h_a| in q̈ that the local error estimate does not see:
        // error-controlled runs, whose steps change all the time, fell to
        // first order (IFToMM A02, atol = 1e-8: 4.5e-3 rad against 9e-5 at
        // a fixed step of the same mean length). Fixed steps that differ by
        // the rounding of t, or a stretch within SLIVER, are left alone.
        if s.h_a > 0.0 && (h - s.h_a).abs() > SLIVER * s.h_a {
            let r = h / s.h_a;
            for (a, qdd) in s.a.iter_mut().zip(&s.qdd) {
                *a = qdd + r * (*a - qdd);
            }
        }
        // Predictor: q̈ and λ extrapolated from the last steps; a_{n+1}
        // and (q, q̇) follow. After three equal steps away from singular
        // positions, quadratically: Newton's first correction is then
        // about the third difference of q̈ over a step, not the second
        // (the slider-crank of the benchmarks at 1 ms: 2e-8 m against
        // 2e-7). Near one the multipliers of the lost direction grow as
        // 1/δ, and a parabola through them overshoots into a spurious
        // root: linearly there, from the last two steps (held constant on
        // the first).
        let p = &self.history;
        if quadratic {
            p.extrapolate_quadratic(&mut s.qdd, &mut s.lambda);
        } else {
            p.extrapolate_linear(h, &mut s.qdd, &mut s.lambda);
        }
        for k in 0..n {
            let a0 = s.a[k];
            let a1 = c.next_a(s.qdd[k], self.start.qdd[k], a0);
            s.q[k] += h * s.qd[k] + h * h * ((0.5 - c.beta) * a0 + c.beta * a1);
            s.qd[k] += h * ((1.0 - c.gamma) * a0 + c.gamma * a1);
        }
        // Near a singular position the multipliers of the lost direction
        // grow as 1/δ with the distance δ from it, and their tension pulls
        // through the constraint curvature towards the position: started
        // from the multipliers of a step nearer to it, Newton converges to
        // a spurious root there (λ ~ 1e9), where the mechanism sticks.
        // When λ grew fast, and faster and faster, in the last steps,
        // Newton starts instead from the multipliers consistent with the
        // predicted state.
        if self.lambda_jumps() {
            self.consistent()?;
            self.state.lambda.copy_from_slice(&self.newton.rhs[n..]);
        }
        Ok(())
    }

    /// Newton's right side −[s R; Φ] at the current iterate into `rhs`:
    /// with the branch rows' forces Aᵀμ in R, and without the residual of
    /// the lost equations the rows replace.
    fn newton_residual(&mut self, k: &StepCoeffs) -> Result<(), AnalysisError> {
        let n = self.sys.n();
        let (r_motion, r_phi) = self.newton.rhs.split_at_mut(n);
        self.sys.residual_and_phi(
            &self.state.q,
            &self.state.qd,
            &self.state.qdd,
            &self.state.lambda,
            k.t1,
            r_motion,
            r_phi,
        )?;
        if let Some(b) = &self.follow.rows {
            for (row, mu) in b.a.chunks(n).zip(&self.follow.mu) {
                for (r, x) in r_motion.iter_mut().zip(row) {
                    *r += x * mu;
                }
            }
        }
        for v in r_motion {
            *v *= -k.s;
        }
        for v in r_phi.iter_mut() {
            *v = -*v;
        }
        // The rows take the place of the lost equations wᵀΦ = 0, which
        // hold along the branch only to the rows' linearisation: their
        // residual is left out, so the two do not pull against each other.
        if let Some(b) = &self.follow.rows {
            for w in b.lost() {
                let c = inner(w, r_phi);
                for (r, x) in r_phi.iter_mut().zip(w) {
                    *r -= c * x;
                }
            }
        }
        Ok(())
    }

    /// Factors Newton's matrix at the current iterate for the step `k`.
    fn newton_matrix(&mut self, k: &StepCoeffs) -> Result<(), AnalysisError> {
        let coefficients = Coefficients {
            mass: k.bp,
            damping: k.gp,
            stiffness: 1.0,
            identity: 0.0,
            scale: k.s,
        };
        let (q, qd, qdd) = (&self.state.q, &self.state.qd, &self.state.qdd);
        if self
            .newton
            .aug
            .refactor(
                &self.sys,
                q,
                qd,
                qdd,
                Some(&self.state.lambda),
                k.t1,
                coefficients,
            )
            .is_err()
        {
            self.newton.h_factored = 0.0;
            return Err(self.error(Kind::LockUp, "the Newton iteration matrix is singular"));
        }
        self.newton.h_factored = k.h;
        self.diagnostics.summary.factorizations += 1;
        Ok(())
    }

    /// Along a branch, the border of the factored matrix,
    /// [S_ε Bᵀ; B −ε I] with B = [A 0]: X = S_ε⁻¹ Bᵀ and the LU of
    /// C = −ε I − B X.
    fn border_matrix(&mut self) -> Result<(), AnalysisError> {
        let n = self.sys.n();
        let (Some(b), Some(lu)) = (&self.follow.rows, &mut self.follow.schur) else {
            return Ok(());
        };
        let nm = self.newton.rhs.len();
        for (x, row) in self.follow.border.chunks_mut(nm).zip(b.a.chunks(n)) {
            x[..n].copy_from_slice(row);
            x[n..].fill(0.0);
            self.newton.aug.solve(x);
        }
        let eps = self.newton.aug.eps();
        let c = faer::Mat::from_fn(b.k, b.k, |v, w| {
            let bx = inner(
                &b.a[v * n..(v + 1) * n],
                &self.follow.border[w * nm..w * nm + n],
            );
            -bx - if v == w { eps } else { 0.0 }
        });
        if lu.factor(c.as_ref()).is_err() {
            self.newton.h_factored = 0.0;
            return Err(self.error(Kind::LockUp, "the Newton iteration matrix is singular"));
        }
        Ok(())
    }

    /// Newton's correction (Δq, s Δλ) into `rhs`: the factored matrix
    /// applied to the right side, through the border along a branch
    /// (updating μ), and cut so that no joint's friction jumps across its
    /// transition band.
    fn newton_correction(&mut self, k: &StepCoeffs) {
        let n = self.sys.n();
        self.newton.aug.solve(&mut self.newton.rhs);
        if let (Some(b), Some(lu)) = (&self.follow.rows, &mut self.follow.schur) {
            // With z = S_ε⁻¹ b₁ in `rhs`: y = C⁻¹ (b₂ − B z) for the
            // rows A (q − q_n) = 0 from the start of the step, then
            // x = z − X y.
            let nm = self.newton.rhs.len();
            let y = &mut self.follow.ext[..b.k];
            for (yw, row) in y.iter_mut().zip(b.a.chunks(n)) {
                let moved = self.state.q.iter().zip(&self.start.q).zip(&self.newton.rhs);
                *yw = -row
                    .iter()
                    .zip(moved)
                    .map(|(a, ((q, q0), dq))| a * (q - q0 + dq))
                    .sum::<f64>();
            }
            lu.solve(y);
            for (x, &yw) in self.follow.border.chunks(nm).zip(y.iter()) {
                for (r, xi) in self.newton.rhs.iter_mut().zip(x) {
                    *r -= xi * yw;
                }
            }
            for (mu, d) in self.follow.mu.iter_mut().zip(y.iter()) {
                *mu += d / k.s;
            }
        }
        // No joint's friction jumps across its transition band.
        let (q, qd) = (&self.state.q, &self.state.qd);
        let theta = self.sys.friction.step_fraction(
            self.sys.model,
            &self.sys.asm,
            q,
            qd,
            &self.newton.rhs,
            k.gp,
            k.t1,
        );
        if theta < 1.0 {
            self.newton.rhs.iter_mut().for_each(|v| *v *= theta);
        }
    }

    /// Applies the correction in `rhs` to (q, q̇, q̈, λ) and tells how
    /// far the iteration is (`last`: the largest |Δq_k| of the iteration
    /// before, infinite on the first).
    fn apply_correction(&mut self, k: &StepCoeffs, last: f64) -> Correction {
        let n = self.sys.n();
        let (bp, gp) = (k.bp, k.gp);
        // The correction applied; its largest |Δq_k| and where (a
        // correction that is not a number leaves them alone).
        let (mut dmax, mut at, mut nan) = (0.0f64, 0, false);
        for i in 0..n {
            let d = self.newton.rhs[i];
            self.state.q[i] += d;
            self.state.qd[i] += gp * d;
            self.state.qdd[i] += bp * d;
            if d.abs() > dmax {
                (dmax, at) = (d.abs(), i);
            }
            nan |= d.is_nan();
        }
        for (l, d) in self.state.lambda.iter_mut().zip(&self.newton.rhs[n..]) {
            *l += d / k.s;
        }
        let theta = if nan { f64::NAN } else { dmax / last };
        let converged = self.converged(k, last, theta, dmax, at, nan);
        Correction {
            dmax,
            theta,
            converged,
        }
    }

    /// Newton's stop test after the correction in `rhs` was applied
    /// (largest |Δq_k| `dmax` at coordinate `at`, contraction `theta`
    /// from the iteration before, whose largest correction was `last`;
    /// `nan` when a correction is not a number).
    ///
    /// Converged when every coordinate's position, velocity and
    /// acceleration corrections (Δq_k, γ'Δq_k, β'Δq_k) are within tol or
    /// the rounding of their own value ([`Self::settles`]), or its
    /// correction is within the rounding noise of the solve. What Newton
    /// leaves of q̈, δq̈, adds γ h δq̈ to q̇ each step, and moves positions
    /// by up to δq̈ t²/2 by time t whatever h: bounding the velocity
    /// correction alone (δq ≤ tol β h/γ) lets that drift grow as 1/h at
    /// a fixed tol. A correction's floor is the rounding of the residual
    /// carried through the solve, `noise`, measured when the iteration
    /// first stalls, and applied from the next iteration, whose matrix
    /// is fresh: at small steps (γ' = γ/(βh) large) or near a singular
    /// position (S ill-conditioned) a velocity's tol can lie below it. A
    /// chord iteration is not stopped at a coarser floor (such as the
    /// rounding of the largest coordinate): it contracts slowly, so what
    /// it leaves is systematic, and at small steps its acceleration β'Δq
    /// adds up over the steps into a drift of the energy and the phase.
    ///
    /// The largest correction decides most iterations alone: within the
    /// noise, or with its position, velocity and acceleration within the
    /// smallest tol of any coordinate, every coordinate has settled; not
    /// settled and above the noise, the step goes on. The other
    /// coordinates are looked at only when neither holds.
    fn converged(
        &self,
        k: &StepCoeffs,
        last: f64,
        theta: f64,
        dmax: f64,
        at: usize,
        nan: bool,
    ) -> bool {
        let n = self.sys.n();
        let d = &self.newton.rhs[..n];
        // (A noise that is not a number settles nothing.)
        if self.newton.noise.is_nan() {
            return false;
        }
        // At a singular position (S_ε factored) the lost direction
        // converges as slowly as an augmented-Lagrangian update; the
        // iteration stops when the position corrections are within tol.
        // Without branch rows S_ε's regularisation damps the lost
        // direction's correction (by σ²/(σ² + ε) at singular value σ): a
        // first correction within tol does not bound the error there, so
        // the iteration goes on at least once more.
        if self.at_singular_position() || self.follow.rows.is_some() {
            let unproven =
                self.at_singular_position() && self.follow.rows.is_none() && last.is_infinite();
            return !unproven
                && (0..n)
                    .all(|i| newton::settled(d[i], self.state.q[i], self.tol_at(self.state.q[i])));
        }
        // With the contraction θ the error left after a correction Δ_k
        // is about θ/(1 − θ) |Δ_k| (Hairer & Wanner IV.8): a slow
        // iteration's correction understates it, a fast one's overstates
        // it. That estimate must pass; where the correction is within
        // [`ESTIMATE_ABOVE_ROUNDING`] times the rounding of the largest
        // coordinate (θ then a ratio of rounding errors), and at the
        // first iteration (θ unknown), the correction itself must too.
        let estimate = if theta < 1.0 {
            theta / (1.0 - theta)
        } else {
            f64::INFINITY
        };
        let above_rounding =
            dmax > ESTIMATE_ABOVE_ROUNDING * newton::rounding(max_abs(&self.state.q));
        let eta = if !last.is_infinite() && above_rounding {
            estimate
        } else {
            estimate.max(1.0)
        };
        if !nan {
            if dmax <= self.newton.noise {
                return true;
            }
            let x = eta * dmax;
            let floor = self.tol_floor();
            if x <= floor && k.gp * x <= floor && k.bp * x <= floor {
                return true;
            }
            let i = at;
            if !self.settles(k, eta, d[i], i) {
                return false;
            }
        }
        // The largest correction of a coordinate that has not settled:
        // within the noise, it has settled too.
        let pending = (0..n)
            .filter(|&i| !self.settles(k, eta, d[i], i))
            .fold(0.0f64, |p, i| p.max(d[i].abs()));
        pending <= self.newton.noise
    }

    /// True when coordinate `i`'s correction `d` (already applied) has
    /// settled: its position, velocity and acceleration corrections
    /// (Δq_i, γ'Δq_i, β'Δq_i), each times `eta` (the error a slow
    /// iteration leaves), are within tol or the rounding of their value
    /// ([`newton::settled`]); a position settled at its rounding settles
    /// its rates too.
    #[inline]
    fn settles(&self, k: &StepCoeffs, eta: f64, d: f64, i: usize) -> bool {
        let (q, tol) = (self.state.q[i], self.tol_at(self.state.q[i]));
        let round = newton::rounding(q);
        let de = eta * d;
        let position = newton::settled(de, q, tol) || d.abs() <= round;
        let velocity = newton::settled(k.gp * de, self.state.qd[i], tol) || d.abs() <= round;
        let acceleration = (k.bp * de).abs() <= tol || d.abs() <= round;
        position && velocity && acceleration
    }

    /// Newton's tolerance at a coordinate of value `q`: `tol`, and in the
    /// error-controlled mode at most [`NEWTON_SHARE`] of the local error
    /// allowed to it, atol + rtol |q|.
    #[inline]
    fn tol_at(&self, q: f64) -> f64 {
        let tol = self.settings.tol;
        match &self.settings.adaptive {
            Some(ad) => tol.min(NEWTON_SHARE * (ad.atol + ad.rtol * q.abs())),
            None => tol,
        }
    }

    /// A tolerance no larger than [`Self::tol_at`] of any coordinate.
    #[inline]
    fn tol_floor(&self) -> f64 {
        let tol = self.settings.tol;
        match &self.settings.adaptive {
            Some(ad) => tol.min(NEWTON_SHARE * ad.atol),
            None => tol,
        }
    }

    /// Ends a converged step `k`: a_{n+1} from q̈_{n+1}, the predictor's
    /// history, t = t₁.
    fn accept(&mut self, k: &StepCoeffs) {
        let c = self.c;
        for i in 0..self.state.a.len() {
            self.state.a[i] = c.next_a(self.state.qdd[i], self.start.qdd[i], self.state.a[i]);
        }
        self.history.push(k.h, &self.start.qdd, &self.start.lambda);
        self.state.h_a = k.h;
        self.state.t = k.t1;
        self.diagnostics.summary.steps += 1;
    }

    /// Records a `near_singular` warning, naming the joints whose
    /// equations lose rank ([`crate::diagnose::weakest_joints`]), when a
    /// step ends at a singular position after one that did not.
    fn watch_singularity(&mut self) {
        let near = self.at_singular_position();
        if near && !self.diagnostics.near_singular {
            let (model, asm) = (self.sys.model, &self.sys.asm);
            let joints = crate::diagnose::weakest_joints(model, asm, &self.state.q, self.state.t);
            self.diagnostics.summary.warnings.push(run::Warning {
                kind: Kind::NearSingular,
                time: self.state.t,
                message: format!(
                    "near-singular configuration{}: the constraint Jacobian loses rank \
                     (a toggle, a dead centre, the flat position of a parallelogram); \
                     the multipliers of the lost direction are not determined here{}",
                    crate::diagnose::losing_rank(&joints),
                    if self.follow.rows.is_some() {
                        "; the motion keeps to the branch nearest to its direction of motion"
                    } else {
                        ""
                    }
                ),
                joints,
            });
        }
        self.diagnostics.near_singular = near;
    }

    /// True when the largest multiplier grew by more than [`LAMBDA_JUMP`]
    /// times in the last step and faster than in the step before (the
    /// 1/δ growth near a singular position, not that of loads building up
    /// from rest, which slows), or by more than [`LAMBDA_LEAP`] times.
    fn lambda_jumps(&self) -> bool {
        let (l0, l1, l2) = (
            max_abs(&self.history.lambda2),
            max_abs(&self.history.lambda),
            max_abs(&self.start.lambda),
        );
        self.history.h > 0.0
            && l2 > LAMBDA_JUMP * l1
            && (l2 * l0 > l1 * l1 || l2 > LAMBDA_LEAP * l1)
    }

    /// True away from singular positions, where the predictor may
    /// extrapolate quadratically: S factored without regularisation, no
    /// branch rows in use or being watched for, and the smallest relative
    /// pivot of the last factorization at least [`QUADRATIC_PIVOT`].
    fn regular(&self) -> bool {
        let f = &self.follow;
        self.newton.aug.eps() == 0.0
            && f.rows.is_none()
            && f.seen.is_none()
            && f.guard.is_none()
            && self
                .newton
                .aug
                .min_pivot()
                .is_some_and(|p| p >= QUADRATIC_PIVOT)
    }

    /// True when the last factorization found S singular in a model
    /// without redundant equations (which always factors S_ε, its lost
    /// directions being exact and harmless): a singular position.
    fn at_singular_position(&self) -> bool {
        self.newton.aug.eps() > 0.0 && self.redundant.is_none()
    }

    /// The rounding noise of a Newton correction at the current iterate
    /// into `noise` (the same level for every coordinate): S⁻¹ applied to the rounding of the
    /// residual, [`newton::ULPS`] ε_mach (|Q| + |M q̈| + |Φ_qᵀλ|) scaled by
    /// `s` in the equations of motion and ULPS ε_mach max |q| in Φ. Small
    /// where S is well conditioned, it sets the floor of the corrections
    /// near a singular position, where it is not.
    fn measure_noise(&mut self, t: f64, s: f64) -> Result<(), AnalysisError> {
        let n = self.sys.n();
        let u = newton::ULPS * f64::EPSILON;
        let (head, tail) = self.newton.rhs.split_at_mut(n);
        self.sys.forces(&self.state.q, &self.state.qd, t, head)?;
        head.iter_mut().for_each(|v| *v = v.abs());
        self.newton.work.fill(0.0);
        self.sys
            .add_mass_times(&self.state.q, &self.state.qdd, &mut self.newton.work);
        self.sys
            .add_jt_lambda(&self.state.q, t, &self.state.lambda, &mut self.newton.work);
        for (h, w) in head.iter_mut().zip(&self.newton.work) {
            *h = u * s * (*h + w.abs());
        }
        tail.fill(u * max_abs(&self.state.q));
        self.newton.aug.solve(&mut self.newton.rhs);
        // One level for all: the pattern of the rounding errors is unknown.
        self.newton.noise = NOISE_SAFETY * max_abs(&self.newton.rhs[..n]);
        Ok(())
    }

    /// The weighted local error estimate of the last step (≤ 1 to accept).
    fn local_error(&self, h: f64, ad: &Adaptive) -> f64 {
        let w = h * h * (self.c.beta - 1.0 / 6.0).abs();
        let mut e = 0.0f64;
        for k in 0..self.state.q.len() {
            let d = w * (self.state.qdd[k] - self.start.qdd[k]);
            e = e.max(d.abs() / (ad.atol + ad.rtol * self.state.q[k].abs()));
        }
        e
    }

    /// Advances to `t_end`: fixed steps of `settings.step` (the last one
    /// shortened to land on `t_end`), or error-controlled steps.
    pub fn advance_to(&mut self, t_end: f64, h_next: &mut f64) -> Result<(), AnalysisError> {
        self.advance_watching(t_end, h_next, &mut || Ok(()))
    }

    /// [`Integrator::advance_to`], calling `tick` before every step; an
    /// error from `tick` stops the run.
    pub fn advance_watching(
        &mut self,
        t_end: f64,
        h_next: &mut f64,
        tick: &mut dyn FnMut() -> Result<(), AnalysisError>,
    ) -> Result<(), AnalysisError> {
        self.advance(t_end, h_next, tick, false)
    }

    /// Advances for an output at `t_out` (s), calling `tick` before every
    /// step; true when `t_out` lies inside the last step, whose state there
    /// is then in [`dense`](Self::dense) ([`dense_output`](Self::dense_output)).
    /// A step lands on `t_out` only when it is within [`SLIVER`] of a whole
    /// fixed step, or at least a quarter of the step the error control
    /// proposes; otherwise the integrator steps on past `t_out`. A later
    /// output time inside the same step is served from it without a step.
    pub fn advance_to_output(
        &mut self,
        t_out: f64,
        h_next: &mut f64,
        tick: &mut dyn FnMut() -> Result<(), AnalysisError>,
    ) -> Result<bool, AnalysisError> {
        self.advance(t_out, h_next, tick, true)?;
        if t_out - self.state.t >= -arrived_within(t_out, self.settings.step) {
            return Ok(false);
        }
        self.dense_output(t_out)?;
        Ok(true)
    }

    /// [`advance_watching`](Self::advance_watching); with `over`, a step
    /// that would land on `t_end` short of a whole step goes past it.
    fn advance(
        &mut self,
        t_end: f64,
        h_next: &mut f64,
        tick: &mut dyn FnMut() -> Result<(), AnalysisError>,
        over: bool,
    ) -> Result<(), AnalysisError> {
        let h_max = self.settings.step;
        let done = arrived_within(t_end, h_max);
        while t_end - self.state.t > done {
            tick()?;
            let left = t_end - self.state.t;
            match self.settings.adaptive.clone() {
                None if over && steps_over(left, h_max) => self.step(h_max)?,
                None => self.step(fixed_step(left, h_max))?,
                Some(ad) => {
                    // The step lands on the output time, or leaves at least
                    // a step's worth: two equal steps rather than one and
                    // a sliver (a sliver's Newton matrix is ill conditioned).
                    let h = h_next.min(h_max);
                    let h = if over && 4.0 * left < h {
                        h
                    } else if h >= left {
                        left
                    } else if h > 0.5 * left {
                        0.5 * left
                    } else {
                        h
                    };
                    // A step below the rounding of t leaves t unchanged.
                    if h < 4.0 * f64::EPSILON * self.state.t.abs()
                        || self.state.t + h == self.state.t
                    {
                        return Err(self.error(
                            Kind::NotConverged,
                            &format!(
                                "the step fell to {} s, below the rounding of t = {} s; \
                             raise h_min or loosen atol/rtol",
                                crate::fmt_num::num(h),
                                crate::fmt_num::num(self.state.t)
                            ),
                        ));
                    }
                    // A step whose Newton fails is rejected like one whose
                    // error is too large, down to h_min.
                    match self.step(h) {
                        Err(e) if e.kind == Kind::NotConverged && h > ad.h_min => {
                            self.history.h = 0.0;
                            self.diagnostics.rejected += 1;
                            *h_next = (0.25 * h).max(ad.h_min);
                            continue;
                        }
                        outcome => outcome?,
                    }
                    let err = self.local_error(h, &ad).max(1e-10);
                    // A PI controller on accepted steps (Gustafsson; Hairer
                    // & Wanner IV.2): the last accepted error damps the
                    // proposal, so h does not oscillate around rejection.
                    let factor = match self.err_prev {
                        Some(prev) if err <= 1.0 => {
                            0.9 * err.powf(-0.7 / 3.0) * prev.powf(0.4 / 3.0)
                        }
                        _ => 0.9 * err.powf(-1.0 / 3.0),
                    }
                    .clamp(0.2, 2.0);
                    if err > 1.0 && h > ad.h_min {
                        // Back to the start of the step, at t₁ − h (which
                        // may differ from t₀ in the last bit; the steps
                        // that follow are taken from there).
                        let t1 = self.state.t;
                        self.take_back();
                        self.state.t = t1 - h;
                        self.diagnostics.rejected += 1;
                        *h_next = (h * factor).max(ad.h_min);
                        continue;
                    }
                    self.err_prev = Some(err);
                    if h != left {
                        *h_next = (h * factor).max(ad.h_min);
                    }
                }
            }
        }
        self.state.t = t_end.max(self.state.t);
        Ok(())
    }
}

/// The step's state at `t` (s) into `d`: q from the cubic Hermite
/// interpolant of (q, q̇) at the step's ends `s0` and `s1` (their times
/// t₀ and t₁), q̇ from that of (q̇, q̈).
fn hermite(d: &mut Dense, t: f64, s0: &State, s1: &State) {
    d.t = t;
    let h = s1.t - s0.t;
    let th = if h > 0.0 {
        ((t - s0.t) / h).clamp(0.0, 1.0)
    } else {
        1.0
    };
    let (t2, t3) = (th * th, th * th * th);
    let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
    let h10 = (t3 - 2.0 * t2 + th) * h;
    let h01 = 3.0 * t2 - 2.0 * t3;
    let h11 = (t3 - t2) * h;
    for k in 0..d.q.len() {
        d.q[k] = h00 * s0.q[k] + h10 * s0.qd[k] + h01 * s1.q[k] + h11 * s1.qd[k];
        d.qd[k] = h00 * s0.qd[k] + h10 * s0.qdd[k] + h01 * s1.qd[k] + h11 * s1.qdd[k];
    }
}

/// [M Φ_qᵀ; Φ_q 0][q̈; λ] = [Q + Q_f(λ); γ] of system `s` at (t, q, q̇) into `rhs`
/// (length n + m), λ of minimum norm; `aug` is refactored for it (q̈
/// enters only terms the coefficients leave out).
fn solve_consistent(
    s: &System,
    aug: &mut Augmented,
    t: f64,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
    rhs: &mut [f64],
) -> Result<(), AnalysisError> {
    let n = s.n();
    let k = Coefficients {
        mass: 1.0,
        scale: 1.0,
        ..Default::default()
    };
    if aug.refactor(s, q, qd, qdd, None, t, k).is_err() {
        let mut message = "the mass matrix is singular on the constraints: give every \
             moving body a mass and an inertia, or constrain the massless ones"
            .to_string();
        if let Err(e) = s.model.check_mass_properties() {
            message.push_str(&format!(" ({e})"));
        }
        return Err(error_at(s, t, q, Kind::SingularMass, &message));
    }
    s.forces(q, qd, t, &mut rhs[..n])?;
    s.asm.gamma(s.model, q, qd, t, &mut rhs[n..]);
    // With joint friction, λ by fixed-point iteration ([`super::friction`]).
    s.friction
        .consistent(s.model, &s.asm, t, q, qd, rhs, &mut |b| {
            aug.solve_refined(b)
        })
}

/// An error at (t, q) of system `s`, naming the joints furthest from
/// Φ = 0 (at most five) and the largest |Φ|.
fn error_at(s: &System, t: f64, q: &[f64], kind: Kind, what: &str) -> AnalysisError {
    let mut phi = vec![0.0; s.m()];
    s.asm.phi(s.model, q, t, &mut phi);
    let (joints, _) = run::worst_joints(s.model, &s.asm, &phi, 0.0);
    AnalysisError::new(kind, t, what).at_joints(joints, max_abs(&phi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::revolute::Revolute;
    use crate::model::{Body, BodyId};

    /// A pendulum pivoted at the origin (frame at the pivot, centroid
    /// 0.5 m out), at 0.3 rad, under gravity.
    fn pendulum() -> Model {
        let mut m = Model::new("pendulum");
        let mut b = Body::new("bob", [0.0, 0.0, 0.3]);
        b.mass = 1.0;
        b.inertia = 0.02;
        b.centroid = [0.5, 0.0];
        let bob = m.add_body(b);
        let pivot = Revolute {
            body_i: BodyId::GROUND,
            s_i: [0.0, 0.0],
            body_j: bob,
            s_j: [0.0, 0.0],
        };
        m.add_joint("pivot", pivot);
        m
    }

    /// The pendulum after ten fixed steps of `h` (s).
    fn swinging(model: &Model, h: f64) -> Integrator<'_> {
        let settings = Settings {
            step: h,
            ..Settings::default()
        };
        let mut it = Integrator::new(model, settings).unwrap();
        for _ in 0..10 {
            it.step(h).unwrap();
        }
        it
    }

    /// Issue 27: a plain step past a window of branch rows that crossed
    /// them is retried along the rows from the start of the step, t to
    /// t + h, and counts once. The rows here hold the pendulum's angle
    /// (A = [0 0 1]), which its swing crosses at once.
    #[test]
    fn issue27_crossed_branch_retry_keeps_the_time() {
        let model = pendulum();
        let h = 1e-3;
        let mut it = swinging(&model, h);
        let (t0, steps) = (it.state.t, it.diagnostics.summary.steps);
        let phi0 = it.state.q[2];
        it.follow.guard = Some(BranchRows::one(
            vec![0.0, 0.0, 1.0],
            vec![1.0, 0.0, 0.0],
            it.sys.m(),
        ));
        it.step(h).unwrap();
        assert_eq!(
            it.state.t,
            t0 + h,
            "the retried step ends at t = {} s",
            it.state.t
        );
        assert_eq!(it.diagnostics.summary.steps, steps + 1);
        // The retry held the rows: the angle of the start of the step.
        assert!(
            (it.state.q[2] - phi0).abs() < 1e-9,
            "φ moved by {}",
            it.state.q[2] - phi0
        );
    }

    /// A push taken back leaves the history as it was: the last two
    /// steps' lengths, q̈ and λ, bit for bit.
    #[test]
    fn a_push_taken_back_leaves_the_history_as_it_was() {
        let mut hist = History::new(2, 1);
        for (i, h) in [1e-3, 2e-3, 3e-3].into_iter().enumerate() {
            let x = i as f64 + 1.0;
            hist.push(h, &[x, -x], &[10.0 * x]);
        }
        let before = hist.clone();
        hist.push(4e-3, &[7.0, 8.0], &[9.0]);
        hist.undo();
        assert_eq!((hist.h, hist.h2), (before.h, before.h2));
        assert_eq!((&hist.qdd, &hist.qdd2), (&before.qdd, &before.qdd2));
        assert_eq!(
            (&hist.lambda, &hist.lambda2),
            (&before.lambda, &before.lambda2)
        );
        // Pushing again gives what a single push gives.
        let mut again = hist.clone();
        let mut once = before.clone();
        again.push(5e-3, &[1.0, 2.0], &[3.0]);
        once.push(5e-3, &[1.0, 2.0], &[3.0]);
        assert_eq!((again.h, again.h2), (once.h, once.h2));
        assert_eq!((&again.qdd, &again.qdd2), (&once.qdd, &once.qdd2));
        assert_eq!(
            (&again.lambda, &again.lambda2),
            (&once.lambda, &once.lambda2)
        );
    }

    /// A step taken back by the crossed-branch retry does not stay in the
    /// predictor's history: after the retry, the step before it is the
    /// one before the retried step, with its λ (the multipliers two steps
    /// back that [`Integrator::lambda_jumps`] compares with).
    #[test]
    fn a_retried_step_leaves_no_trace_in_the_history() {
        let model = pendulum();
        let h = 1e-3;
        let mut it = swinging(&model, h);
        let last_lambda = it.history.lambda.clone();
        let start_lambda = it.state.lambda.clone();
        it.follow.guard = Some(BranchRows::one(
            vec![0.0, 0.0, 1.0],
            vec![1.0, 0.0, 0.0],
            it.sys.m(),
        ));
        it.step(h).unwrap();
        assert_eq!(it.history.lambda, start_lambda);
        assert_eq!(it.history.lambda2, last_lambda);
    }
}
