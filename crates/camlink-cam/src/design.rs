//! A checked design file, in SI units and radians.

use camlink_core::cam::motion::EndConditions;
use camlink_core::cam::{Cam, CamError, Follower, LawKind, MotionError, Program, SegmentSpec};

/// One segment of the motion program as the file gives it.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    pub law: LawKind,
    /// Span β (rad).
    pub span: f64,
    /// Lift h (m), or swing (rad) of an oscillating follower.
    pub lift: f64,
    /// A fitted polynomial's s′, s″, s‴ at the start (per rad of cam
    /// angle); `None` where free.
    pub start: EndConditions,
    /// The same at the end.
    pub end: EndConditions,
}

/// Follower mass (kg, or kg·m² about the pivot), return spring and speeds.
#[derive(Clone, Debug, PartialEq)]
pub struct Dynamics {
    pub mass: f64,
    /// Spring rate (N/m, or N·m/rad).
    pub spring_rate: f64,
    /// Spring preload at zero lift (N, or N·m).
    pub preload: f64,
    /// Viscous damping (N·s/m, or N·m·s/rad).
    pub damping: f64,
    /// Running speed ω (rad/s).
    pub speed: f64,
    /// Highest speed (rad/s) the cam must run at without jump.
    pub redline: Option<f64>,
}

/// The user's limits; `None` where not given.
#[derive(Clone, Debug, PartialEq)]
pub struct Limits {
    /// Largest pressure angle (rad).
    pub max_pressure_angle: Option<f64>,
    /// Least convex radius of curvature of the cam surface (m).
    pub min_radius: Option<f64>,
    /// Face width of a flat follower (m).
    pub max_face_width: Option<f64>,
    /// Search range (m) for the smallest base circle.
    pub base_radius_range: Option<(f64, f64)>,
    /// Allowable Hertz contact stress (Pa).
    pub max_contact_stress: Option<f64>,
    /// Least roller bearing L10 life at the running speed (h).
    pub min_bearing_life_hours: Option<f64>,
    /// Least gap between the spring's coils at the largest lift (m).
    pub min_coil_clearance: Option<f64>,
    /// Least spring surge frequency over the forcing frequency.
    pub min_surge_ratio: f64,
    /// Largest residual vibration after a rise or return (m or rad).
    pub max_residual_vibration: Option<f64>,
}

/// How the DXF draws the profile.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DxfMode {
    Polyline,
    Arcs,
}

impl DxfMode {
    pub fn name(self) -> &'static str {
        match self {
            DxfMode::Polyline => "polyline",
            DxfMode::Arcs => "arcs",
        }
    }
}

/// Files to write, relative to the output folder; `None` to skip.
#[derive(Clone, Debug, PartialEq)]
pub struct Export {
    pub csv: Option<String>,
    /// Angular step (rad) of the CSV, or 0 with a chord tolerance.
    pub csv_step: f64,
    /// Chord tolerance (m) of the CSV's angles.
    pub csv_chord: Option<f64>,
    pub dxf: Option<String>,
    pub dxf_mode: DxfMode,
    /// Chord or arc-fit tolerance (m) of DXF and SVG.
    pub tolerance: f64,
    pub svg: Option<String>,
    /// A cutting tool's radius (m).
    pub tool_radius: Option<f64>,
    pub svaj: Option<String>,
    pub profile: Option<String>,
    /// The export keys whose file names the design file gives (the others
    /// are default names, never replaced without `--force`), in the order
    /// read.
    pub given: Vec<String>,
    /// Length unit of reports, pictures and exports: "m" or "mm".
    pub units: String,
    /// SVAJ against time at the running speed (with `[dynamics]`).
    pub svaj_time: Option<String>,
    /// The follower train's deviation and dynamic contact force over a
    /// turn (with `[vibration]`).
    pub vibration: Option<String>,
    /// Bore radius (m).
    pub bore_radius: Option<f64>,
    /// Keyway width and depth (m).
    pub keyway_width: Option<f64>,
    pub keyway_depth: Option<f64>,
    /// Keyway angle (rad) from the timing mark.
    pub keyway_angle: f64,
    pub timing_mark: bool,
}

