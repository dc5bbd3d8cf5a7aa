//! A force and torque given by expressions of the motion: a force of state.
//!
//! The expressions read [`Channel`]s of the two bodies the force acts on,
//! i and j (the ground, or the reaction body), and of up to [`MAX_READ`]
//! other bodies it reads: their coordinates and velocities, points'
//! positions and velocities, a revolute's relative angle, a translational
//! joint's stroke, their rates, and time. With
//! F = (f_x, f_y) (N; global components, or body-i components turning with
//! body i when `local`) at P_i (s'_i in body i) and a torque T (N·m,
//! counter-clockwise), body i receives F at P_i and T, body j the reaction
//! −F at P_j (s'_j in body j) and −T:
//!
//! Q_i = [F ; (B_i s'_i)ᵀ F + T],  Q_j = [−F ; −(B_j s'_j)ᵀ F − T].
//!
//! Derivatives ∂Q/∂q and ∂Q/∂q̇ are exact: the channels, F and Q are
//! evaluated once more over dual numbers ([`D`]) carrying the partials
//! with respect to the local state variables (q_i, q_j, q̇_i, q̇_j, and
//! q_k, q̇_k of the read bodies k), and each expression's partials ∂f/∂u_k with respect to its channels come
//! from the expression engine's jets ([`Expr::gradient`]), chained as
//! ∂f = Σ_k ∂f/∂u_k ∂u_k. At the switch of an `if`, `sign` or `min` the
//! derivative is that of the branch taken. A force of state has no
//! potential: its work shows up as a change of the mechanism's energy.

use std::ops::{Add, Mul, Neg, Sub};
use std::sync::Arc;

use camlink_expr::Expr;

use super::{Applied, BodyJac, BodyQ, ForceError, ForceJac, Reads, MAX_READ};
use crate::constraint::BodyId;
use crate::constraint::Local;
use crate::math::V2;

/// Most channels one expression may read.
pub(crate) const MAX_CHANNELS: usize = 16;

/// The slot of the ground, which reads as zero, for a channel of a joint
/// between the ground and one of the force's bodies.
pub const GROUND_SLOT: usize = 2;

/// The slot of the first body the force reads besides i and j; read body
/// k is in slot `READ_SLOT + k`.
pub const READ_SLOT: usize = 3;

/// Number of slots: i, j, the ground and the read bodies.
const SLOTS: usize = READ_SLOT + MAX_READ;

/// A quantity of the motion, read from the local state of the force's
/// bodies, slot 0 being body i and slot 1 body j, slot [`GROUND_SLOT`]
/// the ground (the ground reads as zero in any slot) and slots from
/// [`READ_SLOT`] the bodies the force reads ([`StateForce::reads`]).
/// Lengths in m, angles in rad, rates per second.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Channel {
    /// Time t (s).
    Time,
    /// Coordinate `c` (0: x, 1: y, 2: φ) of the body in `slot`, or its rate.
    Body { slot: usize, c: usize, rate: bool },
    /// Global component `axis` (0: x, 1: y) of the point s' of the body in
    /// `slot`, r + A(φ) s', or of its velocity ṙ + B(φ) s' φ̇.
    Point {
        slot: usize,
        s: V2,
        axis: usize,
        rate: bool,
    },
    /// A revolute's relative angle θ = φ_b − φ_a (slots a, b), or θ̇.
    Angle { a: usize, b: usize, rate: bool },
    /// A translational joint's stroke s = vᵀ(r_b^Q − r_a^P), the distance
    /// of its point Q (s_b on slot b) from its point P (s_a on slot a) along
    /// its unit axis v = A_a v'_a, or ṡ.
    Stroke {
        a: usize,
        s_a: V2,
        v_a: V2,
        b: usize,
        s_b: V2,
        rate: bool,
    },
}

/// The numbers channels and forces compute with: `f64`, or [`D`] for
/// derivatives.
trait Scalar:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Neg<Output = Self>
{
    fn c(v: f64) -> Self;
    fn sin_cos(self) -> (Self, Self);
}

