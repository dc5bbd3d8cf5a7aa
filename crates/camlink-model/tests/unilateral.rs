//! Unilateral cam contacts in forward dynamics (lift-off, flight, impact)
//! against closed forms: a ball bouncing on the floor, the energy of
//! elastic and plastic impacts, and a valve tappet that jumps off its
//! eccentric cam.

use camlink_core::dynamics::integrator;
use camlink_core::run::{time_grid, Summary, Table};
use camlink_model::{load_str, Format, Loaded};

const G: f64 = 9.81;

fn load(text: &str) -> Loaded {
    load_str(text, Format::Toml, "test.toml").unwrap_or_else(|e| panic!("{e}"))
}

pub(crate) fn ch(t: &Table, name: &str) -> Vec<f64> {
    t.channel(name)
        .unwrap_or_else(|| panic!("no channel {name} in {:?}", t.channels))
}

pub(crate) fn forward(l: &Loaded, t_end: f64, dt: f64, step: f64) -> (Table, Summary) {
    let times = time_grid(t_end, dt).unwrap();
    let settings = integrator::Settings {
        step,
        tol: 1e-10,
        ..integrator::Settings::default()
    };
    let mut t = Table::default();
    let s =
        integrator::run(&l.model, &times, &settings, &[], &mut t).unwrap_or_else(|e| panic!("{e}"));
    (t, s)
}

/// A ball: body `ball` of mass `m` (kg, inertia 0.008 kg·m²) at `xy` (m)
/// moving vertically at `vy` (m/s), with the circle `rim` of radius 0.1 m,
/// under gravity `g` (m/s², downwards), and `rest` (its contact: more
/// curves and joints) after it.
fn ball_with(name: &str, g: f64, m: f64, xy: [f64; 2], vy: f64, rest: &str) -> Loaded {
    load(&format!(
        r#"
[model]
name = "{name}"
gravity = [0, {gy}]

[[bodies]]
name = "ball"
position = [{x}, {y}]
velocity = [0, {vy:.17}]
mass = {m}
inertia = 0.008

[[curves]]
name = "rim"
body = "ball"
source = "circle"
centre = [0, 0]
radius = 0.1

{rest}"#,
        gy = -g,
        x = xy[0],
        y = xy[1],
    ))
}

/// A ball of radius 0.1 m, mass 2 kg, its centre `h0` + 0.1 m above a
/// floor (a face on the ground), restitution `e`.
fn ball(h0: f64, e: f64, rest_speed: f64) -> Loaded {
    ball_tol(h0, e, rest_speed, 1e-9)
}

/// [`ball`] with the event tolerance `tol` (s).
fn ball_tol(h0: f64, e: f64, rest_speed: f64, tol: f64) -> Loaded {
    ball_with(
        "bouncing ball",
        G,
        2.0,
        [0.3, h0 + 0.1],
        0.0,
        &format!(
            r#"
[[joints]]
type = "flat_follower"
name = "floor"
curve_i = "rim"
body_j = "ground"
axis = [1, 0]
unilateral = true
restitution = {e}
rest_speed = {rest_speed}
event_tol = {tol:e}
"#
        ),
    )
}

/// The impacts of a ball of mass `m` dropped from gap `h0` with
/// restitution `e`: impact k at approach speed v₀ eᵏ, v₀ = √(2 g h0), at
/// t₀ + Σ_{i<k} 2 v₀ eⁱ⁺¹/g (t₀ = √(2 h0/g)), a bounce at e v₀ eᵏ with the
/// impulse m (1 + e) v₀ eᵏ, until the approach is below `rest` and the
/// contact closes.
fn assert_geometric_series(s: &Summary, h0: f64, e: f64, rest: f64, m: f64) {
    let v0 = (2.0 * G * h0).sqrt();
    let bounces = (0..)
        .map(|k| v0 * e.powi(k))
        .take_while(|v| *v >= rest)
        .count();
    assert_eq!(s.impacts.len(), bounces + 1, "{:#?}", s.impacts);
    let mut t_k = (2.0 * h0 / G).sqrt();
    for (k, imp) in s.impacts.iter().enumerate() {
        let v = v0 * e.powi(k as i32);
        assert!(
            (imp.at.time - t_k).abs() < 1e-7,
            "impact {k}: t {} vs {t_k}",
            imp.at.time
        );
        assert!(
            (imp.approach - v).abs() < 1e-7 * v0,
            "impact {k}: v {} vs {v}",
            imp.approach
        );
        if k < bounces {
            assert!(!imp.closed);
            assert!((imp.separation - e * v).abs() < 1e-7 * v0);
            assert!((imp.impulse - m * (1.0 + e) * v).abs() < 1e-6, "{imp:?}");
        } else {
            assert!(imp.closed);
        }
        t_k += 2.0 * e * v / G;
    }
}

