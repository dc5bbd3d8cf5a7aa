//! Joint limits ([`Limits`]): the coordinate a limit bounds, its value
//! and rate at a state, and the kinematic check of a driven motion.
//!
//! A limited coordinate c(q) is a revolute's angle θ = φ_j − φ_i (rad), a
//! translational joint's stroke s (m) or a revolute–translational pin's
//! travel along its line (m), written as the relative constraint
//! Φ = c(q) − c₀ of [`Limits::coordinate`]; its value and rate ċ = Φ_q q̇
//! come from [`RelativeCoord::value_and_rate`].
//!
//! Limits are a dynamics feature: forward dynamics holds c in
//! [lower, upper] with unilateral stops ([`crate::dynamics::stops`]).
//! Kinematics follows its drivers whatever the limits say, and a driven
//! motion that leaves the range is reported as a warning of kind
//! [`Kind::LimitExceeded`] per joint ([`LimitWatch`]), with where it first
//! left and its greatest excursion.

use crate::assembly::Assembly;
use crate::constraint::relative::RelativeCoord;
use crate::fmt_num::num;
use crate::model::{Limits, Model};
use crate::run::{Kind, Warning};

/// Excursion (m or rad) past a limit below which kinematics does not
/// warn: the rounding of a motion that just touches its stop.
pub(crate) const EXCEEDED: f64 = 1e-9;

/// The range text of `limits`, e.g. `[-0.5, 1] rad` or `[0.1, ∞) m`.
pub fn range_text(limits: &Limits, unit: &str) -> String {
    let lo = limits
        .lower
        .map_or("(-∞".to_string(), |v| format!("[{}", num(v)));
    let hi = limits
        .upper
        .map_or("∞)".to_string(), |v| format!("{}]", num(v)));
    format!("{lo}, {hi} {unit}")
}

/// Where a limited coordinate left its range in a kinematic run.
#[derive(Clone, Copy, Debug)]
struct Excursion {
    /// First time outside (s) and the value there.
    first: (f64, f64),
    /// The value farthest outside, and when.
    worst: (f64, f64),
    /// How far outside it is (m or rad).
    past: f64,
}

/// The check of a kinematic run against the model's joint limits.
pub(crate) struct LimitWatch {
    /// Per limited joint: its index, coordinate, limits and excursion.
    joints: Vec<(usize, RelativeCoord, Limits, Option<Excursion>)>,
}

impl LimitWatch {
    pub(crate) fn new(model: &Model) -> Self {
        let joints = model
            .joints
            .iter()
            .enumerate()
            .filter_map(|(j, joint)| {
                let limits = joint.limits?;
                let coord = Limits::coordinate(&joint.constraint, 0.0)?;
                Some((j, coord, limits, None))
            })
            .collect();
        LimitWatch { joints }
    }

    /// Looks at the coordinates at time `t` (s) and positions `q`.
    pub(crate) fn observe(&mut self, model: &Model, asm: &Assembly, q: &[f64], t: f64) {
        for (j, coord, limits, exc) in &mut self.joints {
            let x = asm.local(model, *j, q, &[], t);
            let (c, _) = coord.value_and_rate(&x);
            let past =
                (limits.lower.map_or(0.0, |lo| lo - c)).max(limits.upper.map_or(0.0, |hi| c - hi));
            if past <= EXCEEDED {
                continue;
            }
            match exc {
                None => {
                    *exc = Some(Excursion {
                        first: (t, c),
                        worst: (t, c),
                        past,
                    })
                }
                Some(e) if past > e.past => {
                    e.worst = (t, c);
                    e.past = past;
                }
                Some(_) => {}
            }
        }
    }

    /// One warning per joint whose coordinate left its range.
    pub(crate) fn warnings(&self, model: &Model) -> Vec<Warning> {
        self.joints
            .iter()
            .filter_map(|(j, _, limits, exc)| {
                let e = exc.as_ref()?;
                let joint = &model.joints[*j];
                let (what, unit) = Limits::coordinate_name(&joint.constraint)?;
                Some(Warning {
                    kind: Kind::LimitExceeded,
                    time: e.first.0,
                    joints: vec![joint.name.clone()],
                    message: format!(
                        "joint '{}': the driven motion takes its {what} out of its limits \
                         {} from t = {} s ({} {unit}), farthest at t = {} s ({} {unit}); \
                         kinematics follows the drivers, forward dynamics would stop it",
                        joint.name,
                        range_text(limits, unit),
                        num(e.first.0),
                        num(e.first.1),
                        num(e.worst.0),
                        num(e.worst.1),
                    ),
                })
            })
            .collect()
    }
}
