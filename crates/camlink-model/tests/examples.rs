//! Every model in `examples/` loaded from its file, run, and compared with a
//! closed-form answer written independently here.
//!
//! Tolerances, from the solver's settings and the model's conditioning:
//! - positions within `POS_TOL` = 1e-11 (m or rad, absolute): Newton stops
//!   once max |Φ| ≤ `tol` = 1e-10 and then applies that residual's
//!   correction, which with quadratic convergence leaves an error far below
//!   tol; 1e-11 holds the solution to a tenth of the stopping test.
//! - velocities and accelerations solve Φ_q q̇ = ν and Φ_q q̈ = γ at the
//!   computed positions. A linear solve's relative error is at most the
//!   condition number κ(Φ_q) times the relative error of its data: the
//!   position error relative to the shortest length in these examples (a
//!   gear radius of 0.015 m), POS_TOL / 0.01 m = 1e-9. So
//!   |got − want| ≤ κ·1e-9·max(|want|, scale),
//!   with κ the largest condition number over the run, computed here by SVD,
//!   and `scale` a typical magnitude of the quantity over the run (stated at
//!   each check), so that values passing through zero are held to an
//!   absolute bound.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use camlink_core::diagnose::dense_jacobian;
use camlink_core::kinematics::{run, Solver};
use camlink_core::run::{time_grid, Settings, Table};
use camlink_model::{load_path, Loaded};

/// Position tolerance (m or rad).
const POS_TOL: f64 = 1e-11;
/// Relative error of Φ_q, ν and γ caused by position errors within
/// `POS_TOL` on lengths of at least 0.01 m.
const DATA_TOL: f64 = POS_TOL / 0.01;

fn examples_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// Loads `examples/<name>.toml`, runs its `[analysis]` and returns the
/// loaded file and the table of results.
fn run_example(name: &str) -> (Loaded, Table) {
    let path = examples_dir().join(format!("{name}.toml"));
    let loaded = load_path(&path).unwrap_or_else(|e| panic!("{e}"));
    let a = &loaded.analysis;
    let times = match &a.times {
        Some(times) => times.clone(),
        None => time_grid(
            a.t_end.expect("examples give t_end"),
            a.step.expect("examples give step"),
        )
        .unwrap(),
    };
    let settings = Settings {
        tol: a.tol,
        max_iter: a.max_iter,
        ..Settings::default()
    };
    let points = loaded.point_outputs().unwrap();
    let mut table = Table::default();
    let summary = run(&loaded.model, &times, &settings, &points, &mut table)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(summary.steps, times.len(), "{name}");
    assert!(times.len() > 10, "{name}: too few steps to check");
    (loaded, table)
}

/// The largest condition number κ(Φ_q) = σ_max/σ_min over the run of an
/// example, from the singular values of the dense Jacobian at every step.
fn largest_condition(loaded: &Loaded, times: &[f64]) -> f64 {
    let a = &loaded.analysis;
    let settings = Settings {
        tol: a.tol,
        max_iter: a.max_iter,
        jerk: false,
    };
    let mut solver = Solver::new(&loaded.model, settings).unwrap();
    let mut worst: f64 = 1.0;
    let mut prev = None;
    for &t in times {
        match prev {
            None => solver.step(t, None).map(|_| ()),
            Some(p) => solver.advance(p, t, 0),
        }
        .unwrap();
        let j = dense_jacobian(&loaded.model, solver.assembly(), &solver.q, t);
        let sv = j.singular_values().unwrap();
        worst = worst.max(sv[0] / sv[sv.len() - 1]);
        prev = Some(t);
    }
    worst
}

/// Compares results with closed forms and remembers the worst errors.
struct Check {
    name: &'static str,
    table: Table,
    /// Largest position error (m or rad).
    pos: f64,
    /// Largest relative velocity or acceleration error.
    rate: f64,
    /// Allowed relative velocity or acceleration error: κ·`DATA_TOL`.
    rate_tol: f64,
}

impl Check {
    fn new(name: &'static str) -> (Loaded, Check) {
        let (loaded, table) = run_example(name);
        let kappa = largest_condition(&loaded, &table.t);
        let check = Check {
            name,
            table,
            pos: 0.0,
            rate: 0.0,
            rate_tol: kappa * DATA_TOL,
        };
        (loaded, check)
    }

    /// Output times (s).
    fn t(&self) -> Vec<f64> {
        self.table.t.clone()
    }

    /// The value of channel `c` at row `k`.
    fn at(&self, c: &str, k: usize) -> f64 {
        let j = self
            .table
            .channels
            .iter()
            .position(|n| n == c)
            .unwrap_or_else(|| panic!("{}: no channel '{c}'", self.name));
        self.table.values[k * self.table.channels.len() + j]
    }

