//! Cam design: motion programs, profile synthesis and design limits.
//!
//! - [`motion`]: the follower motion over one revolution as segments of
//!   standard laws ([`law`]), checked for closure and continuity;
//! - [`synthesis`]: the cam surface (and a roller's pitch curve) for four
//!   follower types, exact to the third derivative;
//! - [`limits`]: pressure angle, radius of curvature, undercut, face width,
//!   base circle sizing, contact force and jump speed over a turn.
//!
//! This module reads only [`crate::math`]; the curves use it to turn a synthesised cam into a profile
//! ([`crate::curve::Parametric::Cam`]).

pub mod law;
pub mod limits;
pub mod motion;
pub mod synthesis;
pub mod taylor;

pub use law::LawKind;
pub use motion::{Boundary, Factors, MotionError, Program, SegmentSpec};
pub use synthesis::{Cam, CamError, Contact, Follower, ProfileJet};
