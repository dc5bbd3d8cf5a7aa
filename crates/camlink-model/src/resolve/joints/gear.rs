//! `gear` (two pitch circles rolling) and `rack_pinion` (a pitch circle
//! rolling on a pitch line).

use camlink_core::constraint::gear::{Gear, GearKind, RackPinion};
use camlink_core::math::{norm, sub};

use super::{At, JointKind};
use crate::file::{GearJoint, GearKindSpec, RackPinionJoint};
use crate::resolve::{fail, Ctx, R};
use crate::units::Convert;

impl JointKind for GearJoint {
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
        let mut c = Gear {
            body_i: bi,
            s_i,
            radius_i: cx.positive(&self.radius_i, &at.field("radius_i"), "radius")?,
            body_j: bj,
            s_j,
            radius_j: cx.positive(&self.radius_j, &at.field("radius_j"), "radius")?,
            kind: match self.kind {
                GearKindSpec::External => GearKind::External,
                GearKindSpec::Internal => GearKind::Internal,
            },
            phase: 0.0,
        };
        if norm(sub(cx.r0(bj, s_j), cx.r0(bi, s_i))) <= 0.0 && self.phase.is_none() {
            return fail(
                at.field("point_j"),
                "the gear centres coincide initially, so the centre line is undefined",
            );
        }
        c.phase = match &self.phase {
            Some(v) => cx.num(v, &at.field("phase"))?,
            None => c.phase_from(cx.q0(bi), cx.q0(bj)),
        };
        cx.add(name, c, false);
        cx.defer_joint(self.phase.is_none(), p, "phase", "m");
        Ok(())
    }

    fn to_si(&mut self, u: &Convert) {
        let GearJoint {
            name: _,
            body_i: _,
            point_i,
            radius_i,
            body_j: _,
            point_j,
            radius_j,
            kind: _,
            phase,
        } = self;
        u.point(point_i);
        u.point(point_j);
        u.length(radius_i);
        u.length(radius_j);
        u.opt_length(phase);
    }
}

impl JointKind for RackPinionJoint {
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
        let mut c = RackPinion {
            body_i: bi,
            s_i,
            radius: cx.positive(&self.radius, &at.field("radius"), "radius")?,
            body_j: bj,
            s_j,
            u_j: cx.axis(&self.axis, &at.field("axis"))?,
            phase: 0.0,
        };
        c.phase = match &self.phase {
            Some(v) => cx.num(v, &at.field("phase"))?,
            None => c.phase_from(cx.q0(bi), cx.q0(bj)),
        };
        cx.add(name, c, false);
        cx.defer_joint(self.phase.is_none(), p, "phase", "m");
        Ok(())
    }

    fn to_si(&mut self, u: &Convert) {
        let RackPinionJoint {
            name: _,
            body_i: _,
            point_i,
            radius,
            body_j: _,
            point_j,
            axis: _,
            phase,
        } = self;
        u.point(point_i);
        u.point(point_j);
        u.length(radius);
        u.opt_length(phase);
    }
}
