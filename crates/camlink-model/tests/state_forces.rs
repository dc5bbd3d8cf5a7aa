//! Forces of state: `point_force` and `torque` expressions that read the
//! motion, against the built-in forces they restate, a Rust callback, and
//! finite differences (issue 30).

use std::sync::Arc;

use camlink_core::constraint::Local;
use camlink_core::dynamics::integrator::{run, Settings};
use camlink_core::force::callback::Callback;
use camlink_core::force::{Applied, BodyJac, BodyQ, Force, ForceJac, ForceKind, Reads};
use camlink_core::run::{time_grid, Table};
use camlink_core::BodyId;
use camlink_model::{load_str, Format};

/// A bar on a hinge and a block on a slide, each with a spring and damper
/// given by `forces`.
fn model(forces: &str) -> String {
    format!(
        r#"
[model]
gravity = [0, -9.81]

[parameters]
k = 40
c = 0.7
th0 = 0.3
l0 = 1.0

[[bodies]]
name = "bar"
position = [0.5, 0]
mass = 2
inertia = 0.2
centroid = [0.2, 0]
omega = 1.5

[[bodies]]
name = "block"
position = [1.2, 0]
mass = 3
velocity = [0.4, 0]
points = {{ P = [0.1, 0.05] }}

[[joints]]
type = "revolute"
name = "hinge"
body_i = "ground"
point_i = [0.5, 0]
body_j = "bar"

[[joints]]
type = "translational"
name = "slide"
body_i = "ground"
axis = [1, 0]
body_j = "block"
{forces}
"#
    )
}

const BUILT_IN: &str = r#"
[[forces]]
type = "rsda"
body_i = "ground"
body_j = "bar"
stiffness = "k"
free_angle = "th0"
damping = "c"

[[forces]]
type = "tsda"
body_i = "ground"
body_j = "block"
stiffness = "k"
free_length = "l0"
damping = "c"
"#;

const OF_STATE: &str = r#"
[[forces]]
type = "torque"
body = "bar"
torque = "-k*(hinge_angle - th0) - c*hinge_rate"

[[forces]]
type = "point_force"
body = "block"
fx = "-(k*(slide_stroke - l0) + c*slide_rate)"
"#;

fn simulate(text: &str, extra: Vec<Force>) -> Table {
    let mut model = load_str(text, Format::Toml, "m.toml").unwrap().model;
    for f in extra {
        model.add_force(f);
    }
    let times = time_grid(2.0, 0.01).unwrap();
    let settings = Settings {
        step: 1e-3,
        tol: 1e-10,
        ..Settings::default()
    };
    let mut t = Table::default();
    run(&model, &times, &settings, &[], &mut t).unwrap();
    t
}

/// Largest difference over every channel the two runs share.
fn max_diff(a: &Table, b: &Table, channels: &[&str]) -> f64 {
    let mut worst: f64 = 0.0;
    for ch in channels {
        let (x, y) = (a.channel(ch).unwrap(), b.channel(ch).unwrap());
        assert_eq!(x.len(), y.len());
        for (u, v) in x.iter().zip(y) {
            worst = worst.max((u - v).abs());
        }
    }
    worst
}

#[test]
fn issue30_state_spring_and_damper_equal_the_built_in_forces() {
    let l = load_str(&model(OF_STATE), Format::Toml, "m.toml").unwrap();
    assert!(
        l.model
            .forces
            .iter()
            .all(|f| matches!(f.kind, ForceKind::State(_))),
        "{:?}",
        l.model.forces
    );
    let a = simulate(&model(BUILT_IN), vec![]);
    let b = simulate(&model(OF_STATE), vec![]);
    let ch = [
        "bar.phi",
        "bar.omega",
        "block.x",
        "block.vx",
        "block.ax",
        "bar.alpha",
    ];
    let d = max_diff(&a, &b, &ch);
    eprintln!("state spring and damper vs built-in: max difference {d:e}");
    assert!(d <= 1e-12, "{d}");
    // The motion is not trivial: the bar swings and the block oscillates.
    let x = a.channel("block.x").unwrap();
    let span =
        x.iter().cloned().fold(f64::MIN, f64::max) - x.iter().cloned().fold(f64::MAX, f64::min);
    assert!(span > 0.05, "{span}");
}

