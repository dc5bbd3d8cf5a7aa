//! Finite-difference checks of a constraint's analytic derivatives.
//!
//! On random configurations z = (q_i, q_j, own) and times t:
//! - Φ_q against central differences of Φ in each coordinate;
//! - ν against −Φ_t by central differences in t;
//! - γ against the second time derivative of Φ along the trajectory
//!   z(τ) = z₀ + v τ + a τ²/2, t = t₀ + τ, using
//!   d²Φ/dτ² = Φ_q a − γ;
//! - η against the time derivative of γ − Φ_q q̈ along the trajectory
//!   z(τ) = z₀ + v τ + a τ²/2 + j τ³/6 with a random jerk j, using
//!   d/dτ (γ − Φ_q z̈) = η − Φ_q j (γ itself being checked against Φ).
//!
//! Differences use Richardson extrapolation, so the tolerance can stay tight.

// Rows, coordinates and own coordinates are indexed in parallel arrays.
#![allow(clippy::needless_range_loop)]

use super::{Equations, Jac, Local, LocalBlock, Rows, LOCAL_COORDS, MAX_OWN};
use crate::constraint::BodyId;

/// Deterministic pseudo-random numbers (SplitMix64) for reproducible checks.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

/// The full local coordinate vector z = (q_i, q_j, own) has this many numbers.
const NZ: usize = LOCAL_COORDS;

fn to_z(x: &Local) -> [f64; NZ] {
    let mut z = [0.0; NZ];
    z[..3].copy_from_slice(&x.q[0]);
    z[3..6].copy_from_slice(&x.q[1]);
    z[6..].copy_from_slice(&x.own);
    z
}

fn from_z(z: &[f64; NZ], t: f64, template: &Local) -> Local {
    let mut x = *template;
    x.t = t;
    x.q[0].copy_from_slice(&z[..3]);
    x.q[1].copy_from_slice(&z[3..6]);
    x.own.copy_from_slice(&z[6..]);
    x
}

fn jac_row(j: &Jac, r: usize) -> [f64; NZ] {
    let mut row = [0.0; NZ];
    row[..3].copy_from_slice(&j.body[0][r]);
    row[3..6].copy_from_slice(&j.body[1][r]);
    row[6..].copy_from_slice(&j.own[r]);
    row
}

/// Mask of the coordinates that move: ground bodies and unused own
/// coordinates stay fixed.
fn moving<C: Equations>(c: &C) -> [bool; NZ] {
    let b = c.bodies();
    let mut m = [false; NZ];
    for k in 0..2 {
        if b[k] != BodyId::GROUND {
            m[3 * k..3 * k + 3].fill(true);
        }
    }
    for o in 0..c.own_count() {
        m[6 + o] = true;
    }
    m
}

/// First derivative of `f` at 0 by Richardson-extrapolated central differences.
fn d1(f: impl Fn(f64) -> Rows, h: f64) -> Rows {
    let c = |h: f64| {
        let (p, m) = (f(h), f(-h));
        [0, 1, 2].map(|r| (p[r] - m[r]) / (2.0 * h))
    };
    let (a, b) = (c(h), c(h / 2.0));
    [0, 1, 2].map(|r| (4.0 * b[r] - a[r]) / 3.0)
}

/// As [`d1`], for a function with one value per local coordinate.
fn d1_vec(f: impl Fn(f64) -> [f64; NZ], h: f64) -> [f64; NZ] {
    let c = |h: f64| {
        let (p, m) = (f(h), f(-h));
        std::array::from_fn(|k| (p[k] - m[k]) / (2.0 * h))
    };
    let (a, b): ([f64; NZ], [f64; NZ]) = (c(h), c(h / 2.0));
    std::array::from_fn(|k| (4.0 * b[k] - a[k]) / 3.0)
}

