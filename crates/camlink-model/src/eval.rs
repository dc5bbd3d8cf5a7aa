//! Expressions in model files, through camlink-expr.
//!
//! The one place this crate calls the expression parser: constant fields
//! evaluate with the file's parameters; a driver's `f` becomes a [`TimeFn`]
//! of `t` (s). Errors come back as text: the parser's message, then the
//! expression with a caret under the fault.

use std::collections::HashMap;

use camlink_core::TimeFn;
use camlink_expr::{Expr, ParseError};

/// Evaluates a constant expression with the file's parameters.
pub(crate) fn constant(src: &str, consts: &HashMap<String, f64>) -> Result<f64, String> {
    camlink_expr::eval_constant(src, consts).map_err(|e| describe(src, &e))
}

/// Parses a function of time `t` (s) with the file's parameters.
pub(crate) fn time_fn(src: &str, consts: &HashMap<String, f64>) -> Result<TimeFn, String> {
    let e = Expr::parse_with(src, Some("t"), consts).map_err(|e| describe(src, &e))?;
    if e.is_constant() {
        let v = e.eval(0.0);
        if !v.is_finite() {
            return Err(format!(
                "value is not a finite number ({})",
                camlink_core::fmt_num::num(v)
            ));
        }
        return Ok(TimeFn::Const(v));
    }
    Ok(TimeFn::from(e))
}

/// `invalid expression: <message>` followed by the source line and carets.
fn describe(src: &str, e: &ParseError) -> String {
    let rendered = e.render(src);
    let caret = rendered
        .splitn(3, '\n')
        .take(2)
        .map(|l| format!("    {l}"))
        .collect::<Vec<_>>()
        .join("\n");
    format!("invalid expression: {}\n{caret}", e.message)
}

/// Parses a function of the variable `var` (a curve's `a` or `s`) with the
/// file's parameters.
pub(crate) fn function_of(
    src: &str,
    var: &str,
    consts: &HashMap<String, f64>,
) -> Result<Expr, String> {
    Expr::parse_with(src, Some(var), consts).map_err(|e| describe(src, &e))
}

/// The names `src` reads (its variables and parameters, not its functions).
pub(crate) fn names(src: &str) -> Result<Vec<&str>, String> {
    camlink_expr::names(src).map_err(|e| describe(src, &e))
}

/// Parses an expression of the named `inputs` (a force of state's
/// channels) with the file's parameters.
pub(crate) fn state_expr(
    src: &str,
    inputs: &[&str],
    consts: &HashMap<String, f64>,
) -> Result<Expr, String> {
    Expr::parse_inputs(src, inputs, consts).map_err(|e| describe(src, &e))
}