    /// A position (m) at row `k` within `POS_TOL`.
    fn pos(&mut self, c: &str, k: usize, want: f64) {
        let got = self.at(c, k);
        let err = (got - want).abs();
        assert!(
            err <= POS_TOL,
            "{}: {c} at t = {}: got {got}, want {want} (error {err:.2e})",
            self.name,
            self.table.t[k]
        );
        self.pos = self.pos.max(err);
    }

    /// An angle (rad) at row `k` within `POS_TOL`, modulo 2π.
    fn angle(&mut self, c: &str, k: usize, want: f64) {
        let got = self.at(c, k);
        let err = wrap(got - want).abs();
        assert!(
            err <= POS_TOL,
            "{}: {c} at t = {}: got {got}, want {want} (mod 2π; error {err:.2e})",
            self.name,
            self.table.t[k]
        );
        self.pos = self.pos.max(err);
    }

    /// A velocity or acceleration at row `k`:
    /// |got − want| ≤ κ·`DATA_TOL`·max(|want|, scale).
    fn rate(&mut self, c: &str, k: usize, want: f64, scale: f64) {
        let got = self.at(c, k);
        let err = (got - want).abs() / want.abs().max(scale);
        assert!(
            err <= self.rate_tol,
            "{}: {c} at t = {}: got {got}, want {want} (relative error {err:.2e}, allowed {:.1e})",
            self.name,
            self.table.t[k],
            self.rate_tol
        );
        self.rate = self.rate.max(err);
    }

    /// Position, velocity and acceleration of a point's channels
    /// `<p>.x .y .vx .vy .ax .ay`.
    fn point(&mut self, p: &str, k: usize, r: [f64; 2], v: [f64; 2], a: [f64; 2], scale: [f64; 2]) {
        self.pos(&format!("{p}.x"), k, r[0]);
        self.pos(&format!("{p}.y"), k, r[1]);
        self.rate(&format!("{p}.vx"), k, v[0], scale[0]);
        self.rate(&format!("{p}.vy"), k, v[1], scale[0]);
        self.rate(&format!("{p}.ax"), k, a[0], scale[1]);
        self.rate(&format!("{p}.ay"), k, a[1], scale[1]);
    }

    /// Angle, angular velocity and acceleration of a body's channels
    /// `<b>.phi .omega .alpha`.
    fn rotation(&mut self, b: &str, k: usize, phi: [f64; 3], scale: [f64; 2]) {
        self.angle(&format!("{b}.phi"), k, phi[0]);
        self.rate(&format!("{b}.omega"), k, phi[1], scale[0]);
        self.rate(&format!("{b}.alpha"), k, phi[2], scale[1]);
    }

    /// Prints the worst errors (shown with `--nocapture`).
    fn report(&self) {
        println!(
            "{}: {} steps, worst position error {:.2e}, worst relative rate error {:.2e} (allowed {:.1e})",
            self.name,
            self.table.t.len(),
            self.pos,
            self.rate,
            self.rate_tol
        );
    }
}

/// An angle difference in (−π, π].
fn wrap(a: f64) -> f64 {
    let w = a.rem_euclid(2.0 * PI);
    if w > PI {
        w - 2.0 * PI
    } else {
        w
    }
}

/// A body point of the loaded model (m). Each test restates its file's
/// parameters in Rust; comparing a point built from them with the loaded one
/// catches a test and a file that drift apart.
fn point_of(loaded: &Loaded, body: &str, point: &str) -> [f64; 2] {
    let id = loaded.model.body_id(body).unwrap();
    loaded.model.body(id).point(point).unwrap()
}

// ---------------------------------------------------------------------------
// 1. Driven simple pendulum
// ---------------------------------------------------------------------------

/// θ = θ0 sin ωt from the downward vertical; bob at (L sin θ, h − L cos θ).
#[test]
fn pendulum() {
    let (loaded, mut c) = Check::new("pendulum");
    let (h, l, th0, w) = (1.2, 0.8, 30f64.to_radians(), PI);
    assert_eq!(point_of(&loaded, "arm", "bob"), [0.0, -l]);
    assert_eq!(point_of(&loaded, "ground", "O"), [0.0, h]);
    for (k, t) in c.t().into_iter().enumerate() {
        let th = th0 * (w * t).sin();
        let thd = th0 * w * (w * t).cos();
        let thdd = -th0 * w * w * (w * t).sin();
        // Scales: the amplitudes θ0 ω and θ0 ω².
        c.rotation("arm", k, [th, thd, thdd], [th0 * w, th0 * w * w]);
        let (s, co) = th.sin_cos();
        c.point(
            "arm.bob",
            k,
            [l * s, h - l * co],
            [l * co * thd, l * s * thd],
            [
                l * (co * thdd - s * thd * thd),
                l * (s * thdd + co * thd * thd),
            ],
            [l * th0 * w, l * th0 * w * w],
        );
    }
    c.report();
}

