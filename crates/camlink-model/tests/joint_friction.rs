//! Coulomb friction in joints (`friction = { mu, radius }`, issue 30):
//! a block on an incline that sticks below the friction angle and slides
//! with the closed-form acceleration above it (on a translational joint
//! and as a pin in a straight slot), a pendulum whose amplitude falls by
//! the closed-form step per swing, the friction channels against hand
//! values, inverse dynamics with the friction torque in the motor's
//! effort, and bad input.

use camlink_core::dynamics::{integrator, inverse};
use camlink_core::run::{self, time_grid, Table};
use camlink_model::{load_path, load_str, Format};

const G: f64 = 9.81;

/// A block of mass 2 kg on a guide at angle `alpha` (rad) above +x, the
/// guide given by `guide` (a joint, with `{friction}` in it), starting at
/// the origin with speed `v0` (m/s) up the guide.
fn incline(alpha: f64, v0: f64, guide: &str) -> String {
    let (c, s) = (alpha.cos(), alpha.sin());
    format!(
        r#"
[model]
gravity = [0, -{G}]

[ground]
points = {{ A = [0, 0], B = [{c}, {s}] }}

[[bodies]]
name = "block"
mass = 2
inertia = 0.01
velocity = [{vx}, {vy}]

[[curves]]
name = "slot"
source = "line"
body = "ground"
from = [-3, {m_s}]
to = [{c}, {s}]

{guide}
"#,
        m_s = -3.0 * s / c,
        vx = v0 * c,
        vy = v0 * s,
    )
}

fn simulate(text: &str, t_end: f64, out: f64, h: f64) -> Table {
    let model = load_str(text, Format::Toml, "m.toml")
        .unwrap_or_else(|e| panic!("{e}"))
        .model;
    let times = time_grid(t_end, out).unwrap();
    let settings = integrator::Settings {
        step: h,
        tol: 1e-10,
        ..integrator::Settings::default()
    };
    let mut t = Table::default();
    integrator::run(&model, &times, &settings, &[], &mut t).unwrap_or_else(|e| panic!("{e}"));
    t
}

fn ch(t: &Table, name: &str) -> Vec<f64> {
    t.channel(name)
        .unwrap_or_else(|| panic!("no channel {name}"))
}

/// The block on a translational joint along (cos α, sin α), starting with
/// speed `v0` up it.
fn block_on_guide(alpha: f64, v0: f64, friction: &str) -> String {
    let guide = format!(
        r#"
[[joints]]
type = "translational"
name = "guide"
body_i = "ground"
axis = [{}, {}]
body_j = "block"
friction = {friction}
"#,
        alpha.cos(),
        alpha.sin()
    );
    incline(alpha, v0, &guide)
}

/// u in [0, 1] with s(u) = (3u − u³)/2 = `ratio`: the creep speed of a
/// stuck joint is u v_s (docs/friction.md).
fn creep(ratio: f64) -> f64 {
    let mut u = ratio;
    for _ in 0..50 {
        u -= ((3.0 * u - u.powi(3)) / 2.0 - ratio) / ((3.0 - 3.0 * u * u) / 2.0);
    }
    u
}

#[test]
fn issue30_a_block_below_the_friction_angle_sticks() {
    // tan α = μ/2: gravity pulls with half the friction the joint can give.
    let (mu, vs, t_end) = (0.4, 1e-4, 2.0);
    let alpha = (mu / 2.0f64).atan();
    let text = block_on_guide(
        alpha,
        0.0,
        &format!("{{ mu = {mu}, transition_speed = {vs} }}"),
    );
    let (t, h) = (simulate(&text, t_end, 0.01, 1e-3), 1e-3);
    let (x, y) = (ch(&t, "block.x"), ch(&t, "block.y"));
    let moved = x.last().unwrap().hypot(*y.last().unwrap());
    // Creep bound: |v| ≤ u v_s with s(u) = tan α / μ, over the run and
    // the first step, where the integrator (ρ∞ = 0.8) rings down the jump
    // of the acceleration from the frictionless start at v = 0.
    let bound = creep(alpha.tan() / mu) * vs * (t_end + h);
    assert!(moved <= bound, "moved {moved} m, bound {bound} m");
    assert!(
        moved > 0.5 * bound,
        "the regularised law creeps ({moved} m)"
    );
    // The friction holds the block: m g sin α up the slope, and dissipates.
    let (f, p) = (
        ch(&t, "guide.friction_force"),
        ch(&t, "guide.friction_power"),
    );
    let hold = 2.0 * G * alpha.sin();
    for k in 10..t.t.len() {
        assert!(
            (f[k] - hold).abs() < 1e-6 * hold,
            "t = {}: {} vs {hold}",
            t.t[k],
            f[k]
        );
        assert!(p[k] <= 0.0 && p[k] > -hold * vs);
    }
}

