//! Mechanisms with mass, built in code, shared by the dynamics tests and
//! benchmarks.

use camlink_core::constraint::relative::{RelCoord, RelativeCoord};
use camlink_core::constraint::revolute::Revolute;
use camlink_core::constraint::translational::Translational;
use camlink_core::run::Table;
use camlink_core::{Body, BodyId, Model, Point, TimeFn};

/// Slider-crank: crank a, rod b (m).
pub const CRANK: f64 = 0.1;
pub const ROD: f64 = 0.3;

/// Masses (kg) and centroidal inertias (kg·m²) of crank, rod and slider.
pub const MASS: [f64; 3] = [1.0, 2.0, 0.5];
pub const INERTIA: [f64; 3] = [1.0e-3, 1.5e-2, 1.0e-3];
/// Centroid of the crank in its frame (frame at the ground pivot) and of
/// the rod in its frame (frame at its middle), m.
pub const CRANK_CENTROID: [f64; 2] = [0.05, 0.0];
pub const ROD_CENTROID: [f64; 2] = [0.03, 0.0];

pub fn rev(bi: BodyId, si: [f64; 2], bj: BodyId, sj: [f64; 2]) -> Revolute {
    Revolute {
        body_i: bi,
        s_i: si,
        body_j: bj,
        s_j: sj,
    }
}

pub fn body(name: &str, q0: [f64; 3], mass: f64, inertia: f64, centroid: [f64; 2]) -> Body {
    let mut b = Body::new(name, q0);
    b.mass = mass;
    b.inertia = inertia;
    b.centroid = centroid;
    b
}

/// Crank angle θ → (rod angle ψ, slider x) of the in-line slider-crank.
pub fn slider_crank_position(th: f64) -> (f64, f64) {
    let (a, b) = (CRANK, ROD);
    let h = (b * b - a * a * th.sin().powi(2)).sqrt();
    ((-a * th.sin()).atan2(h), a * th.cos() + h)
}

/// In-line slider-crank, placed exactly at crank angle `th0`: crank frame
/// at the ground pivot O, rod frame at its middle, slider frame at its pin
/// C on the x axis. `driver`: the crank turns at θ = θ₀ + ω t; otherwise
/// it starts with angular speed ω and the bodies' velocities are left at
/// zero for the projection to make consistent.
pub fn slider_crank(th0: f64, omega: f64, driver: bool) -> Model {
    let (a, b) = (CRANK, ROD);
    let (psi, xc) = slider_crank_position(th0);
    let bx = a * th0.cos();
    let by = a * th0.sin();
    let mut m = Model::new("slider-crank");
    let mut crank = body(
        "crank",
        [0.0, 0.0, th0],
        MASS[0],
        INERTIA[0],
        CRANK_CENTROID,
    );
    crank.qd0 = [0.0, 0.0, omega];
    let crank = m.add_body(crank);
    let rod = m.add_body(body(
        "rod",
        [0.5 * (bx + xc), 0.5 * by, psi],
        MASS[1],
        INERTIA[1],
        ROD_CENTROID,
    ));
    let slider = m.add_body(body(
        "slider",
        [xc, 0.0, 0.0],
        MASS[2],
        INERTIA[2],
        [0.0, 0.0],
    ));
    let g = BodyId::GROUND;
    m.add_joint("O", rev(g, [0.0, 0.0], crank, [0.0, 0.0]));
    m.add_joint("B", rev(crank, [a, 0.0], rod, [-b / 2.0, 0.0]));
    m.add_joint("C", rev(rod, [b / 2.0, 0.0], slider, [0.0, 0.0]));
    m.add_joint(
        "slide",
        Translational {
            body_i: g,
            s_i: [0.0, 0.0],
            v_i: [1.0, 0.0],
            body_j: slider,
            s_j: [0.0, 0.0],
            angle: 0.0,
        },
    );
    if driver {
        m.add_driver(
            "motor",
            RelativeCoord {
                body_i: g,
                s_i: [0.0, 0.0],
                body_j: crank,
                s_j: [0.0, 0.0],
                coord: RelCoord::Phi,
                f: TimeFn::Linear {
                    value: th0,
                    rate: omega,
                },
            },
        );
    }
    m
}

