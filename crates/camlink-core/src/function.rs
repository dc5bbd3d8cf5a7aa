//! Functions of time f(t) for drivers, with exact derivatives.

use std::sync::Arc;

use camlink_expr::Expr;

/// A function of time t (s): a constant, a constant-rate ramp, a harmonic or a
/// parsed expression. Values are in the unit of the driven coordinate (m or
/// rad); rates are per second.
///
/// `jet(t)` returns `[f, f', f'', f''']`, derivatives with respect to t,
/// computed exactly (in closed form, or by forward-mode jets for an
/// expression).
#[derive(Clone, Debug)]
pub enum TimeFn {
    /// f = c.
    Const(f64),
    /// f = value + rate·t: a constant-speed motor or actuator.
    Linear { value: f64, rate: f64 },
    /// f = offset + amplitude·sin(omega·t + phase), omega in rad/s and phase
    /// in rad: a harmonic (crank-driven or shaker) motion.
    Sine {
        amplitude: f64,
        omega: f64,
        phase: f64,
        offset: f64,
    },
    /// A parsed expression of t.
    Expr(Arc<Expr>),
}

impl TimeFn {
    /// `[f(t), f'(t), f''(t), f'''(t)]`. Domain errors inside an expression
    /// give non-finite values; `Expr::check` names the operation.
    #[inline]
    pub fn jet(&self, t: f64) -> [f64; 4] {
        match self {
            TimeFn::Const(c) => [*c, 0.0, 0.0, 0.0],
            TimeFn::Linear { value, rate } => [value + rate * t, *rate, 0.0, 0.0],
            TimeFn::Sine {
                amplitude: a,
                omega: w,
                phase,
                offset,
            } => {
                let (sn, cs) = (w * t + phase).sin_cos();
                [
                    offset + a * sn,
                    a * w * cs,
                    -a * w * w * sn,
                    -a * w * w * w * cs,
                ]
            }
            TimeFn::Expr(e) => e.jet(t),
        }
    }

    /// Checks that f and its derivatives are finite at `t`, naming the
    /// failing operation of an expression (a division by zero, the log of a
    /// negative number…).
    pub fn check(&self, t: f64) -> Result<(), String> {
        if let TimeFn::Expr(e) = self {
            return e.check(t).map_err(|err| err.message);
        }
        match self.jet(t).iter().all(|v| v.is_finite()) {
            true => Ok(()),
            false => Err(format!(
                "the function of time is not finite at t = {}",
                crate::fmt_num::num(t)
            )),
        }
    }

    #[inline]
    pub fn value(&self, t: f64) -> f64 {
        self.jet(t)[0]
    }

    /// True for a function that does not depend on time.
    pub fn is_const(&self) -> bool {
        match self {
            TimeFn::Const(_) => true,
            TimeFn::Linear { rate, .. } => *rate == 0.0,
            TimeFn::Sine {
                amplitude, omega, ..
            } => *amplitude == 0.0 || *omega == 0.0,
            TimeFn::Expr(_) => false,
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Central difference of component `k` of the jet at `t`.
    fn fd(f: &TimeFn, k: usize, t: f64) -> f64 {
        let h = 1e-5;
        (f.jet(t + h)[k] - f.jet(t - h)[k]) / (2.0 * h)
    }

    #[test]
    fn linear_jet() {
        let f = TimeFn::Linear {
            value: 0.5,
            rate: 2.0,
        };
        assert_eq!(f.jet(1.5), [3.5, 2.0, 0.0, 0.0]);
        assert!(!f.is_const());
        assert!(TimeFn::Linear {
            value: 1.0,
            rate: 0.0
        }
        .is_const());
    }

    #[test]
    fn sine_jet_values_and_derivatives() {
        let f = TimeFn::Sine {
            amplitude: 0.3,
            omega: 2.0,
            phase: 0.4,
            offset: 1.0,
        };
        let t = 0.7;
        let j = f.jet(t);
        assert!((j[0] - (1.0 + 0.3 * (2.0 * t + 0.4).sin())).abs() < 1e-15);
        for k in 0..3 {
            let d = fd(&f, k, t);
            assert!(
                (j[k + 1] - d).abs() < 1e-8,
                "derivative {}: {} vs {d}",
                k + 1,
                j[k + 1]
            );
        }
        assert!(!f.is_const());
    }
}