#[test]
fn issue30_a_block_above_the_friction_angle_slides_at_the_closed_form_rate() {
    // Launched down the slope at 0.1 m/s, so that the slip speed is past
    // the transition band from the start (see the next test for a start
    // from rest).
    let (mu, vs, alpha, v0) = (0.3, 1e-4, 30f64.to_radians(), -0.1);
    let text = block_on_guide(
        alpha,
        v0,
        &format!("{{ mu = {mu}, transition_speed = {vs} }}"),
    );
    let t = simulate(&text, 1.0, 0.01, 1e-3);
    // Down the slope at a = g (sin α − μ cos α).
    let a = G * (alpha.sin() - mu * alpha.cos());
    let (ax, ay) = (ch(&t, "block.ax"), ch(&t, "block.ay"));
    let (vx, vy) = (ch(&t, "block.vx"), ch(&t, "block.vy"));
    let (f, p) = (
        ch(&t, "guide.friction_force"),
        ch(&t, "guide.friction_power"),
    );
    let normal = 2.0 * G * alpha.cos();
    for k in 0..t.t.len() {
        let along = ax[k] * alpha.cos() + ay[k] * alpha.sin();
        // Past the transition band the law is μ N sign(v) exactly:
        // Newton's tolerance is the error.
        assert!(
            (along + a).abs() < 1e-8,
            "t = {}: {along} vs {}",
            t.t[k],
            -a
        );
        let v = vx[k].hypot(vy[k]);
        // N from λ, which Newton leaves within its tolerance.
        let (fw, pw) = (mu * normal, -mu * normal * v);
        assert!((f[k] - fw).abs() < 1e-8 * fw, "friction {} vs {fw}", f[k]);
        assert!(
            (p[k] - pw).abs() < 1e-8 * fw * (1.0 + v),
            "power {} vs {pw}",
            p[k]
        );
    }
    // s = v0 t − a t²/2 at t = 1 s: the integrator is second order, and
    // exact for a constant acceleration.
    let s = x_along(&t, alpha);
    assert!((s - v0 + 0.5 * a).abs() < 1e-9, "{s} vs {}", v0 - 0.5 * a);
}

#[test]
fn issue30_a_block_released_from_rest_keeps_half_a_step_of_its_start() {
    // At rest the regularised law gives no force: the consistent start
    // accelerates at a₀ = g sin α, and the slip passes the band in
    // v_s / a = 4e-5 s, well inside the first step h. The generalized-α
    // method spreads the jump D = a₀ − a of the acceleration over the
    // steps after it: its pseudo-acceleration deviates by d₀ = D, then
    // d₁ = (α_f − α_m) D/(1 − α_m), d_{n+1} = −α_m d_n/(1 − α_m), and the
    // velocity gains h ((1 − γ) d₀ + Σ_{n≥1} d_n) = h D/2 for every ρ∞.
    // After that the block slides at the closed-form rate.
    let (mu, alpha, h) = (0.3, 30f64.to_radians(), 1e-3);
    let text = block_on_guide(alpha, 0.0, &format!("{{ mu = {mu} }}"));
    let t = simulate(&text, 1.0, 0.01, h);
    let a = G * (alpha.sin() - mu * alpha.cos());
    let jump = G * mu * alpha.cos();
    let (vx, vy) = (ch(&t, "block.vx"), ch(&t, "block.vy"));
    // From t = 0.02 s (20 steps) the deviation has decayed as (−1/2)^n.
    for k in 2..t.t.len() {
        let v = vx[k] * alpha.cos() + vy[k] * alpha.sin();
        let want = -a * t.t[k] - 0.5 * h * jump;
        assert!((v - want).abs() < 1e-8, "t = {}: {v} vs {want}", t.t[k]);
    }
}

fn x_along(t: &Table, alpha: f64) -> f64 {
    let (x, y) = (ch(t, "block.x"), ch(t, "block.y"));
    x.last().unwrap() * alpha.cos() + y.last().unwrap() * alpha.sin()
}

