//! Design checks of the curve contacts: what a cam designer needs to hear
//! before the run, and what must stop a run that has left the mechanism's
//! real geometry.
//!
//! Before the run, [`check`] reports as [`Finding`]s:
//! - a flat-faced follower on a cam profile with concave parts: a flat face
//!   cannot touch them (the α ranges are named, in degrees too for a polar
//!   profile);
//! - a roller (a circular follower curve, radius r) on a cam whose smallest
//!   concave radius of curvature is below r: the cam is undercut there, the
//!   roller cannot reach the bottom of the hollow.
//!
//! Both are warnings, because a run that keeps the contact away from those
//! parts is valid. During the run, [`StepGuard::check`], called after every
//! step, turns them into analysis errors naming the time and the joint when
//! the contact actually gets there, and also stops a contact that runs off
//! the end of an open curve (a slot).
//!
//! Concave means curving away from the follower: for a closed curve, signed
//! curvature κ (positive turning left as the parameter grows) times the
//! curve's orientation (+1 counterclockwise, −1 clockwise) is negative.
//! Polar profiles are counterclockwise. The checks assume the follower
//! touches a closed cam from outside; open cam curves are not checked for
//! concavity.

use std::fmt;

use crate::assembly::Assembly;
use crate::constraint::Feature;
use crate::contact::ContactView;
use crate::curve::Curve;
use crate::fmt_num::num;
use crate::model::Model;
use crate::run::{AnalysisError, Kind};

/// Samples per curve for the pre-run checks.
const SAMPLES: usize = 720;
/// Relative curvature below which a curve counts as straight.
const FLAT: f64 = 1e-9;
/// Relative tolerance of the per-step checks.
const STEP_TOL: f64 = 1e-6;

/// How serious a finding is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    /// The design may be unsound; the run may still be valid.
    Warning,
    /// The model cannot be analysed as given.
    Error,
}

/// One design finding about a joint.
#[derive(Clone, Debug, PartialEq)]
pub struct Finding {
    pub severity: Severity,
    /// The joint concerned.
    pub joint: String,
    pub message: String,
}

impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let level = match self.severity {
            Severity::Warning => "warning",
            Severity::Error => "error",
        };
        write!(f, "{level}: joint '{}': {}", self.joint, self.message)
    }
}

/// The design checks of every curve-contact joint of `model`.
pub fn check(model: &Model) -> Vec<Finding> {
    findings(model).into_iter().map(|(_, f)| f).collect()
}

/// The findings with the index of their joint.
fn findings(model: &Model) -> Vec<(usize, Finding)> {
    let mut out = Vec::new();
    for v in ContactView::all(model) {
        let k = v.joint;
        let j = &model.joints[k];
        match v.sides {
            // A flat face on a cam: the cam must be convex.
            [Feature::Curve(cam), Feature::Face(_)] | [Feature::Face(_), Feature::Curve(cam)] => {
                let Some(o) = cam.orientation() else {
                    continue;
                };
                let name = v.own_name(face_cam_own(&v));
                let tol = FLAT * cam.max_curvature(SAMPLES);
                let r = cam.ranges_where(SAMPLES, |s| o * cam.curvature(s) < -tol);
                if !r.is_empty() {
                    out.push((
                        k,
                        Finding {
                            severity: Severity::Warning,
                            joint: j.name.clone(),
                            message: format!(
                                "the flat-faced follower's cam profile is concave for {}: \
                             a flat face cannot touch it there, and leaves the profile at \
                             the edges of these ranges",
                                describe_ranges(cam, name, &r)
                            ),
                        },
                    ));
                }
            }
            // A roller on a cam: the cam's hollows must be wider than it.
            [Feature::Curve(ci), Feature::Curve(cj)] => {
                let Some((cam, r, which)) = roller_pair(ci, cj) else {
                    continue;
                };
                let Some(o) = cam.orientation() else {
                    continue;
                };
                // Smallest concave radius of curvature, sampled.
                let (s0, s1) = cam.range();
                let min = (0..SAMPLES)
                    .map(|k| s0 + (s1 - s0) * k as f64 / SAMPLES as f64)
                    .map(|s| (o * cam.curvature(s), s))
                    .filter(|(k, _)| *k < 0.0)
                    .map(|(k, s)| (-1.0 / k, s))
                    .fold(None, |m: Option<(f64, f64)>, v| match m {
                        Some(m) if m.0 <= v.0 => Some(m),
                        _ => Some(v),
                    });
                if let Some((rho, at)) = min.filter(|m| m.0 < r) {
                    let bad = cam.ranges_where(SAMPLES, |s| o * cam.curvature(s) < -1.0 / r);
                    let name = v.own_name(which);
                    out.push((
                        k,
                        Finding {
                            severity: Severity::Warning,
                            joint: j.name.clone(),
                            message: format!(
                                "the roller's radius {} m exceeds the cam's smallest concave \
                             radius of curvature {} m (at {name} = {}): the cam is \
                             undercut for {}, where the roller cannot follow the profile",
                                num(r),
                                num(rho),
                                value(cam, at),
                                describe_ranges(cam, name, &bad)
                            ),
                        },
                    ));
                }
            }
            _ => {}
        }
    }
    out
}

