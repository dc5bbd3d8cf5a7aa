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
use crate::math::rot_t;
use crate::model::{Body, BodyId, Model};

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
