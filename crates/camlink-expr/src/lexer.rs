//! The tokenizer: source text to numbers, names and operators with byte spans.

use crate::error::ParseError;

/// A token's kind; names keep their text in the source (see [`Token`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Tok {
    Num(f64),
    Ident,
    Plus,
    Minus,
    Star,
    Slash,
    /// `^` or `**`.
    Caret,
    LParen,
    RParen,
    Comma,
    Lt,
    Le,
    Gt,
    Ge,
    EqEq,
    Ne,
    /// `&&`.
    AndAnd,
    /// `||`.
    OrOr,
    /// `!`.
    Bang,
    End,
}

/// A token and its byte span `start..end` in the source.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Token {
    pub tok: Tok,
    pub start: usize,
    pub end: usize,
}

/// True for a character that may start a name: a letter (any script, so
/// `α` and `π` work) or `_`.
pub(crate) fn is_name_start(c: char) -> bool {
    c.is_alphabetic() || c == '_'
}

/// True for a character that may continue a name.
pub(crate) fn is_name_char(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// Splits `src` into tokens, ending with [`Tok::End`] at `src.len()`.
pub(crate) fn tokenize(src: &str) -> Result<Vec<Token>, ParseError> {
    let bytes = src.as_bytes();
    let mut toks = Vec::new();
    let mut i = 0;
    while let Some(c) = src[i..].chars().next() {
        let start = i;
        if c.is_whitespace() {
            i += c.len_utf8();
            continue;
        }
        let next = bytes.get(i + 1).copied();
        let (tok, len) = match c {
            '0'..='9' | '.' => {
                let len = number_len(&bytes[i..]);
                if len == 0 {
                    return Err(ParseError::new(
                        "unexpected '.'; a number needs a digit after its point",
                        i,
                        1,
                    ));
                }
                let text = &src[i..i + len];
                let v: f64 = text
                    .parse()
                    .map_err(|_| ParseError::new(format!("malformed number '{text}'"), i, len))?;
                if !v.is_finite() {
                    return Err(ParseError::new(
                        format!("number '{text}' is too large"),
                        i,
                        len,
                    ));
                }
                (Tok::Num(v), len)
            }
            c if is_name_start(c) => {
                let len = src[i..]
                    .char_indices()
                    .find(|&(_, c)| !is_name_char(c))
                    .map_or(src.len() - i, |(k, _)| k);
                (Tok::Ident, len)
            }
            '+' => (Tok::Plus, 1),
            '-' => (Tok::Minus, 1),
            '*' if next == Some(b'*') => (Tok::Caret, 2),
            '*' => (Tok::Star, 1),
            '/' => (Tok::Slash, 1),
            '^' => (Tok::Caret, 1),
            '(' => (Tok::LParen, 1),
            ')' => (Tok::RParen, 1),
            ',' => (Tok::Comma, 1),
            '<' if next == Some(b'=') => (Tok::Le, 2),
            '<' => (Tok::Lt, 1),
            '>' if next == Some(b'=') => (Tok::Ge, 2),
            '>' => (Tok::Gt, 1),
            '=' if next == Some(b'=') => (Tok::EqEq, 2),
            '!' if next == Some(b'=') => (Tok::Ne, 2),
            '!' => (Tok::Bang, 1),
            '&' if next == Some(b'&') => (Tok::AndAnd, 2),
            '|' if next == Some(b'|') => (Tok::OrOr, 2),
            '=' => {
                return Err(ParseError::new(
                    "'=' is not an operator here; write '==' to compare",
                    i,
                    1,
                ))
            }
            '&' => return Err(ParseError::new("write '&&' or 'and'", i, 1)),
            '|' => return Err(ParseError::new("write '||' or 'or'", i, 1)),
            c => {
                return Err(ParseError::new(
                    format!("unexpected character '{}'", c.escape_debug()),
                    i,
                    c.len_utf8(),
                ))
            }
        };
        i += len;
        toks.push(Token { tok, start, end: i });
    }
    toks.push(Token {
        tok: Tok::End,
        start: src.len(),
        end: src.len(),
    });
    Ok(toks)
}

/// Length of the number at the start of `b`: digits, an optional point with
/// digits, an optional exponent. An `e` not followed by digits (after an
/// optional sign) is not part of the number, so `2e` lexes as `2` then `e`.
/// Returns 0 for a point without digits on either side.
fn number_len(b: &[u8]) -> usize {
    let digits = |from: usize| b[from..].iter().take_while(|c| c.is_ascii_digit()).count();
    let mut n = digits(0);
    let int = n;
    if b.get(n) == Some(&b'.') {
        let frac = digits(n + 1);
        if int == 0 && frac == 0 {
            return 0;
        }
        n += 1 + frac;
    }
    if matches!(b.get(n), Some(b'e' | b'E')) {
        let sign = usize::from(matches!(b.get(n + 1), Some(b'+' | b'-')));
        let exp = digits(n + 1 + sign);
        if exp > 0 {
            n += 1 + sign + exp;
        }
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(src: &str) -> Vec<Tok> {
        tokenize(src).unwrap().into_iter().map(|t| t.tok).collect()
    }

    #[test]
    fn numbers_in_every_form() {
        for (src, v) in [
            ("1", 1.0),
            ("1.5", 1.5),
            ("1e-3", 1e-3),
            (".5", 0.5),
            ("2.", 2.0),
            ("1.5E+2", 150.0),
            ("1.e2", 100.0),
        ] {
            assert_eq!(kinds(src), vec![Tok::Num(v), Tok::End], "{src}");
        }
    }

    #[test]
    fn exponent_without_digits_is_a_name() {
        assert_eq!(kinds("2e"), vec![Tok::Num(2.0), Tok::Ident, Tok::End]);
    }

    #[test]
    fn operators() {
        assert_eq!(
            kinds("** ^ <= >= == != && || ! < >"),
            vec![
                Tok::Caret,
                Tok::Caret,
                Tok::Le,
                Tok::Ge,
                Tok::EqEq,
                Tok::Ne,
                Tok::AndAnd,
                Tok::OrOr,
                Tok::Bang,
                Tok::Lt,
                Tok::Gt,
                Tok::End
            ]
        );
    }

    #[test]
    fn unicode_names_and_spans() {
        let t = tokenize("α+π").unwrap();
        assert_eq!((t[0].tok, t[0].start, t[0].end), (Tok::Ident, 0, 2));
        assert_eq!((t[2].tok, t[2].start, t[2].end), (Tok::Ident, 3, 5));
        assert_eq!((t[3].tok, t[3].start), (Tok::End, 5));
    }

    #[test]
    fn errors_point_at_the_character() {
        let e = tokenize("1 + $").unwrap_err();
        assert_eq!((e.offset, e.len), (4, 1));
        assert_eq!(e.message, "unexpected character '$'");
        let e = tokenize("t = 1").unwrap_err();
        assert_eq!(e.offset, 2);
        assert_eq!(
            tokenize("1e999").unwrap_err().message,
            "number '1e999' is too large"
        );
        assert_eq!(tokenize("1 + .").unwrap_err().offset, 4);
    }
}
