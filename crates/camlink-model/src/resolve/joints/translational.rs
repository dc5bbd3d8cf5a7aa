//! `translational`: a point of body j slides on a line of body i, and the
//! relative angle stays constant.

use camlink_core::constraint::translational::Translational;

use super::{At, JointKind};
use crate::file::TranslationalJoint;
use crate::resolve::{Ctx, JointInfo, R};
use crate::units::Convert;

impl JointKind for TranslationalJoint {
    fn resolve(&self, cx: &mut Ctx, at: &At) -> R<()> {
        let p = at.path;
        let name = cx.name(self.name.as_ref(), at.default_name(), p)?;
        let ((bi, s_i), (bj, s_j)) = cx.two_bodies(
            &self.body_i,
            self.point_i.as_ref(),
            &self.body_j,
            self.point_j.as_ref(),
            p,
        )?;
        let v_i = cx.axis(&self.axis, &at.field("axis"))?;
        let angle = match &self.angle {
            Some(a) => cx.num(a, &at.field("angle"))?,
            None => Translational::angle_from(cx.q0(bi), cx.q0(bj)),
        };
        let c = Translational {
            body_i: bi,
            s_i,
            v_i,
            body_j: bj,
            s_j,
            angle,
        };
        cx.joints.insert(
            name.clone(),
            JointInfo::Translational {
                bi,
                s_i,
                v_i,
                bj,
                s_j,
            },
        );
        cx.add(name, c, false);
        cx.set_limits(self.limits.as_ref(), p)?;
        cx.defer_joint(self.angle.is_none(), p, "angle", "rad");
        cx.friction(self.friction.as_ref(), false, p)
    }

    fn to_si(&mut self, u: &Convert) {
        let TranslationalJoint {
            name: _,
            body_i: _,
            point_i,
            axis: _,
            body_j: _,
            point_j,
            angle,
            limits,
            friction,
        } = self;
        u.point(point_i);
        u.point(point_j);
        u.opt_angle(angle);
        u.length_limits(limits);
        u.friction(friction);
    }
}
