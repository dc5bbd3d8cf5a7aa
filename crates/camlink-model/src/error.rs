//! Load errors: where (file, line, column, field path) and what.

use std::borrow::Cow;
use std::fmt;

pub(crate) use camlink_core::names::did_you_mean;

/// Why a model file could not be loaded.
///
/// Displays as `four_bar.toml:12:5: joints[2].body_i: no body named 'crnak'
/// (did you mean 'crank'?)`; missing parts are left out.
///
/// `std::error::Error` is implemented by hand: thiserror's derive would take
/// the `source` field (the file name) for the underlying error.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadError {
    /// The file name (or the `source` label given to [`crate::load_str`]).
    pub source: String,
    /// 1-based line of the offending text, when known.
    pub line: Option<usize>,
    /// 1-based column (in characters) of the offending text, when known.
    pub column: Option<usize>,
    /// Path of the offending field, e.g. `joints[2].body_i`.
    pub field: Option<String>,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.source)?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
            if let Some(col) = self.column {
                write!(f, ":{col}")?;
            }
        }
        f.write_str(": ")?;
        if let Some(field) = self.field.as_deref().filter(|s| !s.is_empty()) {
            write!(f, "{}: ", printable(field))?;
        }
        f.write_str(&printable(&self.message))
    }
}

/// `s` with control characters (except newlines) and bidirectional
/// overrides escaped, so that names quoted from a file cannot drive the
/// terminal that shows the error.
pub(crate) fn printable(s: &str) -> Cow<'_, str> {
    let hostile = |c: char| {
        (c.is_control() && c != '\n')
            || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
    };
    if !s.chars().any(hostile) {
        return Cow::Borrowed(s);
    }
    let mut out = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        if hostile(c) {
            out.extend(c.escape_unicode());
        } else {
            out.push(c);
        }
    }
    Cow::Owned(out)
}

impl std::error::Error for LoadError {}

impl LoadError {
    /// An error about the whole file.
    pub fn file(source: &str, message: impl Into<String>) -> Self {
        LoadError {
            source: source.to_string(),
            line: None,
            column: None,
            field: None,
            message: message.into(),
        }
    }
}

/// 1-based (line, column) of byte `offset` in `text`; column counts characters.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |k| k + 1);
    (line, before[start..].chars().count() + 1)
}

/// ` (did you mean 'x'?)` when a candidate is close to `name`, else empty.
/// A parser's message about an unknown `type` or key, such as "unknown
/// variant `revolut`, expected one of `revolute`, …", with the nearest
/// valid name suggested; any other message as it is.
pub(crate) fn with_suggestion(message: &str) -> String {
    let Some(rest) = message
        .strip_prefix("unknown variant `")
        .or_else(|| message.strip_prefix("unknown field `"))
    else {
        return message.to_string();
    };
    let Some((name, valid)) = rest.split_once('`') else {
        return message.to_string();
    };
    // The valid names are the quoted words after "expected".
    let candidates: Vec<&str> = valid.split('`').skip(1).step_by(2).collect();
    if name == "limits" && !candidates.contains(&"limits") {
        return format!(
            "{message}: this joint kind has no limits; revolute, translational and \
             revolute_translational joints do"
        );
    }
    format!("{message}{}", did_you_mean(name, candidates))
}

/// The key `x` of a parser's "unknown field `x`, …" message.
pub(crate) fn unknown_field(message: &str) -> Option<&str> {
    message
        .strip_prefix("unknown field `")?
        .split_once('`')
        .map(|(k, _)| k)
}

/// Inline tables of a joint that the parser reports as the joint itself
/// when a key in them is unknown.
const NESTED: &[&str] = &["friction"];

/// Keys that only some joint kinds take, and those kinds.
const JOINT_KEYS: &[(&str, &str)] = &[(
    "friction",
    "revolute, translational, point_follower, cam_follower and flat_follower joints",
)];

/// An unknown `key` reported at table `path`: the path of the key itself
/// (`path.key`, or `path.<nested>.key` in a joint's inline table) when
/// `exists` finds it, and the message, which for a key that only some
/// joint kinds take says which (`kind` reads a field's text, the joint's
/// `type`).
pub(crate) fn unknown_key(
    path: &str,
    key: &str,
    message: String,
    exists: impl Fn(&str) -> bool,
    kind: impl Fn(&str) -> Option<String>,
) -> (String, String) {
    let Some(at) = std::iter::once(format!("{path}.{key}"))
        .chain(NESTED.iter().map(|n| format!("{path}.{n}.{key}")))
        .find(|p| exists(p))
    else {
        return (path.to_string(), message);
    };
    let joint = path.starts_with("joints[") && !path.contains('.');
    match JOINT_KEYS.iter().find(|(k, _)| *k == key) {
        Some((_, kinds)) if joint => {
            let what = kind(&format!("{path}.type")).unwrap_or_else(|| "this".into());
            let message = format!("a {what} joint takes no {key}: {key} is modelled in {kinds}");
            (at, message)
        }
        _ => (at, message),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_omits_missing_parts() {
        let mut e = LoadError::file("m.toml", "bad");
        assert_eq!(e.to_string(), "m.toml: bad");
        e.field = Some("joints[2].body_i".into());
        assert_eq!(e.to_string(), "m.toml: joints[2].body_i: bad");
        e.line = Some(12);
        e.column = Some(5);
        assert_eq!(e.to_string(), "m.toml:12:5: joints[2].body_i: bad");
    }

    #[test]
    fn line_and_column() {
        assert_eq!(line_col("ab\ncd", 4), (2, 2));
        assert_eq!(line_col("é\nx", 1), (1, 1));
    }
}
