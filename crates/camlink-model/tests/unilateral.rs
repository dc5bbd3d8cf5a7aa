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

fn ch(t: &Table, name: &str) -> Vec<f64> {
    t.channel(name)
        .unwrap_or_else(|| panic!("no channel {name} in {:?}", t.channels))
}

fn forward(l: &Loaded, t_end: f64, dt: f64, step: f64) -> (Table, Summary) {
    let times = time_grid(t_end, dt).unwrap();
    let settings = integrator::Settings {
        step,
        tol: 1e-10,
        ..integrator::Settings::default()
    };
    let mut t = Table::default();
    let s = integrator::run(&l.model, &times, &settings, &[], &mut t)
        .unwrap_or_else(|e| panic!("{e}"));
    (t, s)
}

/// A ball of radius 0.1 m, mass 2 kg, its centre `h0` + 0.1 m above a
/// floor (a face on the ground), restitution `e`.
fn ball(h0: f64, e: f64, rest_speed: f64) -> Loaded {
    ball_tol(h0, e, rest_speed, 1e-9)
}

/// [`ball`] with the event tolerance `tol` (s).
fn ball_tol(h0: f64, e: f64, rest_speed: f64, tol: f64) -> Loaded {
    load(&format!(
        r#"
[model]
name = "bouncing ball"
gravity = [0, -{G}]

[[bodies]]
name = "ball"
position = [0.3, {y}]
mass = 2
inertia = 0.008

[[curves]]
name = "rim"
body = "ball"
source = "circle"
centre = [0, 0]
radius = 0.1

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
"#,
        y = h0 + 0.1
    ))
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
    let expected = (0..)
        .map(|k| v0 * e.powi(k))
        .take_while(|v| *v >= 0.05)
        .count();
    assert_eq!(s.impacts.len(), expected + 1, "{:#?}", s.impacts);
    let mut t_k = (2.0 * h0 / G).sqrt();
    for (k, imp) in s.impacts.iter().enumerate() {
        let v = v0 * e.powi(k as i32);
        assert!((imp.at.time - t_k).abs() < 1e-7, "impact {k}: t {} vs {t_k}", imp.at.time);
        assert!((imp.approach - v).abs() < 1e-7 * v0, "impact {k}: v {} vs {v}", imp.approach);
        if k < expected {
            assert!(!imp.closed);
            assert!((imp.separation - e * v).abs() < 1e-7 * v0);
            assert!((imp.impulse - 2.0 * (1.0 + e) * v).abs() < 1e-6, "{imp:?}");
        } else {
            assert!(imp.closed);
        }
        t_k += 2.0 * e * v / G;
    }
    // Each flight after a bounce rises to e²⁽ᵏ⁺¹⁾ h0 (greatest gap at the
    // 1 ms step ends: within ½ g (1 ms)²).
    for (k, f) in s.flights.iter().skip(1).enumerate() {
        let h = e.powi(2 * (k as i32 + 1)) * h0;
        assert!((f.greatest_gap - h).abs() < 0.5 * G * 1e-6 + 1e-9, "flight {k}: {} vs {h}", f.greatest_gap);
    }
    // At rest: the contact closed, the gap zero, the normal force m g.
    let (state, gap, n) = (ch(&t, "floor.state"), ch(&t, "floor.gap"), ch(&t, "floor.normal_force"));
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
    assert!((lost - 0.5 * 2.0 * v * v).abs() < bound, "{lost} vs {}", v * v);
    assert!(kinetic[kinetic.len() - 1].abs() < 1e-12);
}
