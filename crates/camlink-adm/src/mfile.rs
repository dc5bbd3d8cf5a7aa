//! A `PointForceFile`'s MATLAB force function, translated to expressions of
//! state without running it.
//!
//! The course engine calls `F = mfile(t, qi, qdi)` with the time and the
//! coordinates `qi` = [x, y, φ] and velocities `qdi` of the force's body,
//! and applies the 2-vector F at the force's point. This module reads a
//! small subset of MATLAB and executes it symbolically: every variable
//! holds an expression, and an `if`/`elseif`/`else` chain merges the
//! variables its branches assign into `if(cond, a, b)`. The result is two
//! camlink expressions of `t` and the body's channels `<body>_x`, `_y`,
//! `_phi`, `_vx`, `_vy`, `_omega`. Nothing is evaluated.
//!
//! The subset: a `function F = name(t, qi, qdi)` header (any names, `~`
//! for an unused input, an optional closing `end`); statements `x = expr`,
//! `F = [a; b]`, `F(1) = expr`, `F(2) = expr`, `if`/`elseif`/`else`/`end`
//! (nested); expressions of numbers, `+ - * / ^` (and `.* ./ .^`), unary
//! `-` and `+`, parentheses, comparisons `> < >= <= == ~=`, `&& || & | ~`,
//! `qi(k)`, `qdi(k)` (k = 1, 2, 3), `F(k)`, the time input, `pi` and the
//! functions of [`FUNCTIONS`]; `%` comments, `%{ … %}` blocks and `...`
//! continuations. Anything else is refused with its line.

use std::collections::HashMap;
use std::rc::Rc;

/// MATLAB functions accepted, with their camlink spelling.
const FUNCTIONS: &[(&str, &str)] = &[
    ("sin", "sin"),
    ("cos", "cos"),
    ("tan", "tan"),
    ("exp", "exp"),
    ("log", "log"),
    ("sqrt", "sqrt"),
    ("abs", "abs"),
];

/// Keywords of MATLAB outside the subset, with what they are.
const REFUSED: &[(&str, &str)] = &[
    ("for", "a `for` loop"),
    ("parfor", "a `parfor` loop"),
    ("while", "a `while` loop"),
    ("switch", "a `switch` statement"),
    ("case", "a `case` clause"),
    ("otherwise", "an `otherwise` clause"),
    ("try", "a `try` block"),
    ("catch", "a `catch` block"),
    ("function", "a second function"),
    ("return", "`return`"),
    ("break", "`break`"),
    ("continue", "`continue`"),
    ("global", "a `global` variable"),
    ("persistent", "a `persistent` variable"),
    ("spmd", "an `spmd` block"),
    ("classdef", "a class definition"),
];

/// Longest translated expression (bytes), as camlink's expressions allow.
const MAX_TEXT: usize = 100_000;
/// Deepest expression tree (camlink's expressions nest at most 100 levels).
const MAX_DEPTH: usize = 90;
/// Deepest nesting of parentheses in one MATLAB expression, and of `if`s.
const MAX_NEST: usize = 64;

/// The force's two components as camlink expression text.
#[derive(Clone, Debug, PartialEq)]
pub struct Force {
    pub fx: String,
    pub fy: String,
}

/// Whether `name` is a plain MATLAB identifier (a letter, then letters,
/// digits and `_`, at most 63 characters), the only `mfile` names looked up.
pub fn is_identifier(name: &str) -> bool {
    let mut c = name.chars();
    c.next().is_some_and(|f| f.is_ascii_alphabetic())
        && c.all(|x| x.is_ascii_alphanumeric() || x == '_')
        && name.len() <= 63
}

/// Translates the force function `src` (the text of `file`, named in
/// messages) for a force on the body named `body`. An error reads
/// `file:line: what`.
pub fn translate(src: &str, file: &str, body: &str) -> Result<Force, String> {
    let toks = lex(src).map_err(|(line, m)| format!("{file}:{line}: {m}"))?;
    let mut p = Prog {
        toks,
        pos: 0,
        body: body.to_string(),
        inputs: [None, None, None],
        out: String::new(),
        nest: 0,
    };
    p.run().map_err(|(line, m)| format!("{file}:{line}: {m}"))
}

