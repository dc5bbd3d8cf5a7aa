//! MATLAB-syntax functions of time, as simEngine2D's `fun` fields hold them,
//! translated to camlink's expression language.
//!
//! The source is tokenised and parsed here (a Pratt parser over MATLAB's
//! precedence: `^` and `.^` left-associative and tighter than unary minus,
//! then `* / .* ./`, then `+ -`), and printed back in camlink's syntax with
//! the parentheses that keep MATLAB's grouping. Nothing is evaluated: the
//! result is text for camlink-expr, which never runs user code either.
//! Accepted names are the variable `t`, `pi` and the functions of
//! [`FUNCTIONS`]; anything else is an error that names it.

/// MATLAB functions accepted, with their camlink spelling.
const FUNCTIONS: &[(&str, &str)] = &[
    ("sin", "sin"),
    ("cos", "cos"),
    ("tan", "tan"),
    ("asin", "asin"),
    ("acos", "acos"),
    ("atan", "atan"),
    ("atan2", "atan2"),
    ("sinh", "sinh"),
    ("cosh", "cosh"),
    ("tanh", "tanh"),
    ("exp", "exp"),
    ("log", "log"),
    ("sqrt", "sqrt"),
    ("abs", "abs"),
    ("sign", "sign"),
    ("floor", "floor"),
    ("ceil", "ceil"),
    ("min", "min"),
    ("max", "max"),
    ("mod", "mod"),
    ("hypot", "hypot"),
    ("deg2rad", "deg"),
];

/// A translated function: camlink expression text, and whether it uses `t`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Translated {
    pub text: String,
    pub uses_t: bool,
}

/// Translates MATLAB text to a camlink expression of `t`.
///
/// `allow_t = false` refuses `t` (a number position).
pub(crate) fn translate(src: &str, allow_t: bool) -> Result<Translated, String> {
    let tokens = lex(src)?;
    let mut p = Parser {
        tokens,
        pos: 0,
        depth: 0,
        allow_t,
        uses_t: false,
    };
    let node = p.expr(0)?;
    if let Some(tok) = p.tokens.get(p.pos) {
        return Err(format!("unexpected '{}' in \"{src}\"", tok.kind.text()));
    }
    let mut text = String::new();
    print(&node, &mut text);
    Ok(Translated {
        text,
        uses_t: p.uses_t,
    })
}

#[derive(Clone, Debug, PartialEq)]
enum Kind {
    Num(String),
    Name(String),
    Op(char),
    LParen,
    RParen,
    Comma,
}

impl Kind {
    fn text(&self) -> String {
        match self {
            Kind::Num(s) | Kind::Name(s) => s.clone(),
            Kind::Op(c) => c.to_string(),
            Kind::LParen => "(".into(),
            Kind::RParen => ")".into(),
            Kind::Comma => ",".into(),
        }
    }
}

#[derive(Clone, Debug)]
struct Token {
    kind: Kind,
}

