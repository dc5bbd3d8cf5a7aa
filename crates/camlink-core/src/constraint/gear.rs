//! Gear pair and rack-and-pinion: rolling of pitch circles without slip.
//!
//! Gear pair (own coordinate θ, the angle of the centre line from P_i to P_j
//! in the global frame, so that it stays continuous when a carrier turns):
//! Φ₁ = u(θ)⊥ᵀ (r_j^P − r_i^P)                         (centre line along u(θ))
//! Φ₂ = R_i(φ_i − θ) + R_j(φ_j − θ) − c                 (external)
//! Φ₂ = R_i(φ_i − θ) − R_j(φ_j − θ) − c                 (internal; j is the ring)
//! The centre distance itself is held by other joints (pivots, a carrier).
//!
//! With u = (cos θ, sin θ), d = r_j^P − r_i^P, ± = + external, − internal:
//! Φ₁_q = [−u⊥ᵀ  −u⊥ᵀB_i s'_i | u⊥ᵀ  u⊥ᵀB_j s'_j],  Φ₁_θ = −uᵀd;
//! Φ₂_q = [0 0 R_i | 0 0 ±R_j],  Φ₂_θ = −(R_i ± R_j);
//! ν = 0;
//! γ₁ = u⊥ᵀd θ̇² + 2 θ̇ uᵀḋ + u⊥ᵀ(A_j s'_j φ̇_j² − A_i s'_i φ̇_i²),  γ₂ = 0;
//! η₁ = −(u⊥ᵀd)⃛* by the product rule, u⊥ = A(θ)(0, 1) turning with θ̇, θ̈
//! ([`motion`](crate::motion)); η₂ = 0.
//! With fixed centres θ is constant and Φ₂ gives ω_j = ∓(R_i/R_j) ω_i: an
//! external pair turns the other way, an internal pair the same way.
//!
//! Rack and pinion (pinion centre P_i, radius R; rack pitch line through Q_j
//! along u'_j; the pinion lies to the left of u_j):
//! Φ = (A_j u'_j)ᵀ (r_i^P − r_j^Q) + R(φ_i − φ_j) − c.
//! The first term is the axis projection of `relative.rs` with a = j, b = i,
//! w' = u'_j (giving Φ_q, γ and η); the second adds R and −R to the φ
//! columns and nothing to γ or η; ν = 0.
//! Rolling towards +u_j turns the pinion clockwise: travel = −R Δ(φ_i − φ_j).
//! u'_j is normalised when the equation is evaluated, so c is in metres
//! whatever the length of the given vector (which must not be zero).

use std::f64::consts::TAU;

use super::relative::{
    projection_eta, projection_gamma, projection_jac, projection_phi, rel, rel_path, rel_vel, unit,
};
use super::sketch::{Mark, Side, Sketch};
use super::{Equations, Jac, Local, Rows, MAX_OWN};
use crate::constraint::BodyId;
use crate::math::{dot, perp, point, rot, rot_d, scale, sub, V2};
use crate::motion;
use crate::quantity::Quantity;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GearKind {
    External,
    Internal,
}

#[derive(Clone, Debug)]
pub struct Gear {
    pub body_i: BodyId,
    /// Centre P_i of gear i in body i (m).
    pub s_i: V2,
    /// Pitch radius R_i (m).
    pub radius_i: f64,
    pub body_j: BodyId,
    pub s_j: V2,
    pub radius_j: f64,
    pub kind: GearKind,
    /// Phase constant c (m), so the initial placement satisfies Φ₂.
    pub phase: f64,
}

#[derive(Clone, Debug)]
pub struct RackPinion {
    /// The pinion.
    pub body_i: BodyId,
    pub s_i: V2,
    /// Pitch radius R (m).
    pub radius: f64,
    /// The rack.
    pub body_j: BodyId,
    /// Q_j on the pitch line (m).
    pub s_j: V2,
    /// u'_j along the rack (unit vector).
    pub u_j: V2,
    /// Phase constant c (m).
    pub phase: f64,
}

impl Gear {
    /// The sign of R_j in Φ₂: +1 external, −1 internal.
    fn sign(&self) -> f64 {
        match self.kind {
            GearKind::External => 1.0,
            GearKind::Internal => -1.0,
        }
    }

