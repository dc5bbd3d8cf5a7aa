//! The curve contacts: one view of each ([`ContactView`]: what its bodies
//! carry, which own coordinate runs on which curve, the follower and the
//! cam), read by the contact outputs here, the design checks and the contact
//! forces; and the contact outputs, the global contact point and the
//! pressure angle.
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
use crate::constraint::{Constraint, Equations, Feature};
use crate::curve::Curve;
use crate::math::{cross, dot, norm, perp, point, rot, scale, sub, V2};
use crate::model::{BodyId, Model};
use crate::quantity::{Channel, Quantity};

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

/// One curve-contact joint as the contact outputs, the design checks
/// ([`crate::design`]) and the contact forces see it: what its bodies
/// carry ([`Feature`]), which own coordinate runs on which curve, the
/// contact point and tangent, the follower and the cam.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ContactView<'a> {
    /// Index of the joint in [`Model::joints`].
    pub joint: usize,
    /// Bodies i and j.
    pub bodies: [BodyId; 2],
    /// What body i and body j carry.
    pub sides: [Feature<'a>; 2],
}

impl<'a> ContactView<'a> {
    /// The view of joint `joint`, if it is a curve contact.
    pub(crate) fn of(model: &'a Model, joint: usize) -> Option<Self> {
        let c = &model.joints[joint].constraint;
        Some(ContactView {
            joint,
            bodies: c.bodies(),
            sides: c.contact_sides()?,
        })
    }

    /// Every curve contact of `model`, drivers included, in joint order.
    pub(crate) fn all(model: &'a Model) -> impl Iterator<Item = ContactView<'a>> + 'a {
        (0..model.joints.len()).filter_map(move |j| ContactView::of(model, j))
    }

    /// The curve body `side` (0: i, 1: j) carries, if it carries one.
    pub(crate) fn curve(&self, side: usize) -> Option<&'a Curve> {
        match self.sides[side] {
            Feature::Curve(c) => Some(c),
            _ => None,
        }
    }

    /// The own coordinate that runs on the curve of `side`.
    pub(crate) fn own_of(&self, side: usize) -> Option<usize> {
        self.curve(side)?;
        Some((0..side).filter(|&s| self.curve(s).is_some()).count())
    }

    /// (side, curve) that own coordinate `own` runs on.
    pub(crate) fn own_curve(&self, own: usize) -> Option<(usize, &'a Curve)> {
        (0..2).filter_map(|s| Some((s, self.curve(s)?))).nth(own)
    }

    /// The name of own coordinate `own` in reports: α_i on a curve of
    /// body i, α_j on one of body j.
    pub(crate) fn own_name(&self, own: usize) -> &'static str {
        match self.own_curve(own) {
            Some((0, _)) => "α_i",
            _ => "α_j",
        }
    }

    /// True for a pin in a slot: the slot has two walls and pushes either
    /// way; every other contact is a cam that can only push.
    pub(crate) fn two_walled(&self) -> bool {
        self.sides.iter().any(|s| matches!(s, Feature::Point(_)))
    }

    /// The global contact point (m) and the contact tangent (global, not
    /// normalised) at body coordinates `q` = (q_i, q_j) and own
    /// coordinates `own`. The point is body i's: the point of C_i at α_i,
    /// or the pin. The tangent is a face's direction where there is a face,
    /// else the tangent of the first curve, as α grows.
    pub(crate) fn point_tangent(&self, q: &[[f64; 3]; 2], own: &[f64]) -> (V2, V2) {
        let p = match self.sides[0] {
            Feature::Curve(c) => point(q[0], c.jet(own[0]).p),
            Feature::Point(s) | Feature::Face(s) => point(q[0], s),
        };
        let face = (0..2).find_map(|s| match self.sides[s] {
            Feature::Face(u) => Some(rot(q[s][2], u)),
            _ => None,
        });
        let t = face.unwrap_or_else(|| match self.own_curve(0) {
            Some((s, c)) => rot(q[s][2], c.jet(own[0]).d1),
            None => [f64::NAN; 2],
        });
        (p, t)
    }

    /// The follower body (see the module notes): the body that carries a
    /// face or a pin unless it is the ground; between two curves, the body
    /// that translates, else the one that is not driven, else body j.
    pub(crate) fn follower(&self, model: &Model) -> BodyId {
        let [bi, bj] = self.bodies;
        let carrier = (0..2).find(|&s| self.curve(s).is_none());
        match carrier {
            Some(s) => {
                let (f, other) = if s == 0 { (bi, bj) } else { (bj, bi) };
                if f.is_ground() {
                    other
                } else {
                    f
                }
            }
            None => {
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
        }
    }

    /// The cam: the body whose curve the follower runs on.
    pub(crate) fn cam(&self, model: &Model) -> BodyId {
        let [bi, bj] = self.bodies;
        match (self.curve(0), self.curve(1)) {
            (Some(_), Some(_)) if self.follower(model) == bi => bj,
            (Some(_), _) => bi,
            (None, _) => bj,
        }
    }
}

