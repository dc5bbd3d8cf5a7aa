//! Contact forces of the curve contacts from λ, and follower lift-off.
//!
//! A curve contact's equations act on its bodies through −Φ_qᵀλ like any
//! joint's ([`super::reaction`]); F_j, the force the contact exerts on
//! body j (N, global frame), splits along the common normal and tangent at
//! the contact point:
//!
//! - `<joint>.normal_force` N (N): positive when the bodies press on each
//!   other (compression: the cam pushes the follower), negative when the
//!   contact would have to pull them together;
//! - `<joint>.tangential_force` T (N): along the unit tangent of C_i in the
//!   direction of increasing α_i (of the face along u′_j for a flat-faced
//!   follower, of the slot for a pin in a slot). The contacts are
//!   frictionless, so T is zero up to rounding: a check of λ.
//!
//! Which side is "pressing" comes from the material side of the curves
//! (the rules and the normals are [`crate::curve::contact`]'s). A
//! closed curve (every polar profile, a closed parametric curve) bounds its
//! body's material, with outward unit normal n_k = σ_k (−g_k⊥)/|g_k|,
//! σ_k = +1 for a counterclockwise curve, −1 for a clockwise one
//! ([`Curve::orientation`]). Then:
//!
//! - cam–follower, both curves closed, touching from outside
//!   (n_i · n_j < 0): N = F_j · n_i, the force on j pointing out of i;
//!   one inside the other (n_i · n_j > 0: a roller in a ring groove): the
//!   curve of smaller |κ| encloses the other and is a hole in its body, and
//!   N = F_j · n_j when C_j is that hole, −F_j · n_j when C_i is;
//! - cam–follower with one closed curve: that curve is solid,
//!   N = F_j · n_i or N = −F_j · n_j;
//! - cam–flat-faced follower: N = F_j · n_i, the force on the face body
//!   pointing out of the cam;
//! - when no closed curve is present, the solid side of C_i is the side of
//!   the mean of its sampled points (as the flat-faced follower's start
//!   search assumes);
//! - point–follower (pin in a slot): a slot has two walls and pushes either
//!   way; N = F_i · n_s, the force on the pin along the slot's left normal
//!   n_s = g_j⊥/|g_j|, so its sign tells which wall carries the pin.
//!
//! The contacts are bilateral: the equations hold the follower on its cam
//! whatever the sign of N. A physical cam can only push, so where
//! N < 0 a real follower would leave the cam (jump, or float): the motion
//! computed past that point is not what the machine does. [`LiftOffWatch`]
//! reports every interval of negative normal force of a cam contact (not of
//! a pin in a slot), with its start and end times and the cam angle there,
//! as a [`LiftOff`] record in the run's [`Summary`] and as a warning.

use super::reaction::Reaction;
use crate::assembly::Assembly;
use crate::constraint::Feature;
use crate::contact::ContactView;
use crate::curve::contact::{
    away_from, closed_pair, from_side, normal_force, outward, sample_mean,
};
use crate::curve::Curve;
use crate::math::{dot, norm, perp, point, rot, scale, V2};
use crate::model::{BodyId, Model};
use crate::quantity::{Channel, Quantity};
use crate::run::{Crossing, Kind, LiftOff, Summary, Warning};

/// How one contact joint's normal is oriented.
#[derive(Clone, Debug)]
struct Item {
    joint: usize,
    /// σ_i, σ_j: orientations of closed C_i and C_j (`None`: open, or no
    /// curve on that side).
    sides: [Option<f64>; 2],
    /// Mean of C_i's sampled points, in body i's frame.
    mean_i: V2,
    /// The cam body (the body whose angle lift-off reports), for a cam
    /// contact; `None` for a pin in a slot.
    cam: Option<BodyId>,
}

/// The curve contacts of a model (not driven), found once.
#[derive(Clone, Debug, Default)]
pub struct ContactForces {
    items: Vec<Item>,
}

/// (normal N, tangential T) force of a contact (N).
pub type NormalTangential = [f64; 2];

