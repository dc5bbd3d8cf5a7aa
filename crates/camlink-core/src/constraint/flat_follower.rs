//! Cam–flat-faced follower: a curve C_i on body i touches the straight face
//! of body j (seed 3.4.2, Haug's Φ^cff(i,j)).
//!
//! The face is the line through point P_j (s′_j in body j's frame) along the
//! unit vector u′_j (body frame). Own coordinate α_i: the contact parameter
//! on C_i (p_i(α_i) in body i's frame, tangent g′_i = dp_i/dα_i). With
//! n = B_j u′_j = (A_j u′_j)⊥ the face normal, A_ij = A_iᵀ A_j and
//! B_ij = A_iᵀ B_j:
//!
//! Φ = [ nᵀ (r_i + A_i p_i − r_j − A_j s′_j)     (contact point on the face, m)
//!       nᵀ A_i g′_i = g′_iᵀ B_ij u′_j ]          (tangent along the face)
//!
//! Φ_q, with d = r_i + A_i p_i − r_j − A_j s′_j and t = A_j u′_j:
//! - row 1: r_i nᵀ = u′_jᵀ B_jᵀ, φ_i p_iᵀ A_ij u′_j, α_i g′_iᵀ B_ij u′_j,
//!   r_j −nᵀ, φ_j −tᵀ d − u′_jᵀ s′_j;
//! - row 2: φ_i g′_iᵀ A_ij u′_j, α_i (g′_i)_αᵢᵀ B_ij u′_j, φ_j −tᵀ A_i g′_i.
//!
//! For a polar profile p_i = s′_Q + ρ u′_i: the seed's errata slide for page
//! 83 corrects s′_P to s′_Q in the φ_i entry of row 1, which the
//! finite-difference tests confirm; its α_i entry of row 2 needs the
//! derivative (g′_i)_αᵢ.
//!
//! ν = 0.
//!
//! γ, from ṅ = −t φ̇_j and n̈* = −n φ̇_j², with * marking velocity-quadratic
//! parts ([`Carried`]):
//! γ = −[ −φ̇_j² nᵀ d + 2 ṅᵀ ḋ + nᵀ (r̈_i^P* − r̈_j^P*) ;
//!        −φ̇_j² nᵀ g_i + 2 ṅᵀ ġ_i + nᵀ g̈_i* ].
//!
//! η = −[ (nᵀd)⃛* ; (nᵀg_i)⃛* ] by Leibniz's rule, n = A_j u′_j⊥ turning with
//! body j and the cam point and tangent from [`carried_paths`] (which needs
//! p⁗), the jerks set to zero ([`motion`](crate::motion)).
//!
//! The follower stays in contact only where the cam is convex: see
//! [`Curve::concave_ranges`](crate::curve::Curve::concave_ranges).

use super::sketch::{CurveRole, Mark, Side, Sketch};
use super::{Equations, Feature, Jac, Local, Rows, MAX_OWN};
use crate::constraint::BodyId;
use crate::curve::contact::{sample_mean, side_of};
use crate::curve::{carried_paths, search, Carried, Curve};
use crate::math::{dot, norm, perp, rot, rot_t, scale, sub, V2};
use crate::motion;
use crate::quantity::Quantity;

#[derive(Clone, Debug)]
pub struct FlatFollower {
    pub body_i: BodyId,
    /// C_i, the cam, in body i's frame.
    pub curve_i: Curve,
    pub body_j: BodyId,
    /// s′_j: a point P_j of the face in body j's frame (m).
    pub s_j: V2,
    /// u′_j: the unit direction of the face in body j's frame.
    pub u_j: V2,
}

impl FlatFollower {
    /// A cam–flat-faced follower; `u_j` is normalized. `None` when `u_j`
    /// is zero or not finite.
    pub fn new(body_i: BodyId, curve_i: Curve, body_j: BodyId, s_j: V2, u_j: V2) -> Option<Self> {
        let l = norm(u_j);
        (l > 0.0 && l.is_finite()).then(|| FlatFollower {
            body_i,
            curve_i,
            body_j,
            s_j,
            u_j: scale(1.0 / l, u_j),
        })
    }

    /// Contact point on C_i, face point P_j, face direction t and normal n.
    #[inline]
    fn parts(&self, x: &Local) -> (Carried, Carried, V2, V2) {
        let a = Carried::new(x.q[0], x.qd[0], &self.curve_i.jet(x.own[0]), x.own_d[0]);
        let b = Carried::fixed(x.q[1], x.qd[1], self.s_j);
        let t = rot(x.q[1][2], self.u_j);
        (a, b, t, perp(t))
    }
}

