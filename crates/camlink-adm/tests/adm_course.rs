//! Issue 27: the course engine's own model files run.
//!
//! The public course repository (simEngine2D, the ME451 course engine)
//! holds 19 `.adm` models; it carries no licence, so its files are not
//! copied here. `tests/adm/course/` holds small models of our own that
//! reproduce every construct those files use (the pinned pendulums, the
//! force elements, driven chains, a rack and pinion with `"fun": "0"`, a
//! slotted lever with names containing spaces, tabs, a `forces` list
//! holding `{}` and a `contacts` list, a shaken slider, an offset
//! four-bar), each run with the analysis of the `.acf` beside it.
//! `issue27_course_repository_models_run` runs the course's own files (all
//! 19, `project2.adm` with its force function `pistonForce.m` translated)
//! when `CAMLINK_COURSE_MODELS` names their `Models` folder.

use std::path::{Path, PathBuf};

use camlink_adm::{describe_str, load_adm};
use camlink_core::dynamics::{integrator, statics};
use camlink_core::kinematics;
use camlink_core::run::{time_grid, Settings, Table};
use camlink_model::{AnalysisType, Loaded};

fn course_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/adm/course")
}

/// Runs the analysis the `.acf` asked for; the number of output rows.
fn run(l: &Loaded) -> Result<usize, String> {
    let a = &l.analysis;
    let mut table = Table::default();
    let settings = Settings {
        tol: a.tol_for(a.kind),
        max_iter: a.max_iter_for(a.kind),
        jerk: false,
    };
    let grid = || time_grid(a.t_end.expect("t_end"), a.step.expect("step"));
    match a.kind {
        AnalysisType::Kinematics => {
            kinematics::run(&l.model, &grid()?, &settings, &[], &mut table)
                .map_err(|e| e.to_string())?;
        }
        AnalysisType::Dynamics => {
            integrator::run(
                &l.model,
                &grid()?,
                &a.integrator_settings(),
                &[],
                &mut table,
            )
            .map_err(|e| e.to_string())?;
        }
        other => {
            assert_eq!(other, AnalysisType::Equilibrium);
            let s = statics::Settings {
                tol: settings.tol,
                max_iter: settings.max_iter,
            };
            statics::run(&l.model, a.time, &s, &[], &mut table).map_err(|e| e.to_string())?;
        }
    }
    Ok(table.t.len())
}

/// Loads `adm` with `acf` and runs it to the end of its output grid.
fn load_and_run(adm: &Path, acf: Option<&Path>) -> Loaded {
    let l = load_adm(adm, acf).unwrap_or_else(|e| panic!("{e}"));
    let rows = run(&l).unwrap_or_else(|e| panic!("{}: {e}", adm.display()));
    let a = &l.analysis;
    let expected = time_grid(a.t_end.unwrap(), a.step.unwrap()).unwrap().len();
    assert_eq!(rows, expected, "{}", adm.display());
    l
}

#[test]
fn issue27_course_constructs_run() {
    let mut names: Vec<String> = std::fs::read_dir(course_dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".adm"))
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "driven_chain.adm",
            "driven_slider.adm",
            "offset_four_bar.adm",
            "pendulum_forces.adm",
            "pinned_pendulum.adm",
            "rack_pinion_fun.adm",
            "slotted_lever.adm",
            "spinning_rod.adm",
        ]
    );
    for name in &names {
        let l = load_and_run(&course_dir().join(name), None);
        let expected = match name.as_str() {
            "rack_pinion_fun.adm" => 1,
            "slotted_lever.adm" => 2,
            _ => 0,
        };
        assert_eq!(l.warnings.len(), expected, "{name}: {:?}", l.warnings);
    }
}

