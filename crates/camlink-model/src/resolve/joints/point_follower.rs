//! `point_follower`: a pin of one body in a slot curve of another, the
//! pin's parameter on the slot an own coordinate.

use camlink_core::constraint::point_follower::PointFollower;

use super::{At, JointKind};
use crate::file::PointFollowerJoint;
use crate::resolve::{fail, Ctx, R};
use crate::units::Convert;

impl JointKind for PointFollowerJoint {
    fn resolve(&self, cx: &mut Ctx, at: &At) -> R<()> {
        let p = at.path;
        let name = cx.name(self.name.as_ref(), at.default_name(), p)?;
        let (bi, s_i) = cx.at(&self.body_i, self.point_i.as_ref(), p, "body_i", "point_i")?;
        let (bj, cj) = cx.curve_ref(&self.curve_j, &at.field("curve_j"))?;
        if bi == bj {
            return fail(
                at.field("curve_j"),
                format!(
                    "curve '{}' is on body '{}', which also carries the pin; the slot must be on another body",
                    self.curve_j,
                    cx.model.body(bi).name
                ),
            );
        }
        let own0 = self
            .alpha_j
            .as_ref()
            .map(|n| cx.num(n, &at.field("alpha_j")).map(|a| [a, 0.0]))
            .transpose()?;
        cx.add_contact(name, PointFollower::new(bi, s_i, bj, cj).into(), own0);
        cx.friction(self.friction.as_ref(), false, p)
    }

    fn to_si(&mut self, u: &Convert) {
        let PointFollowerJoint {
            name: _,
            body_i: _,
            point_i,
            curve_j,
            alpha_j,
            friction,
        } = self;
        u.point(point_i);
        u.opt_on_curve(alpha_j, curve_j);
        u.friction(friction);
    }
}
