//! Three-position motion generation (rigid-body guidance) of a four-bar.
//!
//! The coupler carries a line whose three prescribed poses are
//! (x_k, y_k, θ_k), k = 1, 2, 3: the origin r_k = (x_k, y_k) of the line's
//! frame (m) and the line's angle θ_k (rad), in the global frame. The
//! coupler's body frame is that line frame.
//!
//! The free choices are the two moving pivots, each given either
//! - in the coupler frame (a′, m): its global positions are
//!   A_k = r_k + A(θ_k) a′, and the ground pivot O is the circumcentre of
//!   A₁, A₂, A₃ (the centre of the circle through them); or
//! - as its ground pivot O (global, m), by inversion: O seen from the
//!   coupler frame at each pose is o′_k = A(−θ_k)(O − r_k), and the moving
//!   pivot a′ is the circumcentre of o′₁, o′₂, o′₃.
//!
//! Either way |A_k − O| is the same at the three poses, so the dyad O–A
//! guides the coupler through them; two dyads make the four-bar. The
//! first dyad (O₂–A) is the crank, the second (O₄–B) the rocker.

use crate::error::{ErrorKind, SynthError};
use crate::fourbar::{
    add, angle, cross, norm, rotate, sub, wrap_pi, Checks, FourBar, Requirements, P2,
};

/// A pose of the coupler line: origin (x, y) (m) and angle θ (rad).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    pub x: f64,
    pub y: f64,
    pub theta: f64,
}

impl Pose {
    fn origin(&self) -> P2 {
        [self.x, self.y]
    }

    /// The global position of the coupler-frame point `p` (m).
    pub fn place(&self, p: P2) -> P2 {
        add(self.origin(), rotate(self.theta, p))
    }

    /// The coupler-frame coordinates of the global point `p` (m).
    pub fn local(&self, p: P2) -> P2 {
        rotate(-self.theta, sub(p, self.origin()))
    }
}

/// How a dyad's pivots are chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pivot {
    /// The moving pivot in the coupler frame (m).
    Moving(P2),
    /// The ground pivot in the global frame (m).
    Fixed(P2),
}

/// A synthesised four-bar guiding the coupler through the poses.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionSolution {
    pub poses: Vec<Pose>,
    /// The moving pivots A and B in the coupler frame (m).
    pub moving: [P2; 2],
    /// Ground pivots O₂ (crank) and O₄ (rocker); crank and rocker positive.
    pub linkage: FourBar,
    pub checks: Checks,
}

impl MotionSolution {
    /// The global positions of A and B at pose `k` (m).
    pub fn pins(&self, k: usize) -> (P2, P2) {
        (
            self.poses[k].place(self.moving[0]),
            self.poses[k].place(self.moving[1]),
        )
    }
}

/// Relative size under which two points count as one, and the sine of the
/// angle under which three points count as on a line.
const COINCIDENT: f64 = 1e-9;

/// The centre of the circle through `p` (m); `what` names the points in
/// errors (e.g. "the positions of moving pivot A"), `field` the problem
/// field, `size` a length (m) that scales the coincidence test.
fn circumcentre(p: [P2; 3], what: &str, field: &str, size: f64) -> Result<P2, SynthError> {
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        if norm(sub(p[j], p[i])) <= COINCIDENT * size {
            return Err(SynthError::new(
                ErrorKind::Coincident,
                field,
                format!(
                    "{what} at poses {} and {} coincide (the pivot sits at the pole of that \
                     displacement), so no single circle is defined; choose another point",
                    i + 1,
                    j + 1
                ),
            ));
        }
    }
    // Relative to p₀ and scaled to the larger of the two spans, so that the
    // squares below neither overflow nor underflow.
    let (b, c) = (sub(p[1], p[0]), sub(p[2], p[0]));
    let s = norm(b).max(norm(c));
    let (b, c) = ([b[0] / s, b[1] / s], [c[0] / s, c[1] / s]);
    let d = 2.0 * cross(b, c);
    if d.abs() <= 2.0 * COINCIDENT * norm(b) * norm(c) {
        return Err(SynthError::new(
            ErrorKind::Collinear,
            field,
            format!(
                "{what} at the three poses lie on a line: the circle through them has its \
                 centre at infinity (a slider, not a crank); choose another point"
            ),
        ));
    }
    let (bb, cc) = (b[0] * b[0] + b[1] * b[1], c[0] * c[0] + c[1] * c[1]);
    let u = [
        s * (c[1] * bb - b[1] * cc) / d,
        s * (b[0] * cc - c[0] * bb) / d,
    ];
    Ok(add(p[0], u))
}