/// A rack and pinion (or any joint) with a constant `fun` loads, with a
/// warning at the field naming what is ignored; a function of t is refused.
#[test]
fn issue27_rack_pinion_constant_fun_is_ignored_with_a_warning() {
    let l = load_and_run(&course_dir().join("rack_pinion_fun.adm"), None);
    let w = &l.warnings[0];
    assert!(w.contains("rack_pinion_fun.adm:"), "{w}");
    assert!(w.contains("constraints[3].fun"), "{w}");
    assert!(w.contains("constraint 'mesh' (id 4)"), "{w}");
    assert!(
        w.contains("fun \"0\" is ignored: the course engine does not use a RackPinion's fun"),
        "{w}"
    );

    let text = std::fs::read_to_string(course_dir().join("rack_pinion_fun.adm")).unwrap();
    let driven = text.replace(
        r#""R2": 0.15, "fun": "0""#,
        r#""R2": 0.15, "fun": "sin(t)""#,
    );
    assert_ne!(driven, text);
    let e = describe_str(&driven, "rp.adm", None)
        .err()
        .expect("refused");
    let e = e.to_string();
    assert!(e.starts_with("rp.adm:"), "{e}");
    assert!(e.contains("constraints[3].fun: constraint 'mesh' (id 4): a RackPinion takes no function of time, but fun is \"sin(t)\""), "{e}");
    assert!(
        e.contains("drive it with an AbsoluteX, AbsoluteY or AbsoluteAngle"),
        "{e}"
    );

    // The same rule for the other joints, whose fun the course engine
    // reads and never uses either.
    let revolute = r#"{"bodies": [{"name": "a", "id": 1, "q0": [0.5, 0, 0]}],
      "constraints": [{"name": "pin", "id": 1, "type": "RevoluteJoint", "body2": 1,
        "sP1": [0, 0], "sP2": [-0.5, 0], "fun": "FUN"}]}"#;
    let d = describe_str(&revolute.replace("FUN", "0"), "r.adm", None).unwrap();
    assert_eq!(d.warnings.len(), 1, "{:?}", d.warnings);
    assert!(
        d.warnings[0].contains("RevoluteJoint's fun"),
        "{:?}",
        d.warnings
    );
    let e = describe_str(&revolute.replace("FUN", "2*t"), "r.adm", None)
        .err()
        .expect("refused")
        .to_string();
    assert!(
        e.contains("a RevoluteJoint takes no function of time"),
        "{e}"
    );
    let d = describe_str(&revolute.replace("FUN", "NONE"), "r.adm", None).unwrap();
    assert!(d.warnings.is_empty());
}

/// `forces: [{}]` next to a top-level `contacts` list loads as the course
/// engine loads it, with a warning for each thing ignored.
#[test]
fn issue27_empty_force_and_contacts_are_ignored_with_warnings() {
    let l = load_and_run(&course_dir().join("slotted_lever.adm"), None);
    assert!(l.model.forces.is_empty());
    let [empty, contacts] = l.warnings.as_slice() else {
        panic!("{:?}", l.warnings)
    };
    assert!(empty.contains("slotted_lever.adm:20:3:"), "{empty}");
    assert!(
        empty.contains("forces[0]: an empty entry {} is ignored"),
        "{empty}"
    );
    assert!(contacts.contains("slotted_lever.adm:23:"), "{contacts}");
    assert!(
        contacts.contains(
            "contacts: 2 contact entries are ignored: the course engine does not read `contacts`"
        ),
        "{contacts}"
    );
    // Names with spaces become names camlink accepts.
    let joints: Vec<&str> = l.model.joints.iter().map(|j| j.name.as_str()).collect();
    assert!(
        joints.contains(&"Translational_Collar-Long_Rod"),
        "{joints:?}"
    );
    assert!(l.model.bodies.iter().any(|b| b.name == "Long_Rod"));
}

