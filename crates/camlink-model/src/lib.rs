//! camlink model files: one schema for TOML and JSON.
//!
//! [`load_path`] and [`load_str`] read a model file into a validated core
//! [`camlink_core::Model`] plus the [`AnalysisSpec`] of its `[analysis]`
//! table. Errors name the file, the line and column (TOML always, JSON where
//! the value can be found) and the field path, e.g.
//! `four_bar.toml:12:5: joints[2].body_i: no body named 'crnak' (did you mean 'crank'?)`.
//! [`json_schema`] is the published JSON Schema of the format; the format
//! itself is documented in `docs/model-files.md`.

#![warn(unreachable_pub)]

mod analysis;
pub mod convert;
mod data_file;
mod error;
mod eval;
pub mod file;
mod locate;
mod resolve;
pub mod text;
mod units;
mod variant;

use std::path::{Path, PathBuf};

use camlink_core::dynamics::integrator::{Adaptive, Settings as IntegratorSettings};
use camlink_core::dynamics::statics::Settings as StaticsSettings;

pub use analysis::{needs_adaptive, not_applicable, DynamicsArgs, SettingError, ERROR_CONTROL};
pub use data_file::LoadOptions;
pub use error::LoadError;
pub use file::AnalysisType;
pub use resolve::joints::{JointKindEntry, JOINT_KINDS};
use text::{field_path, read_text, too_large};
pub use variant::Recipe;

/// Largest model file accepted (bytes).
pub const MAX_FILE_SIZE: u64 = 16 * 1024 * 1024;

/// The syntax of a model file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Toml,
    Json,
}

impl Format {
    /// The format for a file name's extension (`.toml` or `.json`, any case).
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "toml" => Some(Format::Toml),
            "json" => Some(Format::Json),
            _ => None,
        }
    }
}

/// A loaded model file: the model and how to analyse it.
#[derive(Clone, Debug)]
pub struct Loaded {
    pub model: camlink_core::Model,
    pub analysis: AnalysisSpec,
    /// The `[machine]` table (`camlink machine`), checked against the model.
    pub machine: Option<camlink_core::machine::Spec>,
    /// The data files read (canonical paths), so that a run can refuse to
    /// write its output over one of them.
    pub data_files: Vec<PathBuf>,
    /// Drawn shapes that the file gives for bodies (`outline`).
    pub outlines: Vec<Outline>,
    /// The parsed file, kept to build variants with other `[parameters]`
    /// ([`Loaded::with_parameters`]); `None` for a simEngine2D model.
    pub recipe: Option<std::sync::Arc<Recipe>>,
    /// What the loader read and ignored, one line each naming the file,
    /// line and field (a simEngine2D file's entries that the course engine
    /// does not use either); empty for camlink's own files.
    pub warnings: Vec<String>,
}

/// A body's drawn outline from the model file, in the body frame.
#[derive(Clone, Debug)]
pub struct Outline {
    pub body: String,
    pub shape: OutlineShape,
}

/// A closed polyline (corners, m) or a closed curve.
#[derive(Clone, Debug)]
pub enum OutlineShape {
    Polyline(Vec<camlink_core::math::V2>),
    Curve(camlink_core::curve::Curve),
}

impl Loaded {
    /// The `[analysis] points` as kinematic outputs, each named `"body.point"`
    /// and located by the body's point vector s′ (m).
    ///
    /// The loader has checked every name; an error means `analysis.points`
    /// was changed after loading to name a body or point the model lacks.
    pub fn point_outputs(&self) -> Result<Vec<camlink_core::run::PointOutput>, String> {
        self.analysis
            .points
            .iter()
            .map(|full| camlink_core::run::PointOutput::named(&self.model, full))
            .collect()
    }
}

/// The `[analysis]` table, evaluated. Times in seconds.
///
/// `tol` and `max_iter` are those of the analysis `kind` (its default when
/// the file gives none); `tol_set` and `max_iter_set` say whether the file
/// gave them, so that a program running another analysis than `kind` can
/// use that analysis' own defaults instead.
#[derive(Clone, Debug, PartialEq)]
pub struct AnalysisSpec {
    /// The analysis the file asks for (`type`).
    pub kind: AnalysisType,
    /// End time (s); the run starts at t = 0.
    pub t_end: Option<f64>,
    /// Output step (s).
    pub step: Option<f64>,
    /// Explicit output times (s), increasing; excludes `t_end`/`step`.
    pub times: Option<Vec<f64>>,
    /// Equilibrium: the time (s) at which drivers and forces are evaluated.
    pub time: f64,
    /// Newton tolerance (see [`AnalysisSpec::default_tol`] for its meaning).
    pub tol: f64,
    /// Most Newton iterations per time step.
    pub max_iter: usize,
    pub tol_set: bool,
    pub max_iter_set: bool,
    /// Output points as `"body.point"`; each names an existing point.
    pub points: Vec<String>,
    /// Kinematics: also solve and output the jerk.
    pub jerk: bool,
    /// Forward-dynamics settings (defaults unless `kind` is dynamics).
    pub dynamics: DynamicsSpec,
}

