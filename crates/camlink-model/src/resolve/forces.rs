//! `[[forces]]` into core [`Force`]s.

use camlink_core::force::point::{PointForce, Torque};
use camlink_core::force::rsda::Rsda;
use camlink_core::force::state::StateForce;
use camlink_core::force::translational_damper::TranslationalDamper;
use camlink_core::force::tsda::Tsda;
use camlink_core::force::Force;
use camlink_core::math::{norm, sub};
use camlink_core::{BodyId, TimeFn};

use super::{check_name, fail, initial, Ctx, JointInfo, R};
use crate::error::did_you_mean;
use crate::file::{ForceSpec, Num};
use camlink_core::fmt_num::num;

impl Ctx {
    /// Resolves `forces[k]` and adds it to the model.
    pub(super) fn force(&mut self, f: &ForceSpec, k: usize) -> R<()> {
        let path = format!("forces[{k}]");
        let p = path.as_str();
        // The value measured in the placement, if the file leaves it out.
        let left_out = match f {
            ForceSpec::Tsda { free_length, .. } => {
                free_length.is_none().then_some(("free_length", "m"))
            }
            ForceSpec::Rsda { free_angle, .. } => {
                free_angle.is_none().then_some(("free_angle", "rad"))
            }
            _ => None,
        };
        let (name, kind) = match f {
            ForceSpec::PointForce {
                name,
                body,
                point,
                fx,
                fy,
                local,
                reaction,
                reaction_point,
            } => {
                let (b, s) = self.at(body, point.as_ref(), p, "body", "point")?;
                if reaction.is_some()
                    || self.reads_motion(fx.as_ref())
                    || self.reads_motion(fy.as_ref())
                {
                    let bj = self.reaction(reaction.as_ref(), b, p)?;
                    let mut reads = Vec::new();
                    let fx =
                        self.state_expr(fx.as_ref(), [b, bj], &mut reads, &format!("{p}.fx"))?;
                    let fy =
                        self.state_expr(fy.as_ref(), [b, bj], &mut reads, &format!("{p}.fy"))?;
                    let s_j = match (reaction_point, bj.is_ground()) {
                        (Some(rp), false) => {
                            self.point(bj, Some(rp), &format!("{p}.reaction_point"))?
                        }
                        (None, false) if fx.is_some() || fy.is_some() => {
                            return fail(
                                format!("{p}.reaction_point"),
                                "a force with a reaction body needs reaction_point, where −F acts on it",
                            )
                        }
                        (Some(_), true) => {
                            return fail(
                                format!("{p}.reaction_point"),
                                "reaction_point without a reaction body",
                            )
                        }
                        _ => [0.0; 2],
                    };
                    let kind = StateForce {
                        reads,
                        body_i: b,
                        s_i: s,
                        body_j: bj,
                        s_j,
                        f: [fx, fy],
                        torque: None,
                        local: *local,
                    };
                    let name = self.force_name(name.as_ref(), format!("point_force_{k}"), p)?;
                    self.model.add_force(Force::new(name, kind));
                    return Ok(());
                }
                if reaction_point.is_some() {
                    return fail(
                        format!("{p}.reaction_point"),
                        "reaction_point without a reaction body",
                    );
                }
                let f = [
                    self.opt_time_fn(fx.as_ref(), &format!("{p}.fx"))?,
                    self.opt_time_fn(fy.as_ref(), &format!("{p}.fy"))?,
                ];
                let kind = PointForce {
                    body: b,
                    s,
                    f,
                    local: *local,
                };
                (
                    self.force_name(name.as_ref(), format!("point_force_{k}"), p)?,
                    kind.into(),
                )
            }
            ForceSpec::Torque {
                name,
                body,
                torque,
                reaction,
            } => {
                let b = self.body(body, &format!("{p}.body"))?;
                if reaction.is_some() || self.reads_motion(Some(torque)) {
                    let bj = self.reaction(reaction.as_ref(), b, p)?;
                    let mut reads = Vec::new();
                    let t =
                        self.state_expr(Some(torque), [b, bj], &mut reads, &format!("{p}.torque"))?;
                    let kind = StateForce {
                        reads,
                        body_i: b,
                        s_i: [0.0; 2],
                        body_j: bj,
                        s_j: [0.0; 2],
                        f: [None, None],
                        torque: t,
                        local: false,
                    };
                    let name = self.force_name(name.as_ref(), format!("torque_{k}"), p)?;
                    self.model.add_force(Force::new(name, kind));
                    return Ok(());
                }
                let t = self.time_fn(torque, &format!("{p}.torque"))?;
                (
                    self.force_name(name.as_ref(), format!("torque_{k}"), p)?,
                    Torque { body: b, t }.into(),
                )
            }
            ForceSpec::Tsda {
                name,
                body_i,
                point_i,
                body_j,
                point_j,
                stiffness,
                free_length,
                damping,
                actuator,
            } => {
                let (bi, s_i) = self.at(body_i, point_i.as_ref(), p, "body_i", "point_i")?;
                let (bj, s_j) = self.at(body_j, point_j.as_ref(), p, "body_j", "point_j")?;
                if bi == bj {
                    return fail(format!("{p}.body_j"), "a spring joins two different bodies");
                }
                let l0 = norm(sub(self.r0(bj, s_j), self.r0(bi, s_i)));
                let kind = Tsda {
                    body_i: bi,
                    s_i,
                    body_j: bj,
                    s_j,
                    stiffness: self.non_negative(
                        stiffness.as_ref(),
                        0.0,
                        &format!("{p}.stiffness"),
                    )?,
                    free_length: self.non_negative(
                        free_length.as_ref(),
                        l0,
                        &format!("{p}.free_length"),
                    )?,
                    damping: self.non_negative(damping.as_ref(), 0.0, &format!("{p}.damping"))?,
                    actuator: self.opt_time_fn(actuator.as_ref(), &format!("{p}.actuator"))?,
                };
                (
                    self.force_name(name.as_ref(), format!("tsda_{k}"), p)?,
                    kind.into(),
                )
            }
            ForceSpec::Rsda {
                name,
                body_i,
                body_j,
                stiffness,
                free_angle,
                damping,
                actuator,
            } => {
                let bi = self.body(body_i, &format!("{p}.body_i"))?;
                let bj = self.body(body_j, &format!("{p}.body_j"))?;
                if bi == bj {
                    return fail(format!("{p}.body_j"), "a spring joins two different bodies");
                }
                let th0 = self.q0(bj)[2] - self.q0(bi)[2];
                let kind = Rsda {
                    body_i: bi,
                    body_j: bj,
                    stiffness: self.non_negative(
                        stiffness.as_ref(),
                        0.0,
                        &format!("{p}.stiffness"),
                    )?,
                    free_angle: self.opt(free_angle.as_ref(), th0, &format!("{p}.free_angle"))?,
                    damping: self.non_negative(damping.as_ref(), 0.0, &format!("{p}.damping"))?,
                    actuator: self.opt_time_fn(actuator.as_ref(), &format!("{p}.actuator"))?,
                };
                (
                    self.force_name(name.as_ref(), format!("rsda_{k}"), p)?,
                    kind.into(),
                )
            }
            ForceSpec::ViscousFriction {
                name,
                joint,
                damping,
            } => {
                let jp = format!("{p}.joint");
                let Some(info) = self.joints.get(joint).cloned() else {
                    return fail(
                        jp,
                        format!(
                            "no joint named '{joint}'{}",
                            did_you_mean(joint, self.joints.keys().map(String::as_str))
                        ),
                    );
                };
                let c = self.non_negative(Some(damping), 0.0, &format!("{p}.damping"))?;
                let kind = match info {
                    JointInfo::Revolute { bi, bj, .. } => Rsda {
                        body_i: bi,
                        body_j: bj,
                        stiffness: 0.0,
                        free_angle: 0.0,
                        damping: c,
                        actuator: TimeFn::Const(0.0),
                    }
                    .into(),
                    JointInfo::Translational { bi, v_i, bj, s_j, .. } => {
                        match TranslationalDamper::new(bi, v_i, bj, s_j, c) {
                            Some(d) => d.into(),
                            None => return fail(jp, "the joint's axis is zero"),
                        }
                    }
                    JointInfo::Other(kind) => {
                        return fail(
                            jp,
                            format!(
                                "viscous friction acts in a revolute or translational joint; '{joint}' is a {kind} joint"
                            ),
                        )
                    }
                };
                (
                    self.force_name(name.as_ref(), format!("viscous_friction_{k}"), p)?,
                    kind,
                )
            }
        };
        if let Some((key, unit)) = left_out {
            self.deferred.push(initial::Deferred {
                quantity: initial::Quantity::Force(self.model.forces.len()),
                field: format!("{p}.{key}"),
                owner: format!("force '{name}'"),
                key,
                unit,
            });
        }
        self.model.add_force(Force { name, kind });
        Ok(())
    }