// ---------------------------------------------------------------------------
// 2–3. Offset slider-crank
// ---------------------------------------------------------------------------

/// Slider-crank geometry (m): crank r, rod l, offset e.
const SC: (f64, f64, f64) = (0.05, 0.2, 0.01);

/// The rod angle ψ of A–B and its rates, from the crank angle θ and slider
/// position x with their rates (each [value, rate, second rate]):
/// u = x − r cos θ, v = e − r sin θ, ψ = atan2(v, u), u² + v² = l², so
/// ψ̇ = (u v̇ − v u̇)/l² and ψ̈ = (u v̈ − v ü)/l².
fn rod_angle(th: [f64; 3], x: [f64; 3]) -> [f64; 3] {
    let (r, l, e) = SC;
    let (s, c) = th[0].sin_cos();
    let (u, v) = (x[0] - r * c, e - r * s);
    let ud = x[1] + r * s * th[1];
    let udd = x[2] + r * (c * th[1] * th[1] + s * th[2]);
    let vd = -r * c * th[1];
    let vdd = r * (s * th[1] * th[1] - c * th[2]);
    [
        v.atan2(u),
        (u * vd - v * ud) / (l * l),
        (u * vdd - v * udd) / (l * l),
    ]
}

/// Point [r cos θ, r sin θ] turning about the origin at θ̇, θ̈:
/// (position, velocity, acceleration).
fn on_circle(r: f64, centre: [f64; 2], th: [f64; 3]) -> ([f64; 2], [f64; 2], [f64; 2]) {
    let (s, c) = th[0].sin_cos();
    (
        [centre[0] + r * c, centre[1] + r * s],
        [-r * s * th[1], r * c * th[1]],
        [
            -r * (c * th[1] * th[1] + s * th[2]),
            r * (c * th[2] - s * th[1] * th[1]),
        ],
    )
}

/// Crank-driven: x = r cos θ + D, D = sqrt(l² − σ²), σ = r sin θ − e;
/// Ḋ = −σσ̇/D, D̈ = −(σ̇² + σσ̈ + Ḋ²)/D (from D² = l² − σ²).
#[test]
fn slider_crank() {
    let (loaded, mut c) = Check::new("slider_crank");
    let (r, l, e) = SC;
    let (w, th0) = (2.0 * PI * 10.0, 30f64.to_radians());
    assert_eq!(point_of(&loaded, "rod", "B"), [l / 2.0, 0.0]);
    assert_eq!(point_of(&loaded, "crank", "A"), [r, 0.0]);
    assert_eq!(point_of(&loaded, "ground", "S"), [0.0, e]);
    for (k, t) in c.t().into_iter().enumerate() {
        let th = [th0 + w * t, w, 0.0];
        let (s, co) = th[0].sin_cos();
        let sg = [
            r * s - e,
            r * co * th[1],
            r * (co * th[2] - s * th[1] * th[1]),
        ];
        let dd = (l * l - sg[0] * sg[0]).sqrt();
        let ddot = -sg[0] * sg[1] / dd;
        let dddot = -(sg[1] * sg[1] + sg[0] * sg[2] + ddot * ddot) / dd;
        let x = [
            r * co + dd,
            -r * s * th[1] + ddot,
            -r * (co * th[1] * th[1] + s * th[2]) + dddot,
        ];
        // Scales: r ω and r ω² for the slider and the crank pin; (r/l) ω and
        // (r/l) ω² for the rod's rotation.
        let (vs, as_) = (r * w, r * w * w);
        c.rotation("crank", k, th, [w, w * w]);
        c.pos("slider.x", k, x[0]);
        c.pos("slider.y", k, e);
        c.angle("slider.phi", k, 0.0);
        c.rate("slider.vx", k, x[1], vs);
        c.rate("slider.ax", k, x[2], as_);
        c.rate("slider.vy", k, 0.0, vs);
        c.rate("slider.ay", k, 0.0, as_);
        c.point(
            "slider.B",
            k,
            [x[0], e],
            [x[1], 0.0],
            [x[2], 0.0],
            [vs, as_],
        );
        let (pa, va, aa) = on_circle(r, [0.0, 0.0], th);
        c.point("crank.A", k, pa, va, aa, [vs, as_]);
        let psi = rod_angle(th, x);
        c.rotation("rod", k, psi, [r / l * w, r / l * w * w]);
    }
    c.report();
}