/// Second derivative of `f` at 0 by Richardson-extrapolated central differences.
fn d2(f: impl Fn(f64) -> Rows, h: f64) -> Rows {
    let f0 = f(0.0);
    let c = |h: f64| {
        let (p, m) = (f(h), f(-h));
        [0, 1, 2].map(|r| (p[r] - 2.0 * f0[r] + m[r]) / (h * h))
    };
    let (a, b) = (c(h), c(h / 2.0));
    [0, 1, 2].map(|r| (4.0 * b[r] - a[r]) / 3.0)
}

fn close(what: &str, kind: &str, r: usize, got: f64, want: f64, x: &Local) {
    let tol = 1e-6 * (1.0 + want.abs().max(got.abs()));
    assert!(
        (got - want).abs() <= tol,
        "{kind}: {what} of equation {r}: analytic {got:.12e}, finite difference {want:.12e} at {x:?}"
    );
}

/// Checks Φ_q, ν, γ and η of `c` at the configuration `x` (velocities in
/// `x.qd`, `x.own_d` are the trajectory's v; its acceleration is `acc`, which
/// η reads from `x.qdd`, `x.own_dd` too; its jerk is `jerk`).
pub(crate) fn check_at<C: Equations>(c: &C, x: &Local, acc: &[f64; NZ], jerk: &[f64; NZ]) {
    let m = c.rows();
    let mask = moving(c);
    let z0 = to_z(x);
    let phi_at = |z: &[f64; NZ], t: f64| {
        let mut out = [0.0; 3];
        c.phi(&from_z(z, t, x), &mut out);
        out
    };
    let mut jac = Jac::default();
    c.jacobian(x, &mut jac);

    // Φ and Φ_q in one evaluation are those of the two, to the last bit.
    let (mut phi, mut phi_both, mut jac_both) = ([0.0; 3], [0.0; 3], Jac::default());
    c.phi(x, &mut phi);
    c.phi_and_jacobian(x, &mut phi_both, &mut jac_both);
    for r in 0..m {
        let (row, row_both) = (jac_row(&jac, r), jac_row(&jac_both, r));
        let pairs = std::iter::once((phi[r], phi_both[r]))
            .chain(row.into_iter().zip(row_both))
            .enumerate();
        for (k, (alone, both)) in pairs {
            assert_eq!(
                alone.to_bits(),
                both.to_bits(),
                "{}: row {r}, {} of phi_and_jacobian is {both:e}, of phi or jacobian {alone:e}",
                c.kind(),
                if k == 0 {
                    "Φ".to_string()
                } else {
                    format!("Φ_q entry {}", k - 1)
                }
            );
        }
    }

    // Φ_q against differences in each coordinate.
    for k in 0..NZ {
        if !mask[k] {
            continue;
        }
        let d = d1(
            |h| {
                let mut z = z0;
                z[k] += h;
                phi_at(&z, x.t)
            },
            1e-4,
        );
        for r in 0..m {
            close("Φ_q column", c.kind(), r, jac_row(&jac, r)[k], d[r], x);
        }
    }

    // Φ_q is exactly zero outside its declared pattern.
    let pattern = c.jacobian_pattern();
    for r in 0..m {
        let row = jac_row(&jac, r);
        for k in 0..NZ {
            assert!(
                pattern[r] & (1 << k) != 0 || row[k] == 0.0,
                "{}: Φ_q entry ({r}, {k}) is {:e}, outside the declared pattern",
                c.kind(),
                row[k]
            );
        }
    }

    // Φ_q does not change with the coordinates Φ is declared linear in.
    let nonlinear = c.nonlinear();
    for k in 0..NZ {
        if !mask[k] || nonlinear & (1 << k) != 0 {
            continue;
        }
        let jac_at = |h: f64| {
            let mut z = z0;
            z[k] += h;
            let mut j = Jac::default();
            c.jacobian(&from_z(&z, x.t, x), &mut j);
            j
        };
        let (p, q) = (jac_at(1e-3), jac_at(-1e-3));
        for r in 0..m {
            let (rp, rq) = (jac_row(&p, r), jac_row(&q, r));
            for col in 0..NZ {
                let what = format!("Φ_q column {col} against linear coordinate {k}");
                close(&what, c.kind(), r, (rp[col] - rq[col]) / 2e-3, 0.0, x);
            }
        }
    }

    // An analytic curvature against differences of λᵀΦ_q.
    let lambda = [0.7, -1.3, 0.4];
    let mut curv: LocalBlock = [[0.0; NZ]; NZ];
    if c.curvature(x, &lambda, &mut curv) {
        for b in 0..NZ {
            if !mask[b] {
                continue;
            }
            let d = d1_vec(
                |h| {
                    let mut z = z0;
                    z[b] += h;
                    let mut j = Jac::default();
                    c.jacobian(&from_z(&z, x.t, x), &mut j);
                    std::array::from_fn(|a| (0..m).map(|r| lambda[r] * jac_row(&j, r)[a]).sum())
                },
                1e-4,
            );
            for a in 0..NZ {
                if mask[a] && nonlinear & (1 << a) != 0 && nonlinear & (1 << b) != 0 {
                    let what = format!("curvature ({a}, {b})");
                    close(&what, c.kind(), 0, curv[a][b], d[a], x);
                }
            }
        }
    }

    // ν = −Φ_t.
    let mut nu = [0.0; 3];
    c.nu(x, &mut nu);
    let dt = d1(|h| phi_at(&z0, x.t + h), 1e-4);
    for r in 0..m {
        close("ν", c.kind(), r, nu[r], -dt[r], x);
    }

    // γ = Φ_q a − d²Φ/dτ² along z(τ) = z₀ + v τ + a τ²/2.
    let mut v = [0.0; NZ];
    v[..3].copy_from_slice(&x.qd[0]);
    v[3..6].copy_from_slice(&x.qd[1]);
    v[6..].copy_from_slice(&x.own_d);
    let mut gamma = [0.0; 3];
    c.gamma(x, &mut gamma);
    let dd = d2(
        |h| {
            let z = std::array::from_fn(|k| z0[k] + v[k] * h + 0.5 * acc[k] * h * h);
            phi_at(&z, x.t + h)
        },
        1e-3,
    );
    for r in 0..m {
        let row = jac_row(&jac, r);
        let jac_a: f64 = (0..NZ).map(|k| row[k] * acc[k]).sum();
        close("γ", c.kind(), r, gamma[r], jac_a - dd[r], x);
    }

    // η = d/dτ (γ − Φ_q z̈) + Φ_q j along z(τ) = z₀ + v τ + a τ²/2 + j τ³/6.
    let mut eta = [0.0; 3];
    c.eta(x, &mut eta);
    let residual = d1(
        |h| {
            let z = std::array::from_fn(|k| {
                z0[k] + v[k] * h + 0.5 * acc[k] * h * h + jerk[k] * h * h * h / 6.0
            });
            let zd: [f64; NZ] = std::array::from_fn(|k| v[k] + acc[k] * h + 0.5 * jerk[k] * h * h);
            let zdd: [f64; NZ] = std::array::from_fn(|k| acc[k] + jerk[k] * h);
            let mut y = from_z(&z, x.t + h, x);
            y.qd = [[zd[0], zd[1], zd[2]], [zd[3], zd[4], zd[5]]];
            y.own_d.copy_from_slice(&zd[6..]);
            let (mut g, mut j) = ([0.0; 3], Jac::default());
            c.gamma(&y, &mut g);
            c.jacobian(&y, &mut j);
            [0, 1, 2].map(|r| {
                let row = jac_row(&j, r);
                g[r] - (0..NZ).map(|k| row[k] * zdd[k]).sum::<f64>()
            })
        },
        1e-4,
    );
    for r in 0..m {
        let row = jac_row(&jac, r);
        let jac_j: f64 = (0..NZ).map(|k| row[k] * jerk[k]).sum();
        close("η", c.kind(), r, eta[r], residual[r] + jac_j, x);
    }
}

