//! The parser: a Pratt (precedence-climbing) parser over tokens that emits
//! stack-machine code directly, without building a syntax tree.
//!
//! Precedence, loosest first: `or ||`, `and &&`, `not !`, comparisons (not
//! chainable), `+ -`, `* /`, unary `- +`, `^ **` (right-associative, so
//! `-x^2` is −(x²) and `2^3^2` is 2⁹; the exponent may carry a sign: `2^-t`).

use std::collections::HashMap;
use std::f64::consts::{E, PI};

use crate::compile::{Builder, Span, Sub};
use crate::error::ParseError;
use crate::function::{lookup, Emit, BUILTINS};
use crate::lexer::{is_name_char, is_name_start, tokenize, Tok, Token};
use crate::vm::{max_depth, Cmp, Op};

/// Longest accepted source, in bytes.
pub const MAX_LEN: usize = 100_000;
/// Deepest accepted nesting of sub-expressions (parentheses, calls, operands).
pub const MAX_NESTING: usize = 100;
/// Largest evaluation stack a program may need.
pub(crate) const MAX_STACK: usize = 512;

const NOT_BP: u8 = 5;
const UNARY_BP: u8 = 13;

/// A compiled program.
pub(crate) struct Program {
    pub code: Vec<Op>,
    pub spans: Vec<Span>,
    pub depth: usize,
}

/// An infix operator.
#[derive(Clone, Copy)]
enum Infix {
    Or,
    And,
    Bin(Op),
}

/// Compiles `src` as an expression of `var` (or of nothing) with `constants`.
pub(crate) fn compile(
    src: &str,
    var: Option<&str>,
    constants: &HashMap<String, f64>,
) -> Result<Program, ParseError> {
    compile_inputs(src, var, &[], constants)
}

/// Compiles `src` reading `inputs` (input k as `Op::Input(k)`) besides
/// `var` and `constants`. The variable, then the constants, shadow inputs.
pub(crate) fn compile_inputs(
    src: &str,
    var: Option<&str>,
    inputs: &[&str],
    constants: &HashMap<String, f64>,
) -> Result<Program, ParseError> {
    if src.len() > MAX_LEN {
        let mut cut = MAX_LEN;
        while !src.is_char_boundary(cut) {
            cut -= 1;
        }
        return Err(ParseError::new(
            format!(
                "expression too long ({} bytes; the limit is {MAX_LEN})",
                src.len()
            ),
            cut,
            src.len() - cut,
        ));
    }
    if let Some(v) = var {
        let mut chars = v.chars();
        let valid = chars.next().is_some_and(is_name_start) && chars.all(is_name_char);
        if !valid || matches!(v, "if" | "and" | "or" | "not") {
            return Err(ParseError::new(
                format!("'{v}' cannot name the variable: it must be a name that is not a keyword"),
                0,
                0,
            ));
        }
    }
    let toks = tokenize(src)?;
    if toks[0].tok == Tok::End {
        return Err(ParseError::new("empty expression", 0, src.len()));
    }
    let mut p = Parser {
        src,
        toks,
        pos: 0,
        nesting: 0,
        var,
        inputs,
        constants,
        b: Builder::default(),
    };
    p.expr(0)?;
    let t = p.peek();
    if t.tok != Tok::End {
        return Err(p.after_value(t, "after a complete expression"));
    }
    let Parser { b, .. } = p;
    let depth = max_depth(&b.code)
        .ok_or_else(|| ParseError::new("internal error: malformed program", 0, src.len()))?;
    if depth > MAX_STACK {
        return Err(ParseError::new(
            format!(
                "expression needs too deep an evaluation stack ({depth}; the limit is {MAX_STACK})"
            ),
            0,
            src.len(),
        ));
    }
    Ok(Program {
        code: b.code,
        spans: b.spans,
        depth,
    })
}

struct Parser<'a> {
    src: &'a str,
    toks: Vec<Token>,
    pos: usize,
    nesting: usize,
    var: Option<&'a str>,
    inputs: &'a [&'a str],
    constants: &'a HashMap<String, f64>,
    b: Builder,
}

impl<'a> Parser<'a> {
    fn peek(&self) -> Token {
        self.toks[self.pos]
    }

    fn next(&mut self) -> Token {
        let t = self.toks[self.pos];
        if t.tok != Tok::End {
            self.pos += 1;
        }
        t
    }