/// The own coordinate of the cam curve of a contact between a flat face
/// and a cam.
fn face_cam_own(v: &ContactView) -> usize {
    (0..2).find_map(|s| v.own_of(s)).unwrap_or(0)
}

/// What the per-step guard watches on one contact parameter.
#[derive(Clone, Debug)]
enum Watch {
    /// An open curve: the parameter must stay in [s₀, s₁].
    Ends { s0: f64, s1: f64 },
    /// A flat face on a closed cam: o κ ≥ −tol at the contact.
    Convex { o: f64, tol: f64 },
    /// A roller of radius r on a closed cam: o κ ≥ −1/r at the contact.
    Roller { o: f64, r: f64 },
}

#[derive(Clone, Debug)]
struct Item {
    joint: usize,
    /// Which own coordinate: 0 for α_i (or the point–follower's α_j), 1
    /// for the cam–follower's α_j.
    own: usize,
    watch: Watch,
}

/// Per-step checks of the contacts, set up once.
#[derive(Clone, Debug, Default)]
pub struct StepGuard {
    items: Vec<Item>,
    /// The design findings, to explain a failed step.
    findings: Vec<(usize, Finding)>,
}

impl StepGuard {
    /// Finds what to watch in `model`.
    pub fn new(model: &Model) -> Self {
        let mut items = Vec::new();
        for v in ContactView::all(model) {
            let k = v.joint;
            for own in 0..2 {
                if let Some((_, c)) = v.own_curve(own) {
                    if !c.closed() {
                        let (s0, s1) = c.range();
                        items.push(Item {
                            joint: k,
                            own,
                            watch: Watch::Ends { s0, s1 },
                        });
                    }
                }
            }
            match v.sides {
                [Feature::Curve(cam), Feature::Face(_)]
                | [Feature::Face(_), Feature::Curve(cam)] => {
                    if let Some(o) = cam.orientation() {
                        let tol = STEP_TOL * cam.max_curvature(SAMPLES);
                        items.push(Item {
                            joint: k,
                            own: face_cam_own(&v),
                            watch: Watch::Convex { o, tol },
                        });
                    }
                }
                [Feature::Curve(ci), Feature::Curve(cj)] => {
                    if let Some((cam, r, which)) = roller_pair(ci, cj) {
                        if let Some(o) = cam.orientation() {
                            items.push(Item {
                                joint: k,
                                own: which,
                                watch: Watch::Roller { o, r },
                            });
                        }
                    }
                }
                _ => {}
            }
        }
        StepGuard {
            items,
            findings: findings(model),
        }
    }

    /// Adds to a failed step's error the design findings of the joints it
    /// names: a follower that meets a concave part of its cam or an
    /// undercut does not enter it, its contact equations lose their
    /// solution at the edge, and Newton's method stops there.
    pub fn explain(&self, model: &Model, mut e: AnalysisError) -> AnalysisError {
        for (k, f) in &self.findings {
            if e.joints.contains(&model.joints[*k].name) {
                e.message.push_str(&format!(
                    "; possible cause: joint '{}': {}",
                    f.joint, f.message
                ));
            }
        }
        e
    }

