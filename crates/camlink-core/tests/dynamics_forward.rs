//! Forward dynamics: pendulum period, energy conservation, a slider-crank
//! against an independent minimal-coordinate solution, measured order of
//! convergence.

use crate::mechanisms;

use camlink_core::dynamics::integrator::{run, Adaptive, Integrator, Settings};
use camlink_core::force::tsda::Tsda;
use camlink_core::force::Force;
use camlink_core::run::{time_grid, Table};
use camlink_core::{BodyId, Model, TimeFn};
use mechanisms::{
    chain, pendulum, slider_crank, CRANK, CRANK_CENTROID, INERTIA, MASS, ROD, ROD_CENTROID,
};

const G: f64 = 9.81;

fn settings(h: f64, rho_inf: f64) -> Settings {
    Settings {
        step: h,
        rho_inf,
        ..Settings::default()
    }
}

/// Zero up-crossings of a series, linearly interpolated (s).
fn up_crossings(t: &[f64], x: &[f64]) -> Vec<f64> {
    (1..x.len())
        .filter(|&k| x[k - 1] < 0.0 && x[k] >= 0.0)
        .map(|k| t[k - 1] + (t[k] - t[k - 1]) * (-x[k - 1]) / (x[k] - x[k - 1]))
        .collect()
}

/// T = 2π √((J + m l²)/(m g l)) for a small swing, whichever frame the body has.
#[test]
fn small_amplitude_pendulum_period() {
    let (l, m, j, th0) = (0.5, 1.2, 0.02, 0.01);
    let want = 2.0 * std::f64::consts::PI * ((j + m * l * l) / (m * G * l)).sqrt();
    for at_pivot in [false, true] {
        let model = pendulum(l, m, j, th0, at_pivot);
        let times = time_grid(3.0 * want, 1e-3).unwrap();
        let mut table = Table::default();
        run(&model, &times, &settings(1e-3, 1.0), &[], &mut table).unwrap();
        let phi = table.channel("bob.phi").unwrap();
        let up = up_crossings(&table.t, &phi);
        assert!(up.len() >= 2, "{up:?}");
        let period = (up[up.len() - 1] - up[0]) / (up.len() - 1) as f64;
        // Finite amplitude lengthens the period by θ₀²/16 ≈ 6e-6.
        let rel = (period - want).abs() / want;
        eprintln!("pendulum (frame at pivot: {at_pivot}): period {period:.6} s vs {want:.6} s, relative error {rel:.1e}");
        assert!(rel < 2e-5, "period {period} vs {want}");
    }
}

/// Energy of a three-link chain falling from the horizontal, with no
/// physical damping: its error is that of a second-order method — largest
/// when the chain whips, divided by about 4 when h is halved, and back to
/// almost nothing afterwards (no secular drift). ρ∞ = 0.9 damps only
/// frequencies near 1/h. The constraints stay satisfied to the Newton
/// tolerance.
#[test]
fn energy_is_conserved_without_damping() {
    let model = chain(3, 0.3);
    let mut worst = [0.0; 2];
    for (k, h) in [1e-3, 5e-4].into_iter().enumerate() {
        let times = time_grid(2.0, h).unwrap();
        let mut table = Table::default();
        run(&model, &times, &settings(h, 0.9), &[], &mut table).unwrap();
        let e = table.channel("energy.total").unwrap();
        let ke = table.channel("energy.kinetic").unwrap();
        let scale = ke.iter().fold(0.0f64, |a, v| a.max(*v));
        worst[k] = e.iter().map(|v| (v - e[0]).abs()).fold(0.0, f64::max) / scale;
        let end = (e[e.len() - 1] - e[0]).abs() / scale;
        let res = table.channel("constraint.residual").unwrap();
        let phi = res.iter().fold(0.0f64, |a, v| a.max(*v));
        eprintln!(
            "chain, h = {h}: largest energy error {:.2e}, at t = 2 s {end:.1e} (of the peak kinetic energy {scale:.3} J); max |Φ| {phi:.1e}",
            worst[k]
        );
        assert!(end < 1e-5, "energy error at the end {end}");
        assert!(phi < 1e-9, "constraint drift {phi}");
    }
    assert!(worst[0] < 2.5e-3, "{worst:?}");
    assert!(worst[1] < worst[0] / 3.5, "second order: {worst:?}");
}

