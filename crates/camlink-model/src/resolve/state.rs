//! Forces of state: `[[forces]]` expressions that read the motion.
//!
//! Besides `t` and the parameters, a force's expressions may read channels
//! of any body and joint of the model; bodies other than those it acts on
//! (its `body` and its `reaction` body, the ground by default) are the
//! force's read bodies, at most [`MAX_READ`] of them:
//!
//! - `<body>_x`, `_y`, `_phi` (m, m, rad) and `_vx`, `_vy`, `_omega`
//!   (m/s, m/s, rad/s): the body frame's coordinates and velocities;
//! - `<body>_<point>_x`, `_y`, `_vx`, `_vy`: a named point's global
//!   position and velocity;
//! - `<joint>_angle`, `<joint>_rate` of a revolute joint: θ = φ_j − φ_i
//!   (rad) and θ̇ (rad/s);
//! - `<joint>_stroke`, `<joint>_rate` of a translational joint: the
//!   distance s of its point on body j from its point on body i along its
//!   axis (m), and ṡ (m/s),
//!
//! A parameter of the same name shadows a channel.

use std::sync::Arc;

use camlink_core::force::state::{Channel, StateExpr, GROUND_SLOT, READ_SLOT};
use camlink_core::force::MAX_READ;
use camlink_core::math::V2;
use camlink_core::BodyId;

use super::{fail, Ctx, JointInfo, R};
use crate::error::did_you_mean;
use crate::eval;
use crate::file::Num;

/// A channel of the model, before it is placed in a force's slots.
#[derive(Clone, Copy, Debug)]
enum Def {
    Time,
    Body {
        b: BodyId,
        c: usize,
        rate: bool,
    },
    Point {
        b: BodyId,
        s: V2,
        axis: usize,
        rate: bool,
    },
    Angle {
        bi: BodyId,
        bj: BodyId,
        rate: bool,
    },
    Stroke {
        bi: BodyId,
        s_i: V2,
        v_i: V2,
        bj: BodyId,
        s_j: V2,
        rate: bool,
    },
}

impl Def {
    /// The channel in the slots of a force on `bodies` reading `reads`
    /// besides, another body being added to `reads`; the body that would
    /// make more than [`MAX_READ`] read bodies is the error.
    fn place(&self, bodies: [BodyId; 2], reads: &mut Vec<BodyId>) -> Result<Channel, BodyId> {
        let mut slot = |b: BodyId| {
            if b == bodies[0] {
                Ok(0)
            } else if b == bodies[1] {
                Ok(1)
            } else if b.is_ground() {
                Ok(GROUND_SLOT)
            } else if let Some(k) = reads.iter().position(|&r| r == b) {
                Ok(READ_SLOT + k)
            } else if reads.len() < MAX_READ {
                reads.push(b);
                Ok(READ_SLOT + reads.len() - 1)
            } else {
                Err(b)
            }
        };
        Ok(match *self {
            Def::Time => Channel::Time,
            Def::Body { b, c, rate } => Channel::Body {
                slot: slot(b)?,
                c,
                rate,
            },
            Def::Point { b, s, axis, rate } => Channel::Point {
                slot: slot(b)?,
                s,
                axis,
                rate,
            },
            Def::Angle { bi, bj, rate } => Channel::Angle {
                a: slot(bi)?,
                b: slot(bj)?,
                rate,
            },
            Def::Stroke {
                bi,
                s_i,
                v_i,
                bj,
                s_j,
                rate,
            } => Channel::Stroke {
                a: slot(bi)?,
                s_a: s_i,
                v_a: v_i,
                b: slot(bj)?,
                s_b: s_j,
                rate,
            },
        })
    }
}

/// The names that are not channels: the constants of the language.
fn is_builtin_constant(name: &str) -> bool {
    matches!(name, "pi" | "π" | "e")
}

impl Ctx {
    /// True when `n` is an expression reading more than time and the
    /// parameters.
    pub(super) fn reads_motion(&self, n: Option<&Num>) -> bool {
        let Some(Num::Expr(src)) = n else {
            return false;
        };
        camlink_expr::names(src).is_ok_and(|names| {
            names
                .iter()
                .any(|&n| n != "t" && !self.params.contains_key(n) && !is_builtin_constant(n))
        })
    }

