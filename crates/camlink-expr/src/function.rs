//! The built-in functions: names, parameters and the instruction each compiles to.

use crate::motion::Law;
use crate::vm::Op;

/// How a call compiles.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Emit {
    /// One instruction taking all arguments.
    Op(Op),
    /// `deg(x)` = x·π/180.
    Deg,
    /// `min`/`max` of two or more arguments, folded pairwise left to right.
    Fold(Op),
    /// A motion law `law(x, x0, h0, x1, h1)`.
    Motion(Law),
}

/// A built-in function.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Builtin {
    pub name: &'static str,
    /// Parameter names as written in error messages, e.g. `"y, x"`.
    pub params: &'static str,
    /// Number of arguments (the minimum for `Emit::Fold`).
    pub arity: usize,
    pub emit: Emit,
}

const fn f(name: &'static str, params: &'static str, arity: usize, emit: Emit) -> Builtin {
    Builtin {
        name,
        params,
        arity,
        emit,
    }
}

const LAW: &str = "x, x0, h0, x1, h1";

/// Every built-in function, in the order of the crate documentation.
pub(crate) const BUILTINS: &[Builtin] = &[
    f("sin", "x", 1, Emit::Op(Op::Sin)),
    f("cos", "x", 1, Emit::Op(Op::Cos)),
    f("tan", "x", 1, Emit::Op(Op::Tan)),
    f("asin", "x", 1, Emit::Op(Op::Asin)),
    f("acos", "x", 1, Emit::Op(Op::Acos)),
    f("atan", "x", 1, Emit::Op(Op::Atan)),
    f("atan2", "y, x", 2, Emit::Op(Op::Atan2)),
    f("sinh", "x", 1, Emit::Op(Op::Sinh)),
    f("cosh", "x", 1, Emit::Op(Op::Cosh)),
    f("tanh", "x", 1, Emit::Op(Op::Tanh)),
    f("exp", "x", 1, Emit::Op(Op::Exp)),
    f("log", "x", 1, Emit::Op(Op::Ln)),
    f("ln", "x", 1, Emit::Op(Op::Ln)),
    f("sqrt", "x", 1, Emit::Op(Op::Sqrt)),
    f("abs", "x", 1, Emit::Op(Op::Abs)),
    f("sign", "x", 1, Emit::Op(Op::Sign)),
    f("floor", "x", 1, Emit::Op(Op::Floor)),
    f("ceil", "x", 1, Emit::Op(Op::Ceil)),
    f("min", "a, b, ...", 2, Emit::Fold(Op::Min)),
    f("max", "a, b, ...", 2, Emit::Fold(Op::Max)),
    f("mod", "x, y", 2, Emit::Op(Op::Mod)),
    f("hypot", "x, y", 2, Emit::Op(Op::Hypot)),
    f("deg", "x", 1, Emit::Deg),
    f("step", LAW, 5, Emit::Motion(Law::Step)),
    f("step5", LAW, 5, Emit::Motion(Law::Poly345)),
    f("poly345", LAW, 5, Emit::Motion(Law::Poly345)),
    f("ramp", LAW, 5, Emit::Motion(Law::Ramp)),
    f("harmonic", LAW, 5, Emit::Motion(Law::Harmonic)),
    f("cycloidal", LAW, 5, Emit::Motion(Law::Cycloidal)),
    f(
        "impact",
        "x, xd, x1, k, e, cmax, d",
        7,
        Emit::Op(Op::Impact),
    ),
    f("coulomb", "v, fc, vs", 3, Emit::Op(Op::Coulomb)),
];

/// The built-in function called `name`.
pub(crate) fn lookup(name: &str) -> Option<&'static Builtin> {
    BUILTINS.iter().find(|b| b.name == name)
}

/// Every built-in function as (name, signature), e.g. `("atan2", "atan2(y, x)")`.
pub fn functions() -> impl Iterator<Item = (&'static str, String)> {
    BUILTINS
        .iter()
        .map(|b| (b.name, format!("{}({})", b.name, b.params)))
}
