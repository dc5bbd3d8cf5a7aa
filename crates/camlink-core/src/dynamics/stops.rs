//! Joint limits in forward dynamics: end stops as unilateral contacts
//! (`docs/dynamics.md`, "Joint limits and end stops").
//!
//! A joint with [`Limits`] on its coordinate c (a revolute's angle
//! θ = φ_j − φ_i, a translational joint's stroke, a
//! revolute–translational pin's travel; [`Limits::coordinate`]) gets one
//! stop per given limit c₀, a unilateral joint of the run's model named
//! `<joint>.lower` or `<joint>.upper` whose equation, when closed, is
//!
//! Φ = c(q) − c₀ = 0,
//!
//! and whose gap is g = σ (c − c₀), σ = +1 below (lower), −1 above
//! (upper): positive inside the range. [`super::unilateral`] runs them as
//! it runs cam contacts, with the same event location: a stop is open
//! while g > 0, its impact located where g falls through zero (Newton's
//! restitution law on its row, [`super::impact`]), and a closed stop
//! opens where its force −σλ (N, or N·m for an angle) would pull. A
//! compliant stop is open throughout, pushing back with the Hunt–Crossley
//! force of [`JointStop`].
//!
//! The stops' channels follow from their joints: `<stop>.gap` (rad or m),
//! `<stop>.state` (1 closed or penetrating, 0 open), the reactions
//! `<stop>.fx …` of the stop's equation, and `<stop>.force` (N, a stroke or
//! travel) or `<stop>.moment` (N·m, an angle): the stop's push into the
//! range. Impacts are in the run's summary, their speeds in rad/s for an
//! angle. A coordinate outside its limits at the written placement is
//! refused.

use crate::constraint::relative::RelativeCoord;
use crate::constraint::Local;
use crate::curve::distance::Gap;
use crate::fmt_num::num;
use crate::force::joint_stop::JointStop;
use crate::force::Force;
use crate::limits::range_text;
use crate::model::{Limits, Model};
use crate::run::{AnalysisError, Kind};

/// One side of a joint's limits in the run's model.
#[derive(Clone, Debug)]
pub struct Stop {
    /// Φ = c(q) − c₀.
    pub coord: RelativeCoord,
    /// σ: +1 for a lower stop, −1 for an upper one.
    pub sign: f64,
    /// The channel of the stop's push: `force` or `moment`.
    pub load: &'static str,
}

impl Stop {
    /// The gap g = σ (c − c₀) and its rate at bodies (q_i, q_j), (q̇_i, q̇_j).
    pub fn gap(&self, q: [[f64; 3]; 2], qd: [[f64; 3]; 2]) -> Gap {
        let x = Local {
            q,
            qd,
            ..Local::default()
        };
        let (c, rate) = self.coord.value_and_rate(&x);
        Gap {
            gap: self.sign * (c - self.coord.f.value(0.0)),
            rate: self.sign * rate,
            params: [0.0; 2],
            points: [[0.0; 2]; 2],
            normal: [0.0; 2],
        }
    }

    /// The stop's push into the range (N or N·m) from the multiplier λ of
    /// its equation: −σλ.
    pub fn push(&self, lambda: f64) -> f64 {
        -self.sign * lambda
    }

    /// The weight of its row in [`super::impact::solve`]: −σ.
    pub fn impact_rows(&self) -> [(usize, f64); 1] {
        [(0, -self.sign)]
    }
}

/// True when some joint of `model` has limits.
pub fn any(model: &Model) -> bool {
    model.joints.iter().any(|j| j.limits.is_some())
}

/// The model a forward-dynamics run integrates: `model` with one
/// unilateral joint per given limit appended (limits removed), and each
/// stop's joint index in it. Refuses a coordinate outside its limits at
/// the written placement, with the values.
pub fn expand(model: &Model) -> Result<(Model, Vec<(usize, Stop)>), AnalysisError> {
    let mut out = model.clone();
    let mut stops = Vec::new();
    let asm = crate::assembly::Assembly::new(model);
    let q0 = asm.initial_q(model);
    for (j, joint) in model.joints.iter().enumerate() {
        let Some(limits) = joint.limits else {
            continue;
        };
        let bad = |what: String| {
            AnalysisError::new(
                Kind::InvalidInput,
                0.0,
                format!("joint '{}': {what}", joint.name),
            )
        };
        limits.validate(&joint.constraint).map_err(bad)?;
        let (what, unit) = Limits::coordinate_name(&joint.constraint).expect("validated");
        let x = asm.local(model, j, &q0, &[], 0.0);
        let c = Limits::coordinate(&joint.constraint, 0.0).expect("validated");
        let (c0, _) = c.value_and_rate(&x);
        let past = limits.lower.is_some_and(|lo| c0 < lo) || limits.upper.is_some_and(|hi| c0 > hi);
        if past {
            return Err(bad(format!(
                "its {what} at the start, {} {unit}, is outside its limits {}",
                num(c0),
                range_text(&limits, unit)
            )));
        }
        let load = if unit == "rad" { "moment" } else { "force" };
        for (side, sign, value) in [("lower", 1.0, limits.lower), ("upper", -1.0, limits.upper)] {
            let Some(value) = value else {
                continue;
            };
            let coord = Limits::coordinate(&joint.constraint, value).expect("validated");
            let name = format!("{}.{side}", joint.name);
            if let Some(law) = limits.law.compliant {
                let force = JointStop {
                    coord: coord.clone(),
                    sign,
                    law,
                };
                out.add_force(Force::new(name.clone(), force));
            }
            out.add_joint(name, coord.clone());
            let added = out.joints.len() - 1;
            out.joints[added].unilateral = Some(limits.law);
            stops.push((added, Stop { coord, sign, load }));
        }
        out.joints[j].limits = None;
    }
    Ok((out, stops))
}