#[test]
fn ball_rebounds_in_the_geometric_series_until_rest() {
    // Dropped from h0 = 0.5 m with e = 0.8: impact k (k = 0, 1, …) at
    // approach speed v0 eᵏ, v0 = √(2 g h0), at t_k = t_0 + Σ_{i<k} 2 v0 eⁱ⁺¹/g,
    // and the flight after it rises to e²⁽ᵏ⁺¹⁾ h0. Below rest_speed
    // = 0.05 m/s the ball stays on the floor.
    let (h0, e) = (0.5, 0.8);
    let l = ball(h0, e, 0.05);
    let v0 = (2.0 * G * h0).sqrt();
    let t_rest_series = (2.0 * h0 / G).sqrt() + 2.0 * v0 * e / (G * (1.0 - e));
    let (t, s) = forward(&l, t_rest_series + 0.5, 1e-3, 1e-3);
    assert_geometric_series(&s, h0, e, 0.05, 2.0);
    // Each flight after a bounce rises to e²⁽ᵏ⁺¹⁾ h0 (greatest gap at the
    // 1 ms step ends: within ½ g (1 ms)²).
    for (k, f) in s.flights.iter().skip(1).enumerate() {
        let h = e.powi(2 * (k as i32 + 1)) * h0;
        assert!(
            (f.greatest_gap - h).abs() < 0.5 * G * 1e-6 + 1e-9,
            "flight {k}: {} vs {h}",
            f.greatest_gap
        );
    }
    // At rest: the contact closed, the gap zero, the normal force m g.
    let (state, gap, n) = (
        ch(&t, "floor.state"),
        ch(&t, "floor.gap"),
        ch(&t, "floor.normal_force"),
    );
    let last = state.len() - 1;
    assert_eq!(state[last], 1.0);
    assert_eq!(gap[last], 0.0);
    assert!((n[last] - 2.0 * G).abs() < 1e-6, "{}", n[last]);
    // In flight the normal force is zero and the gap the free fall's.
    let y = ch(&t, "ball.y");
    assert_eq!(state[100], 0.0);
    assert_eq!(n[100], 0.0);
    assert!((gap[100] - (y[100] - 0.1)).abs() < 1e-12);
    assert!((gap[100] - (h0 - 0.5 * G * 0.1 * 0.1)).abs() < 1e-9);
}

#[test]
fn ball_on_a_line_curve_rebounds_in_the_geometric_series() {
    // The same drop (h0 = 0.5 m, e = 0.8) with the floor a line curve on
    // the ground and the ball's rim on it through a cam_follower joint:
    // the gap is the least distance between the two curves.
    let l = ball_with(
        "ball on a line",
        G,
        2.0,
        [0.3, 0.6],
        0.0,
        r#"
[[curves]]
name = "floor_line"
body = "ground"
source = "line"
from = [-2, 0]
to = [2, 0]

[[joints]]
type = "cam_follower"
name = "floor"
curve_i = "floor_line"
curve_j = "rim"
unilateral = true
restitution = 0.8
rest_speed = 0.05
"#,
    );
    let (_, s) = forward(&l, 3.0, 1e-3, 1e-3);
    assert_geometric_series(&s, 0.5, 0.8, 0.05, 2.0);
}

