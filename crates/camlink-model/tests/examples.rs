//! Every model in `examples/` loaded from its file, run, and compared with a
//! closed-form answer written independently here.
//!
//! Tolerances: positions within 1e-9 (m or rad, absolute); velocities and
//! accelerations within 1e-7 relative, |got − want| ≤ 1e-7·max(|want|, scale),
//! where `scale` is a typical magnitude of the quantity over the run (stated
//! at each check), so that values passing through zero are held to an
//! absolute 1e-7·scale.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use camlink_core::kinematics::{run, time_grid, Settings, Table};
use camlink_model::{load_path, Loaded};

/// Position tolerance (m or rad).
const POS_TOL: f64 = 1e-9;
/// Relative tolerance of velocities and accelerations.
const RATE_TOL: f64 = 1e-7;

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
    };
    let points = loaded.point_outputs().unwrap();
    let mut table = Table::default();
    let summary = run(&loaded.model, &times, &settings, &points, &mut table)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(summary.steps, times.len(), "{name}");
    assert!(times.len() > 10, "{name}: too few steps to check");
    (loaded, table)
}

/// Compares results with closed forms and remembers the worst errors.
struct Check {
    name: &'static str,
    table: Table,
    /// Largest position error (m or rad).
    pos: f64,
    /// Largest relative velocity or acceleration error.
    rate: f64,
}

impl Check {
    fn new(name: &'static str) -> (Loaded, Check) {
        let (loaded, table) = run_example(name);
        let check = Check {
            name,
            table,
            pos: 0.0,
            rate: 0.0,
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
    /// |got − want| ≤ `RATE_TOL`·max(|want|, scale).
    fn rate(&mut self, c: &str, k: usize, want: f64, scale: f64) {
        let got = self.at(c, k);
        let err = (got - want).abs() / want.abs().max(scale);
        assert!(
            err <= RATE_TOL,
            "{}: {c} at t = {}: got {got}, want {want} (relative error {err:.2e})",
            self.name,
            self.table.t[k]
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
            "{}: {} steps, worst position error {:.2e}, worst relative rate error {:.2e}",
            self.name,
            self.table.t.len(),
            self.pos,
            self.rate
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
    [v.atan2(u), (u * vd - v * ud) / (l * l), (u * vdd - v * udd) / (l * l)]
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
        let sg = [r * s - e, r * co * th[1], r * (co * th[2] - s * th[1] * th[1])];
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
        c.point("slider.B", k, [x[0], e], [x[1], 0.0], [x[2], 0.0], [vs, as_]);
        let (pa, va, aa) = on_circle(r, [0.0, 0.0], th);
        c.point("crank.A", k, pa, va, aa, [vs, as_]);
        let psi = rod_angle(th, x);
        c.rotation("rod", k, psi, [r / l * w, r / l * w * w]);
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
    let reach = (((l - r) * (l - r) - e * e).sqrt(), ((l + r) * (l + r) - e * e).sqrt());
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
        let th2 = -(f_thth * th1 * th1 + 2.0 * f_thx * th1 * x[1] + f_xx * x[1] * x[1] + f_x * x[2])
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
