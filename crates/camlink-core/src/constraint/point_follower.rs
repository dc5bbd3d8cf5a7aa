//! Point–follower (pin in slot): point P_i of body i runs along a curve C_j
//! of body j (seed 3.4.3, Haug's Φ^pf(i,j)).
//!
//! Own coordinate α_j: the parameter of the pin's place on C_j (for a polar
//! slot the seed's angle α_j, p_j = s′_Q + ρ u′_j; for a parametric slot its
//! length parameter). With p_j(α_j) in body j's frame, g′_j = dp_j/dα_j:
//!
//! Φ = r_i + A_i s′_i − r_j − A_j p_j(α_j)      (2 equations, m)
//! Φ_q = [I  B_i s′_i | −I  −B_j p_j | −A_j g′_j]   (q_i | q_j | α_j)
//! ν = 0
//! γ = A_i s′_i φ̇_i² − A_j (p_j φ̇_j² − 2 g′_j⊥ φ̇_j α̇_j − (g′_j)_α α̇_j²)
//!
//! η = −(r⃛_i^P* − r⃛_j^P*) with the jerks set to zero: the pin as a body
//! point, the slot point from [`carried_paths`] ([`motion`](crate::motion)).
//!
//! γ is the revolute joint's with the moving point's extra terms: the
//! Coriolis term 2 B_j g′_j φ̇_j α̇_j and the curvature term A_j p″_j α̇_j².
//!
//! Travel driver (optional): the pin's place on the slot prescribed as a
//! function of time, "travel along a curve = f(t)", adds a third equation
//!
//! Φ₃ = α_j − f(t),   Φ₃_q = [0 | 0 | 1],   ν₃ = f′(t),   γ₃ = f″(t),
//! η₃ = f‴(t),
//!
//! in the unit of α_j (rad on a polar slot, m of length on a line, arc,
//! circle or spline slot, the user's parameter on an expression slot).

use super::sketch::{CurveRole, Mark, Side, Sketch};
use super::{Equations, Feature, Jac, Local, Rows, MAX_OWN};
use crate::constraint::BodyId;
use crate::curve::{carried_paths, search, Carried, Curve};
use crate::function::TimeFn;
use crate::math::{rot_t, sub, V2};
use crate::quantity::Quantity;

#[derive(Clone, Debug)]
pub struct PointFollower {
    pub body_i: BodyId,
    /// s′_i: the pin P_i in body i's frame (m).
    pub s_i: V2,
    pub body_j: BodyId,
    /// C_j, the slot, in body j's frame.
    pub curve_j: Curve,
    /// f(t): when present, α_j = f(t) drives the pin along the slot.
    pub travel: Option<TimeFn>,
}

impl PointFollower {
    /// An undriven pin in a slot.
    pub fn new(body_i: BodyId, s_i: V2, body_j: BodyId, curve_j: Curve) -> Self {
        PointFollower {
            body_i,
            s_i,
            body_j,
            curve_j,
            travel: None,
        }
    }

    #[inline]
    fn parts(&self, x: &Local) -> (Carried, Carried) {
        (
            Carried::fixed(x.q[0], x.qd[0], self.s_i),
            Carried::new(x.q[1], x.qd[1], &self.curve_j.jet(x.own[0]), x.own_d[0]),
        )
    }
}