    /// Checks the contacts at coordinates `q` (time `t`, s): an error names
    /// the time, the joint and the contact parameter.
    pub fn check(
        &self,
        model: &Model,
        asm: &Assembly,
        q: &[f64],
        t: f64,
    ) -> Result<(), AnalysisError> {
        for it in &self.items {
            let joint = &model.joints[it.joint];
            let a = q[asm.own_col(it.joint) + it.own];
            let Some(view) = ContactView::of(model, it.joint) else {
                continue;
            };
            let Some((_, curve)) = view.own_curve(it.own) else {
                continue;
            };
            let name = view.own_name(it.own);
            let (kind, message) = match it.watch {
                Watch::Ends { s0, s1 } => {
                    let tol = 1e-9 * (s1 - s0);
                    if a >= s0 - tol && a <= s1 + tol {
                        continue;
                    }
                    let (end, at) = if a > s1 { ("upper", s1) } else { ("lower", s0) };
                    (
                        Kind::OffCurve,
                        format!(
                            "the contact ran off the {end} end ({at}) of the open curve of \
                             joint '{}': {name} = {a} is outside its range [{s0}, {s1}]",
                            joint.name
                        ),
                    )
                }
                Watch::Convex { o, tol } => {
                    let k = o * curve.curvature(a);
                    if k >= -tol {
                        continue;
                    }
                    (
                        Kind::Undercut,
                        format!(
                            "the flat-faced follower of joint '{}' touches the cam where it is \
                         concave ({name} = {}, radius of curvature {} m): a flat face \
                         cannot follow this profile",
                            joint.name,
                            value(curve, a),
                            num(-1.0 / k)
                        ),
                    )
                }
                Watch::Roller { o, r } => {
                    let k = o * curve.curvature(a);
                    if k >= -(1.0 + STEP_TOL) / r {
                        continue;
                    }
                    (
                        Kind::Undercut,
                        format!(
                            "the roller of joint '{}' (radius {} m) reaches a hollow of the cam \
                         with a smaller radius of curvature ({} m at {name} = {}): the cam \
                         is undercut there",
                            joint.name,
                            num(r),
                            num(-1.0 / k),
                            value(curve, a)
                        ),
                    )
                }
            };
            return Err(
                AnalysisError::new(kind, t, message).at_joints(vec![joint.name.clone()], 0.0)
            );
        }
        Ok(())
    }
}

/// (cam, roller radius, which own coordinate runs on the cam) when exactly
/// one of the two curves is a circle and the other is closed.
fn roller_pair<'a>(ci: &'a Curve, cj: &'a Curve) -> Option<(&'a Curve, f64, usize)> {
    match (ci.circle_centre(), cj.circle_centre()) {
        (None, Some((_, r))) if ci.closed() => Some((ci, r, 0)),
        (Some((_, r)), None) if cj.closed() => Some((cj, r, 1)),
        _ => None,
    }
}

/// A parameter value with its unit: rad and degrees for a polar profile,
/// the curve's own parameter otherwise.
fn value(c: &Curve, s: f64) -> String {
    match c {
        Curve::Polar(_) => format!("{} rad ({}°)", num(s), num(s.to_degrees())),
        Curve::Parametric(_) => num(s),
    }
}

