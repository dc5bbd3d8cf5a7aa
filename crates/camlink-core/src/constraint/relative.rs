//! Relative constraints between two bodies, and their drivers.
//!
//! With d = r_j^P − r_i^P (global frame):
//! - x: Φ = d_x − f(t); y: Φ = d_y − f(t); φ: Φ = φ_j − φ_i − f(t)
//!   (a revolute joint's relative angle);
//! - along: Φ = (A_i v'_i)ᵀ d − f(t), travel of P_j relative to P_i along the
//!   unit vector v'_i fixed in body i (a translational joint's travel);
//! - distance: Φ = dᵀd − f(t)².
//!
//! v'_i is normalised when the equations are evaluated, so the travel is in
//! metres whatever the length of the given vector (which must not be zero).
//!
//! Derivatives, with ḋ = ṙ_j + B_j s'_j φ̇_j − ṙ_i − B_i s'_i φ̇_i and
//! a_k = A_k s'_k φ̇_k² (centripetal terms):
//! - x, y: Φ_q = ±[I  B s'] rows, ν = f', γ = (a_j − a_i)_{x,y} + f'';
//! - φ: Φ_q = [0 0 −1 | 0 0 1], ν = f', γ = f'';
//! - along: the axis projection below with a = i, b = j, w' = v'_i; ν = f',
//!   γ gains + f'';
//! - distance: Φ_q = 2dᵀ[−I  −B_i s'_i | I  B_j s'_j], ν = 2 f f',
//!   γ = −2ḋᵀḋ + 2dᵀ(a_j − a_i) + 2(f'² + f f'').
//!
//! η = −d³Φ/dt³ with the jerks set to zero ([`motion`](crate::motion)):
//! x, y: −(d⃛*)_{x,y} + f‴; φ: f‴; along: −((A_i v'_i)ᵀd)⃛* + f‴ by the
//! product rule; distance: −(dᵀd)⃛* + (f²)‴.
//!
//! The axis projection (`projection_phi`, `projection_jac`,
//! `projection_gamma`), shared with the translational and
//! revolute–translational joints and the rack, is Φ = (A_a w')ᵀe with
//! e = r_b^P − r_a^P, w' a vector fixed in body a and b the other body:
//! ∂Φ/∂r_a = −(A_a w')ᵀ, ∂Φ/∂φ_a = (B_a w')ᵀe − (A_a w')ᵀB_a s'_a,
//! ∂Φ/∂r_b = (A_a w')ᵀ, ∂Φ/∂φ_b = (A_a w')ᵀB_b s'_b, ν = 0,
//! γ = (A_a w')ᵀe φ̇_a² − 2 φ̇_a (B_a w')ᵀė − (A_a w')ᵀ(A_a s'_a φ̇_a² − A_b s'_b φ̇_b²).

use super::sketch::Sketch;
use super::{CoordMask, Equations, Jac, Local, Rows, ALL_COORDS, MAX_ROWS};
use crate::constraint::BodyId;
use crate::function::TimeFn;
use crate::math::{dot, norm, point, point_vel, rot, rot_d, scale, sub, V2};
use crate::motion;
use crate::quantity::Quantity;

/// Which relative coordinate a [`RelativeCoord`] holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RelCoord {
    X,
    Y,
    Phi,
    /// Travel along the unit vector v'_i (body i frame).
    Along(V2),
}

#[derive(Clone, Debug)]
pub struct RelativeCoord {
    pub body_i: BodyId,
    pub s_i: V2,
    pub body_j: BodyId,
    pub s_j: V2,
    pub coord: RelCoord,
    /// f(t) in m or rad.
    pub f: TimeFn,
}

#[derive(Clone, Debug)]
pub struct RelativeDistance {
    pub body_i: BodyId,
    pub s_i: V2,
    pub body_j: BodyId,
    pub s_j: V2,
    /// f(t) in m.
    pub f: TimeFn,
}

