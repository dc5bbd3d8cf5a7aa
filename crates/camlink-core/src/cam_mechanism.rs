//! The mechanism of a synthesised cam: the cam, its follower and their
//! joints as a [`Model`], so that camlink's own analyses can run the very
//! design they synthesised.
//!
//! Bodies and joints (names as in the model's channels), in the frames of
//! [`crate::cam::synthesis`]:
//! - `cam`: frame at the cam centre O, revolute `cam-pivot` to the ground
//!   at O, driven by `motor`: φ_cam = σ ω t, so the cam angle is θ = ω t;
//! - `follower`, translating: frame at the roller centre (or on the face,
//!   on the stem axis x = σε), φ = 0, translational `follower-guide` along
//!   the ground's y axis;
//! - `follower`, oscillating: frame at the pivot P = (d, 0), φ = ψ,
//!   revolute `follower-pivot`; the roller centre at (L, 0), the face along
//!   the line y = e of the arm frame;
//! - `contact`: a cam–follower joint between the cam surface and the roller
//!   circle, or a cam–flat-faced follower joint with the face.
//!
//! The follower's mass, inertia, centroid and a return spring are set by
//! the caller on the returned model.

use std::f64::consts::TAU;
use std::sync::Arc;

use crate::cam::{Cam, Follower};
use crate::constraint::absolute::{AbsoluteCoord, Coord};
use crate::constraint::cam_follower::CamFollower;
use crate::constraint::flat_follower::FlatFollower;
use crate::constraint::revolute::Revolute;
use crate::constraint::translational::Translational;
use crate::curve::{Curve, Parametric};
use crate::function::TimeFn;
use crate::kinematics::run;
use crate::math::rot_t;
use crate::model::{Body, BodyId, Model};
use crate::run::{AnalysisError, Settings, Table};

/// The cam surface of `cam` as a closed curve in the cam's frame,
/// parametrised by the cam angle θ (rad).
pub fn surface_curve(cam: &Arc<Cam>) -> Curve {
    Curve::Parametric(Parametric::Cam {
        cam: Arc::clone(cam),
        pitch: false,
    })
}

/// The cam and follower of `cam` turning at ω (rad/s), placed at θ = 0.
pub fn mechanism(cam: &Arc<Cam>, omega: f64) -> Model {
    let mut m = Model::new("cam");
    let g = BodyId::GROUND;
    let body = m.add_body(Body::new("cam", [0.0, 0.0, 0.0]));
    m.add_joint(
        "cam-pivot",
        Revolute {
            body_i: g,
            s_i: [0.0, 0.0],
            body_j: body,
            s_j: [0.0, 0.0],
        },
    );
    let c = cam.contact(0.0);
    let q = cam.follower_coordinate(0.0);
    let follower = match cam.follower {
        Follower::TranslatingRoller { offset, .. } => [cam.sigma * offset, q[0], 0.0],
        Follower::TranslatingFlat => [0.0, q[0], 0.0],
        Follower::OscillatingRoller { pivot, .. } | Follower::OscillatingFlat { pivot, .. } => {
            [pivot, 0.0, q[0]]
        }
    };
    let fb = m.add_body(Body::new("follower", follower));
    if cam.follower.oscillating() {
        m.add_joint(
            "follower-pivot",
            Revolute {
                body_i: g,
                s_i: [follower[0], 0.0],
                body_j: fb,
                s_j: [0.0, 0.0],
            },
        );
    } else {
        m.add_joint(
            "follower-guide",
            Translational {
                body_i: g,
                s_i: [follower[0], 0.0],
                v_i: [0.0, 1.0],
                body_j: fb,
                s_j: [0.0, 0.0],
                angle: 0.0,
            },
        );
    }
    let surface = surface_curve(cam);
    match cam.follower {
        Follower::TranslatingRoller { roller, .. } | Follower::OscillatingRoller { roller, .. } => {
            let centre = match cam.follower {
                Follower::OscillatingRoller { arm, .. } => [arm, 0.0],
                _ => [0.0, 0.0],
            };
            let circle = Parametric::circle(centre, roller, 0.0).expect("a positive roller radius");
            // The roller's contact point lies against the normal from its centre.
            let d = rot_t(follower[2], [-c.normal[0], -c.normal[1]]);
            let alpha = d[1].atan2(d[0]).rem_euclid(TAU) * roller;
            m.add_joint(
                "contact",
                CamFollower {
                    body_i: body,
                    curve_i: surface,
                    body_j: fb,
                    curve_j: Curve::Parametric(circle),
                },
            );
            m.joints.last_mut().expect("just added").own0 = Some([0.0, alpha]);
        }
        Follower::TranslatingFlat | Follower::OscillatingFlat { .. } => {
            let face_y = match cam.follower {
                Follower::OscillatingFlat { face_offset, .. } => face_offset,
                _ => 0.0,
            };
            let flat = FlatFollower::new(body, surface, fb, [0.0, face_y], [1.0, 0.0])
                .expect("a unit face direction");
            m.add_joint("contact", flat);
            m.joints.last_mut().expect("just added").own0 = Some([0.0, 0.0]);
        }
    }
    m.add_driver(
        "motor",
        AbsoluteCoord {
            body,
            s: [0.0, 0.0],
            coord: Coord::Phi,
            f: TimeFn::Linear {
                value: 0.0,
                rate: cam.sigma * omega,
            },
        },
    );
    m
}

