//! Expressions of one variable with exact derivatives.
//!
//! Drivers f(t) such as `pi/6 + 2*pi*t` and cam profiles ρ(α) such as
//! `if(a <= 2*pi/3, 5/4 - cos(3*a)/4, 1)` are parsed once into an [`Expr`];
//! [`Expr::jet`] then returns `[f, f', f'', f''']` at a point, derivatives
//! with respect to the variable computed exactly by forward-mode jets
//! (truncated Taylor arithmetic to third order, see [`Jet`]), never by finite
//! differences.
//!
//! ```
//! use camlink_expr::Expr;
//!
//! let rho = Expr::parse("if(a <= 2*pi/3, 5/4 - cos(3*a)/4, 1)", "a").unwrap();
//! let [r, dr, ddr, dddr] = rho.jet(0.5);
//! assert_eq!(r, 1.25 - 1.5f64.cos() / 4.0);
//! assert_eq!(dr, 0.75 * 1.5f64.sin());
//! assert_eq!(rho.jet(3.0), [1.0, 0.0, 0.0, 0.0]);
//!
//! let src = "2*tt";
//! let err = Expr::parse(src, "t").unwrap_err();
//! assert_eq!(err.render(src), "2*tt\n  ^^\nunknown name 'tt'; the variable here is 't'");
//!
//! let f = Expr::parse("log(t - 1)", "t").unwrap();
//! assert_eq!(
//!     f.check(0.5).unwrap_err().to_string(),
//!     "log of a negative number (-0.5) in `log(t - 1)` at t = 0.5"
//! );
//! ```
//!
//! Parsing and evaluating never run user code: a tokenizer and a Pratt
//! parser compile the source to a flat list of stack-machine instructions
//! whose only control flow is forward jumps. Evaluation allocates nothing
//! and never panics; an operation outside its domain yields NaN or infinity,
//! and [`Expr::check`] names it.
//!
//! # Language
//!
//! - Numbers: `1`, `1.5`, `.5`, `2.`, `1e-3`, `1.5E+2`.
//! - Names: the variable (chosen by the caller, e.g. `t` or `a`; any letter
//!   including `α`) or the inputs of a multi-input expression
//!   ([`Expr::parse_inputs`]), parameters passed to [`Expr::parse_with`], and the
//!   constants `pi` (also `π`) and `e`. Parameters shadow `pi` and `e`; a
//!   parameter may not share the variable's name.
//! - Arithmetic: `+ - * /`, powers `^` or `**` (right-associative; `-x^2`
//!   is −(x²)), unary `-` and `+`, parentheses.
//! - Comparisons `< <= > >= == !=` give 1 or 0 and cannot be chained.
//!   Logic: `and` `or` `not` (also `&&` `||` `!`) treat any non-zero value
//!   as true, give 1 or 0, and evaluate their right operand only when needed.
//!   All of these have zero derivatives.
//! - `if(cond, a, b)`: a where cond is non-zero, else b. Only the chosen
//!   branch is evaluated, and the derivatives are those of that branch.
//!
//! Precedence, loosest first: `or`, `and`, `not`, comparisons, `+ -`,
//! `* /`, unary `- +`, `^`.
//!
//! # Functions
//!
//! | call | value | derivative notes |
//! |---|---|---|
//! | `sin(x)` `cos(x)` `tan(x)` | trigonometric, radians | |
//! | `asin(x)` `acos(x)` | inverse sine and cosine, x in [−1, 1] | infinite at ±1 |
//! | `atan(x)` | inverse tangent | |
//! | `atan2(y, x)` | angle of the point (x, y) in (−π, π] | those of atan(y/x) |
//! | `sinh(x)` `cosh(x)` `tanh(x)` | hyperbolic | |
//! | `exp(x)` | eˣ | |
//! | `log(x)` `ln(x)` | natural logarithm, x > 0 | |
//! | `sqrt(x)` | √x, x ≥ 0 | infinite at 0 |
//! | `abs(x)` | \|x\| | sign(x); 0 at x = 0 |
//! | `sign(x)` | −1, 0 or 1 | zero |
//! | `floor(x)` `ceil(x)` | round down, up | zero |
//! | `min(a, b, ...)` `max(a, b, ...)` | smallest, largest | those of the chosen argument (the first on a tie) |
//! | `mod(x, y)` | x − y⌊x/y⌋, the sign of y | x' − ⌊x/y⌋ y' |
//! | `hypot(x, y)` | √(x² + y²) | |
//! | `deg(x)` | x·π/180 (degrees to radians) | |
//! | `impact(x, xd, x1, k, e, cmax, d)` | ADAMS IMPACT: for x < x1, max(0, k (x1 − x)ᵉ − step(x, x1 − d, cmax, x1, 0)·xd); 0 for x ≥ x1 | exact on each side; d > 0, e ≥ 1 |
//! | `coulomb(v, fc, vs)` | smooth Coulomb law fc·step(v, −vs, −1, vs, 1): fc·sign(v) for \|v\| ≥ vs | C1; vs > 0 |
//!
//! # Motion laws
//!
//! Each law is called as `law(x, x0, h0, x1, h1)`, the argument order of
//! ADAMS `STEP`, and goes from the point (x0, h0) to the point (x1, h1):
//! h0 for x on the x0 side, h1 beyond x1, and in between
//! h0 + (h1 − h0)·s(u) with u = (x − x0)/(x1 − x0). x is usually the variable
//! (`step(t, 0, 0, 1, 0.5)`) but may be any expression. Derivatives of the
//! shapes are analytic (see [`Law::shape`]).
//!
//! | call | shape s(u) | smooth to |
//! |---|---|---|
//! | `ramp` | u (constant velocity) | value (C0) |
//! | `step` | u²(3 − 2u), ADAMS STEP | velocity (C1) |
//! | `step5`, `poly345` | 10u³ − 15u⁴ + 6u⁵, ADAMS STEP5 | acceleration (C2) |
//! | `harmonic` | (1 − cos πu)/2 | velocity (C1) |
//! | `cycloidal` | u − sin(2πu)/(2π) | acceleration (C2) |
//!
//! # Limits
//!
//! Sources longer than [`MAX_LEN`] bytes and sub-expressions nested more
//! than [`MAX_NESTING`] levels deep are rejected with a [`ParseError`].