/// The contact joints of a model and their followers, found once.
#[derive(Clone, Debug, Default)]
pub(crate) struct Contacts {
    items: Vec<Item>,
}

impl Contacts {
    /// Finds the contact joints and their followers.
    pub(crate) fn new(model: &Model) -> Self {
        let items = ContactView::all(model)
            .map(|v| Item {
                joint: v.joint,
                follower: follower(model, &v),
            })
            .collect();
        Contacts { items }
    }

    /// Channel names, in fill order: `<joint>.cx`, `<joint>.cy` and, where
    /// the follower's motion is known, `<joint>.pressure_angle`.
    pub(crate) fn channels(&self, model: &Model) -> Vec<Channel> {
        let mut out = Vec::new();
        for it in &self.items {
            let name = &model.joints[it.joint].name;
            out.push(Channel::new(format!("{name}.cx"), Quantity::Length));
            out.push(Channel::new(format!("{name}.cy"), Quantity::Length));
            if it.follower.is_some() {
                out.push(Channel::new(
                    format!("{name}.pressure_angle"),
                    Quantity::Angle,
                ));
            }
        }
        out
    }

    /// Writes the channels for coordinates `q` into `out` (one value per
    /// channel of [`channels`](Self::channels), in its order).
    pub(crate) fn fill(&self, model: &Model, asm: &Assembly, q: &[f64], out: &mut [f64]) {
        let mut k = 0;
        for it in &self.items {
            let Some(v) = ContactView::of(model, it.joint) else {
                continue;
            };
            let x = asm.local(model, it.joint, q, &[], 0.0);
            let (cp, t) = v.point_tangent(&x.q, &x.own);
            let n = perp(t);
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
pub(crate) fn pressure_angle(n: V2, d: V2) -> f64 {
    if norm(n) == 0.0 || norm(d) == 0.0 {
        return f64::NAN;
    }
    cross(n, d).abs().atan2(dot(n, d).abs())
}

/// The follower of a contact joint and its guide, if it has one.
fn follower(model: &Model, v: &ContactView) -> Option<Follower> {
    let [bi, bj] = v.bodies;
    // The follower body and, for a roller, its curve.
    let fb = v.follower(model);
    let curve = v.curve(if fb == bi { 0 } else { 1 });
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

    use crate::constraint::{
        cam_follower::CamFollower, flat_follower::FlatFollower, point_follower::PointFollower,
    };
    use crate::curve::{Parametric, Polar};
    use crate::model::Body;

    /// A model with bodies `cam` (1) and `follower` (2) and one joint.
    fn with_joint(c: Constraint) -> Model {
        let mut m = Model::new("m");
        m.add_body(Body::new("cam", [0.0; 3]));
        m.add_body(Body::new("follower", [0.0, 2.0, 0.0]));
        m.add_joint("contact", c);
        m
    }

    #[test]
    fn the_view_matches_each_contact_joints_own_coordinates() {
        let disc = || Curve::from(Polar::circle([0.0, 0.0], 1.0).unwrap());
        let line = || Curve::from(Parametric::line([0.0, 0.0], [1.0, 0.0]).unwrap());
        let joints: Vec<Constraint> = vec![
            CamFollower {
                body_i: BodyId(1),
                curve_i: disc(),
                body_j: BodyId(2),
                curve_j: disc(),
            }
            .into(),
            FlatFollower::new(BodyId(1), disc(), BodyId(2), [0.0; 2], [1.0, 0.0])
                .unwrap()
                .into(),
            PointFollower::new(BodyId(2), [0.0; 2], BodyId(1), line()).into(),
        ];
        for c in joints {
            let m = with_joint(c);
            let c = &m.joints[0].constraint;
            let v = ContactView::of(&m, 0).expect("a contact view");
            // One own coordinate per curve, named after the body carrying it.
            assert_eq!((0..2).filter_map(|s| v.curve(s)).count(), c.own_count());
            for own in 0..c.own_count() {
                let ascii = c.own_names()[own].replace("alpha", "α");
                assert_eq!(v.own_name(own), ascii, "{}", c.kind());
                let (side, _) = v.own_curve(own).unwrap();
                assert_eq!(v.own_of(side), Some(own));
            }
            // The follower carries the face or the pin.
            let follower = v.follower(&m);
            assert!(!follower.is_ground());
            match c.kind() {
                "flat-follower" => assert_eq!(follower, BodyId(2)),
                "point-follower" => assert_eq!(follower, BodyId(2)),
                _ => {}
            }
            assert_ne!(v.cam(&m), follower, "{}", c.kind());
        }
        assert!(ContactView::all(&with_joint(
            crate::constraint::revolute::Revolute {
                body_i: BodyId(1),
                s_i: [0.0; 2],
                body_j: BodyId(2),
                s_j: [0.0; 2],
            }
            .into()
        ))
        .next()
        .is_none());
    }

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