// ---------------------------------------------------------------------------
// The slider-crank in one coordinate θ (crank angle), by Lagrange's
// equation, m(θ) θ̈ + ½ m'(θ) θ̇² = Q(θ), with positions as second-order
// jets of θ and RK4 in time.

/// (f, f', f'') with respect to θ.
#[derive(Clone, Copy, Debug)]
struct J2(f64, f64, f64);

impl J2 {
    fn c(v: f64) -> J2 {
        J2(v, 0.0, 0.0)
    }
    fn add(self, o: J2) -> J2 {
        J2(self.0 + o.0, self.1 + o.1, self.2 + o.2)
    }
    fn sub(self, o: J2) -> J2 {
        J2(self.0 - o.0, self.1 - o.1, self.2 - o.2)
    }
    fn mul(self, o: J2) -> J2 {
        J2(
            self.0 * o.0,
            self.1 * o.0 + self.0 * o.1,
            self.2 * o.0 + 2.0 * self.1 * o.1 + self.0 * o.2,
        )
    }
    /// g(f) for g, g', g'' at f.
    fn chain(self, g: f64, g1: f64, g2: f64) -> J2 {
        J2(g, g1 * self.1, g2 * self.1 * self.1 + g1 * self.2)
    }
    fn sin(self) -> J2 {
        self.chain(self.0.sin(), self.0.cos(), -self.0.sin())
    }
    fn cos(self) -> J2 {
        self.chain(self.0.cos(), -self.0.sin(), -self.0.cos())
    }
    fn asin(self) -> J2 {
        let s = 1.0 - self.0 * self.0;
        self.chain(self.0.asin(), 1.0 / s.sqrt(), self.0 / s.powf(1.5))
    }
    fn sqrt(self) -> J2 {
        let r = self.0.sqrt();
        self.chain(r, 0.5 / r, -0.25 / (r * r * r))
    }
}

/// Spring on the slider: ground point, stiffness, free length.
const SPRING: ([f64; 2], f64, f64) = ([0.6, 0.1], 200.0, 0.25);

/// Each body's centroid (x, y) and angle as jets of θ.
fn bodies(th: f64) -> [([J2; 2], J2); 3] {
    let t = J2(th, 1.0, 0.0);
    let (a, b) = (J2::c(CRANK), J2::c(ROD));
    // Crank: frame at O, φ = θ.
    let (c1, s1) = (t.cos(), t.sin());
    let rot = |c: J2, s: J2, v: [f64; 2]| {
        [
            c.mul(J2::c(v[0])).sub(s.mul(J2::c(v[1]))),
            s.mul(J2::c(v[0])).add(c.mul(J2::c(v[1]))),
        ]
    };
    let crank = rot(c1, s1, CRANK_CENTROID);
    // Rod: sin ψ = −a sin θ / b, from B = a (cos θ, sin θ).
    let psi = J2::c(0.0).sub(a.mul(s1).mul(J2::c(1.0 / ROD))).asin();
    let (c2, s2) = (psi.cos(), psi.sin());
    let bx = a.mul(c1);
    let by = a.mul(s1);
    let r = rot(c2, s2, [ROD / 2.0 + ROD_CENTROID[0], ROD_CENTROID[1]]);
    let rod = [bx.add(r[0]), by.add(r[1])];
    // Slider: x = a cos θ + b cos ψ.
    let xs = bx.add(b.mul(c2));
    [(crank, t), (rod, psi), ([xs, J2::c(0.0)], J2::c(0.0))]
}

/// (θ̇, θ̈) from Lagrange's equation.
fn rhs(th: f64, w: f64) -> (f64, f64) {
    let mut mass = 0.0;
    let mut quad = 0.0;
    let mut q = 0.0;
    for (k, (r, phi)) in bodies(th).iter().enumerate() {
        let (m, j) = (MASS[k], INERTIA[k]);
        mass += m * (r[0].1 * r[0].1 + r[1].1 * r[1].1) + j * phi.1 * phi.1;
        quad += m * (r[0].1 * r[0].2 + r[1].1 * r[1].2) + j * phi.1 * phi.2;
        q += -m * G * r[1].1;
    }
    // Spring from the ground point to the slider pin: Q = −k (l − l₀) l'.
    let (p, k, l0) = SPRING;
    let xs = bodies(th)[2].0[0];
    let dx = xs.sub(J2::c(p[0]));
    let l = dx.mul(dx).add(J2::c(p[1] * p[1])).sqrt();
    q += -k * (l.0 - l0) * l.1;
    (w, (q - quad * w * w) / mass)
}