// ---------------------------------------------------------------- lexing

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Num(f64),
    Name(String),
    /// An operator or punctuation: `+ - * / ^ ( ) [ ] , ; = < > <= >= == ~= ~ && || & |`.
    Op(&'static str),
    /// A character outside the subset, refused where the parser meets it
    /// (so that `for k = 1:3` is refused as a loop).
    Other(char),
    /// The end of a line.
    Eol,
}

#[derive(Clone, Debug)]
struct Token {
    tok: Tok,
    line: usize,
    /// Whitespace before the token on its line.
    space: bool,
}

type Fail = (usize, String);

fn lex(src: &str) -> Result<Vec<Token>, Fail> {
    let mut out = Vec::new();
    let mut block = false;
    let mut line = 0;
    let mut joined = false;
    for (k, text) in src.lines().enumerate() {
        let number = k + 1;
        let trimmed = text.trim();
        if block {
            if trimmed == "%}" {
                block = false;
            }
            continue;
        }
        if trimmed == "%{" {
            block = true;
            continue;
        }
        if !joined {
            line = number;
        }
        joined = false;
        let chars: Vec<char> = text.chars().collect();
        let mut i = 0;
        let mut space = true;
        while i < chars.len() {
            let c = chars[i];
            if c == ' ' || c == '\t' || c == '\r' {
                space = true;
                i += 1;
                continue;
            }
            if c == '%' {
                break;
            }
            if c == '.' && chars.get(i + 1) == Some(&'.') && chars.get(i + 2) == Some(&'.') {
                joined = true;
                break;
            }
            let digit = |j: usize| chars.get(j).is_some_and(char::is_ascii_digit);
            let start = i;
            let tok = if c.is_ascii_digit() || (c == '.' && digit(i + 1)) {
                while digit(i) {
                    i += 1;
                }
                if chars.get(i) == Some(&'.') && !matches!(chars.get(i + 1), Some('*' | '/' | '^'))
                {
                    i += 1;
                    while digit(i) {
                        i += 1;
                    }
                }
                if matches!(chars.get(i), Some('e' | 'E'))
                    && (digit(i + 1)
                        || (matches!(chars.get(i + 1), Some('+' | '-')) && digit(i + 2)))
                {
                    i += 2;
                    while digit(i) {
                        i += 1;
                    }
                }
                let s: String = chars[start..i].iter().collect();
                if chars
                    .get(i)
                    .is_some_and(|c| c.is_ascii_alphabetic() || *c == '_')
                {
                    return Err((number, format!("the number '{s}{}' is not in the subset (imaginary and suffixed numbers are not read)", chars[i])));
                }
                let v: f64 = s
                    .parse()
                    .map_err(|_| (number, format!("cannot read the number '{s}'")))?;
                Tok::Num(v)
            } else if c.is_ascii_alphabetic() {
                while chars
                    .get(i)
                    .is_some_and(|c| c.is_ascii_alphanumeric() || *c == '_')
                {
                    i += 1;
                }
                Tok::Name(chars[start..i].iter().collect())
            } else {
                let two: String = chars[i..(i + 2).min(chars.len())].iter().collect();
                let op: &'static str = match two.as_str() {
                    "<=" => "<=",
                    ">=" => ">=",
                    "==" => "==",
                    "~=" => "~=",
                    "&&" => "&&",
                    "||" => "||",
                    ".*" => "*",
                    "./" => "/",
                    ".^" => "^",
                    _ => "",
                };
                if !op.is_empty() {
                    i += 2;
                    op_tok(op)
                } else {
                    let op: &'static str = match c {
                        '+' => "+",
                        '-' => "-",
                        '*' => "*",
                        '/' => "/",
                        '^' => "^",
                        '(' => "(",
                        ')' => ")",
                        '[' => "[",
                        ']' => "]",
                        ',' => ",",
                        ';' => ";",
                        '=' => "=",
                        '<' => "<",
                        '>' => ">",
                        '~' => "~",
                        '&' => "&",
                        '|' => "|",
                        _ => "",
                    };
                    i += 1;
                    if op.is_empty() {
                        Tok::Other(c)
                    } else {
                        op_tok(op)
                    }
                }
            };
            out.push(Token { tok, line, space });
            space = false;
        }
        if !joined {
            out.push(Token {
                tok: Tok::Eol,
                line,
                space: false,
            });
        }
    }
    if block {
        return Err((line, "a `%{` block comment is not closed".to_string()));
    }
    Ok(out)
}

