//! The bounds and defaults a design file is held to. Lengths in m, angles
//! in degrees as the file gives them, speeds in rev/min.

/// One rev/min in rad/s.
pub const RPM: f64 = std::f64::consts::TAU / 60.0;

/// Highest cam speed (rev/min) a design file may give.
pub const MAX_RPM: f64 = 1e6;

/// Most segments in a motion program (a real program has tens; each one
/// costs its share of every sample, report line and picture).
pub const MAX_SEGMENTS: usize = 1000;

/// Least span (deg) of a segment.
pub const MIN_SPAN_DEG: f64 = 1e-3;

/// Largest length (m) a design file may give: base radius, follower
/// dimensions, lifts, limits, tool radius, search range, spring sizes.
pub const MAX_LENGTH: f64 = 1e3;

/// Most rows of the profile CSV.
pub const MAX_CSV_ROWS: usize = 1_000_000;

/// Finest chord or arc-fit tolerance of an export, relative to the
/// profile's size (its largest radius plus the tool's).
pub const MIN_RELATIVE_TOLERANCE: f64 = 1e-9;

/// Default least ratio of spring surge frequency to the forcing (cam)
/// frequency: Norton, *Machine Design*, ch. 13 ("at least 13 times").
pub const SURGE_RATIO: f64 = 13.0;

/// Bearing types and their life exponents (ISO 281).
pub const LIFE_EXPONENTS: [(&str, f64); 2] = [("ball", 3.0), ("roller", 10.0 / 3.0)];

/// Most integration steps per turn of `[vibration]`.
pub const MAX_STEPS: usize = 100_000;

/// Most turns of `[vibration]` (seconds of work).
pub const MAX_TURNS: usize = 20;

/// Most coils of a spring.
pub const MAX_COILS: f64 = 1e4;

/// Samples over a turn at which the synthesised profile is checked (finite,
/// clear of the bore): every 0.1°.
pub const PROFILE_SAMPLES: usize = 3600;

/// Samples over a turn (both ends) from which a spring's largest lift is
/// taken: every 0.05°.
pub const LIFT_SAMPLES: usize = 7201;

/// Default angular step (deg) of the profile CSV.
pub const CSV_STEP_DEG: f64 = 1.0;

/// Default chord or arc-fit tolerance (m) of the DXF and SVG.
pub const TOLERANCE: f64 = 1e-5;