/// The integrator settings of `[analysis]` for `type = "dynamics"`.
#[derive(Clone, Debug, PartialEq)]
pub struct DynamicsSpec {
    /// Integration step h (s); `None`: the output step, but at most
    /// [`DynamicsSpec::DEFAULT_H`].
    pub h: Option<f64>,
    /// Spectral radius at infinity ρ∞ ∈ [0, 1].
    pub rho_inf: f64,
    /// Tolerance of the initial position projection (m or rad).
    pub projection_tol: f64,
    /// `Some` for error-controlled steps.
    pub adaptive: Option<Adaptive>,
}

impl DynamicsSpec {
    /// Largest integration step chosen when `h` is not given (s).
    pub const DEFAULT_H: f64 = 1e-3;
    /// Default absolute local-error tolerance of the adaptive mode (m or rad).
    pub const DEFAULT_ATOL: f64 = 1e-6;
    /// Default relative local-error tolerance of the adaptive mode.
    pub const DEFAULT_RTOL: f64 = 0.0;
    /// Default smallest step of the adaptive mode (s).
    pub const DEFAULT_H_MIN: f64 = 1e-8;
}

impl Default for DynamicsSpec {
    fn default() -> Self {
        let d = IntegratorSettings::default();
        DynamicsSpec {
            h: None,
            rho_inf: d.rho_inf,
            projection_tol: d.projection_tol,
            adaptive: None,
        }
    }
}

impl AnalysisSpec {
    pub const DEFAULT_TOL: f64 = 1e-10;
    pub const DEFAULT_MAX_ITER: usize = 25;

    /// The default Newton tolerance of an analysis: on |Φ| (m or rad) for
    /// kinematics and inverse dynamics, on |Φ| and the force balance for
    /// equilibrium, on the corrections of q and q̇ for dynamics.
    pub fn default_tol(kind: AnalysisType) -> f64 {
        match kind {
            AnalysisType::Kinematics | AnalysisType::InverseDynamics => Self::DEFAULT_TOL,
            AnalysisType::Equilibrium => StaticsSettings::default().tol,
            AnalysisType::Dynamics => IntegratorSettings::default().tol,
        }
    }

    /// The default Newton iterations per step of an analysis.
    pub fn default_max_iter(kind: AnalysisType) -> usize {
        match kind {
            AnalysisType::Kinematics | AnalysisType::InverseDynamics => Self::DEFAULT_MAX_ITER,
            AnalysisType::Equilibrium => StaticsSettings::default().max_iter,
            AnalysisType::Dynamics => IntegratorSettings::default().max_iter,
        }
    }

    /// The integrator settings: `h`, else the output `step` but at most
    /// [`DynamicsSpec::DEFAULT_H`]; `tol` and `max_iter` as given, else the
    /// integrator's defaults.
    pub fn integrator_settings(&self) -> IntegratorSettings {
        let d = &self.dynamics;
        IntegratorSettings {
            step: DynamicsSpec::integration_step(d.h, self.step),
            rho_inf: d.rho_inf,
            tol: self.tol_for(AnalysisType::Dynamics),
            max_iter: self.max_iter_for(AnalysisType::Dynamics),
            projection_tol: d.projection_tol,
            adaptive: d.adaptive.clone(),
        }
    }

    /// `tol` if the file gave it, else the default of `kind`.
    pub fn tol_for(&self, kind: AnalysisType) -> f64 {
        if self.tol_set {
            self.tol
        } else {
            Self::default_tol(kind)
        }
    }

    /// `max_iter` if the file gave it, else the default of `kind`.
    pub fn max_iter_for(&self, kind: AnalysisType) -> usize {
        if self.max_iter_set {
            self.max_iter
        } else {
            Self::default_max_iter(kind)
        }
    }
}

impl Default for AnalysisSpec {
    fn default() -> Self {
        AnalysisSpec {
            kind: AnalysisType::Kinematics,
            t_end: None,
            step: None,
            times: None,
            time: 0.0,
            tol: Self::DEFAULT_TOL,
            max_iter: Self::DEFAULT_MAX_ITER,
            tol_set: false,
            max_iter_set: false,
            points: Vec::new(),
            jerk: false,
            dynamics: DynamicsSpec::default(),
        }
    }
}

