//! Consistent initial conditions: positions and velocities projected onto
//! the constraints.
//!
//! Positions: the nearest q (in the Euclidean norm of the coordinates) with
//! Φ(q, t) = 0, by Newton steps of least change,
//!
//! [ I  Φ_qᵀ ; Φ_q  0 ] [Δq ; μ] = [0 ; −Φ],
//!
//! with angle steps limited to [`MAX_ANGLE_STEP`] and a backtracking line
//! search on ‖Φ‖₂, so that a rough placement lands on the nearest branch.
//!
//! Velocities: the nearest q̇ to the given q̇₀ with Φ_q q̇ = ν,
//!
//! [ I  Φ_qᵀ ; Φ_q  0 ] [q̇ ; μ] = [q̇₀ ; ν].

use super::system::{Augmented, Coefficients, System};
use crate::constraint::{Equations, Jac, MAX_OWN};
use crate::kinematics::MAX_ANGLE_STEP;
use crate::newton::{self, Failure};
use crate::run::Kind;

/// The projection matrix's coefficients: D = I.
pub const IDENTITY: Coefficients = Coefficients {
    mass: 0.0,
    damping: 0.0,
    stiffness: 0.0,
    identity: 1.0,
    scale: 1.0,
};

/// Why a projection failed, with the largest |Φ| reached.
#[derive(Clone, Debug, PartialEq)]
pub struct ProjectionError {
    pub kind: Kind,
    pub message: String,
    pub residual: f64,
}

/// The scratch of the projections of one system, made once: a projection
/// in the time loop ([`positions_in`], [`velocities_in`]) allocates nothing.
pub struct Workspace {
    /// Which coordinates are angles (their Newton steps are limited).
    angles: Vec<bool>,
    /// n zeros: q̇ and q̈ of the projection matrix.
    zeros: Vec<f64>,
    /// [Δq ; μ] or [q̇ ; μ] (length n + m).
    rhs: Vec<f64>,
    newton: newton::Workspace,
}

impl Workspace {
    pub fn new(s: &System) -> Self {
        let (n, m) = (s.n(), s.m());
        Workspace {
            angles: s.asm.angle_mask(s.model),
            zeros: vec![0.0; n],
            rhs: vec![0.0; n + m],
            newton: newton::Workspace::new(n, m),
        }
    }
}

/// Projects `q` onto Φ(q, t) = 0 (to max |Φ| ≤ `tol`); returns the Newton
/// iterations used.
pub fn positions(
    s: &System,
    aug: &mut Augmented,
    q: &mut [f64],
    t: f64,
    tol: f64,
    max_iter: usize,
) -> Result<usize, ProjectionError> {
    positions_in(s, aug, q, t, tol, max_iter, &mut Workspace::new(s))
}

/// [`positions`] with the scratch `w` (made for `s`).
pub fn positions_in(
    s: &System,
    aug: &mut Augmented,
    q: &mut [f64],
    t: f64,
    tol: f64,
    max_iter: usize,
    w: &mut Workspace,
) -> Result<usize, ProjectionError> {
    let Workspace {
        angles,
        zeros,
        rhs,
        newton: work,
    } = w;
    let mut problem = LeastChange {
        s,
        aug,
        t,
        tol,
        zeros,
        rhs,
    };
    let options = newton::Options {
        max_iter,
        line_search: Some(newton::LineSearch {
            min_step: 1e-6,
            stall: newton::Stall::Fail,
        }),
        angle_limit: Some((MAX_ANGLE_STEP, &angles[..])),
        polish: false,
    };
    newton::solve(&mut problem, q, work, &options)
        .map(|solved| solved.iterations)
        .map_err(|e| {
            let (kind, message) = match e.why {
                Failure::NotFinite => (
                    Kind::NotFinite,
                    "the constraint equations are not finite numbers".to_string(),
                ),
                Failure::Iterations => (
                    Kind::NotConverged,
                    format!("the positions did not reach the constraints in {max_iter} iterations"),
                ),
                Failure::NoDescent => (
                    Kind::NotAssembled,
                    "the mechanism cannot be assembled from the given placement".to_string(),
                ),
                Failure::Direction(()) => (
                    Kind::LockUp,
                    "the constraint Jacobian is rank deficient (redundant or locked joints)"
                        .to_string(),
                ),
            };
            ProjectionError {
                kind,
                message,
                residual: e.size,
            }
        })
}

/// Φ(q, t) = 0 as a [`newton::Problem`] in q with steps of least change,
/// [ I  Φ_qᵀ ; Φ_q  0 ] [Δq ; μ] = [0 ; −Φ]; converged when max |Φ| ≤ tol.
struct LeastChange<'a> {
    s: &'a System<'a>,
    aug: &'a mut Augmented,
    t: f64,
    tol: f64,
    zeros: &'a [f64],
    /// [Δq ; μ] (length n + m).
    rhs: &'a mut [f64],
}

