//! Contact outputs of the curve-contact joints: the global contact point and
//! the pressure angle.
//!
//! For every cam–follower, cam–flat-faced follower and point–follower joint,
//! channels `<joint>.cx` and `<joint>.cy` give the contact point in the
//! global frame (m): the point of C_i at α_i for the cam joints, the pin for
//! the point–follower. (The contact parameters themselves are the joint's
//! own coordinates, `<joint>.alpha_i` / `<joint>.alpha_j`.)
//!
//! `<joint>.pressure_angle` (rad, 0 to π/2) is the angle between the contact
//! normal n (the line along which a frictionless contact pushes) and the
//! direction of motion d of the follower, |∠(n, d)| folded into [0, π/2]:
//!
//! - n: the normal to C_i at the contact (cam–follower), the face normal
//!   (flat-faced follower), the slot's normal (point–follower);
//! - d: the follower's guide direction when the follower translates (a
//!   `translational` joint to the ground), or, when it turns about a fixed
//!   pivot O (a `revolute` joint to the ground), the perpendicular to the arm
//!   O→P, where P is the follower's reference point: the roller centre when
//!   the follower's curve is a circle or an arc, else the contact point.
//!   A roller pinned (`revolute`) to a guided body is followed through that
//!   body, with P the pin.
//!
//! Which body is the follower is decided once, from the model's structure:
//! the flat-faced follower's face body and the point–follower's pin body
//! are followers by definition, unless that body is the ground (a fixed
//! face or slot: then the other body follows). For a cam–follower pair the
//! follower is the body that translates, else the one that is not driven,
//! else body j. A follower with no such guide gets no pressure angle.

use crate::assembly::Assembly;
use crate::constraint::{Constraint, Equations};
use crate::curve::Curve;
use crate::math::{cross, dot, norm, perp, point, rot, scale, sub, V2};
use crate::model::{BodyId, Model};

/// How a follower body is guided by the ground.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Guide {
    /// Translation along `axis`, fixed in the frame of `frame` (m/m).
    Translation { frame: BodyId, axis: V2 },
    /// Rotation about the ground point `pivot` (m, global).
    Pivot { pivot: V2 },
}

/// The follower of one contact joint and how it moves.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Follower {
    guide: Guide,
    /// The reference point P: a point fixed in `body` (body frame, m), or
    /// the contact point when `None`.
    body: BodyId,
    p: Option<V2>,
}

/// One contact joint's outputs.
#[derive(Clone, Debug)]
struct Item {
    joint: usize,
    follower: Option<Follower>,
}

/// The contact joints of a model and their followers, found once.
#[derive(Clone, Debug, Default)]
pub struct Contacts {
    items: Vec<Item>,
}

impl Contacts {
    /// Finds the contact joints and their followers.
    pub fn new(model: &Model) -> Self {
        let items = model
            .joints
            .iter()
            .enumerate()
            .filter(|(_, j)| is_contact(&j.constraint))
            .map(|(k, j)| Item {
                joint: k,
                follower: follower(model, &j.constraint),
            })
            .collect();
        Contacts { items }
    }

    /// Channel names, in fill order: `<joint>.cx`, `<joint>.cy` and, where
    /// the follower's motion is known, `<joint>.pressure_angle`.
    pub fn channels(&self, model: &Model) -> Vec<String> {
        let mut names = Vec::new();
        for it in &self.items {
            let name = &model.joints[it.joint].name;
            names.push(format!("{name}.cx"));
            names.push(format!("{name}.cy"));
            if it.follower.is_some() {
                names.push(format!("{name}.pressure_angle"));
            }
        }
        names
    }