/// A chain of `n` links of length `l` (m), 1 kg each, hanging from the
/// ground at the origin and starting horizontal along +x: link k's frame is
/// at its middle, its ends at (∓l/2, 0).
pub fn chain(n: usize, l: f64) -> Model {
    let mut m = Model::new("chain");
    let mut prev = BodyId::GROUND;
    for k in 0..n {
        let mut b = body(
            &format!("link{k}"),
            [(k as f64 + 0.5) * l, 0.0, 0.0],
            1.0,
            l * l / 12.0,
            [0.0, 0.0],
        );
        b.points = vec![
            Point {
                name: "A".into(),
                s: [-l / 2.0, 0.0],
            },
            Point {
                name: "B".into(),
                s: [l / 2.0, 0.0],
            },
        ];
        let id = m.add_body(b);
        let sp = if prev.is_ground() {
            [0.0, 0.0]
        } else {
            [l / 2.0, 0.0]
        };
        m.add_joint(format!("J{k}"), rev(prev, sp, id, [-l / 2.0, 0.0]));
        prev = id;
    }
    m
}

/// [`chain`] with every joint driven: the relative angle of link k to the
/// link before it (to the ground for the first) is `rate_k` t, with rates of
/// ±0.01 rad/s alternating in sign, so that the chain waves without coiling.
pub fn driven_chain(n: usize, l: f64) -> Model {
    let mut m = chain(n, l);
    for k in 0..n {
        let body_i = if k == 0 { BodyId::GROUND } else { BodyId(k) };
        m.add_driver(
            format!("D{k}"),
            RelativeCoord {
                body_i,
                s_i: [0.0, 0.0],
                body_j: BodyId(k + 1),
                s_j: [0.0, 0.0],
                coord: RelCoord::Phi,
                f: TimeFn::Linear {
                    value: 0.0,
                    rate: if k % 2 == 0 { 0.01 } else { -0.01 },
                },
            },
        );
    }
    m
}

/// A compound pendulum: one body pivoted at the origin, centroid at
/// distance `l` (m) from the pivot, starting at angle `th0` from the
/// downward vertical. `frame_at_pivot`: the body frame sits at the pivot
/// with the centroid offset (0, −l) when hanging; otherwise at the centroid.
pub fn pendulum(l: f64, mass: f64, inertia: f64, th0: f64, frame_at_pivot: bool) -> Model {
    let mut m = Model::new("pendulum");
    // Body angle φ = θ; the pivot-to-centroid vector is (0, −l) at φ = 0.
    let b = if frame_at_pivot {
        body("bob", [0.0, 0.0, th0], mass, inertia, [0.0, -l])
    } else {
        body(
            "bob",
            [l * th0.sin(), -l * th0.cos(), th0],
            mass,
            inertia,
            [0.0, 0.0],
        )
    };
    let id = m.add_body(b);
    let s = if frame_at_pivot { [0.0, 0.0] } else { [0.0, l] };
    m.add_joint("pivot", rev(BodyId::GROUND, [0.0, 0.0], id, s));
    m
}

/// Parallelogram chain: crank length a, pitch d (coupler length), m.
pub const PAR_CRANK: f64 = 0.2;
pub const PAR_PITCH: f64 = 0.5;
/// Mass (kg) of a crank and of the coupler between two cranks.
pub const PAR_CRANK_MASS: f64 = 1.0;
pub const PAR_COUPLER_MASS: f64 = 2.0;

/// How a crank of [`parallelogram_chain`] carries its mass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CrankMass {
    /// All at the crank pin (centroid at a, no centroidal inertia): at the
    /// flat position every crank would fall alike, so the multipliers stay
    /// bounded through it.
    AtPin,
    /// A uniform bar (centroid at a/2, inertia m a²/12): at the flat
    /// position the cranks would fall at different rates, and the exact
    /// multipliers grow without bound there (the couplers' tension ~ 1/θ).
    Uniform,
}

