//! Issue 32: the shaking force and moment channels of inverse dynamics.
//!
//! Check: the in-line slider-crank of `mechanisms` turned at constant ω,
//! against Newton's and Euler's laws for the whole mechanism with the
//! exact closed-form kinematics of the slider-crank (no series
//! approximation of the slider's motion): the frame carries
//! F_s = Σ m_i (g − a_Gi) and M_O = Σ [r_Gi × m_i (g − a_Gi) − J_i α_i]
//! (the loads of the mechanism on the ground, the motor's reaction torque
//! among them). Source: Newton–Euler for a system of rigid bodies, e.g.
//! R. L. Norton, *Design of Machinery*, ch. 11 (dynamic force analysis)
//! and ch. 12 (shaking force F_s = −Σ F_ground-on-links).

use crate::mechanisms::{self, CRANK, CRANK_CENTROID, INERTIA, MASS, ROD, ROD_CENTROID};

use camlink_core::dynamics::inverse::run;
use camlink_core::math::cross;
use camlink_core::run::{time_grid, Settings, Table};

/// Exact position, velocity and acceleration of the in-line slider-crank
/// at θ = θ₀ + ω t: for each of crank, rod, slider its centroid
/// (r_G, a_G) and its angular acceleration α.
fn exact(th: f64, w: f64) -> [([f64; 2], [f64; 2], f64); 3] {
    let (a, b) = (CRANK, ROD);
    let (sn, cs) = th.sin_cos();
    // s = a sin θ, c = √(b² − s²): the crank pin A = (a cos θ, s), the slider
    // B = (a cos θ + c, 0), the rod angle ψ = −asin(s/b).
    let (s, sd, sdd) = (a * sn, a * w * cs, -a * w * w * sn);
    let c = (b * b - s * s).sqrt();
    let cd = -s * sd / c;
    let cdd = -(sd * sd + s * sdd) / c + s * sd * cd / (c * c);
    let xb_dd = -a * w * w * cs + cdd;
    let psi = (-s / b).asin();
    let psid = -sd / c;
    let psidd = -(sdd * c - sd * cd) / (c * c);
    // Crank: frame at O, angle θ, centroid at CRANK_CENTROID.
    let rot = |phi: f64, v: [f64; 2]| {
        let (sp, cp) = phi.sin_cos();
        [cp * v[0] - sp * v[1], sp * v[0] + cp * v[1]]
    };
    let g2 = rot(th, CRANK_CENTROID);
    let a2 = [-w * w * g2[0], -w * w * g2[1]];
    // Rod: frame at its middle, angle ψ; the middle M = A + (b/2) e_ψ.
    let pa = [a * cs, s];
    let aa = [-w * w * pa[0], -w * w * pa[1]];
    let arm = rot(psi, [b / 2.0 + ROD_CENTROID[0], ROD_CENTROID[1]]);
    let g3 = [pa[0] + arm[0], pa[1] + arm[1]];
    // a_G = a_A + α k × arm − ψ̇² arm.
    let a3 = [
        aa[0] - psidd * arm[1] - psid * psid * arm[0],
        aa[1] + psidd * arm[0] - psid * psid * arm[1],
    ];
    let g4 = [a * cs + c, 0.0];
    let a4 = [xb_dd, 0.0];
    [(g2, a2, 0.0), (g3, a3, psidd), (g4, a4, 0.0)]
}