impl RelativeCoord {
    /// The coordinate g(q) of Φ = g(q) − f(t) and its rate ġ = Φ_q q̇ at
    /// the local state `x` (m and m/s, or rad and rad/s).
    pub fn value_and_rate(&self, x: &Local) -> (f64, f64) {
        let mut phi = [0.0; MAX_ROWS];
        self.phi(x, &mut phi);
        let mut jac = Jac::default();
        self.jacobian(x, &mut jac);
        let rate = (0..2)
            .map(|k| (0..3).map(|c| jac.body[k][0][c] * x.qd[k][c]).sum::<f64>())
            .sum();
        (phi[0] + self.f.value(x.t), rate)
    }
}

/// v / |v|.
pub(super) fn unit(v: V2) -> V2 {
    scale(1.0 / norm(v), v)
}

/// d = r_j^P − r_i^P.
pub(super) fn rel(x: &Local, s_i: V2, s_j: V2) -> V2 {
    sub(point(x.q[1], s_j), point(x.q[0], s_i))
}

/// ḋ = ṙ_j^P − ṙ_i^P.
pub(super) fn rel_vel(x: &Local, s_i: V2, s_j: V2) -> V2 {
    sub(
        point_vel(x.q[1], x.qd[1], s_j),
        point_vel(x.q[0], x.qd[0], s_i),
    )
}

/// a_j − a_i = A_j s'_j φ̇_j² − A_i s'_i φ̇_i², the centripetal part of d̈.
pub(super) fn rel_centripetal(x: &Local, s_i: V2, s_j: V2) -> V2 {
    let (wi, wj) = (x.qd[0][2], x.qd[1][2]);
    sub(
        scale(wj * wj, rot(x.q[1][2], s_j)),
        scale(wi * wi, rot(x.q[0][2], s_i)),
    )
}

/// d = r_j^P − r_i^P with its time derivatives, for η.
pub(super) fn rel_path(x: &Local, s_i: V2, s_j: V2) -> motion::Path {
    motion::sub(&x.point_path(1, s_j), &x.point_path(0, s_i))
}

/// η of the axis projection below, −((A_a w')ᵀ e)⃛* by the product rule.
pub(super) fn projection_eta(x: &Local, axis: usize, s_a: V2, w: V2, s_b: V2) -> f64 {
    let (a, b) = (axis, 1 - axis);
    let e = motion::sub(&x.point_path(b, s_b), &x.point_path(a, s_a));
    -motion::dot(&x.vector_path(a, w), &e)[3]
}

// Projection onto an axis fixed in one body, shared by the along coordinate,
// the translational and revolute–translational joints and the rack:
//
//   Φ = (A_a w')ᵀ e,   e = r_b^P − r_a^P,
//
// where a = `axis` (0 for body i, 1 for body j of the Local view) carries the
// vector w' and the point s'_a, and b is the other body with point s'_b.

/// Φ = (A_a w')ᵀ e.
pub(super) fn projection_phi(x: &Local, axis: usize, s_a: V2, w: V2, s_b: V2) -> f64 {
    let (a, b) = (axis, 1 - axis);
    let e = sub(point(x.q[b], s_b), point(x.q[a], s_a));
    dot(rot(x.q[a][2], w), e)
}

/// Φ_q of the projection as `[block of body i, block of body j]`:
/// ∂/∂r_a = −(A_a w')ᵀ, ∂/∂φ_a = (B_a w')ᵀe − (A_a w')ᵀB_a s'_a,
/// ∂/∂r_b = (A_a w')ᵀ, ∂/∂φ_b = (A_a w')ᵀB_b s'_b.
pub(super) fn projection_jac(x: &Local, axis: usize, s_a: V2, w: V2, s_b: V2) -> [[f64; 3]; 2] {
    projection_phi_and_jac(x, axis, s_a, w, s_b).1
}