    /// θ = atan2 of the centre line from P_i to P_j for bodies at `qi` and
    /// `qj` = (x, y, φ), in (−π, π] (rad); 0 when the centres coincide.
    pub(crate) fn centre_line_angle(&self, qi: [f64; 3], qj: [f64; 3]) -> f64 {
        let d = sub(point(qj, self.s_j), point(qi, self.s_i));
        d[1].atan2(d[0])
    }

    /// c = R_i(φ_i − θ) ± R_j(φ_j − θ) (m): the phase for which bodies at
    /// `qi`, `qj` with centre-line angle `theta` satisfy Φ₂.
    pub(crate) fn phase_at(&self, qi: [f64; 3], qj: [f64; 3], theta: f64) -> f64 {
        self.radius_i * (qi[2] - theta) + self.sign() * self.radius_j * (qj[2] - theta)
    }

    /// The phase c for the placement `qi`, `qj`, with θ from
    /// [`Gear::centre_line_angle`], the value [`Equations::initial_own`]
    /// picks from a zero guess.
    pub fn phase_from(&self, qi: [f64; 3], qj: [f64; 3]) -> f64 {
        self.phase_at(qi, qj, self.centre_line_angle(qi, qj))
    }
}

impl Equations for Gear {
    fn kind(&self) -> &'static str {
        "gear"
    }

    fn equations(&self) -> &'static [&'static str] {
        &["centre_line", "rolling"]
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn sketch(&self) -> Sketch<'_> {
        vec![
            Mark::Circle {
                side: Side::I,
                s: self.s_i,
                radius: self.radius_i,
                internal: false,
            },
            Mark::Circle {
                side: Side::J,
                s: self.s_j,
                radius: self.radius_j,
                internal: matches!(self.kind, GearKind::Internal),
            },
        ]
    }

    fn joint_points(&self, _x: &Local) -> [V2; 2] {
        [self.s_i, self.s_j]
    }

    fn own_count(&self) -> usize {
        1
    }

    fn own_names(&self) -> &'static [&'static str] {
        &["theta"]
    }

    fn own_quantity(&self, _k: usize) -> Quantity {
        Quantity::Angle
    }

    /// θ from the current centre line, on the branch θ + 2πk nearest the
    /// guess (0 without one), so θ stays continuous; the guess is kept when
    /// the centres coincide.
    fn initial_own(&self, x: &Local, guess: Option<[f64; MAX_OWN]>) -> [f64; MAX_OWN] {
        let d = rel(x, self.s_i, self.s_j);
        let mut own = guess.unwrap_or_default();
        if d != [0.0, 0.0] {
            let theta = d[1].atan2(d[0]);
            own[0] = theta + TAU * ((own[0] - theta) / TAU).round_ties_even();
        }
        own
    }

    fn phi(&self, x: &Local, out: &mut Rows) {
        let theta = x.own[0];
        let u_perp = perp(rot(theta, [1.0, 0.0]));
        let d = rel(x, self.s_i, self.s_j);
        out[0] = dot(u_perp, d);
        out[1] = self.phase_at(x.q[0], x.q[1], theta) - self.phase;
        out[2] = 0.0;
    }

    fn jacobian(&self, x: &Local, out: &mut Jac) {
        let theta = x.own[0];
        let u = rot(theta, [1.0, 0.0]);
        let u_perp = perp(u);
        let d = rel(x, self.s_i, self.s_j);
        let bi = rot_d(x.q[0][2], self.s_i);
        let bj = rot_d(x.q[1][2], self.s_j);
        let (ri, rj) = (self.radius_i, self.sign() * self.radius_j);
        *out = Jac::default();
        // Centre line.
        out.body[0][0] = [-u_perp[0], -u_perp[1], -dot(u_perp, bi)];
        out.body[1][0] = [u_perp[0], u_perp[1], dot(u_perp, bj)];
        out.own[0][0] = -dot(u, d);
        // Rolling.
        out.body[0][1] = [0.0, 0.0, ri];
        out.body[1][1] = [0.0, 0.0, rj];
        out.own[1][0] = -(ri + rj);
    }

    fn nu(&self, _x: &Local, out: &mut Rows) {
        *out = [0.0; 3];
    }

    fn gamma(&self, x: &Local, out: &mut Rows) {
        let (theta, theta_d) = (x.own[0], x.own_d[0]);
        let u = rot(theta, [1.0, 0.0]);
        let u_perp = perp(u);
        let d = rel(x, self.s_i, self.s_j);
        let d_d = rel_vel(x, self.s_i, self.s_j);
        let (wi, wj) = (x.qd[0][2], x.qd[1][2]);
        let centripetal = sub(
            scale(wj * wj, rot(x.q[1][2], self.s_j)),
            scale(wi * wi, rot(x.q[0][2], self.s_i)),
        );
        out[0] = dot(u_perp, d) * theta_d * theta_d
            + 2.0 * theta_d * dot(u, d_d)
            + dot(u_perp, centripetal);
        out[1] = 0.0;
        out[2] = 0.0;
    }

    fn eta(&self, x: &Local, out: &mut Rows) {
        let u_perp = motion::rotated(x.own_path(0), &motion::constant([0.0, 1.0]));
        let d = rel_path(x, self.s_i, self.s_j);
        out[0] = -motion::dot(&u_perp, &d)[3];
        out[1] = 0.0;
        out[2] = 0.0;
    }
}

