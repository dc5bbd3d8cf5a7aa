//! A joint's `friction` table into the core [`Friction`] of the joint just
//! added (docs/friction.md).

use camlink_core::fmt_num::num;
use camlink_core::force::friction::{Friction, DEFAULT_TRANSITION_SPEED};

use super::{fail, Ctx, R};
use crate::file::FrictionSpec;

impl Ctx {
    /// Sets the friction of the joint just added (field `path`) from
    /// `spec`, if any; `pin` for a revolute joint, which needs a radius and
    /// is the only kind that takes one.
    pub(super) fn friction(&mut self, spec: Option<&FrictionSpec>, pin: bool, path: &str) -> R<()> {
        let Some(spec) = spec else {
            return Ok(());
        };
        let p = format!("{path}.friction");
        let compliant = self
            .model
            .joints
            .last()
            .and_then(|j| j.unilateral)
            .is_some_and(|u| u.compliant.is_some());
        if compliant {
            return fail(
                p,
                "a compliant contact takes no friction: its force is the \
                 Hunt-Crossley law of the overlap, not the joint's reaction",
            );
        }
        let mu = self.num(&spec.mu, &format!("{p}.mu"))?;
        if mu < 0.0 {
            return fail(
                format!("{p}.mu"),
                format!(
                    "the friction coefficient must be zero or positive ({})",
                    num(mu)
                ),
            );
        }
        let radius = match (&spec.radius, pin) {
            (Some(r), true) => {
                let r = self.num(r, &format!("{p}.radius"))?;
                if r < 0.0 {
                    return fail(
                        format!("{p}.radius"),
                        format!("the pin radius must be zero or positive ({} m)", num(r)),
                    );
                }
                r
            }
            (None, true) => {
                return fail(
                    format!("{p}.radius"),
                    "a revolute joint's friction needs the pin radius (m): \
                     the friction torque is mu * radius * the pin force",
                )
            }
            (Some(_), false) => {
                return fail(
                    format!("{p}.radius"),
                    "a radius is the pin radius of a revolute joint's friction; \
                     this joint slides, and its friction is mu times its normal force",
                )
            }
            (None, false) => 0.0,
        };
        let transition_speed = match &spec.transition_speed {
            Some(v) => {
                let v = self.num(v, &format!("{p}.transition_speed"))?;
                if v <= 0.0 {
                    return fail(
                        format!("{p}.transition_speed"),
                        format!("the transition speed must be positive ({} m/s)", num(v)),
                    );
                }
                v
            }
            None => DEFAULT_TRANSITION_SPEED,
        };
        let joint = self
            .model
            .joints
            .last_mut()
            .expect("a joint was just added");
        joint.friction = Some(Friction {
            mu,
            radius,
            transition_speed,
        });
        Ok(())
    }
}
