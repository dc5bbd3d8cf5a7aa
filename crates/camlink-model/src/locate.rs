//! Field paths such as `joints[2].body_i` and where they are in the text.
//!
//! Semantic errors are found after deserialising, so they carry a field
//! path; this module finds the byte span of that field in the original TOML
//! or JSON text so the error can name its line. When the path is not all
//! there (a key left at its default), the deepest part that is present is
//! used.

use std::ops::Range;

use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// One step of a field path.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Seg {
    Key(String),
    Index(usize),
}

/// Splits `a.b[2].c` into segments. Names never contain `.` or `[`.
pub(crate) fn parse_path(path: &str) -> Vec<Seg> {
    let mut out = Vec::new();
    for part in path.split('.').filter(|p| !p.is_empty()) {
        let mut rest = part;
        if let Some(k) = rest.find('[') {
            if k > 0 {
                out.push(Seg::Key(rest[..k].to_string()));
            }
            rest = &rest[k..];
            while let Some(stripped) = rest.strip_prefix('[') {
                let Some(end) = stripped.find(']') else { break };
                match stripped[..end].parse() {
                    Ok(i) => out.push(Seg::Index(i)),
                    Err(_) => out.push(Seg::Key(stripped[..end].to_string())),
                }
                rest = &stripped[end + 1..];
            }
        } else {
            out.push(Seg::Key(rest.to_string()));
        }
    }
    out
}

/// Byte span of the field at `path` in TOML `text`.
pub(crate) fn toml_span(text: &str, path: &str) -> Option<Range<usize>> {
    toml_walk(text, path).0
}

/// Byte span of the field at `path` in TOML `text` when all of the path is
/// there.
pub(crate) fn toml_exact(text: &str, path: &str) -> Option<Range<usize>> {
    match toml_walk(text, path) {
        (span, true) => span,
        _ => None,
    }
}

/// The span of the deepest part of `path` present in TOML `text`, and
/// whether that is all of it.
fn toml_walk(text: &str, path: &str) -> (Option<Range<usize>>, bool) {
    let Ok(root) = DeTable::parse(text) else {
        return (None, false);
    };
    let mut span = None;
    let mut table: Option<&DeTable> = Some(root.get_ref());
    let mut value: Option<&Spanned<DeValue>> = None;
    for seg in parse_path(path) {
        let next = match (&seg, table, value.map(|v| v.get_ref())) {
            (Seg::Key(k), Some(t), _) => {
                t.iter().find(|(key, _)| key.get_ref() == k).map(|(_, v)| v)
            }
            (Seg::Key(k), None, Some(DeValue::Table(t))) => {
                t.iter().find(|(key, _)| key.get_ref() == k).map(|(_, v)| v)
            }
            (Seg::Index(i), None, Some(DeValue::Array(a))) => a.get(*i),
            _ => None,
        };
        let Some(next) = next else {
            return (span, false);
        };
        span = Some(next.span());
        table = None;
        value = Some(next);
    }
    (span, true)
}

/// Byte span of the value at `path` in JSON `text` (already known to be valid JSON).
pub fn json_span(text: &str, path: &str) -> Option<Range<usize>> {
    let mut s = Scanner {
        b: text.as_bytes(),
        k: 0,
    };
    let mut span = None;
    for seg in parse_path(path) {
        s.ws();
        let found = match (seg, s.peek()?) {
            (Seg::Key(key), b'{') => s.find_key(&key)?,
            (Seg::Index(i), b'[') => s.find_index(i)?,
            _ => false,
        };
        if !found {
            break;
        }
        s.ws();
        let start = s.k;
        let mut probe = Scanner { b: s.b, k: start };
        probe.skip_value()?;
        span = Some(start..probe.k);
    }
    span
}

/// Byte spans of the key and of the value of the field at `path`, whose
/// last segment is a key, in TOML `text`; `None` when it is not there.
pub(crate) fn toml_entry(text: &str, path: &str) -> Option<(Range<usize>, Range<usize>)> {
    let root = DeTable::parse(text).ok()?;
    let segs = parse_path(path);
    let (last, init) = segs.split_last()?;
    let Seg::Key(last) = last else { return None };
    let mut table: &DeTable = root.get_ref();
    let mut value: Option<&Spanned<DeValue>> = None;
    for seg in init {
        let next = match (seg, value.map(|v| v.get_ref())) {
            (Seg::Key(k), None) => table.iter().find(|(key, _)| key.get_ref() == k)?.1,
            (Seg::Key(k), Some(DeValue::Table(t))) => {
                t.iter().find(|(key, _)| key.get_ref() == k)?.1
            }
            (Seg::Index(i), Some(DeValue::Array(a))) => a.get(*i)?,
            _ => return None,
        };
        value = Some(next);
    }
    if let Some(v) = value {
        let DeValue::Table(t) = v.get_ref() else {
            return None;
        };
        table = t;
    }
    let (key, v) = table.iter().find(|(key, _)| key.get_ref() == last)?;
    Some((key.span(), v.span()))
}

