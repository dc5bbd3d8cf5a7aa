//! The Roberts–Chebyshev cognates: the two other four-bars whose coupler
//! points trace the same coupler curve as a given four-bar's.
//!
//! In complex numbers (global frame, m), at one position of the given
//! linkage O₂–A–B–O₄ with coupler point P, let z = (P − A)/(B − A) (the
//! coupler triangle's shape) and w = 1 − z = (P − B)/(A − B). The third
//! ground pivot is O₃ = O₂ + z (O₄ − O₂) (triangle O₂O₄O₃ similar to ABP).
//! - Cognate 1, pivots O₂ and O₃: crank pin A₁ = O₂ + (P − A) (a
//!   parallelogram O₂APA₁), rocker pin C₁ = A₁ + z (A − O₂), so that
//!   C₁ − O₃ = z (B − O₄): crank |P − A|, coupler |z|·a, rocker |z|·c;
//!   P − A₁ = A − O₂.
//! - Cognate 2, pivots O₄ and O₃: crank pin B₂ = O₄ + (P − B), rocker pin
//!   C₂ = B₂ + w (B − O₄), so that C₂ − O₃ = w (A − O₂): crank |P − B|,
//!   coupler |w|·c, rocker |w|·a; P − B₂ = B − O₄.
//!
//! Each vector relation holds at every position, so each cognate keeps one
//! link parallel to the given crank, turned by a fixed angle: cognate 1's
//! coupler A₁C₁ (by arg z) and cognate 2's rocker O₃C₂ (by arg w). Driving
//! that link at the given crank's angle plus its offset makes each
//! cognate's P coincide with the given P at every instant.

use crate::fourbar::{add, angle, norm, sub, FourBar, P2};
use crate::path::CouplerLinkage;

fn cmul(p: P2, q: P2) -> P2 {
    [p[0] * q[0] - p[1] * q[1], p[0] * q[1] + p[1] * q[0]]
}

fn cdiv(p: P2, q: P2) -> P2 {
    let d = q[0] * q[0] + q[1] * q[1];
    [
        (p[0] * q[0] + p[1] * q[1]) / d,
        (p[1] * q[0] - p[0] * q[1]) / d,
    ]
}

/// A cognate: its linkage with the coupler point, and which of its links
/// turns with the given crank.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cognate {
    pub mechanism: CouplerLinkage,
    /// The body of the cognate's model that turns with the given crank:
    /// `"coupler"` (cognate 1) or `"rocker"` (cognate 2).
    pub driven: &'static str,
    /// That body's angle minus the given crank's angle (rad), constant.
    pub offset: f64,
    /// Its crank angle, A and B, at the given linkage's position used.
    pub crank_angle: f64,
    pub a: P2,
    pub b: P2,
}

/// The two cognates of `given`, built at its position at crank angle
/// `phi` (rad); `None` where it does not assemble or the coupler point
/// lies on A or B (a cognate would then have a link of length 0).
pub fn cognates(given: &CouplerLinkage, phi: f64) -> Option<[Cognate; 2]> {
    let (a, b, p) = given.trace(phi)?;
    let (o2, o4) = (given.linkage.o2, given.linkage.o4);
    let size = norm(sub(b, a));
    if norm(sub(p, a)) <= 1e-9 * size || norm(sub(p, b)) <= 1e-9 * size {
        return None;
    }
    let z = cdiv(sub(p, a), sub(b, a));
    let w = [1.0 - z[0], -z[1]];
    let o3 = add(o2, cmul(z, sub(o4, o2)));
    let a1 = add(o2, sub(p, a));
    let c1 = add(a1, cmul(z, sub(a, o2)));
    let b2 = add(o4, sub(p, b));
    let c2 = add(b2, cmul(w, sub(b, o4)));
    let make = |g1: P2, g2: P2, m: P2, n: P2, driven, offset: f64| {
        let linkage = FourBar {
            o2: g1,
            o4: g2,
            crank: norm(sub(m, g1)),
            coupler: norm(sub(n, m)),
            rocker: norm(sub(n, g2)),
        };
        let sigma = linkage.branch(m, n);
        let local = crate::motion::Pose {
            x: m[0],
            y: m[1],
            theta: angle(sub(n, m)),
        }
        .local(p);
        Cognate {
            mechanism: CouplerLinkage {
                linkage,
                point: local,
                sigma,
            },
            driven,
            offset,
            crank_angle: angle(sub(m, g1)),
            a: m,
            b: n,
        }
    };
    Some([
        make(o2, o3, a1, c1, "coupler", angle(z)),
        make(o4, o3, b2, c2, "rocker", angle(w)),
    ])
}
