//! Absolute constraints of one body against the ground, and their drivers.
//!
//! With r_i^P = r_i + A_i s'_i:
//! - coordinate x: Φ = x_i^P − f(t); y: Φ = y_i^P − f(t); φ: Φ = φ_i − f(t);
//! - distance: Φ = (r_i^P − C)ᵀ(r_i^P − C) − f(t)², C a ground point.
//!
//! A constant f makes a joint; a function of t makes a driver.
//!
//! Derivatives, with e = r_i^P − C and ė = ṙ_i + B_i s'_i φ̇_i:
//! - x, y: Φ_q = [1 0 (B_i s'_i)_x] or [0 1 (B_i s'_i)_y], ν = f',
//!   γ = (A_i s'_i)_{x,y} φ̇_i² + f'';
//! - φ: Φ_q = [0 0 1], ν = f', γ = f'';
//! - distance: Φ_q = 2eᵀ[I  B_i s'_i], ν = 2 f f',
//!   γ = −2ėᵀė + 2 φ̇_i² eᵀA_i s'_i + 2(f'² + f f'').
//!
//! η = −d³Φ/dt³ with the jerks set to zero ([`motion`](crate::motion)),
//! with r⃛^P* = −3 A_i s'_i φ̇_i φ̈_i − B_i s'_i φ̇_i³:
//! - x, y: η = −(r⃛^P*)_{x,y} + f‴; φ: η = f‴;
//! - distance: η = −2(eᵀr⃛^P* + 3ėᵀë) + 2f f‴ + 6f′f″.
//!
//! Body j of the [`Local`] view is the ground.

use super::sketch::Sketch;
use super::{CoordMask, Equations, Jac, Local, Rows, MAX_ROWS};
use crate::constraint::BodyId;
use crate::function::TimeFn;
use crate::math::{dot, point, point_vel, rot, rot_d, sub, V2};
use crate::motion;
use crate::quantity::Quantity;

/// Which coordinate a coordinate constraint holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coord {
    X,
    Y,
    Phi,
}

/// x, y (of point P) or φ of one body equals f(t).
#[derive(Clone, Debug)]
pub struct AbsoluteCoord {
    pub body: BodyId,
    /// s'_P: the point in the body frame (m); unused for φ.
    pub s: V2,
    pub coord: Coord,
    /// f(t) in m or rad.
    pub f: TimeFn,
}

/// Distance from body point P to ground point C equals f(t) (m).
#[derive(Clone, Debug)]
pub struct AbsoluteDistance {
    pub body: BodyId,
    /// s'_P (m).
    pub s: V2,
    /// C in the global frame (m).
    pub ground_point: V2,
    pub f: TimeFn,
}

impl Equations for AbsoluteCoord {
    fn check_functions(&self, x: &Local) -> Result<(), String> {
        self.f.check(x.t)
    }

    fn kind(&self) -> &'static str {
        "absolute_coordinate"
    }

    fn driven_quantity(&self) -> Quantity {
        match self.coord {
            Coord::Phi => Quantity::Angle,
            Coord::X | Coord::Y => Quantity::Length,
        }
    }

    fn equations(&self) -> &'static [&'static str] {
        match self.coord {
            Coord::X => &["x"],
            Coord::Y => &["y"],
            Coord::Phi => &["phi"],
        }
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body, BodyId::GROUND]
    }

    fn sketch(&self) -> Sketch<'_> {
        Vec::new()
    }

    fn joint_points(&self, x: &Local) -> [V2; 2] {
        [self.s, x.on_j(self.s)]
    }

    /// φ_i for a point coordinate; nothing for the angle.
    fn nonlinear(&self) -> CoordMask {
        match self.coord {
            Coord::X | Coord::Y => 1 << 2,
            Coord::Phi => 0,
        }
    }

    /// The coordinate itself and φ_i.
    fn jacobian_pattern(&self) -> [CoordMask; MAX_ROWS] {
        let row = match self.coord {
            Coord::X => 0b101,
            Coord::Y => 0b110,
            Coord::Phi => 0b100,
        };
        [row, 0, 0]
    }

    fn phi(&self, x: &Local, out: &mut Rows) {
        let value = match self.coord {
            Coord::X => point(x.q[0], self.s)[0],
            Coord::Y => point(x.q[0], self.s)[1],
            Coord::Phi => x.q[0][2],
        };
        *out = [value - self.f.value(x.t), 0.0, 0.0];
    }

    fn jacobian(&self, x: &Local, out: &mut Jac) {
        *out = Jac::default();
        let b = rot_d(x.q[0][2], self.s);
        out.body[0][0] = match self.coord {
            Coord::X => [1.0, 0.0, b[0]],
            Coord::Y => [0.0, 1.0, b[1]],
            Coord::Phi => [0.0, 0.0, 1.0],
        };
    }

    fn nu(&self, x: &Local, out: &mut Rows) {
        *out = [self.f.jet(x.t)[1], 0.0, 0.0];
    }

    fn gamma(&self, x: &Local, out: &mut Rows) {
        let w = x.qd[0][2];
        let a = rot(x.q[0][2], self.s);
        let centripetal = match self.coord {
            Coord::X => a[0] * w * w,
            Coord::Y => a[1] * w * w,
            Coord::Phi => 0.0,
        };
        *out = [centripetal + self.f.jet(x.t)[2], 0.0, 0.0];
    }

    fn eta(&self, x: &Local, out: &mut Rows) {
        let p = x.point_path(0, self.s);
        let jerk = match self.coord {
            Coord::X => p[3][0],
            Coord::Y => p[3][1],
            Coord::Phi => 0.0,
        };
        *out = [self.f.jet(x.t)[3] - jerk, 0.0, 0.0];
    }
}