impl Equations for PointFollower {
    fn kind(&self) -> &'static str {
        match self.travel {
            None => "point-follower",
            Some(_) => "driven point-follower",
        }
    }

    fn equations(&self) -> &'static [&'static str] {
        match self.travel {
            None => &["x", "y"],
            Some(_) => &["x", "y", "travel"],
        }
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn contact_sides(&self) -> Option<[Feature<'_>; 2]> {
        Some([Feature::Point(self.s_i), Feature::Curve(&self.curve_j)])
    }

    fn sketch(&self) -> Sketch<'_> {
        vec![
            Mark::Curve {
                side: Side::J,
                curve: &self.curve_j,
                role: CurveRole::Slot,
            },
            Mark::Slider {
                side: Side::I,
                s: self.s_i,
            },
        ]
    }

    fn joint_points(&self, x: &Local) -> [V2; 2] {
        [self.s_i, x.on_j(self.s_i)]
    }

    fn own_count(&self) -> usize {
        1
    }

    fn own_names(&self) -> &'static [&'static str] {
        &["alpha_j"]
    }

    fn own_quantity(&self, _k: usize) -> Quantity {
        self.curve_j.parameter_quantity()
    }

    fn driven_quantity(&self) -> Quantity {
        self.curve_j.parameter_quantity()
    }

    /// The point of C_j nearest to the pin; refined from the guess when
    /// there is one. A driven pin starts at α_j = f(0).
    fn initial_own(&self, x: &Local, guess: Option<[f64; MAX_OWN]>) -> [f64; MAX_OWN] {
        if let Some(f) = &self.travel {
            let mut own = [0.0; MAX_OWN];
            own[0] = f.value(x.t);
            return own;
        }
        let pin = Carried::fixed(x.q[0], [0.0; 3], self.s_i).p;
        let local = rot_t(x.q[1][2], sub(pin, [x.q[1][0], x.q[1][1]]));
        let guess = guess.map(|g| g[0]);
        let mut own = [0.0; MAX_OWN];
        own[0] = search::closest(&self.curve_j, local, guess);
        own
    }

    fn phi(&self, x: &Local, out: &mut Rows) {
        let (a, b) = self.parts(x);
        out[0] = a.p[0] - b.p[0];
        out[1] = a.p[1] - b.p[1];
        out[2] = match &self.travel {
            Some(f) => x.own[0] - f.value(x.t),
            None => 0.0,
        };
    }

    fn jacobian(&self, x: &Local, out: &mut Jac) {
        let (a, b) = self.parts(x);
        *out = Jac::default();
        for r in 0..2 {
            out.body[0][r][r] = 1.0;
            out.body[0][r][2] = a.p_phi[r];
            out.body[1][r][r] = -1.0;
            out.body[1][r][2] = -b.p_phi[r];
            out.own[r][0] = -b.g[r];
        }
        // Travel driver.
        if self.travel.is_some() {
            out.own[2][0] = 1.0;
        }
    }

    fn nu(&self, x: &Local, out: &mut Rows) {
        *out = [0.0; 3];
        if let Some(f) = &self.travel {
            out[2] = f.jet(x.t)[1];
        }
    }

    fn gamma(&self, x: &Local, out: &mut Rows) {
        let (a, b) = self.parts(x);
        out[0] = b.p_quad[0] - a.p_quad[0];
        out[1] = b.p_quad[1] - a.p_quad[1];
        out[2] = match &self.travel {
            Some(f) => f.jet(x.t)[2],
            None => 0.0,
        };
    }

    fn eta(&self, x: &Local, out: &mut Rows) {
        let jj = self.curve_j.jet4(x.own[0]);
        let (pj, _) = carried_paths(x.q[1], x.qd[1], x.qdd[1], &jj, x.own_path(0));
        let d = crate::motion::sub(&x.point_path(0, self.s_i), &pj);
        out[0] = -d[3][0];
        out[1] = -d[3][1];
        out[2] = match &self.travel {
            Some(f) => f.jet(x.t)[3],
            None => 0.0,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::check::check_random_own;
    use crate::curve::{Parametric, Polar};
    use crate::math::{norm, point};
    use std::f64::consts::{PI, TAU};

    #[test]
    fn derivatives_match_finite_differences_polar_slot() {
        let c = PointFollower {
            body_i: BodyId(1),
            s_i: [0.3, -0.2],
            body_j: BodyId(2),
            curve_j: Polar::fourier([0.1, 0.0], 1.0, &[0.1, 0.2], &[0.05])
                .unwrap()
                .into(),
            travel: None,
        };
        check_random_own(&c, 40, [(-TAU, 2.0 * TAU); MAX_OWN]);
    }

    #[test]
    fn derivatives_match_finite_differences_parametric_slots() {
        let slots: [Curve; 3] = [
            Parametric::line([0.0, 0.0], [1.0, 0.5]).unwrap().into(),
            Parametric::arc([0.2, 0.1], 0.8, -0.5, 1.5).unwrap().into(),
            Parametric::spline(
                &[[0.0, 0.0], [0.3, 0.5], [0.8, 0.6], [1.2, 0.2], [1.5, -0.1]],
                false,
            )
            .unwrap()
            .into(),
        ];
        for slot in slots {
            let (s0, s1) = slot.range();
            let c = PointFollower {
                body_i: BodyId(2),
                s_i: [0.1, 0.4],
                body_j: BodyId(1),
                curve_j: slot,
                travel: None,
            };
            let m = 0.05 * (s1 - s0);
            check_random_own(&c, 25, [(s0 + m, s1 - m); MAX_OWN]);
        }
        let c = PointFollower {
            body_i: BodyId(1),
            s_i: [0.1, 0.4],
            body_j: BodyId::GROUND,
            curve_j: Parametric::spline(&[[1.0, 0.0], [0.0, 1.0], [-1.0, 0.2], [0.0, -0.8]], true)
                .unwrap()
                .into(),
            travel: None,
        };
        check_random_own(&c, 25, [(-4.0, 12.0); MAX_OWN]);
    }

    #[test]
    fn travel_driver_derivatives_match_finite_differences() {
        let f = camlink_expr::Expr::parse("0.2 + 0.3*t + 0.1*sin(2*t)", "t").unwrap();
        let slots: [Curve; 2] = [
            Polar::fourier([0.1, 0.0], 1.0, &[0.1, 0.2], &[0.05])
                .unwrap()
                .into(),
            Parametric::spline(&[[0.0, 0.0], [0.3, 0.5], [0.8, 0.6], [1.2, 0.2]], false)
                .unwrap()
                .into(),
        ];
        for slot in slots {
            let mut c = PointFollower::new(BodyId(1), [0.1, 0.4], BodyId(2), slot);
            c.travel = Some(TimeFn::from(f.clone()));
            assert_eq!(c.rows(), 3);
            check_random_own(&c, 25, [(0.2, 1.0); MAX_OWN]);
        }
    }

    #[test]
    fn a_driven_pin_starts_at_f_of_zero() {
        let mut c = PointFollower::new(
            BodyId(1),
            [0.0, 0.0],
            BodyId::GROUND,
            Parametric::line([0.0, 0.0], [2.0, 0.0]).unwrap().into(),
        );
        c.travel = Some(TimeFn::Linear {
            value: 0.5,
            rate: 1.0,
        });
        let x = Local::default();
        assert_eq!(c.initial_own(&x, None)[0], 0.5);
        let mut f = [0.0; 3];
        c.phi(
            &Local {
                t: 1.0,
                own: [1.25, 0.0],
                ..x
            },
            &mut f,
        );
        assert!((f[2] + 0.25).abs() < 1e-15, "{f:?}");
    }

    #[test]
    fn pin_in_circular_slot_keeps_its_distance() {
        // A pin at the centre of a roller (r = 0.25) in a ground "slot"
        // that is the circle R + r = 1.25 about Q: the pin stays at 1.25
        // from Q, like a distance constraint; solved for (x, α_j) at fixed y.
        let c = PointFollower {
            body_i: BodyId(1),
            s_i: [0.0, 0.0],
            body_j: BodyId::GROUND,
            curve_j: Polar::circle([0.3, 0.2], 1.25).unwrap().into(),
            travel: None,
        };
        let y = 0.9;
        let mut x = Local::default();
        x.q[0] = [1.5, y, 0.4];
        x.own = c.initial_own(&x, None);
        for _ in 0..30 {
            let (mut f, mut jac) = ([0.0; 3], Jac::default());
            c.phi(&x, &mut f);
            c.jacobian(&x, &mut jac);
            let (a, b, cc, d) = (
                jac.body[0][0][0],
                jac.own[0][0],
                jac.body[0][1][0],
                jac.own[1][0],
            );
            let det = a * d - b * cc;
            x.q[0][0] -= (f[0] * d - b * f[1]) / det;
            x.own[0] -= (a * f[1] - cc * f[0]) / det;
        }
        let dist = norm(sub([x.q[0][0], y], [0.3, 0.2]));
        assert!((dist - 1.25).abs() < 1e-12, "{dist}");
    }

    #[test]
    fn initial_own_is_the_nearest_slot_point() {
        let c = PointFollower {
            body_i: BodyId(1),
            s_i: [0.0, 0.1],
            body_j: BodyId(2),
            curve_j: Polar::circle([0.0, 0.0], 1.0).unwrap().into(),
            travel: None,
        };
        let mut x = Local::default();
        x.q[0] = [-2.0, 0.0, 0.0];
        x.q[1] = [0.0, 0.0, 0.5];
        let own = c.initial_own(&x, None);
        let pin = point(x.q[0], c.s_i);
        let want = (pin[1].atan2(pin[0]) - 0.5).rem_euclid(TAU);
        assert!((own[0] - want).abs() < 1e-9, "{own:?} {want}");
        // From a guess one turn on: the same point, one turn on.
        let own = c.initial_own(&x, Some([want + TAU + 0.2, 0.0]));
        assert!((own[0] - want - TAU).abs() < 1e-9, "{own:?}");
        // Open slot: beyond its end, the end.
        let c = PointFollower {
            curve_j: Parametric::arc([0.0, 0.0], 1.0, 0.0, PI / 2.0)
                .unwrap()
                .into(),
            ..c
        };
        let own = c.initial_own(&x, None);
        assert!(
            (own[0] - PI / 2.0).abs() < 1e-12 || own[0].abs() < 1e-12,
            "{own:?}"
        );
    }
}