impl Scalar for f64 {
    #[inline]
    fn c(v: f64) -> f64 {
        v
    }
    #[inline]
    fn sin_cos(self) -> (f64, f64) {
        crate::math::sin_cos(self)
    }
}

/// Number of local state variables of a force that reads no other body:
/// q_i, q_j, q̇_i, q̇_j.
const NV: usize = 12;

/// Number of local state variables of a force that reads other bodies:
/// q_i, q_j, q̇_i, q̇_j, then q_k of each read body, then q̇_k.
const NV_READ: usize = NV + 6 * MAX_READ;

/// Index of q_k,c (or q̇_k,c with `rate`) of the body in `slot` among the
/// local state variables; `None` for the ground.
fn var_index(slot: usize, c: usize, rate: bool) -> Option<usize> {
    match slot {
        0 | 1 => Some(if rate { 6 } else { 0 } + 3 * slot + c),
        GROUND_SLOT => None,
        _ => {
            let k = slot - READ_SLOT;
            Some(NV + if rate { 3 * MAX_READ } else { 0 } + 3 * k + c)
        }
    }
}

/// A dual number: a value and its partials with respect to N local state
/// variables, in the order of [`var_index`].
#[derive(Clone, Copy, Debug)]
struct D<const N: usize> {
    v: f64,
    d: [f64; N],
}

impl<const N: usize> D<N> {
    fn var(v: f64, k: usize) -> Self {
        let mut d = [0.0; N];
        d[k] = 1.0;
        D { v, d }
    }
    fn scale(self, a: f64) -> Self {
        D {
            v: self.v * a,
            d: self.d.map(|x| x * a),
        }
    }
}

impl<const N: usize> Add for D<N> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        let mut d = self.d;
        for (x, y) in d.iter_mut().zip(o.d) {
            *x += y;
        }
        D { v: self.v + o.v, d }
    }
}

impl<const N: usize> Sub for D<N> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        self + (-o)
    }
}

impl<const N: usize> Neg for D<N> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        self.scale(-1.0)
    }
}

impl<const N: usize> Mul for D<N> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        let mut d = [0.0; N];
        for (k, x) in d.iter_mut().enumerate() {
            *x = self.d[k] * o.v + self.v * o.d[k];
        }
        D { v: self.v * o.v, d }
    }
}

impl<const N: usize> Scalar for D<N> {
    #[inline]
    fn c(v: f64) -> Self {
        D { v, d: [0.0; N] }
    }
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = crate::math::sin_cos(self.v);
        (
            D {
                v: s,
                d: self.d.map(|x| x * c),
            },
            D {
                v: c,
                d: self.d.map(|x| -x * s),
            },
        )
    }
}

/// The local state over a scalar type: slots 0 and 1 are bodies i and j,
/// slot [`GROUND_SLOT`] the ground, slots from [`READ_SLOT`] the read bodies.
struct State<S> {
    t: f64,
    q: [[S; 3]; SLOTS],
    qd: [[S; 3]; SLOTS],
}

impl State<f64> {
    #[inline]
    fn of(x: &Local, r: &Reads) -> Self {
        let mut q = [[0.0; 3]; SLOTS];
        let mut qd = [[0.0; 3]; SLOTS];
        q[..2].copy_from_slice(&x.q);
        qd[..2].copy_from_slice(&x.qd);
        q[READ_SLOT..].copy_from_slice(&r.q);
        qd[READ_SLOT..].copy_from_slice(&r.qd);
        State { t: x.t, q, qd }
    }
}

impl<const N: usize> State<D<N>> {
    /// The state with a variable for every slot whose index fits in N.
    fn of(x: &Local, r: &Reads) -> Self {
        let v = State::<f64>::of(x, r);
        let mut q = [[D::c(0.0); 3]; SLOTS];
        let mut qd = [[D::c(0.0); 3]; SLOTS];
        for slot in 0..SLOTS {
            for c in 0..3 {
                q[slot][c] = match var_index(slot, c, false).filter(|&k| k < N) {
                    Some(k) => D::var(v.q[slot][c], k),
                    None => D::c(v.q[slot][c]),
                };
                qd[slot][c] = match var_index(slot, c, true).filter(|&k| k < N) {
                    Some(k) => D::var(v.qd[slot][c], k),
                    None => D::c(v.qd[slot][c]),
                };
            }
        }
        State { t: x.t, q, qd }
    }
}