/// A cutting force of 500 N against the block while it moves forward
/// (+x), smoothed over 1 mm/s, from the file and from a Rust callback.
#[test]
fn issue30_forward_stroke_cutting_force_equals_a_callback() {
    let cut = r#"
[[forces]]
type = "point_force"
body = "block"
fx = "step(block_vx, 0, 0, 0.5, -500)"
"#;
    let spring = r#"
[[forces]]
type = "tsda"
body_i = "ground"
body_j = "block"
stiffness = 2000
free_length = 1.0
"#;
    let a = simulate(&model(&format!("{spring}{cut}")), vec![]);
    let block = BodyId(2);
    let callback = Callback {
        body: block,
        f: Arc::new(|_t, _q, qd| {
            let v = qd[0];
            let u = (v / 0.5).clamp(0.0, 1.0);
            Ok([-500.0 * u * u * (3.0 - 2.0 * u), 0.0, 0.0])
        }),
    };
    let b = simulate(&model(spring), vec![Force::new("cut", callback)]);
    let d = max_diff(&a, &b, &["block.x", "block.vx"]);
    eprintln!("cutting force of state vs callback: max difference {d:e}");
    assert!(d <= 1e-8, "{d}");
    // The force acts: it takes energy on every forward stroke, so the
    // block's swing over the last second is far smaller than the spring's
    // alone.
    let free = simulate(&model(spring), vec![]);
    let swing = |t: &Table| {
        let x = &t.channel("block.x").unwrap()[100..];
        x.iter().cloned().fold(f64::MIN, f64::max) - x.iter().cloned().fold(f64::MAX, f64::min)
    };
    let (sa, sf) = (swing(&a), swing(&free));
    assert!(sa < 0.5 * sf, "{sa} vs {sf}");
}