/// `[contact]`: the cam–follower contact's width and materials.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactSpec {
    /// Contact length along the cam axis (m).
    pub width: f64,
    /// Contact modulus E* (Pa).
    pub modulus: f64,
    /// The cam's and the follower's material names ("given" for a table).
    pub materials: (String, String),
    /// Bearing dynamic rating C (N).
    pub rating: Option<f64>,
    /// Bearing life exponent (3 ball, 10/3 roller).
    pub exponent: f64,
    /// A crowned roller's crown radius (m).
    pub crown: Option<f64>,
}

/// `[spring]`: a helical return spring on a translating stem and its
/// figures as installed ([`camlink_core::cam::spring::Installed`]).
#[derive(Clone, Debug, PartialEq)]
pub struct SpringSpec {
    /// Wire diameter d (m).
    pub wire: f64,
    /// Mean coil diameter D (m).
    pub mean_diameter: f64,
    pub active_coils: f64,
    pub total_coils: f64,
    /// Free and installed lengths (m).
    pub free_length: f64,
    pub installed_length: f64,
    /// Shear modulus G (Pa) and density (kg/m³) of the wire.
    pub shear_modulus: f64,
    pub density: f64,
    /// Rate, preload, solid height, shortest length, clash margin, mass,
    /// surge frequency and index, as installed.
    pub figures: camlink_core::cam::spring::Installed,
}

/// `[vibration]`: the follower train as lumped masses.
#[derive(Clone, Debug, PartialEq)]
pub struct VibrationSpec {
    /// Masses (kg) from the cam outwards.
    pub masses: Vec<f64>,
    /// Stiffness (N/m) of the link before each mass.
    pub stiffness: Vec<f64>,
    /// Damping (N·s/m) of the link before each mass.
    pub damping: Vec<f64>,
    pub steps: usize,
    pub turns: usize,
    /// Compensate the cam for the train's deflection (one mass).
    pub polydyne: bool,
}

/// Why a design's cam does not synthesise.
#[derive(Clone, Debug, PartialEq)]
pub enum CamBuildError {
    /// The motion program (a segment, or spans not closing the turn).
    Program(MotionError),
    /// The follower's kind or dimensions.
    Follower(String),
    /// The profile's geometry (the follower cannot ride the program).
    Geometry(CamError),
}

impl std::fmt::Display for CamBuildError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CamBuildError::Program(e) => e.fmt(f),
            CamBuildError::Follower(m) => f.write_str(m),
            CamBuildError::Geometry(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for CamBuildError {}

/// A checked design file.
#[derive(Clone, Debug, PartialEq)]
pub struct Design {
    /// The file as errors name it.
    pub source: String,
    pub name: String,
    /// The follower kind (one of [`Follower::KINDS`]).
    pub follower: &'static str,
    /// Its dimensions (m) in the order of [`Follower::KINDS`].
    pub dims: Vec<f64>,
    /// Base circle radius R_b (m).
    pub base_radius: f64,
    /// The cam turns counterclockwise.
    pub ccw: bool,
    pub segments: Vec<Segment>,
    pub limits: Limits,
    pub dynamics: Option<Dynamics>,
    pub export: Export,
    pub contact: Option<ContactSpec>,
    pub spring: Option<SpringSpec>,
    pub vibration: Option<VibrationSpec>,
}

impl Design {
    /// Whether the follower swings (lifts are angles, rad).
    pub fn oscillating(&self) -> bool {
        self.follower.starts_with("oscillating")
    }

    /// The motion program.
    pub fn program(&self) -> Result<Program, MotionError> {
        let specs: Vec<SegmentSpec> = self
            .segments
            .iter()
            .map(|s| SegmentSpec {
                law: s.law,
                span: s.span,
                lift: s.lift,
                start: s.start,
                end: s.end,
            })
            .collect();
        Program::new(&specs)
    }

    /// The synthesised cam with base circle `base_radius` (m); an error
    /// says which part (program, follower, geometry) does not work and why.
    pub fn cam_with(&self, base_radius: f64) -> Result<Cam, CamBuildError> {
        let program = self.program().map_err(CamBuildError::Program)?;
        let follower =
            Follower::from_dims(self.follower, &self.dims).map_err(CamBuildError::Follower)?;
        Cam::new(program, follower, base_radius, self.ccw).map_err(CamBuildError::Geometry)
    }

    /// The synthesised cam.
    pub fn cam(&self) -> Result<Cam, CamBuildError> {
        self.cam_with(self.base_radius)
    }
}