impl newton::Problem for LeastChange<'_> {
    type Error = ();

    fn residual(&mut self, q: &[f64], phi: &mut [f64]) -> newton::Measure {
        self.s.asm.phi(self.s.model, q, self.t, phi);
        newton::Measure::max_abs(phi, self.tol)
    }

    fn direction(
        &mut self,
        q: &[f64],
        phi: &[f64],
        dq: &mut [f64],
        _: newton::Progress,
    ) -> Result<(), ()> {
        let (s, n) = (self.s, self.zeros.len());
        self.aug
            .refactor(s, q, self.zeros, self.zeros, None, self.t, IDENTITY)
            .map_err(|_| ())?;
        self.rhs[..n].fill(0.0);
        for (r, p) in self.rhs[n..].iter_mut().zip(phi) {
            *r = -p;
        }
        self.aug.solve(self.rhs);
        dq.copy_from_slice(&self.rhs[..n]);
        Ok(())
    }
}

/// Sets the rates of the joints' own coordinates (contact parameters,
/// centre-line angles) from the bodies' velocities in `qd`: for each joint,
/// the least-squares solution of Φ_own α̇ = ν − Φ_bodies q̇_bodies. The
/// model gives body velocities only, so this keeps a projection from
/// sharing a given speed with the contact parameters.
fn own_rates(s: &System, q: &[f64], qd: &mut [f64], t: f64) {
    let mut jac = Jac::default();
    let mut nu = [0.0; 3];
    for (j, joint) in s.model.joints.iter().enumerate() {
        let c = &joint.constraint;
        let k = c.own_count();
        if k == 0 {
            continue;
        }
        let mut x = s.asm.local(s.model, j, q, qd, t);
        x.own_d = [0.0; MAX_OWN];
        c.jacobian(&x, &mut jac);
        c.nu(&x, &mut nu);
        // r = ν − Φ_bodies q̇_bodies, then the normal equations in α̇.
        let mut ata = [[0.0; MAX_OWN]; MAX_OWN];
        let mut atr = [0.0; MAX_OWN];
        for (r, &nu_r) in nu.iter().enumerate().take(c.rows()) {
            let mut res = nu_r;
            for (block, qd_b) in jac.body.iter().zip(&x.qd) {
                res -= block[r].iter().zip(qd_b).map(|(j, v)| j * v).sum::<f64>();
            }
            let own = &jac.own[r][..k];
            for (a, &ja) in own.iter().enumerate() {
                atr[a] += ja * res;
                for (b, &jb) in own.iter().enumerate() {
                    ata[a][b] += ja * jb;
                }
            }
        }
        let rates = if k == 1 {
            [atr[0] / ata[0][0], 0.0]
        } else {
            let det = ata[0][0] * ata[1][1] - ata[0][1] * ata[1][0];
            [
                (atr[0] * ata[1][1] - ata[0][1] * atr[1]) / det,
                (ata[0][0] * atr[1] - atr[0] * ata[1][0]) / det,
            ]
        };
        if rates[..k].iter().all(|v| v.is_finite()) {
            let o = s.asm.own_col(j);
            qd[o..o + k].copy_from_slice(&rates[..k]);
        }
    }
}

/// Projects `qd` onto Φ_q q̇ = ν at a consistent `q`, after setting the
/// own coordinates' rates from the bodies' velocities.
pub fn velocities(
    s: &System,
    aug: &mut Augmented,
    q: &[f64],
    qd: &mut [f64],
    t: f64,
) -> Result<(), ProjectionError> {
    velocities_in(s, aug, q, qd, t, &mut Workspace::new(s))
}

/// [`velocities`] with the scratch `w` (made for `s`).
pub fn velocities_in(
    s: &System,
    aug: &mut Augmented,
    q: &[f64],
    qd: &mut [f64],
    t: f64,
    w: &mut Workspace,
) -> Result<(), ProjectionError> {
    let n = s.n();
    own_rates(s, q, qd, t);
    let zeros = &w.zeros;
    aug.refactor(s, q, zeros, zeros, None, t, IDENTITY)
        .map_err(|_| ProjectionError {
            kind: Kind::LockUp,
            message: "the constraint Jacobian is rank deficient (redundant or locked joints)"
                .into(),
            residual: 0.0,
        })?;
    let rhs = &mut w.rhs;
    rhs[..n].copy_from_slice(qd);
    s.asm.nu(s.model, q, t, &mut rhs[n..]);
    aug.solve_refined(rhs);
    qd.copy_from_slice(&rhs[..n]);
    Ok(())
}