#![forbid(unsafe_code)]
#![warn(unreachable_pub)]

mod compile;
mod error;
pub mod fmt_num;
mod function;
#[macro_use]
mod jet_common;
mod jet;
mod jet4;
mod lexer;
mod motion;
mod parser;
mod vm;

use std::collections::HashMap;
use std::fmt;

use compile::Span;
use vm::{run, Args, Fault, Op};

pub use error::{EvalError, ParseError, RENDER_WIDTH};
pub use function::functions;
pub use jet::Jet;
pub use jet4::Jet4;
pub use motion::Law;
pub use parser::{MAX_LEN, MAX_NESTING};

/// A compiled expression of one variable, immutable after parsing.
#[derive(Clone, Debug)]
pub struct Expr {
    source: String,
    var: Option<String>,
    /// Names of the inputs of a multi-input expression, in input order.
    inputs: Box<[String]>,
    code: Box<[Op]>,
    spans: Box<[Span]>,
    /// Evaluation stack slots the code needs.
    depth: usize,
}

impl Expr {
    /// Parses `src` as an expression of the single variable named `var`
    /// (e.g. `"t"` or `"a"`).
    pub fn parse(src: &str, var: &str) -> Result<Expr, ParseError> {
        Expr::parse_with(src, Some(var), &HashMap::new())
    }

    /// Parses `src` with named constants (model parameters) substituted at
    /// compile time; `var: None` makes a constant expression.
    pub fn parse_with(
        src: &str,
        var: Option<&str>,
        constants: &HashMap<String, f64>,
    ) -> Result<Expr, ParseError> {
        let p = parser::compile(src, var, constants)?;
        Ok(Expr {
            source: src.to_owned(),
            var: var.map(str::to_owned),
            inputs: Box::default(),
            code: p.code.into_boxed_slice(),
            spans: p.spans.into_boxed_slice(),
            depth: p.depth,
        })
    }

    /// Parses `src` as an expression of several inputs, named in `inputs`
    /// (input k is `inputs[k]`), with named constants substituted at compile
    /// time; the constants shadow inputs of the same name.
    /// [`eval_inputs`](Self::eval_inputs) and [`gradient`](Self::gradient)
    /// evaluate it.
    ///
    /// ```
    /// use std::collections::HashMap;
    /// use camlink_expr::Expr;
    ///
    /// let f = Expr::parse_inputs("if(v > 0, -k*v^2, 0)", &["v"], &HashMap::from([("k".into(), 2.0)])).unwrap();
    /// assert_eq!(f.eval_inputs(&[3.0]), -18.0);
    /// let mut g = [0.0];
    /// assert_eq!(f.gradient(&[3.0], &mut g), -18.0);
    /// assert_eq!(g, [-12.0]);
    /// ```
    pub fn parse_inputs(
        src: &str,
        inputs: &[&str],
        constants: &HashMap<String, f64>,
    ) -> Result<Expr, ParseError> {
        let p = parser::compile_inputs(src, None, inputs, constants)?;
        Ok(Expr {
            source: src.to_owned(),
            var: None,
            inputs: inputs.iter().map(|&n| n.to_owned()).collect(),
            code: p.code.into_boxed_slice(),
            spans: p.spans.into_boxed_slice(),
            depth: p.depth,
        })
    }

