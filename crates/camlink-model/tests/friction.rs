//! `[[forces]] type = "viscous_friction"`: loading, errors, and a block
//! sliding down an inclined guide to its terminal speed.

use camlink_core::dynamics::integrator::{run, Settings};
use camlink_core::force::ForceKind;
use camlink_core::run::{time_grid, Table};
use camlink_model::{load_str, Format};

/// A block on a guide inclined at `beta`, and a wheel on a pin.
fn model(beta: f64, c_slide: &str, joint: &str) -> String {
    format!(
        r#"
[model]
gravity = [0, -9.81]

[[bodies]]
name = "block"
mass = 2

[[bodies]]
name = "wheel"
position = [1, 0]
mass = 1
inertia = 0.01
omega = 3

[[joints]]
type = "translational"
name = "incline"
body_i = "ground"
axis = [{}, {}]
body_j = "block"

[[joints]]
type = "revolute"
name = "axle"
body_i = "ground"
point_i = [1, 0]
body_j = "wheel"

[[forces]]
type = "viscous_friction"
name = "slide"
joint = "{joint}"
damping = {c_slide}

[[forces]]
type = "viscous_friction"
joint = "axle"
damping = 0.02
"#,
        beta.cos(),
        -beta.sin()
    )
}

#[test]
fn viscous_friction_loads_for_both_joint_kinds() {
    let m = load_str(&model(0.3, "4", "incline"), Format::Toml, "f.toml")
        .unwrap()
        .model;
    match &m.forces[0].kind {
        ForceKind::TranslationalDamper(d) => {
            assert_eq!(d.damping, 4.0);
            assert!((d.v_i[0] - 0.3f64.cos()).abs() < 1e-15);
        }
        k => panic!("{k:?}"),
    }
    assert_eq!(m.forces[1].name, "viscous_friction_1");
    match &m.forces[1].kind {
        ForceKind::Rsda(r) => {
            assert_eq!((r.stiffness, r.damping), (0.0, 0.02));
        }
        k => panic!("{k:?}"),
    }
}

#[test]
fn viscous_friction_errors_name_the_field() {
    let err = |text: String| {
        load_str(&text, Format::Toml, "f.toml")
            .unwrap_err()
            .to_string()
    };
    let e = err(model(0.3, "4", "inclne"));
    assert!(
        e.contains("forces[0].joint") && e.contains("did you mean 'incline'"),
        "{e}"
    );
    let e = err(model(0.3, "-1", "incline"));
    assert!(e.contains("forces[0].damping") && e.contains("≥ 0"), "{e}");
    let text = model(0.3, "4", "incline").replace(
        "[[forces]]\ntype = \"viscous_friction\"\nname",
        "[[joints]]\ntype = \"relative_phi\"\nname = \"lock\"\nbody_i = \"block\"\nbody_j = \"wheel\"\n\n\
         [[forces]]\ntype = \"viscous_friction\"\nname",
    );
    let e = err(text.replace("joint = \"incline\"", "joint = \"lock\""));
    assert!(
        e.contains("forces[0].joint") && e.contains("revolute or translational"),
        "{e}"
    );
}

/// v(t) = v_∞ (1 − e^{−c t/m}) down the incline, v_∞ = m g sin β / c, and
/// the wheel's spin decays as ω₀ e^{−c_r t/J}.
#[test]
fn block_slides_to_its_terminal_speed() {
    let (beta, c, m, g) = (0.4f64, 4.0, 2.0, 9.81);
    let l = load_str(
        &model(beta, &c.to_string(), "incline"),
        Format::Toml,
        "f.toml",
    )
    .unwrap();
    let times = time_grid(2.0, 0.01).unwrap();
    let settings = Settings {
        step: 1e-3,
        tol: 1e-10,
        ..Settings::default()
    };
    let mut t = Table::default();
    run(&l.model, &times, &settings, &[], &mut t).unwrap();
    let (vx, vy, w) = (
        t.channel("block.vx").unwrap(),
        t.channel("block.vy").unwrap(),
        t.channel("wheel.omega").unwrap(),
    );
    let v_inf = m * g * beta.sin() / c;
    let mut worst: f64 = 0.0;
    let mut worst_w: f64 = 0.0;
    for k in 0..t.t.len() {
        let v = vx[k] * beta.cos() - vy[k] * beta.sin();
        let want = v_inf * (1.0 - (-c * t.t[k] / m).exp());
        worst = worst.max((v - want).abs());
        let want_w = 3.0 * (-0.02 * t.t[k] / 0.01).exp();
        worst_w = worst_w.max((w[k] - want_w).abs());
    }
    eprintln!("sliding speed error {worst:.1e} m/s of {v_inf:.3}; spin error {worst_w:.1e} rad/s");
    assert!(worst < 1e-5 * v_inf, "{worst}");
    assert!(worst_w < 1e-5 * 3.0, "{worst_w}");
}
