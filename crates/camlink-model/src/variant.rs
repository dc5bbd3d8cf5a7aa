//! Variants of a loaded model: the same file with other `[parameters]`.
//!
//! A [`Recipe`] keeps the parsed file, so that [`Loaded::with_parameters`]
//! re-resolves everything that depends on the parameters (points, curves,
//! drivers, forces, defaults computed from the initial placement) without
//! reading or parsing the file again. Errors name the file, the line and
//! the field, as those of the first load do.

use std::path::PathBuf;
use std::sync::Arc;

use crate::error::did_you_mean;
use crate::file::{ModelFile, Num};
use crate::{at, data_file, locate, resolve, Format, LoadError, Loaded};

/// The parsed model file and where it came from.
#[derive(Clone, Debug)]
pub struct Recipe {
    pub(crate) file: ModelFile,
    /// The file's text (for error positions and for keying study results).
    pub text: String,
    pub format: Format,
    /// The name of the file in errors.
    pub source: String,
    /// The model name used when the file gives none.
    pub(crate) stem: String,
    /// The folder data files resolve against.
    pub(crate) base: PathBuf,
    pub(crate) allow_outside_data: bool,
}

impl Recipe {
    /// The model this recipe describes.
    pub(crate) fn resolve(recipe: &Arc<Recipe>) -> Result<Loaded, LoadError> {
        let r = recipe.as_ref();
        let data = data_file::DataFiles::new(&r.base, r.allow_outside_data);
        let loaded = crate::resolve_with(&r.file, &r.stem, data, |f| r.error_at(f))?;
        Ok(Loaded {
            recipe: Some(Arc::clone(recipe)),
            ..loaded
        })
    }

    /// A resolver failure placed at its field in the file's text.
    fn error_at(&self, f: resolve::Fail) -> LoadError {
        let span = match self.format {
            Format::Toml => locate::toml_span(&self.text, &f.path),
            Format::Json => locate::json_span(&self.text, &f.path),
        };
        at(
            &self.text,
            &self.source,
            span.map(|s| s.start),
            Some(f.path),
            f.message,
        )
    }

    /// The names of the file's `[parameters]`, in sorted order.
    pub fn parameter_names(&self) -> Vec<String> {
        self.file.parameters.keys().cloned().collect()
    }
}

impl Loaded {
    /// This model with the `[parameters]` named in `values` set to the
    /// given numbers (each replacing the file's number or expression), and
    /// everything that depends on them resolved again, as
    /// [`Loaded::with_parameter_values`].
    pub fn with_parameters(&self, values: &[(String, f64)]) -> Result<Loaded, LoadError> {
        let values: Vec<(String, Num)> = values
            .iter()
            .map(|(name, v)| (name.clone(), Num::Value(*v)))
            .collect();
        self.with_parameter_values(&values)
    }