impl CrankMass {
    /// (centroidal inertia J' in kg·m², centroid distance c from the pivot in m).
    pub fn inertia(self) -> (f64, f64) {
        let a = PAR_CRANK;
        match self {
            CrankMass::AtPin => (0.0, a),
            CrankMass::Uniform => (PAR_CRANK_MASS * a * a / 12.0, a / 2.0),
        }
    }
}

/// A chain of `n` parallelogram four-bars: n + 1 equal cranks of length a
/// pivoted on the ground at (k d, 0), frames at the pivots, all at angle
/// `th0` (rad); their pins carried by `n` uniform couplers of length d
/// (frame at the left end), or, with `fused`, by one rigid bar of length
/// n d and mass n m_b: 4(n + 1) equations of rank 3n + 5, so n − 1
/// redundant. One degree of freedom either way: every crank at the same
/// angle θ, the couplers translating. At θ = 0 and θ = ±π all links are
/// collinear and Φ_q loses one rank per four-bar.
pub fn parallelogram_chain(n: usize, th0: f64, fused: bool, crank: CrankMass) -> Model {
    let (a, d) = (PAR_CRANK, PAR_PITCH);
    let (mc, mb) = (PAR_CRANK_MASS, PAR_COUPLER_MASS);
    let (jc, c) = crank.inertia();
    let mut m = Model::new("parallelogram chain");
    let g = BodyId::GROUND;
    let tip = [a * th0.cos(), a * th0.sin()];
    let cranks: Vec<BodyId> = (0..=n)
        .map(|k| {
            let x = k as f64 * d;
            let id = m.add_body(body(&format!("crank{k}"), [x, 0.0, th0], mc, jc, [c, 0.0]));
            m.add_joint(format!("O{k}"), rev(g, [x, 0.0], id, [0.0, 0.0]));
            id
        })
        .collect();
    if fused {
        let len = n as f64 * d;
        let bar = m.add_body(body(
            "coupler",
            [tip[0], tip[1], 0.0],
            n as f64 * mb,
            n as f64 * mb * len * len / 12.0,
            [len / 2.0, 0.0],
        ));
        for (k, &c) in cranks.iter().enumerate() {
            m.add_joint(format!("P{k}"), rev(c, [a, 0.0], bar, [k as f64 * d, 0.0]));
        }
    } else {
        for k in 0..n {
            let id = m.add_body(body(
                &format!("coupler{k}"),
                [k as f64 * d + tip[0], tip[1], 0.0],
                mb,
                mb * d * d / 12.0,
                [d / 2.0, 0.0],
            ));
            m.add_joint(format!("L{k}"), rev(cranks[k], [a, 0.0], id, [0.0, 0.0]));
            m.add_joint(format!("R{k}"), rev(id, [d, 0.0], cranks[k + 1], [a, 0.0]));
        }
    }
    m
}

/// θ̈ = −κ cos θ, the exact motion of every crank of
/// [`parallelogram_chain`] (couplers translating), from the energy
/// equation in the crank angle: with n_c = n + 1 cranks of first moment
/// m_c c and inertia J_O = J' + m_c c² about the pivot,
/// κ = g (n_c m_c c + n m_b a) / (n_c J_O + n m_b a²).
pub fn parallelogram_kappa(n: usize, crank: CrankMass, g: f64) -> f64 {
    let (a, mc, mb) = (PAR_CRANK, PAR_CRANK_MASS, PAR_COUPLER_MASS);
    let (nc, nb) = ((n + 1) as f64, n as f64);
    let (jc, c) = crank.inertia();
    g * (nc * mc * c + nb * mb * a) / (nc * (jc + mc * c * c) + nb * mb * a * a)
}