    /// Number of channels.
    pub fn len(&self) -> usize {
        self.items
            .iter()
            .map(|it| 2 + usize::from(it.follower.is_some()))
            .sum()
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Writes the channels for coordinates `q` into `out` (length
    /// [`len`](Self::len)).
    pub fn fill(&self, model: &Model, asm: &Assembly, q: &[f64], out: &mut [f64]) {
        let mut k = 0;
        for it in &self.items {
            let c = &model.joints[it.joint].constraint;
            let x = asm.local(model, it.joint, q, &[], 0.0);
            let (cp, n) = contact(c, &x.q, &x.own);
            out[k] = cp[0];
            out[k + 1] = cp[1];
            k += 2;
            if let Some(f) = &it.follower {
                let bq = |b: BodyId| match asm.body_col(b.0) {
                    Some(col) => [q[col], q[col + 1], q[col + 2]],
                    None => [0.0; 3],
                };
                let d = match f.guide {
                    Guide::Translation { frame, axis } => rot(bq(frame)[2], axis),
                    Guide::Pivot { pivot } => {
                        let p = f.p.map_or(cp, |s| point(bq(f.body), s));
                        perp(sub(p, pivot))
                    }
                };
                out[k] = pressure_angle(n, d);
                k += 1;
            }
        }
    }
}

/// The angle between the lines along `n` and `d`, in [0, π/2] (rad); NaN
/// when either is zero.
pub fn pressure_angle(n: V2, d: V2) -> f64 {
    if norm(n) == 0.0 || norm(d) == 0.0 {
        return f64::NAN;
    }
    cross(n, d).abs().atan2(dot(n, d).abs())
}

/// True for the curve-contact joints.
pub fn is_contact(c: &Constraint) -> bool {
    matches!(
        c,
        Constraint::CamFollower(_) | Constraint::FlatFollower(_) | Constraint::PointFollower(_)
    )
}

/// The global contact point and contact normal (not normalised) of a
/// contact joint at body coordinates `q` = (q_i, q_j) and own coordinates.
pub fn contact(c: &Constraint, q: &[[f64; 3]; 2], own: &[f64]) -> (V2, V2) {
    match c {
        Constraint::CamFollower(cf) => {
            let j = cf.curve_i.jet(own[0]);
            (point(q[0], j.p), perp(rot(q[0][2], j.d1)))
        }
        Constraint::FlatFollower(ff) => {
            let j = ff.curve_i.jet(own[0]);
            (point(q[0], j.p), perp(rot(q[1][2], ff.u_j)))
        }
        Constraint::PointFollower(pf) => {
            let j = pf.curve_j.jet(own[0]);
            (point(q[0], pf.s_i), perp(rot(q[1][2], j.d1)))
        }
        _ => ([f64::NAN; 2], [f64::NAN; 2]),
    }
}

/// The follower body of a contact joint (see the module notes); `None`
/// for other joints.
pub fn follower_body(model: &Model, c: &Constraint) -> Option<BodyId> {
    let [bi, bj] = c.bodies();
    Some(match c {
        Constraint::CamFollower(_) => {
            let ti = translates(model, bi);
            let tj = translates(model, bj);
            let pick_i = if bj.is_ground() {
                true
            } else if bi.is_ground() {
                false
            } else if ti != tj {
                ti
            } else {
                driven(model, bj) && !driven(model, bi)
            };
            if pick_i {
                bi
            } else {
                bj
            }
        }
        Constraint::FlatFollower(_) => {
            if bj.is_ground() {
                bi
            } else {
                bj
            }
        }
        Constraint::PointFollower(_) => {
            if bi.is_ground() {
                bj
            } else {
                bi
            }
        }
        _ => return None,
    })
}

/// The follower of a contact joint and its guide, if it has one.
fn follower(model: &Model, c: &Constraint) -> Option<Follower> {
    let [bi, bj] = c.bodies();
    // The follower body and, for a roller, its curve.
    let fb = follower_body(model, c)?;
    let curve: Option<&Curve> = match c {
        Constraint::CamFollower(cf) if fb == bi => Some(&cf.curve_i),
        Constraint::CamFollower(cf) => Some(&cf.curve_j),
        _ => None,
    };
    if fb.is_ground() {
        return None;
    }
    let roller = curve
        .and_then(Curve::circle_centre)
        .map(|(centre, _)| centre);
    if let Some(guide) = guide(model, fb) {
        return Some(Follower {
            guide,
            body: fb,
            p: roller,
        });
    }
    // A roller pinned to a guided body: that body's motion at the pin.
    let other = if fb == bi { bj } else { bi };
    for j in &model.joints {
        if let Constraint::Revolute(r) = &j.constraint {
            let (b, s) = if r.body_i == fb {
                (r.body_j, r.s_j)
            } else if r.body_j == fb {
                (r.body_i, r.s_i)
            } else {
                continue;
            };
            if b.is_ground() || b == other {
                continue;
            }
            if let Some(guide) = guide(model, b) {
                return Some(Follower {
                    guide,
                    body: b,
                    p: Some(s),
                });
            }
        }
    }
    None
}

/// True when `b` has a translational joint to the ground.
fn translates(model: &Model, b: BodyId) -> bool {
    matches!(guide(model, b), Some(Guide::Translation { .. }))
}

/// True when a driver acts on body `b`.
fn driven(model: &Model, b: BodyId) -> bool {
    model
        .joints
        .iter()
        .any(|j| j.driver && j.constraint.bodies().contains(&b))
}

/// How `b` is guided by a joint to the ground: translational first, then
/// revolute.
fn guide(model: &Model, b: BodyId) -> Option<Guide> {
    let ground_joint = |j: &&crate::model::Joint| {
        let [i, k] = j.constraint.bodies();
        (i == b && k.is_ground()) || (k == b && i.is_ground())
    };
    let to_ground = || model.joints.iter().filter(ground_joint);
    for j in to_ground() {
        if let Constraint::Translational(t) = &j.constraint {
            let l = norm(t.v_i);
            if l > 0.0 {
                return Some(Guide::Translation {
                    frame: t.body_i,
                    axis: scale(1.0 / l, t.v_i),
                });
            }
        }
    }
    for j in to_ground() {
        if let Constraint::Revolute(r) = &j.constraint {
            let pivot = if r.body_i.is_ground() { r.s_i } else { r.s_j };
            return Some(Guide::Pivot { pivot });
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn pressure_angle_folds_into_a_quarter_turn() {
        let close = |a: f64, b: f64| (a - b).abs() < 1e-15;
        assert!(close(pressure_angle([0.0, 1.0], [0.0, 1.0]), 0.0));
        assert!(close(pressure_angle([0.0, 1.0], [0.0, -2.0]), 0.0));
        assert!(close(pressure_angle([1.0, 0.0], [0.0, 1.0]), FRAC_PI_2));
        assert!(close(
            pressure_angle([1.0, 1.0], [0.0, -1.0]),
            FRAC_PI_2 / 2.0
        ));
        assert!(close(
            pressure_angle([-1.0, 1.0], [0.0, 1.0]),
            FRAC_PI_2 / 2.0
        ));
        assert!(pressure_angle([0.0, 0.0], [0.0, 1.0]).is_nan());
    }
}