/// "α_i in [a, b] rad ([a°, b°]), …".
fn describe_ranges(c: &Curve, name: &str, r: &[(f64, f64)]) -> String {
    let one = |&(a, b): &(f64, f64)| match c {
        Curve::Polar(_) => format!(
            "{name} in [{}, {}] rad ([{}°, {}°])",
            num(a),
            num(b),
            num(a.to_degrees()),
            num(b.to_degrees())
        ),
        Curve::Parametric(_) => format!("{name} in [{}, {}]", num(a), num(b)),
    };
    r.iter().map(one).collect::<Vec<_>>().join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::{cam_follower::CamFollower, flat_follower::FlatFollower, Constraint};
    use crate::curve::{Parametric, Polar};
    use crate::model::{Body, BodyId};
    use std::f64::consts::PI;

    fn model_with(c: impl Into<Constraint>) -> Model {
        let mut m = Model::new("m");
        m.add_body(Body::new("cam", [0.0; 3]));
        m.add_body(Body::new("follower", [0.0, 2.0, 0.0]));
        m.add_joint("contact", c);
        m
    }

    #[test]
    fn flat_follower_on_a_three_lobe_cam_names_the_concave_ranges() {
        // ρ = 1 + 0.3 cos 3α is concave about α = π/3, π, 5π/3.
        let cam = Polar::fourier([0.0, 0.0], 1.0, &[0.0, 0.0, 0.3], &[]).unwrap();
        let ff = FlatFollower::new(BodyId(1), cam.into(), BodyId(2), [0.0; 2], [1.0, 0.0]);
        let f = check(&model_with(ff.unwrap()));
        assert_eq!(f.len(), 1, "{f:?}");
        assert_eq!(f[0].severity, Severity::Warning);
        assert!(f[0].message.contains("concave"), "{}", f[0]);
        assert!(f[0].message.contains("°"), "{}", f[0]);
        // Three ranges centred on 60°, 180°, 300°.
        assert_eq!(f[0].message.matches("α_i in").count(), 3, "{}", f[0]);
        // A circle has none.
        let ff = FlatFollower::new(
            BodyId(1),
            Polar::circle([0.2, 0.0], 1.0).unwrap().into(),
            BodyId(2),
            [0.0; 2],
            [1.0, 0.0],
        );
        assert!(check(&model_with(ff.unwrap())).is_empty());
    }

    #[test]
    fn roller_larger_than_the_hollow_is_an_undercut() {
        // Concave radius of curvature of ρ = 1 + 0.3 cos 3α at α = π/3:
        // ρ = 0.7, ρ′ = 0, ρ″ = 2.7: κ = (ρ² − ρρ″)/ρ³ = (0.49 − 1.89)/0.343.
        let cam: Curve = Polar::fourier([0.0, 0.0], 1.0, &[0.0, 0.0, 0.3], &[])
            .unwrap()
            .into();
        let rho_min = 0.343 / 1.4;
        let with = |r: f64| {
            model_with(CamFollower {
                body_i: BodyId(1),
                curve_i: cam.clone(),
                body_j: BodyId(2),
                curve_j: Polar::circle([0.0, 0.0], r).unwrap().into(),
            })
        };
        assert!(check(&with(0.9 * rho_min)).is_empty());
        let f = check(&with(1.1 * rho_min));
        assert_eq!(f.len(), 1, "{f:?}");
        assert!(f[0].message.contains("undercut"), "{}", f[0]);
        assert!(f[0].message.contains(&num(rho_min)), "{}", f[0]);
    }

    #[test]
    fn a_clockwise_closed_spline_is_convex() {
        let pts: Vec<[f64; 2]> = (0..12)
            .map(|k| {
                let a = -(k as f64) * PI / 6.0;
                [a.cos(), 0.5 * a.sin()]
            })
            .collect();
        let c: Curve = Parametric::spline(&pts, true).unwrap().into();
        assert_eq!(c.orientation(), Some(-1.0));
        let ff = FlatFollower::new(BodyId(1), c, BodyId(2), [0.0; 2], [1.0, 0.0]);
        assert!(check(&model_with(ff.unwrap())).is_empty());
    }

    #[test]
    fn ranges_across_the_start_come_back_whole() {
        let c: Curve = Polar::circle([0.0, 0.0], 1.0).unwrap().into();
        let r = c.ranges_where(SAMPLES, |s| !(0.5..=6.0).contains(&s));
        assert_eq!(r.len(), 1, "{r:?}");
        assert!((r[0].0 - 6.0).abs() < 1e-9 && (r[0].1 - (0.5 + 2.0 * PI)).abs() < 1e-9);
    }
}