/// Runs `model` (the slider-crank turned at θ₀ + ω t) by inverse dynamics
/// over one turn and compares its shaking channels with Newton and Euler
/// for the whole mechanism: F = Σ m_i (g − a_Gi) + P and
/// M_O = Σ [r_Gi × m_i (g − a_Gi) − J_i α_i] + r_C × P, P an outside load
/// on the slider's centroid C. Returns (peak |F|, largest force error,
/// peak |M|, largest moment error) and the sample times.
fn against_newton(
    model: &camlink_core::Model,
    th0: f64,
    omega: f64,
    p: [f64; 2],
) -> ([f64; 4], Vec<f64>) {
    let g = model.gravity;
    let times = time_grid(0.2, 1e-3).unwrap();
    let mut table = Table::default();
    run(model, &times, &Settings::default(), &[], &mut table).unwrap();
    let ch = |n: &str| table.channel(n).unwrap();
    let (fx, fy, mo) = (ch("shaking.fx"), ch("shaking.fy"), ch("shaking.moment"));
    let (mut peak, mut err_f, mut err_m, mut peak_m) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for (k, &t) in times.iter().enumerate() {
        let bodies = exact(th0 + omega * t, omega);
        let mut f = p;
        let mut m = cross(bodies[2].0, p);
        for (i, (r, acc, alpha)) in bodies.into_iter().enumerate() {
            let load = [MASS[i] * (g[0] - acc[0]), MASS[i] * (g[1] - acc[1])];
            f[0] += load[0];
            f[1] += load[1];
            m += cross(r, load) - INERTIA[i] * alpha;
        }
        peak = peak.max(f[0].hypot(f[1]));
        peak_m = peak_m.max(m.abs());
        err_f = err_f.max((fx[k] - f[0]).hypot(fy[k] - f[1]));
        err_m = err_m.max((mo[k] - m).abs());
    }
    ([peak, err_f, peak_m, err_m], times)
}

#[test]
fn issue32_shaking_force_slider_crank() {
    let (th0, omega) = (0.3, 2.0 * std::f64::consts::PI * 5.0);
    let model = mechanisms::slider_crank(th0, omega, true);
    let ([peak, err_f, peak_m, err_m], _) = against_newton(&model, th0, omega, [0.0; 2]);
    eprintln!("shaking force peak {peak:.3} N, error {err_f:.2e} N; moment peak {peak_m:.3} N·m, error {err_m:.2e} N·m");
    assert!(peak > 100.0, "a shaking force of order m r ω²: {peak} N");
    assert!(err_f <= 1e-9 * peak, "shaking force off by {err_f} N");
    assert!(err_m <= 1e-9 * peak_m, "shaking moment off by {err_m} N·m");
}

/// Forward dynamics has the same channels: the slider-crank coasting from
/// 10 rad/s under gravity, where F_s = Σ m_i (g − a_Gi) and
/// M_O = Σ [r_Gi × m_i (g − a_Gi) − J_i α_i] with a_Gi and α_i from the
/// run's own acceleration channels (a_G = a_O + α k × ρ − ω² ρ, ρ = A s′_G).
#[test]
fn issue32_shaking_force_forward_dynamics() {
    use camlink_core::dynamics::integrator;
    let model = mechanisms::slider_crank(0.3, 10.0, false);
    let g = model.gravity;
    let times = time_grid(0.3, 1e-3).unwrap();
    let mut table = Table::default();
    // The balance holds to the Newton tolerance of the step's equations.
    let settings = integrator::Settings {
        tol: 1e-11,
        ..integrator::Settings::default()
    };
    integrator::run(&model, &times, &settings, &[], &mut table).unwrap();
    let ch = |n: &str| table.channel(n).unwrap();
    let (fx, fy, mo) = (ch("shaking.fx"), ch("shaking.fy"), ch("shaking.moment"));
    let (mut err_f, mut err_m, mut peak, mut peak_m) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for k in 0..times.len() {
        let (mut f, mut m) = ([0.0; 2], 0.0);
        for (b, (s, mass, inertia)) in [
            ("crank", CRANK_CENTROID),
            ("rod", ROD_CENTROID),
            ("slider", [0.0, 0.0]),
        ]
        .into_iter()
        .zip(MASS.into_iter().zip(INERTIA))
        .map(|((b, s), (m, j))| (b, (s, m, j)))
        {
            let v = |c: &str| ch(&format!("{b}.{c}"))[k];
            let (sp, cp) = v("phi").sin_cos();
            let rho = [cp * s[0] - sp * s[1], sp * s[0] + cp * s[1]];
            let (w, al) = (v("omega"), v("alpha"));
            let a = [
                v("ax") - al * rho[1] - w * w * rho[0],
                v("ay") + al * rho[0] - w * w * rho[1],
            ];
            let r = [v("x") + rho[0], v("y") + rho[1]];
            let load = [mass * (g[0] - a[0]), mass * (g[1] - a[1])];
            f = [f[0] + load[0], f[1] + load[1]];
            m += cross(r, load) - inertia * al;
        }
        peak = peak.max(f[0].hypot(f[1]));
        peak_m = peak_m.max(m.abs());
        err_f = err_f.max((fx[k] - f[0]).hypot(fy[k] - f[1]));
        err_m = err_m.max((mo[k] - m).abs());
    }
    eprintln!("forward: shaking force peak {peak:.3} N, error {err_f:.2e} N; moment peak {peak_m:.3} N·m, error {err_m:.2e} N·m");
    assert!(err_f <= 1e-8 * peak, "shaking force off by {err_f} N");
    assert!(err_m <= 1e-8 * peak_m, "shaking moment off by {err_m} N·m");
}