    /// This model with the `[parameters]` named in `values` set to the
    /// given numbers or expressions (an expression reads the other
    /// parameters, with their new values, as the file's do), each
    /// replacing the file's number or expression, and everything that
    /// depends on them resolved again.
    ///
    /// An unknown name, a model without a parsed file (simEngine2D) or a
    /// variant that does not resolve (a point that no longer fits, a
    /// non-finite value) is a [`LoadError`] naming the file and field; a
    /// given expression that does not evaluate (a syntax error, an unknown
    /// name, a cycle) names the parameter, without a line of the file.
    pub fn with_parameter_values(&self, values: &[(String, Num)]) -> Result<Loaded, LoadError> {
        let Some(recipe) = &self.recipe else {
            return Err(LoadError::file(
                &self.model.name,
                "this model has no [parameters] to change (it was not loaded from a camlink model file)",
            ));
        };
        let mut next = Recipe::clone(recipe);
        for (name, value) in values {
            let Some(slot) = next.file.parameters.get_mut(name) else {
                let known = recipe.file.parameters.keys().map(String::as_str);
                let hint = did_you_mean(name, known);
                let list = if recipe.file.parameters.is_empty() {
                    "the file has no [parameters]".to_string()
                } else {
                    format!("its parameters are {}", recipe.parameter_names().join(", "))
                };
                return Err(LoadError {
                    field: Some("parameters".into()),
                    ..LoadError::file(
                        &recipe.source,
                        format!("no parameter named '{name}'{hint}; {list}"),
                    )
                });
            };
            *slot = value.clone();
        }
        // Given expressions are checked here: the file's text does not
        // hold them, so a fault is not placed at a line of it.
        if values.iter().any(|(_, v)| matches!(v, Num::Expr(_))) {
            if let Err(f) = resolve::parameters(&next.file.parameters) {
                return Err(LoadError {
                    field: Some(f.path),
                    ..LoadError::file(&recipe.source, f.message)
                });
            }
        }
        Recipe::resolve(&Arc::new(next))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use camlink_core::math::V2;

    const FILE: &str = r#"
[parameters]
a = 0.1
b = "2*a"

[ground]
points = { O = [0, 0] }

[[bodies]]
name = "arm"
points = { O = [0, 0], P = ["b", 0] }

[[joints]]
name = "pin"
type = "revolute"
body_i = "ground"
point_i = "O"
body_j = "arm"
point_j = "O"

[[drivers]]
name = "motor"
type = "revolute_angle"
joint = "pin"
f = "a*t"
"#;

    fn point(l: &Loaded, body: &str, name: &str) -> V2 {
        let b = l.model.bodies.iter().find(|b| b.name == body).unwrap();
        b.points.iter().find(|p| p.name == name).unwrap().s
    }

    #[test]
    fn a_changed_parameter_reaches_the_parameters_and_points_that_depend_on_it() {
        let base = crate::load_str(FILE, Format::Toml, "arm.toml").unwrap();
        assert_eq!(point(&base, "arm", "P"), [0.2, 0.0]);
        let v = base.with_parameters(&[("a".into(), 0.25)]).unwrap();
        assert_eq!(point(&v, "arm", "P"), [0.5, 0.0]);
        // The base model is unchanged.
        assert_eq!(point(&base, "arm", "P"), [0.2, 0.0]);
        // A parameter given an expression in the file can be set too.
        let w = base.with_parameters(&[("b".into(), 0.7)]).unwrap();
        assert_eq!(point(&w, "arm", "P"), [0.7, 0.0]);
    }

    #[test]
    fn an_unknown_parameter_is_named_with_a_suggestion() {
        let base = crate::load_str(FILE, Format::Toml, "arm.toml").unwrap();
        let e = base.with_parameters(&[("aa".into(), 1.0)]).unwrap_err();
        let text = e.to_string();
        assert!(
            text.starts_with("arm.toml: parameters: no parameter named 'aa'"),
            "{text}"
        );
        assert!(text.contains("did you mean 'a'"), "{text}");
    }

    #[test]
    fn a_variant_that_does_not_resolve_names_the_line_and_field() {
        let base = crate::load_str(FILE, Format::Toml, "arm.toml").unwrap();
        let e = base
            .with_parameters(&[("a".into(), f64::INFINITY)])
            .unwrap_err();
        assert_eq!(e.field.as_deref(), Some("parameters.a"), "{e}");
        assert_eq!(e.line, Some(3), "{e}");
        assert!(e.message.contains("not a finite number"), "{e}");
    }

    #[test]
    fn issue30_parameters_take_expressions() {
        let base = crate::load_str(FILE, Format::Toml, "arm.toml").unwrap();
        // An expression reads pi and the other parameters' new values.
        let v = base
            .with_parameter_values(&[
                ("a".into(), Num::Value(0.5)),
                ("b".into(), Num::Expr("a/2 + pi".into())),
            ])
            .unwrap();
        assert_eq!(point(&v, "arm", "P"), [0.25 + std::f64::consts::PI, 0.0]);
        // A fault names the parameter, not a line of the file.
        for (src, says) in [("3*", "b"), ("2*nope", "nope"), ("b + 1", "cycle")] {
            let e = base
                .with_parameter_values(&[("b".into(), Num::Expr(src.into()))])
                .unwrap_err();
            assert_eq!(e.field.as_deref(), Some("parameters.b"), "{e}");
            assert_eq!(e.line, None, "{e}");
            assert!(e.to_string().contains(says), "{src}: {e}");
        }
    }
}