fn out_of_range(field: &str) -> SynthError {
    SynthError::new(
        ErrorKind::Invalid,
        field,
        "the poses and pivots are out of the range of floating-point numbers; give them in \
         metres of a machine's size",
    )
}

/// Solves one dyad: (moving pivot in the coupler frame, ground pivot).
pub(crate) fn dyad(
    poses: &[Pose; 3],
    pivot: Pivot,
    name: &str,
    field: &str,
    size: f64,
) -> Result<(P2, P2), SynthError> {
    match pivot {
        Pivot::Moving(m) => {
            let at = [poses[0].place(m), poses[1].place(m), poses[2].place(m)];
            let what = format!("the positions of moving pivot {name}");
            Ok((m, circumcentre(at, &what, field, size)?))
        }
        Pivot::Fixed(o) => {
            let seen = [poses[0].local(o), poses[1].local(o), poses[2].local(o)];
            let what = format!("ground pivot {name} seen from the coupler frame");
            Ok((circumcentre(seen, &what, field, size)?, o))
        }
    }
}

/// The four-bar whose coupler passes through the three `poses` with the
/// crank's pivot chosen by `crank` and the rocker's by `rocker`; checked
/// against `req`.
///
/// Errors: two coincident poses, a pivot whose positions coincide or lie
/// on a line, a crank or rocker of zero length, coincident ground or
/// moving pivots. `fields` names the problem fields of (poses, crank,
/// rocker) for the errors.
pub fn three_positions(
    poses: &[Pose; 3],
    crank: Pivot,
    rocker: Pivot,
    req: &Requirements,
    fields: [&str; 3],
) -> Result<MotionSolution, SynthError> {
    let pivot_size = |p: Pivot| match p {
        Pivot::Moving(v) | Pivot::Fixed(v) => norm(v),
    };
    let mut size = pivot_size(crank).max(pivot_size(rocker));
    for p in poses {
        size = size.max(norm(sub(p.origin(), poses[0].origin())));
    }
    if !size.is_finite() {
        return Err(out_of_range(fields[0]));
    }
    let size = size.max(f64::MIN_POSITIVE);
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        let (p, q) = (poses[i], poses[j]);
        if norm(sub(q.origin(), p.origin())) <= COINCIDENT * size
            && wrap_pi(q.theta - p.theta).abs() <= COINCIDENT
        {
            return Err(SynthError::new(
                ErrorKind::Coincident,
                fields[0],
                format!(
                    "poses {} and {} coincide; three distinct poses are needed",
                    i + 1,
                    j + 1
                ),
            ));
        }
    }
    let (a, o2) = dyad(poses, crank, "A", fields[1], size)?;
    let (b, o4) = dyad(poses, rocker, "B", fields[2], size)?;
    if norm(sub(b, a)) <= COINCIDENT * size {
        return Err(SynthError::new(
            ErrorKind::NoSolution,
            fields[2],
            "the moving pivots A and B coincide: the coupler would have no length",
        ));
    }
    if norm(sub(o4, o2)) <= COINCIDENT * size {
        return Err(SynthError::new(
            ErrorKind::NoSolution,
            fields[2],
            "the ground pivots of the crank and the rocker coincide: the ground link would have \
             no length",
        ));
    }
    let a1 = poses[0].place(a);
    let b1 = poses[0].place(b);
    let linkage = FourBar {
        o2,
        o4,
        crank: norm(sub(a1, o2)),
        coupler: norm(sub(b, a)),
        rocker: norm(sub(b1, o4)),
    };
    let numbers = [o2[0], o2[1], o4[0], o4[1], a[0], a[1], b[0], b[1]];
    if numbers.iter().any(|v| !v.is_finite())
        || !linkage.crank.is_finite()
        || !linkage.rocker.is_finite()
    {
        return Err(out_of_range(fields[0]));
    }
    for (len, name, field) in [
        (linkage.crank, "crank", fields[1]),
        (linkage.rocker, "rocker", fields[2]),
    ] {
        if len <= COINCIDENT * size {
            return Err(SynthError::new(
                ErrorKind::NoSolution,
                field,
                format!("the {name} has no length: its moving pivot stays on its ground pivot"),
            ));
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

/// The coupler frame's pose when A and B, its points `a_local` and
/// `b_local` (coupler frame, m), are at `a` and `b` (global, m).
pub fn coupler_pose(a_local: P2, b_local: P2, a: P2, b: P2) -> Pose {
    let theta = angle(sub(b, a)) - angle(sub(b_local, a_local));
    let r = sub(a, rotate(theta, a_local));
    Pose {
        x: r[0],
        y: r[1],
        theta,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FIELDS: [&str; 3] = ["synthesis.poses", "synthesis.crank", "synthesis.rocker"];

    fn poses() -> [Pose; 3] {
        [
            Pose {
                x: 0.0,
                y: 0.0,
                theta: 0.0,
            },
            Pose {
                x: 0.1,
                y: 0.05,
                theta: 0.3,
            },
            Pose {
                x: 0.18,
                y: 0.02,
                theta: 0.7,
            },
        ]
    }

    #[test]
    fn pivots_keep_their_distances() {
        let req = Requirements::default();
        let s = three_positions(
            &poses(),
            Pivot::Moving([-0.05, -0.02]),
            Pivot::Moving([0.08, 0.01]),
            &req,
            FIELDS,
        )
        .unwrap();
        for k in 0..3 {
            let (a, b) = s.pins(k);
            assert!((norm(sub(a, s.linkage.o2)) - s.linkage.crank).abs() < 1e-13);
            assert!((norm(sub(b, s.linkage.o4)) - s.linkage.rocker).abs() < 1e-13);
        }
    }

    #[test]
    fn fixed_pivots_invert_to_the_same_linkage() {
        let req = Requirements::default();
        let s = three_positions(
            &poses(),
            Pivot::Moving([-0.05, -0.02]),
            Pivot::Moving([0.08, 0.01]),
            &req,
            FIELDS,
        )
        .unwrap();
        let t = three_positions(
            &poses(),
            Pivot::Fixed(s.linkage.o2),
            Pivot::Fixed(s.linkage.o4),
            &req,
            FIELDS,
        )
        .unwrap();
        for k in 0..2 {
            let d = norm(sub(s.moving[k], t.moving[k]));
            assert!(d < 1e-12, "moving pivot {k} off by {d}");
        }
    }

    #[test]
    fn coincident_poses_are_refused() {
        let mut p = poses();
        p[2] = p[0];
        let e = three_positions(
            &p,
            Pivot::Moving([0.0, 0.1]),
            Pivot::Moving([0.1, 0.0]),
            &Requirements::default(),
            FIELDS,
        )
        .unwrap_err();
        assert_eq!(e.kind, ErrorKind::Coincident);
        assert_eq!(
            e.to_string(),
            "synthesis.poses: poses 1 and 3 coincide; three distinct poses are needed"
        );
    }

    #[test]
    fn translation_along_a_line_leaves_a_pivot_collinear() {
        let p = [
            Pose {
                x: 0.0,
                y: 0.0,
                theta: 0.2,
            },
            Pose {
                x: 0.1,
                y: 0.0,
                theta: 0.2,
            },
            Pose {
                x: 0.3,
                y: 0.0,
                theta: 0.2,
            },
        ];
        let e = three_positions(
            &p,
            Pivot::Moving([0.0, 0.1]),
            Pivot::Moving([0.1, 0.0]),
            &Requirements::default(),
            FIELDS,
        )
        .unwrap_err();
        assert_eq!(e.kind, ErrorKind::Collinear);
        assert_eq!(e.field.as_deref(), Some("synthesis.crank"));
    }
}