/// Largest errors of a round trip: camlink's kinematic analysis of
/// [`mechanism`] against the motion program over one turn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoundTrip {
    /// Largest |x − x_program| over the turn, relative to the largest |s|
    /// (x the stem's y or the arm's angle).
    pub displacement: f64,
    /// Largest velocity and acceleration errors relative to their peaks
    /// ω max|s′| and ω² max|s″|.
    pub velocity: f64,
    pub acceleration: f64,
    /// Analysis steps run.
    pub steps: usize,
}

/// Runs the kinematics of [`mechanism`] at ω (rad/s) over one turn in `n`
/// steps (shifted by 0.3 of a step off the start, so that samples miss the
/// segment boundaries) and compares the follower's coordinate and its
/// rates with the program.
pub fn round_trip(cam: &Arc<Cam>, omega: f64, n: usize) -> Result<RoundTrip, AnalysisError> {
    let model = mechanism(cam, omega);
    let times: Vec<f64> = (0..=n)
        .map(|k| (k as f64 + 0.3) / n as f64 * TAU / omega)
        .collect();
    let settings = Settings {
        tol: 1e-13,
        ..Settings::default()
    };
    let mut table = Table::default();
    run(&model, &times, &settings, &[], &mut table)?;
    let (c, r) = if cam.follower.oscillating() {
        ("phi", ["omega", "alpha"])
    } else {
        ("y", ["vy", "ay"])
    };
    let get = |name: &str| {
        table
            .channel(&format!("follower.{name}"))
            .unwrap_or_default()
    };
    let (x, v, a) = (get(c), get(r[0]), get(r[1]));
    let peak = |k: usize| {
        (0..3600)
            .map(|i| cam.program.eval(i as f64 * TAU / 3600.0)[k].abs())
            .fold(0.0, f64::max)
    };
    let (sx, sv, sa) = (peak(0), peak(1) * omega, peak(2) * omega * omega);
    let mut out = RoundTrip {
        displacement: 0.0,
        velocity: 0.0,
        acceleration: 0.0,
        steps: times.len(),
    };
    for (k, &t) in times.iter().enumerate() {
        let want = cam.follower_coordinate(omega * t);
        out.displacement = out.displacement.max((x[k] - want[0]).abs() / sx);
        out.velocity = out.velocity.max((v[k] - omega * want[1]).abs() / sv);
        out.acceleration = out
            .acceleration
            .max((a[k] - omega * omega * want[2]).abs() / sa);
    }
    Ok(out)
}
