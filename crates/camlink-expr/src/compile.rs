//! Code generation: the parser emits postfix code through a [`Builder`],
//! which folds constant sub-expressions and fuses constant operands into
//! their instruction as it goes.

use crate::vm::{max_depth, run, truth, Args, Op};

/// A byte range `start..end` of the source.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Span {
    pub start: usize,
    pub end: usize,
}

impl Span {
    pub(crate) fn new(start: usize, end: usize) -> Span {
        Span { start, end }
    }
}

/// What the code of a sub-expression is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Kind {
    /// Depends on the variable.
    Var,
    /// Exactly one `Op::Const` with this value.
    Const(f64),
    /// Independent of the variable but left unfolded because it does not
    /// evaluate to a finite number; checked evaluation reports it.
    Fixed,
}

/// The code of one sub-expression: `code[start..]` at the time it was built.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sub {
    pub start: usize,
    pub kind: Kind,
    pub span: Span,
}

impl Sub {
    pub(crate) fn is_const(&self) -> bool {
        matches!(self.kind, Kind::Const(_))
    }
}

/// Postfix code and, for each op, the span of source it came from.
#[derive(Debug, Default)]
pub(crate) struct Builder {
    pub code: Vec<Op>,
    pub spans: Vec<Span>,
}

impl Builder {
    /// Appends `op`; returns its index.
    pub(crate) fn push(&mut self, op: Op, span: Span) -> usize {
        self.code.push(op);
        self.spans.push(span);
        self.code.len() - 1
    }

    /// A constant leaf.
    pub(crate) fn constant(&mut self, c: f64, span: Span) -> Sub {
        let start = self.push(Op::Const(c), span);
        Sub {
            start,
            kind: Kind::Const(c),
            span,
        }
    }

    /// The variable as a leaf.
    pub(crate) fn variable(&mut self, span: Span) -> Sub {
        let start = self.push(Op::Var, span);
        Sub {
            start,
            kind: Kind::Var,
            span,
        }
    }

    /// Input k of a multi-input expression as a leaf.
    pub(crate) fn input(&mut self, k: u16, span: Span) -> Sub {
        let start = self.push(Op::Input(k), span);
        Sub {
            start,
            kind: Kind::Var,
            span,
        }
    }

    /// Sets the forward jump at `at` to land on the next op to be emitted.
    pub(crate) fn patch(&mut self, at: usize) {
        let off = (self.code.len() - at - 1) as u32;
        match &mut self.code[at] {
            Op::JumpIfFalse(o) | Op::Jump(o) | Op::AndJump(o) | Op::OrJump(o) => *o = off,
            _ => {}
        }
    }

    /// Removes `code[from..to]`. Jumps are relative and never cross the
    /// boundary of a sub-expression, so the code that moves stays valid.
    fn remove(&mut self, from: usize, to: usize) {
        self.code.drain(from..to);
        self.spans.drain(from..to);
    }

    /// Emits `op` applied to `args`, whose code is contiguous and ends the
    /// program: folds it when every argument is a constant and the result is
    /// finite, fuses a single constant operand of a binary op into the op.
    pub(crate) fn apply(&mut self, op: Op, args: &[Sub], span: Span) -> Sub {
        let start = args.first().map_or(self.code.len(), |a| a.start);
        if args.iter().all(Sub::is_const) {
            self.push(op, span);
            return self.fold(start, span);
        }
        let kind = if args.iter().any(|a| a.kind == Kind::Var) {
            Kind::Var
        } else {
            Kind::Fixed
        };
        if let [a, b] = args {
            match (a.kind, b.kind) {
                (_, Kind::Const(c)) => {
                    if let Some(fused) = fuse_right(op, c) {
                        self.remove(b.start, b.start + 1);
                        self.push(fused, span);
                        return Sub { start, kind, span };
                    }
                }
                (Kind::Const(c), _) => {
                    if let Some(fused) = fuse_left(op, c) {
                        self.remove(a.start, a.start + 1);
                        self.push(fused, span);
                        return Sub { start, kind, span };
                    }
                }
                _ => {}
            }
        }
        self.push(op, span);
        Sub { start, kind, span }
    }

    /// Closes `a and b` / `a or b` (code already emitted from `a.start`).
    pub(crate) fn logic(&mut self, a: Sub, b: Sub, span: Span) -> Sub {
        if a.is_const() && b.is_const() {
            return self.fold(a.start, span);
        }
        let kind = if a.kind == Kind::Var || b.kind == Kind::Var {
            Kind::Var
        } else {
            Kind::Fixed
        };
        Sub {
            start: a.start,
            kind,
            span,
        }
    }

    /// Closes `if(cond, a, b)` emitted as
    /// `cond JumpIfFalse(→b) a Jump(→end) b`; a constant condition keeps
    /// only the chosen branch.
    pub(crate) fn branch(
        &mut self,
        cond: Sub,
        jif: usize,
        a: Sub,
        jump: usize,
        b: Sub,
        span: Span,
    ) -> Sub {
        if let Kind::Const(c) = cond.kind {
            let kind = if truth(c) {
                self.remove(jump, self.code.len());
                self.remove(cond.start, jif + 1);
                a.kind
            } else {
                self.remove(cond.start, jump + 1);
                b.kind
            };
            return Sub {
                start: cond.start,
                kind,
                span,
            };
        }
        let kind = if [cond.kind, a.kind, b.kind].contains(&Kind::Var) {
            Kind::Var
        } else {
            Kind::Fixed
        };
        Sub {
            start: cond.start,
            kind,
            span,
        }
    }

    /// Replaces `code[start..]`, which does not read the variable, by its
    /// value when that value is finite.
    fn fold(&mut self, start: usize, span: Span) -> Sub {
        let code = &self.code[start..];
        let value = max_depth(code).and_then(|depth| {
            let mut stack = vec![0.0; depth];
            run::<f64, false>(code, Args::at(f64::NAN), &mut stack).ok()
        });
        match value {
            Some(v) if v.is_finite() => {
                self.remove(start, self.code.len());
                self.constant(v, span)
            }
            _ => Sub {
                start,
                kind: Kind::Fixed,
                span,
            },
        }
    }
}

/// `u op c` as one instruction.
fn fuse_right(op: Op, c: f64) -> Option<Op> {
    Some(match op {
        Op::Add => Op::AddC(c),
        Op::Sub => Op::AddC(-c),
        Op::Mul => Op::MulC(c),
        Op::Div => Op::DivC(c),
        Op::Pow if c.fract() == 0.0 && c.abs() <= 1024.0 => Op::PowI(c as i32),
        Op::Pow => Op::PowC(c),
        Op::Cmp(k) => Op::CmpC(k, c),
        _ => return None,
    })
}

/// `c op u` as one instruction.
fn fuse_left(op: Op, c: f64) -> Option<Op> {
    Some(match op {
        Op::Add => Op::AddC(c),
        Op::Sub => Op::RSubC(c),
        Op::Mul => Op::MulC(c),
        Op::Div => Op::RDivC(c),
        Op::Cmp(k) => Op::CmpC(k.flip(), c),
        _ => return None,
    })
}
