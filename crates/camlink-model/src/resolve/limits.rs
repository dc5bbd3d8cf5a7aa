//! A joint's `limits` (end stops on its coordinate): read, checked, and
//! set on the joint just added ([`camlink_core::model::Limits`]).

use camlink_core::constraint::Local;
use camlink_core::fmt_num::num;
use camlink_core::limits::range_text;
use camlink_core::model::Limits;
use camlink_core::Equations;

use super::{fail, Ctx, R};
use crate::file::LimitsSpec;

impl Ctx {
    /// Sets `spec`, the `limits` of the joint at field `p`, on the joint
    /// just added: lower < upper, the law of its stops, and the joint's
    /// coordinate inside them at the written placement.
    pub(super) fn set_limits(&mut self, spec: Option<&LimitsSpec>, p: &str) -> R<()> {
        let Some(l) = spec else {
            return Ok(());
        };
        let p = format!("{p}.limits");
        let value = |n: &Option<_>, key: &str| {
            n.as_ref()
                .map(|n| self.num(n, &format!("{p}.{key}")))
                .transpose()
        };
        let (lower, upper) = (value(&l.lower, "lower")?, value(&l.upper, "upper")?);
        match (lower, upper) {
            (None, None) => return fail(p, "give a lower limit, an upper limit or both"),
            (Some(lo), Some(hi)) if lo >= hi => {
                return fail(
                    format!("{p}.upper"),
                    format!(
                        "the upper limit {} must be above the lower limit {}",
                        num(hi),
                        num(lo)
                    ),
                )
            }
            _ => {}
        }
        let law = [
            &l.restitution,
            &l.rest_speed,
            &l.event_tol,
            &l.stiffness,
            &l.exponent,
            &l.damping,
        ];
        let limits = Limits {
            lower,
            upper,
            law: self.unilateral_law(law, &p)?,
        };
        let Some(joint) = self.model.joints.last() else {
            return Ok(());
        };
        let c = &joint.constraint;
        limits.validate(c).or_else(|e| fail(&p, e))?;
        // The coordinate where the file places the bodies.
        let [bi, bj] = c.bodies();
        let x = Local {
            q: [self.model.body(bi).q0, self.model.body(bj).q0],
            ..Local::default()
        };
        let coord = Limits::coordinate(c, 0.0).expect("validated");
        let (at, _) = coord.value_and_rate(&x);
        let (what, unit) = Limits::coordinate_name(c).expect("validated");
        if limits.lower.is_some_and(|lo| at < lo) || limits.upper.is_some_and(|hi| at > hi) {
            return fail(
                p,
                format!(
                    "the joint's {what} where the bodies are placed, {} {unit}, is outside \
                     its limits {}",
                    num(at),
                    range_text(&limits, unit)
                ),
            );
        }
        if let Some(j) = self.model.joints.last_mut() {
            j.limits = Some(limits);
        }
        Ok(())
    }
}