/// θ(t) and the slider x(t) at the times `every` steps of h, by RK4.
pub(crate) fn reference(th0: f64, w0: f64, t_end: f64, h: f64) -> (f64, f64) {
    let (mut th, mut w) = (th0, w0);
    let n = (t_end / h).round() as usize;
    for _ in 0..n {
        let (k1, l1) = rhs(th, w);
        let (k2, l2) = rhs(th + 0.5 * h * k1, w + 0.5 * h * l1);
        let (k3, l3) = rhs(th + 0.5 * h * k2, w + 0.5 * h * l2);
        let (k4, l4) = rhs(th + h * k3, w + h * l3);
        th += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        w += h / 6.0 * (l1 + 2.0 * l2 + 2.0 * l3 + l4);
    }
    (th, bodies(th)[2].0[0].0)
}

/// The free slider-crank with gravity and the spring, started with
/// consistent velocities for crank speed ω₀.
pub(crate) fn free_slider_crank(th0: f64, w0: f64) -> Model {
    let mut m = slider_crank(th0, w0, false);
    let [_, rod, slider] = bodies(th0);
    // Rod frame origin: its centroid minus the centroid offset, as a jet.
    let psi = rod.1;
    let off = ROD_CENTROID;
    let (cs, sn) = (psi.0.cos(), psi.0.sin());
    let dorigin = [
        rod.0[0].1 - (-sn * off[0] - cs * off[1]) * psi.1,
        rod.0[1].1 - (cs * off[0] - sn * off[1]) * psi.1,
    ];
    m.bodies[2].qd0 = [dorigin[0] * w0, dorigin[1] * w0, psi.1 * w0];
    m.bodies[3].qd0 = [slider.0[0].1 * w0, 0.0, 0.0];
    let (p, k, l0) = SPRING;
    m.add_force(Force::new(
        "spring",
        Tsda {
            body_i: BodyId::GROUND,
            s_i: p,
            body_j: BodyId(3),
            s_j: [0.0, 0.0],
            stiffness: k,
            free_length: l0,
            damping: 0.0,
            actuator: TimeFn::Const(0.0),
        },
    ));
    m
}

pub(crate) const TH0: f64 = 0.3;
pub(crate) const W0: f64 = 10.0;

fn slider_x(model: &Model, t_end: f64, s: Settings) -> (f64, f64, usize) {
    let mut it = Integrator::new(model, s).unwrap();
    let mut h = 1e-3;
    it.advance_to(t_end, &mut h).unwrap();
    (
        it.state().q[6],
        it.state().q[2],
        it.diagnostics().summary.steps,
    )
}

#[test]
fn slider_crank_matches_minimal_coordinates() {
    let model = free_slider_crank(TH0, W0);
    let (th_ref, x_ref) = reference(TH0, W0, 1.0, 1e-5);
    // The velocities given are consistent: the projection keeps them.
    let it = Integrator::new(&model, settings(1e-3, 0.8)).unwrap();
    assert!((it.state().qd[2] - W0).abs() < 1e-12);
    let (x, th, steps) = slider_x(&model, 1.0, settings(1e-3, 0.8));
    assert_eq!(steps, 1000);
    let err = (x - x_ref).abs();
    eprintln!(
        "slider-crank at t = 1 s, h = 1 ms, ρ∞ = 0.8: slider x {x:.9} m vs {x_ref:.9} m (error {err:.2e} m), θ error {:.2e} rad",
        (th - th_ref).abs()
    );
    assert!(err < 4.4e-5, "slider error {err}");
    // Error control to 1e-6 m.
    let ad = Settings {
        step: 1e-2,
        adaptive: Some(Adaptive {
            atol: 2e-9,
            rtol: 0.0,
            h_min: 1e-7,
        }),
        ..settings(1e-2, 0.8)
    };
    let mut it = Integrator::new(&model, ad).unwrap();
    let mut h = 1e-4;
    it.advance_to(1.0, &mut h).unwrap();
    let err = (it.state().q[6] - x_ref).abs();
    let (steps, rejected) = (it.diagnostics().summary.steps, it.diagnostics().rejected);
    eprintln!(
        "error-controlled (atol 2e-9): slider error {err:.2e} m in {steps} steps ({rejected} rejected)"
    );
    assert!(err < 1e-6, "adaptive slider error {err}");
    // The step controller does not hover at the rejection limit.
    assert!(
        rejected * 10 < steps,
        "{rejected} of {steps} steps rejected"
    );
}

