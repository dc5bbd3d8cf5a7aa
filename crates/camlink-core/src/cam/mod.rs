//! Cam design: motion programs, profile synthesis and design limits.
//!
//! - [`motion`]: the follower motion over one revolution as segments of
//!   standard laws ([`law`]), checked for closure and continuity;
//! - [`synthesis`]: the cam surface (and a roller's pitch curve) for four
//!   follower types, exact to the third derivative;
//! - [`hertz`], [`spring`]: contact stress, bearing life and helical
//!   springs (formulas only);
//! - [`vibration`]: the follower train as lumped masses driven by the cam.
//!
//! The design limits over a turn (pressure angle, radius of curvature,
//! undercut, face width, base circle sizing, contact force and jump speed)
//! are in [`crate::cam_limits`], and the mechanism that runs a cam in
//! [`crate::cam_mechanism`]: both read the curves, which read this module.
//! This module reads only [`crate::math`] and [`crate::fmt_num`]; the curves use it to turn a
//! synthesised cam into a profile ([`crate::curve::Parametric::Cam`]).

pub mod hertz;
pub mod law;
pub mod motion;
pub mod spring;
pub mod synthesis;
pub mod taylor;
pub mod vibration;

/// The largest base circle radius (m) taken without a question: cams of
/// machines have base circles of millimetres to a few hundred; a radius
/// of metres is most often millimetres written as metres.
pub const LARGEST_PLAIN_BASE_RADIUS: f64 = 1.0;

/// The question to ask of a base circle radius `r` (m) larger than
/// [`LARGEST_PLAIN_BASE_RADIUS`]: "a base circle of radius 25 m: is it
/// 25 mm (0.025 m)?"; `None` for one in range.
pub fn base_radius_question(r: f64) -> Option<String> {
    use crate::fmt_num::num;
    (r > LARGEST_PLAIN_BASE_RADIUS).then(|| {
        format!(
            "a base circle of radius {} m: is it {} mm ({} m)?",
            num(r),
            num(r),
            num(r / 1000.0)
        )
    })
}

pub use law::LawKind;
pub use motion::{Boundary, Factors, MotionError, Program, SegmentSpec};
pub use synthesis::{Cam, CamError, Contact, Follower, ProfileJet};
