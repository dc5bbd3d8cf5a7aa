//! Numbers in messages, readable: at most [`DIGITS`] significant digits,
//! with an exponent when the number is very large or very small
//! (`1e-300`, not three hundred digits). The project's one number
//! formatter: it lives in this, the lowest crate, so that expression errors
//! use it too; `camlink_core::fmt_num` is the same module.

/// Significant digits shown.
pub const DIGITS: usize = 6;

/// `v` with at most [`DIGITS`] significant digits and no trailing zeros:
/// `0.25`, `1234.57`, `1e-300`, `-3.5e+12`, `NaN`, `inf`.
pub fn num(v: f64) -> String {
    num_digits(v, DIGITS)
}

/// `a` and `b` as [`num`] writes them, with more significant digits (up to
/// 17, which tell any two doubles apart) when six would show two different
/// numbers alike: `1e-7` and `1.0000000000000001e-7`, not `1e-7` twice.
pub fn apart(a: f64, b: f64) -> (String, String) {
    let mut digits = DIGITS;
    loop {
        // Never more digits than the number's shortest exact form needs.
        let show = |v: f64| num_digits(v, digits.min(shortest_digits(v)));
        let (x, y) = (show(a), show(b));
        if x != y || a == b || digits >= 17 || a.is_nan() || b.is_nan() {
            return (x, y);
        }
        digits += 1;
    }
}

/// The significant digits of the shortest text that reads back as `v`
/// (`1e-7`: 1; `1.0000000000000001e-7`: 17).
fn shortest_digits(v: f64) -> usize {
    let s = format!("{:e}", v.abs());
    let mantissa = s.split('e').next().unwrap_or("");
    mantissa.chars().filter(char::is_ascii_digit).count().max(1)
}

/// `v` with at most `digits` significant digits, as [`num`] writes it
/// with [`DIGITS`]: in fixed notation from 1e-4 up to 10^`digits` (at most
/// 1e6), with an exponent outside (`num_digits(12345.6, 4)` is
/// `1.235e+4`).
pub fn num_digits(v: f64, digits: usize) -> String {
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
    // Fixed notation below 10^digits: no more digits than asked for.
    let fixed_below = 10f64.powi(digits.min(DIGITS) as i32);
    if (1e-4..fixed_below).contains(&a) {
        // Fixed notation: enough decimals for DIGITS significant digits.
        let mag = a.log10().floor() as i32;
        let decimals = (digits as i32 - 1 - mag).max(0) as usize;
        let s = format!("{v:.decimals$}");
        let s = if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        };
        // Rounding can carry into a new digit (999999.5 → 1000000).
        if s.parse::<f64>().is_ok_and(|r| r.abs() < fixed_below) {
            return s;
        }
    }
    let s = format!("{v:.prec$e}", prec = digits - 1);
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

    #[test]
    fn fewer_digits_never_show_more() {
        assert_eq!(num_digits(12345.6, 4), "1.235e+4");
        assert_eq!(num_digits(1234.56, 4), "1235");
        assert_eq!(num_digits(9999.7, 4), "1e+4");
        assert_eq!(num_digits(0.0123456, 3), "0.0123");
        assert_eq!(num_digits(123.456, 3), "123");
        // Six digits and more: as num.
        assert_eq!(num_digits(123456.7, 6), "123457");
        assert_eq!(num_digits(1234567.0, 7), "1.234567e+6");
    }

    /// Issue 27: times such as 1e-300 s and 1.0000000000000001e-7 s are
    /// written short, and two that differ are never shown alike.
    #[test]
    fn issue27_tiny_and_nearly_equal_times() {
        assert_eq!(num(1e-300), "1e-300");
        assert_eq!(num(1.0000000000000001e-7), "1e-7");
        assert_eq!(num(5e-324), "4.94066e-324");
        assert_eq!(
            apart(1.0000000000000001e-7, 1e-7),
            ("1.0000000000000001e-7".to_string(), "1e-7".to_string())
        );
        assert_eq!(apart(1e-300, 0.5), ("1e-300".into(), "0.5".into()));
        assert_eq!(apart(0.25, 0.25), ("0.25".into(), "0.25".into()));
        assert_eq!(apart(1.0, 1.0 + f64::EPSILON).1, "1.0000000000000002");
        assert_eq!(apart(f64::NAN, 1.0), ("NaN".into(), "1".into()));
    }
}