impl ContactForces {
    pub fn new(model: &Model) -> Self {
        let items = ContactView::all(model)
            .filter(|v| !model.joints[v.joint].driver)
            .map(|v| Item {
                joint: v.joint,
                sides: [0, 1].map(|s| v.curve(s).and_then(Curve::orientation)),
                mean_i: v.curve(0).map_or([0.0; 2], sample_mean),
                cam: (!v.two_walled()).then(|| v.cam(model)),
            })
            .collect();
        ContactForces { items }
    }

    /// True when joint `j` is a curve contact with force channels.
    pub fn has(&self, j: usize) -> bool {
        self.items.iter().any(|it| it.joint == j)
    }

    /// The channels of joint `j` (empty when it is not a contact).
    pub fn channels(&self, model: &Model, j: usize) -> Vec<Channel> {
        if !self.has(j) {
            return Vec::new();
        }
        let name = &model.joints[j].name;
        vec![
            Channel::new(format!("{name}.normal_force"), Quantity::Force),
            Channel::new(format!("{name}.tangential_force"), Quantity::Force),
        ]
    }

    /// (N, T) of contact joint `j` at q from its reactions `r` (on bodies
    /// i and j, [`super::reaction::reactions`]).
    pub fn resolve(
        &self,
        model: &Model,
        asm: &Assembly,
        j: usize,
        q: &[f64],
        r: &[Reaction; 2],
    ) -> NormalTangential {
        let Some(it) = self.items.iter().find(|it| it.joint == j) else {
            return [f64::NAN; 2];
        };
        let Some(v) = ContactView::of(model, j) else {
            return [f64::NAN; 2];
        };
        let x = asm.local(model, j, q, &[], 0.0);
        let unit = |v: V2| scale(1.0 / norm(v), v);
        let (_, t) = v.point_tangent(&x.q, &x.own);
        let t = unit(t);
        // A pin in a slot: the force on the pin along the slot's left normal.
        if let Some(pin) = v.sides.iter().position(|s| matches!(s, Feature::Point(_))) {
            let f = r[pin].force;
            return [dot(f, perp(t)), dot(f, t)];
        }
        // A cam (C_i) against a curve or a face on body j: the force on j
        // along the normal out of the solid side.
        let Some(ci) = v.curve(0) else {
            return [f64::NAN; 2];
        };
        let fj = r[1].force;
        let ji = ci.jet(x.own[0]);
        let gi = rot(x.q[0][2], ji.d1);
        // The tangent of C_j (global) and its parameter, when j carries a curve.
        let cj = v.curve(1).zip(v.own_of(1)).map(|(c, o)| (c, x.own[o]));
        let gj = || cj.map_or([f64::NAN; 2], |(c, a)| rot(x.q[1][2], c.jet(a).d1));
        let n = match it.sides {
            [Some(si), Some(sj)] => {
                let kj = cj.map_or(0.0, |(c, a)| c.curvature(a));
                let ki = ci.curvature(x.own[0]);
                closed_pair(outward(si, gi), outward(sj, gj()), ki, kj)
            }
            [Some(si), None] => outward(si, gi),
            [None, Some(sj)] => from_side(1, outward(sj, gj())),
            [None, None] => away_from(point(x.q[0], it.mean_i), point(x.q[0], ji.p), gi),
        };
        [normal_force(fj, n), dot(fj, t)]
    }
}

/// Relative size, against the largest |N| seen so far, under which a
/// negative normal force counts as zero (rounding, not lift-off).
pub const LIFT_OFF_TOL: f64 = 1e-9;

/// One watched cam contact.
#[derive(Clone, Debug)]
struct Watched {
    joint: String,
    cam: String,
    /// Indices of `<joint>.normal_force` and of `<cam>.phi` in a row.
    n: usize,
    phi: Option<usize>,
    /// The previous sample (t, N, φ).
    prev: Option<(f64, f64, f64)>,
    /// Largest |N| so far.
    scale: f64,
    open: Option<LiftOff>,
}

/// Finds the lift-off intervals of every cam contact (cam–follower and
/// cam–flat-faced follower) in a stream of output rows.
#[derive(Clone, Debug, Default)]
pub struct LiftOffWatch {
    watched: Vec<Watched>,
    /// The intervals closed so far.
    pub found: Vec<LiftOff>,
}