/// Loads a model file; the format comes from the extension (`.toml`, `.json`).
/// Data files must lie in the model file's folder or below.
pub fn load_path(path: &Path) -> Result<Loaded, LoadError> {
    load_path_with(path, &LoadOptions::default())
}

/// [`load_path`] with options: where data files resolve and whether they
/// may lie outside that folder.
pub fn load_path_with(path: &Path, options: &LoadOptions) -> Result<Loaded, LoadError> {
    let source = path.display().to_string();
    let Some(format) = Format::from_path(path) else {
        return Err(LoadError::file(
            &source,
            "unknown model file type; expected a .toml or .json file",
        ));
    };
    let text = read_text(path)?;
    load_str_with(&text, format, &source, options)
}

/// Loads a model from text; `source` names it in errors (usually the file
/// name), and data files it names (a spline's CSV points) are read relative
/// to `source`'s directory, and only from there and below.
///
/// A leading byte order mark (U+FEFF, written by some Windows editors) is
/// skipped; positions in errors count from the character after it.
pub fn load_str(text: &str, format: Format, source: &str) -> Result<Loaded, LoadError> {
    load_str_with(text, format, source, &LoadOptions::default())
}

/// [`load_str`] with options: where data files resolve
/// ([`LoadOptions::base_dir`], else `source`'s directory) and whether they
/// may lie outside that folder.
pub fn load_str_with(
    text: &str,
    format: Format,
    source: &str,
    options: &LoadOptions,
) -> Result<Loaded, LoadError> {
    if text.len() as u64 > MAX_FILE_SIZE {
        return Err(too_large(source, Some(text.len() as u64)));
    }
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let file = match format {
        Format::Toml => parse_toml(text, source)?,
        Format::Json => parse_json(text, source)?,
    };
    let base = match &options.base_dir {
        Some(dir) => dir.as_path(),
        None => Path::new(source).parent().unwrap_or(Path::new("")),
    };
    let recipe = Recipe {
        file,
        text: text.to_string(),
        format,
        source: source.to_string(),
        stem: stem(source).to_string(),
        base: base.to_path_buf(),
        allow_outside_data: options.allow_outside_data,
    };
    Recipe::resolve(&std::sync::Arc::new(recipe))
}

/// Resolves a model description built in memory rather than read from a
/// file's text — a course file's translation (`camlink-adm`) — as
/// [`load_str`] resolves a file's: named after `source`'s stem unless it
/// names itself, data files read from `source`'s folder and below, lengths
/// and angles in the units of its `[model] units`. A bad value reaches
/// `place` as its field path in the description (`joints[2].body_i`) and
/// the message; `place` returns the error placed in the file the caller
/// read.
pub fn resolve_file(
    file: &file::ModelFile,
    source: &str,
    place: impl Fn(&str, &str) -> LoadError,
) -> Result<Loaded, LoadError> {
    let base = Path::new(source).parent().unwrap_or(Path::new(""));
    let data = data_file::DataFiles::new(base, false);
    resolve_with(file, stem(source), data, |f| place(&f.path, &f.message))
}

/// `file` in SI, resolved with its `[machine]`, data files read through
/// `data`; `place` turns a resolver failure into the caller's error. The
/// result has no recipe and no warnings.
fn resolve_with(
    file: &file::ModelFile,
    stem: &str,
    data: data_file::DataFiles,
    place: impl Fn(resolve::Fail) -> LoadError,
) -> Result<Loaded, LoadError> {
    let file = units::to_si(file);
    let (model, analysis, outlines, data) = resolve::resolve(&file, stem, data).map_err(&place)?;
    let machine = resolve::machine(&file, &model).map_err(&place)?;
    Ok(Loaded {
        model,
        analysis,
        machine,
        outlines,
        data_files: data.into_read(),
        recipe: None,
        warnings: Vec::new(),
    })
}

/// The model name of a file named `source` that gives none: its stem, else
/// `model`.
fn stem(source: &str) -> &str {
    Path::new(source)
        .file_stem()
        .and_then(|s| s.to_str())
        .filter(|s| !s.is_empty())
        .unwrap_or("model")
}

/// The 1-based (line, column) of the field `path` (`study.outputs.swing`)
/// in TOML `text`, or of the deepest part of it that is present; `None`
/// when the text is not TOML or holds none of it. Lets files read
/// elsewhere (a study table) name the line of a bad field.
pub fn toml_position(text: &str, path: &str) -> Option<(usize, usize)> {
    locate::toml_span(text, path).map(|s| error::line_col(text, s.start))
}