/// A(φ) s and B(φ) s of a constant body vector s.
#[inline]
fn rot<S: Scalar>(phi: S, s: V2) -> ([S; 2], [S; 2]) {
    let (sn, cs) = phi.sin_cos();
    let (x, y) = (S::c(s[0]), S::c(s[1]));
    (
        [cs * x - sn * y, sn * x + cs * y],
        [-(sn * x) - cs * y, cs * x - sn * y],
    )
}

impl Channel {
    /// The channel's value at the state.
    #[inline]
    fn value<S: Scalar>(&self, x: &State<S>) -> S {
        match *self {
            Channel::Time => S::c(x.t),
            Channel::Body { slot, c, rate } => {
                if rate {
                    x.qd[slot][c]
                } else {
                    x.q[slot][c]
                }
            }
            Channel::Point {
                slot,
                s,
                axis,
                rate,
            } => {
                let (a, b) = rot(x.q[slot][2], s);
                if rate {
                    x.qd[slot][axis] + b[axis] * x.qd[slot][2]
                } else {
                    x.q[slot][axis] + a[axis]
                }
            }
            Channel::Angle { a, b, rate } => {
                if rate {
                    x.qd[b][2] - x.qd[a][2]
                } else {
                    x.q[b][2] - x.q[a][2]
                }
            }
            Channel::Stroke {
                a,
                s_a,
                v_a,
                b,
                s_b,
                rate,
            } => {
                let (ra, ba) = rot(x.q[a][2], s_a);
                let (rb, bb) = rot(x.q[b][2], s_b);
                let (v, vb) = rot(x.q[a][2], v_a);
                let d = [
                    x.q[b][0] + rb[0] - x.q[a][0] - ra[0],
                    x.q[b][1] + rb[1] - x.q[a][1] - ra[1],
                ];
                if rate {
                    let dd = [
                        x.qd[b][0] + bb[0] * x.qd[b][2] - x.qd[a][0] - ba[0] * x.qd[a][2],
                        x.qd[b][1] + bb[1] * x.qd[b][2] - x.qd[a][1] - ba[1] * x.qd[a][2],
                    ];
                    let w = x.qd[a][2];
                    (vb[0] * d[0] + vb[1] * d[1]) * w + v[0] * dd[0] + v[1] * dd[1]
                } else {
                    v[0] * d[0] + v[1] * d[1]
                }
            }
        }
    }

    /// The body slots the channel reads.
    fn slots(&self) -> [Option<usize>; 2] {
        match *self {
            Channel::Time => [None, None],
            Channel::Body { slot, .. } | Channel::Point { slot, .. } => [Some(slot), None],
            Channel::Angle { a, b, .. } | Channel::Stroke { a, b, .. } => [Some(a), Some(b)],
        }
    }
}

/// An expression and the channels it reads, input k being `channels[k]`.
#[derive(Clone, Debug)]
pub struct StateExpr {
    pub expr: Arc<Expr>,
    pub channels: Vec<Channel>,
}

impl StateExpr {
    /// The value, or an error naming the failing operation.
    #[inline]
    fn value(&self, x: &State<f64>) -> Result<f64, ForceError> {
        let mut u = [0.0; MAX_CHANNELS];
        let n = self.channels.len();
        for (uk, c) in u.iter_mut().zip(&self.channels) {
            *uk = c.value(x);
        }
        let v = self.expr.eval_inputs(&u[..n]);
        if v.is_finite() {
            return Ok(v);
        }
        Err(ForceError(match self.expr.check_inputs(&u[..n]) {
            Err(e) => e.message,
            Ok(()) => format!("`{}` is not finite", self.expr.source()),
        }))
    }