    fn text(&self, t: Token) -> &'a str {
        &self.src[t.start..t.end]
    }

    fn error(&self, message: impl Into<String>, t: Token) -> ParseError {
        ParseError::new(message, t.start, t.end - t.start)
    }

    /// How a token reads in an error message.
    fn describe(&self, t: Token) -> String {
        match t.tok {
            Tok::End => "the end of the expression".into(),
            Tok::Num(_) => format!("number {}", self.text(t)),
            Tok::Ident => format!("name '{}'", self.text(t)),
            _ => format!("'{}'", self.text(t)),
        }
    }

    /// The error for token `t` found where an operator or a closing token
    /// was expected (`context` says where).
    fn after_value(&self, t: Token, context: &str) -> ParseError {
        let starts_value = match t.tok {
            Tok::Num(_) | Tok::LParen => true,
            Tok::Ident => !matches!(self.text(t), "and" | "or"),
            _ => false,
        };
        match t.tok {
            _ if starts_value => self.error(
                format!(
                    "missing operator before {}; write '*' to multiply",
                    self.describe(t)
                ),
                t,
            ),
            Tok::RParen => self.error("unmatched ')'", t),
            Tok::Comma => self.error("',' outside of a function's arguments", t),
            _ => self.error(format!("unexpected {} {context}", self.describe(t)), t),
        }
    }

    /// The infix operator at `t` with its left and right binding powers.
    fn infix(&self, t: Token) -> Option<(Infix, u8, u8)> {
        let cmp = |k| Some((Infix::Bin(Op::Cmp(k)), 7, 8));
        match t.tok {
            Tok::OrOr => Some((Infix::Or, 1, 2)),
            Tok::AndAnd => Some((Infix::And, 3, 4)),
            Tok::Ident => match self.text(t) {
                "or" => Some((Infix::Or, 1, 2)),
                "and" => Some((Infix::And, 3, 4)),
                _ => None,
            },
            Tok::Lt => cmp(Cmp::Lt),
            Tok::Le => cmp(Cmp::Le),
            Tok::Gt => cmp(Cmp::Gt),
            Tok::Ge => cmp(Cmp::Ge),
            Tok::EqEq => cmp(Cmp::Eq),
            Tok::Ne => cmp(Cmp::Ne),
            Tok::Plus => Some((Infix::Bin(Op::Add), 9, 10)),
            Tok::Minus => Some((Infix::Bin(Op::Sub), 9, 10)),
            Tok::Star => Some((Infix::Bin(Op::Mul), 11, 12)),
            Tok::Slash => Some((Infix::Bin(Op::Div), 11, 12)),
            Tok::Caret => Some((Infix::Bin(Op::Pow), 15, 14)),
            _ => None,
        }
    }

    /// An expression whose operators all bind at least as tightly as `min_bp`.
    fn expr(&mut self, min_bp: u8) -> Result<Sub, ParseError> {
        self.nesting += 1;
        if self.nesting > MAX_NESTING {
            return Err(self.error(
                format!("expression nested too deeply (over {MAX_NESTING} levels)"),
                self.peek(),
            ));
        }
        let r = self.expr_inner(min_bp);
        self.nesting -= 1;
        r
    }

    fn expr_inner(&mut self, min_bp: u8) -> Result<Sub, ParseError> {
        let mut lhs = self.prefix()?;
        let mut lhs_is_cmp = false;
        while let Some((op, lbp, rbp)) = self.infix(self.peek()) {
            if lbp < min_bp {
                break;
            }
            let t = self.next();
            let is_cmp = matches!(op, Infix::Bin(Op::Cmp(_)));
            if is_cmp && lhs_is_cmp {
                return Err(self.error(
                    "comparisons cannot be chained; write (a < b) and (b < c)",
                    t,
                ));
            }
            lhs = match op {
                Infix::Or | Infix::And => {
                    let jump = if let Infix::Or = op {
                        Op::OrJump(0)
                    } else {
                        Op::AndJump(0)
                    };
                    let at = self.b.push(jump, Span::new(t.start, t.end));
                    let rhs = self.expr(rbp)?;
                    let rhs = self.b.apply(Op::Truth, &[rhs], rhs.span);
                    self.b.patch(at);
                    self.b
                        .logic(lhs, rhs, Span::new(lhs.span.start, rhs.span.end))
                }
                Infix::Bin(op) => {
                    let rhs = self.expr(rbp)?;
                    let span = Span::new(lhs.span.start, rhs.span.end);
                    self.b.apply(op, &[lhs, rhs], span)
                }
            };
            lhs_is_cmp = is_cmp;
        }
        Ok(lhs)
    }

    /// A value, a name, a call, a parenthesized expression or a prefix operator.
    fn prefix(&mut self) -> Result<Sub, ParseError> {
        let t = self.next();
        match t.tok {
            Tok::Num(v) => Ok(self.b.constant(v, Span::new(t.start, t.end))),
            Tok::Ident => self.name(t),
            Tok::Minus => {
                let a = self.expr(UNARY_BP)?;
                Ok(self.b.apply(Op::Neg, &[a], Span::new(t.start, a.span.end)))
            }
            Tok::Plus => {
                let a = self.expr(UNARY_BP)?;
                Ok(Sub {
                    span: Span::new(t.start, a.span.end),
                    ..a
                })
            }
            Tok::Bang => self.not(t),
            Tok::LParen => {
                let inner = self.expr(0)?;
                let close = self.peek();
                match close.tok {
                    Tok::RParen => {
                        self.next();
                        Ok(Sub {
                            span: Span::new(t.start, close.end),
                            ..inner
                        })
                    }
                    Tok::End => Err(self.error("unclosed '('", t)),
                    _ => Err(self.after_value(close, "where ')' was expected")),
                }
            }
            _ => Err(self.error(format!("expected a value, found {}", self.describe(t)), t)),
        }
    }

    fn not(&mut self, t: Token) -> Result<Sub, ParseError> {
        let a = self.expr(NOT_BP)?;
        Ok(self.b.apply(Op::Not, &[a], Span::new(t.start, a.span.end)))
    }

    /// A name: keyword, variable, parameter, built-in constant or call.
    fn name(&mut self, t: Token) -> Result<Sub, ParseError> {
        let text = self.text(t);
        let span = Span::new(t.start, t.end);
        let call = self.peek().tok == Tok::LParen;
        match text {
            "if" if call => return self.branch(t),
            "if" => return Err(self.error("'if' needs arguments: if(condition, then, else)", t)),
            "not" => return self.not(t),
            "and" | "or" => return Err(self.error(format!("expected a value, found '{text}'"), t)),
            _ if call => return self.call(t),
            _ => {}
        }
        if Some(text) == self.var {
            if self.constants.contains_key(text) {
                return Err(self.error(format!("'{text}' is both the variable and a parameter"), t));
            }
            return Ok(self.b.variable(span));
        }
        if let Some(&v) = self.constants.get(text) {
            if !v.is_finite() {
                return Err(self.error(format!("parameter '{text}' is not finite ({v})"), t));
            }
            return Ok(self.b.constant(v, span));
        }
        match text {
            "pi" | "π" => return Ok(self.b.constant(PI, span)),
            "e" => return Ok(self.b.constant(E, span)),
            _ => {}
        }
        if let Some(k) = self.inputs.iter().position(|&n| n == text) {
            return Ok(self.b.input(k as u16, span));
        }
        if lookup(text).is_some() {
            return Err(self.error(format!("'{text}' is a function; call it as {text}(...)"), t));
        }
        Err(self.error(self.unknown_name(text), t))
    }

    fn unknown_name(&self, text: &str) -> String {
        let mut names: Vec<&str> = self.var.into_iter().collect();
        names.extend(self.inputs.iter().copied());
        let mut params: Vec<&str> = self.constants.keys().map(String::as_str).collect();
        params.sort_unstable();
        names.extend(params);
        names.extend(["pi", "e"]);
        match (suggest(text, &names), self.var) {
            (Some(s), Some(v)) if s == v => {
                format!("unknown name '{text}'; the variable here is '{v}'")
            }
            (Some(s), Some(v)) => {
                format!("unknown name '{text}'; did you mean '{s}'? (the variable here is '{v}')")
            }
            (Some(s), None) => format!("unknown name '{text}'; did you mean '{s}'?"),
            (None, Some(v)) => format!("unknown name '{text}'; the variable here is '{v}'"),
            (None, None) => format!("unknown name '{text}'"),
        }
    }

    /// `if(cond, a, b)`, compiled as `cond JumpIfFalse(→b) a Jump(→end) b`.
    fn branch(&mut self, name: Token) -> Result<Sub, ParseError> {
        const USAGE: &str = "if takes 3 arguments: if(condition, then, else)";
        self.next();
        let cond = self.expr(0)?;
        self.expect(Tok::Comma, USAGE)?;
        let jif = self.b.push(Op::JumpIfFalse(0), cond.span);
        let a = self.expr(0)?;
        self.expect(Tok::Comma, USAGE)?;
        let jump = self.b.push(Op::Jump(0), a.span);
        self.b.patch(jif);
        let b = self.expr(0)?;
        let close = self.expect(Tok::RParen, USAGE)?;
        self.b.patch(jump);
        let span = Span::new(name.start, close.end);
        Ok(self.b.branch(cond, jif, a, jump, b, span))
    }

    /// Consumes a `want` token or fails with `usage` and what was found.
    fn expect(&mut self, want: Tok, usage: &str) -> Result<Token, ParseError> {
        let t = self.peek();
        if t.tok == want {
            return Ok(self.next());
        }
        let found = self.describe(t);
        Err(self.error(format!("{usage}; found {found}"), t))
    }

    /// A call `name(args...)` of a built-in function.
    fn call(&mut self, name: Token) -> Result<Sub, ParseError> {
        let text = self.text(name);
        let Some(f) = lookup(text) else {
            let value = Some(text) == self.var
                || self.inputs.contains(&text)
                || self.constants.contains_key(text)
                || matches!(text, "pi" | "π" | "e");
            let message = if value {
                format!("'{text}' is not a function; write '{text}*(...)' to multiply")
            } else {
                let names: Vec<&str> = BUILTINS.iter().map(|b| b.name).collect();
                match suggest(text, &names) {
                    Some(s) => format!("unknown function '{text}'; did you mean '{s}'?"),
                    None => format!("unknown function '{text}'"),
                }
            };
            return Err(self.error(message, name));
        };
        self.next();
        let mut args: Vec<Sub> = Vec::new();
        let mut folded: Option<Sub> = None;
        let close = if self.peek().tok == Tok::RParen {
            self.next()
        } else {
            loop {
                let a = self.expr(0)?;
                args.push(a);
                if let (Emit::Fold(op), Some(acc)) = (f.emit, folded) {
                    let span = Span::new(name.start, a.span.end);
                    folded = Some(self.b.apply(op, &[acc, a], span));
                } else {
                    folded = Some(a);
                }
                let t = self.next();
                match t.tok {
                    Tok::Comma => continue,
                    Tok::RParen => break t,
                    Tok::End => {
                        return Err(self.error(format!("unclosed '(' of {text}(...)"), name))
                    }
                    _ => {
                        let context = format!("in the arguments of {text}(...)");
                        return Err(self.after_value(t, &context));
                    }
                }
            }
        };
        let span = Span::new(name.start, close.end);
        let n = args.len();
        let arity_ok = match f.emit {
            Emit::Fold(_) => n >= f.arity,
            _ => n == f.arity,
        };
        if !arity_ok {
            let count = match (f.emit, f.arity) {
                (Emit::Fold(_), k) => format!("{k} or more arguments"),
                (_, 1) => "1 argument".into(),
                (_, k) => format!("{k} arguments"),
            };
            return Err(ParseError::new(
                format!("{text} takes {count} ({text}({})), found {n}", f.params),
                span.start,
                span.end - span.start,
            ));
        }
        Ok(match f.emit {
            Emit::Op(op) => self.b.apply(op, &args, span),
            Emit::Deg => self.b.apply(Op::MulC(PI / 180.0), &args, span),
            Emit::Motion(law) => self.b.apply(Op::Motion(law), &args, span),
            Emit::Fold(_) => {
                // Every pairwise op reports the whole call.
                let acc = folded.unwrap_or(args[0]);
                for s in &mut self.b.spans[acc.start..] {
                    if s.start == name.start {
                        *s = span;
                    }
                }
                Sub { span, ..acc }
            }
        })
    }
}