/// `machine_slider_crank.toml` (in-line, r = 0.1 m, l = 0.35 m, 300 rpm
/// from θ = 0): the slider at x = r cos θ + √(l² − r² sin² θ) and its
/// rates. Its machine figures are checked in `issue32_machine.rs`.
#[test]
fn machine_slider_crank() {
    let (_loaded, mut c) = Check::new("machine_slider_crank");
    let (r, l, w) = (0.1, 0.35, 2.0 * PI * 5.0);
    for (k, t) in c.t().into_iter().enumerate() {
        let th = w * t;
        let (s, co) = th.sin_cos();
        let sg = [r * s, r * co * w, -r * s * w * w];
        let dd = (l * l - sg[0] * sg[0]).sqrt();
        let ddot = -sg[0] * sg[1] / dd;
        let dddot = -(sg[1] * sg[1] + sg[0] * sg[2] + ddot * ddot) / dd;
        let (vs, as_) = (r * w, r * w * w);
        c.rotation("crank", k, [th, w, 0.0], [w, w * w]);
        c.pos("slider.x", k, r * co + dd);
        c.rate("slider.vx", k, -r * s * w + ddot, vs);
        c.rate("slider.ax", k, -r * co * w * w + dddot, as_);
    }
    c.report();
}

/// Slider-driven: x = xm + s0 sin ωt; θ = δ + acos(K / (2 r ρ)) with
/// K = x² + e² + r² − l², ρ = |(x, e)|, δ = atan2(e, x) (crank above the
/// line). Rates by implicit differentiation of
/// F(θ, x) = x cos θ + e sin θ − (x² + e² + r² − l²)/(2r) = 0:
/// F_θ θ̇ + F_x ẋ = 0 and
/// F_θ θ̈ + F_θθ θ̇² + 2 F_θx θ̇ ẋ + F_xx ẋ² + F_x ẍ = 0.
#[test]
fn slider_crank_slider_driven() {
    let (loaded, mut c) = Check::new("slider_crank_slider_driven");
    let (r, l, e) = SC;
    let (xm, s0, w) = (0.2, 0.035, 2.0 * PI);
    assert_eq!(point_of(&loaded, "rod", "A"), [-l / 2.0, 0.0]);
    assert_eq!(point_of(&loaded, "ground", "S"), [0.0, e]);
    // The stroke keeps clear of both dead centres, |K/(2rρ)| < 1.
    let reach = (
        ((l - r) * (l - r) - e * e).sqrt(),
        ((l + r) * (l + r) - e * e).sqrt(),
    );
    assert!(reach.0 + 0.01 < xm - s0 && xm + s0 < reach.1 - 0.01);
    for (k, t) in c.t().into_iter().enumerate() {
        let x = [
            xm + s0 * (w * t).sin(),
            s0 * w * (w * t).cos(),
            -s0 * w * w * (w * t).sin(),
        ];
        let kk = x[0] * x[0] + e * e + r * r - l * l;
        let rho = x[0].hypot(e);
        let th0 = e.atan2(x[0]) + (kk / (2.0 * r * rho)).acos();
        let (s, co) = th0.sin_cos();
        let f_th = -x[0] * s + e * co;
        let f_x = co - x[0] / r;
        let (f_thth, f_thx, f_xx) = (-x[0] * co - e * s, -s, -1.0 / r);
        let th1 = -f_x * x[1] / f_th;
        let th2 =
            -(f_thth * th1 * th1 + 2.0 * f_thx * th1 * x[1] + f_xx * x[1] * x[1] + f_x * x[2])
                / f_th;
        let th = [th0, th1, th2];
        // Scales: s0 ω, s0 ω² for the slider; divided by r for the crank,
        // by l for the rod; the crank pin moves about as fast as the slider.
        let (vs, as_) = (s0 * w, s0 * w * w);
        c.pos("slider.x", k, x[0]);
        c.rate("slider.vx", k, x[1], vs);
        c.rate("slider.ax", k, x[2], as_);
        c.rotation("crank", k, th, [vs / r, as_ / r]);
        let (pa, va, aa) = on_circle(r, [0.0, 0.0], th);
        c.point("crank.A", k, pa, va, aa, [vs, as_]);
        c.point("rod.B", k, [x[0], e], [x[1], 0.0], [x[2], 0.0], [vs, as_]);
        c.rotation("rod", k, rod_angle(th, x), [vs / l, as_ / l]);
    }
    c.report();
}

// ---------------------------------------------------------------------------
// 4. Four-bar crank-rocker
// ---------------------------------------------------------------------------