#[test]
fn issue30_a_pin_in_a_slot_has_the_same_friction_as_the_guide() {
    let alpha = 30f64.to_radians();
    let pin = r#"
[[joints]]
type = "point_follower"
name = "guide"
body_i = "block"
curve_j = "slot"
friction = { mu = 0.3, transition_speed = 1e-4 }

[[joints]]
type = "absolute_phi"
body = "block"
"#;
    let t = simulate(&incline(alpha, -0.1, pin), 1.0, 0.01, 1e-3);
    let a = G * (alpha.sin() - 0.3 * alpha.cos());
    let s = x_along(&t, alpha);
    assert!(
        (s + 0.1 + 0.5 * a).abs() < 1e-9,
        "{s} vs {}",
        -0.1 - 0.5 * a
    );
    // The channel is the force on body j, the slot (the ground), along
    // its tangent, which runs up the slope (from → to): the block's
    // friction up the slope is −μ N there.
    let f = ch(&t, "guide.friction_force");
    let want = -0.3 * 2.0 * G * alpha.cos();
    assert!(
        (f.last().unwrap() - want).abs() < 1e-8 * want.abs(),
        "{f:?} vs {want}"
    );
}

/// A rigid pendulum: mass 1 kg, centroid at L = 0.5 m from the pin, J' =
/// 0.01 kg·m², released at rest at θ₀ from the vertical, pin friction
/// `{mu, radius}`.
fn pendulum(theta0: f64, friction: &str) -> String {
    format!(
        r#"
[model]
gravity = [0, -{G}]

[[bodies]]
name = "arm"
angle = {phi}
mass = 1
inertia = 0.01
centroid = [0.5, 0]

[[joints]]
type = "revolute"
name = "pin"
body_i = "ground"
body_j = "arm"
friction = {friction}
"#,
        phi = -std::f64::consts::FRAC_PI_2 + theta0
    )
}

/// The turning points (t, θ) of θ = φ + π/2: the extremes between
/// samples, refined by the parabola through the three samples about each.
fn turning_points(t: &Table) -> Vec<(f64, f64)> {
    let phi = ch(t, "arm.phi");
    let th: Vec<f64> = phi
        .iter()
        .map(|p| p + std::f64::consts::FRAC_PI_2)
        .collect();
    let mut out = vec![(0.0, th[0])];
    for k in 1..th.len() - 1 {
        let (a, b, c) = (th[k - 1], th[k], th[k + 1]);
        if (b - a) * (c - b) < 0.0 {
            let d = a - 2.0 * b + c;
            let s = 0.5 * (a - c) / d;
            let dt = t.t[k + 1] - t.t[k];
            out.push((t.t[k] + s * dt, b - 0.25 * (a - c) * s));
        }
    }
    out
}

#[test]
fn issue30_pin_friction_takes_the_same_amplitude_off_every_swing() {
    let (mu, r, theta0) = (0.2, 0.02, 0.1);
    let text = pendulum(
        theta0,
        &format!("{{ mu = {mu}, radius = {r}, transition_speed = 1e-5 }}"),
    );
    let t = simulate(&text, 6.0, 1e-3, 1e-3);
    // Coulomb damping: with a friction torque T_f = μ r N, N ≈ m g, the
    // amplitude falls by 2 θ_f per half swing, θ_f = T_f / (m g L).
    let theta_f = mu * r / 0.5;
    let turns = turning_points(&t);
    assert!(turns.len() >= 6, "{turns:?}");
    for (k, &(_, th)) in turns.iter().enumerate().take(6) {
        let want = (theta0 - 2.0 * theta_f * k as f64) * if k % 2 == 0 { 1.0 } else { -1.0 };
        // N differs from m g by O(θ₀²) over a swing (≤ 1 % at θ₀ = 0.1 rad):
        // 2 % of the amplitude lost so far.
        let tol = 0.02 * 2.0 * theta_f * k as f64 + 1e-6;
        assert!(
            (th - want).abs() <= tol,
            "turn {k}: {th} vs {want} (tol {tol})"
        );
    }
    // The pendulum stops inside the dead band |θ| < θ_f and stays there.
    let last = ch(&t, "arm.phi").last().unwrap() + std::f64::consts::FRAC_PI_2;
    assert!(last.abs() < theta_f, "{last}");
    // Hand values: |T| = μ r N with N the pin force, while slipping; the
    // power is T θ̇ ≤ 0; the energy lost is the friction's work.
    let (torque, power) = (ch(&t, "pin.friction_torque"), ch(&t, "pin.friction_power"));
    let (fx, fy, w) = (ch(&t, "pin.fx_j"), ch(&t, "pin.fy_j"), ch(&t, "arm.omega"));
    for k in 0..t.t.len() {
        if (r * w[k]).abs() > 1e-5 {
            let n = fx[k].hypot(fy[k]);
            assert!((torque[k].abs() - mu * r * n).abs() < 1e-9 * n);
            assert!(torque[k] * w[k] < 0.0);
        }
        assert!((power[k] - torque[k] * w[k]).abs() < 1e-12);
    }
    let e = ch(&t, "energy.total");
    let work: f64 = (1..t.t.len())
        .map(|k| 0.5 * (power[k] + power[k - 1]) * (t.t[k] - t.t[k - 1]))
        .sum();
    let lost = e.last().unwrap() - e[0];
    assert!(
        (lost - work).abs() < 1e-3 * work.abs(),
        "ΔE {lost} vs work {work}"
    );
}