impl LiftOffWatch {
    /// Watches the cam contacts of `model` in rows with channels `names`
    /// (which hold `<joint>.normal_force` and the cam's `<body>.phi`).
    pub fn new<C: AsRef<str>>(model: &Model, channels: &[C]) -> Self {
        let cf = ContactForces::new(model);
        let find = |s: String| channels.iter().position(|c| c.as_ref() == s);
        let watched = cf
            .items
            .iter()
            .filter_map(|it| {
                let cam = it.cam?;
                let joint = model.joints[it.joint].name.clone();
                let cam_name = model.body(cam).name.clone();
                let n = find(format!("{joint}.normal_force"))?;
                let phi = find(format!("{cam_name}.phi"));
                Some(Watched {
                    joint,
                    cam: cam_name,
                    n,
                    phi,
                    prev: None,
                    scale: 0.0,
                    open: None,
                })
            })
            .collect();
        LiftOffWatch {
            watched,
            found: Vec::new(),
        }
    }

    /// Takes one output row at time t.
    pub fn observe(&mut self, t: f64, row: &[f64]) {
        for w in &mut self.watched {
            let n = row[w.n];
            let phi = w.phi.map_or(0.0, |k| row[k]);
            w.scale = w.scale.max(n.abs());
            let negative = n < -LIFT_OFF_TOL * w.scale;
            // The zero of N between the previous sample and this one.
            let cross = |prev: Option<(f64, f64, f64)>| match prev {
                Some((t0, n0, p0)) if n0 != n => {
                    let s = (n0 / (n0 - n)).clamp(0.0, 1.0);
                    Crossing {
                        time: t0 + s * (t - t0),
                        cam_angle: p0 + s * (phi - p0),
                    }
                }
                _ => Crossing {
                    time: t,
                    cam_angle: phi,
                },
            };
            let here = Crossing {
                time: t,
                cam_angle: phi,
            };
            match (&mut w.open, negative) {
                (None, true) => {
                    w.open = Some(LiftOff {
                        joint: w.joint.clone(),
                        cam: w.cam.clone(),
                        start: cross(w.prev),
                        end: None,
                        least: n,
                        least_at: here,
                    });
                }
                (Some(l), true) => {
                    if n < l.least {
                        l.least = n;
                        l.least_at = here;
                    }
                }
                (Some(_), false) => {
                    let mut l = w.open.take().expect("open interval");
                    l.end = Some(cross(w.prev));
                    self.found.push(l);
                }
                (None, false) => {}
            }
            w.prev = Some((t, n, phi));
        }
    }

    /// Every interval found, by start time; those still open at the end
    /// of the run have no end.
    pub fn finish(mut self) -> Vec<LiftOff> {
        for w in &mut self.watched {
            if let Some(l) = w.open.take() {
                self.found.push(l);
            }
        }
        self.found
            .sort_by(|a, b| a.start.time.total_cmp(&b.start.time));
        self.found
    }

    /// Finishes the watch into a run's summary: each interval as a warning
    /// at its start time ([`LiftOff::message`]) and, in the same order, as
    /// data in `summary.lift_off`.
    pub fn report(self, summary: &mut Summary) {
        for l in self.finish() {
            summary.warnings.push(Warning {
                kind: Kind::LiftOff,
                time: l.start.time,
                joints: vec![l.joint.clone()],
                message: l.message(),
            });
            summary.lift_off.push(l);
        }
    }
}

