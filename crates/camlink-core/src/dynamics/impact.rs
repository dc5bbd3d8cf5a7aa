//! The impact of a unilateral cam contact: Newton's restitution law with
//! the impulse along the contact normal, consistent with every other
//! constraint of the mechanism.
//!
//! At the impact (t, q) the contact's equations are closed again. The
//! velocity after the impact q̇⁺ and the impulses Λ (N·s, one per
//! equation) solve, with the augmented matrix of the forward dynamics,
//!
//! ```text
//! [ M  Φ_qᵀ ] [ q̇⁺ ]   [ M q̇⁻  ]
//! [ Φ_q  0  ] [ Λ  ] = [ ν + δ ],
//! ```
//!
//! the momentum balance M (q̇⁺ − q̇⁻) = −Φ_qᵀΛ with every equation's
//! velocity satisfied after the impact, except the contact's along its
//! normal N: there the gap rate is ġ⁺ = −e ġ⁻ (e the coefficient of
//! restitution, ġ⁻ < 0 the approach). With the contact's rows written as
//! the normal (flat-faced follower, row 1: n_fᵀ(P_i − P_j)) or as the
//! point difference P_i − P_j (cam–follower, rows 1–2), δ = e ġ⁻ N on the
//! point rows (their tangential part is taken up by the contact
//! parameters' rates) and δ = e ġ⁻ (Nᵀ n_f) on the normal row. The
//! impulse on body j along N is Λ-derived: NᵀΛ₁₂ or (Nᵀn_f) Λ₁.
//!
//! A joint stop ([`super::stops`]) is the one row Φ = c − c₀ of its
//! coordinate with gap g = σΦ: its weight is w = −σ, so that
//! Φ̇⁺ = −σ e ġ⁻ (ġ⁺ = −e ġ⁻), and its impulse −σΛ pushes the joint back
//! into its range (N·s, or N·m·s for an angle).
//!
//! For e = 0 this is the plastic impact, q̇⁺ the M-orthogonal projection
//! of q̇⁻ onto the closed constraints, losing the kinetic energy
//! ½ m_eff (ġ⁻)², 1/m_eff = J M⁻¹ Jᵀ on the motions the other constraints
//! allow, J the row of ġ in the generalized velocities; for e = 1 kinetic
//! energy is conserved.

use super::system::{Augmented, Coefficients, System};
use crate::constraint::Constraint;
use crate::math::{dot, perp, rot, V2};

/// The post-impact velocity and the normal impulse.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// q̇⁺ (length n of the closed model).
    pub qd: Vec<f64>,
    /// The impulse on body j along N (N·s).
    pub impulse: f64,
}

/// The contact rows of curve-contact joint `j` of system `s` at `q` and
/// their weights w along the normal N (global): the rows' indices among
/// the joint's equations. `None` for a joint that is not a curve contact.
pub fn contact_rows(s: &System, j: usize, q: &[f64], normal: V2) -> Option<Vec<(usize, f64)>> {
    match &s.model.joints[j].constraint {
        Constraint::CamFollower(_) => Some(vec![(0, normal[0]), (1, normal[1])]),
        Constraint::FlatFollower(f) => {
            let body = s.asm.body_col(f.body_j.0);
            let phi_j = body.map_or(0.0, |c| q[c + 2]);
            let n_f = perp(rot(phi_j, f.u_j));
            Some(vec![(0, dot(normal, n_f))])
        }
        _ => None,
    }
}

/// Solves the impact of joint `j` of the closed system `s` at (q, t):
/// `qd` the velocity before (own coordinates' rates need not be set),
/// `rows` the joint's equations along the gap and their weights w (the
/// velocity target of row r is ν_r + e ġ⁻ w_r; [`contact_rows`] for a
/// curve contact), `approach_rate` ġ⁻ (m/s, < 0), `e` the restitution.
/// The impulse is Σ w_r Λ_r. `None` when the matrix is singular.
#[allow(clippy::too_many_arguments)]
pub fn solve(
    s: &System,
    aug: &mut Augmented,
    j: usize,
    q: &[f64],
    qd: &[f64],
    t: f64,
    rows: &[(usize, f64)],
    approach_rate: f64,
    e: f64,
) -> Option<Outcome> {
    let (n, m) = (s.n(), s.m());
    let zeros = vec![0.0; n];
    let k = Coefficients {
        mass: 1.0,
        scale: 1.0,
        ..Default::default()
    };
    aug.refactor(s, q, &zeros, &zeros, None, t, k).ok()?;
    let mut rhs = vec![0.0; n + m];
    s.add_mass_times(q, qd, &mut rhs[..n]);
    s.asm.nu(s.model, q, t, &mut rhs[n..]);
    let r0 = n + s.asm.rows_of(j).start;
    let target = e * approach_rate;
    for &(r, w) in rows {
        rhs[r0 + r] += target * w;
    }
    aug.solve_refined(&mut rhs);
    aug.invalidate();
    let impulse = rows.iter().map(|&(r, w)| w * rhs[r0 + r]).sum();
    rhs.truncate(n);
    Some(Outcome { qd: rhs, impulse })
}
