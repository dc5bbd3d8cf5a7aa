//! Numbers in messages, readable: at most [`DIGITS`] significant digits,
//! with an exponent when the number is very large or very small
//! (`1e-300`, not three hundred digits).

/// Significant digits shown.
pub const DIGITS: usize = 6;

/// `v` with at most [`DIGITS`] significant digits and no trailing zeros:
/// `0.25`, `1234.57`, `1e-300`, `-3.5e+12`, `NaN`, `inf`.
pub fn num(v: f64) -> String {
    if !v.is_finite() {
        return if v.is_nan() {
            "NaN".into()
        } else if v > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        };
    }
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if (1e-4..1e6).contains(&a) {
        // Fixed notation: enough decimals for DIGITS significant digits.
        let mag = a.log10().floor() as i32;
        let decimals = (DIGITS as i32 - 1 - mag).max(0) as usize;
        let s = format!("{v:.decimals$}");
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
        // Rounding can carry into a new digit (999999.5 → 1000000).
        if s.parse::<f64>().is_ok_and(|r| r.abs() < 1e6) {
            return s;
        }
    }
    let s = format!("{v:.prec$e}", prec = DIGITS - 1);
    let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
    let mantissa = if mantissa.contains('.') {
        mantissa.trim_end_matches('0').trim_end_matches('.')
    } else {
        mantissa
    };
    let exp: i32 = exp.parse().unwrap_or(0);
    if exp > 0 {
        format!("{mantissa}e+{exp}")
    } else {
        format!("{mantissa}e{exp}")
    }
}

/// A count that may be too large for any integer type: the whole number
/// `n` up to 1e15, else in exponent form.
pub fn count(n: f64) -> String {
    if n.is_finite() && n.abs() < 1e15 {
        format!("{}", n.round() as i64)
    } else {
        num(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn readable_numbers() {
        assert_eq!(num(0.25), "0.25");
        assert_eq!(num(1e-300), "1e-300");
        assert_eq!(num(1234.5678), "1234.57");
        assert_eq!(num(-3.5e12), "-3.5e+12");
        assert_eq!(num(0.1 + 0.2), "0.3");
        assert_eq!(num(999999.7), "1e+6");
        assert_eq!(num(2.0), "2");
        assert_eq!(num(-5.0), "-5");
        assert_eq!(num(f64::NAN), "NaN");
        assert_eq!(num(0.00012345678), "0.000123457");
        assert_eq!(count(1e300), "1e+300");
        assert_eq!(count(12.0), "12");
    }
}
