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
    /// source has several lines. A line longer than [`RENDER_WIDTH`]
    /// characters is cut to a window around the problem, with `...` where
    /// text is left out.
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
        // Characters of the line, and the span of the carets in them.
        let chars: Vec<char> = line.chars().collect();
        let start = src[line_start..off].chars().count();
        let count = src[off..end.max(off)].chars().count().max(1);
        let (from, to) = window(chars.len(), start);
        let mut shown: String = chars[from..to].iter().collect();
        let mut pad = String::new();
        if from > 0 {
            shown.insert_str(0, "...");
            pad.push_str("   ");
        }
        if to < chars.len() {
            shown.push_str("...");
        }
        pad.extend(
            chars[from..start.min(to)]
                .iter()
                .map(|&c| if c == '\t' { '\t' } else { ' ' }),
        );
        let carets = "^".repeat(count.min(to.saturating_sub(start)).max(1));
        let prefix = if src.contains('\n') {
            let number = src[..line_start].matches('\n').count() + 1;
            format!("line {number}: ")
        } else {
            String::new()
        };
        format!("{shown}\n{pad}{carets}\n{prefix}{}", self.message)
    }
}

/// Longest source line [`ParseError::render`] shows whole (characters).
pub const RENDER_WIDTH: usize = 80;

/// The characters `from..to` of a line of `len` characters to show for a
/// problem starting at character `start`: all of a short line, else a
/// window of [`RENDER_WIDTH`] that starts a little before the problem.
fn window(len: usize, start: usize) -> (usize, usize) {
    if len <= RENDER_WIDTH {
        return (0, len);
    }
    let from = start
        .saturating_sub(RENDER_WIDTH / 4)
        .min(len - RENDER_WIDTH);
    (from, from + RENDER_WIDTH)
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

#[cfg(test)]
mod long_line_tests {
    use super::*;

    #[test]
    fn long_line_error_is_cut_to_a_window() {
        // A 120 kB expression used to be echoed whole, carets and all.
        let src = format!("{}sinn(t){}", "1+".repeat(60_000), "+1".repeat(60_000));
        let e = ParseError::new("unknown function 'sinn'", 120_000, 4);
        let shown = e.render(&src);
        let lines: Vec<&str> = shown.lines().collect();
        assert_eq!(lines.len(), 3, "{shown}");
        assert!(
            lines[0].starts_with("...") && lines[0].ends_with("..."),
            "{shown}"
        );
        assert_eq!(lines[0].chars().count(), RENDER_WIDTH + 6);
        let caret = lines[1].find('^').unwrap();
        assert_eq!(&lines[0][caret..caret + 4], "sinn", "{shown}");
        assert_eq!(lines[1].trim(), "^^^^");

        // The whole of a too-long source: carets to the end of the window.
        let e = ParseError::new("expression too long", 0, src.len());
        let shown = e.render(&src);
        let lines: Vec<&str> = shown.lines().collect();
        assert_eq!(lines[1], "^".repeat(RENDER_WIDTH), "{shown}");
        assert!(!lines[0].starts_with("..."));

        // Short lines are shown whole, as before.
        let e = ParseError::new("unknown function 'coss'", 4, 4);
        assert_eq!(
            e.render("1 + coss(t)"),
            "1 + coss(t)\n    ^^^^\nunknown function 'coss'"
        );
    }
}
