//! `cam_follower`: two curves in contact, each contact parameter an own
//! coordinate.

use camlink_core::constraint::cam_follower::CamFollower;
use camlink_core::math::point;

use super::{At, JointKind};
use crate::file::CamFollowerJoint;
use crate::resolve::{Ctx, R};
use crate::units::Convert;

impl JointKind for CamFollowerJoint {
    fn resolve(&self, cx: &mut Ctx, at: &At) -> R<()> {
        let p = at.path;
        let name = cx.name(self.name.as_ref(), at.default_name(), p)?;
        let (bi, ci) = cx.curve_ref(&self.curve_i, &at.field("curve_i"))?;
        let (bj, cj) = cx.curve_ref(&self.curve_j, &at.field("curve_j"))?;
        cx.different(bi, bj, &self.curve_i, &self.curve_j, &at.field("curve_j"))?;
        let ai = self
            .alpha_i
            .as_ref()
            .map(|n| cx.num(n, &at.field("alpha_i")))
            .transpose()?;
        let aj = self
            .alpha_j
            .as_ref()
            .map(|n| cx.num(n, &at.field("alpha_j")))
            .transpose()?;
        let own0 = match (ai, aj) {
            (None, None) => None,
            (Some(a), Some(b)) => Some([a, b]),
            (Some(a), None) => {
                let r = point(cx.q0(bi), ci.jet(a).p);
                Some([a, cx.nearest(bj, &cj, r)])
            }
            (None, Some(b)) => {
                let r = point(cx.q0(bj), cj.jet(b).p);
                Some([cx.nearest(bi, &ci, r), b])
            }
        };
        let cf = CamFollower {
            body_i: bi,
            curve_i: ci,
            body_j: bj,
            curve_j: cj,
        };
        cx.add_contact(name, cf.into(), own0);
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
        let CamFollowerJoint {
            name: _,
            curve_i,
            curve_j,
            alpha_i,
            alpha_j,
            unilateral: _,
            restitution: _,
            rest_speed: _,
            event_tol: _,
            stiffness: _,
            exponent: _,
            damping: _,
            friction,
        } = self;
        u.opt_on_curve(alpha_i, curve_i);
        u.opt_on_curve(alpha_j, curve_j);
        u.friction(friction);
    }
}