    /// The names of a multi-input expression's inputs, in input order.
    pub fn inputs(&self) -> &[String] {
        &self.inputs
    }

    /// The value at the inputs `u` (one per input; a missing one reads as
    /// NaN).
    #[inline]
    pub fn eval_inputs(&self, u: &[f64]) -> f64 {
        match self.depth {
            0..=4 => self.eval_inputs_on::<4>(u),
            5..=8 => self.eval_inputs_on::<8>(u),
            9..=32 => self.eval_inputs_on::<32>(u),
            _ => self.eval_inputs_on::<{ parser::MAX_STACK }>(u),
        }
    }

    #[inline]
    fn eval_inputs_on<const N: usize>(&self, u: &[f64]) -> f64 {
        let mut stack = [0.0; N];
        let args = Args {
            x: f64::NAN,
            inputs: u,
            active: usize::MAX,
        };
        run::<f64, false>(&self.code, args, &mut stack).unwrap_or(f64::NAN)
    }

    /// The value at the inputs `u`, returned, and its partial derivatives
    /// ∂f/∂u_k into `grad[k]`, exact: forward-mode jets, one pass per
    /// input with that input as the variable. Where the expression is not
    /// differentiable (the switch of an `if`, `sign`, `min`) the
    /// derivative is that of the branch taken.
    pub fn gradient(&self, u: &[f64], grad: &mut [f64]) -> f64 {
        match self.depth {
            0..=4 => self.gradient_on::<4>(u, grad),
            5..=8 => self.gradient_on::<8>(u, grad),
            9..=32 => self.gradient_on::<32>(u, grad),
            _ => self.gradient_on::<{ parser::MAX_STACK }>(u, grad),
        }
    }

    fn gradient_on<const N: usize>(&self, u: &[f64], grad: &mut [f64]) -> f64 {
        let mut stack = [Jet::ZERO; N];
        let mut value = f64::NAN;
        if grad.is_empty() {
            return self.eval_inputs(u);
        }
        for (k, g) in grad.iter_mut().enumerate() {
            let args = Args {
                x: f64::NAN,
                inputs: u,
                active: k,
            };
            let j = run::<Jet, false>(&self.code, args, &mut stack).map_or([f64::NAN; 4], |j| j.0);
            value = j[0];
            *g = j[1];
        }
        value
    }

    /// Evaluates at the inputs `u` with checks and names the first
    /// operation that fails, as [`check`](Self::check) does.
    pub fn check_inputs(&self, u: &[f64]) -> Result<(), EvalError> {
        let mut stack = vec![Jet::ZERO; self.depth.max(1)];
        let args = Args {
            x: f64::NAN,
            inputs: u,
            active: 0,
        };
        match run::<Jet, true>(&self.code, args, &mut stack) {
            Ok(_) => Ok(()),
            Err(Fault { pc, what }) => {
                let mut message = format!("{what} in `{}`", self.snippet(self.spans[pc]));
                let at: Vec<String> = self
                    .inputs
                    .iter()
                    .zip(u)
                    .map(|(n, v)| format!("{n} = {}", fmt_num::num(*v)))
                    .collect();
                if !at.is_empty() {
                    message += &format!(" at {}", at.join(", "));
                }
                Err(EvalError {
                    message,
                    x: u.first().copied().unwrap_or(f64::NAN),
                })
            }
        }
    }

    /// The value f(x).
    #[inline]
    pub fn eval(&self, x: f64) -> f64 {
        match self.depth {
            0..=4 => self.eval_on::<4>(x),
            5..=8 => self.eval_on::<8>(x),
            9..=32 => self.eval_on::<32>(x),
            _ => self.eval_on::<{ parser::MAX_STACK }>(x),
        }
    }

    /// `[f, f', f'', f''']` at x, derivatives with respect to the variable.
    /// Domain errors give NaN or infinity, never a panic.
    #[inline]
    pub fn jet(&self, x: f64) -> [f64; 4] {
        // The stack is an array on the call stack, of the smallest size
        // class that holds the program's depth.
        match self.depth {
            0..=4 => self.jet_on::<4>(x),
            5..=8 => self.jet_on::<8>(x),
            9..=32 => self.jet_on::<32>(x),
            _ => self.jet_on::<{ parser::MAX_STACK }>(x),
        }
    }

    /// `[f, f', f'', f''', f'''']` at x: [`jet`](Self::jet) one order
    /// further ([`Jet4`]), for the jerk analysis.
    pub fn jet4(&self, x: f64) -> [f64; 5] {
        match self.depth {
            0..=4 => self.jet4_on::<4>(x),
            5..=8 => self.jet4_on::<8>(x),
            9..=32 => self.jet4_on::<32>(x),
            _ => self.jet4_on::<{ parser::MAX_STACK }>(x),
        }
    }

