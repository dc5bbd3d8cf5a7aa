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