fn op_tok(op: &'static str) -> Tok {
    Tok::Op(op)
}

// ---------------------------------------------------------------- values

/// A translated expression; shared between the variables that hold it.
#[derive(Debug)]
enum E {
    Num(f64),
    /// A camlink name: `t`, `pi` or a channel.
    Name(String),
    Neg(Rc<Node>),
    Not(Rc<Node>),
    /// A binary operator in camlink spelling.
    Bin(&'static str, Rc<Node>, Rc<Node>),
    Call(&'static str, Rc<Node>),
    If(Rc<Node>, Rc<Node>, Rc<Node>),
}

#[derive(Debug)]
struct Node {
    e: E,
    depth: usize,
}

fn node(e: E, line: usize) -> Result<Rc<Node>, Fail> {
    let depth = 1 + match &e {
        E::Num(_) | E::Name(_) => 0,
        E::Neg(a) | E::Not(a) | E::Call(_, a) => a.depth,
        E::Bin(_, a, b) => a.depth.max(b.depth),
        E::If(c, a, b) => c.depth.max(a.depth).max(b.depth),
    };
    if depth > MAX_DEPTH {
        return Err((
            line,
            format!("the translated force nests deeper than {MAX_DEPTH} levels"),
        ));
    }
    Ok(Rc::new(Node { e, depth }))
}

/// A variable's state on the paths reaching a statement.
#[derive(Clone, Debug)]
enum Val {
    Set(Rc<Node>),
    /// Assigned on some paths only (at the line given).
    Partly(usize),
}

type Env = HashMap<String, Val>;

/// camlink binding levels: `||` 1, `&&` 2, `!` 3, comparisons 4, + - 5,
/// * / 6, unary minus 7, ^ 8, atoms 9.
fn level(n: &Node) -> u8 {
    match &n.e {
        E::Num(_) | E::Name(_) | E::Call(..) | E::If(..) => 9,
        E::Not(_) => 3,
        E::Neg(_) => 7,
        E::Bin(op, ..) => bin_level(op),
    }
}

fn bin_level(op: &str) -> u8 {
    match op {
        "||" => 1,
        "&&" => 2,
        "<" | "<=" | ">" | ">=" | "==" | "!=" => 4,
        "+" | "-" => 5,
        "*" | "/" => 6,
        _ => 8,
    }
}

fn print(n: &Node, out: &mut String) -> Result<(), String> {
    if out.len() > MAX_TEXT {
        return Err(format!(
            "the translated force is longer than {MAX_TEXT} characters"
        ));
    }
    let child = |c: &Node, min: u8, out: &mut String| -> Result<(), String> {
        if level(c) < min {
            out.push('(');
            print(c, out)?;
            out.push(')');
            Ok(())
        } else {
            print(c, out)
        }
    };
    match &n.e {
        E::Num(v) => {
            if v.fract() == 0.0 && v.abs() < 1e15 {
                out.push_str(&format!("{}", *v as i64));
            } else {
                out.push_str(&format!("{v:?}"));
            }
        }
        E::Name(s) => out.push_str(s),
        E::Neg(a) => {
            out.push('-');
            child(a, 8, out)?;
        }
        E::Not(a) => {
            out.push('!');
            child(a, 9, out)?;
        }
        E::Bin(op, a, b) => {
            let p = bin_level(op);
            let (l, r) = match p {
                4 => (5, 5),
                8 => (9, 8),
                _ => (p, p + 1),
            };
            child(a, l, out)?;
            if p <= 5 {
                out.push(' ');
                out.push_str(op);
                out.push(' ');
            } else {
                out.push_str(op);
            }
            child(b, r, out)?;
        }
        E::Call(f, a) => {
            out.push_str(f);
            out.push('(');
            print(a, out)?;
            out.push(')');
        }
        E::If(c, a, b) => {
            out.push_str("if(");
            print(c, out)?;
            out.push_str(", ");
            print(a, out)?;
            out.push_str(", ");
            print(b, out)?;
            out.push(')');
        }
    }
    Ok(())
}

// ---------------------------------------------------------------- program

struct Prog {
    toks: Vec<Token>,
    pos: usize,
    body: String,
    /// The names of the inputs (time, positions, velocities); `None` for `~`.
    inputs: [Option<String>; 3],
    /// The output's name.
    out: String,
    nest: usize,
}

/// The env key of the output's component k (1 or 2): not an identifier.
fn comp(k: usize) -> String {
    format!("#{k}")
}

impl Prog {
    fn peek(&self) -> Option<&Tok> {
        self.toks.get(self.pos).map(|t| &t.tok)
    }

    fn line(&self) -> usize {
        self.toks
            .get(self.pos)
            .or(self.toks.last())
            .map_or(1, |t| t.line)
    }

    fn next(&mut self) -> Option<Tok> {
        let t = self.peek().cloned();
        self.pos += 1;
        t
    }

    fn fail<T>(&self, m: impl Into<String>) -> Result<T, Fail> {
        Err((self.line(), m.into()))
    }

    fn expect(&mut self, op: &str, what: &str) -> Result<(), Fail> {
        match self.peek() {
            Some(Tok::Op(o)) if *o == op => {
                self.pos += 1;
                Ok(())
            }
            _ => self.fail(format!("expected {what}")),
        }
    }

    fn name(&mut self, what: &str) -> Result<String, Fail> {
        match self.next() {
            Some(Tok::Name(n)) => Ok(n),
            _ => {
                self.pos -= 1;
                self.fail(format!("expected {what}"))
            }
        }
    }

    /// Skips line ends and statement separators.
    fn skip_separators(&mut self) {
        while matches!(self.peek(), Some(Tok::Eol | Tok::Op(";" | ","))) {
            self.pos += 1;
        }
    }

    fn run(&mut self) -> Result<Force, Fail> {
        self.skip_separators();
        self.header()?;
        let mut env = Env::new();
        if let Some(t) = &self.inputs[0] {
            env.insert(t.clone(), Val::Set(node(E::Name("t".into()), 1)?));
        }
        let end = self.block(&mut env)?;
        match end {
            Some(kw) if kw == "end" => {
                self.skip_separators();
                if self.peek().is_some() {
                    return self.fail(
                        "code after the function's `end` (a second function) is not in the subset",
                    );
                }
            }
            Some(kw) => return self.fail(format!("`{kw}` without an `if`")),
            None => {}
        }
        let line = self.line();
        let get = |k: usize| match env.get(&comp(k)) {
            Some(Val::Set(n)) => Ok(n.clone()),
            Some(Val::Partly(_)) => Err((
                line,
                format!(
                    "the output {}({k}) is not assigned on every path through the function",
                    self.out
                ),
            )),
            None => Err((
                line,
                format!(
                    "the function never assigns its output {} = [a; b]",
                    self.out
                ),
            )),
        };
        let (fx, fy) = (get(1)?, get(2)?);
        let text = |n: &Node| {
            let mut s = String::new();
            print(n, &mut s).map(|_| s).map_err(|m| (line, m))
        };
        Ok(Force {
            fx: text(&fx)?,
            fy: text(&fy)?,
        })
    }

    fn header(&mut self) -> Result<(), Fail> {
        match self.peek() {
            Some(Tok::Name(n)) if n == "function" => self.pos += 1,
            _ => {
                return self.fail(
                    "expected the header `function F = name(t, qi, qdi)` (a script is not in the subset)",
                )
            }
        }
        let bracket = matches!(self.peek(), Some(Tok::Op("[")));
        if bracket {
            self.pos += 1;
        }
        self.out = self.name("the output's name in `function F = name(t, qi, qdi)`")?;
        if bracket {
            self.expect("]", "`]` after the output's name (one output)")?;
        }
        self.expect("=", "`=` in `function F = name(t, qi, qdi)`")?;
        self.name("the function's name")?;
        self.expect("(", "`(t, qi, qdi)`: three inputs")?;
        for k in 0..3 {
            if k > 0 {
                self.expect(",", "`,` between the three inputs (t, qi, qdi)")?;
            }
            self.inputs[k] = match self.next() {
                Some(Tok::Op("~")) => None,
                Some(Tok::Name(n)) => Some(n),
                _ => {
                    self.pos -= 1;
                    return self.fail("expected three inputs (t, qi, qdi)");
                }
            };
        }
        self.expect(")", "`)` after three inputs (t, qi, qdi)")?;
        match self.peek() {
            Some(Tok::Eol | Tok::Op(";" | ",")) | None => Ok(()),
            _ => self.fail("unexpected text after the function header"),
        }
    }

    /// Runs statements until `end`, `else`, `elseif` (returned) or the end
    /// of the file (`None`).
    fn block(&mut self, env: &mut Env) -> Result<Option<String>, Fail> {
        loop {
            self.skip_separators();
            let Some(tok) = self.peek().cloned() else {
                return Ok(None);
            };
            let line = self.line();
            let Tok::Name(name) = tok else {
                return self.fail(format!(
                    "a statement starts with '{}'; only assignments and `if` are in the subset",
                    show(&tok)
                ));
            };
            match name.as_str() {
                "end" | "else" | "elseif" => {
                    self.pos += 1;
                    return Ok(Some(name));
                }
                "if" => {
                    self.pos += 1;
                    self.if_chain(env, line)?;
                }
                _ => {
                    if let Some((_, what)) = REFUSED.iter().find(|(k, _)| *k == name) {
                        return self.fail(format!("{what} is not in the subset"));
                    }
                    self.assignment(env, &name)?;
                }
            }
            match self.peek() {
                Some(Tok::Eol | Tok::Op(";" | ",")) | None => {}
                Some(t) => {
                    let t = show(t);
                    return self.fail(format!("unexpected '{t}' after the statement"));
                }
            }
        }
    }

    fn if_chain(&mut self, env: &mut Env, line: usize) -> Result<(), Fail> {
        self.nest += 1;
        if self.nest > MAX_NEST {
            return self.fail(format!(
                "`if` statements nest deeper than {MAX_NEST} levels"
            ));
        }
        let before = env.clone();
        let mut arms: Vec<(Rc<Node>, Env)> = Vec::new();
        let mut otherwise: Option<Env> = None;
        let mut cond = self.expr(&before, 0)?;
        loop {
            let mut branch = before.clone();
            let end = self.block(&mut branch)?;
            arms.push((cond.clone(), branch));
            match end.as_deref() {
                Some("elseif") => cond = self.expr(&before, 0)?,
                Some("else") => {
                    let mut branch = before.clone();
                    match self.block(&mut branch)?.as_deref() {
                        Some("end") => {}
                        _ => return Err((line, "this `if` has no matching `end`".into())),
                    }
                    otherwise = Some(branch);
                    break;
                }
                Some(_) => break,
                None => return Err((line, "this `if` has no matching `end`".into())),
            }
        }
        let mut merged = otherwise.unwrap_or(before);
        for (c, branch) in arms.into_iter().rev() {
            merged = merge(&c, branch, merged, line)?;
        }
        *env = merged;
        self.nest -= 1;
        Ok(())
    }

    fn assignment(&mut self, env: &mut Env, name: &str) -> Result<(), Fail> {
        self.pos += 1;
        if name == self.out {
            if matches!(self.peek(), Some(Tok::Op("("))) {
                self.pos += 1;
                let k = match self.next() {
                    Some(Tok::Num(v)) if v == 1.0 || v == 2.0 => v as usize,
                    _ => {
                        self.pos -= 1;
                        return self
                            .fail(format!("only {0}(1) and {0}(2) may be assigned", self.out));
                    }
                };
                self.expect(")", &format!("`)` in {}({k})", self.out))?;
                self.expect("=", "`=`")?;
                if !matches!(env.get(&comp(1)), Some(Val::Set(_)))
                    || !matches!(env.get(&comp(2)), Some(Val::Set(_)))
                {
                    return self.fail(format!(
                        "{0}({k}) is assigned before {0} = [a; b] on every path (MATLAB would make {0} a row vector)",
                        self.out
                    ));
                }
                let v = self.expr(env, 0)?;
                env.insert(comp(k), Val::Set(v));
                return Ok(());
            }
            self.expect("=", "`=`")?;
            self.expect("[", &format!("`{} = [a; b]`", self.out))?;
            let a = self.element(env)?;
            self.expect(";", &format!("`;` in `{} = [a; b]` (a column)", self.out))?;
            let b = self.element(env)?;
            self.expect("]", &format!("`]` closing `{} = [a; b]`", self.out))?;
            env.insert(comp(1), Val::Set(a));
            env.insert(comp(2), Val::Set(b));
            return Ok(());
        }
        if self.inputs[1..].iter().flatten().any(|i| i == name) {
            return self.fail(format!(
                "assigning to the input '{name}' is not in the subset"
            ));
        }
        if FUNCTIONS.iter().any(|(f, _)| *f == name) || name == "pi" {
            return self.fail(format!("assigning to '{name}' is not in the subset"));
        }
        match self.peek() {
            Some(Tok::Op("=")) => self.pos += 1,
            Some(Tok::Op("(")) => {
                return self.fail(format!(
                "an indexed assignment to '{name}' is not in the subset (only {} holds a vector)",
                self.out
            ))
            }
            _ => {
                return self.fail(format!(
                    "a statement that is not an assignment (`{name} …`) is not in the subset"
                ))
            }
        }
        if matches!(self.peek(), Some(Tok::Op("["))) {
            return self.fail(format!(
                "'{name}' = [...]: only {} holds a vector",
                self.out
            ));
        }
        let v = self.expr(env, 0)?;
        env.insert(name.to_string(), Val::Set(v));
        Ok(())
    }

    /// An element of `[a; b]`: one scalar expression, with no second
    /// element separated by a space (MATLAB reads `[x -1; 0]` as a row).
    fn element(&mut self, env: &Env) -> Result<Rc<Node>, Fail> {
        let start = self.pos;
        let v = self.expr(env, 0)?;
        for k in start + 1..self.pos.min(self.toks.len()) {
            let (prev, t) = (&self.toks[k - 1], &self.toks[k]);
            let ends = matches!(prev.tok, Tok::Num(_) | Tok::Name(_) | Tok::Op(")" | "]"));
            let starts = matches!(t.tok, Tok::Op("+" | "-" | "(" | "~"));
            let glued = self
                .toks
                .get(k + 1)
                .is_some_and(|n| !n.space || matches!(t.tok, Tok::Op("(")));
            if t.space && ends && starts && glued {
                return Err((
                    t.line,
                    format!(
                        "inside [ ], MATLAB reads '… {}…' after a space as a second element; write the operator with spaces on both sides",
                        show(&t.tok)
                    ),
                ));
            }
        }
        if matches!(self.peek(), Some(Tok::Op(",")))
            || matches!(self.peek(), Some(Tok::Num(_) | Tok::Name(_)))
        {
            return self.fail(format!(
                "{} = [a; b] holds one value per row (a column of two)",
                self.out
            ));
        }
        Ok(v)
    }

    /// MATLAB binding powers: `||` 1, `&&` 2, `|` 3, `&` 4, comparisons 5,
    /// `+ -` 6, `* /` 7, unary 8, `^` 9 (all binary operators left-associative).
    fn expr(&mut self, env: &Env, min: u8) -> Result<Rc<Node>, Fail> {
        self.nest += 1;
        if self.nest > MAX_NEST + 64 {
            return self.fail("the expression nests too deeply");
        }
        let r = self.binary(env, min);
        self.nest -= 1;
        r
    }

    fn binary(&mut self, env: &Env, min: u8) -> Result<Rc<Node>, Fail> {
        let mut lhs = self.unary(env)?;
        while let Some(Tok::Op(op)) = self.peek() {
            let (power, ours): (u8, &'static str) = match *op {
                "||" => (1, "||"),
                "&&" => (2, "&&"),
                "|" => (3, "||"),
                "&" => (4, "&&"),
                "<" => (5, "<"),
                "<=" => (5, "<="),
                ">" => (5, ">"),
                ">=" => (5, ">="),
                "==" => (5, "=="),
                "~=" => (5, "!="),
                "+" => (6, "+"),
                "-" => (6, "-"),
                "*" => (7, "*"),
                "/" => (7, "/"),
                "^" => (9, "^"),
                _ => break,
            };
            if power <= min {
                break;
            }
            let line = self.line();
            self.pos += 1;
            let rhs = if ours == "^" {
                self.power_operand(env)?
            } else {
                self.expr(env, power)?
            };
            lhs = node(E::Bin(ours, lhs, rhs), line)?;
        }
        Ok(lhs)
    }

    /// The operand of `^`: an atom, with signs (MATLAB reads 2^-t as 2^(-t)).
    fn power_operand(&mut self, env: &Env) -> Result<Rc<Node>, Fail> {
        let line = self.line();
        match self.peek() {
            Some(Tok::Op("-")) => {
                self.pos += 1;
                let x = self.nested(|p| p.power_operand(env))?;
                node(E::Neg(x), line)
            }
            Some(Tok::Op("+")) => {
                self.pos += 1;
                self.nested(|p| p.power_operand(env))
            }
            _ => self.atom(env),
        }
    }

    fn nested(
        &mut self,
        f: impl FnOnce(&mut Self) -> Result<Rc<Node>, Fail>,
    ) -> Result<Rc<Node>, Fail> {
        self.nest += 1;
        if self.nest > MAX_NEST + 64 {
            return self.fail("the expression nests too deeply");
        }
        let r = f(self);
        self.nest -= 1;
        r
    }

    fn unary(&mut self, env: &Env) -> Result<Rc<Node>, Fail> {
        let line = self.line();
        match self.peek() {
            Some(Tok::Op("-")) => {
                self.pos += 1;
                let x = self.expr(env, 8)?;
                node(E::Neg(x), line)
            }
            Some(Tok::Op("+")) => {
                self.pos += 1;
                self.expr(env, 8)
            }
            Some(Tok::Op("~")) => {
                self.pos += 1;
                let x = self.expr(env, 8)?;
                node(E::Not(x), line)
            }
            _ => self.atom(env),
        }
    }

    /// The index of `qi(k)`, `qdi(k)` or `F(k)`: a literal from 1 to `n`.
    fn index(&mut self, name: &str, n: usize) -> Result<usize, Fail> {
        if !matches!(self.peek(), Some(Tok::Op("("))) {
            return self.fail(format!(
                "'{name}' is a vector: read its elements as {name}(1) … {name}({n})"
            ));
        }
        self.pos += 1;
        let k = match self.next() {
            Some(Tok::Num(v)) if v.fract() == 0.0 && v >= 1.0 && v <= n as f64 => v as usize,
            _ => {
                self.pos -= 1;
                return self.fail(format!("{name}(k) is read with k a number from 1 to {n}"));
            }
        };
        self.expect(")", &format!("`)` in {name}({k})"))?;
        Ok(k)
    }

    fn atom(&mut self, env: &Env) -> Result<Rc<Node>, Fail> {
        let line = self.line();
        match self.next() {
            Some(Tok::Num(v)) => node(E::Num(v), line),
            Some(Tok::Op("(")) => {
                let e = self.expr(env, 0)?;
                self.expect(")", "`)`")?;
                Ok(e)
            }
            Some(Tok::Name(name)) => {
                for (k, what) in [(1, ["x", "y", "phi"]), (2, ["vx", "vy", "omega"])] {
                    if self.inputs[k].as_deref() == Some(name.as_str()) {
                        let i = self.index(&name, 3)?;
                        return node(E::Name(format!("{}_{}", self.body, what[i - 1])), line);
                    }
                }
                if name == self.out {
                    let k = self.index(&name, 2)?;
                    return match env.get(&comp(k)) {
                        Some(Val::Set(n)) => Ok(n.clone()),
                        _ => self.fail(format!(
                            "{name}({k}) is read before it is assigned on every path"
                        )),
                    };
                }
                if let Some(v) = env.get(&name) {
                    if matches!(self.peek(), Some(Tok::Op("("))) {
                        return self.fail(format!("'{name}' is a scalar and cannot be indexed"));
                    }
                    return match v {
                        Val::Set(n) => Ok(n.clone()),
                        Val::Partly(at) => self.fail(format!(
                            "'{name}' is read but is assigned only on some paths before it (line {at})"
                        )),
                    };
                }
                if matches!(self.peek(), Some(Tok::Op("("))) {
                    if name == "eval" || name == "feval" || name == "evalin" {
                        return self.fail(format!(
                            "`{name}` is not in the subset: camlink never runs code"
                        ));
                    }
                    let Some(&(_, f)) = FUNCTIONS.iter().find(|(m, _)| *m == name) else {
                        return self.fail(format!(
                            "a call to '{name}' is not in the subset (the functions read are {})",
                            FUNCTIONS
                                .iter()
                                .map(|(m, _)| *m)
                                .collect::<Vec<_>>()
                                .join(", ")
                        ));
                    };
                    self.pos += 1;
                    let a = self.expr(env, 0)?;
                    if matches!(self.peek(), Some(Tok::Op(","))) {
                        return self.fail(format!("{name} takes one argument"));
                    }
                    self.expect(")", &format!("`)` after the argument of {name}"))?;
                    return node(E::Call(f, a), line);
                }
                if name == "pi" {
                    return node(E::Name("pi".into()), line);
                }
                if REFUSED.iter().any(|(k, _)| *k == name) || name == "end" {
                    return self.fail(format!("the keyword `{name}` is not in the subset here"));
                }
                self.fail(format!("'{name}' is not defined"))
            }
            Some(t) => {
                self.pos -= 1;
                self.fail(format!("unexpected '{}' in an expression", show(&t)))
            }
            None => self.fail("the expression ends too early"),
        }
    }
}

fn show(t: &Tok) -> String {
    match t {
        Tok::Num(v) => format!("{v}"),
        Tok::Name(n) => n.clone(),
        Tok::Op(o) => o.to_string(),
        Tok::Other('\'') => "' (a string or a transpose)".into(),
        Tok::Other(c) => c.to_string(),
        Tok::Eol => "end of line".into(),
    }
}

/// The variables after `if c, A, else B, end`.
fn merge(c: &Rc<Node>, a: Env, mut b: Env, line: usize) -> Result<Env, Fail> {
    let mut out = Env::new();
    for (k, va) in a {
        let vb = b.remove(&k);
        let v = match (va, vb) {
            (Val::Set(x), Some(Val::Set(y))) => {
                if Rc::ptr_eq(&x, &y) {
                    Val::Set(x)
                } else {
                    Val::Set(node(E::If(c.clone(), x, y), line)?)
                }
            }
            _ => Val::Partly(line),
        };
        out.insert(k, v);
    }
    for (k, _) in b {
        out.insert(k, Val::Partly(line));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tr(src: &str) -> Result<Force, String> {
        translate(src, "f.m", "b")
    }

    #[test]
    fn branches_merge_into_if() {
        let f = tr("function F = f(t, qi, qdi)\nF = [0;0];\nif qdi(1) > 0\n  F(1) = -qi(1);\nelse\n  F(2) = 2^-t;\nend\n").unwrap();
        assert_eq!(f.fx, "if(b_vx > 0, -b_x, 0)");
        assert_eq!(f.fy, "if(b_vx > 0, 0, 2^(-t))");
    }

    #[test]
    fn matlab_grouping() {
        let f = tr("function F = f(t, q, qd)\nx = 2^3^2; y = -q(3)^2 ...\n  + 1\nF = [x; ~(y > 1) && t < 1 || 1 - (t - 1)];").unwrap();
        assert_eq!(f.fx, "(2^3)^2");
        assert_eq!(f.fy, "!(-b_phi^2 + 1 > 1) && t < 1 || 1 - (t - 1)");
    }

    #[test]
    fn refusals_name_the_line() {
        let e = tr("function F = f(t, qi, qdi)\nF = [0;0];\nfor k = 1:2\nend").unwrap_err();
        assert!(e.starts_with("f.m:3: a `for` loop"), "{e}");
        let e = tr("function F = f(t, qi, qdi)\nif t > 1\n x = 1;\nend\nF = [x; 0];").unwrap_err();
        assert!(e.starts_with("f.m:5: 'x' is read but"), "{e}");
        let e = tr("function F = f(t, qi, qdi)\nF = [y; 0];").unwrap_err();
        assert!(e.starts_with("f.m:2: 'y' is not defined"), "{e}");
        let e = tr("function F = f(t, qi, qdi)\nF = [t -1; 0];").unwrap_err();
        assert!(e.contains("second element"), "{e}");
        let e = tr("function F = f(t, qi, qdi)\nF(1) = 2;").unwrap_err();
        assert!(e.contains("row vector"), "{e}");
        let e = tr("function F = f(t, qi, qdi)\nx = 1;").unwrap_err();
        assert!(e.contains("never assigns"), "{e}");
        let deep = format!(
            "function F = f(t, qi, qdi)\nx = t;\n{}F = [x; 0];",
            "x = x + x;\n".repeat(200)
        );
        assert!(tr(&deep).unwrap_err().contains("nests deeper"));
    }
}
