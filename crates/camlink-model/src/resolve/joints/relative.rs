//! `relative_x`, `relative_y`, `relative_phi` and `relative_distance`: a
//! coordinate of body j relative to body i held constant.

use camlink_core::constraint::relative::{RelCoord, RelativeCoord, RelativeDistance};
use camlink_core::math::{norm, sub};
use camlink_core::{Constraint, TimeFn};

use super::{At, JointKind};
use crate::file::{RelativeCoordJoint, RelativePhiJoint};
use crate::resolve::{Ctx, R};
use crate::units::Convert;

/// `relative_x`, `relative_y` or `relative_distance`, told apart by
/// `at.kind`.
impl JointKind for RelativeCoordJoint {
    fn resolve(&self, cx: &mut Ctx, at: &At) -> R<()> {
        let p = at.path;
        let name = cx.name(self.name.as_ref(), at.default_name(), p)?;
        let (bi, s_i) = cx.at(&self.body_i, self.point_i.as_ref(), p, "body_i", "point_i")?;
        let (bj, s_j) = cx.at(&self.body_j, self.point_j.as_ref(), p, "body_j", "point_j")?;
        cx.distinct(bi, bj, p)?;
        let d = sub(cx.r0(bj, s_j), cx.r0(bi, s_i));
        let vp = at.field("value");
        let c: Constraint = if at.kind == "relative_distance" {
            let f = match &self.value {
                Some(v) => cx.positive(v, &vp, "distance")?,
                None => norm(d),
            };
            RelativeDistance {
                body_i: bi,
                s_i,
                body_j: bj,
                s_j,
                f: TimeFn::Const(f),
            }
            .into()
        } else {
            let (coord, k) = if at.kind == "relative_x" {
                (RelCoord::X, 0)
            } else {
                (RelCoord::Y, 1)
            };
            let f = cx.opt(self.value.as_ref(), d[k], &vp)?;
            RelativeCoord {
                body_i: bi,
                s_i,
                body_j: bj,
                s_j,
                coord,
                f: TimeFn::Const(f),
            }
            .into()
        };
        cx.add(name, c, false);
        cx.defer_joint(self.value.is_none(), p, "value", "m");
        Ok(())
    }

    fn to_si(&mut self, u: &Convert) {
        let RelativeCoordJoint {
            name: _,
            body_i: _,
            point_i,
            body_j: _,
            point_j,
            value,
        } = self;
        u.point(point_i);
        u.point(point_j);
        u.opt_length(value);
    }
}

impl JointKind for RelativePhiJoint {
    fn resolve(&self, cx: &mut Ctx, at: &At) -> R<()> {
        let p = at.path;
        let name = cx.name(self.name.as_ref(), at.default_name(), p)?;
        let bi = cx.body(&self.body_i, &at.field("body_i"))?;
        let bj = cx.body(&self.body_j, &at.field("body_j"))?;
        cx.distinct(bi, bj, p)?;
        let f0 = cx.q0(bj)[2] - cx.q0(bi)[2];
        let f = cx.opt(self.value.as_ref(), f0, &at.field("value"))?;
        let c = RelativeCoord {
            body_i: bi,
            s_i: [0.0; 2],
            body_j: bj,
            s_j: [0.0; 2],
            coord: RelCoord::Phi,
            f: TimeFn::Const(f),
        };
        cx.add(name, c, false);
        cx.defer_joint(self.value.is_none(), p, "value", "rad");
        Ok(())
    }

    fn to_si(&mut self, u: &Convert) {
        let RelativePhiJoint {
            name: _,
            body_i: _,
            body_j: _,
            value,
        } = self;
        u.opt_angle(value);
    }
}