    fn jet4_on<const N: usize>(&self, x: f64) -> [f64; 5] {
        let mut stack = [Jet4::ZERO; N];
        run::<Jet4, false>(&self.code, Args::at(x), &mut stack).map_or([f64::NAN; 5], |j| j.0)
    }

    #[inline]
    fn eval_on<const N: usize>(&self, x: f64) -> f64 {
        let mut stack = [0.0; N];
        run::<f64, false>(&self.code, Args::at(x), &mut stack).unwrap_or(f64::NAN)
    }

    #[inline]
    fn jet_on<const N: usize>(&self, x: f64) -> [f64; 4] {
        let mut stack = [Jet::ZERO; N];
        run::<Jet, false>(&self.code, Args::at(x), &mut stack).map_or([f64::NAN; 4], |j| j.0)
    }

    /// Evaluates the jet at x with checks and names the first operation that
    /// fails: division by zero, log or square root of a negative number,
    /// asin/acos outside [−1, 1], a value or derivative that is not finite.
    pub fn check(&self, x: f64) -> Result<(), EvalError> {
        self.fault(x).map_or(Ok(()), |(what, span)| {
            let mut message = format!("{what} in `{}`", self.snippet(span));
            if let Some(v) = &self.var {
                message += &format!(" at {v} = {}", fmt_num::num(x));
            }
            Err(EvalError { message, x })
        })
    }

    /// The first failing operation at x and its source span.
    fn fault(&self, x: f64) -> Option<(String, Span)> {
        let mut stack = vec![Jet::ZERO; self.depth.max(1)];
        match run::<Jet, true>(&self.code, Args::at(x), &mut stack) {
            Ok(_) => None,
            Err(Fault { pc, what }) => Some((what, self.spans[pc])),
        }
    }

    /// The source of `span` on one line, shortened to about 60 characters.
    fn snippet(&self, span: Span) -> String {
        let text = self.source.get(span.start..span.end).unwrap_or("");
        let words: Vec<&str> = text.split_whitespace().collect();
        let one_line = words.join(" ");
        if one_line.chars().count() > 60 {
            let head: String = one_line.chars().take(57).collect();
            format!("{head}...")
        } else {
            one_line
        }
    }

    /// The source text.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// The variable's name; `None` for a constant expression.
    pub fn var(&self) -> Option<&str> {
        self.var.as_deref()
    }

    /// True when the expression does not depend on the variable: the
    /// variable does not appear in it, or appears only in an `if` branch
    /// that a constant condition rules out.
    pub fn is_constant(&self) -> bool {
        !self
            .code
            .iter()
            .any(|op| matches!(op, Op::Var | Op::Input(_)))
    }
}

impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.source)
    }
}

/// The smooth Coulomb law of the expression function `coulomb(v, fc, vs)`,
/// fc·STEP(v, −vs, −1, vs, 1), and its slope: `[f, ∂f/∂v]` at slip speed
/// `v`, friction level `fc` and transition speed `vs` > 0. Joint friction
/// in the core evaluates this same law.
pub fn coulomb(v: f64, fc: f64, vs: f64) -> [f64; 2] {
    let f = vm::coulomb(Jet::variable(v), Jet::constant(fc), Jet::constant(vs));
    [f.0[0], f.0[1]]
}

/// The names `src` reads — its variable and named constants, not the
/// functions it calls — each once, in order of first appearance. Only the
/// tokens are read (no parsing, no evaluation), so this is linear in the
/// length of `src`; a model file uses it to order its parameters.
pub fn names(src: &str) -> Result<Vec<&str>, ParseError> {
    let toks = lexer::tokenize(src)?;
    let mut out: Vec<&str> = Vec::new();
    for (k, t) in toks.iter().enumerate() {
        let call = toks.get(k + 1).is_some_and(|n| n.tok == lexer::Tok::LParen);
        if t.tok == lexer::Tok::Ident && !call {
            let name = &src[t.start..t.end];
            // The word operators are keywords, not names.
            if !matches!(name, "and" | "or" | "not") && !out.contains(&name) {
                out.push(name);
            }
        }
    }
    Ok(out)
}

/// Evaluates a constant expression such as `"deg(30)"` or `"2*r"` with
/// parameters. A value that is not finite (`1/0`, `log(-1)`) is an error
/// pointing at the operation.
pub fn eval_constant(src: &str, constants: &HashMap<String, f64>) -> Result<f64, ParseError> {
    let e = Expr::parse_with(src, None, constants)?;
    if let Some((what, span)) = e.fault(0.0) {
        return Err(ParseError::new(what, span.start, span.end - span.start));
    }
    Ok(e.eval(0.0))
}
