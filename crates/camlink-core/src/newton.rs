//! Newton's method: the stopping test at the rounding level.
//!
//! A correction Δx of a value x can be no smaller than the rounding of x
//! itself, about ε_mach |x|: asking for less makes Newton iterate on
//! rounding noise and fail. A value has converged when its last correction
//! is within the tolerance or within [`ULPS`] units of rounding of its
//! value, whichever is larger:
//!
//! |Δx| ≤ max(tol, ULPS · ε_mach · |x|).

/// Units of rounding (ε_mach |x|) a converged correction may keep.
pub const ULPS: f64 = 8.0;

/// The rounding level of a value `x`: ULPS · ε_mach · |x|.
#[inline]
pub fn rounding(x: f64) -> f64 {
    ULPS * f64::EPSILON * x.abs()
}

/// True when the correction `dx` of the value `x` is within `tol` or
/// within the rounding level of `x`, whichever is larger.
#[inline]
pub fn settled(dx: f64, x: f64, tol: f64) -> bool {
    dx.abs() <= tol.max(rounding(x))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_correction_below_tolerance_is_settled() {
        assert!(settled(1e-9, 0.0, 1e-8));
        assert!(!settled(1e-7, 0.0, 1e-8));
    }

    /// A coordinate of 1e3 m cannot be corrected by less than ~1e-13 m:
    /// with tol = 1e-15 a correction of 1e-13 is settled, one of 1e-11 not.
    #[test]
    fn a_correction_at_the_rounding_of_the_value_is_settled() {
        assert!(settled(1e-13, 1e3, 1e-15));
        assert!(!settled(1e-11, 1e3, 1e-15));
        assert!(!settled(1e-13, 1.0, 1e-15));
    }
}