impl Equations for AbsoluteDistance {
    fn driver_slope(&self, t: f64) -> f64 {
        -2.0 * self.f.value(t)
    }

    fn check_functions(&self, x: &Local) -> Result<(), String> {
        self.f.check(x.t)
    }

    fn kind(&self) -> &'static str {
        "absolute_distance"
    }

    fn equations(&self) -> &'static [&'static str] {
        &["distance"]
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body, BodyId::GROUND]
    }

    fn sketch(&self) -> Sketch<'_> {
        Vec::new()
    }

    fn joint_points(&self, _x: &Local) -> [V2; 2] {
        [self.s, self.ground_point]
    }

    fn phi(&self, x: &Local, out: &mut Rows) {
        let e = sub(point(x.q[0], self.s), self.ground_point);
        let f = self.f.value(x.t);
        *out = [dot(e, e) - f * f, 0.0, 0.0];
    }

    fn jacobian(&self, x: &Local, out: &mut Jac) {
        let e = sub(point(x.q[0], self.s), self.ground_point);
        let b = rot_d(x.q[0][2], self.s);
        *out = Jac::default();
        out.body[0][0] = [2.0 * e[0], 2.0 * e[1], 2.0 * dot(e, b)];
    }

    fn nu(&self, x: &Local, out: &mut Rows) {
        let [f, f_d, ..] = self.f.jet(x.t);
        *out = [2.0 * f * f_d, 0.0, 0.0];
    }

    fn gamma(&self, x: &Local, out: &mut Rows) {
        let w = x.qd[0][2];
        let e = sub(point(x.q[0], self.s), self.ground_point);
        let e_d = point_vel(x.q[0], x.qd[0], self.s);
        let a = rot(x.q[0][2], self.s);
        let [f, f_d, f_dd, _] = self.f.jet(x.t);
        *out = [
            -2.0 * dot(e_d, e_d) + 2.0 * w * w * dot(e, a) + 2.0 * (f_d * f_d + f * f_dd),
            0.0,
            0.0,
        ];
    }

    fn eta(&self, x: &Local, out: &mut Rows) {
        let e = motion::sub(
            &x.point_path(0, self.s),
            &motion::constant(self.ground_point),
        );
        let (ee, ff) = (motion::dot(&e, &e), motion::square(self.f.jet(x.t)));
        *out = [ff[3] - ee[3], 0.0, 0.0];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::check::check_random;

    fn sine() -> TimeFn {
        TimeFn::Sine {
            amplitude: 0.5,
            omega: 2.1,
            phase: -0.4,
            offset: 0.8,
        }
    }

    fn coord(coord: Coord, f: TimeFn) -> AbsoluteCoord {
        AbsoluteCoord {
            body: BodyId(1),
            s: [0.6, -0.35],
            coord,
            f,
        }
    }

    #[test]
    fn coordinates_match_finite_differences() {
        for c in [Coord::X, Coord::Y, Coord::Phi] {
            check_random(&coord(c, sine()), 30);
            check_random(&coord(c, (-0.3).into()), 10);
            let linear = TimeFn::Linear {
                value: 0.2,
                rate: -1.5,
            };
            check_random(&coord(c, linear), 10);
        }
    }

    #[test]
    fn distance_matches_finite_differences() {
        let c = AbsoluteDistance {
            body: BodyId(1),
            s: [0.6, -0.35],
            ground_point: [0.3, 1.1],
            f: sine(),
        };
        check_random(&c, 40);
    }

    #[test]
    fn values_at_a_known_configuration() {
        // Body at (1, 2) turned by π: P = (1, 2) − (0.6, −0.35) = (0.4, 2.35).
        let x = Local {
            t: 0.5,
            q: [[1.0, 2.0, std::f64::consts::PI], [0.0; 3]],
            ..Local::default()
        };
        let mut out = [0.0; 3];
        coord(Coord::X, 0.4.into()).phi(&x, &mut out);
        assert!(out[0].abs() < 1e-12);
        coord(Coord::Y, 2.0.into()).phi(&x, &mut out);
        assert!((out[0] - 0.35).abs() < 1e-12);
        let linear = TimeFn::Linear {
            value: 1.0,
            rate: 2.0,
        };
        coord(Coord::Phi, linear).phi(&x, &mut out);
        assert!((out[0] - (std::f64::consts::PI - 2.0)).abs() < 1e-12);
        let c = AbsoluteDistance {
            body: BodyId(1),
            s: [0.6, -0.35],
            ground_point: [0.4, -0.65],
            f: 1.0.into(),
        };
        c.phi(&x, &mut out);
        assert!((out[0] - (3.0 * 3.0 - 1.0)).abs() < 1e-12);
    }

    #[test]
    fn driver_velocity_and_acceleration() {
        // A point at radius 0.5 on a body spinning at 2 rad/s about the origin:
        // γ of its x-driver is the centripetal term A s' φ̇² plus f''.
        let x = Local {
            t: 0.3,
            q: [[0.0, 0.0, 0.0], [0.0; 3]],
            qd: [[0.0, 0.0, 2.0], [0.0; 3]],
            ..Local::default()
        };
        let c = AbsoluteCoord {
            body: BodyId(1),
            s: [0.5, 0.0],
            coord: Coord::X,
            f: sine(),
        };
        let [_, f_d, f_dd, _] = sine().jet(0.3);
        let (mut nu, mut gamma) = ([0.0; 3], [0.0; 3]);
        c.nu(&x, &mut nu);
        c.gamma(&x, &mut gamma);
        assert_eq!(nu[0], f_d);
        assert!((gamma[0] - (0.5 * 4.0 + f_dd)).abs() < 1e-12);
    }
}