/// A [`LoadError`] at byte `offset` of `text`.
pub(crate) fn at(
    text: &str,
    source: &str,
    offset: Option<usize>,
    field: Option<String>,
    message: String,
) -> LoadError {
    let (line, column) = match offset.map(|o| error::line_col(text, o)) {
        Some((l, c)) => (Some(l), Some(c)),
        None => (None, None),
    };
    LoadError {
        source: source.to_string(),
        line,
        column,
        field: field.filter(|f| !f.is_empty()),
        message,
    }
}

fn parse_toml(text: &str, source: &str) -> Result<file::ModelFile, LoadError> {
    let de = toml::Deserializer::parse(text).map_err(|e| {
        let offset = e.span().map(|s| s.start);
        at(
            text,
            source,
            offset,
            None,
            format!("syntax error: {}", e.message().trim()),
        )
    })?;
    serde_path_to_error::deserialize(de).map_err(|e| {
        let mut path = field_path(e.path());
        let inner = e.inner();
        let mut offset = inner
            .span()
            .map(|s| s.start)
            .or_else(|| locate::toml_span(text, &path).map(|s| s.start));
        let mut message = error::with_suggestion(inner.message().trim());
        // An unknown key: its own line and path.
        if let Some(key) = error::unknown_field(inner.message()) {
            let exists = |p: &str| locate::toml_exact(text, p).is_some();
            let kind = |p: &str| {
                let span = locate::toml_exact(text, p)?;
                Some(text[span].trim_matches('"').to_string())
            };
            (path, message) = error::unknown_key(&path, key, message, exists, kind);
            if let Some(span) = locate::toml_exact(text, &path) {
                offset = Some(span.start);
            }
        }
        at(text, source, offset, Some(path), message)
    })
}

fn parse_json(text: &str, source: &str) -> Result<file::ModelFile, LoadError> {
    let mut de = serde_json::Deserializer::from_str(text);
    let file: file::ModelFile =
        serde_path_to_error::deserialize(&mut de).map_err(|e| json_error(text, source, e))?;
    de.end().map_err(|e| json_syntax(text, source, &e))?;
    Ok(file)
}

fn json_error(
    text: &str,
    source: &str,
    e: serde_path_to_error::Error<serde_json::Error>,
) -> LoadError {
    let path = field_path(e.path());
    let inner = e.into_inner();
    if inner.is_syntax() || inner.is_eof() {
        return json_syntax(text, source, &inner);
    }
    let mut err = json_syntax(text, source, &inner);
    let plain = strip_json_position(&inner.to_string());
    let mut message = error::with_suggestion(&plain);
    let mut path = path;
    // An unknown key: its own path.
    if let Some(key) = error::unknown_field(&plain) {
        let value: Option<serde_json::Value> = serde_json::from_str(text).ok();
        let find = |p: &str| value.as_ref().and_then(|v| json_at(v, p)).cloned();
        let exists = |p: &str| find(p).is_some();
        let kind = |p: &str| find(p).and_then(|v| v.as_str().map(str::to_string));
        (path, message) = error::unknown_key(&path, key, message, exists, kind);
    }
    err.message = message;
    err.field = Some(path).filter(|p| !p.is_empty());
    err
}

fn json_syntax(_text: &str, source: &str, e: &serde_json::Error) -> LoadError {
    let known = e.line() > 0;
    let mut message = strip_json_position(&e.to_string());
    if e.is_syntax() || e.is_eof() {
        message = format!("syntax error: {message}");
    }
    LoadError {
        source: source.to_string(),
        line: known.then(|| e.line()),
        // serde_json gives column 0 at the very start of a line.
        column: known.then(|| e.column().max(1)),
        field: None,
        message,
    }
}

/// The value at field path `path` in `v`.
fn json_at<'v>(v: &'v serde_json::Value, path: &str) -> Option<&'v serde_json::Value> {
    locate::parse_path(path)
        .into_iter()
        .try_fold(v, |v, seg| match seg {
            locate::Seg::Key(k) => v.get(k),
            locate::Seg::Index(i) => v.get(i),
        })
}

/// serde_json appends " at line L column C"; the position is reported separately.
fn strip_json_position(msg: &str) -> String {
    match msg.rfind(" at line ") {
        Some(k) => msg[..k].to_string(),
        None => msg.to_string(),
    }
}

/// The JSON Schema of the model file format (draft 2020-12).
pub fn json_schema() -> serde_json::Value {
    let schema = schemars::schema_for!(file::ModelFile);
    serde_json::to_value(&schema).unwrap_or(serde_json::Value::Null)
}
