//! Redundant constraint equations in the dynamics analyses.
//!
//! A model whose Φ_q has dependent rows (parallel cranks, a pantograph, a
//! doubly supported shaft) determines its motion but not how its
//! reactions split among the joints involved: Φ_qᵀλ = f has a family of
//! solutions λ + w, Φ_qᵀw = 0. The analyses detect the dependent rows once,
//! at the start and after a small allowed motion (so that a singular
//! starting position is not taken for redundancy) (Gram–Schmidt on the rows of Φ_q, as `camlink check` does,
//! [`crate::diagnose::redundant_equations`]), solve through the regularised
//! augmented matrix ([`super::system`]) and report the minimum-norm λ (no
//! component w), with a warning that names the equations and the joints
//! whose reactions are not unique.

use super::project;
use super::system::{Augmented, System};
use crate::diagnose::{dense_jacobian, redundant_equations, svd_rank};
use crate::run::{Kind, Warning};

/// The redundant equations of a model and the joints they involve.
#[derive(Clone, Debug, PartialEq)]
pub struct Redundant {
    /// `joint.equation` of each dependent row, in model order.
    pub equations: Vec<String>,
    /// The joints of those rows and of the rows they depend on, in model
    /// order: their reactions are not unique.
    pub joints: Vec<String>,
}

impl Redundant {
    /// The redundant equations of the model assembled at `q` (m or rad)
    /// and time `t` (s); None when every equation is independent.
    ///
    /// Rows dependent at `q` may only mark a singular position (the flat
    /// position of a parallelogram): the rank is measured again after a
    /// small motion that the constraints allow (a mix of the null-space
    /// directions of Φ_q, some 0.05 rad, projected back onto Φ = 0), and
    /// the equations dependent there are the redundant ones.
    pub fn detect(sys: &System, aug: &mut Augmented, q: &[f64], t: f64) -> Option<Redundant> {
        if redundant_equations(sys.model, &sys.asm, q, t).is_empty() {
            return None;
        }
        let j = dense_jacobian(sys.model, &sys.asm, q, t);
        let (_, _, null) = svd_rank(&j);
        let mut moved = q.to_vec();
        let angles = sys.asm.angle_mask(sys.model);
        let mut v = vec![0.0; q.len()];
        for (k, basis) in null.iter().enumerate() {
            let w = 1.0 / (k as f64 + 1.37);
            v.iter_mut().zip(basis).for_each(|(a, b)| *a += w * b);
        }
        let big = (0..v.len())
            .filter(|&k| angles[k])
            .fold(0.0f64, |a, k| a.max(v[k].abs()))
            .max(1e-300);
        moved
            .iter_mut()
            .zip(&v)
            .for_each(|(x, d)| *x += 0.05 * d / big);
        project::positions(sys, aug, &mut moved, t, 1e-12, 100).ok()?;
        let found = redundant_equations(sys.model, &sys.asm, &moved, t);
        if found.is_empty() {
            return None;
        }
        let joint = |e: &str| e.rsplit_once('.').map_or(e, |(j, _)| j).to_string();
        let mut involved: Vec<String> = found
            .iter()
            .flat_map(|r| {
                std::iter::once(joint(&r.equation))
                    .chain(r.depends_on.iter().map(|(e, _)| joint(e)))
            })
            .collect();
        let order = |name: &String| {
            sys.model
                .joints
                .iter()
                .position(|j| &j.name == name)
                .unwrap_or(usize::MAX)
        };
        involved.sort_by_key(order);
        involved.dedup();
        Some(Redundant {
            equations: found.into_iter().map(|r| r.equation).collect(),
            joints: involved,
        })
    }

    /// The warning of a run on a redundant model, at time `t` (s).
    pub fn warning(&self, t: f64) -> Warning {
        Warning {
            kind: Kind::Redundant,
            time: t,
            joints: self.joints.clone(),
            message: format!(
                "{} redundant constraint equation(s) ({}): the motion is determined, but the \
                 reactions of joints {} are not unique; the minimum-norm split is reported",
                self.equations.len(),
                self.equations.join(", "),
                self.joints.join(", ")
            ),
        }
    }
}
