//! Defaults marked *initial*: values measured in the written placement,
//! checked against the assembled one.
//!
//! A value the file leaves out (a translational joint's `angle`, a
//! coupler's `length`, a slot's `offset`, a gear's `phase`, a spring's
//! `free_length`, …) is measured where the file places the bodies. That
//! placement may be rough, and a value measured in a rough placement is not
//! what the drawing meant. Which value was meant is not defined by the
//! joints (each left-out value removes a freedom they leave), so the value
//! measured in the written placement is kept, and it is checked: when the
//! written placement does not satisfy the joints whose values are all given
//! (drivers aside, as a drawing may show any position of them, and curve
//! contacts, which find their contact from the placement), the nearest
//! placement that does (least change of the coordinates,
//! [`project::positions`]) is found, the value is measured there too, and
//! a value that differs by more than [`MOVED`] is reported
//! ([`KIND_UNASSEMBLED`]) with the joint, the value used and the assembled
//! value. When those joints do not assemble, every left-out value is
//! reported.

use camlink_core::constraint::composite::RevoluteTranslational;
use camlink_core::constraint::{absolute::Coord, relative::RelCoord};
use camlink_core::dynamics::project;
use camlink_core::dynamics::system::{Augmented, System};
use camlink_core::fmt_num::num;
use camlink_core::math::{dot, norm, perp, point, rot, sub};
use camlink_core::{BodyId, Constraint, Equations, ForceKind, Model, ModelWarning};

/// Warning kind: a default measured in the written placement, which does
/// not satisfy the joints given in full, differs from its value in the
/// assembled placement (or they do not assemble).
pub(crate) const KIND_UNASSEMBLED: &str = "default_unassembled";

/// Largest max |Φ| (m or rad) of the joints given in full at which the
/// written placement counts as assembled; also the projection's tolerance.
const ASSEMBLED: f64 = 1e-12;
/// Change of a default (m or rad) beyond which it is reported.
const MOVED: f64 = 1e-9;

/// The quantity a default measures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Quantity {
    /// A joint's value (its kind says which).
    Joint(usize),
    /// A force's `free_length` or `free_angle`.
    Force(usize),
}

/// A value left out of the file and measured in the placement.
#[derive(Clone, Debug)]
pub(crate) struct Deferred {
    pub quantity: Quantity,
    /// The file's field, e.g. `joints[3].offset`.
    pub field: String,
    /// The joint or force, e.g. `joint 'slot'`.
    pub owner: String,
    /// The key, e.g. `offset`, and its unit.
    pub key: &'static str,
    pub unit: &'static str,
}

/// The value of a default in the placement `q` (per body, ground first).
fn measure(model: &Model, d: &Deferred, q: &[[f64; 3]]) -> f64 {
    let at = |b: BodyId| q[b.0];
    let r = |b: BodyId, s| point(q[b.0], s);
    match d.quantity {
        Quantity::Joint(j) => match &model.joints[j].constraint {
            Constraint::Translational(c) => at(c.body_j)[2] - at(c.body_i)[2],
            Constraint::RevoluteRevolute(c) => norm(sub(r(c.body_j, c.s_j), r(c.body_i, c.s_i))),
            Constraint::RevoluteTranslational(c) => {
                let u = rot(at(c.body_j)[2], c.v_j);
                dot(perp(u), sub(r(c.body_i, c.s_i), r(c.body_j, c.s_j)))
            }
            Constraint::AbsoluteCoord(c) => match c.coord {
                Coord::X => r(c.body, c.s)[0],
                Coord::Y => r(c.body, c.s)[1],
                Coord::Phi => at(c.body)[2],
            },
            Constraint::AbsoluteDistance(c) => norm(sub(r(c.body, c.s), c.ground_point)),
            Constraint::RelativeCoord(c) => {
                let dr = sub(r(c.body_j, c.s_j), r(c.body_i, c.s_i));
                match c.coord {
                    RelCoord::X => dr[0],
                    RelCoord::Y => dr[1],
                    RelCoord::Phi => at(c.body_j)[2] - at(c.body_i)[2],
                    RelCoord::Along(v) => dot(rot(at(c.body_i)[2], v), dr),
                }
            }
            Constraint::RelativeDistance(c) => norm(sub(r(c.body_j, c.s_j), r(c.body_i, c.s_i))),
            Constraint::Gear(c) => c.phase_from(at(c.body_i), at(c.body_j)),
            Constraint::RackPinion(c) => c.phase_from(at(c.body_i), at(c.body_j)),
            _ => f64::NAN,
        },
        Quantity::Force(f) => match &model.forces[f].kind {
            ForceKind::Tsda(s) => norm(sub(r(s.body_j, s.s_j), r(s.body_i, s.s_i))),
            ForceKind::Rsda(s) => at(s.body_j)[2] - at(s.body_i)[2],
            _ => f64::NAN,
        },
    }
}