/// Link angles θ₃, θ₄ and their rates from Freudenstein (open branch, B
/// above the ground line); the coupler point P = A + A(θ₃)[b/2, p] and the
/// rocker tip B by rigid-body kinematics on those.
#[test]
fn four_bar() {
    let (loaded, mut c) = Check::new("four_bar");
    let l @ [d, a, b, cc] = [0.4, 0.12, 0.38, 0.3];
    let (p, w, th0) = (0.1, 2.0 * PI, 0.3);
    assert_eq!(point_of(&loaded, "coupler", "P"), [b / 2.0, p]);
    assert_eq!(point_of(&loaded, "rocker", "B"), [cc, 0.0]);
    assert_eq!(point_of(&loaded, "ground", "O4"), [d, 0.0]);
    // Grashof crank-rocker: the crank is the shortest link and s + l ≤ p + q.
    assert!(a + d <= b + cc && a < b.min(cc).min(d));
    for (k, t) in c.t().into_iter().enumerate() {
        let th2 = [th0 + w * t, w, 0.0];
        let (th, om, al) = camlink_testkit::common::freudenstein(l, th2[0], w, -1.0);
        assert!(th[1].sin() > 0.0, "open branch");
        // Scales: a ω and a ω² for points, (a/c) ω and (a/c) ω² for rotations.
        let (vs, as_) = (a * w, a * w * w);
        c.rotation("crank", k, th2, [w, w * w]);
        c.rotation("coupler", k, [th[0], om[0], al[0]], [vs / cc, as_ / cc]);
        c.rotation("rocker", k, [th[1], om[1], al[1]], [vs / cc, as_ / cc]);
        let (ra, va, aa) = on_circle(a, [0.0, 0.0], th2);
        let (s3, c3) = th[0].sin_cos();
        let rho = [b / 2.0 * c3 - p * s3, b / 2.0 * s3 + p * c3];
        let (w3, a3) = (om[0], al[0]);
        c.point(
            "coupler.P",
            k,
            [ra[0] + rho[0], ra[1] + rho[1]],
            [va[0] - w3 * rho[1], va[1] + w3 * rho[0]],
            [
                aa[0] - a3 * rho[1] - w3 * w3 * rho[0],
                aa[1] + a3 * rho[0] - w3 * w3 * rho[1],
            ],
            [vs, as_],
        );
        let (rb, vb, ab) = on_circle(cc, [d, 0.0], [th[1], om[1], al[1]]);
        c.point("rocker.B", k, rb, vb, ab, [vs, as_]);
    }
    c.report();
}

// ---------------------------------------------------------------------------
// 5. Crank-shaper quick return
// ---------------------------------------------------------------------------

/// Lever angle β = atan2(r sin θ, d + r cos θ) about O4 at the origin, crank
/// pivot O2 = (d, 0). With ρ² = d² + r² + 2dr cos θ:
/// β̇ = N(θ) θ̇, N = r (r + d cos θ)/ρ²; β̈ = N θ̈ + N′ θ̇²,
/// N′ = r d sin θ (r² − d²)/ρ⁴.
#[test]
fn whitworth_global() {
    // Bodies in global coordinates; the comparison with frames placed by
    // hand is in global_points.rs.
    let (_, mut c) = Check::new("whitworth_global");
    let (d, r, big_r, l, w) = (0.05, 0.1, 0.08, 0.3, 2.0 * PI);
    for (k, t) in c.t().into_iter().enumerate() {
        let th = [w * t, w, 0.0];
        c.rotation("crank", k, th, [w, w * w]);
        let (pa, va, aa) = on_circle(r, [0.0, d], th);
        c.point("crank.A", k, pa, va, aa, [r * w, r * w * w]);
        // The lever through A: β = atan2(d + r sin θ, r cos θ); its arm B
        // opposite A, the ram C on the x axis at the rod's length.
        let beta = (d + r * th[0].sin()).atan2(r * th[0].cos());
        let (bx, by) = (-big_r * beta.cos(), -big_r * beta.sin());
        c.pos("lever.B.x", k, bx);
        c.pos("lever.B.y", k, by);
        c.pos("ram.C.x", k, bx - (l * l - by * by).sqrt());
        c.pos("ram.C.y", k, 0.0);
    }
    c.report();
}