/// The closest of `names` to `text`: equal ignoring case, or within an edit
/// distance of 1 (names up to 3 characters) or 2 (longer names) that keeps
/// at least one character (`x` suggests nothing, not `e`).
fn suggest<'n>(text: &str, names: &[&'n str]) -> Option<&'n str> {
    let len = text.chars().count();
    let limit = if len <= 3 { 1 } else { 2 }.min(len.saturating_sub(1));
    let lower = text.to_lowercase();
    names
        .iter()
        .map(|&n| {
            let d = if n.to_lowercase() == lower {
                0
            } else {
                edit_distance(text, n)
            };
            (d, n)
        })
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, _)| d)
        .map(|(_, n)| n)
}

/// Levenshtein distance over characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let next = (diag + usize::from(ca != cb))
                .min(row[j] + 1)
                .min(row[j + 1] + 1);
            diag = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distances() {
        assert_eq!(edit_distance("tt", "t"), 1);
        assert_eq!(edit_distance("coss", "cos"), 1);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
    }

    #[test]
    fn suggestions() {
        assert_eq!(suggest("tt", &["t", "pi", "e"]), Some("t"));
        assert_eq!(suggest("PI", &["t", "pi", "e"]), Some("pi"));
        assert_eq!(suggest("zzz", &["t", "pi", "e"]), None);
        assert_eq!(suggest("x", &["t", "pi", "e"]), None);
        assert_eq!(suggest("T", &["t", "pi", "e"]), Some("t"));
    }
}
