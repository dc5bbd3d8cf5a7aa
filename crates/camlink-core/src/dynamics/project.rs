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
use crate::math::{max_abs, norm2};
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
    let (n, m) = (s.n(), s.m());
    let angles = s.asm.angle_mask(s.model);
    let zeros = vec![0.0; n];
    let mut phi = vec![0.0; m];
    let mut rhs = vec![0.0; n + m];
    let mut trial = q.to_vec();
    for it in 0..=max_iter {
        s.asm.phi(s.model, q, t, &mut phi);
        let r = max_abs(&phi);
        if r <= tol {
            return Ok(it);
        }
        if !r.is_finite() || it == max_iter {
            return Err(ProjectionError {
                kind: if r.is_finite() {
                    Kind::NotConverged
                } else {
                    Kind::NotFinite
                },
                message: if r.is_finite() {
                    format!("the positions did not reach the constraints in {max_iter} iterations")
                } else {
                    "the constraint equations are not finite numbers".into()
                },
                residual: r,
            });
        }
        aug.refactor(s, q, &zeros, &zeros, None, t, IDENTITY)
            .map_err(|_| ProjectionError {
                kind: Kind::LockUp,
                message: "the constraint Jacobian is rank deficient (redundant or locked joints)"
                    .into(),
                residual: r,
            })?;
        rhs[..n].fill(0.0);
        for (k, p) in phi.iter().enumerate() {
            rhs[n + k] = -p;
        }
        aug.solve(&mut rhs);
        let big = (0..n)
            .filter(|&k| angles[k])
            .fold(0.0f64, |a, k| a.max(rhs[k].abs()));
        let mut step = if big > MAX_ANGLE_STEP {
            MAX_ANGLE_STEP / big
        } else {
            1.0
        };
        // Backtrack until ‖Φ‖₂ decreases.
        let r2 = norm2(&phi);
        loop {
            for k in 0..n {
                trial[k] = q[k] + step * rhs[k];
            }
            s.asm.phi(s.model, &trial, t, &mut phi);
            if norm2(&phi) <= (1.0 - 1e-4 * step) * r2 {
                break;
            }
            step *= 0.5;
            if step < 1e-6 {
                return Err(ProjectionError {
                    kind: Kind::NotAssembled,
                    message: "the mechanism cannot be assembled from the given placement".into(),
                    residual: r,
                });
            }
        }
        q.copy_from_slice(&trial);
    }
    unreachable!("the loop returns")
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
    let (n, m) = (s.n(), s.m());
    own_rates(s, q, qd, t);
    let zeros = vec![0.0; n];
    aug.refactor(s, q, &zeros, &zeros, None, t, IDENTITY)
        .map_err(|_| ProjectionError {
            kind: Kind::LockUp,
            message: "the constraint Jacobian is rank deficient (redundant or locked joints)"
                .into(),
            residual: 0.0,
        })?;
    let mut rhs = vec![0.0; n + m];
    rhs[..n].copy_from_slice(qd);
    s.asm.nu(s.model, q, t, &mut rhs[n..]);
    aug.solve_refined(&mut rhs);
    qd.copy_from_slice(&rhs[..n]);
    Ok(())
}