/// The projection ([`projection_phi`]) and its Φ_q ([`projection_jac`])
/// from one evaluation of e and A_a w'.
pub(super) fn projection_phi_and_jac(
    x: &Local,
    axis: usize,
    s_a: V2,
    w: V2,
    s_b: V2,
) -> (f64, [[f64; 3]; 2]) {
    let (a, b) = (axis, 1 - axis);
    let (pa, pb) = (x.q[a][2], x.q[b][2]);
    let e = sub(point(x.q[b], s_b), point(x.q[a], s_a));
    let (aw, bw) = (rot(pa, w), rot_d(pa, w));
    let mut out = [[0.0; 3]; 2];
    out[a] = [-aw[0], -aw[1], dot(bw, e) - dot(aw, rot_d(pa, s_a))];
    out[b] = [aw[0], aw[1], dot(aw, rot_d(pb, s_b))];
    (dot(aw, e), out)
}

/// γ of the projection:
/// γ = (A_a w')ᵀe φ̇_a² − 2 φ̇_a (B_a w')ᵀė − (A_a w')ᵀ(A_a s'_a φ̇_a² − A_b s'_b φ̇_b²).
pub(super) fn projection_gamma(x: &Local, axis: usize, s_a: V2, w: V2, s_b: V2) -> f64 {
    let (a, b) = (axis, 1 - axis);
    let (pa, pb) = (x.q[a][2], x.q[b][2]);
    let (wa, wb) = (x.qd[a][2], x.qd[b][2]);
    let e = sub(point(x.q[b], s_b), point(x.q[a], s_a));
    let e_d = sub(
        point_vel(x.q[b], x.qd[b], s_b),
        point_vel(x.q[a], x.qd[a], s_a),
    );
    let (aw, bw) = (rot(pa, w), rot_d(pa, w));
    let centripetal = sub(scale(wa * wa, rot(pa, s_a)), scale(wb * wb, rot(pb, s_b)));
    dot(aw, e) * wa * wa - 2.0 * wa * dot(bw, e_d) - dot(aw, centripetal)
}

impl Equations for RelativeCoord {
    fn check_functions(&self, x: &Local) -> Result<(), String> {
        self.f.check(x.t)
    }

    fn kind(&self) -> &'static str {
        "relative_coordinate"
    }

    fn driven_quantity(&self) -> Quantity {
        match self.coord {
            RelCoord::Phi => Quantity::Angle,
            RelCoord::X | RelCoord::Y | RelCoord::Along(_) => Quantity::Length,
        }
    }

    fn equations(&self) -> &'static [&'static str] {
        match self.coord {
            RelCoord::X => &["x"],
            RelCoord::Y => &["y"],
            RelCoord::Phi => &["phi"],
            RelCoord::Along(_) => &["along"],
        }
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn sketch(&self) -> Sketch<'_> {
        Vec::new()
    }

    fn joint_points(&self, _x: &Local) -> [V2; 2] {
        [self.s_i, self.s_j]
    }

    /// φ_i and φ_j for a point coordinate, nothing for the angle.
    fn nonlinear(&self) -> CoordMask {
        match self.coord {
            RelCoord::X | RelCoord::Y => 1 << 2 | 1 << 5,
            RelCoord::Phi => 0,
            RelCoord::Along(_) => ALL_COORDS,
        }
    }

    /// The coordinate and the angle of each body.
    fn jacobian_pattern(&self) -> [CoordMask; MAX_ROWS] {
        let row = match self.coord {
            RelCoord::X => 0b10_1101,
            RelCoord::Y => 0b11_0110,
            RelCoord::Phi => 0b10_0100,
            RelCoord::Along(_) => ALL_COORDS,
        };
        [row, 0, 0]
    }

    fn phi(&self, x: &Local, out: &mut Rows) {
        let f = self.f.value(x.t);
        let value = match self.coord {
            RelCoord::X => rel(x, self.s_i, self.s_j)[0],
            RelCoord::Y => rel(x, self.s_i, self.s_j)[1],
            RelCoord::Phi => x.q[1][2] - x.q[0][2],
            RelCoord::Along(v) => projection_phi(x, 0, self.s_i, unit(v), self.s_j),
        };
        *out = [value - f, 0.0, 0.0];
    }

    fn jacobian(&self, x: &Local, out: &mut Jac) {
        *out = Jac::default();
        match self.coord {
            RelCoord::X | RelCoord::Y => {
                let c = usize::from(self.coord == RelCoord::Y);
                let bi = rot_d(x.q[0][2], self.s_i);
                let bj = rot_d(x.q[1][2], self.s_j);
                out.body[0][0][c] = -1.0;
                out.body[0][0][2] = -bi[c];
                out.body[1][0][c] = 1.0;
                out.body[1][0][2] = bj[c];
            }
            RelCoord::Phi => {
                out.body[0][0][2] = -1.0;
                out.body[1][0][2] = 1.0;
            }
            RelCoord::Along(v) => {
                let [ji, jj] = projection_jac(x, 0, self.s_i, unit(v), self.s_j);
                out.body[0][0] = ji;
                out.body[1][0] = jj;
            }
        }
    }

    fn nu(&self, x: &Local, out: &mut Rows) {
        *out = [self.f.jet(x.t)[1], 0.0, 0.0];
    }

    fn gamma(&self, x: &Local, out: &mut Rows) {
        let f_dd = self.f.jet(x.t)[2];
        let value = match self.coord {
            RelCoord::X => rel_centripetal(x, self.s_i, self.s_j)[0],
            RelCoord::Y => rel_centripetal(x, self.s_i, self.s_j)[1],
            RelCoord::Phi => 0.0,
            RelCoord::Along(v) => projection_gamma(x, 0, self.s_i, unit(v), self.s_j),
        };
        *out = [value + f_dd, 0.0, 0.0];
    }

    fn eta(&self, x: &Local, out: &mut Rows) {
        let f3 = self.f.jet(x.t)[3];
        let value = match self.coord {
            RelCoord::X => -rel_path(x, self.s_i, self.s_j)[3][0],
            RelCoord::Y => -rel_path(x, self.s_i, self.s_j)[3][1],
            RelCoord::Phi => 0.0,
            RelCoord::Along(v) => projection_eta(x, 0, self.s_i, unit(v), self.s_j),
        };
        *out = [value + f3, 0.0, 0.0];
    }
}