/// The joints given in full: `model`'s joints without its drivers, its
/// curve contacts (which find their contact from the placement) and the
/// equations whose values are deferred (a translational joint
/// keeps its line, a revolute–translational joint with `offset` 0 of the
/// same points).
fn given_in_full(model: &Model, deferred: &[Deferred]) -> Model {
    let mut rest = model.clone();
    rest.forces.clear();
    rest.joints.clear();
    for (j, joint) in model.joints.iter().enumerate() {
        if joint.driver || joint.constraint.contact_sides().is_some() {
            continue;
        }
        if !deferred.iter().any(|d| d.quantity == Quantity::Joint(j)) {
            rest.joints.push(joint.clone());
            continue;
        }
        if let Constraint::Translational(c) = &joint.constraint {
            let line = RevoluteTranslational {
                body_i: c.body_j,
                s_i: c.s_j,
                body_j: c.body_i,
                s_j: c.s_i,
                v_j: c.v_i,
                offset: 0.0,
            };
            rest.add_joint(joint.name.clone(), line);
        }
    }
    rest
}

/// Checks the deferred defaults (measured in the written placement)
/// against the assembled placement, adding a warning to `model` for each
/// that differs there (or for every one, when it does not assemble).
pub(crate) fn check(model: &mut Model, deferred: &[Deferred]) {
    if deferred.is_empty() {
        return;
    }
    let given: Vec<[f64; 3]> = model.bodies.iter().map(|b| b.q0).collect();
    let rest = given_in_full(model, deferred);
    let sys = System::new(&rest);
    let mut q = sys.asm.initial_q(&rest);
    let mut phi = vec![0.0; sys.asm.m];
    sys.asm.phi(&rest, &q, 0.0, &mut phi);
    let residual = phi.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    if residual <= ASSEMBLED {
        return;
    }
    let projected = Augmented::new(&sys, &q)
        .map_err(|e| e.to_string())
        .and_then(|mut aug| {
            project::positions(&sys, &mut aug, &mut q, 0.0, ASSEMBLED, 100).map_err(|e| e.message)
        });
    let assembled: Option<Vec<[f64; 3]>> = projected.as_ref().ok().map(|_| {
        (0..model.bodies.len())
            .map(|b| match sys.asm.body_col(b) {
                Some(c) => [q[c], q[c + 1], q[c + 2]],
                None => given[b],
            })
            .collect()
    });
    for d in deferred {
        let used = measure(model, d, &given);
        let head = format!(
            "{}: `{}` is left out, so it is measured where the bodies are written: {} {} \
             (used); that placement does not satisfy the joints given in full (largest \
             residual {})",
            d.owner,
            d.key,
            num(used),
            d.unit,
            num(residual)
        );
        let message = match (&assembled, &projected) {
            (Some(at), _) => {
                let v = measure(model, d, at);
                if (v - used).abs() <= MOVED {
                    continue;
                }
                format!(
                    "{head}, and in the nearest placement that does it is {} {} \
                     (assembled); give `{}` to say which is meant",
                    num(v),
                    d.unit,
                    d.key
                )
            }
            (None, Err(why)) => format!(
                "{head}, and they do not assemble from it ({why}); give `{}` to say \
                 what is meant",
                d.key
            ),
            (None, Ok(_)) => continue,
        };
        model.warnings.push(ModelWarning {
            kind: KIND_UNASSEMBLED,
            field: d.field.clone(),
            message,
        });
    }
}
