//! `flat_follower`: a curve touching a straight face of another body, the
//! contact parameter on the curve an own coordinate.

use camlink_core::constraint::flat_follower::FlatFollower;

use super::{At, JointKind};
use crate::file::FlatFollowerJoint;
use crate::resolve::{fail, Ctx, R};
use crate::units::Convert;

impl JointKind for FlatFollowerJoint {
    fn resolve(&self, cx: &mut Ctx, at: &At) -> R<()> {
        let p = at.path;
        let name = cx.name(self.name.as_ref(), at.default_name(), p)?;
        let (bi, ci) = cx.curve_ref(&self.curve_i, &at.field("curve_i"))?;
        let (bj, s_j) = cx.at(&self.body_j, self.point_j.as_ref(), p, "body_j", "point_j")?;
        if bi == bj {
            return fail(
                at.field("body_j"),
                format!(
                    "curve '{}' is on body '{}' itself; the face must be on another body",
                    self.curve_i,
                    cx.model.body(bi).name
                ),
            );
        }
        let u_j = cx.axis(&self.axis, &at.field("axis"))?;
        let Some(ff) = FlatFollower::new(bi, ci, bj, s_j, u_j) else {
            return fail(at.field("axis"), "axis has zero length");
        };
        let own0 = self
            .alpha_i
            .as_ref()
            .map(|n| cx.num(n, &at.field("alpha_i")).map(|a| [a, 0.0]))
            .transpose()?;
        cx.add_contact(name, ff.into(), own0);
        let law = [
            &self.restitution,
            &self.rest_speed,
            &self.event_tol,
            &self.stiffness,
            &self.exponent,
            &self.damping,
        ];
        cx.set_unilateral(self.unilateral, law, p)?;
        cx.friction(self.friction.as_ref(), false, p)
    }

    fn to_si(&mut self, u: &Convert) {
        let FlatFollowerJoint {
            name: _,
            curve_i,
            body_j: _,
            point_j,
            axis: _,
            alpha_i,
            unilateral: _,
            restitution: _,
            rest_speed: _,
            event_tol: _,
            stiffness: _,
            exponent: _,
            damping: _,
            friction,
        } = self;
        u.point(point_j);
        u.opt_on_curve(alpha_i, curve_i);
        u.friction(friction);
    }
}