/// Errors at t = 0.5 s against the minimal-coordinate reference for
/// h = 4, 2, 1, 0.5 ms: each halving divides the error by about 4.
#[test]
fn second_order_convergence() {
    let model = free_slider_crank(TH0, W0);
    let (_, x_ref) = reference(TH0, W0, 0.5, 1e-5);
    let hs = [4e-3, 2e-3, 1e-3, 5e-4];
    let errs: Vec<f64> = hs
        .iter()
        .map(|&h| (slider_x(&model, 0.5, settings(h, 0.8)).0 - x_ref).abs())
        .collect();
    let orders: Vec<f64> = errs.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
    eprintln!("errors {errs:?}, observed orders {orders:.3?}");
    for p in &orders {
        assert!((1.8..2.3).contains(p), "order {p}: {errs:?}");
    }
}

/// The integrator's fused pass (R and Φ over the joints once) gives what
/// the separate residual and Φ give, on an arbitrary state.
#[test]
fn fused_residual_and_phi_match_the_separate_ones() {
    use camlink_core::dynamics::system::System;
    let model = slider_crank(0.3, 10.0, false);
    let sys = System::new(&model);
    let (n, m) = (sys.n(), sys.m());
    let wave = |k: usize, a: f64| (k as f64 * a).sin();
    let q: Vec<f64> = (0..n).map(|k| wave(k, 1.3)).collect();
    let qd: Vec<f64> = (0..n).map(|k| wave(k, 0.7)).collect();
    let qdd: Vec<f64> = (0..n).map(|k| wave(k, 2.1)).collect();
    let lambda: Vec<f64> = (0..m).map(|k| 10.0 * wave(k, 0.4) + 1.0).collect();
    let (mut r1, mut phi1) = (vec![0.0; n], vec![0.0; m]);
    sys.residual(&q, &qd, &qdd, &lambda, 0.2, &mut r1).unwrap();
    sys.asm.phi(&model, &q, 0.2, &mut phi1);
    let (mut r2, mut phi2) = (vec![7.0; n], vec![7.0; m]);
    sys.residual_and_phi(&q, &qd, &qdd, &lambda, 0.2, &mut r2, &mut phi2)
        .unwrap();
    assert_eq!(r1, r2);
    assert_eq!(phi1, phi2);
    assert!(
        phi1.iter().any(|v| v.abs() > 1e-3),
        "an inconsistent state: {phi1:?}"
    );
}

/// The drift channels of `output::fill` on an arbitrary (inconsistent)
/// state of a driven slider-crank: `constraint.residual` is max |Φ| and
/// `constraint.velocity` is max |Φ_q q̇ − ν| = max |dΦ/dt| along (q̇, 1),
/// here from central differences of Φ; `fill` (which reuses the ν of its
/// driver efforts) and `energy_and_drift` (which computes its own) agree.
#[test]
fn fill_reports_the_drift_of_phi_and_of_its_time_derivative() {
    use camlink_core::dynamics::output;
    use camlink_core::dynamics::system::System;
    let model = slider_crank(0.3, 10.0, true);
    let sys = System::new(&model);
    let (n, m) = (sys.n(), sys.m());
    let wave = |k: usize, a: f64| (k as f64 * a).sin();
    let q: Vec<f64> = (0..n).map(|k| wave(k, 1.3)).collect();
    let qd: Vec<f64> = (0..n).map(|k| 2.0 * wave(k + 1, 0.7)).collect();
    let lambda: Vec<f64> = (0..m).map(|k| 10.0 * wave(k, 0.4) + 1.0).collect();
    let t = 0.2;
    let width = output::channels(&model).len();
    let mut out = vec![f64::NAN; width];
    let mut scratch = output::Scratch::new(&sys);
    output::fill(&sys, &mut scratch, &q, &qd, &lambda, t, &mut out);

    let phi_at = |s: f64| {
        let qs: Vec<f64> = q.iter().zip(&qd).map(|(a, b)| a + s * b).collect();
        let mut phi = vec![0.0; m];
        sys.asm.phi(&model, &qs, t + s, &mut phi);
        phi
    };
    let max = |v: &[f64]| v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let eps = 1e-6;
    let (ahead, behind) = (phi_at(eps), phi_at(-eps));
    let rate: Vec<f64> = ahead
        .iter()
        .zip(&behind)
        .map(|(a, b)| (a - b) / (2.0 * eps))
        .collect();
    let (residual, velocity) = (out[width - 2], out[width - 1]);
    assert_eq!(residual, max(&phi_at(0.0)));
    assert!(velocity > 1.0, "an inconsistent velocity: {velocity}");
    // Central differences at ε = 1e-6: Φ's terms (below 1 m) round at a
    // few ulps, ~1e-15 m, which over 2ε is ~5e-10 m/s; truncation,
    // ε²/6 |d³Φ/ds³| with |q̇| ≤ 2 and lengths below 1 m, is ~1e-11 m/s.
    // Measured: 1.6e-10 m/s on a velocity of 8.3 m/s.
    assert!(
        (velocity - max(&rate)).abs() < 1e-9,
        "constraint.velocity {velocity} against dΦ/dt {}",
        max(&rate)
    );
    let mut drift = output::DriftScratch::new(m);
    let alone = output::energy_and_drift(&sys, &mut drift, &q, &qd, t);
    assert_eq!(&out[width - 5..], &alone[..]);
}

