//! camlink cam design files: a motion program and a follower in, a
//! synthesised cam, its design limits and a pass/fail report out.
//!
//! A design file (TOML) holds `[cam]`, `[follower]`, `[[segments]]` and
//! optionally `[limits]`, `[dynamics]`, `[contact]`, `[spring]`,
//! `[vibration]` and `[export]` (docs/cam-design.md). Angles in the file
//! are in degrees (keys end in `_deg`), cam speeds in rev/min (`_rpm`),
//! lengths in metres; a loaded [`Design`] is in SI units and radians.
//!
//! - [`load_path`], [`load_toml`], [`load_json`]: read and check a file
//!   into a [`Design`]; an error ([`camlink_model::LoadError`]) names the
//!   file, the line and column (TOML) and the field, as model files do:
//!   `valve.toml:14:7: segments[1].law: 'septic' is not one of dwell, …`;
//! - [`design`]: the checked file's types;
//! - [`limits`]: the bounds and defaults every design file is held to;
//! - [`export`]: the cam angles and fitted arcs of the exports;
//! - [`timing`]: timing files (several cams on one master angle), their
//!   clearances and servo cam tables;
//! - [`report`]: the design report, each limit checked with its margin.
//!
//! The mechanics (motion laws, synthesis, contact stress, springs,
//! vibration, the limits over a turn) are camlink-core's
//! ([`camlink_core::cam`], [`camlink_core::cam_limits`]): the mechanism
//! that runs a synthesised cam needs them too.

#![warn(unreachable_pub)]

pub mod design;
pub mod export;
pub mod limits;
pub mod load;
pub mod report;
mod table;
pub mod timing;

pub use design::{
    ContactSpec, Design, DxfMode, Dynamics, Export, Limits, Segment, SpringSpec, VibrationSpec,
};
pub use load::{is_design, load_json, load_path, load_toml, Loaded};