    /// The value with its partials over the local state.
    fn dual<const N: usize>(&self, x: &State<D<N>>) -> D<N> {
        let mut u = [D::c(0.0); MAX_CHANNELS];
        let mut v = [0.0; MAX_CHANNELS];
        let n = self.channels.len();
        for k in 0..n {
            u[k] = self.channels[k].value(x);
            v[k] = u[k].v;
        }
        let mut g = [0.0; MAX_CHANNELS];
        let f = self.expr.gradient(&v[..n], &mut g[..n]);
        let mut out = D::c(f);
        for k in 0..n {
            for (o, dk) in out.d.iter_mut().zip(u[k].d) {
                *o += g[k] * dk;
            }
        }
        out
    }
}

/// A force and torque of state on body i, with the reaction on body j.
#[derive(Clone, Debug)]
pub struct StateForce {
    /// The bodies besides i and j the expressions read, slot
    /// [`READ_SLOT`] + k being `reads[k]` (at most [`MAX_READ`]).
    pub reads: Vec<BodyId>,
    pub body_i: BodyId,
    /// s'_i: the point of application on body i, in its frame (m).
    pub s_i: V2,
    /// The reaction body (the ground for none).
    pub body_j: BodyId,
    /// s'_j: the point of the reaction on body j, in its frame (m).
    pub s_j: V2,
    /// f_x, f_y (N); `None` for zero.
    pub f: [Option<StateExpr>; 2],
    /// T (N·m), counter-clockwise; `None` for zero.
    pub torque: Option<StateExpr>,
    /// True when f gives body-i components (turning with body i).
    pub local: bool,
}

impl StateForce {
    /// Q_i and Q_j over a scalar type, from the values of f_x, f_y and T.
    #[inline]
    fn loads<S: Scalar>(&self, x: &State<S>, f: [S; 2], torque: S) -> [[S; 3]; 2] {
        let zero = S::c(0.0);
        if self.f[0].is_none() && self.f[1].is_none() {
            return [[zero, zero, torque], [zero, zero, -torque]];
        }
        let f = if self.local {
            let (sn, cs) = x.q[0][2].sin_cos();
            [cs * f[0] - sn * f[1], sn * f[0] + cs * f[1]]
        } else {
            f
        };
        // (B s')ᵀF, zero for a force at the frame origin.
        let moment = |phi: S, s: V2| {
            if s == [0.0; 2] {
                return zero;
            }
            let (_, b) = rot(phi, s);
            b[0] * f[0] + b[1] * f[1]
        };
        let ni = moment(x.q[0][2], self.s_i) + torque;
        let nj = moment(x.q[1][2], self.s_j) + torque;
        [[f[0], f[1], ni], [-f[0], -f[1], -nj]]
    }

    fn parts(&self) -> impl Iterator<Item = &StateExpr> {
        self.f.iter().flatten().chain(self.torque.as_ref())
    }
}

impl StateForce {
    /// ∂Q/∂q and ∂Q/∂q̇ over N local state variables.
    fn jacobians<const N: usize>(&self, x: &Local, r: &Reads, out: &mut ForceJac) {
        let s = State::<D<N>>::of(x, r);
        let value = |p: &Option<StateExpr>| p.as_ref().map_or(D::c(0.0), |p| p.dual(&s));
        let q = self.loads(
            &s,
            [value(&self.f[0]), value(&self.f[1])],
            value(&self.torque),
        );
        let partial = |a: usize, row: usize, k: Option<usize>| {
            k.filter(|&k| k < N).map_or(0.0, |k| q[a][row].d[k])
        };
        for a in 0..2 {
            for row in 0..3 {
                for c in 0..3 {
                    for b in 0..2 {
                        out.dq[a][b][row][c] = partial(a, row, var_index(b, c, false));
                        out.dqd[a][b][row][c] = partial(a, row, var_index(b, c, true));
                    }
                    for k in 0..MAX_READ {
                        let slot = READ_SLOT + k;
                        out.rq[a][k][row][c] = partial(a, row, var_index(slot, c, false));
                        out.rqd[a][k][row][c] = partial(a, row, var_index(slot, c, true));
                    }
                }
            }
        }
    }
}