/// The course repository's 19 models (`CAMLINK_COURSE_MODELS`: its
/// `Models` folder), each with the `.acf` the course pairs it with (by
/// name: `*KIN` kinematics, `*DYN` and the undriven pendulums dynamics):
/// the 18 that need no MATLAB code run to the end; the 19th,
/// `project2.adm`, computes a force with the MATLAB file `pistonForce.m`
/// and is refused.
#[test]
fn issue27_course_repository_models_run() {
    let Some(dir) = std::env::var_os("CAMLINK_COURSE_MODELS") else {
        eprintln!("CAMLINK_COURSE_MODELS is not set: the course's own files are not run");
        return;
    };
    let dir = PathBuf::from(dir);
    let runs = [
        ("doublePendDYN", "dynamics"),
        ("dpendKIN", "kinematics"),
        ("dpendVIS", "dynamics"),
        ("finalExam", "finalExam"),
        ("pend1", "dynamics"),
        ("pend2", "dynamics"),
        ("pendDYN", "dynamics"),
        ("pendEQL", "dynamics"),
        ("pendKIN", "kinematics"),
        ("project1", "project1"),
        ("project2", "project2"),
        ("projectFinalDYN", "dynamics"),
        ("projectFinalKIN", "kinematics"),
        ("rack_pinion", "kinematics"),
        ("rodDYN", "dynamics"),
        ("shurikenCatapult", "shurikenCatapult"),
        ("simplePend", "kinematics"),
        ("sliderCrankDYN", "dynamics"),
        ("sliderCrankKIN", "kinematics"),
    ];
    for (adm, acf) in runs {
        let l = load_and_run(
            &dir.join(format!("{adm}.adm")),
            Some(&dir.join(format!("{acf}.acf"))),
        );
        eprintln!("{adm}.adm with {acf}.acf: runs; warnings {:?}", l.warnings);
    }
    assert_eq!(runs.len(), 19);
    // project2's PointForceFile: pistonForce.m, in the repository root (the
    // course engine's working folder), translated and compared with the
    // function evaluated by hand in every branch.
    let m = dir.join("../pistonForce.m");
    let src = std::fs::read_to_string(&m).unwrap_or_else(|e| panic!("{}: {e}", m.display()));
    let f = camlink_adm::mfile::translate(&src, "pistonForce.m", "slider").unwrap();
    let piston = |_t: f64, q: [f64; 3], qd: [f64; 3]| {
        let (x3, x3d) = (q[0], qd[0]);
        let mut f = [0.0, 0.0];
        if x3d > 0.0 {
            f[0] = if x3 > 5.5 {
                0.0
            } else if x3 > 5.0 {
                -110000.0 * (1.0 - (2.0 * std::f64::consts::PI * (x3 - 5.25)).sin())
            } else if x3 >= 1.5 {
                62857.0 - 282857.0 / (6.0 - x3)
            } else {
                0.0
            };
        }
        f
    };
    let n = crate::adm_mfile::compare_on_branches(
        crate::adm_mfile::compiled(&f.fx, &f.fy, "slider"),
        piston,
        &[1.0, 1.5, 3.0, 5.0, 5.2, 5.5, 5.8],
        &[0.0, 0.5],
    );
    eprintln!("pistonForce.m: fx = {}, fy = {} ({n} points)", f.fx, f.fy);
}

/// `camlink check` assembles a course model in millimetres whose crank is
/// placed 0.444 rad from its driven angle, as the course's catapult is: the
/// least-squares assembly moves lengths by hundreds of units (it limits
/// only how far an angle turns in one step), and the model is fully driven.
#[test]
fn issue27_check_assembles_a_course_model_in_millimetres() {
    let adm = r#"{"name": "crank_slider_mm", "gravity": [0, 0],
      "bodies": [
        {"name": "crank", "id": 1, "mass": 5, "jbar": 900, "q0": [97, -46.2, -0.444]},
        {"name": "rod", "id": 2, "mass": 5, "jbar": 900, "q0": [450, -46, 0.185]},
        {"name": "slider", "id": 3, "mass": 5, "jbar": 900, "q0": [700, 0, 0]}
      ],
      "constraints": [
        {"name": "O_x", "id": 1, "type": "AbsoluteX", "body1": 1, "sP1": [-107.5, 0], "fun": "0"},
        {"name": "O_y", "id": 2, "type": "AbsoluteY", "body1": 1, "sP1": [-107.5, 0], "fun": "0"},
        {"name": "A", "id": 3, "type": "RevoluteJoint", "body1": 1, "sP1": [107.5, 0], "body2": 2, "sP2": [-250, 0], "fun": "NONE"},
        {"name": "B", "id": 4, "type": "RevoluteJoint", "body1": 2, "sP1": [250, 0], "body2": 3, "sP2": [0, 0], "fun": "NONE"},
        {"name": "rail", "id": 5, "type": "AbsoluteY", "body1": 3, "sP1": [0, 0], "fun": "0"},
        {"name": "level", "id": 6, "type": "AbsoluteAngle", "body1": 3, "fun": "0"},
        {"name": "motor", "id": 7, "type": "AbsoluteAngle", "body1": 1, "fun": "15*t"}
      ]}"#;
    let l = describe_str(adm, "mm.adm", None)
        .unwrap()
        .resolve()
        .unwrap();
    let d = camlink_core::diagnose::diagnose(&l.model, 0.0, l.analysis.tol);
    assert!(d.open_joints.is_empty(), "{:?}", d.open_joints);
    assert!(d.residual <= l.analysis.tol, "{}", d.residual);
    assert_eq!(d.dof, 0);
}
