//! Parse errors: messages, spans and their rendering with carets.

use camlink_expr::{eval_constant, Expr, ParseError, MAX_LEN, MAX_NESTING};
use std::collections::HashMap;

/// The rendered error of `src` in the variable `t`.
fn rendered(src: &str) -> String {
    match Expr::parse(src, "t") {
        Ok(_) => panic!("`{src}` parsed"),
        Err(e) => e.render(src),
    }
}

fn error(src: &str) -> ParseError {
    Expr::parse(src, "t")
        .err()
        .unwrap_or_else(|| panic!("`{src}` parsed"))
}

#[test]
fn unknown_names_suggest_the_variable_and_constants() {
    assert_eq!(
        rendered("tt + 1"),
        "tt + 1\n^^\nunknown name 'tt'; the variable here is 't'"
    );
    assert_eq!(
        rendered("2*pj"),
        "2*pj\n  ^^\nunknown name 'pj'; did you mean 'pi'? (the variable here is 't')"
    );
    assert_eq!(
        rendered("foo"),
        "foo\n^^^\nunknown name 'foo'; the variable here is 't'"
    );
    let p: HashMap<String, f64> = [("radius".to_owned(), 1.0)].into();
    let e = Expr::parse_with("2*raduis", None, &p).unwrap_err();
    assert_eq!(e.message, "unknown name 'raduis'; did you mean 'radius'?");
    assert_eq!((e.offset, e.len), (2, 6));
    assert_eq!(
        eval_constant("x + 1", &HashMap::new()).unwrap_err().message,
        "unknown name 'x'"
    );
}

#[test]
fn unknown_functions_suggest_a_builtin() {
    assert_eq!(
        rendered("1 + coss(t)"),
        "1 + coss(t)\n    ^^^^\nunknown function 'coss'; did you mean 'cos'?"
    );
    assert_eq!(
        rendered("frob(t)"),
        "frob(t)\n^^^^\nunknown function 'frob'"
    );
    assert_eq!(
        rendered("t(1 + t)"),
        "t(1 + t)\n^\n't' is not a function; write 't*(...)' to multiply"
    );
    assert_eq!(
        rendered("sin + 1"),
        "sin + 1\n^^^\n'sin' is a function; call it as sin(...)"
    );
}

#[test]
fn wrong_argument_counts_point_at_the_call() {
    assert_eq!(
        rendered("1 + sin(t, 2)"),
        "1 + sin(t, 2)\n    ^^^^^^^^^\nsin takes 1 argument (sin(x)), found 2"
    );
    assert_eq!(
        rendered("atan2(t)"),
        "atan2(t)\n^^^^^^^^\natan2 takes 2 arguments (atan2(y, x)), found 1"
    );
    assert_eq!(
        rendered("step(t, 0, 1)"),
        "step(t, 0, 1)\n^^^^^^^^^^^^^\nstep takes 5 arguments (step(x, x0, h0, x1, h1)), found 3"
    );
    assert_eq!(
        rendered("min(t)"),
        "min(t)\n^^^^^^\nmin takes 2 or more arguments (min(a, b, ...)), found 1"
    );
    assert_eq!(
        error("exp()").message,
        "exp takes 1 argument (exp(x)), found 0"
    );
    assert_eq!(
        rendered("if(t, 1)"),
        "if(t, 1)\n       ^\nif takes 3 arguments: if(condition, then, else); found ')'"
    );
    assert_eq!(
        error("if(t, 1, 2, 3)").message,
        "if takes 3 arguments: if(condition, then, else); found ','"
    );
    assert_eq!(
        rendered("if + 1"),
        "if + 1\n^^\n'if' needs arguments: if(condition, then, else)"
    );
}

#[test]
fn trailing_garbage_and_missing_operators() {
    assert_eq!(
        rendered("2 pi"),
        "2 pi\n  ^^\nmissing operator before name 'pi'; write '*' to multiply"
    );
    assert_eq!(
        rendered("2(t + 1)"),
        "2(t + 1)\n ^\nmissing operator before '('; write '*' to multiply"
    );
    assert_eq!(rendered("1 + 2)"), "1 + 2)\n     ^\nunmatched ')'");
    assert_eq!(
        rendered("1, 2"),
        "1, 2\n ^\n',' outside of a function's arguments"
    );
    assert_eq!(
        rendered("(t 2)"),
        "(t 2)\n   ^\nmissing operator before number 2; write '*' to multiply"
    );
    assert_eq!(
        rendered("sin(t t)"),
        "sin(t t)\n      ^\nmissing operator before name 't'; write '*' to multiply"
    );
}