#[test]
fn issue30_inverse_dynamics_drives_through_the_pin_friction() {
    // A crank turned at a constant rate ω: the motor's torque is the
    // frictionless torque plus μ r N against the turning, N the pin force
    // of the run with friction.
    let text = |friction: &str| {
        format!(
            r#"
[[bodies]]
name = "crank"
mass = 1.5
inertia = 0.02
centroid = [0.1, 0]

[[joints]]
type = "revolute"
name = "pin"
body_i = "ground"
body_j = "crank"
{friction}

[[drivers]]
type = "revolute_angle"
name = "motor"
joint = "pin"
f = "3*t"
"#
        )
    };
    let run_inverse = |src: String| {
        let model = load_str(&src, Format::Toml, "m.toml")
            .unwrap_or_else(|e| panic!("{e}"))
            .model;
        let times = time_grid(2.0, 0.01).unwrap();
        let mut t = Table::default();
        inverse::run(&model, &times, &run::Settings::default(), &[], &mut t)
            .unwrap_or_else(|e| panic!("{e}"));
        t
    };
    let (mu, r) = (0.25, 0.015);
    let with = run_inverse(text(&format!("friction = {{ mu = {mu}, radius = {r} }}")));
    let without = run_inverse(text(""));
    let (e1, e0) = (ch(&with, "motor.effort"), ch(&without, "motor.effort"));
    let (fx, fy) = (ch(&with, "pin.fx_j"), ch(&with, "pin.fy_j"));
    let torque = ch(&with, "pin.friction_torque");
    for k in 0..with.t.len() {
        let n = fx[k].hypot(fy[k]);
        // The crank turns forward: the friction takes μ r N from the motor.
        assert!(
            (torque[k] + mu * r * n).abs() < 1e-12 * (1.0 + n),
            "{}",
            torque[k]
        );
        assert!(
            (e1[k] - e0[k] - mu * r * n).abs() < 1e-9,
            "t = {}: {} − {} vs {}",
            with.t[k],
            e1[k],
            e0[k],
            mu * r * n
        );
    }
}

fn load_error(text: &str) -> String {
    load_str(text, Format::Toml, "m.toml")
        .unwrap_err()
        .to_string()
}

#[test]
fn issue30_friction_on_a_joint_that_cannot_take_it_is_refused() {
    let text = r#"
[[bodies]]
name = "a"

[[bodies]]
name = "b"

[[joints]]
type = "revolute"
body_i = "ground"
body_j = "a"

[[joints]]
type = "gear"
body_i = "a"
radius_i = 0.1
body_j = "b"
radius_j = 0.2
friction = { mu = 0.1 }
"#;
    let e = load_error(text);
    assert!(e.starts_with("m.toml:19:"), "{e}");
    assert!(e.contains("joints[1].friction"), "{e}");
    assert!(e.contains("gear"), "{e}");
    assert!(e.contains("revolute, translational"), "{e}");
}

#[test]
fn issue30_bad_friction_numbers_name_their_field() {
    let cases = [
        (
            "{ mu = -0.1, radius = 0.01 }",
            "friction.mu",
            "zero or positive",
        ),
        (
            "{ mu = 0.1, radius = -0.01 }",
            "friction.radius",
            "zero or positive",
        ),
        ("{ mu = 0.1 }", "friction.radius", "needs the pin radius"),
        (
            "{ mu = 0.1, radius = 0.01, transition_speed = 0 }",
            "friction.transition_speed",
            "positive",
        ),
        (
            "{ mu = 0.1, radius = 0.01, sped = 1 }",
            "friction",
            "unknown field `sped`",
        ),
    ];
    for (friction, field, what) in cases {
        let e = load_error(&pendulum(0.1, friction));
        assert!(e.starts_with("m.toml:17:"), "{friction}: {e}");
        assert!(e.contains(&format!("joints[0].{field}")), "{friction}: {e}");
        assert!(e.contains(what), "{friction}: {e}");
    }
    let e = load_error(&block_on_guide(0.3, 0.0, "{ mu = 0.1, radius = 0.01 }"));
    assert!(e.contains("joints[0].friction.radius"), "{e}");
    assert!(e.contains("normal force"), "{e}");
}