impl Equations for FlatFollower {
    fn kind(&self) -> &'static str {
        "flat-follower"
    }

    fn equations(&self) -> &'static [&'static str] {
        &["normal", "tangent"]
    }

    fn bodies(&self) -> [BodyId; 2] {
        [self.body_i, self.body_j]
    }

    fn contact_sides(&self) -> Option<[Feature<'_>; 2]> {
        Some([Feature::Curve(&self.curve_i), Feature::Face(self.u_j)])
    }

    fn sketch(&self) -> Sketch<'_> {
        vec![
            Mark::Curve {
                side: Side::I,
                curve: &self.curve_i,
                role: CurveRole::Cam,
            },
            Mark::Face {
                side: Side::J,
                s: self.s_j,
                u: self.u_j,
            },
        ]
    }

    fn joint_points(&self, x: &Local) -> [V2; 2] {
        let p = self.curve_i.jet(x.own[0]).p;
        [p, x.on_j(p)]
    }

    fn own_count(&self) -> usize {
        1
    }

    fn own_names(&self) -> &'static [&'static str] {
        &["alpha_i"]
    }

    fn own_quantity(&self, _k: usize) -> Quantity {
        self.curve_i.parameter_quantity()
    }

    /// The support point of C_i toward the face: the cam point extreme in
    /// the direction of the face normal pointing from the cam's side (the
    /// side of the mean of its sampled points) to the face. Refined from
    /// the guess when there is one.
    fn initial_own(&self, x: &Local, guess: Option<[f64; MAX_OWN]>) -> [f64; MAX_OWN] {
        let n = perp(rot(x.q[1][2], self.u_j));
        let face = Carried::fixed(x.q[1], [0.0; 3], self.s_j).p;
        let guess = guess.map(|g| g[0]);
        // The cam's side of the face.
        let mean = Carried::fixed(x.q[0], [0.0; 3], sample_mean(&self.curve_i)).p;
        let side = side_of(n, face, mean);
        let dir = rot_t(x.q[0][2], scale(-side, n));
        let mut own = [0.0; MAX_OWN];
        own[0] = search::support(&self.curve_i, dir, guess);
        own
    }

    fn phi(&self, x: &Local, out: &mut Rows) {
        let (a, b, _, n) = self.parts(x);
        out[0] = dot(n, sub(a.p, b.p));
        out[1] = dot(n, a.g);
        out[2] = 0.0;
    }

    fn jacobian(&self, x: &Local, out: &mut Jac) {
        let (a, b, t, n) = self.parts(x);
        let d = sub(a.p, b.p);
        *out = Jac::default();
        // Contact point on the face line.
        out.body[0][0] = [n[0], n[1], dot(n, a.p_phi)];
        out.own[0][0] = dot(n, a.g);
        out.body[1][0] = [-n[0], -n[1], -dot(t, d) - dot(n, b.p_phi)];
        // Tangent along the face.
        out.body[0][1] = [0.0, 0.0, dot(n, a.g_phi)];
        out.own[1][0] = dot(n, a.g_s);
        out.body[1][1] = [0.0, 0.0, -dot(t, a.g)];
    }

    fn nu(&self, _x: &Local, out: &mut Rows) {
        *out = [0.0; 3];
    }

    fn gamma(&self, x: &Local, out: &mut Rows) {
        let (a, b, t, n) = self.parts(x);
        let w = x.qd[1][2];
        let nd = scale(-w, t);
        let d = sub(a.p, b.p);
        let dd = sub(a.v, b.v);
        out[0] = w * w * dot(n, d) - 2.0 * dot(nd, dd) - dot(n, sub(a.p_quad, b.p_quad));
        out[1] = w * w * dot(n, a.g) - 2.0 * dot(nd, a.gd) - dot(n, a.g_quad);
        out[2] = 0.0;
    }

    fn eta(&self, x: &Local, out: &mut Rows) {
        let ji = self.curve_i.jet4(x.own[0]);
        let (pi, gi) = carried_paths(x.q[0], x.qd[0], x.qdd[0], &ji, x.own_path(0));
        let d = motion::sub(&pi, &x.point_path(1, self.s_j));
        let n = x.vector_path(1, perp(self.u_j));
        out[0] = -motion::dot(&n, &d)[3];
        out[1] = -motion::dot(&n, &gi)[3];
        out[2] = 0.0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::check::check_random_own;
    use crate::curve::{Parametric, Polar};
    use crate::math::point;
    use std::f64::consts::{FRAC_PI_2, PI, TAU};

    #[test]
    fn derivatives_match_finite_differences_polar() {
        let c = FlatFollower::new(
            BodyId(1),
            Polar::fourier([0.1, 0.05], 1.0, &[0.15, 0.05], &[0.0, 0.03])
                .unwrap()
                .into(),
            BodyId(2),
            [0.2, -0.3],
            [1.0, 0.4],
        )
        .unwrap();
        check_random_own(&c, 40, [(-TAU, 2.0 * TAU); MAX_OWN]);
    }

    #[test]
    fn derivatives_match_finite_differences_parametric() {
        let c = FlatFollower::new(
            BodyId::GROUND,
            Parametric::spline(&[[0.0, 0.0], [0.5, 0.4], [1.0, 0.3], [1.4, 0.9]], false)
                .unwrap()
                .into(),
            BodyId(1),
            [0.0, 0.1],
            [0.0, 1.0],
        )
        .unwrap();
        check_random_own(&c, 30, [(0.1, 1.5); MAX_OWN]);
        let c = FlatFollower::new(
            BodyId(2),
            Parametric::circle([0.2, 0.0], 0.7, 1.0).unwrap().into(),
            BodyId(1),
            [0.0, 0.1],
            [1.0, 0.0],
        )
        .unwrap();
        check_random_own(&c, 30, [(-5.0, 10.0); MAX_OWN]);
    }

    #[test]
    fn support_point_and_lift_of_an_eccentric_circle() {
        // Eccentric circular cam (radius 1, centre e = 0.3 from the pivot)
        // on body 1 turned by φ; horizontal face above it on body 2. The
        // contact lies straight above the circle's centre, and the face
        // height is e sin(φ) + 1: the lift of an eccentric cam.
        let e = 0.3;
        let c = FlatFollower::new(
            BodyId(1),
            Polar::circle([e, 0.0], 1.0).unwrap().into(),
            BodyId(2),
            [0.0, 0.0],
            [1.0, 0.0],
        )
        .unwrap();
        for &phi in &[0.0, 0.6, 2.0, -1.0] {
            let mut x = Local::default();
            x.q[0] = [0.0, 0.0, phi];
            x.q[1] = [0.4, 1.5, 0.0];
            let own = c.initial_own(&x, None);
            let want = (FRAC_PI_2 - phi).rem_euclid(TAU);
            assert!((own[0] - want).abs() < 1e-8, "{phi}: {own:?} vs {want}");
            let p = point(x.q[0], c.curve_i.jet(own[0]).p);
            assert!((p[1] - (e * phi.sin() + 1.0)).abs() < 1e-12);
            let mut f = [0.0; 3];
            c.phi(&Local { own, ..x }, &mut f);
            assert!(f[1].abs() < 1e-8, "{f:?}");
        }
        // A face below the cam touches its bottom.
        let mut x = Local::default();
        x.q[1] = [0.0, -2.0, 0.0];
        let own = c.initial_own(&x, None);
        assert!((own[0] - 1.5 * PI).abs() < 1e-8, "{own:?}");
    }

    #[test]
    fn initial_own_refines_a_guess_on_a_lobed_cam() {
        // Two-lobe cam ρ = 1 + 0.2 cos 2α turned by π/2 under a face: the
        // lobe tip α = 0 points at the face. A guess one turn on is refined
        // to the tip one turn on, not wrapped.
        let c = FlatFollower::new(
            BodyId(1),
            Polar::fourier([0.0, 0.0], 1.0, &[0.0, 0.2], &[])
                .unwrap()
                .into(),
            BodyId(2),
            [0.0, 0.0],
            [1.0, 0.0],
        )
        .unwrap();
        let mut x = Local::default();
        x.q[0] = [0.0, 0.0, FRAC_PI_2];
        x.q[1] = [0.0, 1.5, 0.0];
        let own = c.initial_own(&x, None)[0];
        assert!(own.abs() < 1e-9 || (own - TAU).abs() < 1e-9, "{own}");
        let own = c.initial_own(&x, Some([TAU + 0.3, 0.0]));
        assert!((own[0] - TAU).abs() < 1e-9, "{own:?}");
    }

    #[test]
    fn rejects_a_zero_face_direction() {
        let cam: Curve = Polar::circle([0.0, 0.0], 1.0).unwrap().into();
        assert!(FlatFollower::new(BodyId(1), cam, BodyId(2), [0.0; 2], [0.0; 2]).is_none());
    }
}
