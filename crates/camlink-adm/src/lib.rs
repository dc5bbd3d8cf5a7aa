//! camlink's course-file importer: simEngine2D (the ME451 course engine)
//! `.adm` model files and `.acf` analysis files.
//!
//! [`load_adm`] reads a `.adm` (and the `.acf` beside it, or one given) into
//! camlink's own model description — the structure a TOML or JSON model
//! file holds — and resolves it with the same code as those files, so the
//! validation is the same; [`convert_adm`] writes that description as a
//! TOML or JSON model file, which loads to the same model. Errors name the
//! `.adm` (or `.acf`) file, the line, the field and the constraint, force or
//! body (name and id). The mapping of every type is documented in
//! `docs/simengine2d.md` and in [`build`].

#![warn(unreachable_pub)]

mod build;
mod format;
mod item;
mod lenient;
mod matlab;
pub mod mfile;

use std::path::{Path, PathBuf};

use serde_json::Value;

pub use build::{constraint_types, FORCE_TYPES};
pub use item::Item;

use camlink_model::text::{field_path, json_span, line_col, read_text, too_large};
use camlink_model::{Format, LoadError, Loaded, MAX_FILE_SIZE};

/// A file's text, its leniently quoted form and its JSON value.
struct Json {
    source: String,
    text: String,
    relaxed: lenient::Relaxed,
    value: Value,
}

impl Json {
    fn read(path: &Path) -> Result<Json, LoadError> {
        let text = read_text(path)?;
        Json::parse(text, path.display().to_string())
    }

    fn parse(text: String, source: String) -> Result<Json, LoadError> {
        if text.len() as u64 > MAX_FILE_SIZE {
            return Err(too_large(&source, Some(text.len() as u64)));
        }
        let text = text
            .strip_prefix('\u{feff}')
            .map(str::to_string)
            .unwrap_or(text);
        let relaxed = lenient::relax(&text);
        let value = serde_json::from_str(&relaxed.text).map_err(|e| {
            let (line, column) = if e.line() > 0 {
                // serde_json's position is in the quoted text: map it back.
                let offset = offset_of(&relaxed.text, e.line(), e.column().max(1));
                let (l, c) = line_col(&text, relaxed.original(offset));
                (Some(l), Some(c))
            } else {
                (None, None)
            };
            let message = e.to_string();
            let message = message
                .rfind(" at line ")
                .map_or(message.clone(), |k| message[..k].to_string());
            LoadError {
                source: source.clone(),
                line,
                column,
                field: None,
                message: format!("syntax error: {message}"),
            }
        })?;
        Ok(Json {
            source,
            text,
            relaxed,
            value,
        })
    }

    /// An error at the value of `path` (a field path such as `constraints[2].sP1`).
    fn error(&self, path: &str, label: Option<&str>, message: &str) -> LoadError {
        let span = json_span(&self.relaxed.text, path);
        let (line, column) = match span {
            Some(s) => {
                let (l, c) = line_col(&self.text, self.relaxed.original(s.start));
                (Some(l), Some(c))
            }
            None => (None, None),
        };
        LoadError {
            source: self.source.clone(),
            line,
            column,
            field: Some(path.to_string()).filter(|p| !p.is_empty()),
            message: match label {
                Some(l) => format!("{l}: {message}"),
                None => message.to_string(),
            },
        }
    }
}

/// The byte offset of 1-based `line` and `column` (characters) in `text`.
fn offset_of(text: &str, line: usize, column: usize) -> usize {
    let start: usize = text
        .split_inclusive('\n')
        .take(line - 1)
        .map(str::len)
        .sum();
    let rest = &text[start.min(text.len())..];
    start
        + rest
            .chars()
            .take(column - 1)
            .map(char::len_utf8)
            .sum::<usize>()
}

/// The `.acf` beside `adm` (same name, extension `.acf`), if there is one.
pub fn acf_beside(adm: &Path) -> Option<PathBuf> {
    let acf = adm.with_extension("acf");
    acf.is_file().then_some(acf)
}

/// A `.adm` read into camlink's model description, ready to resolve or write.
pub struct Described {
    /// The description (a model file's tables), `[analysis]` included when
    /// an `.acf` was read.
    pub doc: Item,
    /// What the file holds that is read and ignored, as the course engine
    /// ignores it (a joint's constant `fun`, an empty force entry,
    /// `contacts`): one line each, placed as an error would be.
    pub warnings: Vec<String>,
    adm: Json,
    acf: Option<Json>,
    origins: Vec<build::Origin>,
}

/// Reads `adm` and the analysis file `acf` (`None`: the `.acf` beside
/// `adm`, if any) into camlink's model description, then resolves it.
pub fn load_adm(adm: &Path, acf: Option<&Path>) -> Result<Loaded, LoadError> {
    describe(adm, acf)?.resolve()
}

/// The model file in `format` that describes the same mechanism as `adm`
/// (with the analysis of `acf`, or of the `.acf` beside `adm`). The model is
/// resolved first, so a model that does not load is not converted.
pub fn convert_adm(adm: &Path, acf: Option<&Path>, format: Format) -> Result<String, LoadError> {
    let d = describe(adm, acf)?;
    d.resolve()?;
    d.write(format)
}