/// Byte spans of the key (with its quotes) and of the value of the field
/// at `path`, whose last segment is a key, in JSON `text`.
pub(crate) fn json_entry(text: &str, path: &str) -> Option<(Range<usize>, Range<usize>)> {
    let segs = parse_path(path);
    let (last, init) = segs.split_last()?;
    let Seg::Key(last) = last else { return None };
    let mut s = Scanner {
        b: text.as_bytes(),
        k: 0,
    };
    for seg in init {
        s.ws();
        let found = match (seg, s.peek()?) {
            (Seg::Key(key), b'{') => s.find_key(key)?,
            (Seg::Index(i), b'[') => s.find_index(*i)?,
            _ => false,
        };
        if !found {
            return None;
        }
    }
    s.ws();
    if s.peek()? != b'{' {
        return None;
    }
    s.k += 1;
    loop {
        s.ws();
        if s.peek()? == b'}' {
            return None;
        }
        let key_start = s.k;
        let name = s.string()?;
        let hit = name == last.as_bytes();
        let key = key_start..s.k;
        s.ws();
        s.k += 1; // ':'
        s.ws();
        let start = s.k;
        s.skip_value()?;
        if hit {
            return Some((key, start..s.k));
        }
        s.ws();
        if s.peek()? == b',' {
            s.k += 1;
        }
    }
}

/// A minimal scanner over valid JSON, used only to find value positions.
struct Scanner<'a> {
    b: &'a [u8],
    k: usize,
}

impl Scanner<'_> {
    fn peek(&self) -> Option<u8> {
        self.b.get(self.k).copied()
    }

    fn ws(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t' | b'\n' | b'\r')) {
            self.k += 1;
        }
    }

    /// Reads a string at the cursor and returns its raw (escaped) contents.
    fn string(&mut self) -> Option<&[u8]> {
        if self.peek()? != b'"' {
            return None;
        }
        self.k += 1;
        let start = self.k;
        loop {
            match self.peek()? {
                b'\\' => self.k += 2,
                b'"' => {
                    self.k += 1;
                    return Some(&self.b[start..self.k - 1]);
                }
                _ => self.k += 1,
            }
        }
    }

    fn skip_value(&mut self) -> Option<()> {
        self.ws();
        match self.peek()? {
            b'"' => {
                self.string()?;
            }
            open @ (b'{' | b'[') => {
                let close = if open == b'{' { b'}' } else { b']' };
                self.k += 1;
                self.ws();
                if self.peek()? == close {
                    self.k += 1;
                    return Some(());
                }
                loop {
                    if open == b'{' {
                        self.ws();
                        self.string()?;
                        self.ws();
                        self.k += 1; // ':'
                    }
                    self.skip_value()?;
                    self.ws();
                    let c = self.peek()?;
                    self.k += 1;
                    if c == close {
                        break;
                    }
                }
            }
            _ => {
                while !matches!(
                    self.peek()?,
                    b',' | b'}' | b']' | b' ' | b'\n' | b'\r' | b'\t'
                ) {
                    self.k += 1;
                    if self.k >= self.b.len() {
                        break;
                    }
                }
            }
        }
        Some(())
    }

    /// With the cursor on `{`, moves it to the value of `key`.
    fn find_key(&mut self, key: &str) -> Option<bool> {
        self.k += 1;
        loop {
            self.ws();
            if self.peek()? == b'}' {
                return Some(false);
            }
            let name = self.string()?;
            let hit = name == key.as_bytes();
            self.ws();
            self.k += 1; // ':'
            if hit {
                return Some(true);
            }
            self.skip_value()?;
            self.ws();
            if self.peek()? == b',' {
                self.k += 1;
            }
        }
    }

    /// With the cursor on `[`, moves it to element `i`.
    fn find_index(&mut self, i: usize) -> Option<bool> {
        self.k += 1;
        for _ in 0..i {
            self.ws();
            if self.peek()? == b']' {
                return Some(false);
            }
            self.skip_value()?;
            self.ws();
            if self.peek()? == b',' {
                self.k += 1;
            }
        }
        self.ws();
        Some(self.peek()? != b']')
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths() {
        assert_eq!(
            parse_path("joints[2].body_i"),
            vec![
                Seg::Key("joints".into()),
                Seg::Index(2),
                Seg::Key("body_i".into())
            ]
        );
        assert_eq!(
            parse_path("a.b"),
            vec![Seg::Key("a".into()), Seg::Key("b".into())]
        );
    }

    #[test]
    fn toml_spans() {
        let text = "[model]\nname = \"m\"\n\n[[joints]]\ntype = \"revolute\"\n\n[[joints]]\ntype = \"revolute\"\nbody_i = \"crnak\"\n";
        let span = toml_span(text, "joints[1].body_i").unwrap();
        assert_eq!(&text[span], "\"crnak\"");
        assert!(toml_span(text, "model.gravity").is_some());
    }

    #[test]
    fn json_spans() {
        let text = r#"{"model": {"name": "m"}, "joints": [{"type": "revolute"}, {"type": "x", "body_i": "crnak"}]}"#;
        let span = json_span(text, "joints[1].body_i").unwrap();
        assert_eq!(&text[span], "\"crnak\"");
        let span = json_span(text, "model.name").unwrap();
        assert_eq!(&text[span], "\"m\"");
        let span = json_span(text, "joints[5]").unwrap();
        assert!(text[span].starts_with('['));
    }
}
