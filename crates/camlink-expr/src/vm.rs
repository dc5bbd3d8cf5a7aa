//! The stack machine that evaluates compiled expressions.
//!
//! A program is a flat list of [`Op`]s in postfix order. Each op pops its
//! operands from the stack and pushes one result; jumps are relative and only
//! go forward, so every program terminates after at most `code.len()` steps.
//! The same loop runs over plain values (`f64`) and over jets ([`Jet`]), and
//! in a checked mode that stops at the first operation leaving its domain.

use crate::fmt_num::{apart, num};
use crate::jet::{floor_mod, sign, Jet};
use crate::jet4::Jet4;
use crate::motion::Law;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A comparison operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Cmp {
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
    Ne,
}

impl Cmp {
    #[inline]
    pub(crate) fn test(self, a: f64, b: f64) -> bool {
        match self {
            Cmp::Lt => a < b,
            Cmp::Le => a <= b,
            Cmp::Gt => a > b,
            Cmp::Ge => a >= b,
            Cmp::Eq => a == b,
            Cmp::Ne => a != b,
        }
    }

    /// The comparison with its operands swapped: `a < b` ⇔ `b > a`.
    pub(crate) fn flip(self) -> Cmp {
        match self {
            Cmp::Lt => Cmp::Gt,
            Cmp::Le => Cmp::Ge,
            Cmp::Gt => Cmp::Lt,
            Cmp::Ge => Cmp::Le,
            Cmp::Eq => Cmp::Eq,
            Cmp::Ne => Cmp::Ne,
        }
    }
}

/// One instruction. `C` suffixes carry a constant operand folded in at
/// compile time (`AddC(c)`: u + c; `RSubC(c)`: c − u; `RDivC(c)`: c / u).
/// Jump offsets count the ops skipped after the jump itself.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Op {
    Const(f64),
    Var,
    /// Pushes input k of a multi-input expression ([`Args::inputs`]).
    Input(u16),
    Add,
    Sub,
    Mul,
    Div,
    Pow,
    Neg,
    AddC(f64),
    MulC(f64),
    DivC(f64),
    RSubC(f64),
    RDivC(f64),
    PowC(f64),
    PowI(i32),
    Cmp(Cmp),
    CmpC(Cmp, f64),
    /// 1 when the operand is zero, else 0.
    Not,
    /// 0 when the operand is zero, else 1.
    Truth,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sinh,
    Cosh,
    Tanh,
    Exp,
    Ln,
    Sqrt,
    Abs,
    Sign,
    Floor,
    Ceil,
    Atan2,
    Hypot,
    Min,
    Max,
    Mod,
    Motion(Law),
    /// `impact(x, xd, x1, k, e, cmax, d)`, ADAMS IMPACT.
    Impact,
    /// `coulomb(v, fc, vs)`, a smooth Coulomb law.
    Coulomb,
    /// Pops the condition; skips when it is zero.
    JumpIfFalse(u32),
    Jump(u32),
    /// `and`: when the top is zero, replaces it by 0 and skips; else pops it.
    AndJump(u32),
    /// `or`: when the top is non-zero, replaces it by 1 and skips; else pops it.
    OrJump(u32),
}

impl Op {
    /// Net change of the stack height on the fall-through path.
    pub(crate) fn stack_effect(self) -> isize {
        match self {
            Op::Const(_) | Op::Var | Op::Input(_) => 1,
            Op::Add
            | Op::Sub
            | Op::Mul
            | Op::Div
            | Op::Pow
            | Op::Cmp(_)
            | Op::Atan2
            | Op::Hypot
            | Op::Min
            | Op::Max
            | Op::Mod
            | Op::JumpIfFalse(_)
            | Op::AndJump(_)
            | Op::OrJump(_) => -1,
            Op::Motion(_) => -4,
            Op::Impact => -6,
            Op::Coulomb => -2,
            _ => 0,
        }
    }

