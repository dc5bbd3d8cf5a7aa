//! Issue 27: forward-dynamics outputs at any time, between step ends as at
//! them, come from the state at that time; forces and accelerations are
//! checked against inverse dynamics along the same motion.

use camlink_core::dynamics::{integrator, inverse};
use camlink_core::run::{Settings, Table};
use camlink_model::Loaded;

fn example(name: &str) -> Loaded {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    camlink_model::load_path(&path).unwrap_or_else(|e| panic!("{e}"))
}

fn ch(t: &Table, name: &str) -> Vec<f64> {
    t.channel(name)
        .unwrap_or_else(|| panic!("no channel {name} in {:?}", t.channels))
}

/// Forward dynamics of `l` at fixed steps `h` (s), output at `times`.
fn forward(l: &Loaded, times: &[f64], h: f64) -> Table {
    let settings = integrator::Settings {
        step: h,
        ..integrator::Settings::default()
    };
    let mut t = Table::default();
    integrator::run(&l.model, times, &settings, &[], &mut t).unwrap_or_else(|e| panic!("{e}"));
    t
}

/// Inverse dynamics of `l` at `times`.
fn inverse_at(l: &Loaded, times: &[f64]) -> Table {
    let mut t = Table::default();
    inverse::run(&l.model, times, &Settings::default(), &[], &mut t)
        .unwrap_or_else(|e| panic!("{e}"));
    t
}

#[test]
fn issue27_effort_just_past_a_step_end_is_inverse_dynamics() {
    let l = example("dyn_slider_crank.toml");
    for d in [0.0, 1e-6, 1e-8, 1e-9] {
        let t = 0.05 + d;
        let f = forward(&l, &[0.0, t], 1e-4);
        let i = inverse_at(&l, &[0.0, t]);
        let (ef, ei) = (ch(&f, "motor.effort")[1], ch(&i, "motor.effort")[1]);
        eprintln!(
            "d = {d:e}: forward {ef}, inverse {ei}, rel {:e}",
            (ef - ei) / ei
        );
    }
}

/// The valve-jump example's tappet on its cam: N(θ) = k (y − y_free) + m g
/// − m e ω² sin θ (N) and ÿ = −e ω² sin θ (m/s²) at y = R + e sin θ,
/// θ = ω t, the cam turning at ω (rad/s).
fn valve_on_cam(w: f64, t: f64) -> (f64, f64) {
    let (r, e, m, k, preload, g) = (0.02, 0.004, 0.1, 5000.0, 50.0, 9.81);
    let y_free = r - e - preload / k;
    let s = (w * t).sin();
    let y = r + e * s;
    (k * (y - y_free) + m * g - m * e * w * w * s, -e * w * w * s)
}

#[test]
fn issue27_contact_force_just_past_a_landing_is_the_cam_s() {
    // The valve-jump example: the tappet leaves its cam, bounces and
    // comes to rest on it (a landing slower than rest_speed closes the
    // contact). Outputs d = 1e-10 … 1e-6 s past that landing, where the
    // integrator restarts, are the cam's closed form: the steps are the
    // same with and without those output times.
    let l = example("cam_valve_jump.toml");
    let w = 6000.0 * std::f64::consts::TAU / 60.0;
    let h = 1e-5;
    let mut times = camlink_core::run::time_grid(0.02, 1e-4).unwrap();
    let settings = integrator::Settings {
        step: h,
        ..integrator::Settings::default()
    };
    let mut t = Table::default();
    let s = integrator::run(&l.model, &times, &settings, &[], &mut t).unwrap();
    let landing = s
        .impacts
        .iter()
        .find(|i| i.closed)
        .expect("the tappet comes to rest on its cam")
        .at
        .time;
    let ds = [1e-10, 1e-9, 1e-8, 1e-6];
    times.extend(ds.iter().map(|d| landing + d));
    times.sort_by(f64::total_cmp);
    let mut t = Table::default();
    let s2 = integrator::run(&l.model, &times, &settings, &[], &mut t).unwrap();
    assert_eq!(s2.impacts, s.impacts);
    let (n, ay) = (ch(&t, "bucket.normal_force"), ch(&t, "tappet.ay"));
    for d in ds {
        let k = t.t.iter().position(|&x| x == landing + d).unwrap();
        let (nf, af) = valve_on_cam(w, landing + d);
        eprintln!("d = {d:e}: N {} vs {nf} N, ÿ {} vs {af} m/s²", n[k], ay[k]);
        assert!(
            (n[k] - nf).abs() < 1e-9 * nf.abs().max(1.0),
            "N {} vs {nf}",
            n[k]
        );
        assert!(
            (ay[k] - af).abs() < 1e-9 * af.abs().max(1.0),
            "ÿ {} vs {af}",
            ay[k]
        );
    }
}