    /// The reaction body of a force on body `b`: the ground by default.
    fn reaction(&self, r: Option<&String>, b: BodyId, p: &str) -> R<BodyId> {
        let Some(r) = r else {
            return Ok(BodyId::GROUND);
        };
        let path = format!("{p}.reaction");
        let bj = self.body(r, &path)?;
        if bj == b {
            return fail(path, "the reaction body must differ from the body");
        }
        Ok(bj)
    }

    /// A force name, unique among forces.
    fn force_name(&self, given: Option<&String>, default: String, path: &str) -> R<String> {
        let name = given.cloned().unwrap_or(default);
        check_name(&name, "force", &format!("{path}.name"))?;
        if self.model.forces.iter().any(|f| f.name == name) {
            return fail(
                format!("{path}.name"),
                format!("duplicate force name '{name}'"),
            );
        }
        Ok(name)
    }

    fn opt_time_fn(&self, f: Option<&Num>, path: &str) -> R<TimeFn> {
        f.map_or(Ok(TimeFn::Const(0.0)), |f| self.time_fn(f, path))
    }

    fn non_negative(&self, n: Option<&Num>, default: f64, path: &str) -> R<f64> {
        let v = self.opt(n, default, path)?;
        if v < 0.0 {
            return fail(path, format!("must be ≥ 0 (got {})", num(v)));
        }
        Ok(v)
    }
}
