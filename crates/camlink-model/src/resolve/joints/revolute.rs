//! `revolute`: a pin joining a point of each of two bodies.

use camlink_core::constraint::revolute::Revolute;

use super::{At, JointKind};
use crate::file::RevoluteJoint;
use crate::resolve::{Ctx, JointInfo, R};
use crate::units::Convert;

impl JointKind for RevoluteJoint {
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
        cx.joints
            .insert(name.clone(), JointInfo::Revolute { bi, s_i, bj, s_j });
        cx.add(
            name,
            Revolute {
                body_i: bi,
                s_i,
                body_j: bj,
                s_j,
            },
            false,
        );
        cx.set_limits(self.limits.as_ref(), p)?;
        cx.friction(self.friction.as_ref(), true, p)
    }

    fn to_si(&mut self, u: &Convert) {
        let RevoluteJoint {
            name: _,
            body_i: _,
            point_i,
            body_j: _,
            point_j,
            limits,
            friction,
        } = self;
        u.point(point_i);
        u.point(point_j);
        u.angle_limits(limits);
        u.friction(friction);
    }
}