impl RackPinion {
    /// c = (A_j u'_j)ᵀ(r_i^P − r_j^Q) + R(φ_i − φ_j) (m): the phase for which
    /// the pinion at `qi` and the rack at `qj` = (x, y, φ) satisfy Φ.
    pub fn phase_from(&self, qi: [f64; 3], qj: [f64; 3]) -> f64 {
        let x = Local {
            q: [qi, qj],
            ..Local::default()
        };
        projection_phi(&x, 1, self.s_j, unit(self.u_j), self.s_i) + self.radius * (qi[2] - qj[2])
    }
}

impl Equations for RackPinion {
    fn kind(&self) -> &'static str {
        "rack_pinion"
    }

    fn equations(&self) -> &'static [&'static str] {
        &["rolling"]
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn sketch(&self) -> Sketch<'_> {
        vec![
            Mark::Circle {
                side: Side::I,
                s: self.s_i,
                radius: self.radius,
                internal: false,
            },
            Mark::Face {
                side: Side::J,
                s: self.s_j,
                u: self.u_j,
            },
        ]
    }

    fn joint_points(&self, x: &Local) -> [V2; 2] {
        [self.s_i, x.on_j(self.s_i)]
    }

    fn phi(&self, x: &Local, out: &mut Rows) {
        let travel = projection_phi(x, 1, self.s_j, unit(self.u_j), self.s_i);
        let turn = self.radius * (x.q[0][2] - x.q[1][2]);
        *out = [travel + turn - self.phase, 0.0, 0.0];
    }

    fn jacobian(&self, x: &Local, out: &mut Jac) {
        *out = Jac::default();
        let [ji, jj] = projection_jac(x, 1, self.s_j, unit(self.u_j), self.s_i);
        out.body[0][0] = ji;
        out.body[1][0] = jj;
        out.body[0][0][2] += self.radius;
        out.body[1][0][2] -= self.radius;
    }

    fn nu(&self, _x: &Local, out: &mut Rows) {
        *out = [0.0; 3];
    }

    fn gamma(&self, x: &Local, out: &mut Rows) {
        let g = projection_gamma(x, 1, self.s_j, unit(self.u_j), self.s_i);
        *out = [g, 0.0, 0.0];
    }

    fn eta(&self, x: &Local, out: &mut Rows) {
        let e = projection_eta(x, 1, self.s_j, unit(self.u_j), self.s_i);
        *out = [e, 0.0, 0.0];
    }
}

