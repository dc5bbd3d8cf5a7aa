//! No input panics: random token soup, random bytes, and random well-formed
//! expressions, all from a fixed-seed generator.

use camlink_expr::{eval_constant, Expr};
use std::collections::HashMap;

/// xorshift64*: a small deterministic generator.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len())]
    }
}

const POINTS: [f64; 10] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    2.0944,
    1e300,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NAN,
];

/// Everything a caller can do with an expression.
fn exercise(src: &str, rng: &mut Rng) {
    let p: HashMap<String, f64> = [("r".to_owned(), 0.5)].into();
    for r in [
        Expr::parse(src, "t"),
        Expr::parse_with(src, None, &p),
        Expr::parse_with(src, Some("a"), &p),
    ] {
        match r {
            Ok(e) => {
                let _ = e.is_constant();
                for x in POINTS {
                    let _ = e.eval(x);
                    let _ = e.jet(x);
                    let _ = e.check(x);
                }
            }
            Err(err) => {
                let _ = err.render(src);
                assert!(err.offset <= src.len(), "`{src}`: offset {}", err.offset);
            }
        }
    }
    let _ = eval_constant(src, &p);
    // Errors rendered against other text must not panic either.
    if let Err(err) = Expr::parse(src, "t") {
        let cut = rng.below(src.len() + 1);
        let _ = err.render(src.get(..cut).unwrap_or("x\ny"));
        let _ = err.render("");
    }
}

const SOUP: &[&str] = &[
    "t",
    "a",
    "r",
    "1",
    "0",
    ".5",
    "2.",
    "1e",
    "1e-3",
    "e",
    "E",
    "pi",
    "π",
    "α",
    "(",
    ")",
    ",",
    "+",
    "-",
    "*",
    "**",
    "/",
    "^",
    "<",
    "<=",
    ">",
    ">=",
    "==",
    "!=",
    "!",
    "&&",
    "||",
    "and",
    "or",
    "not",
    "if",
    "if(",
    "sin(",
    "atan2(",
    "step(",
    "min(",
    "mod(",
    "deg(",
    "cycloidal(",
    " ",
    "\n",
    "\t",
    "$",
    "=",
    "&",
    "|",
    ".",
    "..",
    "1e308",
    "1e999",
    "é",
    "日本",
    "🙂",
    "\u{0}",
    "\u{200b}",
    "'",
    "\"",
    "_",
    "t_1",
    "__",
    "9t",
    "0x1F",
];

#[test]
fn token_soup_never_panics() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for _ in 0..20_000 {
        let n = rng.below(24);
        let src: String = (0..n).map(|_| rng.pick(SOUP)).collect();
        exercise(&src, &mut rng);
    }
}

#[test]
fn random_bytes_never_panic() {
    let mut rng = Rng(12345);
    for _ in 0..5_000 {
        let n = rng.below(40);
        let bytes: Vec<u8> = (0..n).map(|_| (rng.next() >> 56) as u8).collect();
        let src = String::from_utf8_lossy(&bytes).into_owned();
        exercise(&src, &mut rng);
    }
}

/// A random well-formed expression in `t` of at most `depth` levels.
fn expression(rng: &mut Rng, depth: usize) -> String {
    if depth == 0 || rng.below(4) == 0 {
        return rng
            .pick(&["t", "t", "2", "0.5", "pi", "e", "0", "-1", "3.25"])
            .to_owned();
    }
    let mut sub = || expression(rng, depth - 1);
    let (a, b) = (sub(), sub());
    match rng.below(12) {
        0..=2 => {
            let op = rng.pick(&[
                "+", "-", "*", "/", "^", "**", "<", "<=", ">", ">=", "==", "!=", "and", "or", "&&",
                "||",
            ]);
            format!("({a} {op} {b})")
        }
        3 => format!("-{a}"),
        4 => format!("not ({a})"),
        5 => format!("if({a}, {b}, {})", expression(rng, depth - 1)),
        6 | 7 => {
            let f = rng.pick(&[
                "sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "exp", "log",
                "ln", "sqrt", "abs", "sign", "floor", "ceil", "deg",
            ]);
            format!("{f}({a})")
        }
        8 | 9 => {
            let f = rng.pick(&["atan2", "hypot", "mod", "min", "max"]);
            format!("{f}({a}, {b})")
        }
        _ => {
            let f = rng.pick(&["step", "step5", "poly345", "ramp", "harmonic", "cycloidal"]);
            let (c, d, e) = (
                expression(rng, depth - 1),
                expression(rng, depth - 1),
                expression(rng, depth - 1),
            );
            format!("{f}({a}, {b}, {c}, {d}, {e})")
        }
    }
}

/// Well-formed expressions parse; value-only evaluation agrees with the
/// jet's value bit for bit; a point that passes the check has a finite jet.
#[test]
fn random_expressions_are_consistent() {
    let mut rng = Rng(0xdead_beef);
    let mut checked_ok = 0;
    for _ in 0..4_000 {
        let depth = 1 + rng.below(6);
        let src = expression(&mut rng, depth);
        let e = Expr::parse(&src, "t").unwrap_or_else(|err| panic!("{}", err.render(&src)));
        for x in [-1.3, -0.2, 0.0, 0.7, 1.0, 2.5] {
            let (v, j) = (e.eval(x), e.jet(x));
            assert!(
                v.to_bits() == j[0].to_bits() || (v.is_nan() && j[0].is_nan()),
                "`{src}` at {x}: eval {v}, jet {}",
                j[0]
            );
            if e.check(x).is_ok() {
                checked_ok += 1;
                assert!(
                    j.iter().all(|v| v.is_finite()),
                    "`{src}` at {x} passed the check with {j:?}"
                );
            }
        }
    }
    assert!(
        checked_ok > 5_000,
        "the generator makes too few healthy points ({checked_ok})"
    );
}
