//! The rules of every run setting, checked in one place: a model file's
//! `[analysis]` keys, the command line's options and the Python API's
//! arguments all go through [`check`], so the same value gets the same
//! answer (and a message naming the setting) whichever way it came.

use crate::fmt_num::num;

/// What a setting's value must be.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    /// A finite number.
    Finite,
    /// A finite number ≥ 0.
    NonNegative,
    /// A finite number > 0.
    Positive,
    /// A finite number in [0, 1].
    UnitInterval,
    /// A whole number ≥ 1.
    Count,
    /// True or false (1 or 0 as a number).
    Flag,
}

/// Every run setting and its rule; units in the comments.
pub(crate) const RULES: &[(&str, Rule)] = &[
    ("t_end", Rule::NonNegative),       // s
    ("step", Rule::Positive),           // s
    ("time", Rule::Finite),             // s
    ("tol", Rule::Positive),            // m or rad (see the analysis)
    ("max_iter", Rule::Count),          // Newton iterations per step
    ("h", Rule::Positive),              // s
    ("rho_inf", Rule::UnitInterval),    // spectral radius at infinity
    ("projection_tol", Rule::Positive), // m or rad
    ("atol", Rule::NonNegative),        // m or rad
    ("rtol", Rule::NonNegative),        // relative
    ("h_min", Rule::Positive),          // s
    ("adaptive", Rule::Flag),           // error control on or off
    ("jerk", Rule::Flag),               // third derivatives on or off
];

/// The rule of setting `key`, if it is one.
pub fn rule(key: &str) -> Option<Rule> {
    RULES.iter().find(|(k, _)| *k == key).map(|(_, r)| *r)
}

/// Checks `value` against the rule of `key`; the error says what the
/// value must be, e.g. "max_iter must be a whole number of at least 1 (-5)".
pub fn check(key: &str, value: f64) -> Result<(), String> {
    let Some(rule) = rule(key) else {
        return Err(format!("unknown setting '{key}'"));
    };
    let ok = value.is_finite()
        && match rule {
            Rule::Finite => true,
            Rule::NonNegative => value >= 0.0,
            Rule::Positive => value > 0.0,
            Rule::UnitInterval => (0.0..=1.0).contains(&value),
            Rule::Count => value >= 1.0 && value.fract() == 0.0 && value <= u32::MAX as f64,
            Rule::Flag => value == 0.0 || value == 1.0,
        };
    if ok {
        return Ok(());
    }
    let must = match rule {
        Rule::Finite => "a finite number",
        Rule::NonNegative => "a finite number of at least 0",
        Rule::Positive => "a positive finite number",
        Rule::UnitInterval => "between 0 and 1",
        Rule::Count => "a whole number of at least 1",
        Rule::Flag => "true or false",
    };
    Err(format!("{key} must be {must} ({})", num(value)))
}

/// Checks the error-control tolerances together: both 0 lets no step pass.
pub fn check_error_control(atol: f64, rtol: f64) -> Result<(), String> {
    check("atol", atol)?;
    check("rtol", rtol)?;
    if atol == 0.0 && rtol == 0.0 {
        return Err("atol and rtol are both 0: no step would pass".into());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_rule_accepts_and_refuses() {
        assert!(check("tol", 1e-9).is_ok());
        for bad in [-1.0, 0.0, f64::NAN, f64::INFINITY] {
            let e = check("tol", bad).unwrap_err();
            assert!(e.starts_with("tol must be a positive finite number"), "{e}");
        }
        assert!(check("max_iter", 3.0).is_ok());
        for bad in [0.0, -5.0, 1.5, f64::NAN, 1e300] {
            assert!(check("max_iter", bad).is_err(), "{bad}");
        }
        assert_eq!(
            check("max_iter", -5.0).unwrap_err(),
            "max_iter must be a whole number of at least 1 (-5)"
        );
        assert!(check("rho_inf", 1.0).is_ok() && check("rho_inf", 1.01).is_err());
        assert!(check("t_end", 0.0).is_ok() && check("t_end", -1e-9).is_err());
        assert!(check("time", -3.0).is_ok() && check("time", f64::NAN).is_err());
        assert!(check("atol", 0.0).is_ok() && check("h_min", 0.0).is_err());
        assert!(check_error_control(0.0, 0.0).is_err());
        assert!(check("nope", 1.0).unwrap_err().contains("unknown setting"));
        assert!(check("jerk", 1.0).is_ok() && check("adaptive", 0.0).is_ok());
        assert_eq!(
            check("jerk", 2.0).unwrap_err(),
            "jerk must be true or false (2)"
        );
        assert_eq!(rule("adaptive"), Some(Rule::Flag));
    }
}