    /// How many operands the op reads from the top of the stack.
    pub(crate) fn arity(self) -> usize {
        match self {
            Op::Const(_) | Op::Var | Op::Input(_) | Op::Jump(_) => 0,
            Op::Motion(_) => 5,
            Op::Impact => 7,
            Op::Coulomb => 3,
            op if op.stack_effect() == -1
                && !matches!(op, Op::JumpIfFalse(_) | Op::AndJump(_) | Op::OrJump(_)) =>
            {
                2
            }
            _ => 1,
        }
    }

    fn is_jump(self) -> bool {
        matches!(
            self,
            Op::JumpIfFalse(_) | Op::Jump(_) | Op::AndJump(_) | Op::OrJump(_)
        )
    }
}

/// What the machine computes with: plain values or jets.
pub(crate) trait Value:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    fn constant(c: f64) -> Self;
    fn variable(x: f64) -> Self;
    fn value(self) -> f64;
    fn first_non_finite(self) -> Option<(usize, f64)>;
    fn add_c(self, c: f64) -> Self;
    fn mul_c(self, c: f64) -> Self;
    fn div_c(self, c: f64) -> Self;
    fn rsub_c(self, c: f64) -> Self;
    fn rdiv_c(self, c: f64) -> Self;
    fn pow(self, v: Self) -> Self;
    fn pow_c(self, c: f64) -> Self;
    fn pow_i(self, n: i32) -> Self;
    fn unary(self, op: Op) -> Self;
    fn atan2(self, x: Self) -> Self;
    fn hypot(self, v: Self) -> Self;
    fn modulo(self, v: Self) -> Self;
    fn motion(law: Law, a: [Self; 5]) -> Self;
}

impl Value for f64 {
    #[inline]
    fn constant(c: f64) -> f64 {
        c
    }
    #[inline]
    fn variable(x: f64) -> f64 {
        x
    }
    #[inline]
    fn value(self) -> f64 {
        self
    }
    fn first_non_finite(self) -> Option<(usize, f64)> {
        (!self.is_finite()).then_some((0, self))
    }
    #[inline]
    fn add_c(self, c: f64) -> f64 {
        self + c
    }
    #[inline]
    fn mul_c(self, c: f64) -> f64 {
        self * c
    }
    #[inline]
    fn div_c(self, c: f64) -> f64 {
        self / c
    }
    #[inline]
    fn rsub_c(self, c: f64) -> f64 {
        c - self
    }
    #[inline]
    fn rdiv_c(self, c: f64) -> f64 {
        c / self
    }
    #[inline]
    fn pow(self, v: f64) -> f64 {
        self.powf(v)
    }
    #[inline]
    fn pow_c(self, c: f64) -> f64 {
        self.powf(c)
    }
    #[inline]
    fn pow_i(self, n: i32) -> f64 {
        self.powi(n)
    }
    #[inline]
    fn unary(self, op: Op) -> f64 {
        match op {
            Op::Sin => self.sin(),
            Op::Cos => self.cos(),
            Op::Tan => self.tan(),
            Op::Asin => self.asin(),
            Op::Acos => self.acos(),
            Op::Atan => self.atan(),
            Op::Sinh => self.sinh(),
            Op::Cosh => self.cosh(),
            Op::Tanh => self.tanh(),
            Op::Exp => self.exp(),
            Op::Ln => self.ln(),
            Op::Sqrt => self.sqrt(),
            Op::Abs => self.abs(),
            Op::Sign => sign(self),
            Op::Floor => self.floor(),
            Op::Ceil => self.ceil(),
            _ => f64::NAN,
        }
    }
    #[inline]
    fn atan2(self, x: f64) -> f64 {
        self.atan2(x)
    }
    #[inline]
    fn hypot(self, v: f64) -> f64 {
        self.hypot(v)
    }
    #[inline]
    fn modulo(self, v: f64) -> f64 {
        floor_mod(self, v)
    }
    #[inline]
    fn motion(law: Law, [x, x0, h0, x1, h1]: [f64; 5]) -> f64 {
        law.value(x, x0, h0, x1, h1)
    }
}