/// Reads `adm` (and `acf`, else the `.acf` beside it) into a description.
pub fn describe(adm: &Path, acf: Option<&Path>) -> Result<Described, LoadError> {
    let beside = acf_beside(adm);
    let acf = acf.or(beside.as_deref());
    let adm = Json::read(adm)?;
    let acf = acf.map(Json::read).transpose()?;
    describe_json(adm, acf)
}

/// [`describe`] from text; `source` names the texts in errors.
pub fn describe_str(
    adm: &str,
    adm_source: &str,
    acf: Option<(&str, &str)>,
) -> Result<Described, LoadError> {
    let adm = Json::parse(adm.to_string(), adm_source.to_string())?;
    let acf = acf
        .map(|(text, source)| Json::parse(text.to_string(), source.to_string()))
        .transpose()?;
    describe_json(adm, acf)
}

fn describe_json(adm: Json, acf: Option<Json>) -> Result<Described, LoadError> {
    let folder = Path::new(&adm.source).parent().map(Path::to_path_buf);
    let built = build::build(&adm.value, folder.as_deref())
        .map_err(|f| adm.error(&f.path, f.label.as_deref(), &f.message))?;
    let mut doc = built.doc;
    let warnings = built
        .warnings
        .iter()
        .map(|w| {
            adm.error(&w.path, w.label.as_deref(), &w.message)
                .to_string()
        })
        .collect();
    if let Some(acf) = &acf {
        let table =
            build::analysis(&acf.value).map_err(|f| acf.error(&f.path, None, &f.message))?;
        doc.push("analysis", table);
    }
    Ok(Described {
        doc,
        warnings,
        adm,
        acf,
        origins: built.origins,
    })
}

impl Described {
    /// The core model and analysis settings, resolved as a model file's.
    pub fn resolve(&self) -> Result<Loaded, LoadError> {
        let value = serde_json::to_value(&self.doc)
            .map_err(|e| LoadError::file(&self.adm.source, format!("internal error: {e}")))?;
        let file: camlink_model::file::ModelFile = serde_path_to_error::deserialize(value)
            .map_err(|e| {
                LoadError::file(
                    &self.adm.source,
                    format!(
                        "internal error: the translated model does not read back ({}: {})",
                        field_path(e.path()),
                        e.inner()
                    ),
                )
            })?;
        let loaded = camlink_model::resolve_file(&file, &self.adm.source, |path, message| {
            self.locate(path, message)
        })?;
        Ok(Loaded {
            warnings: self.warnings.clone(),
            ..loaded
        })
    }

    /// A resolver error at description path `path`, placed in the `.adm`
    /// (or the `.acf` for `analysis.*`).
    fn locate(&self, path: &str, message: &str) -> LoadError {
        if let (Some(key), Some(acf)) = (path.strip_prefix("analysis"), &self.acf) {
            // The [analysis] keys come from these .acf fields.
            let field = match key.trim_start_matches('.') {
                "t_end" => "tend",
                "step" => "outputSteps",
                "h" => "stepSize",
                _ => "simulation",
            };
            return acf.error(field, None, message);
        }
        let entry = self.origins.iter().find(|o| {
            path.strip_prefix(o.prefix.as_str()).is_some_and(|rest| {
                rest.is_empty() || rest.starts_with('.') || rest.starts_with('[')
            })
        });
        match entry {
            Some(o) => {
                let rest = path[o.prefix.len()..].trim_start_matches('.');
                let key = rest.split(['.', '[']).next().unwrap_or("");
                let adm_path = match o.fields.iter().find(|(ours, _)| *ours == key) {
                    Some((_, theirs)) => format!("{}.{theirs}", o.adm_path),
                    None => o.adm_path.clone(),
                };
                self.adm.error(&adm_path, Some(&o.label), message)
            }
            None => self.adm.error("", None, message),
        }
    }

    /// The description as a model file in `format`, with a header naming the
    /// files it came from.
    pub fn write(&self, format: Format) -> Result<String, LoadError> {
        let internal =
            |e: String| LoadError::file(&self.adm.source, format!("internal error: {e}"));
        match format {
            Format::Toml => {
                let body = toml::to_string(&self.doc).map_err(|e| internal(e.to_string()))?;
                let name = |source: &str| {
                    let p = Path::new(source);
                    p.file_name()
                        .map_or(source.to_string(), |n| n.to_string_lossy().into_owned())
                };
                let from = match &self.acf {
                    Some(acf) => format!("{} and {}", name(&self.adm.source), name(&acf.source)),
                    None => name(&self.adm.source),
                };
                Ok(format!(
                    "# camlink model converted from the simEngine2D files {from}\n\n{body}"
                ))
            }
            Format::Json => {
                let mut body =
                    serde_json::to_string_pretty(&self.doc).map_err(|e| internal(e.to_string()))?;
                body.push('\n');
                Ok(body)
            }
        }
    }
}
