//! The lenient JSON of course files: bare arithmetic such as `187/255` in a
//! value position, as MATLAB's reader accepted it.
//!
//! [`relax`] quotes every bare value that is not a JSON literal (number,
//! `true`, `false`, `null`), so that serde_json reads it as a string; the
//! reader then parses such strings as constant expressions where a number
//! is expected. Nothing is evaluated here. [`Relaxed::original`] maps a byte
//! offset in the quoted text back to the file, for error positions.

/// Quoted text and where quotes were inserted.
pub(crate) struct Relaxed {
    pub text: String,
    /// Offsets in `text` of the inserted quote characters, increasing.
    inserted: Vec<usize>,
}

impl Relaxed {
    /// The byte offset in the original file of byte `offset` of `self.text`.
    pub(crate) fn original(&self, offset: usize) -> usize {
        offset - self.inserted.iter().take_while(|&&k| k < offset).count()
    }
}

/// Quotes bare non-literal values of `text` (outside strings).
pub(crate) fn relax(text: &str) -> Relaxed {
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut inserted = Vec::new();
    let mut k = 0;
    while k < b.len() {
        let c = b[k];
        if c == b'"' {
            // Copy a string through its closing quote, skipping escapes.
            let start = k;
            k += 1;
            while k < b.len() && b[k] != b'"' {
                if b[k] == b'\\' {
                    k += 1;
                }
                // Step over one whole character (escaped or not).
                k += text[k.min(b.len())..]
                    .chars()
                    .next()
                    .map_or(1, char::len_utf8);
            }
            k = (k + 1).min(b.len());
            out.push_str(&text[start..k]);
            continue;
        }
        if c.is_ascii_whitespace() || matches!(c, b'{' | b'}' | b'[' | b']' | b':' | b',') {
            out.push(c as char);
            k += 1;
            continue;
        }
        // A bare value: up to the next separator outside parentheses.
        let start = k;
        let mut depth = 0usize;
        while k < b.len() {
            match b[k] {
                b'(' => depth += 1,
                b')' => depth = depth.saturating_sub(1),
                b',' if depth == 0 => break,
                b'}' | b']' | b':' | b'\n' | b'"' => break,
                _ => {}
            }
            k += 1;
        }
        let raw = &text[start..k];
        let value = raw.trim_end();
        if is_literal(value) {
            out.push_str(raw);
        } else {
            inserted.push(out.len());
            out.push('"');
            out.push_str(value);
            inserted.push(out.len());
            out.push('"');
            out.push_str(&raw[value.len()..]);
        }
    }
    Relaxed {
        text: out,
        inserted,
    }
}

/// A JSON number or keyword.
fn is_literal(s: &str) -> bool {
    if matches!(s, "true" | "false" | "null") {
        return true;
    }
    let b = s.as_bytes();
    let mut k = 0;
    let digits = |k: &mut usize| {
        let start = *k;
        while *k < b.len() && b[*k].is_ascii_digit() {
            *k += 1;
        }
        *k > start
    };
    if b.first() == Some(&b'-') {
        k += 1;
    }
    if b.get(k) == Some(&b'0') {
        k += 1;
    } else if !digits(&mut k) {
        return false;
    }
    if b.get(k) == Some(&b'.') {
        k += 1;
        if !digits(&mut k) {
            return false;
        }
    }
    if matches!(b.get(k), Some(b'e' | b'E')) {
        k += 1;
        if matches!(b.get(k), Some(b'+' | b'-')) {
            k += 1;
        }
        if !digits(&mut k) {
            return false;
        }
    }
    k == b.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arithmetic_is_quoted_and_literals_kept() {
        let r = relax(r#"{"c": [187/255, 0.5, -1e-3], "s": "a/b", "x": 2 * pi , "b": true}"#);
        assert_eq!(
            r.text,
            r#"{"c": ["187/255", 0.5, -1e-3], "s": "a/b", "x": "2 * pi" , "b": true}"#
        );
        let v: serde_json::Value = serde_json::from_str(&r.text).unwrap();
        assert_eq!(v["c"][0], "187/255");
        assert_eq!(v["c"][2], -1e-3);
    }

    #[test]
    fn commas_inside_calls_stay_in_the_value() {
        let r = relax(r#"[max(1, 2), 3]"#);
        assert_eq!(r.text, r#"["max(1, 2)", 3]"#);
    }

    #[test]
    fn offsets_map_back() {
        let src = r#"{"a": 1/2, "b": x}"#;
        let r = relax(src);
        let in_relaxed = r.text.find("\"b\"").unwrap();
        assert_eq!(r.original(in_relaxed), src.find("\"b\"").unwrap());
        let x = r.text.find('x').unwrap();
        assert_eq!(r.original(x), src.find('x').unwrap());
    }

    #[test]
    fn an_escape_before_a_wide_character_does_not_split_it() {
        let src = "{\"a\": \"\\é\", \"b\": 1/2}";
        assert_eq!(relax(src).text, "{\"a\": \"\\é\", \"b\": \"1/2\"}");
        let src = "\"\\é";
        assert_eq!(relax(src).text, src);
    }

    #[test]
    fn strict_json_is_unchanged() {
        let src = "{\"a\": [1, 2.5, -0, 3E+2], \"b\": \"q\\\"uote\", \"n\": null}";
        assert_eq!(relax(src).text, src);
    }
}
