//! Joint limits and end stops (issue 30): a pendulum bouncing off its stop
//! and a slider pushed onto its stroke limit against closed forms, a
//! compliant stop against its energy balance, kinematics unaffected but
//! warned, and the refusals of bad limits.

use crate::unilateral::{ch, forward};
use camlink_core::run::{time_grid, Kind, Settings, Summary, Table};
use camlink_model::{load_path, load_str, Format, Loaded};

const G: f64 = 9.81;

fn examples() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn load(text: &str) -> Loaded {
    load_str(text, Format::Toml, "limits.toml").unwrap_or_else(|e| panic!("{e}"))
}

fn kinematics(l: &Loaded, t_end: f64, dt: f64) -> (Table, Summary) {
    let times = time_grid(t_end, dt).unwrap();
    let mut t = Table::default();
    let s = camlink_core::kinematics::run(&l.model, &times, &Settings::default(), &[], &mut t)
        .unwrap_or_else(|e| panic!("{e}"));
    (t, s)
}

/// ∫₀^a f(u) du by Simpson's rule on `n` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, a: f64, n: usize) -> f64 {
    let h = a / n as f64;
    let inner: f64 = (1..n)
        .map(|k| f(k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    (f(0.0) + inner + f(a)) * h / 3.0
}

/// examples/dyn_pendulum_stop.toml: a uniform bar (L = 0.4 m) released at
/// rest from the horizontal falls onto its stop at θ_s = −π/4 (e = 0.6).
/// Energy gives θ̇² = k sin(−θ) with k = 3g/L (I_O = mL²/3), so it arrives
/// at v = √(k sin(π/4)) after t₁ = ∫₀^{π/4} dψ/√(k sin ψ) (with ψ = u², a
/// smooth integrand for Simpson's rule), leaves at e v and rises to
/// sin θ = (1 − e²) sin θ_s.
#[test]
fn issue30_pendulum_bounces_off_its_stop_with_the_closed_form_rebound() {
    let l = load_path(&examples().join("dyn_pendulum_stop.toml")).unwrap();
    let (len, e) = (0.4, 0.6);
    let k = 3.0 * G / len;
    let theta_s = -std::f64::consts::FRAC_PI_4;
    let v = (k * theta_s.abs().sin()).sqrt();
    let t1 = simpson(
        |u| {
            if u == 0.0 {
                2.0 / k.sqrt()
            } else {
                2.0 * u / (k * (u * u).sin()).sqrt()
            }
        },
        theta_s.abs().sqrt(),
        20_000,
    );
    // The integrator's O(h²) error: measured 2.6e-7 s and 1.2e-6 (relative)
    // at h = 1 ms, 1.6e-8 s and 7.4e-8 at 0.25 ms.
    for (h, tol_t, tol_v) in [(1e-3, 5e-7, 2e-6), (2.5e-4, 5e-8, 2e-7)] {
        let (t, s) = forward(&l, 1.0, 1e-3, h);
        let first = &s.impacts[0];
        eprintln!(
            "h = {h}: impact at {} s (closed form {t1}), approach {} rad/s ({v}), \
             separation {}",
            first.at.time, first.approach, first.separation
        );
        assert_eq!(first.joint, "pivot.lower");
        assert!(
            (first.at.time - t1).abs() < tol_t,
            "{} vs {t1}",
            first.at.time
        );
        assert!(
            (first.approach - v).abs() < tol_v * v,
            "{} vs {v}",
            first.approach
        );
        // The restitution law: separation e times the approach, exactly.
        assert!((first.separation - e * first.approach).abs() < 1e-9 * v);
        assert!(!first.closed && first.impulse > 0.0);
        // The impulse stops and reverses the bar: I_O (1 + e) v (N·m·s).
        let i_o = 1.0 * len * len / 3.0;
        let want = i_o * (1.0 + e) * first.approach;
        assert!(
            (first.impulse - want).abs() < 1e-9 * want,
            "{}",
            first.impulse
        );
        // The bar never passes the stop, and rises to the closed form.
        let phi = ch(&t, "bar.phi");
        let least = phi.iter().cloned().fold(f64::INFINITY, f64::min);
        assert!(least > theta_s - 1e-9, "{least}");
        let second = s.impacts[1].at.time;
        let rise =
            t.t.iter()
                .zip(&phi)
                .filter(|(tk, _)| **tk > first.at.time && **tk < second)
                .map(|(_, p)| *p)
                .fold(f64::NEG_INFINITY, f64::max);
        let want = ((1.0 - e * e) * theta_s.sin()).asin();
        eprintln!("h = {h}: rebound to {rise} rad (closed form {want})");
        // Sampled every 1 ms: the peak is missed by up to θ̈ (0.5 ms)²/2.
        assert!((rise - want).abs() < 5e-6, "{rise} vs {want}");
        // The stop's channels: its gap is the angle above it, zero while
        // closed, and it pushes only while closed.
        let (gap, state) = (ch(&t, "pivot.lower.gap"), ch(&t, "pivot.lower.state"));
        let push = ch(&t, "pivot.lower.moment");
        for k in 0..phi.len() {
            if state[k] == 0.0 {
                assert!((gap[k] - (phi[k] - theta_s)).abs() < 1e-12);
                assert_eq!(push[k], 0.0);
            }
        }
        // It comes to rest on the stop (rest_speed 0.05 rad/s), pressed by
        // gravity: m g (L/2) cos θ_s.
        let last = s.impacts.last().unwrap();
        assert!(last.closed, "{:?}", last);
        let n = phi.len() - 1;
        assert_eq!(state[n], 1.0);
        let torque = 1.0 * G * len / 2.0 * theta_s.cos();
        assert!(
            (push[n] - torque).abs() < 1e-6 * torque,
            "{} vs {torque}",
            push[n]
        );
        assert!(s.flights.is_empty(), "{:?}", s.flights);
    }
}

/// A slider (`body`: its mass and velocity) on a `guide` along the
/// ground's x axis through the origin with `limits`, in a `[model]` of
/// `gravity`, with `rest` after it.
fn slider(gravity: &str, body: &str, limits: &str, rest: &str) -> Loaded {
    load(&format!(
        r#"
[model]
{gravity}

[[bodies]]
name = "slider"
inertia = 0.01
{body}

[[joints]]
name = "guide"
type = "translational"
body_i = "ground"
axis = [1, 0]
body_j = "slider"
limits = {{ {limits} }}

{rest}
"#
    ))
}

/// A 2 kg slider on the ground's x axis pushed by 20 N onto its upper
/// stroke limit 0.1 m from rest at 0: a = 10 m/s², impacts at v₀ = √(2 a s)
/// after √(2 s/a), then bounces v₀ eᵏ every 2 v₀ eᵏ/a (e = 0.5) until one is
/// slower than rest_speed; the stroke stays within the limit throughout.
#[test]
fn issue30_a_slider_pushed_against_its_stroke_limit_stays_within_it() {
    let l = slider(
        "gravity = [0, -9.81]",
        "mass = 2",
        "lower = -0.05, upper = 0.1, restitution = 0.5, rest_speed = 0.02",
        "[[forces]]\nname = \"push\"\ntype = \"point_force\"\nbody = \"slider\"\nfx = 20",
    );
    let (t, s) = forward(&l, 1.5, 1e-3, 1e-3);
    let (a, stroke, e): (f64, f64, f64) = (10.0, 0.1, 0.5);
    let v0 = (2.0 * a * stroke).sqrt();
    let mut at = (2.0 * stroke / a).sqrt();
    let bounces: Vec<_> = s.impacts.iter().filter(|i| !i.closed).collect();
    for (k, imp) in bounces.iter().enumerate() {
        let v = v0 * e.powi(k as i32);
        assert_eq!(imp.joint, "guide.upper");
        // A force constant along the guide: the integrator's motion is the
        // parabola, to rounding.
        assert!(
            (imp.at.time - at).abs() < 1e-8,
            "impact {k}: {} vs {at}",
            imp.at.time
        );
        assert!(
            (imp.approach - v).abs() < 1e-8,
            "impact {k}: {} vs {v}",
            imp.approach
        );
        assert!((imp.separation - e * imp.approach).abs() < 1e-12);
        at += 2.0 * e * v / a;
    }
    // Bounces while the approach is at least 0.02 m/s: v₀ eᵏ ≥ 0.02, k ≤ 6.
    assert_eq!(bounces.len(), 7, "{:?}", s.impacts);
    assert!(s.impacts.last().unwrap().closed);
    let x = ch(&t, "slider.x");
    let worst = x.iter().cloned().fold(f64::NEG_INFINITY, f64::max) - stroke;
    eprintln!("slider: greatest stroke past the limit {worst:e} m");
    assert!(worst < 1e-9, "{worst}");
    // At rest on the stop the stop takes the push: 20 N, through the
    // reaction on the slider too.
    let n = x.len() - 1;
    assert_eq!(ch(&t, "guide.upper.state")[n], 1.0);
    assert!((ch(&t, "guide.upper.force")[n] - 20.0).abs() < 1e-8);
    assert!((ch(&t, "guide.upper.fx_j")[n] + 20.0).abs() < 1e-8);
    // The lower stop is never touched.
    assert!(ch(&t, "guide.lower.state").iter().all(|&v| v == 0.0));
}

/// A compliant stop (Hunt–Crossley, no damping): a 1 kg slider arriving at
/// 0.5 m/s without other forces penetrates to δ_m with
/// ½ m v² = k δ_mⁿ⁺¹/(n + 1) and leaves at 0.5 m/s.
#[test]
fn issue30_a_compliant_stop_returns_the_slider_at_its_arrival_speed() {
    let l = slider(
        "gravity = [0, 0]",
        "mass = 1\nvelocity = [0.5, 0]",
        "upper = 0.01, stiffness = 1e6, exponent = 1.5",
        "",
    );
    let (t, s) = forward(&l, 0.06, 1e-5, 1e-5);
    let (k, n, v): (f64, f64, f64) = (1e6, 1.5, 0.5);
    let delta = (0.5 * v * v * (n + 1.0) / k).powf(1.0 / (n + 1.0));
    let gap = ch(&t, "guide.upper.gap");
    let least = gap.iter().cloned().fold(f64::INFINITY, f64::min);
    let vx = ch(&t, "slider.vx");
    eprintln!(
        "compliant stop: penetration {} m (closed form {delta}), leaves at {} m/s",
        -least,
        vx.last().unwrap()
    );
    assert!((-least - delta).abs() < 1e-3 * delta, "{least} vs {delta}");
    assert!((vx.last().unwrap() + v).abs() < 1e-3 * v);
    // Its force channel is the law's force, and there are no impacts.
    let force = ch(&t, "guide.upper.force");
    let at = gap.iter().position(|&g| g == least).unwrap();
    let want = k * (-least).powf(n);
    assert!((force[at] - want).abs() < 1e-9 * want);
    assert!(s.impacts.is_empty());
}

/// Limits are a dynamics feature: a driven slider's kinematics is the
/// same with and without them, and a driven stroke past a limit is a
/// warning naming the joint, when and how far.
#[test]
fn issue30_kinematics_ignores_limits_and_warns_when_driven_past_them() {
    let text = |limits: &str| {
        format!(
            r#"
[[bodies]]
name = "slider"
[[joints]]
name = "guide"
type = "translational"
body_i = "ground"
axis = [1, 0]
body_j = "slider"
{limits}
[[drivers]]
name = "push"
type = "translational_travel"
joint = "guide"
f = "0.2*sin(2*pi*t)"
"#
        )
    };
    let free = load(&text(""));
    let limited = load(&text("limits = { lower = -0.3, upper = 0.15 }"));
    let (a, sa) = kinematics(&free, 1.0, 0.01);
    let (b, sb) = kinematics(&limited, 1.0, 0.01);
    assert_eq!(a.channels, b.channels);
    assert_eq!(a.values, b.values);
    assert!(sa.warnings.is_empty());
    let w: Vec<_> = sb
        .warnings
        .iter()
        .filter(|w| w.kind == Kind::LimitExceeded)
        .collect();
    assert_eq!(w.len(), 1, "{:?}", sb.warnings);
    assert_eq!(w[0].joints, ["guide"]);
    eprintln!("{}", w[0].message);
    // First past 0.15 m where 0.2 sin 2πt = 0.15: t = asin(0.75)/2π ≈ 0.135 s.
    assert!(w[0].time > 0.13 && w[0].time < 0.15, "{}", w[0].time);
    assert!(w[0].message.contains("[-0.3, 0.15] m"), "{}", w[0].message);
    assert!(
        w[0].message.contains("t = 0.25 s (0.2 m)"),
        "{}",
        w[0].message
    );
}

fn load_err(text: &str) -> String {
    match load_str(text, Format::Toml, "limits.toml") {
        Ok(_) => panic!("loaded"),
        Err(e) => e.to_string(),
    }
}

const ARM: &str = r#"
[[bodies]]
name = "arm"
angle = 0.2
mass = 1
inertia = 0.1
"#;

#[test]
fn issue30_bad_limits_are_refused_naming_the_field() {
    // Lower at or above upper.
    let e = load_err(&format!(
        "{ARM}[[joints]]\nname = \"hinge\"\ntype = \"revolute\"\nbody_i = \"ground\"\n\
         body_j = \"arm\"\nlimits = {{ lower = 0.5, upper = 0.5 }}\n"
    ));
    assert!(e.starts_with("limits.toml:12:"), "{e}");
    assert!(
        e.contains("joints[0].limits.upper: the upper limit 0.5 must be above the lower limit 0.5"),
        "{e}"
    );
    // The placement outside the limits, with the values.
    let e = load_err(&format!(
        "{ARM}[[joints]]\nname = \"hinge\"\ntype = \"revolute\"\nbody_i = \"ground\"\n\
         body_j = \"arm\"\nlimits = {{ lower = 0.3, upper = 1 }}\n"
    ));
    assert!(
        e.contains(
            "joints[0].limits: the joint's angle where the bodies are placed, 0.2 rad, is \
             outside its limits [0.3, 1] rad"
        ),
        "{e}"
    );
    // Neither limit; a law out of range; a restitution on a compliant stop.
    for (limits, want) in [
        (
            "{ restitution = 0.5 }",
            "give a lower limit, an upper limit or both",
        ),
        (
            "{ upper = 1, restitution = 2 }",
            "limits.restitution: must be between 0 and 1",
        ),
        (
            "{ upper = 1, stiffness = 1e4, restitution = 0.5 }",
            "a compliant contact (stiffness given) has no impacts",
        ),
        ("{ upper = 1, lowr = 0 }", "did you mean 'lower'?"),
    ] {
        let e = load_err(&format!(
            "{ARM}[[joints]]\ntype = \"revolute\"\nbody_i = \"ground\"\nbody_j = \"arm\"\n\
             limits = {limits}\n"
        ));
        assert!(e.contains(want), "{limits}: {e}");
    }
    // A joint kind without limits.
    let e = load_err(&format!(
        "{ARM}[[joints]]\ntype = \"revolute_revolute\"\nbody_i = \"ground\"\npoint_i = [0, 1]\n\
         body_j = \"arm\"\nlimits = {{ upper = 1 }}\n"
    ));
    assert!(e.starts_with("limits.toml:"), "{e}");
    assert!(
        e.contains("unknown field `limits`")
            && e.contains(
                "this joint kind has no limits; revolute, translational and \
                 revolute_translational joints do"
            ),
        "{e}"
    );
}

/// examples/whitworth_global.toml: the ram's stroke limits sit 5 mm beyond
/// its travel, so kinematics gives no warning and forward dynamics never
/// touches them.
#[test]
fn issue30_whitworth_ram_stops_are_never_touched() {
    let l = load_path(&examples().join("whitworth_global.toml")).unwrap();
    let guide = l.model.joint("guide").unwrap();
    let limits = guide.limits.expect("ram stroke limits");
    assert_eq!((limits.lower, limits.upper), (Some(-0.385), Some(-0.215)));
    let (t, s) = kinematics(&l, 1.0, 0.005);
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    let x = ch(&t, "ram.x");
    let (lo, hi) = x
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    // The closed form of the travel: −R − l and R − l (β through 0 and π).
    assert!(
        (lo + 0.38).abs() < 1e-4 && (hi + 0.22).abs() < 1e-4,
        "{lo} {hi}"
    );
    let (t, s) = forward(&l, 1.0, 0.005, 1e-3);
    assert!(s.impacts.is_empty());
    for stop in ["guide.lower", "guide.upper"] {
        assert!(ch(&t, &format!("{stop}.state")).iter().all(|&v| v == 0.0));
        let gap = ch(&t, &format!("{stop}.gap"));
        assert!(gap.iter().all(|&g| g > 4e-3), "{stop}");
    }
}
