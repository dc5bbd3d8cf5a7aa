//! Errors: a source that does not parse, a value outside an operation's domain.

/// Why an expression could not be parsed, and where.
///
/// `offset` and `len` are in bytes into the source; `len` may be 0 (a point,
/// such as the end of the input).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct ParseError {
    pub message: String,
    pub offset: usize,
    pub len: usize,
}

impl ParseError {
    pub(crate) fn new(message: impl Into<String>, offset: usize, len: usize) -> ParseError {
        ParseError {
            message: message.into(),
            offset,
            len,
        }
    }

    /// The source line holding the problem, a line of carets (`^^^`) under
    /// it, then the message; the message starts with `line N: ` when the
    /// source has several lines.
    ///
    /// ```text
    /// 1 + coss(t)
    ///     ^^^^
    /// unknown function 'coss'; did you mean 'cos'?
    /// ```
    pub fn render(&self, src: &str) -> String {
        let off = floor_boundary(src, self.offset.min(src.len()));
        let line_start = src[..off].rfind('\n').map_or(0, |i| i + 1);
        let line_end = src[off..].find('\n').map_or(src.len(), |i| off + i);
        let line = src[line_start..line_end].trim_end_matches('\r');
        let end = floor_boundary(
            src,
            off.saturating_add(self.len).min(line_start + line.len()),
        );
        let pad: String = src[line_start..off]
            .chars()
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        let carets = "^".repeat(src[off..end.max(off)].chars().count().max(1));
        let prefix = if src.contains('\n') {
            let number = src[..line_start].matches('\n').count() + 1;
            format!("line {number}: ")
        } else {
            String::new()
        };
        format!("{line}\n{pad}{carets}\n{prefix}{}", self.message)
    }
}

/// The largest char boundary of `s` at or before `i`.
fn floor_boundary(s: &str, mut i: usize) -> usize {
    while !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// Why evaluation at x failed: the first operation that left its domain or
/// produced a value that is not finite, quoted from the source, e.g.
/// ``log of a negative number (-0.5) in `log(t - 1)` at t = 0.5``.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct EvalError {
    pub message: String,
    pub x: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn caret_under_the_span() {
        let e = ParseError::new("unknown function 'coss'", 4, 4);
        assert_eq!(
            e.render("1 + coss(t)"),
            "1 + coss(t)\n    ^^^^\nunknown function 'coss'"
        );
    }

    #[test]
    fn caret_at_the_end_of_input() {
        let e = ParseError::new("expected an expression", 3, 0);
        assert_eq!(e.render("1 +"), "1 +\n   ^\nexpected an expression");
    }

    #[test]
    fn second_line_of_a_multiline_source() {
        let e = ParseError::new("bad", 7, 1);
        assert_eq!(e.render("1 +\n\t2 $ 3"), "\t2 $ 3\n\t  ^\nline 2: bad");
    }

    #[test]
    fn wide_characters_count_as_one_column() {
        // 'α' is two bytes; the caret still sits under the '$'.
        let e = ParseError::new("bad", 5, 1);
        assert_eq!(e.render("α + $"), "α + $\n    ^\nbad");
    }

    #[test]
    fn out_of_range_offsets_do_not_panic() {
        let e = ParseError::new("bad", 99, 99);
        assert_eq!(e.render("αβ"), "αβ\n  ^\nbad");
        let e = ParseError::new("bad", 1, 99);
        assert_eq!(e.render("αβ"), "αβ\n^^\nbad");
    }
}