/// Implements [`Value`] for a jet type by its inherent methods of the same
/// names; `$law` is the [`Law`] method for that order.
macro_rules! jet_value {
    ($jet:ident, $law:ident) => {
        impl Value for $jet {
            #[inline]
            fn constant(c: f64) -> $jet {
                $jet::constant(c)
            }
            #[inline]
            fn variable(x: f64) -> $jet {
                $jet::variable(x)
            }
            #[inline]
            fn value(self) -> f64 {
                self.0[0]
            }
            fn first_non_finite(self) -> Option<(usize, f64)> {
                $jet::first_non_finite(self)
            }
            #[inline]
            fn add_c(self, c: f64) -> $jet {
                $jet::add_c(self, c)
            }
            #[inline]
            fn mul_c(self, c: f64) -> $jet {
                $jet::mul_c(self, c)
            }
            #[inline]
            fn div_c(self, c: f64) -> $jet {
                $jet::div_c(self, c)
            }
            #[inline]
            fn rsub_c(self, c: f64) -> $jet {
                $jet::rsub_c(self, c)
            }
            #[inline]
            fn rdiv_c(self, c: f64) -> $jet {
                $jet::rdiv_c(self, c)
            }
            #[inline]
            fn pow(self, v: $jet) -> $jet {
                $jet::pow(self, v)
            }
            #[inline]
            fn pow_c(self, c: f64) -> $jet {
                $jet::pow_c(self, c)
            }
            #[inline]
            fn pow_i(self, n: i32) -> $jet {
                $jet::pow_i(self, n)
            }
            #[inline]
            fn unary(self, op: Op) -> $jet {
                match op {
                    Op::Sin => self.sin(),
                    Op::Cos => self.cos(),
                    Op::Tan => self.tan(),
                    Op::Asin => self.asin(),
                    Op::Acos => self.acos(),
                    Op::Atan => self.atan(),
                    Op::Sinh => self.sinh(),
                    Op::Cosh => self.cosh(),
                    Op::Tanh => self.tanh(),
                    Op::Exp => self.exp(),
                    Op::Ln => self.ln(),
                    Op::Sqrt => self.sqrt(),
                    Op::Abs => self.abs(),
                    Op::Sign => $jet::constant(sign(self.0[0])),
                    Op::Floor => $jet::constant(self.0[0].floor()),
                    Op::Ceil => $jet::constant(self.0[0].ceil()),
                    _ => $jet::constant(f64::NAN),
                }
            }
            #[inline]
            fn atan2(self, x: $jet) -> $jet {
                $jet::atan2(self, x)
            }
            #[inline]
            fn hypot(self, v: $jet) -> $jet {
                $jet::hypot(self, v)
            }
            #[inline]
            fn modulo(self, v: $jet) -> $jet {
                $jet::modulo(self, v)
            }
            #[inline]
            fn motion(law: Law, [x, x0, h0, x1, h1]: [$jet; 5]) -> $jet {
                law.$law(x, x0, h0, x1, h1)
            }
        }
    };
}

jet_value!(Jet, jet);
jet_value!(Jet4, jet4);

/// The truth of a condition: any value other than zero (NaN included).
#[inline]
pub(crate) fn truth(v: f64) -> bool {
    v != 0.0
}

#[inline]
fn boolean<V: Value>(b: bool) -> V {
    V::constant(if b { 1.0 } else { 0.0 })
}

/// Where and why checked evaluation stopped: the index of the op and a
/// description of the failure.
#[derive(Debug)]
pub(crate) struct Fault {
    pub pc: usize,
    pub what: String,
}

/// What a program reads: the variable x and, for a multi-input expression,
/// its inputs, of which the one at `active` (if any) is the variable of
/// the jet and the others are constants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Args<'a> {
    pub x: f64,
    pub inputs: &'a [f64],
    pub active: usize,
}

impl Args<'static> {
    /// A single-variable program at x.
    #[inline]
    pub(crate) fn at(x: f64) -> Args<'static> {
        Args {
            x,
            inputs: &[],
            active: usize::MAX,
        }
    }
}

