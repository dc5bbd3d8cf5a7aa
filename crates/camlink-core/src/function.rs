//! Functions of time f(t) for drivers, with exact derivatives.

use std::sync::Arc;

use camlink_expr::Expr;

/// A function of time t (s): a constant or a parsed expression.
///
/// `jet(t)` returns `[f, f', f'', f''']`, derivatives with respect to t,
/// computed exactly by forward-mode jets.
#[derive(Clone, Debug)]
pub enum TimeFn {
    Const(f64),
    Expr(Arc<Expr>),
}

impl TimeFn {
    /// `[f(t), f'(t), f''(t), f'''(t)]`. Domain errors inside an expression
    /// give non-finite values; `Expr::check` names the operation.
    #[inline]
    pub fn jet(&self, t: f64) -> [f64; 4] {
        match self {
            TimeFn::Const(c) => [*c, 0.0, 0.0, 0.0],
            TimeFn::Expr(e) => e.jet(t),
        }
    }

    #[inline]
    pub fn value(&self, t: f64) -> f64 {
        self.jet(t)[0]
    }

    /// True for a function that does not depend on time.
    pub fn is_const(&self) -> bool {
        matches!(self, TimeFn::Const(_))
    }
}

impl From<f64> for TimeFn {
    fn from(c: f64) -> Self {
        TimeFn::Const(c)
    }
}

impl From<Expr> for TimeFn {
    fn from(e: Expr) -> Self {
        TimeFn::Expr(Arc::new(e))
    }
}