#[test]
fn elastic_impacts_conserve_energy_and_plastic_ones_lose_half_m_v_squared() {
    // e = 1: the total energy across the bounces equals the start's. An
    // impact is located within the event tolerance τ, so the ball meets
    // the floor up to v τ deep and the restart lifts it back: each impact
    // may change the energy by up to m g v τ.
    for tol in [1e-9, 1e-12] {
        let l = ball_tol(0.3, 1.0, 0.0, tol);
        let (t, s) = forward(&l, 2.5, 1e-3, 1e-3);
        assert!(s.impacts.len() >= 4, "{}", s.impacts.len());
        let energy = ch(&t, "energy.total");
        let e0 = energy[0];
        let worst = energy.iter().map(|e| (e - e0).abs()).fold(0.0, f64::max);
        let v = (2.0 * G * 0.3f64).sqrt();
        let bound = s.impacts.len() as f64 * 2.0 * G * v * tol + 1e-11 * e0.abs();
        assert!(worst < bound, "tol {tol}: energy drift {worst} > {bound}");
    }
    // e = 0: the ball stops at the first impact, losing ½ m v² (m_eff = m
    // for a free ball hit at its centre's height).
    let l = ball(0.3, 0.0, 0.0);
    let (t, s) = forward(&l, 0.4, 1e-3, 1e-3);
    assert_eq!(s.impacts.len(), 1);
    let v = s.impacts[0].approach;
    let energy = ch(&t, "energy.total");
    let kinetic = ch(&t, "energy.kinetic");
    let lost = energy[0] - energy[energy.len() - 1];
    // Up to m g v τ apart: the impact is located within τ = 1e-9 s.
    let bound = 2.0 * G * v * 1e-9;
    assert!(
        (lost - 0.5 * 2.0 * v * v).abs() < bound,
        "{lost} vs {}",
        v * v
    );
    assert!(kinetic[kinetic.len() - 1].abs() < 1e-12);
}

/// The valve jump example's parameters (`examples/cam_valve_jump.toml`).
mod valve {
    pub const R: f64 = 0.02;
    pub const E: f64 = 0.004;
    pub const M: f64 = 0.1;
    pub const K: f64 = 5000.0;
    pub const PRELOAD: f64 = 50.0;
    pub const Y_FREE: f64 = R - E - PRELOAD / K;
}

/// The first flight of the valve tappet in closed form at cam speed ω:
/// (lift-off time t₁, landing time t₂, approach speed at landing, gap(t)).
fn valve_flight(w: f64) -> (f64, f64, f64, impl Fn(f64) -> f64) {
    use valve::*;
    // Closed: y = R + e sin ωt, N = k (y − y_free) + m g − m e ω² sin ωt,
    // zero at sin θ₁ = (k (R − y_free) + m g) / (e (m ω² − k)).
    let th1 = ((K * (R - Y_FREE) + M * G) / (E * (M * w * w - K))).asin();
    let t1 = th1 / w;
    // Flight: m ÿ = −k (y − y_free) − m g from y(t₁), ẏ(t₁) on the cam.
    let om = (K / M).sqrt();
    let y_eq = Y_FREE - M * G / K;
    let (y1, v1) = (R + E * th1.sin(), E * w * th1.cos());
    let y = move |t: f64| {
        let s = t - t1;
        y_eq + (y1 - y_eq) * (om * s).cos() + v1 / om * (om * s).sin()
    };
    let yd = move |t: f64| {
        let s = t - t1;
        -(y1 - y_eq) * om * (om * s).sin() + v1 * (om * s).cos()
    };
    let gap = move |t: f64| y(t) - R - E * (w * t).sin();
    // Landing: the first zero of the gap after lift-off, by scanning and
    // bisection of the closed form.
    let mut a = t1 + 1e-7;
    let dt = 1e-6;
    while gap(a + dt) > 0.0 {
        a += dt;
    }
    let mut b = a + dt;
    for _ in 0..100 {
        let c = 0.5 * (a + b);
        if gap(c) > 0.0 {
            a = c;
        } else {
            b = c;
        }
    }
    let t2 = 0.5 * (a + b);
    let approach = -(yd(t2) - E * w * (w * t2).cos());
    (t1, t2, approach, gap)
}