#[test]
fn incomplete_and_malformed_input() {
    assert_eq!(rendered(""), "\n^\nempty expression");
    assert_eq!(rendered("   "), "   \n^^^\nempty expression");
    assert_eq!(
        rendered("1 +"),
        "1 +\n   ^\nexpected a value, found the end of the expression"
    );
    assert_eq!(
        rendered("1 + * 2"),
        "1 + * 2\n    ^\nexpected a value, found '*'"
    );
    assert_eq!(rendered("(1 + 2"), "(1 + 2\n^\nunclosed '('");
    assert_eq!(rendered("sin(t"), "sin(t\n^^^\nunclosed '(' of sin(...)");
    assert_eq!(
        rendered("t = 1"),
        "t = 1\n  ^\n'=' is not an operator here; write '==' to compare"
    );
    assert_eq!(rendered("t $ 1"), "t $ 1\n  ^\nunexpected character '$'");
    assert_eq!(
        rendered("0 < t < 1"),
        "0 < t < 1\n      ^\ncomparisons cannot be chained; write (a < b) and (b < c)"
    );
    assert_eq!(
        rendered("1 and"),
        "1 and\n     ^\nexpected a value, found the end of the expression"
    );
    assert_eq!(
        rendered("and 1"),
        "and 1\n^^^\nexpected a value, found 'and'"
    );
    assert_eq!(
        rendered("1e999"),
        "1e999\n^^^^^\nnumber '1e999' is too large"
    );
}

#[test]
fn multiline_sources_name_the_line() {
    assert_eq!(
        rendered("1 +\n  cos(t) +\n  tt"),
        "  tt\n  ^^\nline 3: unknown name 'tt'; the variable here is 't'"
    );
}

#[test]
fn nesting_and_length_limits() {
    let deep = format!(
        "{}t{}",
        "(".repeat(MAX_NESTING + 1),
        ")".repeat(MAX_NESTING + 1)
    );
    let e = error(&deep);
    assert_eq!(e.message, "expression nested too deeply (over 100 levels)");
    assert_eq!((e.offset, e.len), (MAX_NESTING, 1));
    // Just inside the limit parses.
    let ok = format!(
        "{}t{}",
        "(".repeat(MAX_NESTING - 1),
        ")".repeat(MAX_NESTING - 1)
    );
    assert_eq!(Expr::parse(&ok, "t").unwrap().eval(2.0), 2.0);
    // Far beyond it fails cleanly rather than overflowing the stack.
    assert!(error(&"-".repeat(50_000))
        .message
        .starts_with("expression nested too deeply"));
    assert!(error(&"sin(".repeat(20_000))
        .message
        .starts_with("expression nested too deeply"));
    assert!(error(&"2^".repeat(40_000))
        .message
        .starts_with("expression nested too deeply"));

    let long = "1+".repeat(MAX_LEN / 2) + "1";
    let e = error(&long);
    assert_eq!(
        e.message,
        format!(
            "expression too long ({} bytes; the limit is {MAX_LEN})",
            MAX_LEN + 1
        )
    );
    assert_eq!((e.offset, e.len), (MAX_LEN, 1));
    // The offset stays on a character boundary.
    let wide = "1".repeat(MAX_LEN - 1) + "ααα";
    let e = error(&wide);
    assert_eq!((e.offset, e.len), (MAX_LEN - 1, 6));
    assert!(wide.is_char_boundary(e.offset));
}

#[test]
fn parameters_clash_with_the_variable_or_are_not_finite() {
    let p: HashMap<String, f64> = [("t".to_owned(), 1.0), ("bad".to_owned(), f64::NAN)].into();
    let e = Expr::parse_with("2*t", Some("t"), &p).unwrap_err();
    assert_eq!(e.message, "'t' is both the variable and a parameter");
    assert_eq!((e.offset, e.len), (2, 1));
    let e = Expr::parse_with("bad + 1", None, &p).unwrap_err();
    assert_eq!(e.message, "parameter 'bad' is not finite (NaN)");
}

#[test]
fn errors_display_their_message() {
    let e = error("tt");
    assert_eq!(e.to_string(), "unknown name 'tt'; the variable here is 't'");
}
