//! Path generation through three precision points at prescribed crank
//! rotations, in closed form (the dyad standard form of Erdman & Sandor,
//! *Mechanism Design*, ch. 8).
//!
//! The coupler point P passes P₁, P₂, P₃ (global frame, m) while the crank
//! turns by β₂, β₃ (rad) from its angle at P₁. With δ_j = P_j − P₁ each
//! side of the four-bar is a dyad whose links turn from position 1 to
//! position j:
//!
//!   crank side:  W (e^{iβ_j} − 1) + Z (e^{iα_j} − 1) = δ_j,   j = 2, 3,
//!   rocker side: U (e^{iγ_j} − 1) + S (e^{iα_j} − 1) = δ_j,
//!
//! W = A₁ − O₂ (the crank), Z = P₁ − A₁ (crank pin to P), U = B₁ − O₄
//! (the rocker), S = P₁ − B₁ (rocker pin to P), all at position 1; α_j is
//! the coupler's rotation and γ_j the rocker's (rad). The free choices are
//! α₂, α₃ and γ₂, γ₃: given them, each side is two complex equations
//! linear in its two link vectors, solved exactly by Cramer's rule. Then
//! O₂ = P₁ − Z − W, A₁ = P₁ − Z, B₁ = P₁ − S, O₄ = B₁ − U, and the crank
//! angle at P_j is φ_j = arg W + β_j.

use crate::complex::C;
use crate::error::{ErrorKind, SynthError};
use crate::fourbar::{angle, norm, rotate, sub, FourBar, P2};
use crate::path::CouplerLinkage;

/// The problem: three points and the rotations from position 1 to
/// positions 2 and 3 (rad).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThreePoints {
    /// P₁, P₂, P₃ (m).
    pub points: [P2; 3],
    /// β₂, β₃: the crank's rotations (prescribed).
    pub crank: [f64; 2],
    /// α₂, α₃: the coupler's rotations (free choice).
    pub coupler: [f64; 2],
    /// γ₂, γ₃: the rocker's rotations (free choice).
    pub rocker: [f64; 2],
}

/// The dyad (link, coupler side) of `link` rotations and the coupler's
/// `alpha` through displacements `delta`; `None` where the equations are
/// singular (to 1e-12 relative).
fn dyad(link: [f64; 2], alpha: [f64; 2], delta: [C; 2]) -> Option<(C, C)> {
    let one = C(1.0, 0.0);
    let c = [C::cis(link[0]) - one, C::cis(link[1]) - one];
    let a = [C::cis(alpha[0]) - one, C::cis(alpha[1]) - one];
    let det = c[0] * a[1] - c[1] * a[0];
    let size = (c[0].abs() + a[0].abs()) * (c[1].abs() + a[1].abs());
    if det.abs().is_nan() || det.abs() <= 1e-12 * size {
        return None;
    }
    let w = (delta[0] * a[1] - delta[1] * a[0]).div(det);
    let z = (c[0] * delta[1] - c[1] * delta[0]).div(det);
    Some((w, z))
}

/// The four-bar whose coupler point passes the three points at the
/// prescribed crank rotations, and the crank angles there (rad). `fields`
/// name, in errors, the points, the crank's, the coupler's and the
/// rocker's rotations.
pub fn three_points(
    spec: &ThreePoints,
    fields: [&str; 4],
) -> Result<(CouplerLinkage, [f64; 3]), SynthError> {
    let [f_points, _, f_coupler, f_rocker] = fields;
    let [p1, p2, p3] = spec.points.map(|p| C(p[0], p[1]));
    let delta = [p2 - p1, p3 - p1];
    let size = delta[0].abs().max(delta[1].abs());
    let singular = |side: &str, field: &str, other: &str| {
        SynthError::new(
            ErrorKind::NoSolution,
            field,
            format!(
                "the {side} side's equations are singular with these rotations (the coupler turns \
                 as the {side} does, or both stand still); choose other {other} rotations"
            ),
        )
    };
    let (w, z) = dyad(spec.crank, spec.coupler, delta)
        .ok_or_else(|| singular("crank", f_coupler, "coupler"))?;
    let (u, s) = dyad(spec.rocker, spec.coupler, delta)
        .ok_or_else(|| singular("rocker", f_rocker, "rocker"))?;
    let a1 = p1 - z;
    let b1 = p1 - s;
    let (o2, o4) = (a1 - w, b1 - u);
    let none =
        |field: &str, what: &str| SynthError::new(ErrorKind::NoSolution, field, what.to_string());
    if !(o2.0.is_finite() && o2.1.is_finite() && o4.0.is_finite() && o4.1.is_finite()) {
        return Err(none(f_points, "the dyad equations have no finite solution"));
    }
    let tiny = 1e-9 * size;
    if w.abs() <= tiny {
        return Err(none(
            f_coupler,
            "the crank comes out of zero length with these coupler rotations; choose others",
        ));
    }
    if u.abs() <= tiny {
        return Err(none(
            f_rocker,
            "the rocker comes out of zero length with these rotations; choose others",
        ));
    }
    if (b1 - a1).abs() <= tiny || (o4 - o2).abs() <= tiny {
        return Err(none(
            f_rocker,
            "the rocker's dyad is the crank's (rocker rotations equal to the crank's make one \
             dyad twice); choose other rocker rotations",
        ));
    }
    let (a1, b1) = (a1.p(), b1.p());
    let linkage = FourBar {
        o2: o2.p(),
        o4: o4.p(),
        crank: w.abs(),
        coupler: norm(sub(b1, a1)),
        rocker: u.abs(),
    };
    let branch = linkage.branch(a1, b1);
    let mechanism = CouplerLinkage {
        linkage,
        // P₁ in the coupler frame: origin A₁, x towards B₁.
        point: rotate(-angle(sub(b1, a1)), sub(p1.p(), a1)),
        sigma: if branch == 0.0 { 1.0 } else { branch },
    };
    let phi1 = w.arg();
    Ok((
        mechanism,
        [phi1, phi1 + spec.crank[0], phi1 + spec.crank[1]],
    ))
}