/// A random configuration for `c` with its acceleration and jerk: ground
/// bodies at rest at the origin, own coordinates drawn from `own_range`;
/// the acceleration is also in the configuration's `qdd`, `own_dd`.
pub(crate) fn random_local<C: Equations>(
    c: &C,
    rng: &mut Rng,
    own_range: [(f64, f64); MAX_OWN],
) -> (Local, [f64; NZ], [f64; NZ]) {
    let mask = moving(c);
    let mut x = Local {
        t: rng.range(0.0, 2.0),
        ..Local::default()
    };
    for k in 0..2 {
        if mask[3 * k] {
            x.q[k] = [
                rng.range(-2.0, 2.0),
                rng.range(-2.0, 2.0),
                rng.range(-3.1, 3.1),
            ];
            x.qd[k] = [
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
            ];
        }
    }
    for o in 0..c.own_count() {
        x.own[o] = rng.range(own_range[o].0, own_range[o].1);
        x.own_d[o] = rng.range(-2.0, 2.0);
    }
    let acc: [f64; NZ] = std::array::from_fn(|k| if mask[k] { rng.range(-3.0, 3.0) } else { 0.0 });
    x.qdd = [[acc[0], acc[1], acc[2]], [acc[3], acc[4], acc[5]]];
    x.own_dd.copy_from_slice(&acc[6..]);
    let jerk = std::array::from_fn(|k| if mask[k] { rng.range(-3.0, 3.0) } else { 0.0 });
    (x, acc, jerk)
}