/// Runs `code` with `args` on `stack`, which must hold at least the
/// program's maximum stack depth (see [`max_depth`]).
///
/// With `CHECK`, each op's operands are tested against its domain first and
/// its result for finiteness after; the first failure is returned. Without
/// it, domain errors flow on as NaN or infinity and `Err` is never returned.
#[inline]
pub(crate) fn run<V: Value, const CHECK: bool>(
    code: &[Op],
    args: Args,
    s: &mut [V],
) -> Result<V, Fault> {
    let x = args.x;
    let mut sp = 0usize;
    let mut pc = 0usize;
    while pc < code.len() {
        let op = code[pc];
        if CHECK {
            if let Some(what) = domain(op, &s[..sp], args) {
                return Err(Fault { pc, what });
            }
        }
        match op {
            Op::Const(c) => {
                s[sp] = V::constant(c);
                sp += 1;
            }
            Op::Var => {
                s[sp] = V::variable(x);
                sp += 1;
            }
            Op::Input(k) => {
                let k = k as usize;
                let u = args.inputs.get(k).copied().unwrap_or(f64::NAN);
                s[sp] = if k == args.active {
                    V::variable(u)
                } else {
                    V::constant(u)
                };
                sp += 1;
            }
            Op::Add => {
                sp -= 1;
                s[sp - 1] = s[sp - 1] + s[sp];
            }
            Op::Sub => {
                sp -= 1;
                s[sp - 1] = s[sp - 1] - s[sp];
            }
            Op::Mul => {
                sp -= 1;
                s[sp - 1] = s[sp - 1] * s[sp];
            }
            Op::Div => {
                sp -= 1;
                s[sp - 1] = s[sp - 1] / s[sp];
            }
            Op::Pow => {
                sp -= 1;
                s[sp - 1] = s[sp - 1].pow(s[sp]);
            }
            Op::Neg => s[sp - 1] = -s[sp - 1],
            Op::AddC(c) => s[sp - 1] = s[sp - 1].add_c(c),
            Op::MulC(c) => s[sp - 1] = s[sp - 1].mul_c(c),
            Op::DivC(c) => s[sp - 1] = s[sp - 1].div_c(c),
            Op::RSubC(c) => s[sp - 1] = s[sp - 1].rsub_c(c),
            Op::RDivC(c) => s[sp - 1] = s[sp - 1].rdiv_c(c),
            Op::PowC(c) => s[sp - 1] = s[sp - 1].pow_c(c),
            Op::PowI(n) => s[sp - 1] = s[sp - 1].pow_i(n),
            Op::Cmp(k) => {
                sp -= 1;
                s[sp - 1] = boolean(k.test(s[sp - 1].value(), s[sp].value()));
            }
            Op::CmpC(k, c) => s[sp - 1] = boolean(k.test(s[sp - 1].value(), c)),
            Op::Not => s[sp - 1] = boolean(!truth(s[sp - 1].value())),
            Op::Truth => s[sp - 1] = boolean(truth(s[sp - 1].value())),
            Op::Sin
            | Op::Cos
            | Op::Tan
            | Op::Asin
            | Op::Acos
            | Op::Atan
            | Op::Sinh
            | Op::Cosh
            | Op::Tanh
            | Op::Exp
            | Op::Ln
            | Op::Sqrt
            | Op::Abs
            | Op::Sign
            | Op::Floor
            | Op::Ceil => s[sp - 1] = s[sp - 1].unary(op),
            Op::Atan2 => {
                sp -= 1;
                s[sp - 1] = s[sp - 1].atan2(s[sp]);
            }
            Op::Hypot => {
                sp -= 1;
                s[sp - 1] = s[sp - 1].hypot(s[sp]);
            }
            Op::Min => {
                sp -= 1;
                if s[sp].value() < s[sp - 1].value() {
                    s[sp - 1] = s[sp];
                }
            }
            Op::Max => {
                sp -= 1;
                if s[sp].value() > s[sp - 1].value() {
                    s[sp - 1] = s[sp];
                }
            }
            Op::Mod => {
                sp -= 1;
                s[sp - 1] = s[sp - 1].modulo(s[sp]);
            }
            Op::Motion(law) => {
                sp -= 4;
                let a = [s[sp - 1], s[sp], s[sp + 1], s[sp + 2], s[sp + 3]];
                s[sp - 1] = V::motion(law, a);
            }
            Op::Impact => {
                sp -= 6;
                let a = [
                    s[sp - 1],
                    s[sp],
                    s[sp + 1],
                    s[sp + 2],
                    s[sp + 3],
                    s[sp + 4],
                    s[sp + 5],
                ];
                s[sp - 1] = impact(a);
            }
            Op::Coulomb => {
                sp -= 2;
                s[sp - 1] = coulomb(s[sp - 1], s[sp], s[sp + 1]);
            }
            Op::JumpIfFalse(off) => {
                sp -= 1;
                if !truth(s[sp].value()) {
                    pc += off as usize;
                }
            }
            Op::Jump(off) => pc += off as usize,
            Op::AndJump(off) => {
                if truth(s[sp - 1].value()) {
                    sp -= 1;
                } else {
                    s[sp - 1] = V::constant(0.0);
                    pc += off as usize;
                }
            }
            Op::OrJump(off) => {
                if truth(s[sp - 1].value()) {
                    s[sp - 1] = V::constant(1.0);
                    pc += off as usize;
                } else {
                    sp -= 1;
                }
            }
        }
        if CHECK && !op.is_jump() {
            if let Some((k, v)) = s[sp - 1].first_non_finite() {
                return Err(Fault {
                    pc,
                    what: non_finite(k, v),
                });
            }
        }
        pc += 1;
    }
    Ok(s[0])
}