/// Springs and dampers anchored to the frame load it too. The slider-crank
/// of the first test with a spring–damper from a ground point to the
/// slider, a torsion spring–damper between the ground and the crank, a
/// viscous damper in the slide and a constant point load P on the slider
/// (a load from outside, with no reaction in the model). By hand, Newton
/// and Euler for the whole mechanism: the frame's reactions balance the
/// weights, the inertia forces and P, so F_s = Σ m_i (g − a_Gi) + P and
/// M_O = Σ [r_Gi × m_i (g − a_Gi) − J_i α_i] + r_C × P, whatever the
/// springs do; with the springs' reactions left out the sums would be off
/// by the spring forces.
#[test]
fn issue32_shaking_force_counts_springs_to_the_frame() {
    use camlink_core::force::point::PointForce;
    use camlink_core::force::rsda::Rsda;
    use camlink_core::force::translational_damper::TranslationalDamper;
    use camlink_core::force::tsda::Tsda;
    use camlink_core::force::Force;
    use camlink_core::{BodyId, TimeFn};

    let (th0, omega) = (0.3, 2.0 * std::f64::consts::PI * 5.0);
    let mut model = mechanisms::slider_crank(th0, omega, true);
    let (g0, crank, slider) = (BodyId::GROUND, BodyId(1), BodyId(3));
    model.add_force(Force::new(
        "return_spring",
        Tsda {
            body_i: g0,
            s_i: [0.6, 0.15],
            body_j: slider,
            s_j: [0.0, 0.0],
            stiffness: 4.0e3,
            free_length: 0.1,
            damping: 30.0,
            actuator: TimeFn::Const(5.0),
        },
    ));
    model.add_force(Force::new(
        "torsion",
        Rsda {
            body_i: g0,
            body_j: crank,
            stiffness: 20.0,
            free_angle: 0.5,
            damping: 0.4,
            actuator: TimeFn::Const(0.0),
        },
    ));
    model.add_force(Force::new(
        "slide_friction",
        TranslationalDamper::new(g0, [1.0, 0.0], slider, [0.0, 0.0], 12.0).unwrap(),
    ));
    let p = [-150.0, 40.0];
    model.add_force(Force::new(
        "load",
        PointForce {
            body: slider,
            s: [0.0, 0.0],
            f: [TimeFn::Const(p[0]), TimeFn::Const(p[1])],
            local: false,
        },
    ));
    let ([peak, err_f, peak_m, err_m], times) = against_newton(&model, th0, omega, p);
    // The spring's pull: stiffness times stretch, of order 1e3 N.
    let spring = times.iter().fold(0.0f64, |a, &t| {
        let c = exact(th0 + omega * t, omega)[2].0;
        let len = (c[0] - 0.6).hypot(c[1] - 0.15);
        a.max(4.0e3 * (len - 0.1).abs())
    });
    eprintln!("with springs: shaking force peak {peak:.3} N (spring up to {spring:.1} N), error {err_f:.2e} N; moment peak {peak_m:.3} N·m, error {err_m:.2e} N·m");
    assert!(spring > 100.0, "the spring loads the frame: {spring} N");
    assert!(err_f <= 1e-9 * peak, "shaking force off by {err_f} N");
    assert!(err_m <= 1e-9 * peak_m, "shaking moment off by {err_m} N·m");
}
