//! Expressions of one variable with exact derivatives.
//!
//! Interface placeholder while the parser lands: `Expr::parse` reports that
//! expressions are not available yet.

/// A compiled expression of one variable.
#[derive(Clone, Debug)]
pub struct Expr {
    source: String,
}

/// Why an expression could not be parsed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct ParseError {
    pub message: String,
}

impl Expr {
    /// Parses `src` as an expression of the variable `var`.
    pub fn parse(src: &str, var: &str) -> Result<Expr, ParseError> {
        let _ = var;
        Err(ParseError {
            message: format!("expressions are not available yet: {src}"),
        })
    }

    /// `[f, f', f'', f''']` at `x`.
    pub fn jet(&self, _x: f64) -> [f64; 4] {
        [f64::NAN; 4]
    }

    pub fn source(&self) -> &str {
        &self.source
    }
}