/// Fixed steps that do not divide an output interval exactly in binary
/// (h = 1e-5 s, outputs every 0.01 s) land on every output time without a
/// sliver of a step left over from the rounding of t: 60,000 steps to
/// 0.6 s, no more. A sliver (~1e-14 s) has a Newton matrix scaled by 1/h²
/// and used to end runs with "the Newton iteration matrix is singular".
#[test]
fn fixed_steps_leave_no_sliver_before_an_output_time() {
    let model = pendulum(0.5, 1.0, 0.02, 0.3, false);
    let times = time_grid(0.6, 0.01).unwrap();
    let mut table = Table::default();
    let summary = run(&model, &times, &settings(1e-5, 0.8), &[], &mut table).unwrap();
    assert_eq!(summary.steps, 60_000);
}

/// A fixed step longer than the output interval is cut to it: outputs
/// every 0.01 s at h = 1e15 s are those at h = 0.01 s, bit for bit (issue
/// 27: steps go past an output time only within the longest interval).
#[test]
fn issue27_a_huge_fixed_step_is_cut_to_the_output_interval() {
    let model = pendulum(0.5, 1.0, 0.02, 1.0, false);
    let times = time_grid(0.5, 0.01).unwrap();
    let table = |h: f64| {
        let settings = Settings {
            step: h,
            ..Settings::default()
        };
        let mut t = Table::default();
        run(&model, &times, &settings, &[], &mut t).unwrap();
        t
    };
    let (a, b) = (table(1e15), table(0.01));
    assert_eq!(a.t, b.t);
    assert_eq!(a.values, b.values);
}

/// Output times between step ends through a singular position (a chain of
/// two parallelograms released at rest at its flat position) and in a
/// model with a redundant equation (three cranks on one bar): the rows
/// come from the interpolated state and follow θ̈ = −κ cos θ as closely
/// as the rows at step ends do (issue 27).
#[test]
fn issue27_outputs_between_step_ends_of_singular_and_redundant_chains() {
    use mechanisms::{parallelogram_chain, parallelogram_error, CrankMass};
    let h = 1e-3;
    let settings = Settings {
        step: h,
        tol: 1e-10,
        ..Settings::default()
    };
    let ends = time_grid(0.6, 0.01).unwrap();
    let between: Vec<f64> = std::iter::once(0.0)
        .chain((0..60).map(|k| (k as f64 + 0.37) * 0.01))
        .collect();
    for (n, th0, fused) in [(2, 0.0, false), (3, -0.5, true)] {
        let model = parallelogram_chain(n, th0, fused, CrankMass::AtPin);
        let mut errs = Vec::new();
        for times in [&ends, &between] {
            let mut t = Table::default();
            run(&model, times, &settings, &[], &mut t).unwrap();
            errs.push(parallelogram_error(&t, n, CrankMass::AtPin, th0, G));
        }
        eprintln!(
            "n = {n}, fused {fused}: error at step ends {:e}, between {:e}",
            errs[0], errs[1]
        );
        assert!(errs[1] < 2.0 * errs[0] + 1e-9, "{errs:?}");
    }
}