#[test]
fn quick_return() {
    let (loaded, mut c) = Check::new("quick_return");
    let (d, r, l, w, th0) = (0.3, 0.1, 0.5, 2.0 * PI, 0.0);
    assert_eq!(point_of(&loaded, "lever", "T"), [l, 0.0]);
    assert_eq!(point_of(&loaded, "ground", "O2"), [d, 0.0]);
    for (k, t) in c.t().into_iter().enumerate() {
        let th = [th0 + w * t, w, 0.0];
        let (s, co) = th[0].sin_cos();
        let rho2 = d * d + r * r + 2.0 * d * r * co;
        let n = r * (r + d * co) / rho2;
        let n1 = r * d * s * (r * r - d * d) / (rho2 * rho2);
        let b = [
            (r * s).atan2(d + r * co),
            n * th[1],
            n * th[2] + n1 * th[1] * th[1],
        ];
        // Scales: (r/d) ω and (r/d) ω² for the lever, times L at its tip.
        let (ws, als) = (r / d * w, r / d * w * w);
        c.rotation("crank", k, th, [w, w * w]);
        c.rotation("lever", k, b, [ws, als]);
        let (pt, vt, at) = on_circle(l, [0.0, 0.0], b);
        c.point("lever.T", k, pt, vt, at, [l * ws, l * als]);
        let (pa, va, aa) = on_circle(r, [d, 0.0], th);
        c.point("crank.A", k, pa, va, aa, [r * w, r * w * w]);
    }
    // camlink's lever swings ±asin(r/d), reached where cos θ = −r/d (crank
    // perpendicular to the slot). Its extreme angles on the output grid
    // overshoot that by at most POS_TOL and fall short of it by at most the
    // grid's sampling error ½ max|β″| (Δθ/2)², with Δθ = ω·step the crank's
    // turn per output step and β″ = dN/dθ = N′, |N′| ≤ r d (d² − r²)/(d − r)⁴
    // (|sin θ| ≤ 1, ρ ≥ d − r).
    let lever: Vec<f64> = c
        .table
        .channel("lever.phi")
        .unwrap()
        .into_iter()
        .map(wrap)
        .collect();
    let (lo, hi) = lever
        .iter()
        .fold((f64::MAX, f64::MIN), |m, &b| (m.0.min(b), m.1.max(b)));
    let extreme = (r / d).asin();
    let dth = w * loaded.analysis.step.unwrap();
    let sampling = 0.5 * r * d * (d * d - r * r) / (d - r).powi(4) * (dth / 2.0).powi(2);
    for (side, got, sign) in [("largest", hi, 1.0), ("smallest", lo, -1.0)] {
        // How far camlink's extreme reaches beyond ±asin(r/d).
        let over = sign * got - extreme;
        assert!(
            over <= POS_TOL && -over <= sampling + POS_TOL,
            "quick_return: {side} lever angle {got} rad, want {} rad = ±asin(r/d), \
             at most {POS_TOL:.0e} rad beyond it and {:.1e} rad short of it",
            sign * extreme,
            sampling + POS_TOL
        );
        println!("quick_return: {side} lever angle {over:.2e} rad beyond ±asin(r/d)");
    }
    c.report();
}

// ---------------------------------------------------------------------------
// 6. Rack and pinion
// ---------------------------------------------------------------------------

/// φ = φ0 sin ωt; a counter-clockwise pinion above the rack drives the rack
/// towards +x (the pinion's lowest point moves at ω × (0, −R) = (ωR, 0)), so
/// x_rack = R φ, ẋ = R φ̇, ẍ = R φ̈.
#[test]
fn rack_pinion() {
    let (loaded, mut c) = Check::new("rack_pinion");
    let (rr, phi0, w) = (0.02, 270f64.to_radians(), PI);
    assert_eq!(point_of(&loaded, "pinion", "tooth"), [rr, 0.0]);
    assert_eq!(point_of(&loaded, "rack", "E"), [0.3, 0.0]);
    for (k, t) in c.t().into_iter().enumerate() {
        let phi = [
            phi0 * (w * t).sin(),
            phi0 * w * (w * t).cos(),
            -phi0 * w * w * (w * t).sin(),
        ];
        // Scales: φ0 ω and φ0 ω², times R for the rack.
        let (ws, als) = (phi0 * w, phi0 * w * w);
        c.rotation("pinion", k, phi, [ws, als]);
        c.rotation("rack", k, [0.0; 3], [ws, als]);
        c.pos("rack.x", k, rr * phi[0]);
        c.pos("rack.y", k, 0.0);
        c.rate("rack.vx", k, rr * phi[1], rr * ws);
        c.rate("rack.ax", k, rr * phi[2], rr * als);
        c.point(
            "rack.E",
            k,
            [0.3 + rr * phi[0], 0.0],
            [rr * phi[1], 0.0],
            [rr * phi[2], 0.0],
            [rr * ws, rr * als],
        );
        let (pt, vt, at) = on_circle(rr, [0.0, rr], phi);
        c.point("pinion.tooth", k, pt, vt, at, [rr * ws, rr * als]);
    }
    c.report();
}

// ---------------------------------------------------------------------------
// 7. Gear train
// ---------------------------------------------------------------------------