/// The lift-off intervals in a finished table of dynamic results.
pub fn lift_off(model: &Model, table: &crate::run::Table) -> Vec<LiftOff> {
    let mut w = LiftOffWatch::new(model, &table.channels);
    let width = table.channels.len().max(1);
    for (t, row) in table.t.iter().zip(table.values.chunks(width)) {
        w.observe(*t, row);
    }
    w.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A watch of contact `joint` on `cam` whose N and φ are row[n], row[n + 1].
    fn watched(joint: &str, cam: &str, n: usize) -> Watched {
        Watched {
            joint: joint.into(),
            cam: cam.into(),
            n,
            phi: Some(n + 1),
            prev: None,
            scale: 0.0,
            open: None,
        }
    }

    /// A watch over rows (N, φ).
    fn watch() -> LiftOffWatch {
        LiftOffWatch {
            watched: vec![watched("bucket", "cam", 0)],
            found: Vec::new(),
        }
    }

    #[test]
    fn intervals_start_and_end_at_interpolated_zeros() {
        let mut w = watch();
        // N = 1, −1, −3, 1, 2 at t = 0..4, φ = 10 t.
        for (k, n) in [1.0, -1.0, -3.0, 1.0, 2.0].into_iter().enumerate() {
            let t = k as f64;
            w.observe(t, &[n, 10.0 * t]);
        }
        let found = w.finish();
        assert_eq!(found.len(), 1);
        let l = &found[0];
        assert_eq!(
            l.start,
            Crossing {
                time: 0.5,
                cam_angle: 5.0
            }
        );
        assert_eq!(
            l.end,
            Some(Crossing {
                time: 2.75,
                cam_angle: 27.5
            })
        );
        assert_eq!((l.least, l.least_at.time), (-3.0, 2.0));
        let m = l.message();
        assert!(
            m.starts_with("bucket: normal force < 0, the follower would leave cam 'cam'"),
            "{m}"
        );
        assert!(
            m.contains("from t = 0.5 s (cam angle 5 rad, 286.479°)"),
            "{m}"
        );
        assert!(m.contains("to t = 2.75 s"), "{m}");
    }

    #[test]
    fn rounding_is_not_lift_off_and_an_open_interval_has_no_end() {
        let mut w = watch();
        w.observe(0.0, &[100.0, 0.0]);
        w.observe(1.0, &[-1e-8, 0.0]);
        w.observe(2.0, &[50.0, 0.0]);
        assert!(w.found.is_empty());
        // Starts negative: the interval starts at the first sample.
        let mut w = watch();
        w.observe(0.0, &[-2.0, 0.3]);
        w.observe(1.0, &[-1.0, 0.4]);
        let found = w.finish();
        assert_eq!(found.len(), 1);
        assert_eq!(
            found[0].start,
            Crossing {
                time: 0.0,
                cam_angle: 0.3
            }
        );
        assert_eq!(found[0].end, None);
        assert!(found[0].message().contains("to the end of the run"));
    }

    #[test]
    fn report_adds_each_interval_to_the_summary_as_data_and_as_a_warning() {
        // Rows (N_a, φ_a, N_b, φ_b): contact "a" leaves its cam from
        // t = 0.5 to 1.5; "b" from the start to the end of the run.
        let mut w = LiftOffWatch {
            watched: vec![watched("a", "cam_a", 0), watched("b", "cam_b", 2)],
            found: Vec::new(),
        };
        for (t, na, nb) in [(0.0, 1.0, -1.0), (1.0, -1.0, -2.0), (2.0, 1.0, -1.0)] {
            w.observe(t, &[na, t, nb, 2.0 * t]);
        }
        let mut summary = Summary {
            warnings: vec![Warning {
                kind: Kind::NearSingular,
                time: 0.25,
                joints: Vec::new(),
                message: "an earlier warning".into(),
            }],
            ..Summary::default()
        };
        w.report(&mut summary);
        // By start time: "b" (t = 0) before "a" (t = 0.5), though "a" ends
        // first.
        let starts: Vec<(&str, f64)> = summary
            .lift_off
            .iter()
            .map(|l| (l.joint.as_str(), l.start.time))
            .collect();
        assert_eq!(starts, [("b", 0.0), ("a", 0.5)]);
        assert_eq!(summary.lift_off[0].end, None);
        assert_eq!(
            summary.lift_off[1].end,
            Some(Crossing {
                time: 1.5,
                cam_angle: 1.5
            })
        );
        let mut want = vec![(Kind::NearSingular, 0.25, "an earlier warning".to_string())];
        want.extend(
            summary
                .lift_off
                .iter()
                .map(|l| (Kind::LiftOff, l.start.time, l.message())),
        );
        let got: Vec<_> = summary
            .warnings
            .iter()
            .map(|w| (w.kind, w.time, w.message.clone()))
            .collect();
        assert_eq!(got, want);
        // A lift-off warning names its joint.
        assert_eq!(summary.warnings[1].joints, ["b"]);
    }
}