fn lex(src: &str) -> Result<Vec<Token>, String> {
    let chars: Vec<char> = src.chars().collect();
    let mut out = Vec::new();
    let mut k = 0;
    while k < chars.len() {
        let c = chars[k];
        if c.is_whitespace() {
            k += 1;
            continue;
        }
        let digit_at = |j: usize| chars.get(j).is_some_and(|c| c.is_ascii_digit());
        if c.is_ascii_digit() || (c == '.' && digit_at(k + 1)) {
            let start = k;
            while digit_at(k) {
                k += 1;
            }
            // A '.' followed by an operator is MATLAB's element-wise operator, not a decimal point.
            if chars.get(k) == Some(&'.') && !matches!(chars.get(k + 1), Some('*' | '/' | '^')) {
                k += 1;
                while digit_at(k) {
                    k += 1;
                }
            }
            if matches!(chars.get(k), Some('e' | 'E'))
                && (digit_at(k + 1)
                    || (matches!(chars.get(k + 1), Some('+' | '-')) && digit_at(k + 2)))
            {
                k += 2;
                while digit_at(k) {
                    k += 1;
                }
            }
            let mut text: String = chars[start..k].iter().collect();
            if text.starts_with('.') {
                text.insert(0, '0');
            }
            if text.ends_with('.') {
                text.push('0');
            }
            if chars.get(k).is_some_and(|c| c.is_ascii_alphabetic()) {
                return Err(format!(
                    "unsupported number '{}{}' in \"{src}\" (imaginary and suffixed numbers are not accepted)",
                    text, chars[k]
                ));
            }
            out.push(Token {
                kind: Kind::Num(text),
            });
            continue;
        }
        if c.is_ascii_alphabetic() {
            let start = k;
            while chars
                .get(k)
                .is_some_and(|c| c.is_ascii_alphanumeric() || *c == '_')
            {
                k += 1;
            }
            out.push(Token {
                kind: Kind::Name(chars[start..k].iter().collect()),
            });
            continue;
        }
        let kind = match c {
            '.' if matches!(chars.get(k + 1), Some('*' | '/' | '^')) => {
                k += 1;
                Kind::Op(chars[k])
            }
            '+' | '-' | '*' | '/' | '^' => Kind::Op(c),
            '(' => Kind::LParen,
            ')' => Kind::RParen,
            ',' => Kind::Comma,
            _ => {
                return Err(format!(
                    "unsupported character '{c}' in \"{src}\"; a function of t may use numbers, t, pi, + - * / ^ (and .* ./ .^), parentheses and {}",
                    function_list()
                ))
            }
        };
        k += 1;
        out.push(Token { kind });
    }
    if out.is_empty() {
        return Err("empty function".to_string());
    }
    if out.len() > MAX_TOKENS {
        return Err(format!(
            "the expression is too long ({} tokens; at most {MAX_TOKENS})",
            out.len()
        ));
    }
    Ok(out)
}

fn function_list() -> String {
    FUNCTIONS
        .iter()
        .map(|(m, _)| *m)
        .collect::<Vec<_>>()
        .join(", ")
}

#[derive(Clone, Debug)]
enum Node {
    Num(String),
    Var(String),
    Neg(Box<Node>),
    Bin(char, Box<Node>, Box<Node>),
    Call(&'static str, Vec<Node>),
}

/// Most tokens in one expression (course functions are a line long); this
/// also bounds the depth of the tree that is printed.
const MAX_TOKENS: usize = 2000;

/// Deepest nesting of parentheses, calls and signs accepted.
const MAX_DEPTH: usize = 64;

struct Parser {
    tokens: Vec<Token>,
    pos: usize,
    depth: usize,
    allow_t: bool,
    uses_t: bool,
}

/// Binding powers: `+ -` 1, `* /` 2, unary minus 3, `^` 4.
fn infix_power(op: char) -> Option<u8> {
    match op {
        '+' | '-' => Some(1),
        '*' | '/' => Some(2),
        '^' => Some(4),
        _ => None,
    }
}

impl Parser {
    fn peek(&self) -> Option<&Kind> {
        self.tokens.get(self.pos).map(|t| &t.kind)
    }

    fn next(&mut self) -> Option<Kind> {
        let t = self.tokens.get(self.pos).map(|t| t.kind.clone());
        self.pos += 1;
        t
    }