/// Fixed shafts, all gears starting at φ = 0: φ2 = −(R1/R2) φ1,
/// φ3 = (R1/R3) φ1, φ4 = (R3b/R4) φ3; accelerations zero.
#[test]
fn gear_train() {
    let (loaded, mut c) = Check::new("gear_train");
    let (r1, r2, r3, r3b, r4, w) = (0.03, 0.05, 0.04, 0.015, 0.06, 4.0 * PI);
    let c3 = [r1 + 2.0 * r2 + r3, 0.0];
    let c4 = [c3[0] + r4 - r3b, 0.0];
    assert_eq!(point_of(&loaded, "ground", "C3"), c3);
    assert_eq!(point_of(&loaded, "ground", "C4"), c4);
    assert_eq!(point_of(&loaded, "ring", "P"), [r4, 0.0]);
    for (k, t) in c.t().into_iter().enumerate() {
        let ratios = [1.0, -r1 / r2, r1 / r3, r1 / r3 * r3b / r4];
        // Scales: ω1 and ω1² for every rotation (the accelerations are zero,
        // so this bounds them absolutely by a multiple of ω1²), times R at the pitch points.
        let (ws, als) = (w, w * w);
        for (body, ratio) in ["gear1", "gear2", "gear3", "ring"].iter().zip(ratios) {
            c.rotation(body, k, [ratio * w * t, ratio * w, 0.0], [ws, als]);
        }
        let (p3, v3, a3) = on_circle(r3, c3, [ratios[2] * w * t, ratios[2] * w, 0.0]);
        c.point("gear3.P", k, p3, v3, a3, [r3 * ws, r3 * als]);
        let (p4, v4, a4) = on_circle(r4, c4, [ratios[3] * w * t, ratios[3] * w, 0.0]);
        c.point("ring.P", k, p4, v4, a4, [r4 * ws, r4 * als]);
    }
    c.report();
}

// ---------------------------------------------------------------------------
// 7b. Planetary stage
// ---------------------------------------------------------------------------

/// Sun driven at ω_s, ring fixed, all bodies starting at φ = 0:
/// ω_c = ω_s Rs/(Rs + Rr), ω_p = ω_c − (Rs/Rp)(ω_s − ω_c); the planet centre
/// is (Rs + Rp)(cos φ_c, sin φ_c). The sun–planet centre line points along
/// the carrier (θ = φ_c), the planet–ring one back to the centre
/// (θ = φ_c + π), both continuous over turns.
#[test]
fn planetary() {
    let (loaded, mut c) = Check::new("planetary");
    let (rs, rp, w) = (0.03, 0.02, 10.0 * PI);
    let rr = rs + 2.0 * rp;
    assert_eq!(point_of(&loaded, "carrier", "pin"), [rs + rp, 0.0]);
    assert_eq!(point_of(&loaded, "planet", "P"), [rp, 0.0]);
    let wc = w * rs / (rs + rr);
    let wp = wc - rs / rp * (w - wc);
    // The planet's rate from the other mesh, with the fixed ring:
    // (ω_p − ω_c)/(0 − ω_c) = Rr/Rp; camlink's is checked against both.
    let wp_ring = wc - rr / rp * wc;
    let own = |c: &Check, joint: &str| {
        let prefix = format!("{joint}.");
        let names: Vec<&String> = c
            .table
            .channels
            .iter()
            .filter(|n| n.starts_with(&prefix))
            .collect();
        assert_eq!(
            names.len(),
            1,
            "one own coordinate for '{joint}': {names:?}"
        );
        names[0].clone()
    };
    let (sun_planet, planet_ring) = (own(&c, "sun_planet"), own(&c, "planet_ring"));
    for (k, t) in c.t().into_iter().enumerate() {
        // Scales: ω_s and ω_s² (accelerations are zero: bounded absolutely by a multiple of ω_s²),
        // times the radius at points.
        let (ws, als) = (w, w * w);
        c.rotation("sun", k, [w * t, w, 0.0], [ws, als]);
        c.rotation("carrier", k, [wc * t, wc, 0.0], [ws, als]);
        c.rotation("planet", k, [wp * t, wp, 0.0], [ws, als]);
        c.rate("planet.omega", k, wp_ring, ws);
        let th_c = [wc * t, wc, 0.0];
        let (pc, vc, ac) = on_circle(rs + rp, [0.0, 0.0], th_c);
        c.point("carrier.pin", k, pc, vc, ac, [rs * ws, rs * als]);
        c.pos("planet.x", k, pc[0]);
        c.pos("planet.y", k, pc[1]);
        // Planet pitch point: centre motion plus rotation about the centre.
        let (pp, vp, ap) = on_circle(rp, [0.0, 0.0], [wp * t, wp, 0.0]);
        c.point(
            "planet.P",
            k,
            [pc[0] + pp[0], pc[1] + pp[1]],
            [vc[0] + vp[0], vc[1] + vp[1]],
            [ac[0] + ap[0], ac[1] + ap[1]],
            [rs * ws, rs * als],
        );
        c.pos(&sun_planet, k, wc * t);
        c.pos(&planet_ring, k, wc * t + PI);
    }
    c.report();
}