impl Applied for StateForce {
    fn kind(&self) -> &'static str {
        "state_force"
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn reads(&self) -> &[BodyId] {
        &self.reads
    }

    fn validate(&self) -> Result<(), String> {
        if self.body_i.is_ground() {
            return Err("a force of state acts on a moving body".into());
        }
        if self.body_i == self.body_j {
            return Err("the reaction body must differ from the body".into());
        }
        if self.reads.len() > MAX_READ {
            return Err(format!(
                "it reads {} bodies besides its own; at most {MAX_READ}",
                self.reads.len()
            ));
        }
        for (k, b) in self.reads.iter().enumerate() {
            if b.is_ground()
                || *b == self.body_i
                || *b == self.body_j
                || self.reads[..k].contains(b)
            {
                return Err(format!(
                    "read body {} is the ground, one of the force's bodies or read twice",
                    b.0
                ));
            }
        }
        let slots = READ_SLOT + self.reads.len();
        for p in self.parts() {
            if p.channels.len() > MAX_CHANNELS {
                return Err(format!(
                    "`{}` reads {} channels; at most {MAX_CHANNELS}",
                    p.expr.source(),
                    p.channels.len()
                ));
            }
            if p.expr.inputs().len() != p.channels.len() {
                return Err(format!(
                    "`{}` has {} inputs for {} channels",
                    p.expr.source(),
                    p.expr.inputs().len(),
                    p.channels.len()
                ));
            }
            for c in &p.channels {
                if c.slots().iter().flatten().any(|&s| s >= slots) {
                    return Err(format!("channel {c:?} reads a slot past {}", slots - 1));
                }
            }
        }
        Ok(())
    }

    #[inline]
    fn generalized(&self, x: &Local, out: &mut BodyQ) -> Result<(), ForceError> {
        self.generalized_reading(x, &Reads::default(), out)
    }

    #[inline]
    fn generalized_reading(&self, x: &Local, r: &Reads, out: &mut BodyQ) -> Result<(), ForceError> {
        let s = State::<f64>::of(x, r);
        let value = |p: &Option<StateExpr>| p.as_ref().map_or(Ok(0.0), |p| p.value(&s));
        let f = [value(&self.f[0])?, value(&self.f[1])?];
        let torque = value(&self.torque)?;
        *out = self.loads(&s, f, torque);
        Ok(())
    }

    /// The reaction on the ground acts where F acts, at P_i: −F and
    /// −(r_P × F) − T about the global origin, r_P = r_i + A_i s'_i. (The
    /// ground's slot of Q would put −F at the ground point s'_j, which is
    /// the origin for a reaction on the ground.)
    fn frame_load(&self, x: &Local) -> Result<Option<[f64; 3]>, ForceError> {
        if !self.body_j.is_ground() {
            return Ok(None);
        }
        let mut q = BodyQ::default();
        self.generalized(x, &mut q)?;
        // Q_i's moment is (A_i s'_i) × F + T, about body i's origin.
        let [fx, fy, n] = q[0];
        let m = n + x.q[0][0] * fy - x.q[0][1] * fx;
        Ok(Some([-fx, -fy, -m]))
    }

    fn derivatives(&self, x: &Local, dq: &mut BodyJac, dqd: &mut BodyJac) {
        let mut j = ForceJac::default();
        self.derivatives_reading(x, &Reads::default(), &mut j);
        (*dq, *dqd) = (j.dq, j.dqd);
    }