    /// Parses operators binding tighter than `min` (all operators are left-associative).
    fn expr(&mut self, min: u8) -> Result<Node, String> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(format!(
                "the expression nests deeper than {MAX_DEPTH} levels"
            ));
        }
        let e = self.binary(min);
        self.depth -= 1;
        e
    }

    fn binary(&mut self, min: u8) -> Result<Node, String> {
        let mut lhs = self.prefix()?;
        while let Some(Kind::Op(op)) = self.peek() {
            let op = *op;
            let Some(power) = infix_power(op) else { break };
            if power <= min {
                break;
            }
            self.pos += 1;
            let rhs = if op == '^' {
                // MATLAB allows a signed exponent: 2^-t is 2^(-t).
                self.power_operand()?
            } else {
                self.expr(power)?
            };
            lhs = Node::Bin(op, Box::new(lhs), Box::new(rhs));
        }
        Ok(lhs)
    }

    fn power_operand(&mut self) -> Result<Node, String> {
        match self.peek() {
            Some(Kind::Op('-' | '+')) => {
                let minus = self.peek() == Some(&Kind::Op('-'));
                self.pos += 1;
                self.depth += 1;
                if self.depth > MAX_DEPTH {
                    return Err(format!(
                        "the expression nests deeper than {MAX_DEPTH} levels"
                    ));
                }
                let x = self.power_operand();
                self.depth -= 1;
                let x = x?;
                Ok(if minus { Node::Neg(Box::new(x)) } else { x })
            }
            _ => self.atom(),
        }
    }

    fn prefix(&mut self) -> Result<Node, String> {
        match self.peek() {
            Some(Kind::Op('-')) => {
                self.pos += 1;
                Ok(Node::Neg(Box::new(self.expr(3)?)))
            }
            Some(Kind::Op('+')) => {
                self.pos += 1;
                self.expr(3)
            }
            _ => self.atom(),
        }
    }

    fn atom(&mut self) -> Result<Node, String> {
        match self.next() {
            Some(Kind::Num(s)) => Ok(Node::Num(s)),
            Some(Kind::LParen) => {
                let e = self.expr(0)?;
                match self.next() {
                    Some(Kind::RParen) => Ok(e),
                    _ => Err("missing ')'".to_string()),
                }
            }
            Some(Kind::Name(name)) => {
                if self.peek() == Some(&Kind::LParen) {
                    let Some(&(_, f)) = FUNCTIONS.iter().find(|(m, _)| *m == name) else {
                        return Err(format!(
                            "unknown function '{name}'; the functions accepted are {}",
                            function_list()
                        ));
                    };
                    self.pos += 1;
                    let mut args = vec![self.expr(0)?];
                    loop {
                        match self.next() {
                            Some(Kind::Comma) => args.push(self.expr(0)?),
                            Some(Kind::RParen) => break,
                            _ => return Err(format!("missing ')' after the arguments of {name}")),
                        }
                    }
                    return Ok(Node::Call(f, args));
                }
                match name.as_str() {
                    "t" if self.allow_t => {
                        self.uses_t = true;
                        Ok(Node::Var(name))
                    }
                    "t" => Err("'t' is not allowed here: a constant number is expected".into()),
                    "pi" => Ok(Node::Var(name)),
                    _ => Err(format!(
                        "unknown name '{name}'; {} pi and functions ({})",
                        if self.allow_t {
                            "a function may use t,"
                        } else {
                            "a number may use"
                        },
                        function_list()
                    )),
                }
            }
            Some(other) => Err(format!("unexpected '{}'", other.text())),
            None => Err("the expression ends too early".to_string()),
        }
    }
}

/// The binding power of the node's outermost operator (5 for atoms).
fn level(n: &Node) -> u8 {
    match n {
        Node::Num(_) | Node::Var(_) | Node::Call(..) => 5,
        Node::Neg(_) => 3,
        Node::Bin(op, ..) => infix_power(*op).unwrap_or(5),
    }
}

fn print_child(n: &Node, min: u8, out: &mut String) {
    if level(n) < min {
        out.push('(');
        print(n, out);
        out.push(')');
    } else {
        print(n, out);
    }
}