/// θ(t) at `times` of θ̈ = −κ cos θ from θ(0) = θ₀, θ̇(0) = 0: classical
/// Runge–Kutta with at most 1e-4 s steps, landing on every output time
/// (global error ~ (√κ h)⁴ ≈ 1e-13 rad over 20 s for κ ≈ 50 s⁻²).
pub fn parallelogram_reference(kappa: f64, th0: f64, times: &[f64]) -> Vec<f64> {
    pendulum_like_reference(kappa, th0, 0.0, times)
}

/// Largest |θ − θ_exact| (rad) of crank 0 of a [`parallelogram_chain`]
/// released at rest from `th0`, over the rows of `table` (channel
/// `crank0.phi` against [`parallelogram_reference`], gravity g in m/s²).
pub fn parallelogram_error(table: &Table, n: usize, crank: CrankMass, th0: f64, g: f64) -> f64 {
    let want = parallelogram_reference(parallelogram_kappa(n, crank, g), th0, &table.t);
    let th = table.channel("crank0.phi").expect("crank0.phi");
    th.iter()
        .zip(&want)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
}

/// Forward dynamics of a [`parallelogram_chain`] of `n` four-bars released
/// at rest from the flat position (θ = 0) with step `h` (s) and Newton
/// tolerance `tol` for `t_end` (s), output every 0.01 s: the largest
/// |θ − θ_exact| of crank 0 and the largest difference between the cranks'
/// angles (rad), or the run's error.
pub fn parallelogram_chain_error(
    n: usize,
    crank: CrankMass,
    h: f64,
    tol: f64,
    t_end: f64,
) -> Result<(f64, f64), String> {
    let table = forward(&parallelogram_chain(n, 0.0, false, crank), h, tol, t_end)?;
    let err = parallelogram_error(&table, n, crank, 0.0, 9.81);
    Ok((err, crank_spread(&table, n)))
}

/// Forward dynamics of `model` with fixed step `h` (s) and Newton
/// tolerance `tol` to `t_end` (s), output every 0.01 s, or the run's error.
pub fn forward(model: &Model, h: f64, tol: f64, t_end: f64) -> Result<Table, String> {
    forward_with_summary(model, h, tol, t_end).map(|(table, _)| table)
}

/// [`forward`], with the run's summary (its step and Newton counts).
pub fn forward_with_summary(
    model: &Model,
    h: f64,
    tol: f64,
    t_end: f64,
) -> Result<(Table, camlink_core::run::Summary), String> {
    use camlink_core::dynamics::integrator::{run, Settings};
    let times = camlink_core::run::time_grid(t_end, 0.01).unwrap();
    let settings = Settings {
        step: h,
        tol,
        ..Settings::default()
    };
    let mut table = Table::default();
    let summary = run(model, &times, &settings, &[], &mut table).map_err(|e| e.to_string())?;
    Ok((table, summary))
}

/// The largest difference (rad) between the angles of cranks 1..=n and
/// crank 0 at each row of `table`: 0 on the parallelogram branch.
pub fn crank_spreads(table: &Table, n: usize) -> Vec<f64> {
    let th0 = table.channel("crank0.phi").unwrap();
    let mut spread = vec![0.0f64; th0.len()];
    for k in 1..=n {
        let thk = table.channel(&format!("crank{k}.phi")).unwrap();
        for ((s, a), b) in spread.iter_mut().zip(&thk).zip(&th0) {
            *s = s.max((a - b).abs());
        }
    }
    spread
}

/// The largest of [`crank_spreads`] over the rows of `table` (rad).
pub fn crank_spread(table: &Table, n: usize) -> f64 {
    crank_spreads(table, n).into_iter().fold(0.0, f64::max)
}