/// ADAMS IMPACT: with penetration p = x1 − x > 0,
/// max(0, k pᵉ − STEP(x, x1 − d, cmax, x1, 0) ẋ), and 0 for x ≥ x1. The
/// damping rises from 0 at x = x1 to cmax at x = x1 − d, so the force is
/// continuous at first contact; the max keeps it from pulling.
#[inline]
fn impact<V: Value>([x, xd, x1, k, e, cmax, d]: [V; 7]) -> V {
    if x.value() >= x1.value() {
        return V::constant(0.0);
    }
    let p = x1 - x;
    let damping = V::motion(Law::Step, [x, x1 - d, cmax, x1, V::constant(0.0)]);
    let f = k * p.pow(e) - damping * xd;
    if f.value() > 0.0 {
        f
    } else {
        V::constant(0.0)
    }
}

/// A smooth Coulomb law fc·STEP(v, −vs, −1, vs, 1): fc·sign(v) for
/// |v| ≥ vs, a cubic through 0 between (C1).
#[inline]
pub(crate) fn coulomb<V: Value>(v: V, fc: V, vs: V) -> V {
    fc * V::motion(Law::Step, [v, -vs, V::constant(-1.0), vs, V::constant(1.0)])
}

fn non_finite(order: usize, v: f64) -> String {
    match order {
        0 => format!("result is not finite ({})", num(v)),
        1 => format!("first derivative is not finite ({})", num(v)),
        2 => format!("second derivative is not finite ({})", num(v)),
        _ => format!("third derivative is not finite ({})", num(v)),
    }
}