    fn derivatives_reading(&self, x: &Local, r: &Reads, out: &mut ForceJac) {
        // Twelve variables, the cost of a built-in force, unless the
        // force reads other bodies.
        if self.reads.is_empty() {
            self.jacobians::<NV>(x, r, out);
        } else {
            self.jacobians::<NV_READ>(x, r, out);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::force::check;
    use std::collections::HashMap;

    fn part(src: &str, channels: &[(&str, Channel)]) -> StateExpr {
        let names: Vec<&str> = channels.iter().map(|c| c.0).collect();
        StateExpr {
            expr: Arc::new(Expr::parse_inputs(src, &names, &HashMap::new()).unwrap()),
            channels: channels.iter().map(|c| c.1).collect(),
        }
    }

    /// Every channel kind, on both slots.
    fn channels() -> Vec<(&'static str, Channel)> {
        vec![
            ("t", Channel::Time),
            (
                "xi",
                Channel::Body {
                    slot: 0,
                    c: 0,
                    rate: false,
                },
            ),
            (
                "wj",
                Channel::Body {
                    slot: 1,
                    c: 2,
                    rate: true,
                },
            ),
            (
                "py",
                Channel::Point {
                    slot: 0,
                    s: [0.3, -0.2],
                    axis: 1,
                    rate: false,
                },
            ),
            (
                "pvx",
                Channel::Point {
                    slot: 1,
                    s: [-0.1, 0.4],
                    axis: 0,
                    rate: true,
                },
            ),
            (
                "th",
                Channel::Angle {
                    a: 0,
                    b: 1,
                    rate: false,
                },
            ),
            (
                "thd",
                Channel::Angle {
                    a: GROUND_SLOT,
                    b: 0,
                    rate: true,
                },
            ),
            (
                "s",
                Channel::Stroke {
                    a: 0,
                    s_a: [0.1, 0.2],
                    v_a: [0.6, 0.8],
                    b: 1,
                    s_b: [-0.3, 0.1],
                    rate: false,
                },
            ),
            (
                "sd",
                Channel::Stroke {
                    a: 1,
                    s_a: [0.2, -0.1],
                    v_a: [0.0, 1.0],
                    b: 0,
                    s_b: [0.05, 0.3],
                    rate: true,
                },
            ),
        ]
    }

    fn force(local: bool) -> StateForce {
        let ch = channels();
        StateForce {
            reads: Vec::new(),
            body_i: BodyId(1),
            s_i: [0.2, 0.1],
            body_j: BodyId(2),
            s_j: [-0.3, 0.4],
            f: [
                Some(part(
                    "3*xi*wj + sin(py)*pvx - 2*s*sd + t^2 + coulomb(sd, 2, 5)",
                    &ch,
                )),
                Some(part("th^2 - thd*s + step(s, -1, 0, 1, 4)", &ch)),
            ],
            torque: Some(part("-5*th - 0.7*thd + py*pvx*wj", &ch)),
            local,
        }
    }

    #[test]
    fn issue30_state_force_derivatives_match_finite_differences() {
        for seed in 0..20 {
            check::derivatives(&force(false), &check::state(seed));
            check::derivatives(&force(true), &check::state(seed));
        }
    }

    /// A force on bodies 1 and 2 that reads bodies 3 and 4 (slots
    /// READ_SLOT and READ_SLOT + 1) through every channel kind.
    fn reading_force() -> StateForce {
        let (r0, r1) = (READ_SLOT, READ_SLOT + 1);
        let ch = vec![
            ("t", Channel::Time),
            (
                "x3",
                Channel::Body {
                    slot: r0,
                    c: 0,
                    rate: false,
                },
            ),
            (
                "w4",
                Channel::Body {
                    slot: r1,
                    c: 2,
                    rate: true,
                },
            ),
            (
                "p3",
                Channel::Point {
                    slot: r0,
                    s: [0.3, -0.2],
                    axis: 1,
                    rate: false,
                },
            ),
            (
                "v4",
                Channel::Point {
                    slot: r1,
                    s: [-0.1, 0.4],
                    axis: 0,
                    rate: true,
                },
            ),
            (
                "th",
                Channel::Angle {
                    a: r0,
                    b: 0,
                    rate: false,
                },
            ),
            (
                "thd",
                Channel::Angle {
                    a: GROUND_SLOT,
                    b: r1,
                    rate: true,
                },
            ),
            (
                "s",
                Channel::Stroke {
                    a: r1,
                    s_a: [0.1, 0.2],
                    v_a: [0.6, 0.8],
                    b: r0,
                    s_b: [-0.3, 0.1],
                    rate: false,
                },
            ),
            (
                "sd",
                Channel::Stroke {
                    a: r0,
                    s_a: [0.2, -0.1],
                    v_a: [0.0, 1.0],
                    b: 1,
                    s_b: [0.05, 0.3],
                    rate: true,
                },
            ),
        ];
        StateForce {
            reads: vec![BodyId(3), BodyId(4)],
            f: [
                Some(part("3*x3*w4 + sin(p3)*v4 - 2*s*sd + t^2", &ch)),
                Some(part("th^2 - thd*s + coulomb(sd, 2, 5)", &ch)),
            ],
            torque: Some(part("-5*th - 0.7*thd + p3*v4*w4", &ch)),
            ..force(true)
        }
    }

    /// The read bodies' state for a seed.
    fn reads(seed: u64) -> Reads {
        let a = check::state(seed + 100);
        let b = check::state(seed + 200);
        let mut r = Reads::default();
        r.q[..2].copy_from_slice(&a.q);
        r.qd[..2].copy_from_slice(&a.qd);
        r.q[2] = b.q[0];
        r.qd[2] = b.qd[0];
        r
    }

    #[test]
    fn issue30_derivatives_over_read_bodies_match_finite_differences() {
        let f = reading_force();
        assert_eq!(f.validate(), Ok(()));
        for seed in 0..20 {
            let (x, r) = (check::state(seed), reads(seed));
            let mut j = ForceJac::default();
            f.derivatives_reading(&x, &r, &mut j);
            let q_at = |x: &Local, r: &Reads| {
                let mut q = BodyQ::default();
                f.generalized_reading(x, r, &mut q).unwrap();
                q
            };
            let h = 1e-6;
            // Columns of the force's own bodies and of each read body.
            for k in 0..4 {
                for c in 0..3 {
                    for vel in [false, true] {
                        // The state with variable (k, c) moved by dh.
                        let moved = |dh: f64| {
                            let (mut x, mut r) = (x, r);
                            match (k, vel) {
                                (0 | 1, false) => x.q[k][c] += dh,
                                (0 | 1, true) => x.qd[k][c] += dh,
                                (_, false) => r.q[k - 2][c] += dh,
                                (_, true) => r.qd[k - 2][c] += dh,
                            }
                            q_at(&x, &r)
                        };
                        let (qp, qm) = (moved(h), moved(-h));
                        for a in 0..2 {
                            for row in 0..3 {
                                let fd = (qp[a][row] - qm[a][row]) / (2.0 * h);
                                let an = match (k, vel) {
                                    (0 | 1, false) => j.dq[a][k][row][c],
                                    (0 | 1, true) => j.dqd[a][k][row][c],
                                    (_, false) => j.rq[a][k - 2][row][c],
                                    (_, true) => j.rqd[a][k - 2][row][c],
                                };
                                assert!(
                                    (fd - an).abs() <= 1e-6 * (1.0 + fd.abs()),
                                    "seed {seed}: dQ[{a}][{row}]/d{}[{k}][{c}]: {an} vs {fd}",
                                    if vel { "qd" } else { "q" }
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn issue30_a_force_without_reads_takes_the_short_path() {
        // The same derivatives whichever dual size computes them.
        let f = force(false);
        let x = check::state(7);
        let r = Reads::default();
        let (mut a, mut b) = (ForceJac::default(), ForceJac::default());
        f.jacobians::<NV>(&x, &r, &mut a);
        f.jacobians::<NV_READ>(&x, &r, &mut b);
        assert_eq!(a, b);
        assert_eq!(b.rq, ForceJac::default().rq);
    }

    #[test]
    fn issue30_read_bodies_are_checked() {
        let mut f = reading_force();
        f.reads = vec![BodyId(3)];
        assert!(f.validate().unwrap_err().contains("past"));
        f.reads = vec![BodyId(3), BodyId(1)];
        assert!(f.validate().unwrap_err().contains("force's bodies"));
    }

    #[test]
    fn issue30_channels_match_the_closed_forms() {
        let x = check::state(3);
        let s = State::<f64>::of(&x, &Reads::default());
        let value = |name: &str| {
            let c = channels().into_iter().find(|c| c.0 == name).unwrap().1;
            c.value(&s)
        };
        assert_eq!(value("t"), x.t);
        assert_eq!(value("xi"), x.q[0][0]);
        assert_eq!(value("wj"), x.qd[1][2]);
        let p = crate::math::point(x.q[0], [0.3, -0.2]);
        assert!((value("py") - p[1]).abs() < 1e-15);
        let v = crate::math::point_vel(x.q[1], x.qd[1], [-0.1, 0.4]);
        assert!((value("pvx") - v[0]).abs() < 1e-15);
        assert_eq!(value("th"), x.q[1][2] - x.q[0][2]);
        // The stroke: P and Q as points, the axis turned with body a.
        let pa = crate::math::point(x.q[0], [0.1, 0.2]);
        let qb = crate::math::point(x.q[1], [-0.3, 0.1]);
        let axis = crate::math::rot(x.q[0][2], [0.6, 0.8]);
        let stroke = crate::math::dot(axis, crate::math::sub(qb, pa));
        assert!((value("s") - stroke).abs() < 1e-15);
    }

    #[test]
    fn issue30_the_reaction_balances_the_force() {
        // With s'_j at the same global point as s'_i, the pair has no net
        // force and no net moment about any point.
        let mut x = check::state(5);
        let f = force(false);
        let pi = crate::math::point(x.q[0], f.s_i);
        let s_j = crate::math::rot_t(x.q[1][2], crate::math::sub(pi, [x.q[1][0], x.q[1][1]]));
        let f = StateForce { s_j, ..f };
        x.t = 0.4;
        let mut q = BodyQ::default();
        f.generalized(&x, &mut q).unwrap();
        assert!((q[0][0] + q[1][0]).abs() < 1e-12 && (q[0][1] + q[1][1]).abs() < 1e-12);
        // Moments about the global origin: n_k + r_k × F_k.
        let m = |k: usize| q[k][2] + x.q[k][0] * q[k][1] - x.q[k][1] * q[k][0];
        assert!((m(0) + m(1)).abs() < 1e-12, "{} {}", m(0), m(1));
    }

    /// With its reaction on the ground, the frame takes −F at the global
    /// point P_i where F acts and −T: −(r_P × F + T) about the origin.
    #[test]
    fn issue32_frame_load_acts_where_the_force_acts() {
        let mut f = force(true);
        f.body_j = BodyId::GROUND;
        f.s_j = [0.0; 2];
        let mut x = check::state(5);
        x.q[1] = [0.0; 3];
        x.qd[1] = [0.0; 3];
        let mut q = BodyQ::default();
        f.generalized(&x, &mut q).unwrap();
        let force = [q[0][0], q[0][1]];
        // T is Q_i's moment less that of F about body i's origin.
        let arm = crate::math::rot(x.q[0][2], f.s_i);
        let t = q[0][2] - crate::math::cross(arm, force);
        let p = crate::math::point(x.q[0], f.s_i);
        let want = [-force[0], -force[1], -(crate::math::cross(p, force) + t)];
        let got = f.frame_load(&x).unwrap().unwrap();
        for k in 0..3 {
            assert!(
                (got[k] - want[k]).abs() <= 1e-12 * (1.0 + want[k].abs()),
                "{got:?} {want:?}"
            );
        }
        f.body_j = BodyId(2);
        assert_eq!(f.frame_load(&x).unwrap(), None);
    }

    #[test]
    fn issue30_a_failing_expression_names_the_operation() {
        let ch = channels();
        let f = StateForce {
            f: [Some(part("log(xi - 10)", &ch)), None],
            torque: None,
            ..force(false)
        };
        let mut q = BodyQ::default();
        let e = f.generalized(&check::state(1), &mut q).unwrap_err();
        assert!(e.0.starts_with("log of a negative number"), "{}", e.0);
    }
}
