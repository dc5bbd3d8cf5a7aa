//! Two-position motion generation (rigid-body guidance) of a four-bar, in
//! closed form.
//!
//! Poses (x_k, y_k, θ_k), k = 1, 2, as in [`crate::motion`]. Each dyad is
//! chosen by one of its pivots and a signed distance t (m) along a
//! perpendicular bisector:
//! - a moving pivot a′ (coupler frame): its positions A₁, A₂; the ground
//!   pivot is O = (A₁ + A₂)/2 + t·n, n the unit normal of A₁→A₂ turned
//!   +90° (to its left);
//! - a ground pivot O (global): seen from the coupler frame at the poses,
//!   o′_k = A(−θ_k)(O − r_k); the moving pivot is
//!   a′ = (o′₁ + o′₂)/2 + t·n′, n′ the left normal of o′₁→o′₂.
//!
//! Either way |A₁ − O| = |A₂ − O|: the dyad takes the coupler from pose 1
//! to pose 2.

use crate::error::{ErrorKind, SynthError};
use crate::fourbar::{add, norm, sub, wrap_pi, Checks, FourBar, Requirements, P2};
use crate::motion::{MotionSolution, Pivot, Pose};

const COINCIDENT: f64 = 1e-9;

/// The point at signed distance `t` (m) along the perpendicular bisector
/// of `p`→`q` from its midpoint, to the left of `p`→`q`; `None` where `p`
/// and `q` coincide (to 1e-9 of `size`).
pub fn on_bisector(p: P2, q: P2, t: f64, size: f64) -> Option<P2> {
    let d = sub(q, p);
    let l = norm(d);
    if l <= COINCIDENT * size {
        return None;
    }
    let n = [-d[1] / l, d[0] / l];
    Some(add(
        [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])],
        [t * n[0], t * n[1]],
    ))
}

/// One dyad: (moving pivot in the coupler frame, ground pivot).
pub fn dyad(
    poses: &[Pose; 2],
    pivot: Pivot,
    t: f64,
    name: &str,
    field: &str,
    size: f64,
) -> Result<(P2, P2), SynthError> {
    let pole = |what: &str| {
        SynthError::new(
            ErrorKind::Coincident,
            field,
            format!(
                "{what} {name} is at the same place at both poses (the pole of the \
                 displacement): every point is a centre for it and no bisector is defined; \
                 choose another point"
            ),
        )
    };
    match pivot {
        Pivot::Moving(m) => {
            let (a1, a2) = (poses[0].place(m), poses[1].place(m));
            let o = on_bisector(a1, a2, t, size).ok_or_else(|| pole("moving pivot"))?;
            Ok((m, o))
        }
        Pivot::Fixed(o) => {
            let (o1, o2) = (poses[0].local(o), poses[1].local(o));
            let m = on_bisector(o1, o2, t, size).ok_or_else(|| pole("ground pivot"))?;
            Ok((m, o))
        }
    }
}

/// The four-bar that takes the coupler from `poses[0]` to `poses[1]`,
/// its crank and rocker chosen by `crank`, `rocker` and the bisector
/// distances `along` (m); checked against `req`. `fields` names the
/// problem fields of (poses, crank, rocker).
pub fn two_positions(
    poses: &[Pose; 2],
    crank: Pivot,
    rocker: Pivot,
    along: [f64; 2],
    req: &Requirements,
    fields: [&str; 3],
) -> Result<MotionSolution, SynthError> {
    let scale = crate::burmester::check_poses(poses, fields[0])?;
    let pv = |p: Pivot| match p {
        Pivot::Moving(v) | Pivot::Fixed(v) => norm(v),
    };
    let size = scale
        .max(pv(crank))
        .max(pv(rocker))
        .max(along[0].abs())
        .max(along[1].abs());
    if !size.is_finite() {
        return Err(SynthError::new(
            ErrorKind::Invalid,
            fields[0],
            "the poses and pivots are out of the range of floating-point numbers",
        ));
    }
    if norm(sub([poses[1].x, poses[1].y], [poses[0].x, poses[0].y])) <= COINCIDENT * size
        && wrap_pi(poses[1].theta - poses[0].theta).abs() <= COINCIDENT
    {
        return Err(SynthError::new(
            ErrorKind::Coincident,
            fields[0],
            "poses 1 and 2 coincide; two distinct poses are needed",
        ));
    }
    let (a, o2) = dyad(poses, crank, along[0], "A", fields[1], size)?;
    let (b, o4) = dyad(poses, rocker, along[1], "B", fields[2], size)?;
    let linkage = FourBar {
        o2,
        o4,
        crank: norm(sub(poses[0].place(a), o2)),
        coupler: norm(sub(b, a)),
        rocker: norm(sub(poses[0].place(b), o4)),
    };
    for (len, what, field) in [
        (linkage.crank, "the crank has no length", fields[1]),
        (linkage.rocker, "the rocker has no length", fields[2]),
        (
            linkage.coupler,
            "the moving pivots A and B coincide",
            fields[2],
        ),
        (linkage.ground(), "the ground pivots coincide", fields[2]),
    ] {
        if len <= COINCIDENT * size {
            return Err(SynthError::new(ErrorKind::NoSolution, field, what));
        }
    }
    let pins: Vec<P2> = poses.iter().map(|p| p.place(a)).collect();
    let rockers: Vec<P2> = poses.iter().map(|p| p.place(b)).collect();
    let checks = Checks::of(&linkage, &pins, &rockers, req, None);
    Ok(MotionSolution {
        poses: poses.to_vec(),
        moving: [a, b],
        linkage,
        checks,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_pivots_keep_their_distances_and_inversion_agrees() {
        let poses = [
            Pose {
                x: 0.0,
                y: 0.0,
                theta: 0.1,
            },
            Pose {
                x: 0.12,
                y: 0.04,
                theta: 0.6,
            },
        ];
        let f = ["poses", "crank", "rocker"];
        let req = Requirements::default();
        let s = two_positions(
            &poses,
            Pivot::Moving([-0.03, -0.05]),
            Pivot::Moving([0.06, -0.04]),
            [0.1, -0.15],
            &req,
            f,
        )
        .unwrap();
        for k in 0..2 {
            let (a, b) = s.pins(k);
            assert!((norm(sub(a, s.linkage.o2)) - s.linkage.crank).abs() < 1e-15);
            assert!((norm(sub(b, s.linkage.o4)) - s.linkage.rocker).abs() < 1e-15);
        }
        // The ground pivots given back, each on its moving pivot's bisector.
        let t = |o: P2, m: P2| {
            let (o1, o2) = (poses[0].local(o), poses[1].local(o));
            let d = sub(o2, o1);
            let l = norm(d);
            let mid = [0.5 * (o1[0] + o2[0]), 0.5 * (o1[1] + o2[1])];
            let r = sub(m, mid);
            (-d[1] * r[0] + d[0] * r[1]) / l
        };
        let back = two_positions(
            &poses,
            Pivot::Fixed(s.linkage.o2),
            Pivot::Fixed(s.linkage.o4),
            [t(s.linkage.o2, s.moving[0]), t(s.linkage.o4, s.moving[1])],
            &req,
            f,
        )
        .unwrap();
        for k in 0..2 {
            assert!(norm(sub(back.moving[k], s.moving[k])) < 1e-14);
        }
    }
}