impl Equations for RelativeDistance {
    fn driver_slope(&self, t: f64) -> f64 {
        -2.0 * self.f.value(t)
    }

    fn check_functions(&self, x: &Local) -> Result<(), String> {
        self.f.check(x.t)
    }

    fn kind(&self) -> &'static str {
        "relative_distance"
    }

    fn equations(&self) -> &'static [&'static str] {
        &["distance"]
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn sketch(&self) -> Sketch<'_> {
        Vec::new()
    }

    fn joint_points(&self, _x: &Local) -> [V2; 2] {
        [self.s_i, self.s_j]
    }

    fn phi(&self, x: &Local, out: &mut Rows) {
        let d = rel(x, self.s_i, self.s_j);
        let f = self.f.value(x.t);
        *out = [dot(d, d) - f * f, 0.0, 0.0];
    }

    fn jacobian(&self, x: &Local, out: &mut Jac) {
        let d = rel(x, self.s_i, self.s_j);
        let bi = rot_d(x.q[0][2], self.s_i);
        let bj = rot_d(x.q[1][2], self.s_j);
        *out = Jac::default();
        out.body[0][0] = [-2.0 * d[0], -2.0 * d[1], -2.0 * dot(d, bi)];
        out.body[1][0] = [2.0 * d[0], 2.0 * d[1], 2.0 * dot(d, bj)];
    }

    fn nu(&self, x: &Local, out: &mut Rows) {
        let [f, f_d, ..] = self.f.jet(x.t);
        *out = [2.0 * f * f_d, 0.0, 0.0];
    }

    fn gamma(&self, x: &Local, out: &mut Rows) {
        let d = rel(x, self.s_i, self.s_j);
        let d_d = rel_vel(x, self.s_i, self.s_j);
        let a = rel_centripetal(x, self.s_i, self.s_j);
        let [f, f_d, f_dd, _] = self.f.jet(x.t);
        *out = [
            -2.0 * dot(d_d, d_d) + 2.0 * dot(d, a) + 2.0 * (f_d * f_d + f * f_dd),
            0.0,
            0.0,
        ];
    }

    fn eta(&self, x: &Local, out: &mut Rows) {
        let d = rel_path(x, self.s_i, self.s_j);
        let (dd, ff) = (motion::dot(&d, &d), motion::square(self.f.jet(x.t)));
        *out = [ff[3] - dd[3], 0.0, 0.0];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::check::check_random;

    fn sine() -> TimeFn {
        TimeFn::Sine {
            amplitude: 0.4,
            omega: 1.7,
            phase: 0.3,
            offset: 1.2,
        }
    }

    fn coord(coord: RelCoord, body_j: BodyId, f: TimeFn) -> RelativeCoord {
        RelativeCoord {
            body_i: BodyId(1),
            s_i: [0.4, -0.2],
            body_j,
            s_j: [-0.3, 0.7],
            coord,
            f,
        }
    }

    const COORDS: [RelCoord; 4] = [
        RelCoord::X,
        RelCoord::Y,
        RelCoord::Phi,
        RelCoord::Along([0.6, -1.1]),
    ];

    #[test]
    fn coordinates_match_finite_differences() {
        for c in COORDS {
            check_random(&coord(c, BodyId(2), sine()), 30);
            check_random(&coord(c, BodyId(2), 0.5.into()), 10);
        }
    }

    #[test]
    fn coordinates_match_with_ground() {
        for c in COORDS {
            check_random(&coord(c, BodyId::GROUND, sine()), 20);
            let mut g = coord(c, BodyId(2), sine());
            g.body_i = BodyId::GROUND;
            check_random(&g, 20);
        }
    }

    fn distance(body_j: BodyId, f: TimeFn) -> RelativeDistance {
        RelativeDistance {
            body_i: BodyId(1),
            s_i: [0.4, -0.2],
            body_j,
            s_j: [-0.3, 0.7],
            f,
        }
    }

    #[test]
    fn distance_matches_finite_differences() {
        check_random(&distance(BodyId(2), sine()), 30);
        check_random(&distance(BodyId::GROUND, sine()), 20);
        check_random(&distance(BodyId(2), 1.5.into()), 10);
    }

    #[test]
    fn values_at_a_known_configuration() {
        // Body i at (1, 0) turned by π/2: P_i = (1, 0) + A(π/2)(0.4, −0.2) = (1.2, 0.4).
        // Body j at (2, 3), not turned: P_j = (2, 3) + (−0.3, 0.7) = (1.7, 3.7).
        let x = Local {
            t: 0.0,
            q: [[1.0, 0.0, std::f64::consts::FRAC_PI_2], [2.0, 3.0, 0.0]],
            ..Local::default()
        };
        let (dx, dy) = (0.5, 3.3);
        let mut out = [0.0; 3];
        coord(RelCoord::X, BodyId(2), 0.1.into()).phi(&x, &mut out);
        assert!((out[0] - (dx - 0.1)).abs() < 1e-12);
        coord(RelCoord::Y, BodyId(2), 0.0.into()).phi(&x, &mut out);
        assert!((out[0] - dy).abs() < 1e-12);
        coord(RelCoord::Phi, BodyId(2), 0.0.into()).phi(&x, &mut out);
        assert!((out[0] + std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        // v'_i = (2, 0) in body i points along global +y: travel is d_y, in metres.
        coord(RelCoord::Along([2.0, 0.0]), BodyId(2), 0.0.into()).phi(&x, &mut out);
        assert!((out[0] - dy).abs() < 1e-12);
        distance(BodyId(2), 2.0.into()).phi(&x, &mut out);
        assert!((out[0] - (dx * dx + dy * dy - 4.0)).abs() < 1e-12);
    }

    #[test]
    fn linear_driver_velocity() {
        let c = coord(
            RelCoord::Phi,
            BodyId(2),
            TimeFn::Linear {
                value: 0.0,
                rate: 2.5,
            },
        );
        let mut nu = [0.0; 3];
        c.nu(&Local::default(), &mut nu);
        assert_eq!(nu[0], 2.5);
    }
}