/// Checks `c` on `n` random configurations, own coordinates in [−π, π].
pub(crate) fn check_random<C: Equations>(c: &C, n: usize) {
    let pi = std::f64::consts::PI;
    check_random_own(c, n, [(-pi, pi); MAX_OWN]);
}

/// Checks `c` on `n` random configurations with own coordinates drawn from
/// `own_range` (for curves with a limited parameter range).
pub(crate) fn check_random_own<C: Equations>(c: &C, n: usize, own_range: [(f64, f64); MAX_OWN]) {
    let mut rng = Rng::new(0x5EED ^ n as u64);
    for _ in 0..n {
        let (x, acc, jerk) = random_local(c, &mut rng, own_range);
        check_at(c, &x, &acc, &jerk);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::revolute::Revolute;
    use crate::math::rot;

    /// Which derivative a [`Broken`] revolute gets wrong.
    #[derive(Clone, Copy)]
    enum Fault {
        /// γ without the −A_j s'_j φ̇_j² term.
        GammaTerm,
        /// ∂Φ/∂φ_j with the wrong sign.
        JacobianSign,
        /// ν = 1 instead of 0.
        Nu,
        /// Declared linear in φ_j.
        Mask,
        /// Declared without x_j in the x equation.
        Pattern,
        /// Curvature with the wrong sign at (φ_j, φ_j).
        Curvature,
        /// η without the −B_j s'_j φ̇_j³ term.
        EtaTerm,
    }

    /// A revolute joint with one deliberate mistake.
    struct Broken(Revolute, Fault);

    impl Equations for Broken {
        fn kind(&self) -> &'static str {
            "broken_revolute"
        }
        fn equations(&self) -> &'static [&'static str] {
            self.0.equations()
        }
        fn bodies(&self) -> [BodyId; 2] {
            self.0.bodies()
        }
        fn sketch(&self) -> crate::constraint::sketch::Sketch<'_> {
            Vec::new()
        }
        fn joint_points(&self, x: &Local) -> [crate::math::V2; 2] {
            self.0.joint_points(x)
        }
        fn nonlinear(&self) -> crate::constraint::CoordMask {
            match self.1 {
                Fault::Mask => 1 << 2,
                _ => self.0.nonlinear(),
            }
        }
        fn jacobian_pattern(&self) -> [crate::constraint::CoordMask; 3] {
            let mut p = self.0.jacobian_pattern();
            if let Fault::Pattern = self.1 {
                p[0] &= !(1 << 3);
            }
            p
        }
        fn curvature(
            &self,
            x: &Local,
            lambda: &Rows,
            out: &mut crate::constraint::LocalBlock,
        ) -> bool {
            self.0.curvature(x, lambda, out);
            if let Fault::Curvature = self.1 {
                out[5][5] = -out[5][5];
            }
            true
        }
        fn phi(&self, x: &Local, out: &mut Rows) {
            self.0.phi(x, out)
        }
        fn jacobian(&self, x: &Local, out: &mut Jac) {
            self.0.jacobian(x, out);
            if let Fault::JacobianSign = self.1 {
                out.body[1][0][2] = -out.body[1][0][2];
            }
        }
        fn nu(&self, x: &Local, out: &mut Rows) {
            self.0.nu(x, out);
            if let Fault::Nu = self.1 {
                out[0] = 1.0;
            }
        }
        fn eta(&self, x: &Local, out: &mut Rows) {
            self.0.eta(x, out);
            if let Fault::EtaTerm = self.1 {
                let wj = x.qd[1][2];
                let bj = crate::math::rot_d(x.q[1][2], self.0.s_j);
                out[0] -= bj[0] * wj * wj * wj;
                out[1] -= bj[1] * wj * wj * wj;
            }
        }
        fn gamma(&self, x: &Local, out: &mut Rows) {
            self.0.gamma(x, out);
            if let Fault::GammaTerm = self.1 {
                let wj = x.qd[1][2];
                let aj = rot(x.q[1][2], self.0.s_j);
                out[0] += aj[0] * wj * wj;
                out[1] += aj[1] * wj * wj;
            }
        }
    }

    fn broken(fault: Fault) -> Broken {
        let joint = Revolute {
            body_i: BodyId(1),
            s_i: [0.4, -0.2],
            body_j: BodyId(2),
            s_j: [-0.3, 0.7],
        };
        Broken(joint, fault)
    }

    #[test]
    #[should_panic(expected = "γ of equation")]
    fn catches_a_missing_gamma_term() {
        check_random(&broken(Fault::GammaTerm), 10);
    }

    #[test]
    #[should_panic(expected = "Φ_q column of equation")]
    fn catches_a_wrong_jacobian_entry() {
        check_random(&broken(Fault::JacobianSign), 10);
    }

    #[test]
    #[should_panic(expected = "against linear coordinate 5")]
    fn catches_a_wrong_linearity_declaration() {
        check_random(&broken(Fault::Mask), 10);
    }

    #[test]
    #[should_panic(expected = "Φ_q entry (0, 3) is -1e0, outside the declared pattern")]
    fn catches_a_wrong_pattern_declaration() {
        check_random(&broken(Fault::Pattern), 10);
    }

    #[test]
    #[should_panic(expected = "curvature (5, 5)")]
    fn catches_a_wrong_curvature() {
        check_random(&broken(Fault::Curvature), 10);
    }

    /// Φ_q, ν, γ and η of every constraint kind, each with a moving body on
    /// both sides and with the ground as body i and as body j, curve
    /// contacts on polar (expression, Fourier) and parametric (open spline,
    /// closed circle, expression) curves, drivers on every coordinate and
    /// on curve travel.
    #[test]
    fn every_kind_with_ground_on_either_side() {
        use crate::constraint::absolute::{AbsoluteCoord, AbsoluteDistance, Coord};
        use crate::constraint::cam_follower::CamFollower;
        use crate::constraint::composite::{RevoluteRevolute, RevoluteTranslational};
        use crate::constraint::flat_follower::FlatFollower;
        use crate::constraint::gear::{Gear, GearKind, RackPinion};
        use crate::constraint::point_follower::PointFollower;
        use crate::constraint::relative::{RelCoord, RelativeCoord, RelativeDistance};
        use crate::constraint::translational::Translational;
        use crate::constraint::Constraint;
        use crate::curve::{Curve, Parametric, Polar};
        use crate::function::TimeFn;
        use std::sync::Arc;

        let f = || TimeFn::Sine {
            amplitude: 0.4,
            omega: 1.7,
            phase: 0.3,
            offset: 1.2,
        };
        let expr_f = || {
            TimeFn::Expr(Arc::new(
                camlink_expr::Expr::parse("0.3 + t^2/4 + sin(2*t)/5", "t").unwrap(),
            ))
        };
        let lobe: Curve = Polar::expr([0.05, 0.0], "1 + 0.15*cos(2*a) + 0.05*sin(3*a)")
            .unwrap()
            .into();
        let fourier: Curve = Polar::fourier([0.1, -0.05], 1.0, &[0.2, 0.0, 0.05], &[0.1])
            .unwrap()
            .into();
        let open: Curve =
            Parametric::spline(&[[0.0, 0.0], [0.4, 0.2], [0.9, 0.1], [1.3, 0.5]], false)
                .unwrap()
                .into();
        let closed: Curve = Parametric::circle([0.2, 0.0], 0.3, 0.4).unwrap().into();
        let pexpr: Curve = Parametric::expr(
            "0.3*cos(s) + s^3/10",
            "0.2*sin(s) + 0.1*s",
            -1.0,
            2.0,
            false,
        )
        .unwrap()
        .into();
        let (si, sj) = ([0.4, -0.2], [-0.3, 0.7]);
        let pi = std::f64::consts::PI;
        let mut cases: Vec<(Constraint, [(f64, f64); MAX_OWN])> = Vec::new();
        let any = [(-pi, pi); MAX_OWN];
        for (bi, bj) in [
            (BodyId(1), BodyId(2)),
            (BodyId::GROUND, BodyId(2)),
            (BodyId(1), BodyId::GROUND),
        ] {
            cases.push((
                Revolute {
                    body_i: bi,
                    s_i: si,
                    body_j: bj,
                    s_j: sj,
                }
                .into(),
                any,
            ));
            for coord in [
                RelCoord::X,
                RelCoord::Y,
                RelCoord::Phi,
                RelCoord::Along([0.6, -1.1]),
            ] {
                let c = RelativeCoord {
                    body_i: bi,
                    s_i: si,
                    body_j: bj,
                    s_j: sj,
                    coord,
                    f: f(),
                };
                cases.push((c.into(), any));
            }
            let d = RelativeDistance {
                body_i: bi,
                s_i: si,
                body_j: bj,
                s_j: sj,
                f: expr_f(),
            };
            cases.push((d.into(), any));
            let t = Translational {
                body_i: bi,
                s_i: si,
                v_i: [0.8, 0.3],
                body_j: bj,
                s_j: sj,
                angle: 0.25,
            };
            cases.push((t.into(), any));
            let rr = RevoluteRevolute {
                body_i: bi,
                s_i: si,
                body_j: bj,
                s_j: sj,
                length: 1.3,
            };
            cases.push((rr.into(), any));
            let rt = RevoluteTranslational {
                body_i: bi,
                s_i: si,
                body_j: bj,
                s_j: sj,
                v_j: [0.5, -1.2],
                offset: 0.15,
            };
            cases.push((rt.into(), any));
            for kind in [GearKind::External, GearKind::Internal] {
                let g = Gear {
                    body_i: bi,
                    s_i: si,
                    radius_i: 0.5,
                    body_j: bj,
                    s_j: sj,
                    radius_j: 1.25,
                    kind,
                    phase: 0.2,
                };
                cases.push((g.into(), any));
            }
            let rp = RackPinion {
                body_i: bi,
                s_i: si,
                radius: 0.4,
                body_j: bj,
                s_j: sj,
                u_j: [1.0, 0.3],
                phase: 0.1,
            };
            cases.push((rp.into(), any));
            for (ci, cj, range) in [
                (&lobe, &closed, [(-pi, 3.0 * pi), (-2.0, 4.0)]),
                (&fourier, &open, [(-pi, pi), (0.1, 1.4)]),
                (&closed, &pexpr, [(-1.0, 3.0), (-0.9, 1.9)]),
            ] {
                let cf = CamFollower {
                    body_i: bi,
                    curve_i: ci.clone(),
                    body_j: bj,
                    curve_j: cj.clone(),
                };
                cases.push((cf.into(), range));
            }
            for (cam, range) in [
                (&lobe, (-pi, 3.0 * pi)),
                (&open, (0.1, 1.4)),
                (&pexpr, (-0.9, 1.9)),
            ] {
                let ff = FlatFollower::new(bi, cam.clone(), bj, [0.2, -0.3], [1.0, 0.4]).unwrap();
                cases.push((ff.into(), [range; MAX_OWN]));
            }
            for (slot, range) in [
                (&fourier, (-pi, 3.0 * pi)),
                (&open, (0.1, 1.4)),
                (&closed, (-1.0, 3.0)),
                (&pexpr, (-0.9, 1.9)),
            ] {
                cases.push((
                    PointFollower::new(bi, si, bj, slot.clone()).into(),
                    [range; MAX_OWN],
                ));
                let driven = PointFollower {
                    travel: Some(expr_f()),
                    ..PointFollower::new(bi, si, bj, slot.clone())
                };
                cases.push((driven.into(), [range; MAX_OWN]));
            }
        }
        // Absolute constraints hold a body against the ground (body j).
        for coord in [Coord::X, Coord::Y, Coord::Phi] {
            let c = AbsoluteCoord {
                body: BodyId(1),
                s: si,
                coord,
                f: expr_f(),
            };
            cases.push((c.into(), any));
        }
        let d = AbsoluteDistance {
            body: BodyId(1),
            s: si,
            ground_point: [0.3, 1.1],
            f: f(),
        };
        cases.push((d.into(), any));
        let kinds: std::collections::BTreeSet<&str> = cases.iter().map(|(c, _)| c.kind()).collect();
        // The 13 variants of `Constraint`, the point–follower with and without
        // its travel driver.
        assert_eq!(kinds.len(), 14, "{kinds:?}");
        for (c, range) in &cases {
            check_random_own(c, 12, *range);
        }
    }

    #[test]
    #[should_panic(expected = "η of equation")]
    fn catches_a_missing_eta_term() {
        check_random(&broken(Fault::EtaTerm), 10);
    }

    /// η is checked at the trajectory's acceleration: an η that ignores q̈
    /// (the φ̈ terms of a revolute's) is caught too.
    #[test]
    #[should_panic(expected = "η of equation")]
    fn catches_an_eta_that_ignores_the_acceleration() {
        struct NoAcc(Revolute);
        impl Equations for NoAcc {
            fn kind(&self) -> &'static str {
                "revolute_without_acceleration"
            }
            fn equations(&self) -> &'static [&'static str] {
                self.0.equations()
            }
            fn bodies(&self) -> [BodyId; 2] {
                self.0.bodies()
            }
            fn sketch(&self) -> crate::constraint::sketch::Sketch<'_> {
                Vec::new()
            }
            fn joint_points(&self, x: &Local) -> [crate::math::V2; 2] {
                self.0.joint_points(x)
            }
            fn phi(&self, x: &Local, out: &mut Rows) {
                self.0.phi(x, out)
            }
            fn jacobian(&self, x: &Local, out: &mut Jac) {
                self.0.jacobian(x, out)
            }
            fn nu(&self, x: &Local, out: &mut Rows) {
                self.0.nu(x, out)
            }
            fn gamma(&self, x: &Local, out: &mut Rows) {
                self.0.gamma(x, out)
            }
            fn eta(&self, x: &Local, out: &mut Rows) {
                let y = Local {
                    qdd: [[0.0; 3]; 2],
                    ..*x
                };
                self.0.eta(&y, out)
            }
        }
        check_random(&NoAcc(broken(Fault::Nu).0), 10);
    }

    #[test]
    #[should_panic(expected = "ν of equation")]
    fn catches_a_wrong_nu() {
        check_random(&broken(Fault::Nu), 10);
    }
}