/// The N-four-bar mechanism of the IFToMM multibody benchmark library
/// (problem A02; González, Dopico, Luaces & Cuadrado 2006): `n` parallelogram
/// four-bars of 2n + 1 uniform links of 1 m and 1 kg (n + 1 cranks pivoted
/// on the ground at (k, 0) m, frames at the pivots; n couplers, frames at
/// their left pin), all cranks upright (θ = 90°), the pin B₀ of crank 0
/// moving at 1 m/s along +x (θ̇ = −1 rad/s), gravity 9.81 m/s² along −y.
/// The mechanism turns over and over, through the flat positions θ = 0
/// and θ = −π (where Φ_q loses one rank per four-bar) at speed.
pub fn benchmark_a02(n: usize) -> Model {
    let (len, mass) = (1.0, 1.0);
    let jc = mass * len * len / 12.0;
    let (th0, omega) = (std::f64::consts::FRAC_PI_2, -1.0);
    let mut m = Model::new("IFToMM A02 N-four-bar");
    let g = BodyId::GROUND;
    let tip = [len * th0.cos(), len * th0.sin()];
    let cranks: Vec<BodyId> = (0..=n)
        .map(|k| {
            let x = k as f64 * len;
            let mut b = body(
                &format!("crank{k}"),
                [x, 0.0, th0],
                mass,
                jc,
                [len / 2.0, 0.0],
            );
            b.qd0 = [0.0, 0.0, omega];
            let id = m.add_body(b);
            m.add_joint(format!("O{k}"), rev(g, [x, 0.0], id, [0.0, 0.0]));
            id
        })
        .collect();
    for k in 0..n {
        let mut b = body(
            &format!("coupler{k}"),
            [k as f64 * len + tip[0], tip[1], 0.0],
            mass,
            jc,
            [len / 2.0, 0.0],
        );
        b.qd0 = [-omega * len * th0.sin(), omega * len * th0.cos(), 0.0];
        let id = m.add_body(b);
        m.add_joint(format!("L{k}"), rev(cranks[k], [len, 0.0], id, [0.0, 0.0]));
        m.add_joint(
            format!("R{k}"),
            rev(id, [len, 0.0], cranks[k + 1], [len, 0.0]),
        );
    }
    m
}

/// θ(t) at `times` of θ̈ = −κ cos θ from (θ₀, θ̇₀): classical Runge–Kutta
/// with at most 1e-4 s steps, landing on every output time.
pub fn pendulum_like_reference(kappa: f64, th0: f64, omega0: f64, times: &[f64]) -> Vec<f64> {
    let f = |y: [f64; 2]| [y[1], -kappa * y[0].cos()];
    let mut y = [th0, omega0];
    let mut t = 0.0;
    let mut out = Vec::with_capacity(times.len());
    for &te in times {
        let steps = ((te - t) / 1e-4).ceil().max(0.0) as usize;
        if steps > 0 {
            let h = (te - t) / steps as f64;
            for _ in 0..steps {
                let k1 = f(y);
                let k2 = f([y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]]);
                let k3 = f([y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]]);
                let k4 = f([y[0] + h * k3[0], y[1] + h * k3[1]]);
                for i in 0..2 {
                    y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
                }
            }
            t = te;
        }
        out.push(y[0]);
    }
    out
}

/// κ (1/s²) of the exact motion θ̈ = −κ cos θ of [`benchmark_a02`] with
/// `n` four-bars: κ = g (n_c m c + n m a)/(n_c J_O + n m a²), c = a/2,
/// J_O = m a²/3, n_c = n + 1 cranks.
pub fn benchmark_a02_kappa(n: usize) -> f64 {
    let (nc, nb) = ((n + 1) as f64, n as f64);
    9.81 * (nc * 0.5 + nb) / (nc / 3.0 + nb)
}

/// The exact crank angle θ (rad) of [`benchmark_a02`] with `n` four-bars
/// at `times` (s).
pub fn benchmark_a02_exact(n: usize, times: &[f64]) -> Vec<f64> {
    pendulum_like_reference(
        benchmark_a02_kappa(n),
        std::f64::consts::FRAC_PI_2,
        -1.0,
        times,
    )
}