    /// Every channel of the model, by name, in a stable order.
    fn channel_defs(&self) -> Vec<(String, Def)> {
        let mut out = vec![("t".to_string(), Def::Time)];
        for (k, body) in self.model.bodies.iter().enumerate().skip(1) {
            let b = BodyId(k);
            let n = &body.name;
            for (c, what) in ["x", "y", "phi"].iter().enumerate() {
                out.push((format!("{n}_{what}"), Def::Body { b, c, rate: false }));
            }
            for (c, what) in ["vx", "vy", "omega"].iter().enumerate() {
                out.push((format!("{n}_{what}"), Def::Body { b, c, rate: true }));
            }
            for p in &body.points {
                for (axis, what) in ["x", "y"].iter().enumerate() {
                    let s = p.s;
                    out.push((
                        format!("{n}_{}_{what}", p.name),
                        Def::Point {
                            b,
                            s,
                            axis,
                            rate: false,
                        },
                    ));
                    out.push((
                        format!("{n}_{}_v{what}", p.name),
                        Def::Point {
                            b,
                            s,
                            axis,
                            rate: true,
                        },
                    ));
                }
            }
        }
        let mut joints: Vec<(&String, &JointInfo)> = self.joints.iter().collect();
        joints.sort_by(|a, b| a.0.cmp(b.0));
        for (name, info) in joints {
            match *info {
                JointInfo::Revolute { bi, bj, .. } => {
                    for (what, rate) in [("angle", false), ("rate", true)] {
                        out.push((format!("{name}_{what}"), Def::Angle { bi, bj, rate }));
                    }
                }
                JointInfo::Translational {
                    bi,
                    s_i,
                    v_i,
                    bj,
                    s_j,
                } => {
                    for (what, rate) in [("stroke", false), ("rate", true)] {
                        out.push((
                            format!("{name}_{what}"),
                            Def::Stroke {
                                bi,
                                s_i,
                                v_i,
                                bj,
                                s_j,
                                rate,
                            },
                        ));
                    }
                }
                JointInfo::Other(_) => {}
            }
        }
        out
    }

    /// The expression `n` of a force on `bodies` ([body, reaction body]),
    /// with the channels it reads; `None` when `n` is absent. Bodies it
    /// reads besides `bodies` are added to `reads`, the force's read
    /// bodies (shared by its expressions).
    pub(super) fn state_expr(
        &self,
        n: Option<&Num>,
        bodies: [BodyId; 2],
        reads: &mut Vec<BodyId>,
        path: &str,
    ) -> R<Option<StateExpr>> {
        let src = match n {
            None => return Ok(None),
            Some(Num::Value(v)) if v.is_finite() => format!("{v:?}"),
            Some(Num::Value(v)) => {
                return fail(path, format!("value is not a finite number ({v})"));
            }
            Some(Num::Expr(src)) => src.clone(),
        };
        let names = eval::names(&src).or_else(|e| fail(path, e))?;
        let defs = self.channel_defs();
        let mut inputs: Vec<&str> = Vec::new();
        let mut channels = Vec::new();
        for name in names {
            if self.params.contains_key(name) || is_builtin_constant(name) {
                continue;
            }
            let Some((_, def)) = defs.iter().find(|(n, _)| n == name) else {
                return fail(path, self.unknown_channel(name, &defs, bodies));
            };
            match def.place(bodies, reads) {
                Ok(c) => channels.push(c),
                Err(b) => {
                    let names: Vec<&str> = reads
                        .iter()
                        .map(|&r| self.model.body(r).name.as_str())
                        .collect();
                    return fail(
                        path,
                        format!(
                            "'{name}' reads body '{}'; a force reads the motion of its own \
                             bodies ({}) and of at most {MAX_READ} others, and this one reads \
                             '{}' already",
                            self.model.body(b).name,
                            self.force_bodies(bodies),
                            names.join("', '")
                        ),
                    );
                }
            }
            inputs.push(name);
        }
        let expr = eval::state_expr(&src, &inputs, &self.params).or_else(|e| fail(path, e))?;
        Ok(Some(StateExpr {
            expr: Arc::new(expr),
            channels,
        }))
    }

    /// "body 'a' and ground" for messages.
    fn force_bodies(&self, bodies: [BodyId; 2]) -> String {
        format!(
            "'{}' and '{}'",
            self.model.body(bodies[0]).name,
            self.model.body(bodies[1]).name
        )
    }

    /// The message for a name that is neither a parameter nor a channel:
    /// the closest channel, and the channels this force can read.
    fn unknown_channel(&self, name: &str, defs: &[(String, Def)], bodies: [BodyId; 2]) -> String {
        let readable: Vec<&str> = defs.iter().map(|(n, _)| n.as_str()).collect();
        let mut params: Vec<&str> = self.params.keys().map(String::as_str).collect();
        params.sort_unstable();
        let hint = did_you_mean(name, readable.iter().copied().chain(params.iter().copied()));
        // The channels nearest the name: those sharing its first word, else all.
        let stem = name.split('_').next().unwrap_or(name);
        let near: Vec<&str> = readable
            .iter()
            .copied()
            .filter(|n| n.split('_').next() == Some(stem))
            .collect();
        let list = if near.is_empty() { &readable } else { &near };
        const SHOWN: usize = 16;
        let mut shown = list
            .iter()
            .take(SHOWN)
            .copied()
            .collect::<Vec<_>>()
            .join(", ");
        if list.len() > SHOWN {
            shown += &format!(", … ({} in all)", list.len());
        }
        format!(
            "unknown name '{name}'{hint}; a force of {} reads t, the parameters and the channels {shown}",
            self.force_bodies(bodies)
        )
    }
}