#[test]
fn issue30_state_force_jacobian_matches_finite_differences() {
    let text = model(
        r#"
[[forces]]
type = "point_force"
body = "block"
point = "P"
reaction = "bar"
reaction_point = [0.3, 0]
fx = "-k*block_P_x*bar_omega + impact(slide_stroke, slide_rate, 0.9, 1e4, 1.5, 50, 0.01)"
fy = "coulomb(block_P_vy - bar_vx, 3, 0.5) + sin(bar_phi)*t"
local = true

[[forces]]
type = "torque"
body = "block"
reaction = "bar"
torque = "max(hinge_angle, -0.2)*block_vx + abs(slide_rate)"
"#,
    );
    let m = load_str(&text, Format::Toml, "m.toml").unwrap().model;
    for f in &m.forces {
        for seed in 0..10u32 {
            let mut x = Local {
                t: 0.3,
                ..Local::default()
            };
            let s = seed as f64;
            x.q[0] = [0.7 + 0.1 * s.sin(), 0.05 * s.cos(), 0.2 * s];
            x.q[1] = [0.4, -0.1, 0.3 - 0.05 * s];
            x.qd[0] = [0.3 * s.cos(), -0.2, 0.5 * s.sin()];
            x.qd[1] = [0.1, 0.3, -0.7];
            let (mut dq, mut dqd) = (BodyJac::default(), BodyJac::default());
            f.kind.derivatives(&x, &mut dq, &mut dqd);
            let h = 1e-6;
            for b in 0..2 {
                for c in 0..3 {
                    for vel in [false, true] {
                        let (mut xp, mut xm) = (x, x);
                        if vel {
                            xp.qd[b][c] += h;
                            xm.qd[b][c] -= h;
                        } else {
                            xp.q[b][c] += h;
                            xm.q[b][c] -= h;
                        }
                        let (mut qp, mut qm) = (BodyQ::default(), BodyQ::default());
                        f.kind.generalized(&xp, &mut qp).unwrap();
                        f.kind.generalized(&xm, &mut qm).unwrap();
                        for a in 0..2 {
                            for r in 0..3 {
                                let fd = (qp[a][r] - qm[a][r]) / (2.0 * h);
                                let an = if vel { dqd[a][b][r][c] } else { dq[a][b][r][c] };
                                assert!(
                                    (fd - an).abs() <= 1e-6 * (1.0 + fd.abs()),
                                    "{}: dQ[{a}][{r}]/d{}[{b}][{c}]: {an} vs {fd}",
                                    f.name,
                                    if vel { "qd" } else { "q" }
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn issue30_unknown_channels_are_named_with_the_nearby_ones() {
    let err = |forces: &str| {
        load_str(&model(forces), Format::Toml, "m.toml")
            .unwrap_err()
            .to_string()
    };
    let e = err("[[forces]]\ntype = \"point_force\"\nbody = \"block\"\nfx = \"-5*block_vz\"\n");
    assert!(
        e.contains("forces[0].fx")
            && e.contains("unknown name 'block_vz'")
            && e.contains("did you mean 'block_vx'")
            && e.contains("block_vy"),
        "{e}"
    );
    let e = err(
        "[[forces]]\ntype = \"point_force\"\nbody = \"block\"\nreaction = \"bar\"\nfx = \"-5*bar_phi\"\n",
    );
    assert!(e.contains("forces[0].reaction_point"), "{e}");
    let e = err(
        "[[forces]]\ntype = \"torque\"\nbody = \"block\"\nreaction = \"block\"\ntorque = \"1\"\n",
    );
    assert!(
        e.contains("forces[0].reaction") && e.contains("differ"),
        "{e}"
    );
}

/// A force on the block reading the bar, a body it does not act on: with
/// the bar driven, `bar_phi` is a known function of time, and the same
/// force written in time gives the same motion; its
/// derivatives with respect to the bar's coordinates equal central
/// differences.
#[test]
fn issue30_a_force_reading_a_third_body() {
    let driven = |fx: &str| {
        model(&format!(
            r#"
[[drivers]]
type = "revolute_angle"
joint = "hinge"
f = "0.3*sin(2*t)"

[[forces]]
type = "point_force"
body = "block"
fx = "{fx}"
"#
        ))
    };
    // The bar's angle is held by the driver to Newton's tolerance; its
    // rate only to the integrator's accuracy, so the comparison reads φ.
    let reading = driven("-k*(slide_stroke - l0 - 0.2*sin(bar_phi)) - c*slide_rate");
    let timed = driven("-k*(slide_stroke - l0 - 0.2*sin(0.3*sin(2*t))) - c*slide_rate");
    let l = load_str(
        &driven("-k*(slide_stroke - l0 - 0.2*sin(bar_phi)) - c*slide_rate + 3*bar_omega"),
        Format::Toml,
        "m.toml",
    )
    .unwrap();
    let bar = BodyId(1);
    assert_eq!(l.model.forces[0].kind.reads(), [bar]);
    let (a, b) = (simulate(&reading, vec![]), simulate(&timed, vec![]));
    let d = max_diff(&a, &b, &["block.x", "block.vx", "block.ax"]);
    eprintln!("force reading a third body vs the same force in time: {d:e}");
    assert!(d <= 1e-12, "{d}");
    let x = a.channel("block.x").unwrap();
    let span =
        x.iter().cloned().fold(f64::MIN, f64::max) - x.iter().cloned().fold(f64::MAX, f64::min);
    assert!(span > 0.05, "{span}");
    // ∂Q/∂q and ∂Q/∂q̇ of the bar's columns against central differences.
    let f = &l.model.forces[0].kind;
    let x = Local {
        t: 0.3,
        q: [[1.1, 0.0, 0.0], [0.0; 3]],
        qd: [[0.2, 0.0, 0.0], [0.0; 3]],
        ..Local::default()
    };
    let mut r = Reads::default();
    r.q[0] = [0.5, 0.0, 0.4];
    r.qd[0] = [0.0, 0.0, -0.8];
    let mut j = ForceJac::default();
    f.derivatives_reading(&x, &r, &mut j);
    let (rq, rqd) = (j.rq, j.rqd);
    let h = 1e-6;
    for c in 0..3 {
        for vel in [false, true] {
            let q_at = |dh: f64| {
                let mut r = r;
                if vel {
                    r.qd[0][c] += dh;
                } else {
                    r.q[0][c] += dh;
                }
                let mut q = BodyQ::default();
                f.generalized_reading(&x, &r, &mut q).unwrap();
                q
            };
            let (qp, qm) = (q_at(h), q_at(-h));
            for a in 0..2 {
                for row in 0..3 {
                    let fd = (qp[a][row] - qm[a][row]) / (2.0 * h);
                    let an = if vel {
                        rqd[a][0][row][c]
                    } else {
                        rq[a][0][row][c]
                    };
                    assert!(
                        (fd - an).abs() <= 1e-6 * (1.0 + fd.abs()),
                        "{a} {row} {c} {vel}: {an} vs {fd}"
                    );
                }
            }
        }
    }
    // The force depends on the bar: φ (through sin) and φ̇.
    assert!((rq[0][0][0][2] - (40.0 * 0.2 * 0.4f64.cos())).abs() < 1e-12);
    assert_eq!(rqd[0][0][0][2], 3.0);
}

#[test]
fn issue30_a_force_reads_at_most_four_other_bodies() {
    let mut text = String::new();
    for k in 0..6 {
        text += &format!(
            "[[bodies]]\nname = \"b{k}\"\nmass = 1\ninertia = 1\n\n[[joints]]\ntype = \"revolute\"\nname = \"pin{k}\"\nbody_i = \"ground\"\nbody_j = \"b{k}\"\n\n"
        );
    }
    let force = |others: usize| {
        let read: Vec<String> = (1..=others).map(|k| format!("pin{k}_angle")).collect();
        format!(
            "{text}[[forces]]\ntype = \"torque\"\nbody = \"b0\"\ntorque = \"{}\"\n",
            read.join(" + ")
        )
    };
    let l = load_str(&force(4), Format::Toml, "m.toml").unwrap();
    assert_eq!(l.model.forces[0].kind.reads().len(), 4);
    let e = load_str(&force(5), Format::Toml, "m.toml")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("forces[0].torque")
            && e.contains("'pin5_angle' reads body 'b5'")
            && e.contains("at most 4 others"),
        "{e}"
    );
}

/// examples/whitworth_global.toml in dynamics. The motor drives the crank
/// at constant speed: in inverse dynamics the motor's extra power for the
/// cutting force is the force's power, ΔP = 500·s(v)·v with s the STEP
/// from 0 to 1 over v ∈ [0, 0.01] m/s; forward dynamics runs the same
/// motion.
#[test]
fn issue30_whitworth_global_cuts_in_dynamics() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/whitworth_global.toml");
    let loaded = camlink_model::load_path(&path).unwrap();
    assert!(matches!(loaded.model.forces[0].kind, ForceKind::State(_)));
    let mut idle_model = loaded.model.clone();
    idle_model.forces.clear();
    let times = time_grid(1.0, 0.005).unwrap();
    let inverse = |m: &camlink_core::Model| {
        let mut t = Table::default();
        camlink_core::dynamics::inverse::run(
            m,
            &times,
            &camlink_core::run::Settings::default(),
            &[],
            &mut t,
        )
        .unwrap();
        t
    };
    let (cut, idle) = (inverse(&loaded.model), inverse(&idle_model));
    let v = cut.channel("ram.vx").unwrap();
    let (pc, pi) = (
        cut.channel("motor.power").unwrap(),
        idle.channel("motor.power").unwrap(),
    );
    let mut worst: f64 = 0.0;
    let mut forward = 0;
    for k in 0..v.len() {
        let u = (v[k] / 0.01).clamp(0.0, 1.0);
        let want = 500.0 * u * u * (3.0 - 2.0 * u) * v[k];
        worst = worst.max((pc[k] - pi[k] - want).abs());
        forward += usize::from(v[k] > 0.01);
    }
    let peak = 500.0 * v.iter().cloned().fold(0.0, f64::max);
    eprintln!("whitworth cutting power: max error {worst:e} W of {peak:.1} W");
    assert!(worst < 1e-9 * peak, "{worst} of {peak}");
    // The cutting stroke is the slow one: about 240° of the crank's 360°.
    let share = forward as f64 / v.len() as f64;
    assert!((share - 2.0 / 3.0).abs() < 0.03, "{share}");
    // Forward dynamics with the force runs the driven motion.
    let settings = Settings {
        step: 1e-3,
        tol: 1e-10,
        ..Settings::default()
    };
    let mut fwd = Table::default();
    run(&loaded.model, &times, &settings, &[], &mut fwd).unwrap();
    let (dx, dv) = (
        max_diff(&fwd, &cut, &["ram.x"]),
        max_diff(&fwd, &cut, &["ram.vx"]),
    );
    eprintln!("forward dynamics against the driven motion: ram.x {dx:e} m, ram.vx {dv:e} m/s");
    assert!(dx < 1e-8, "{dx}");
    // Velocities to the integrator's accuracy at h = 1 ms.
    assert!(dv < 1e-4, "{dv}");
}
