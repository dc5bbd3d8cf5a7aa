//! `revolute_revolute` (a massless coupler) and `revolute_translational`
//! (a pin on a line of another body).

use camlink_core::constraint::composite::{RevoluteRevolute, RevoluteTranslational};
use camlink_core::math::{dot, norm, perp, rot, sub};

use super::{At, JointKind};
use crate::file::{RevoluteRevoluteJoint, RevoluteTranslationalJoint};
use crate::resolve::{fail, Ctx, R};
use crate::units::Convert;

impl JointKind for RevoluteRevoluteJoint {
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
        let length = match &self.length {
            Some(l) => cx.positive(l, &at.field("length"), "length")?,
            None => {
                let l = norm(sub(cx.r0(bj, s_j), cx.r0(bi, s_i)));
                if l <= 0.0 {
                    return fail(
                        at.field("length"),
                        "the two points coincide initially; give the length",
                    );
                }
                l
            }
        };
        let c = RevoluteRevolute {
            body_i: bi,
            s_i,
            body_j: bj,
            s_j,
            length,
        };
        cx.add(name, c, false);
        cx.defer_joint(self.length.is_none(), p, "length", "m");
        Ok(())
    }

    fn to_si(&mut self, u: &Convert) {
        let RevoluteRevoluteJoint {
            name: _,
            body_i: _,
            point_i,
            body_j: _,
            point_j,
            length,
        } = self;
        u.point(point_i);
        u.point(point_j);
        u.opt_length(length);
    }
}

impl JointKind for RevoluteTranslationalJoint {
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
        let v_j = cx.axis(&self.axis, &at.field("axis"))?;
        let offset = match &self.offset {
            Some(c) => cx.num(c, &at.field("offset"))?,
            None => {
                let u = rot(cx.q0(bj)[2], v_j);
                dot(perp(u), sub(cx.r0(bi, s_i), cx.r0(bj, s_j)))
            }
        };
        let c = RevoluteTranslational {
            body_i: bi,
            s_i,
            body_j: bj,
            s_j,
            v_j,
            offset,
        };
        cx.add(name, c, false);
        cx.set_limits(self.limits.as_ref(), p)?;
        cx.defer_joint(self.offset.is_none(), p, "offset", "m");
        Ok(())
    }

    fn to_si(&mut self, u: &Convert) {
        let RevoluteTranslationalJoint {
            name: _,
            body_i: _,
            point_i,
            body_j: _,
            point_j,
            axis: _,
            offset,
            limits,
        } = self;
        u.point(point_i);
        u.point(point_j);
        u.opt_length(offset);
        u.length_limits(limits);
    }
}