fn example(name: &str) -> Loaded {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    camlink_model::load_path(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn valve_jump_flight_is_the_spring_mass_motion() {
    // Lift-off where the closed-form normal force falls through zero, the
    // flight the free spring–mass motion, the landing where that motion
    // meets the cam again, at its closed-form approach speed. Lift-off and
    // landing within the event tolerance (1e-9 s) at h = 5 µs; the flight
    // carries the integrator's O(h²) error, which halving h divides by 4.
    let l = example("cam_valve_jump.toml");
    let w = 6000.0 * std::f64::consts::TAU / 60.0;
    let (t1, t2, approach, gap) = valve_flight(w);
    let mut errors = Vec::new();
    for step in [1e-5, 5e-6] {
        let (t, s) = forward(&l, 0.01, 1e-5, step);
        let f = &s.flights[0];
        let end = f.end.as_ref().expect("the tappet lands").time;
        let imp = &s.impacts[0];
        let g = ch(&t, "bucket.gap");
        let state = ch(&t, "bucket.state");
        let n = ch(&t, "bucket.normal_force");
        let mut worst: f64 = 0.0;
        for (k, &tt) in t.t.iter().enumerate() {
            if tt > t1 && tt < t2 {
                worst = worst.max((g[k] - gap(tt)).abs());
                assert_eq!((state[k], n[k]), (0.0, 0.0), "in flight at {tt}");
            } else if tt < t1 {
                assert_eq!((state[k], g[k]), (1.0, 0.0), "on the cam at {tt}");
            }
        }
        errors.push([f.start.time - t1, end - t2, imp.approach - approach, worst]);
    }
    eprintln!("errors (lift-off s, landing s, approach m/s, gap m) at h = 10, 5 µs: {errors:?}");
    // The landing is taken where the computed gap is zero, so its time
    // and approach speed carry the flight's O(h²) error only (a quarter
    // when h halves): -5.5e-9 s, -1.4e-9 s and -1.3e-5, -3.1e-6 m/s.
    let [lift, land, speed, flight] = errors[1];
    assert!(lift.abs() <= 1e-9, "lift-off {lift} s");
    assert!(land.abs() <= 1.5e-9, "landing {land} s");
    assert!(
        speed.abs() <= 3.5e-6 * approach,
        "approach {speed} of {approach} m/s"
    );
    assert!(flight <= 1e-8, "flight gap {flight} m");
    for (e, what) in [(1, "landing"), (2, "approach"), (3, "flight gap")] {
        let ratio = errors[0][e] / errors[1][e];
        assert!(
            (3.5..4.5).contains(&ratio),
            "{what}: second order, x{ratio}: {errors:?}"
        );
    }
}

/// The valve jump example at `rpm`, unilateral or not.
fn valve_at(rpm: f64, unilateral: bool) -> Loaded {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/cam_valve_jump.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let text = text.replace("rpm = 6000 ", &format!("rpm = {rpm} "));
    let text: String = if unilateral {
        text
    } else {
        text.lines()
            .filter(|l| {
                !["unilateral", "restitution", "rest_speed", "event_tol"]
                    .iter()
                    .any(|k| l.starts_with(k))
            })
            .map(|l| format!("{l}\n"))
            .collect()
    };
    load(&text)
}

#[test]
fn below_the_jump_speed_the_unilateral_run_is_the_bilateral_one() {
    // 4000 rpm < 4554 rpm: N > 0 throughout, no event; every channel of
    // the bilateral run is equal, bit for bit.
    let (a, sa) = forward(&valve_at(4000.0, true), 0.015, 1e-4, 1e-5);
    let (b, sb) = forward(&valve_at(4000.0, false), 0.015, 1e-4, 1e-5);
    assert!(sa.impacts.is_empty() && sa.flights.is_empty());
    assert!(sb.lift_off.is_empty());
    assert_eq!(a.t, b.t);
    for name in &b.channels {
        assert_eq!(ch(&a, name), ch(&b, name), "{name}");
    }
    assert!(ch(&a, "bucket.state").iter().all(|&s| s == 1.0));
    assert!(ch(&a, "bucket.gap").iter().all(|&g| g == 0.0));
}

#[test]
fn above_the_jump_speed_the_flight_starts_where_inverse_dynamics_says() {
    // At 6000 rpm the inverse dynamics of the bilateral model reports
    // lift-off where N falls through zero (interpolated between its output
    // times); the unilateral run's located lift-off is within that
    // interpolation's spacing, and its lift-off angle is the closed form's.
    use camlink_core::dynamics::inverse;
    let l = valve_at(6000.0, false);
    let times = time_grid(0.01, 1e-6).unwrap();
    let mut t = Table::default();
    let si = inverse::run(
        &l.model,
        &times,
        &camlink_core::run::Settings::default(),
        &[],
        &mut t,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let predicted = si.lift_off[0].start.time;
    let (_, s) = forward(&valve_at(6000.0, true), 0.01, 1e-4, 1e-5);
    let located = s.flights[0].start.time;
    assert!(
        (located - predicted).abs() < 1e-6,
        "{located} vs {predicted}"
    );
    let w = 6000.0 * std::f64::consts::TAU / 60.0;
    let (t1, ..) = valve_flight(w);
    assert!((s.flights[0].start.cam_angle - w * t1).abs() < 1e-9 * w);
}

#[test]
fn a_grazing_impact_between_step_ends_is_caught() {
    // A ball thrown up under a ceiling (a face on the ground at y = 1 m),
    // its top 10 mm below, at v₀ = √(2 g (0.01 + 1e-4)): in free flight it
    // would rise 0.1 mm into the ceiling and fall back, the gap positive
    // at every end of the 0.1 s steps. It hits the ceiling at
    // t = (v₀ − √(v₀² − 2 g 0.01))/g with approach speed √(2 g 1e-4).
    let v0 = (2.0 * G * (0.01 + 1e-4)).sqrt();
    let l = ball_with(
        "ball under a ceiling",
        G,
        1.0,
        [0.0, 0.89],
        v0,
        r#"
[[joints]]
type = "flat_follower"
name = "ceiling"
curve_i = "rim"
body_j = "ground"
point_j = [0, 1]
axis = [1, 0]
unilateral = true
restitution = 1
rest_speed = 0
"#,
    );
    let (_, s) = forward(&l, 0.2, 0.1, 0.1);
    assert_eq!(s.impacts.len(), 1, "{:?}", s.impacts);
    let t_hit = (v0 - (v0 * v0 - 2.0 * G * 0.01).sqrt()) / G;
    let speed = (2.0 * G * 1e-4).sqrt();
    let imp = &s.impacts[0];
    assert!(
        (imp.at.time - t_hit).abs() < 1e-9,
        "{} vs {t_hit}",
        imp.at.time
    );
    assert!(
        (imp.approach - speed).abs() < 1e-7,
        "{} vs {speed}",
        imp.approach
    );
    assert!((imp.separation - speed).abs() < 1e-7);
}

#[test]
fn a_plastic_impact_on_a_constrained_follower_loses_half_m_eff_v_squared() {
    // A pendulum (arm of length L = 0.5 m, mass m = 1 kg at its tip,
    // I_c = 0.01 kg·m²) hinged to a cart (M_c = 2 kg) that slides freely
    // along x, released horizontal; a disc of radius ρ = 0.05 m at the tip
    // meets a floor at y_f = −L sin 60° − ρ when φ = −60°. With
    // coordinates (x, φ) the mass matrix is
    // [[M_c + m, −m L sin φ], [−m L sin φ, m L² + I_c]] and the contact's
    // normal speed ġ = L cos φ φ̇, so m_eff = 1 / ((L cos φ)² (M⁻¹)₂₂),
    // (M⁻¹)₂₂ = (M_c + m) / det M. A plastic impact (e = 0) loses
    // ½ m_eff ġ², and the horizontal momentum (zero) is kept.
    let (l_arm, rho, m, ic, mc) = (0.5f64, 0.05f64, 1.0f64, 0.01f64, 2.0f64);
    let phi = -std::f64::consts::FRAC_PI_3;
    let y_f = l_arm * phi.sin() - rho;
    let model = load(&format!(
        r#"
[model]
name = "pendulum on a cart hitting a floor"
gravity = [0, -{G}]

[[bodies]]
name = "cart"
mass = {mc}
inertia = 1

[[bodies]]
name = "arm"
mass = {m}
inertia = {ic}
centroid = [{l_arm}, 0]

[[curves]]
name = "disc"
body = "arm"
source = "circle"
centre = [{l_arm}, 0]
radius = {rho}

[[joints]]
type = "translational"
name = "rail"
body_i = "ground"
axis = [1, 0]
body_j = "cart"

[[joints]]
type = "revolute"
name = "hinge"
body_i = "cart"
body_j = "arm"

[[joints]]
type = "flat_follower"
name = "floor"
curve_i = "disc"
body_j = "ground"
point_j = [0, {y_f:.17}]
axis = [1, 0]
unilateral = true
restitution = 0
"#
    ));
    let (t, s) = forward(&model, 0.5, 1e-3, 1e-4);
    let imp = &s.impacts[0];
    let t_hit = imp.at.time;
    // Only the one impact before the end of the run, which then stays on.
    assert_eq!(s.impacts.len(), 1, "{:?}", s.impacts);
    assert!(imp.closed);
    let det = (mc + m) * (m * l_arm * l_arm + ic) - (m * l_arm * phi.sin()).powi(2);
    let m_eff = det / ((l_arm * phi.cos()).powi(2) * (mc + m));
    let energy = ch(&t, "energy.total");
    let lost = energy[0] - energy[energy.len() - 1];
    let v = imp.approach;
    let expected = 0.5 * m_eff * v * v;
    // The impact is located within 1e-9 s: the energy may differ by
    // (m + M_c) g v τ, and the integrator's drift of the total energy
    // over the run (measured before the impact) adds to it.
    let before: Vec<f64> =
        t.t.iter()
            .zip(&energy)
            .filter(|(tt, _)| **tt < t_hit)
            .map(|(_, e)| (e - energy[0]).abs())
            .collect();
    let drift = before.iter().copied().fold(0.0, f64::max);
    eprintln!("lost {lost} J, ½ m_eff v² {expected} J, m_eff {m_eff} kg, drift {drift} J");
    assert!(
        (lost - expected).abs() < 2.0 * drift + (m + mc) * G * v * 1e-9 + 1e-9,
        "lost {lost} J, ½ m_eff v² = {expected} J (drift {drift})"
    );
    // Horizontal momentum p_x = (M_c + m) ẋ − m L sin φ φ̇ stays zero: the
    // impulse is vertical. The integrator keeps it to its own accuracy
    // (the body frame is not at the centroid, so M depends on φ); the
    // impact adds nothing beyond that drift.
    let (xd, w, ph) = (ch(&t, "cart.vx"), ch(&t, "arm.omega"), ch(&t, "arm.phi"));
    let px = |k: usize| (mc + m) * xd[k] - m * l_arm * ph[k].sin() * w[k];
    let k_hit = t.t.iter().position(|tt| *tt > t_hit).unwrap();
    let drift_px = (0..k_hit).map(|k| px(k).abs()).fold(0.0, f64::max);
    let last = t.t.len() - 1;
    assert!(
        px(last).abs() <= 3.0 * drift_px + 1e-9,
        "p_x {} after, drift {drift_px} before",
        px(last)
    );
    // At the impact the arm is at −60°: the floor was placed there.
    assert!((ph[k_hit] - phi).abs() < 1e-8, "{}", ph[k_hit]);
}

#[test]
fn a_unilateral_contact_without_a_closed_curve_is_refused_by_name() {
    // A flat face on a line curve: no solid side to measure a gap from.
    let l = load(&format!(
        r#"
[model]
name = "open cam"
gravity = [0, -{G}]

[[bodies]]
name = "slider"
position = [0, 0.5]
mass = 1
inertia = 0.01

[[curves]]
name = "edge"
body = "slider"
source = "line"
from = [-0.1, 0]
to = [0.1, 0]

[[joints]]
type = "flat_follower"
name = "floor"
curve_i = "edge"
body_j = "ground"
axis = [1, 0]
unilateral = true
"#
    ));
    let times = time_grid(0.01, 1e-3).unwrap();
    let mut t = Table::default();
    let e = integrator::run(
        &l.model,
        &times,
        &integrator::Settings::default(),
        &[],
        &mut t,
    )
    .expect_err("an open cam curve cannot be unilateral");
    assert_eq!(e.kind, camlink_core::run::Kind::InvalidInput);
    assert!(e.to_string().contains("joint 'floor'"), "{e}");
    assert!(e.to_string().contains("closed cam curve"), "{e}");
}

#[test]
fn a_compliant_hertz_contact_matches_the_closed_form() {
    // A 2 kg ball dropped from 50 mm on a floor with a Hertz contact
    // F = k δ^{3/2}, k = 1e6 N/m^{3/2}, no damping: ½ m v² = (2/5) k δ_m^{5/2}
    // gives the greatest overlap δ_m = (5 m v² / (4 k))^{2/5}; the contact
    // lasts T = 2 (δ_m / v) ∫₀¹ (1 − x^{5/2})^{−1/2} dx and returns the ball
    // at v. Without numerical damping (ρ∞ = 1) and with 10 µs steps.
    let (m, k, h0) = (2.0f64, 1e6f64, 0.05f64);
    let l = ball_with(
        "Hertz drop",
        G,
        m,
        [0.0, 0.1 + h0],
        0.0,
        &format!(
            r#"
[[joints]]
type = "flat_follower"
name = "floor"
curve_i = "rim"
body_j = "ground"
axis = [1, 0]
unilateral = true
stiffness = {k}
exponent = 1.5
"#
        ),
    );
    let v = (2.0 * G * h0).sqrt();
    let t0 = (2.0 * h0 / G).sqrt();
    let times = time_grid(0.15, 1e-5).unwrap();
    let settings = integrator::Settings {
        step: 1e-5,
        rho_inf: 1.0,
        tol: 1e-12,
        ..integrator::Settings::default()
    };
    let mut t = Table::default();
    let s =
        integrator::run(&l.model, &times, &settings, &[], &mut t).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.impacts.is_empty() && s.flights.is_empty());
    let (gap, state, n) = (
        ch(&t, "floor.gap"),
        ch(&t, "floor.state"),
        ch(&t, "floor.normal_force"),
    );
    let vy = ch(&t, "ball.vy");
    // Gravity adds m g δ_m to the work of the spring; its share is
    // m g / (k δ_m^{3/2}) ~ 1 %, so it is included: ½ m v² + m g δ =
    // (2/5) k δ^{5/2}, solved by bisection.
    let f = |d: f64| 0.4 * k * d.powf(2.5) - 0.5 * m * v * v - m * G * d;
    let (mut a, mut b) = (0.0, 0.1);
    for _ in 0..200 {
        let c = 0.5 * (a + b);
        if f(c) > 0.0 {
            b = c;
        } else {
            a = c;
        }
    }
    let delta_m = 0.5 * (a + b);
    let least = gap.iter().copied().fold(f64::INFINITY, f64::min);
    eprintln!("δ_m {delta_m:e} m, camlink {:e} m", -least);
    assert!(
        (-least - delta_m).abs() < 1e-3 * delta_m,
        "{} vs {delta_m}",
        -least
    );
    // The force at the deepest point is k δ_m^{3/2}.
    let deepest = gap.iter().position(|&g| g == least).unwrap();
    assert!((n[deepest] - k * (-least).powf(1.5)).abs() < 1e-9 * n[deepest]);
    // Contact from t₀ for T = 2 ∫₀^δ_m dδ / δ̇, δ̇² = v² + 2 g δ − (4k/5m) δ^{5/2}
    // (energy, gravity included), by quadrature with δ = δ_m (1 − u²);
    // the ball leaves at v.
    let duration_closed: f64 = {
        let steps = 200_000;
        (0..steps)
            .map(|i| {
                let u = (i as f64 + 0.5) / steps as f64;
                let d = delta_m * (1.0 - u * u);
                let rate2 = v * v + 2.0 * G * d - 0.8 * k / m * d.powf(2.5);
                2.0 * 2.0 * delta_m * u / rate2.sqrt() / steps as f64
            })
            .sum()
    };
    let on: Vec<f64> =
        t.t.iter()
            .zip(&state)
            .filter(|(_, s)| **s == 1.0)
            .map(|(tt, _)| *tt)
            .collect();
    let duration = on[on.len() - 1] - on[0];
    eprintln!(
        "T {duration_closed:e} s, camlink {duration:e} s, from {} vs {t0}",
        on[0]
    );
    assert!((on[0] - t0).abs() < 2e-5);
    // The state is sampled every 10 µs.
    assert!(
        (duration - duration_closed).abs() < 2e-5,
        "{duration} vs {duration_closed}"
    );
    // Energy (kinetic, gravity and the contact's elastic k δ^{5/2}/(5/2))
    // is kept through the contact to the integrator's accuracy, and the
    // ball leaves at v: at the first output after contact it has climbed
    // for Δt, vy = v − g Δt to O(Δt²).
    let energy = ch(&t, "energy.total");
    let worst = energy
        .iter()
        .map(|e| (e - energy[0]).abs())
        .fold(0.0, f64::max);
    eprintln!("energy drift {worst:e} J of {:e} J", m * G * h0);
    assert!(worst < 1e-5 * m * G * h0, "{worst}");
    let after = t.t.iter().position(|tt| *tt > on[on.len() - 1]).unwrap();
    let gap_after = gap[after];
    let v_out = (vy[after] * vy[after] + 2.0 * G * gap_after).sqrt();
    assert!((v_out - v).abs() < 1e-4 * v, "{v_out} vs {v}");
}

#[test]
fn a_hunt_crossley_contact_rebounds_at_its_closed_form_speed() {
    // Without gravity, a 2 kg ball thrown at v = 1 m/s onto a floor with
    // F = k δⁿ (1 + c δ̇), k = 1e6 N/m^{3/2}, n = 3/2, c = 0.2 s/m. With
    // w = δ̇, m w dw/dδ = −k δⁿ (1 + c w) separates:
    // (m/c²) [G(w)]_{v}^{w} = −k δⁿ⁺¹/(n + 1), G(w) = c w − ln(1 + c w),
    // so the overlap is greatest at (m/c²) G(v) = k δ_m^{5/2}/(5/2) and
    // the ball leaves at u with G(−u) = G(v).
    let (m, k, c, v) = (2.0f64, 1e6f64, 0.2f64, 1.0f64);
    let l = ball_with(
        "Hunt–Crossley throw",
        0.0,
        m,
        [0.0, 0.11],
        -v,
        &format!(
            r#"
[[joints]]
type = "flat_follower"
name = "floor"
curve_i = "rim"
body_j = "ground"
axis = [1, 0]
unilateral = true
stiffness = {k}
damping = {c}
"#
        ),
    );
    let big_g = |w: f64| c * w - (1.0 + c * w).ln();
    let delta_m = (2.5 * m / (c * c) * big_g(v) / k).powf(0.4);
    let (mut a, mut b) = (0.0, v);
    for _ in 0..200 {
        let mid = 0.5 * (a + b);
        if big_g(-mid) < big_g(v) {
            a = mid;
        } else {
            b = mid;
        }
    }
    let u = 0.5 * (a + b);
    let times = time_grid(0.05, 1e-5).unwrap();
    let settings = integrator::Settings {
        step: 1e-5,
        rho_inf: 1.0,
        tol: 1e-12,
        ..integrator::Settings::default()
    };
    let mut t = Table::default();
    integrator::run(&l.model, &times, &settings, &[], &mut t).unwrap_or_else(|e| panic!("{e}"));
    let (gap, vy) = (ch(&t, "floor.gap"), ch(&t, "ball.vy"));
    let least = gap.iter().copied().fold(f64::INFINITY, f64::min);
    let u_out = vy[vy.len() - 1];
    eprintln!(
        "δ_m {delta_m:e} vs {:e} m; leaves at {u_out} vs {u} m/s",
        -least
    );
    assert!((-least - delta_m).abs() < 1e-4 * delta_m);
    assert!((u_out - u).abs() < 1e-4 * u, "{u_out} vs {u}");
    assert!(u_out < 0.97 * v, "the damping takes energy: {u_out}");
}

#[test]
fn a_normal_force_dipping_below_zero_inside_one_step_is_caught() {
    // Just above the jump speed (4560 rpm, ω_jump at 4554 rpm) N < 0 only
    // for 85.5°–94.5° of cam angle (closed form), inside one 20° step
    // (80° to 100°) whose ends have N > 0: the parabola through N at the
    // last three step ends dips there, and the lift-off is located at the
    // closed form's angle.
    let rpm = 4560.0;
    let w = rpm * std::f64::consts::TAU / 60.0;
    let h = 20f64.to_radians() / w;
    let l = valve_at(rpm, true);
    let times: Vec<f64> = (0..=7).map(|k| k as f64 * h).collect();
    let settings = integrator::Settings {
        step: h,
        tol: 1e-10,
        ..integrator::Settings::default()
    };
    let mut t = Table::default();
    let s =
        integrator::run(&l.model, &times, &settings, &[], &mut t).unwrap_or_else(|e| panic!("{e}"));
    let (th1, ..) = valve_flight(w);
    let th1 = th1 * w;
    let start = s
        .flights
        .first()
        .expect("the dip is caught")
        .start
        .cam_angle;
    eprintln!(
        "lift-off at {}° vs {}°",
        start.to_degrees(),
        th1.to_degrees()
    );
    // Within the event tolerance: ω · 1e-9 s, twice.
    assert!((start - th1).abs() < 2.0 * w * 1e-9, "{start} vs {th1}");
}

/// Fixed steps of a run with a unilateral contact land on every output
/// time without a sliver of a step left by the rounding of t (h = 1e-5 s,
/// outputs every 0.01 s): the ball of tests/no_alloc/ball_over_floor.toml
/// falls for 0.6 s, before it meets the floor, in exactly 60,000 steps.
#[test]
fn fixed_steps_leave_no_sliver_before_an_output_time() {
    let text = include_str!("no_alloc/ball_over_floor.toml");
    let (t, s) = forward(&load(text), 0.6, 0.01, 1e-5);
    assert_eq!(
        ch(&t, "ball.y").last().copied().map(|y| y > 8.0),
        Some(true)
    );
    assert_eq!(s.steps, 60_000);
}