/// Forward dynamics of [`benchmark_a02`] with `n` four-bars, step `h` (s)
/// and Newton tolerance `tol` for `t_end` (s), output every 0.01 s: the
/// largest |θ − θ_exact| of crank 0 and the largest difference between the
/// cranks' angles (rad), or the run's error. Exact: θ̈ = −κ cos θ with
/// κ = g (n_c m c + n m a)/(n_c J_O + n m a²), c = a/2, J_O = m a²/3.
pub fn benchmark_a02_error(n: usize, h: f64, tol: f64, t_end: f64) -> Result<(f64, f64), String> {
    let table = forward(&benchmark_a02(n), h, tol, t_end)?;
    let want = benchmark_a02_exact(n, &table.t);
    let th0 = table.channel("crank0.phi").unwrap();
    let err = th0
        .iter()
        .zip(&want)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    Ok((err, crank_spread(&table, n)))
}

/// The checks of a [`parallelogram_chain`] of `n` four-bars released at
/// rest from the flat position, run at each of `steps` (s) and `tols` for
/// `t_end` (s); the failures, described. Every run must finish; stay on
/// the parallelogram branch (cranks within 1e-8 rad + `tol` of each other,
/// a converged step resolving positions to `tol`: the crossed branch parts
/// them by order 1); and keep its error within the
/// discretisation error C h² t of a second-order method (the phase error
/// grows with t; C = 250 rad/s³ against 70 to 190 measured at h = 1e-3 s
/// over 1.2 and 20 s, N = 2 and 40) plus what the Newton tolerance allows,
/// at most `tol` per step over t/h steps. At `tol` = 1e-10 the errors must
/// fall by more than a third of (h₁/h₂)² from each step to the next.
pub fn released_chain_failures(
    n: usize,
    crank: CrankMass,
    steps: &[f64],
    tols: &[f64],
    t_end: f64,
) -> Vec<String> {
    let mut failures = Vec::new();
    for &tol in tols {
        let mut errs = Vec::new();
        for &h in steps {
            let what = format!("N = {n}, {crank:?}, h = {h:e} s, tol = {tol:e}, {t_end} s");
            match parallelogram_chain_error(n, crank, h, tol, t_end) {
                Err(e) => {
                    eprintln!("{what}: failed: {e}");
                    failures.push(format!("{what}: {e}"));
                    errs.push(f64::NAN);
                }
                Ok((err, spread)) => {
                    eprintln!(
                        "{what}: max |θ − θ_exact| {err:.2e} rad, crank spread {spread:.1e} rad"
                    );
                    if spread >= 1e-8 + tol {
                        failures.push(format!("{what}: the cranks parted by {spread}"));
                    }
                    let bound = 250.0 * h * h * t_end + t_end / h * tol;
                    if err > bound {
                        failures.push(format!("{what}: error {err} > {bound}"));
                    }
                    errs.push(err);
                }
            }
        }
        if tol <= 1e-10 {
            for (w, hs) in errs.windows(2).zip(steps.windows(2)) {
                let ratio = hs[0] / hs[1];
                // A failed run's NaN does not fall either.
                let falls = w[0] / w[1] > ratio * ratio / 3.0;
                if !falls {
                    failures.push(format!(
                        "N = {n}, {crank:?}, tol {tol:e}: errors {errs:?} at h = {steps:?} \
                         do not fall at second order"
                    ));
                }
            }
        }
    }
    failures
}

/// One column of the long matrix of [`released_chain_failures`] (full
/// tier, `bash scripts/gate.sh --full`): N = 2 and 40 at h = 1e-3, 1e-4 and 1e-5 s and
/// Newton tolerance `tol`, 20 s each. The matrix is run a column at a
/// time (`tol` = 1e-6, 1e-8, 1e-10), one test each, so that the full
/// tier spreads its columns over the machine's cores.
pub fn released_chain_long_failures(crank: CrankMass, tol: f64) -> Vec<String> {
    let steps = [1e-3, 1e-4, 1e-5];
    let mut failures = released_chain_failures(2, crank, &steps, &[tol], 20.0);
    failures.extend(released_chain_failures(40, crank, &steps, &[tol], 20.0));
    failures
}