// The hand assembly indexes rows and columns of several arrays in parallel.
#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;
    use crate::constraint::absolute::{AbsoluteCoord, Coord};
    use crate::constraint::check::check_random;
    use crate::constraint::revolute::Revolute;
    use crate::function::TimeFn;

    /// A hand-assembled system: moving body k ≥ 1 owns columns 3(k−1)..3k,
    /// constraint c's own coordinates start at column `own_col[c]`.
    struct System<'a> {
        cs: Vec<&'a dyn Equations>,
        own_col: Vec<usize>,
    }

    impl System<'_> {
        fn local(&self, c: usize, q: &[f64], qd: &[f64]) -> Local {
            let mut x = Local::default();
            for (k, b) in self.cs[c].bodies().into_iter().enumerate() {
                if !b.is_ground() {
                    let at = 3 * (b.0 - 1);
                    x.q[k].copy_from_slice(&q[at..at + 3]);
                    x.qd[k].copy_from_slice(&qd[at..at + 3]);
                }
            }
            for o in 0..self.cs[c].own_count() {
                x.own[o] = q[self.own_col[c] + o];
                x.own_d[o] = qd[self.own_col[c] + o];
            }
            x
        }

        /// The largest |Φ| over all equations.
        fn residual(&self, q: &[f64]) -> f64 {
            let mut worst = 0.0_f64;
            for c in 0..self.cs.len() {
                let mut out = [0.0; 3];
                self.cs[c].phi(&self.local(c, q, &vec![0.0; q.len()]), &mut out);
                for v in &out[..self.cs[c].rows()] {
                    worst = worst.max(v.abs());
                }
            }
            worst
        }

        /// q̇ from Φ_q q̇ = ν (the system must be square and regular).
        fn velocities(&self, q: &[f64]) -> Vec<f64> {
            let n = q.len();
            let mut a = vec![vec![0.0; n + 1]; n];
            let mut row = 0;
            for c in 0..self.cs.len() {
                let x = self.local(c, q, &vec![0.0; n]);
                let (mut jac, mut nu) = (Jac::default(), [0.0; 3]);
                self.cs[c].jacobian(&x, &mut jac);
                self.cs[c].nu(&x, &mut nu);
                for r in 0..self.cs[c].rows() {
                    for (k, b) in self.cs[c].bodies().into_iter().enumerate() {
                        if !b.is_ground() {
                            for col in 0..3 {
                                a[row][3 * (b.0 - 1) + col] += jac.body[k][r][col];
                            }
                        }
                    }
                    for o in 0..self.cs[c].own_count() {
                        a[row][self.own_col[c] + o] += jac.own[r][o];
                    }
                    a[row][n] = nu[r];
                    row += 1;
                }
            }
            assert_eq!(row, n, "the test system must be square");
            solve(a)
        }
    }

    /// Gaussian elimination with partial pivoting on an augmented matrix.
    fn solve(mut a: Vec<Vec<f64>>) -> Vec<f64> {
        let n = a.len();
        for k in 0..n {
            let p = (k..n)
                .max_by(|&r, &s| a[r][k].abs().total_cmp(&a[s][k].abs()))
                .unwrap();
            a.swap(k, p);
            assert!(a[k][k].abs() > 1e-12, "singular test system");
            for r in k + 1..n {
                let m = a[r][k] / a[k][k];
                for c in k..=n {
                    a[r][c] -= m * a[k][c];
                }
            }
        }
        let mut x = vec![0.0; n];
        for k in (0..n).rev() {
            let s: f64 = (k + 1..n).map(|c| a[k][c] * x[c]).sum();
            x[k] = (a[k][n] - s) / a[k][k];
        }
        x
    }

    fn gear(kind: GearKind, body_i: BodyId, body_j: BodyId) -> Gear {
        Gear {
            body_i,
            s_i: [0.3, -0.1],
            radius_i: 0.5,
            body_j,
            s_j: [-0.2, 0.4],
            radius_j: 1.25,
            kind,
            phase: 0.2,
        }
    }

    #[test]
    fn gear_matches_finite_differences() {
        for kind in [GearKind::External, GearKind::Internal] {
            check_random(&gear(kind, BodyId(1), BodyId(2)), 40);
            check_random(&gear(kind, BodyId::GROUND, BodyId(2)), 20);
            check_random(&gear(kind, BodyId(1), BodyId::GROUND), 20);
        }
    }

    /// Gears on fixed pivots at `ci` and `cj`, gear i driven at 1 rad/s:
    /// returns (ω_i, ω_j, θ̇).
    fn fixed_centre_rates(kind: GearKind, ci: V2, cj: V2) -> (f64, f64, f64) {
        let g0 = gear(kind, BodyId(1), BodyId(2));
        // Bodies turned by 0.4 and −1.1 rad, their gear centres on the pivots.
        let place = |c: V2, s: V2, phi: f64| {
            let a = rot(phi, s);
            [c[0] - a[0], c[1] - a[1], phi]
        };
        let (qi, qj) = (place(ci, g0.s_i, 0.4), place(cj, g0.s_j, -1.1));
        let g = Gear {
            phase: g0.phase_from(qi, qj),
            ..g0.clone()
        };
        let pivot_i = Revolute {
            body_i: BodyId(1),
            s_i: g.s_i,
            body_j: BodyId::GROUND,
            s_j: ci,
        };
        let pivot_j = Revolute {
            body_i: BodyId(2),
            s_i: g.s_j,
            body_j: BodyId::GROUND,
            s_j: cj,
        };
        let motor = AbsoluteCoord {
            body: BodyId(1),
            s: [0.0, 0.0],
            coord: Coord::Phi,
            f: TimeFn::Linear {
                value: 0.4,
                rate: 1.0,
            },
        };
        let sys = System {
            cs: vec![&pivot_i, &pivot_j, &g, &motor],
            own_col: vec![0, 0, 6, 0],
        };
        let theta = g.centre_line_angle(qi, qj);
        let q = [qi.as_slice(), qj.as_slice(), &[theta]].concat();
        assert!(sys.residual(&q) < 1e-12);
        let qd = sys.velocities(&q);
        (qd[2], qd[5], qd[6])
    }

    #[test]
    fn external_pair_turns_the_other_way_at_the_radius_ratio() {
        let (wi, wj, wt) = fixed_centre_rates(GearKind::External, [0.1, 0.2], [1.1, 1.4]);
        assert!(
            (wj / wi + 0.5 / 1.25).abs() < 1e-12,
            "ω_j/ω_i = {}",
            wj / wi
        );
        assert!(wt.abs() < 1e-12);
    }

    #[test]
    fn internal_pair_turns_the_same_way_at_the_radius_ratio() {
        // Pinion i inside ring j, centres 0.75 apart.
        let (wi, wj, wt) = fixed_centre_rates(GearKind::Internal, [0.45, -0.6], [0.0, 0.0]);
        assert!(
            (wj / wi - 0.5 / 1.25).abs() < 1e-12,
            "ω_j/ω_i = {}",
            wj / wi
        );
        assert!(wt.abs() < 1e-12);
    }

    #[test]
    fn planet_on_fixed_sun_turns_at_carrier_ratio() {
        // Sun (ground, radius R_s at the origin), carrier (body 1) pivoted at
        // the origin, planet (body 2, radius R_p) pivoted on the carrier.
        let (rs, rp, alpha) = (0.8_f64, 0.3_f64, 0.9_f64);
        let arm = rs + rp;
        let mesh = Gear {
            body_i: BodyId::GROUND,
            s_i: [0.0, 0.0],
            radius_i: rs,
            body_j: BodyId(2),
            s_j: [0.0, 0.0],
            radius_j: rp,
            kind: GearKind::External,
            phase: 0.0,
        };
        let carrier_pivot = Revolute {
            body_i: BodyId(1),
            s_i: [0.0, 0.0],
            body_j: BodyId::GROUND,
            s_j: [0.0, 0.0],
        };
        let planet_pivot = Revolute {
            body_i: BodyId(1),
            s_i: [arm, 0.0],
            body_j: BodyId(2),
            s_j: [0.0, 0.0],
        };
        let motor = AbsoluteCoord {
            body: BodyId(1),
            s: [0.0, 0.0],
            coord: Coord::Phi,
            f: TimeFn::Linear {
                value: alpha,
                rate: 1.0,
            },
        };
        let sys = System {
            cs: vec![&carrier_pivot, &planet_pivot, &mesh, &motor],
            own_col: vec![0, 0, 6, 0],
        };
        // φ_planet = θ (R_s + R_p)/R_p with θ the carrier angle, phase 0.
        let q_planet = [arm * alpha.cos(), arm * alpha.sin(), alpha * arm / rp];
        assert!(mesh.phase_from([0.0; 3], q_planet).abs() < 1e-12);
        let q = [
            0.0,
            0.0,
            alpha,
            q_planet[0],
            q_planet[1],
            q_planet[2],
            alpha,
        ];
        assert!(sys.residual(&q) < 1e-12);
        let qd = sys.velocities(&q);
        assert!((qd[2] - 1.0).abs() < 1e-12);
        assert!((qd[5] - arm / rp).abs() < 1e-12, "ω_planet = {}", qd[5]);
        assert!((qd[6] - 1.0).abs() < 1e-12, "θ̇ = {}", qd[6]);
    }

    #[test]
    fn initial_own_keeps_the_branch_of_the_guess() {
        let g = gear(GearKind::External, BodyId(1), BodyId(2));
        // Centre line at −3.1 rad, just past −π.
        let ci = point([0.0; 3], g.s_i);
        let mut x = Local::default();
        x.q[1] = [
            ci[0] + (-3.1_f64).cos() - g.s_j[0],
            ci[1] + (-3.1_f64).sin() - g.s_j[1],
            0.0,
        ];
        assert!((g.initial_own(&x, None)[0] + 3.1).abs() < 1e-12);
        let guess = |a: f64| Some([a, 0.0]);
        assert!((g.initial_own(&x, guess(3.0))[0] - (TAU - 3.1)).abs() < 1e-12);
        let near = -3.1 + 2.0 * TAU;
        assert!((g.initial_own(&x, guess(near + 0.5))[0] - near).abs() < 1e-12);
    }

    fn rack(body_i: BodyId, body_j: BodyId) -> RackPinion {
        RackPinion {
            body_i,
            s_i: [0.3, -0.1],
            radius: 0.4,
            body_j,
            s_j: [-0.2, 0.5],
            u_j: [0.9, 0.2],
            phase: -0.3,
        }
    }

    #[test]
    fn rack_matches_finite_differences() {
        check_random(&rack(BodyId(1), BodyId(2)), 40);
        check_random(&rack(BodyId::GROUND, BodyId(2)), 20);
        check_random(&rack(BodyId(1), BodyId::GROUND), 20);
    }

    #[test]
    fn pinion_on_fixed_rack_travels_minus_r_per_radian() {
        // Rack: ground, pitch line y = 0 along +x. Pinion: body 1, centre at
        // its origin, held at height R by a y-constraint, driven at 1 rad/s.
        let r = 0.4;
        let c0 = RackPinion {
            body_i: BodyId(1),
            s_i: [0.0, 0.0],
            radius: r,
            body_j: BodyId::GROUND,
            s_j: [0.0, 0.0],
            u_j: [1.0, 0.0],
            phase: 0.0,
        };
        let q0 = [0.7, r, 0.2];
        let c = RackPinion {
            phase: c0.phase_from(q0, [0.0; 3]),
            ..c0
        };
        let height = AbsoluteCoord {
            body: BodyId(1),
            s: [0.0, 0.0],
            coord: Coord::Y,
            f: r.into(),
        };
        let motor = AbsoluteCoord {
            body: BodyId(1),
            s: [0.0, 0.0],
            coord: Coord::Phi,
            f: TimeFn::Linear {
                value: 0.2,
                rate: 1.0,
            },
        };
        let sys = System {
            cs: vec![&height, &c, &motor],
            own_col: vec![0; 3],
        };
        assert!(sys.residual(&q0) < 1e-12);
        // Turning by Δφ moves the centre by −R Δφ.
        let delta = 0.9;
        let moved = [q0[0] - r * delta, r, q0[2] + delta];
        let mut out = [0.0; 3];
        c.phi(
            &Local {
                q: [moved, [0.0; 3]],
                ..Local::default()
            },
            &mut out,
        );
        assert!(out[0].abs() < 1e-12);
        let qd = sys.velocities(&q0);
        assert!((qd[0] + r).abs() < 1e-12 && qd[1].abs() < 1e-12);
    }
}
