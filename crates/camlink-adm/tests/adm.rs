//! simEngine2D `.adm`/`.acf` models: every type against closed forms and
//! against the course's own equations evaluated on the results, the same
//! mechanism in camlink's format, converted files, and errors by kind and
//! by the names they give.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use camlink_adm::{convert_adm, describe_str, load_adm};
use camlink_core::dynamics::integrator;
use camlink_core::kinematics;
use camlink_core::run::{time_grid, Settings, Table};
use camlink_model::{load_path, load_str, Format, LoadError, Loaded};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/adm")
        .join(name)
}

fn example() -> PathBuf {
    root().join("examples/simengine2d/slider_crank.adm")
}

fn times(l: &Loaded) -> Vec<f64> {
    time_grid(l.analysis.t_end.unwrap(), l.analysis.step.unwrap()).unwrap()
}

fn kin(l: &Loaded) -> Table {
    let settings = Settings {
        tol: l.analysis.tol,
        max_iter: l.analysis.max_iter,
        ..Settings::default()
    };
    let mut table = Table::default();
    kinematics::run(&l.model, &times(l), &settings, &[], &mut table)
        .unwrap_or_else(|e| panic!("{e}"));
    table
}

fn dyn_run(l: &Loaded) -> Table {
    let mut table = Table::default();
    integrator::run(
        &l.model,
        &times(l),
        &l.analysis.integrator_settings(),
        &[],
        &mut table,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    table
}

fn ch(t: &Table, name: &str) -> Vec<f64> {
    t.channel(name)
        .unwrap_or_else(|| panic!("no channel {name} in {:?}", t.channels))
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn load_adm_text(adm: &str, acf: Option<&str>) -> Result<Loaded, LoadError> {
    describe_str(adm, "bad.adm", acf.map(|a| (a, "bad.acf")))?.resolve()
}

/// Slider x = r cos θ + √(l² − r² sin² θ) with θ = t², r = 0.2, l = 0.5.
#[test]
fn slider_crank_matches_the_closed_form() {
    let l = load_adm(&example(), None).unwrap();
    assert_eq!(l.model.name, "slider_crank");
    assert_eq!(l.analysis.kind, camlink_model::AnalysisType::Kinematics);
    assert_eq!(l.analysis.t_end, Some(2.0));
    let t = kin(&l);
    assert_eq!(t.t.len(), 201);
    let (r, len) = (0.2, 0.5);
    let x = ch(&t, "slider.x");
    let phi = ch(&t, "crank.phi");
    let slider_phi = ch(&t, "slider.phi");
    for (k, &time) in t.t.iter().enumerate() {
        let th = time * time;
        let want = r * th.cos() + (len * len - (r * th.sin()).powi(2)).sqrt();
        assert!(
            (x[k] - want).abs() < 1e-9,
            "t = {time}: x = {} want {want}",
            x[k]
        );
        assert!((phi[k] - th).abs() < 1e-9);
        // The course's v₁⊥·v₂ = 0 with v₁ = (2, 0), v₂' = (−1, 0): the slider keeps φ = 0.
        assert!(slider_phi[k].sin().abs() < 1e-12);
    }
}

#[test]
fn slider_crank_equals_the_same_mechanism_in_camlinks_format() {
    let adm = kin(&load_adm(&example(), None).unwrap());
    let own = kin(&load_path(&fixture("slider_crank.toml")).unwrap());
    assert_eq!(adm.t, own.t);
    for c in ["crank", "rod", "slider"] {
        for q in ["x", "y", "phi", "vx", "vy", "omega", "ax", "ay", "alpha"] {
            let name = format!("{c}.{q}");
            let d = max_diff(&ch(&adm, &name), &ch(&own, &name));
            assert!(d < 1e-8, "{name}: differs by {d}");
        }
    }
}

#[test]
fn pinned_pair_becomes_a_revolute_to_a_named_ground_point() {
    let text = convert_adm(&example(), None, Format::Toml).unwrap();
    assert!(text.contains("[ground.points]"), "{text}");
    assert!(text.contains("crank_pin = [0.0, 0.0]"), "{text}");
    assert!(text.contains("name = \"O\""), "{text}");
    assert!(text.contains("type = \"revolute\""), "{text}");
    assert!(!text.contains("absolute_x"), "{text}");
    assert!(
        text.contains("[[drivers]]") && text.contains("f = \"t^2\""),
        "{text}"
    );
    let l = load_adm(&example(), None).unwrap();
    let names: Vec<&str> = l.model.joints.iter().map(|c| c.name.as_str()).collect();
    assert!(
        names.contains(&"O") && names.contains(&"motor") && names.contains(&"slide"),
        "{names:?}"
    );
}

/// Results of a model and of its converted TOML and JSON files agree to 1e-12.
fn converted_files_agree(adm: &Path, dynamics: bool) {
    let run = |l: &Loaded| if dynamics { dyn_run(l) } else { kin(l) };
    let from_adm = run(&load_adm(adm, None).unwrap());
    for format in [Format::Toml, Format::Json] {
        let text = convert_adm(adm, None, format).unwrap();
        let source = adm.with_extension(if format == Format::Toml {
            "toml"
        } else {
            "json"
        });
        let converted = load_str(&text, format, &source.display().to_string())
            .unwrap_or_else(|e| panic!("{e}\n{text}"));
        let t = run(&converted);
        assert_eq!(t.channels, from_adm.channels);
        assert_eq!(t.t, from_adm.t);
        let d = max_diff(&t.values, &from_adm.values);
        assert!(d <= 1e-12, "{}: {format:?} differs by {d}", adm.display());
    }
}

#[test]
fn converted_files_give_the_same_results() {
    converted_files_agree(&example(), false);
    converted_files_agree(&fixture("rack_pinion.adm"), false);
    converted_files_agree(&fixture("forces.adm"), true);
    converted_files_agree(&fixture("translational.adm"), false);
    converted_files_agree(&fixture("course/slotted_lever.adm"), false);
    converted_files_agree(&fixture("course/rack_pinion_fun.adm"), false);
    converted_files_agree(&fixture("course/pendulum_forces.adm"), true);
}

/// The course's rack-and-pinion equations, evaluated on camlink's results,
/// hold; and the pinion rolls: at the contact point C (R from the pinion
/// centre, towards the pitch line) the pinion and the rack move alike.
/// The rack turns (φ₁ = 0.1 sin t) and slides; the pinion centre keeps x = 0.3.
#[test]
fn rack_pinion_obeys_the_course_equations_and_rolls() {
    let l = load_adm(&fixture("rack_pinion.adm"), None).unwrap();
    let t = kin(&l);
    let (r, th1, th2) = (0.1, 0.3, 0.1);
    let phi2_0 = 2.2 + 3.0 * PI / 2.0;
    let (x1, y1, p1) = (ch(&t, "rack.x"), ch(&t, "rack.y"), ch(&t, "rack.phi"));
    let (vx1, vy1, w1) = (ch(&t, "rack.vx"), ch(&t, "rack.vy"), ch(&t, "rack.omega"));
    let (x2, y2, p2) = (ch(&t, "pinion.x"), ch(&t, "pinion.y"), ch(&t, "pinion.phi"));
    let (vx2, vy2, w2) = (
        ch(&t, "pinion.vx"),
        ch(&t, "pinion.vy"),
        ch(&t, "pinion.omega"),
    );
    // The initial placement satisfies the course's equations: assembly keeps it.
    assert!(
        (p2[0] - phi2_0).abs() < 1e-12,
        "assembly moved the pinion: {}",
        p2[0]
    );
    let mut turned = 0.0f64;
    for k in 0..t.t.len() {
        let time = t.t[k];
        assert!((x1[k] - (0.1 * time + 0.05 * (2.0 * time).sin())).abs() < 1e-12);
        assert!((p1[k] - 0.1 * time.sin()).abs() < 1e-12);
        assert!((x2[k] - 0.3).abs() < 1e-12);
        turned = turned.max((p2[k] - phi2_0).abs());
        // Course: v₁ = A₁(sQ1 − sP1), L = |sQ1 − sP1| = 1.
        let (c, s) = (p1[k].cos(), p1[k].sin());
        let rot = |v: [f64; 2]| [c * v[0] - s * v[1], s * v[0] + c * v[1]];
        let v = rot([1.0, 0.0]);
        let rp = [x1[k] + rot([-0.5, 0.0])[0], y1[k] + rot([-0.5, 0.0])[1]];
        let rq = [x1[k] + rot([0.5, 0.0])[0], y1[k] + rot([0.5, 0.0])[1]];
        let alpha = p1[k] + th1 - p2[k] - th2 + 1.5 * PI;
        let phi_1 = (x2[k] - rq[0]) * v[0] + (y2[k] - rq[1]) * v[1] - r * alpha;
        let phi_2 = (x2[k] - rp[0]) * -v[1] + (y2[k] - rp[1]) * v[0] - r;
        assert!(
            phi_1.abs() < 1e-10 && phi_2.abs() < 1e-10,
            "t = {time}: {phi_1} {phi_2}"
        );
        // Rolling: velocity of C as a pinion point equals that as a rack point.
        let cp = [x2[k] + r * v[1], y2[k] - r * v[0]];
        let on_pinion = [
            vx2[k] - w2[k] * (cp[1] - y2[k]),
            vy2[k] + w2[k] * (cp[0] - x2[k]),
        ];
        let on_rack = [
            vx1[k] - w1[k] * (cp[1] - y1[k]),
            vy1[k] + w1[k] * (cp[0] - x1[k]),
        ];
        let slip = (on_pinion[0] - on_rack[0]).hypot(on_pinion[1] - on_rack[1]);
        assert!(slip < 1e-9, "t = {time}: slip {slip}");
    }
    assert!(turned > 1.0, "the pinion hardly turned ({turned} rad)");
}

/// Haug's translational joint between two moving bodies: the course's
/// v₁⊥·d = 0 and v₁⊥·v₂ = 0 hold on camlink's results, on the root chosen
/// nearest the initial angles: v′₂ = (0, −3) and v′₁ at 0.2 rad are parallel
/// for φ₂ − φ₁ = 0.2 + π/2 + kπ, and the initial −1.37 rad picks k = −1.
#[test]
fn translational_obeys_the_course_equations() {
    let l = load_adm(&fixture("translational.adm"), None).unwrap();
    let t = kin(&l);
    let (x1, y1, p1) = (ch(&t, "arm.x"), ch(&t, "arm.y"), ch(&t, "arm.phi"));
    let (x2, y2, p2) = (ch(&t, "block.x"), ch(&t, "block.y"), ch(&t, "block.phi"));
    let rot = |phi: f64, v: [f64; 2]| {
        let (c, s) = (phi.cos(), phi.sin());
        [c * v[0] - s * v[1], s * v[0] + c * v[1]]
    };
    for k in 0..t.t.len() {
        let time = t.t[k];
        assert!((p1[k] - (0.5 + 0.3 * time)).abs() < 1e-12);
        assert!(
            (p2[k] - p1[k] - (0.2 - PI / 2.0)).abs() < 1e-10,
            "t = {time}"
        );
        let v1 = rot(p1[k], [0.2f64.cos(), 0.2f64.sin()]);
        let v2 = rot(p2[k], [0.0, -3.0]);
        let r1 = rot(p1[k], [0.1, 0.05]);
        let r2 = rot(p2[k], [0.05, -0.1]);
        let d = [x2[k] + r2[0] - x1[k] - r1[0], y2[k] + r2[1] - y1[k] - r1[1]];
        let perp = [-v1[1], v1[0]];
        assert!(
            (perp[0] * d[0] + perp[1] * d[1]).abs() < 1e-10,
            "t = {time}"
        );
        assert!(
            (perp[0] * v2[0] + perp[1] * v2[1]).abs() < 1e-10,
            "t = {time}"
        );
        assert!((x2[k] + r2[0] - (1.0 + 0.2 * time)).abs() < 1e-10);
    }
}

/// Initial accelerations by hand: α = T/J and a = F/m + g for every force type.
#[test]
fn force_signs_match_a_hand_calculation() {
    let l = load_adm(&fixture("forces.adm"), None).unwrap();
    assert_eq!(l.analysis.kind, camlink_model::AnalysisType::Dynamics);
    let t = dyn_run(&l);
    let at0 = |name: &str| ch(&t, name)[0];
    let g = -9.81;
    // RSDA1 on the wheel: −(k(φ − θ0) + c φ̇ + fun(0)).
    let n1 = -(10.0 * (0.7 - 0.2) + 0.5 * 1.5 + 1.0);
    assert!(
        (at0("wheel.alpha") - n1 / 0.3).abs() < 1e-9,
        "{}",
        at0("wheel.alpha")
    );
    // RSDA2: n = k(φ2 − φ1 − θ0) + c(φ̇2 − φ̇1) + fun; +n on body1, −n on body2.
    let n = 4.0 * (0.1 - 0.4 + 0.1) + 0.3 * (2.0 + 0.5) + 1.0;
    assert!(
        (at0("left.alpha") - n / 0.2).abs() < 1e-9,
        "{}",
        at0("left.alpha")
    );
    assert!(
        (at0("right.alpha") + n / 0.5).abs() < 1e-9,
        "{}",
        at0("right.alpha")
    );
    // LRF point force (3, −1) at s' = (0.2, 0.1) on the plate at φ = 0.5.
    let (c, s) = (0.5f64.cos(), 0.5f64.sin());
    let f = [3.0 * c + s, 3.0 * s - c];
    let arm = [0.2 * c - 0.1 * s, 0.2 * s + 0.1 * c];
    assert!((at0("plate.ax") - f[0] / 3.0).abs() < 1e-9);
    assert!((at0("plate.ay") - (f[1] / 3.0 + g)).abs() < 1e-9);
    let torque = arm[0] * f[1] - arm[1] * f[0];
    assert!((at0("plate.alpha") - torque / 0.4).abs() < 1e-9);
    // Torque 2.5 + t on the disc.
    assert!((at0("disc.alpha") - 2.5 / 0.25).abs() < 1e-9);
    // GRF point force (4, 2) at s' = (0.1, −0.2) on the block at φ = 0.3.
    let (c, s) = (0.3f64.cos(), 0.3f64.sin());
    let arm = [0.1 * c + 0.2 * s, 0.1 * s - 0.2 * c];
    assert!((at0("block.ax") - 4.0 / 2.5).abs() < 1e-9);
    assert!((at0("block.alpha") - (arm[0] * 2.0 - arm[1] * 4.0) / 0.1).abs() < 1e-9);
}

// ----- errors, by kind and by the names they give -----

const BODY: &str = r#"{"name": "b", "id": 1, "mass": 1, "jbar": 1, "q0": [0, 0, 0]}"#;

fn one_constraint(c: &str) -> String {
    format!("{{\"bodies\": [{BODY}],\n \"constraints\": [\n  {c}\n ]}}")
}

#[test]
fn unknown_type_lists_the_supported_ones() {
    let e = load_adm_text(
        &one_constraint(r#"{"name": "c", "id": 7, "type": "Spherical", "body1": 1}"#),
        None,
    )
    .unwrap_err();
    let s = e.to_string();
    assert!(s.starts_with("bad.adm:3:"), "{s}");
    assert_eq!(e.field.as_deref(), Some("constraints[0].type"));
    assert!(
        s.contains("constraint 'c' (id 7)") && s.contains("'Spherical'"),
        "{s}"
    );
    for t in camlink_adm::constraint_types() {
        assert!(s.contains(t), "{s}");
    }
    let e = load_adm_text(&format!("{{\"bodies\": [{BODY}], \"forces\": [{{\"name\": \"f\", \"id\": 2, \"type\": \"Spring\"}}]}}"), None).unwrap_err();
    assert!(
        e.to_string().contains("force 'f' (id 2)") && e.to_string().contains("RSDA2"),
        "{e}"
    );
}

#[test]
fn point_force_file_is_refused_with_the_force_and_the_file() {
    let adm = format!(
        "{{\"bodies\": [{BODY}], \"forces\": [{{\"name\": \"tire\", \"id\": 3, \"type\": \"PointForceFile\", \"body1\": 1, \"sP1\": [0, 0], \"frame\": \"GRF\", \"mfile\": \"tireForce\"}}]}}"
    );
    let e = load_adm_text(&adm, None).unwrap_err();
    let s = e.to_string();
    assert!(
        s.contains("force 'tire' (id 3)") && s.contains("no file tireForce.m"),
        "{s}"
    );
    assert!(
        s.contains("[[forces]]") && s.contains("Python force"),
        "{s}"
    );
    assert_eq!(e.field.as_deref(), Some("forces[0].mfile"));
}

#[test]
fn a_missing_body_id_names_the_constraint_and_field() {
    let e = load_adm_text(&one_constraint(r#"{"name": "pin", "id": 4, "type": "RevoluteJoint", "body1": 1, "sP1": [0, 0], "body2": 9, "sP2": [0, 0]}"#), None).unwrap_err();
    assert_eq!(e.field.as_deref(), Some("constraints[0].body2"));
    assert_eq!(e.line, Some(3));
    assert!(
        e.message.contains("constraint 'pin' (id 4)") && e.message.contains("no body has id 9"),
        "{e}"
    );
}

#[test]
fn a_missing_field_and_a_bad_point_are_named() {
    let e = load_adm_text(
        &one_constraint(r#"{"name": "x", "id": 5, "type": "AbsoluteX", "body1": 1, "fun": "0"}"#),
        None,
    )
    .unwrap_err();
    assert!(
        e.message.contains("constraint 'x' (id 5)") && e.message.contains("sP1"),
        "{e}"
    );
    let e = load_adm_text(&one_constraint(r#"{"name": "x", "id": 5, "type": "AbsoluteX", "body1": 1, "sP1": [0, 0, 1], "fun": "0"}"#), None).unwrap_err();
    assert_eq!(e.field.as_deref(), Some("constraints[0].sP1"), "{e}");
}

#[test]
fn bad_functions_name_the_field() {
    let e = load_adm_text(
        &one_constraint(
            r#"{"name": "drive", "id": 6, "type": "AbsoluteAngle", "body1": 1, "fun": "sin(w*t)"}"#,
        ),
        None,
    )
    .unwrap_err();
    assert_eq!(e.field.as_deref(), Some("constraints[0].fun"));
    assert!(
        e.message.contains("constraint 'drive' (id 6)") && e.message.contains("unknown name 'w'"),
        "{e}"
    );
    let e = load_adm_text(
        &one_constraint(
            r#"{"name": "drive", "id": 6, "type": "AbsoluteAngle", "body1": 1, "fun": "NONE"}"#,
        ),
        None,
    )
    .unwrap_err();
    assert!(e.message.contains("needs a fun"), "{e}");
}

#[test]
fn arithmetic_is_accepted_where_a_number_is_expected() {
    let adm = r#"{"bodies": [{"name": "b", "id": 1, "mass": 3/4, "jbar": "1/8", "q0": [2*0.5, 0, pi/2]}],
      "vis": {"color": [187/255, 0.5, 1]}}"#;
    let l = load_adm_text(adm, None).unwrap();
    let b = &l.model.bodies[1];
    assert_eq!(b.mass, 0.75);
    assert_eq!(b.inertia, 0.125);
    assert_eq!(b.q0, [1.0, 0.0, PI / 2.0]);
    // Arithmetic is parsed, never run: a name that is not a number is an error.
    let e = load_adm_text(
        r#"{"bodies": [{"id": 1, "mass": system(1), "q0": [0, 0, 0]}]}"#,
        None,
    )
    .unwrap_err();
    assert_eq!(e.field.as_deref(), Some("bodies[0].mass"), "{e}");
    assert!(e.message.contains("unknown function 'system'"), "{e}");
    let e = load_adm_text(
        r#"{"bodies": [{"id": 1, "jbar": 1/0, "q0": [0, 0, 0]}]}"#,
        None,
    )
    .unwrap_err();
    assert_eq!(e.field.as_deref(), Some("bodies[0].jbar"), "{e}");
    assert!(e.message.contains("division by zero"), "{e}");
}

#[test]
fn syntax_errors_give_the_line_in_the_file() {
    let e = load_adm_text(
        "{\"bodies\": [\n  {\"id\": 1, \"mass\": 1/2 \"q0\": [0, 0, 0]}\n]}",
        None,
    )
    .unwrap_err();
    assert_eq!(e.line, Some(2), "{e}");
    assert!(e.message.starts_with("syntax error"), "{e}");
}

#[test]
fn analysis_file_errors_name_the_acf() {
    let adm = format!("{{\"bodies\": [{BODY}]}}");
    let e = load_adm_text(&adm, Some(r#"{"simulation": "Static", "tend": 1}"#)).unwrap_err();
    assert_eq!(e.source, "bad.acf");
    assert!(
        e.message.contains("Kinematics, Dynamics or Equilibrium"),
        "{e}"
    );
    let e = load_adm_text(
        &adm,
        Some(r#"{"simulation": "Kinematics", "tend": -1, "outputSteps": 10}"#),
    )
    .unwrap_err();
    assert_eq!(e.source, "bad.acf", "{e}");
    assert_eq!(e.field.as_deref(), Some("tend"), "{e}");
    assert!(
        e.message
            .contains("t_end must be a finite number of at least 0"),
        "{e}"
    );
    let l = load_adm_text(&adm, Some(r#"{"simulation": "Equilibrium"}"#)).unwrap();
    assert_eq!(l.analysis.kind, camlink_model::AnalysisType::Equilibrium);
    let l = load_adm_text(
        &adm,
        Some(r#"{"simulation": "Dynamics", "tend": 1, "stepSize": 0.002, "outputSteps": 20}"#),
    )
    .unwrap();
    assert_eq!(l.analysis.step, Some(0.05));
    assert_eq!(l.analysis.dynamics.h, Some(0.002));
}

#[test]
fn names_fall_back_to_ids_and_duplicates_get_their_id() {
    let adm = r#"{"bodies": [{"id": 1, "q0": [0, 0, 0]}, {"name": "ground", "id": 2, "q0": [1, 0, 0]}],
      "constraints": [
        {"id": 1, "type": "AbsoluteAngle", "body1": 1, "fun": "0"},
        {"name": "fix", "id": 2, "type": "AbsoluteAngle", "body1": 2, "fun": "0"},
        {"name": "fix", "id": 3, "type": "AbsoluteX", "body1": 2, "sP1": [0, 0], "fun": "1"}
      ]}"#;
    let l = load_adm_text(adm, None).unwrap();
    let bodies: Vec<&str> = l.model.bodies.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(bodies, ["ground", "body1", "ground_2"]);
    let names: Vec<&str> = l.model.joints.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["constraint1", "fix", "fix_3"]);
}

#[test]
fn a_resolver_error_is_placed_at_the_adm_field() {
    // sqrt(-1) is read as a constant and fails in camlink's resolver (not a
    // finite number), which places the error at the .adm field it came from.
    let e = load_adm_text(&one_constraint(r#"{"name": "x", "id": 5, "type": "AbsoluteX", "body1": 1, "sP1": [0, 0], "fun": "sqrt(-1)"}"#), None).unwrap_err();
    assert!(e.message.contains("constraint 'x' (id 5)"), "{e}");
    assert_eq!(e.field.as_deref(), Some("constraints[0].fun"), "{e}");
}

#[test]
fn constant_absolutes_are_joints_and_a_pair_at_one_point_a_revolute() {
    use camlink_core::Equations;
    let adm = r#"{"bodies": [{"name": "a", "id": 1, "q0": [0, 0, 0]}, {"name": "b", "id": 2, "q0": [1, 0, 0]}],
      "constraints": [
        {"name": "ax", "id": 1, "type": "AbsoluteX", "body1": 1, "sP1": [0.5, 0], "fun": "0.5"},
        {"name": "ay", "id": 2, "type": "AbsoluteY", "body1": 1, "sP1": [0.1, 0], "fun": "0"},
        {"name": "aphi", "id": 3, "type": "AbsoluteAngle", "body1": 1, "fun": "pi/2 - pi/2"},
        {"name": "by", "id": 4, "type": "AbsoluteY", "body1": 2, "sP1": [0, 0], "fun": "0"},
        {"name": "bx", "id": 5, "type": "AbsoluteX", "body1": 2, "sP1": [0, 0], "fun": "2/2"},
        {"name": "bphi", "id": 6, "type": "AbsoluteAngle", "body1": 2, "fun": "2*t"}
      ]}"#;
    let l = load_adm_text(adm, None).unwrap();
    let kinds: Vec<(&str, &str, bool)> = l
        .model
        .joints
        .iter()
        .map(|j| (j.name.as_str(), j.constraint.kind(), j.driver))
        .collect();
    assert_eq!(
        kinds,
        [
            ("aphi", "absolute_coordinate", false),
            ("ax", "absolute_coordinate", false),
            ("ay", "absolute_coordinate", false),
            ("b", "revolute", false),
            ("bphi", "absolute_coordinate", true),
        ]
    );
    let ground = &l.model.bodies[0];
    assert_eq!(ground.point("b_pin"), Some([1.0, 0.0]));
}

/// Every file in `examples/simengine2d/` is checked by a test of this file:
/// adding one without a test fails here.
#[test]
fn every_simengine2d_example_has_a_test() {
    let mut files: Vec<String> = std::fs::read_dir(root().join("examples/simengine2d"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    assert_eq!(files, ["slider_crank.acf", "slider_crank.adm"]);
}

/// MATLAB's JSON writer gives `[]` for an empty body and may leave a
/// constant `fun` as a number: both are read as the course engine reads them.
#[test]
fn empty_body_is_the_ground_and_a_numeric_fun_a_constant() {
    let adm = r#"{"bodies": [{"name": "a", "id": 1, "q0": [0.5, 0, 0]}],
      "constraints": [
        {"name": "pin", "id": 1, "type": "RevoluteJoint", "body1": [], "sP1": [0, 0], "body2": 1, "sP2": [-0.5, 0], "fun": null},
        {"name": "hold", "id": 2, "type": "AbsoluteAngle", "body1": 1, "fun": 0.25}
      ]}"#;
    let l = load_adm_text(adm, None).unwrap();
    assert_eq!(l.model.joints.len(), 2);
    assert_eq!(l.model.bodies[0].point("pin"), Some([0.0, 0.0]));
    let e = load_adm_text(
        &one_constraint(
            r#"{"name": "d", "id": 3, "type": "AbsoluteAngle", "body1": 1, "fun": [1, 2]}"#,
        ),
        None,
    )
    .unwrap_err();
    assert_eq!(e.field.as_deref(), Some("constraints[0].fun"), "{e}");
    assert!(e.message.contains("function of t"), "{e}");
}

/// Each kind of mistake names its entry and field.
#[test]
fn mistakes_by_kind_name_the_entry_and_field() {
    let cases: &[(&str, &str, &str)] = &[
        (
            r#"{"bodies": [{"name": "a", "id": 1, "q0": [0, 0, 0]}, {"name": "b", "id": 1, "q0": [0, 0, 0]}]}"#,
            "bodies[1].id",
            "body 'b' (id 1): id 1 is also the id of bodies[0]",
        ),
        (
            r#"{"bodies": [{"name": "a", "id": 1, "mass": -2, "q0": [0, 0, 0]}]}"#,
            "bodies[0].mass",
            "body 'a' (id 1): mass must not be negative",
        ),
        (
            r#"{"bodies": [{"name": "a", "id": 1, "q0": [0, 0]}]}"#,
            "bodies[0].q0",
            "body 'a' (id 1): invalid length 2",
        ),
        (
            &one_constraint(r#"{"name": "j", "id": 2, "type": "RevoluteJoint", "sP1": [0, 0], "sP2": [0, 0]}"#),
            "constraints[0].body2",
            "constraint 'j' (id 2): both bodies are the ground",
        ),
        (
            &one_constraint(r#"{"name": "j", "id": 2, "type": "RevoluteJoint", "body1": 1, "sP1": [0, 0], "body2": 1, "sP2": [0, 0]}"#),
            "constraints[0].body2",
            "constraint 'j' (id 2): body1 and body2 are the same body",
        ),
        (
            &one_constraint(r#"{"name": "j", "id": 2, "type": "RevoluteJoint", "sP1": [0, 0], "body2": 1, "sP2": [0, 0], "fun": "t"}"#),
            "constraints[0].fun",
            "constraint 'j' (id 2): a RevoluteJoint takes no function",
        ),
        (
            &one_constraint(r#"{"name": "s", "id": 3, "type": "TranslationalJoint", "sP1": [0, 0], "vP1": [0, 0], "body2": 1, "sP2": [0, 0], "vP2": [1, 0]}"#),
            "constraints[0].vP1",
            "constraint 's' (id 3): the direction vector is zero",
        ),
        (
            &one_constraint(r#"{"name": "r", "id": 4, "type": "RackPinion", "sP1": [0, 0], "sQ1": [1, 0], "body2": 1, "sP2": [0, 0], "R2": 0, "theta1": 0, "theta2": 0}"#),
            "constraints[0].R2",
            "constraint 'r' (id 4): the pitch radius R2 must be positive",
        ),
        (
            &one_constraint(r#"{"name": "r", "id": 4, "type": "RackPinion", "sP1": [1, 0], "sQ1": [1, 0], "body2": 1, "sP2": [0, 0], "R2": 1, "theta1": 0, "theta2": 0}"#),
            "constraints[0].sQ1",
            "constraint 'r' (id 4): sQ1 equals sP1",
        ),
        (
            &format!("{{\"bodies\": [{BODY}], \"forces\": [{{\"name\": \"p\", \"id\": 5, \"type\": \"PointForce\", \"body1\": 1, \"sP1\": [0, 0], \"frame\": \"XYZ\"}}]}}"),
            "forces[0].frame",
            "force 'p' (id 5): unknown frame 'XYZ'",
        ),
        (
            &format!("{{\"bodies\": [{BODY}], \"forces\": [{{\"name\": \"k\", \"id\": 6, \"type\": \"RSDA1\", \"body1\": 1, \"theta0\": 0, \"k\": -1, \"c\": 0}}]}}"),
            "forces[0].k",
            "force 'k' (id 6): k must not be negative",
        ),
        (
            &format!("{{\"bodies\": [{BODY}], \"forces\": [{{\"name\": \"k\", \"id\": 6, \"type\": \"RSDA1\", \"theta0\": 0, \"k\": 1, \"c\": 0}}]}}"),
            "forces[0].body1",
            "force 'k' (id 6): missing field `body1`",
        ),
    ];
    for (adm, field, message) in cases {
        let e = load_adm_text(adm, None).unwrap_err();
        assert_eq!(e.source, "bad.adm");
        assert_eq!(e.field.as_deref(), Some(*field), "{e}");
        assert!(e.message.starts_with(message), "{e}\nexpected: {message}");
        assert!(e.line.is_some(), "{e}");
    }
}

#[test]
fn a_text_over_the_size_limit_is_refused() {
    let big = format!(
        "{{\"pad\": \"{}\"}}",
        " ".repeat(camlink_model::MAX_FILE_SIZE as usize)
    );
    let e = load_adm_text(&big, None).unwrap_err();
    assert!(e.message.contains("too large"), "{e}");
}

/// A body's one `vis` rectangle becomes its drawn outline, corners
/// counter-clockwise in the body frame.
#[test]
fn a_vis_rectangle_becomes_the_body_outline() {
    let l = load_adm(&example(), None).unwrap();
    assert_eq!(l.outlines.len(), 3);
    let crank = l.outlines.iter().find(|o| o.body == "crank").unwrap();
    match &crank.shape {
        camlink_model::OutlineShape::Polyline(p) => {
            assert_eq!(p, &[[-0.1, -0.01], [0.1, -0.01], [0.1, 0.01], [-0.1, 0.01]]);
        }
        other => panic!("{other:?}"),
    }
    let text = convert_adm(&example(), None, Format::Toml).unwrap();
    assert!(
        text.contains("outline = [[-0.25, -0.01], [0.25, -0.01], [0.25, 0.01], [-0.25, 0.01]]"),
        "{text}"
    );
}