/// max |a − b| / max |b| over two equal-length series.
fn rel_err(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

#[test]
fn issue27_forward_efforts_match_inverse_dynamics_at_and_between_step_ends() {
    // The driven slider-crank: forward dynamics follows the prescribed
    // motion, so its motor effort and pin loads are inverse dynamics'
    // along it. Between step ends they are the consistent ones at the
    // interpolated state: within 1e-9 of the peak (3.3e-13 and 5.7e-13
    // measured) whatever h and tol. At step ends they are the
    // generalized-α step's multipliers, which carry the start's transient
    // and what Newton leaves of q̈, at most tol (docs/dynamics.md):
    // measured, as max error / peak over 0.5 s (and from 0.1 s on), effort
    // 2.2e-3 (5.1e-5) at h = 1e-3 s, tol = 1e-6; 2.0e-4 (1.0e-6) at
    // h = 1e-4 s, tol = 1e-6; 2.0e-4 (1.0e-6) at h = 1e-4 s, tol = 1e-10
    // (1.7e-3 (1.7e-3) at h = 1e-4 s, tol = 1e-6 when Newton stopped on
    // the velocity correction, leaving up to tol/(β h) of q̈).
    let l = example("dyn_slider_crank.toml");
    let ends: Vec<f64> = (0..=500).map(|k| k as f64 * 1e-3).collect();
    let between: Vec<f64> = std::iter::once(0.0)
        .chain((0..500).map(|k| (k as f64 + 0.37) * 1e-3))
        .collect();
    let id_ends = inverse_at(&l, &ends);
    let id_between = inverse_at(&l, &between);
    for (h, tol, at_ends, later) in [
        (1e-3, 1e-6, 3e-3, 2e-4),
        (1e-4, 1e-6, 3e-4, 2e-6),
        (1e-4, 1e-10, 3e-4, 2e-6),
    ] {
        let settings = integrator::Settings {
            step: h,
            tol,
            ..integrator::Settings::default()
        };
        let mut f = Table::default();
        integrator::run(&l.model, &between, &settings, &[], &mut f).unwrap();
        for c in ["motor.effort", "O.fx", "O.fy", "B.fx"] {
            let e = rel_err(&ch(&f, c)[1..], &ch(&id_between, c)[1..]);
            assert!(
                e < 1e-9,
                "h = {h}, tol = {tol}: {c} between step ends: {e:e}"
            );
        }
        let mut f = Table::default();
        integrator::run(&l.model, &ends, &settings, &[], &mut f).unwrap();
        let (ef, ei) = (ch(&f, "motor.effort"), ch(&id_ends, "motor.effort"));
        let (all, tail) = (rel_err(&ef[1..], &ei[1..]), rel_err(&ef[100..], &ei[100..]));
        eprintln!("h = {h:e}, tol = {tol:e}: effort at step ends {all:e}, from 0.1 s {tail:e}");
        assert!(all < at_ends && tail < later, "{all:e} {tail:e}");
    }
}

#[test]
fn issue27_valve_contact_force_between_step_ends_is_the_cam_s() {
    // The valve-jump example on its cam, before the first lift-off
    // (0.86 ms), over 0.8 ms: the normal force and the tappet's acceleration between
    // step ends are the closed form's within 1e-9 (9e-11 and 1e-15
    // measured); at step ends they are the step's, 7.8e-3 of the peak
    // force from 0.2 ms on at h = 1e-5 s and 1.6e-4 at 5e-6 s.
    let l = example("cam_valve_jump.toml");
    let w = 6000.0 * std::f64::consts::TAU / 60.0;
    let amplitude = 0.004 * w * w;
    let between: Vec<f64> = std::iter::once(0.0)
        .chain((0..80).map(|k| (k as f64 + 0.37) * 1e-5))
        .collect();
    for h in [1e-5, 5e-6] {
        let settings = integrator::Settings {
            step: h,
            ..integrator::Settings::default()
        };
        let mut t = Table::default();
        integrator::run(&l.model, &between, &settings, &[], &mut t).unwrap();
        let (n, ay) = (ch(&t, "bucket.normal_force"), ch(&t, "tappet.ay"));
        let state = ch(&t, "bucket.state");
        let (mut en, mut ea, mut peak) = (0.0f64, 0.0f64, 0.0f64);
        for (k, &tt) in t.t.iter().enumerate().skip(1) {
            assert_eq!(state[k], 1.0, "on the cam at {tt}");
            let (nf, af) = valve_on_cam(w, tt);
            en = en.max((n[k] - nf).abs());
            ea = ea.max((ay[k] - af).abs());
            peak = peak.max(nf.abs());
        }
        eprintln!(
            "h = {h:e}: N {:e} of the peak, ÿ {:e}",
            en / peak,
            ea / amplitude
        );
        assert!(
            en < 1e-9 * peak && ea < 1e-9 * amplitude,
            "{en} N, {ea} m/s²"
        );
    }
}

#[test]
fn issue27_adaptive_effort_just_past_an_output_time_is_inverse_dynamics() {
    // The error-controlled mode lands on 0.05 s, then has 1e-9 s to the
    // next output time: it steps past it and interpolates, instead of a
    // step of 1e-9 s.
    let l = example("dyn_slider_crank.toml");
    let settings = integrator::Settings {
        step: 1e-3,
        adaptive: Some(integrator::Adaptive {
            atol: 1e-8,
            rtol: 1e-8,
            h_min: 1e-12,
        }),
        ..integrator::Settings::default()
    };
    let times = [0.0, 0.05, 0.05 + 1e-9, 0.05 + 2e-9];
    let mut f = Table::default();
    integrator::run(&l.model, &times, &settings, &[], &mut f).unwrap();
    let i = inverse_at(&l, &times);
    let (ef, ei) = (ch(&f, "motor.effort"), ch(&i, "motor.effort"));
    // 0.05 s is a step end (the step's multipliers: -4.9747 N·m, 8e-3 off
    // at these tolerances); the two rows after it are interpolated.
    for k in 1..times.len() {
        eprintln!("t = {}: forward {}, inverse {}", times[k], ef[k], ei[k]);
    }
    for k in 2..times.len() {
        assert!(
            (ef[k] - ei[k]).abs() < 1e-9 * ei[k].abs(),
            "{} vs {}",
            ef[k],
            ei[k]
        );
    }
}