/// camlink text with parentheses wherever camlink's grammar would group
/// differently (its `^` is right-associative and its unary minus binds
/// looser than `*`).
fn print(n: &Node, out: &mut String) {
    match n {
        Node::Num(s) | Node::Var(s) => out.push_str(s),
        Node::Neg(x) => {
            out.push('-');
            print_child(x, 4, out);
        }
        Node::Bin(op, a, b) => {
            let p = infix_power(*op).unwrap_or(5);
            // `^`: both operands atoms; others: left at the same level, right tighter.
            let (left_min, right_min) = if *op == '^' { (5, 5) } else { (p, p + 1) };
            print_child(a, left_min, out);
            if *op == '+' || *op == '-' {
                out.push(' ');
                out.push(*op);
                out.push(' ');
            } else {
                out.push(*op);
            }
            print_child(b, right_min, out);
        }
        Node::Call(f, args) => {
            out.push_str(f);
            out.push('(');
            for (k, a) in args.iter().enumerate() {
                if k > 0 {
                    out.push_str(", ");
                }
                print(a, out);
            }
            out.push(')');
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tr(s: &str) -> String {
        translate(s, true).unwrap().text
    }

    fn value(s: &str, t: f64) -> f64 {
        let e = camlink_expr::Expr::parse(&tr(s), "t").unwrap();
        e.eval(t)
    }

    #[test]
    fn course_functions() {
        assert_eq!(tr("t^2"), "t^2");
        assert_eq!(tr("pi/2 + 2*pi*t"), "pi/2 + 2*pi*t");
        assert_eq!(tr("sin(10*t)"), "sin(10*t)");
        assert_eq!(tr("t.^2 .* 3 ./ 4"), "t^2*3/4");
    }

    #[test]
    fn matlab_grouping_is_kept() {
        // MATLAB: ^ is left-associative, so 2^3^2 = 64.
        assert_eq!(value("2^3^2", 0.0), 64.0);
        // -t^2 = -(t^2); 2^-t = 2^(-t); a - b - c = (a - b) - c; a/b/c = (a/b)/c.
        assert_eq!(value("-t^2", 3.0), -9.0);
        assert_eq!(value("2^-t", 2.0), 0.25);
        assert_eq!(value("1 - t - 1", 3.0), -3.0);
        assert_eq!(value("8/t/2", 2.0), 2.0);
        assert_eq!(value("2*-t", 3.0), -6.0);
        assert_eq!(value("-(t+1)*2", 1.0), -4.0);
        assert_eq!(value("(-2)^2", 0.0), 4.0);
        assert_eq!(value("-2^2", 0.0), -4.0);
        assert_eq!(value(".5*t + 2.*t", 2.0), 5.0);
        assert_eq!(value("1e-1*t", 2.0), 0.2);
        assert_eq!(value("deg2rad(180)", 0.0), std::f64::consts::PI);
    }

    #[test]
    fn t_is_detected() {
        assert!(translate("sin(t)", true).unwrap().uses_t);
        assert!(!translate("pi/2", true).unwrap().uses_t);
    }

    #[test]
    fn errors_name_the_fault() {
        assert!(translate("foo(t)", true)
            .unwrap_err()
            .contains("unknown function 'foo'"));
        assert!(translate("x*t", true)
            .unwrap_err()
            .contains("unknown name 'x'"));
        assert!(translate("t'", true)
            .unwrap_err()
            .contains("unsupported character"));
        assert!(translate("t", false).unwrap_err().contains("not allowed"));
        assert!(translate("2i", true).unwrap_err().contains("imaginary"));
        assert!(translate("(t", true).unwrap_err().contains("missing ')'"));
        assert!(translate("t t", true)
            .unwrap_err()
            .contains("unexpected 't'"));
        assert!(translate("", true).is_err());
        let deep = format!("{}t{}", "(".repeat(500), ")".repeat(500));
        assert!(translate(&deep, true).unwrap_err().contains("nests deeper"));
        let signs = format!("2^{}t", "-".repeat(1000));
        assert!(translate(&signs, true)
            .unwrap_err()
            .contains("nests deeper"));
        let long = vec!["t"; 100_000].join("+");
        assert!(translate(&long, true).unwrap_err().contains("too long"));
        let minus = format!("{}t", "-".repeat(1000));
        assert!(translate(&minus, true)
            .unwrap_err()
            .contains("nests deeper"));
    }
}
