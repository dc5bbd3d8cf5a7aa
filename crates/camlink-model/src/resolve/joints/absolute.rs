//! `absolute_x`, `absolute_y`, `absolute_phi` and `absolute_distance`: a
//! coordinate of one body held constant.

use camlink_core::constraint::absolute::{AbsoluteCoord, AbsoluteDistance, Coord};
use camlink_core::math::{norm, sub};
use camlink_core::{BodyId, TimeFn};

use super::{At, JointKind};
use crate::file::{AbsoluteCoordJoint, AbsoluteDistanceJoint, AbsolutePhiJoint};
use crate::resolve::{Ctx, R};
use crate::units::Convert;

/// `absolute_x` or `absolute_y`, told apart by `at.kind`.
impl JointKind for AbsoluteCoordJoint {
    fn resolve(&self, cx: &mut Ctx, at: &At) -> R<()> {
        let p = at.path;
        let (coord, axis) = if at.kind == "absolute_x" {
            (Coord::X, 0)
        } else {
            (Coord::Y, 1)
        };
        let name = cx.name(self.name.as_ref(), at.default_name(), p)?;
        let (b, s) = cx.at(&self.body, self.point.as_ref(), p, "body", "point")?;
        cx.moving(b, &at.field("body"))?;
        let f = cx.opt(self.value.as_ref(), cx.r0(b, s)[axis], &at.field("value"))?;
        let c = AbsoluteCoord {
            body: b,
            s,
            coord,
            f: TimeFn::Const(f),
        };
        cx.add(name, c, false);
        cx.defer_joint(self.value.is_none(), p, "value", "m");
        Ok(())
    }

    fn to_si(&mut self, u: &Convert) {
        let AbsoluteCoordJoint {
            name: _,
            body: _,
            point,
            value,
        } = self;
        u.point(point);
        u.opt_length(value);
    }
}

impl JointKind for AbsolutePhiJoint {
    fn resolve(&self, cx: &mut Ctx, at: &At) -> R<()> {
        let p = at.path;
        let name = cx.name(self.name.as_ref(), at.default_name(), p)?;
        let b = cx.body(&self.body, &at.field("body"))?;
        cx.moving(b, &at.field("body"))?;
        let f = cx.opt(self.value.as_ref(), cx.q0(b)[2], &at.field("value"))?;
        let c = AbsoluteCoord {
            body: b,
            s: [0.0; 2],
            coord: Coord::Phi,
            f: TimeFn::Const(f),
        };
        cx.add(name, c, false);
        cx.defer_joint(self.value.is_none(), p, "value", "rad");
        Ok(())
    }

    fn to_si(&mut self, u: &Convert) {
        let AbsolutePhiJoint {
            name: _,
            body: _,
            value,
        } = self;
        u.opt_angle(value);
    }
}

impl JointKind for AbsoluteDistanceJoint {
    fn resolve(&self, cx: &mut Ctx, at: &At) -> R<()> {
        let p = at.path;
        let name = cx.name(self.name.as_ref(), at.default_name(), p)?;
        let (b, s) = cx.at(&self.body, self.point.as_ref(), p, "body", "point")?;
        cx.moving(b, &at.field("body"))?;
        let c0 = cx.point(
            BodyId::GROUND,
            Some(&self.ground_point),
            &at.field("ground_point"),
        )?;
        let f = match &self.distance {
            Some(d) => cx.positive(d, &at.field("distance"), "distance")?,
            None => norm(sub(cx.r0(b, s), c0)),
        };
        let c = AbsoluteDistance {
            body: b,
            s,
            ground_point: c0,
            f: TimeFn::Const(f),
        };
        cx.add(name, c, false);
        cx.defer_joint(self.distance.is_none(), p, "distance", "m");
        Ok(())
    }

    fn to_si(&mut self, u: &Convert) {
        let AbsoluteDistanceJoint {
            name: _,
            body: _,
            point,
            ground_point,
            distance,
        } = self;
        u.point(point);
        u.point_ref(ground_point);
        u.opt_length(distance);
    }
}