#[test]
fn issue30_the_incline_friction_example_runs() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/dyn_incline_friction.toml");
    let loaded = load_path(&path).unwrap_or_else(|e| panic!("{e}"));
    let a = &loaded.analysis;
    let times = time_grid(a.t_end.unwrap(), a.step.unwrap()).unwrap();
    let settings = integrator::Settings {
        step: a.dynamics.h.unwrap_or(1e-3),
        rho_inf: a.dynamics.rho_inf,
        tol: 1e-10,
        ..integrator::Settings::default()
    };
    let mut t = Table::default();
    integrator::run(&loaded.model, &times, &settings, &[], &mut t).unwrap();
    // The steep block slides at g (sin α − μ cos α), with the start's
    // extra speed h D/2 (the test of a release from rest above); the
    // shallow one stays.
    let (mu, steep) = (0.3, 30f64.to_radians());
    let a = G * (steep.sin() - mu * steep.cos());
    let extra = 0.5 * settings.step * G * mu * steep.cos();
    let end = *t.t.last().unwrap();
    let (x, y) = (ch(&t, "slider.x"), ch(&t, "slider.y"));
    let s = (x.last().unwrap() - x[0]).hypot(y.last().unwrap() - y[0]);
    let want = 0.5 * a * end * end + extra * end;
    // The start's transient moves the position by O(h² D) besides.
    let transient = settings.step.powi(2) * G * mu * steep.cos();
    assert!((s - want).abs() < transient, "{s} vs {want}");
    let (x, y) = (ch(&t, "sticker.x"), ch(&t, "sticker.y"));
    let s = (x.last().unwrap() - x[0]).hypot(y.last().unwrap() - y[0]);
    assert!(s < 1e-4 * end, "{s}");
}

#[test]
fn issue30_cam_friction_costs_the_motor_exactly_the_power_it_dissipates() {
    // The valve train of examples/cam_valve_spring.toml is driven through
    // its whole motion (inverse dynamics): friction on the flat-faced
    // tappet's contact changes no motion, so the motor's extra power is
    // the friction's dissipated power, −P_f, at every instant.
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/cam_valve_spring.toml");
    let plain = std::fs::read_to_string(path).unwrap();
    let face = "body_j = \"tappet\"\npoint_j = [0, 0]\naxis = [1, 0]\n";
    assert!(plain.contains(face));
    let rough = plain.replace(face, &format!("{face}friction = {{ mu = 0.15 }}\n"));
    let run_inverse = |src: &str| {
        let model = load_str(src, Format::Toml, "m.toml")
            .unwrap_or_else(|e| panic!("{e}"))
            .model;
        let times = time_grid(0.02, 0.0000625).unwrap();
        let mut t = Table::default();
        inverse::run(&model, &times, &run::Settings::default(), &[], &mut t)
            .unwrap_or_else(|e| panic!("{e}"));
        t
    };
    let (with, without) = (run_inverse(&rough), run_inverse(&plain));
    let (p1, p0) = (ch(&with, "motor.power"), ch(&without, "motor.power"));
    let (pf, ff) = (
        ch(&with, "bucket.friction_power"),
        ch(&with, "bucket.friction_force"),
    );
    let n = ch(&with, "bucket.normal_force");
    let scale = p0.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut slipping = 0;
    for k in 0..with.t.len() {
        assert!(pf[k] <= 0.0);
        assert!(
            (p1[k] - p0[k] + pf[k]).abs() < 1e-9 * scale,
            "t = {}: {} − {} vs {}",
            with.t[k],
            p1[k],
            p0[k],
            -pf[k]
        );
        // Sliding on the face (all but the instants the slip reverses):
        // |F| = μ N.
        if (ff[k].abs() - 0.15 * n[k].abs()).abs() < 1e-9 * (1.0 + n[k].abs()) {
            slipping += 1;
        }
    }
    assert!(
        slipping > with.t.len() * 9 / 10,
        "{slipping} of {}",
        with.t.len()
    );
}