/// The domain failure of `op` on the operands at the top of `stack`, if any;
/// a number near a limit (1.0000000000000002 for asin) is written with the
/// digits that tell it from the limit.
fn domain<V: Value>(op: Op, stack: &[V], args: Args) -> Option<String> {
    let x = args.x;
    let n = stack.len();
    let top = || stack[n - 1].value();
    let pair = || (stack[n - 2].value(), stack[n - 1].value());
    let outside = |name: &str, u: f64| {
        (!(-1.0..=1.0).contains(&u))
            .then(|| format!("{name} of {}, outside [-1, 1]", apart(u, u.signum()).0))
    };
    let power = |u: f64, c: f64| {
        if u < 0.0 && c.fract() != 0.0 {
            Some(format!(
                "negative number ({}) raised to the non-integer power {}",
                num(u),
                apart(c, c.round()).0
            ))
        } else if u == 0.0 && c < 0.0 {
            Some(format!("zero raised to a negative power ({})", num(c)))
        } else {
            None
        }
    };
    match op {
        Op::Var if !x.is_finite() => Some(format!("the variable is not finite ({})", num(x))),
        Op::Input(k) => {
            let u = args.inputs.get(k as usize).copied().unwrap_or(f64::NAN);
            (!u.is_finite()).then(|| format!("input {k} is not finite ({})", num(u)))
        }
        Op::Div if pair().1 == 0.0 => Some("division by zero".into()),
        Op::DivC(0.0) => Some("division by zero".into()),
        Op::RDivC(_) if top() == 0.0 => Some("division by zero".into()),
        Op::Mod if pair().1 == 0.0 => Some("mod by zero".into()),
        Op::Ln if top() < 0.0 => Some(format!("log of a negative number ({})", num(top()))),
        Op::Ln if top() == 0.0 => Some("log of zero".into()),
        Op::Sqrt if top() < 0.0 => {
            Some(format!("square root of a negative number ({})", num(top())))
        }
        Op::Asin => outside("asin", top()),
        Op::Acos => outside("acos", top()),
        Op::Pow => {
            let (u, c) = pair();
            power(u, c)
        }
        Op::PowC(c) => power(top(), c),
        Op::PowI(k) if top() == 0.0 && k < 0 => {
            Some(format!("zero raised to a negative power ({k})"))
        }
        Op::Atan2 if pair() == (0.0, 0.0) => Some("atan2(0, 0) is undefined".into()),
        Op::Motion(_) => {
            let (x0, x1) = (stack[n - 4].value(), stack[n - 2].value());
            (x0 == x1).then(|| format!("motion law with x0 = x1 (= {})", num(x0)))
        }
        Op::Impact => {
            let (x, x1, e, d) = (
                stack[n - 7].value(),
                stack[n - 5].value(),
                stack[n - 3].value(),
                stack[n - 1].value(),
            );
            if d <= 0.0 {
                Some(format!(
                    "impact with a penetration depth d ≤ 0 ({})",
                    num(d)
                ))
            } else if e < 1.0 && x < x1 {
                Some(format!("impact with an exponent e < 1 ({})", num(e)))
            } else {
                None
            }
        }
        Op::Coulomb => {
            let vs = stack[n - 1].value();
            (vs <= 0.0).then(|| format!("coulomb with a transition speed vs ≤ 0 ({})", num(vs)))
        }
        _ => None,
    }
}

/// The maximum stack depth of a program, or `None` when the program is not
/// well formed (a stack underflow, a jump out of range, branches that leave
/// different heights, or a final height other than one).
pub(crate) fn max_depth(code: &[Op]) -> Option<usize> {
    let n = code.len();
    // Height recorded at each jump target.
    let mut at: Vec<Option<isize>> = vec![None; n + 1];
    let mut d: isize = 0;
    let mut max: isize = 0;
    // False right after an unconditional jump, until a jump target.
    let mut live = true;
    for (pc, &op) in code.iter().enumerate() {
        match (at[pc], live) {
            (Some(t), true) if t != d => return None,
            (Some(t), _) => d = t,
            (None, false) => return None,
            (None, true) => {}
        }
        live = true;
        if d < op.arity() as isize {
            return None;
        }
        let target = |off: u32| pc.checked_add(1 + off as usize).filter(|&t| t <= n);
        let mut record = |t: usize, h: isize| match at[t] {
            Some(prev) if prev != h => false,
            _ => {
                at[t] = Some(h);
                true
            }
        };
        match op {
            Op::JumpIfFalse(off) => {
                d -= 1;
                if !record(target(off)?, d) {
                    return None;
                }
            }
            Op::Jump(off) => {
                if !record(target(off)?, d) {
                    return None;
                }
                live = false;
            }
            Op::AndJump(off) | Op::OrJump(off) => {
                if !record(target(off)?, d) {
                    return None;
                }
                d -= 1;
            }
            _ => d += op.stack_effect(),
        }
        max = max.max(d);
    }
    match (at[n], live) {
        (Some(t), true) if t != d => return None,
        (Some(t), _) => d = t,
        (None, false) => return None,
        (None, true) => {}
    }
    (d == 1).then_some(max as usize)
}