// ---------------------------------------------------------------------------
// Every example is tested and documented
// ---------------------------------------------------------------------------

/// The examples this file runs: the names passed to `Check::new` in its
/// source.
fn tested_examples() -> Vec<String> {
    let src = include_str!("examples.rs");
    let key = concat!("Check::new", "(\"");
    src.split(key)
        .skip(1)
        .filter_map(|s| s.split('"').next())
        .map(str::to_string)
        .collect()
}

/// Adding a model to `examples/` without a test here fails (cam and slot
/// examples are held to the same rule by cam_examples.rs, dynamics examples
/// by `tests/python/test_dyn_examples.py`).
#[test]
fn every_example_has_a_test() {
    let tested = tested_examples();
    let mut untested = Vec::new();
    let mut count = 0;
    for entry in std::fs::read_dir(examples_dir()).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        // Data files of the examples live in examples/data.
        if path.is_dir() && name == "data" {
            continue;
        }
        // simEngine2D course models are run and checked by camlink-adm's tests (adm.rs).
        if path.is_dir() && name == "simengine2d" {
            continue;
        }
        // Cam and slot examples are run, and checked for coverage, by
        // cam_examples.rs; dynamics examples by test_dyn_examples.py.
        if name.starts_with("cam_") || name.starts_with("slot_") || name.starts_with("dyn_") {
            continue;
        }
        // Study files (`study_*.toml`) name a model; tests/python/test_study.py runs them.
        if name.starts_with("study_") {
            continue;
        }
        // Synthesis problems (`synthesis_*.toml`) are solved and their
        // models run by crates/camlink-synth/tests.
        if name.starts_with("synthesis_") {
            continue;
        }
        let Some(stem) = name.strip_suffix(".toml") else {
            untested.push(format!("{name} (examples/ holds .toml model files only)"));
            continue;
        };
        count += 1;
        if !tested.iter().any(|t| t == stem) {
            untested.push(name);
        }
    }
    assert!(
        untested.is_empty(),
        "examples without a test in crates/camlink-model/tests/examples.rs: {untested:?}"
    );
    assert_eq!(
        count,
        tested.len(),
        "each example is tested once: {tested:?}"
    );
}

/// Every example has a section in `docs/examples.md` naming its file.
#[test]
fn every_example_is_documented() {
    let doc = std::fs::read_to_string(examples_dir().join("../docs/examples.md")).unwrap();
    for name in tested_examples() {
        assert!(
            doc.contains(&format!("examples/{name}.toml")),
            "docs/examples.md does not mention examples/{name}.toml"
        );
    }
}

// ---------------------------------------------------------------------------
// Regressions found while writing the examples
// ---------------------------------------------------------------------------

/// A gear pair whose centre line points along −x at the start (θ = π, the
/// planet–ring pair of `planetary.toml`) must start where it was placed:
/// the loader's default phase and the joint's initial centre-line angle
/// have to agree on θ = π rather than −π, or the assembly turns the
/// mechanism by half a turn to make up the 2π (Rr − Rp) of phase.
#[test]
fn issue_gear_centre_line_along_negative_x() {
    let text = r#"
        [ground]
        points = { O = [0, 0], C = [0.05, 0] }
        [[bodies]]
        name = "big"
        points = { C = [0, 0] }
        [[bodies]]
        name = "small"
        position = [0.05, 0]
        points = { C = [0, 0] }
        [[joints]]
        name = "big_shaft"
        type = "revolute"
        body_i = "ground"
        point_i = "O"
        body_j = "big"
        point_j = "C"
        [[joints]]
        name = "small_shaft"
        type = "revolute"
        body_i = "ground"
        point_i = "C"
        body_j = "small"
        point_j = "C"
        # body i is the one on the right: the centre line from i to j is −x.
        [[joints]]
        name = "mesh"
        type = "gear"
        body_i = "small"
        point_i = "C"
        radius_i = 0.02
        body_j = "big"
        point_j = "C"
        radius_j = 0.03
        [[drivers]]
        type = "absolute_phi"
        body = "small"
        f = "t"
    "#;
    let loaded = camlink_model::load_str(text, camlink_model::Format::Toml, "gear.toml").unwrap();
    let mut table = Table::default();
    run(
        &loaded.model,
        &[0.0, 0.1],
        &Settings::default(),
        &[],
        &mut table,
    )
    .unwrap();
    let big = table.channel("big.phi").unwrap();
    assert!(
        big[0].abs() < 1e-12,
        "the big gear turned to {} at t = 0",
        big[0]
    );
    // ω_big = −(R_small/R_big) ω_small.
    assert!((big[1] + 0.1 * 0.02 / 0.03).abs() < 1e-12, "{}", big[1]);
}
