//! The joint-kind registry (issue 28): every `[[joints]]` type of the
//! schema has its registry line (`JOINT_KINDS`), resolves, converts its
//! units, has a drawing or says it has none, and is documented; the
//! binding and the drawings never name a kind (camlink-adm's
//! `joint_kinds` checks the course-file types of the registry).
//! `docs/adding-a-joint.md` lists the files.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use camlink_core::assembly::Assembly;
use camlink_core::Equations;
use camlink_model::{load_str, Format, Loaded, JOINT_KINDS};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn read(rel: &str) -> String {
    std::fs::read_to_string(root().join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

const FIXTURE: &str = "crates/camlink-model/tests/joint_kinds/every_kind.toml";

/// Kinds with nothing to draw: a held coordinate or distance.
const NOT_DRAWN: &[&str] = &[
    "absolute_x",
    "absolute_y",
    "absolute_phi",
    "absolute_distance",
    "relative_x",
    "relative_y",
    "relative_phi",
    "relative_distance",
];

fn kinds() -> Vec<&'static str> {
    JOINT_KINDS.iter().map(|k| k.kind).collect()
}

fn load(text: &str) -> Loaded {
    load_str(text, Format::Toml, "every_kind.toml").unwrap_or_else(|e| panic!("{e}"))
}

/// The `type` of each `[[joints]]` entry of the fixture, in order.
fn fixture_types() -> Vec<String> {
    let doc: toml::Value = toml::from_str(&read(FIXTURE)).unwrap();
    doc["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j["type"].as_str().unwrap().to_string())
        .collect()
}

#[test]
fn the_registry_lists_the_schema_kinds_in_order() {
    let schema = camlink_model::json_schema();
    let variants = schema["$defs"]["JointSpec"]["oneOf"].as_array().unwrap();
    let in_schema: Vec<&str> = variants
        .iter()
        .map(|v| v["properties"]["type"]["const"].as_str().unwrap())
        .collect();
    assert_eq!(kinds(), in_schema);
}

#[test]
fn every_kind_resolves_once_in_the_fixture() {
    let types = fixture_types();
    assert_eq!(
        types.iter().map(String::as_str).collect::<BTreeSet<_>>(),
        kinds().into_iter().collect::<BTreeSet<_>>(),
        "{FIXTURE} must hold one joint of every kind"
    );
    let loaded = load(&read(FIXTURE));
    assert_eq!(loaded.model.joints.len(), types.len());
}

#[test]
fn every_kind_is_drawn_or_has_nothing_to_draw() {
    let loaded = load(&read(FIXTURE));
    for (kind, joint) in fixture_types().iter().zip(&loaded.model.joints) {
        let marks = joint.constraint.sketch();
        let drawn = !NOT_DRAWN.contains(&kind.as_str());
        assert_eq!(
            !marks.is_empty(),
            drawn,
            "{kind}: a sketch ({} marks) in its core file, or a NOT_DRAWN entry here",
            marks.len()
        );
    }
}

/// The fixture in centimetres describes a mechanism 100 times smaller, so
/// each row of Φ at the placement scales by 0.01^d, d its power of length
/// (0 to 3): a length a kind leaves unconverted breaks that.
#[test]
fn every_kind_converts_its_lengths() {
    let si = load(&read(FIXTURE));
    let cm = load(&format!(
        "[model]\nunits = {{ length = \"cm\" }}\n{}",
        read(FIXTURE)
    ));
    let phi = |l: &Loaded| {
        let a = Assembly::new(&l.model);
        let q = a.initial_q(&l.model);
        let mut out = vec![0.0; a.m];
        a.phi(&l.model, &q, 0.0, &mut out);
        out
    };
    let (p_si, p_cm) = (phi(&si), phi(&cm));
    assert_eq!(p_si.len(), p_cm.len());
    let mut row = 0;
    for (kind, joint) in fixture_types().iter().zip(&si.model.joints) {
        for eq in joint.constraint.equations() {
            let (a, b) = (p_si[row], p_cm[row]);
            row += 1;
            if a.abs() < 1e-9 {
                assert!(b.abs() < 1e-9, "{kind}.{eq}: Φ {a} in m, {b} in cm");
                continue;
            }
            let d = (b / a).log(0.01);
            assert!(
                (b / a) > 0.0 && (d - d.round()).abs() < 1e-6 && (0.0..=3.0).contains(&d.round()),
                "{kind}.{eq}: Φ {a} in m but {b} in cm (not 0.01^d times)"
            );
        }
    }
}

#[test]
fn every_kind_is_documented() {
    let model_files = read("docs/model-files.md");
    let walkthrough = read("docs/adding-a-joint.md");
    for k in kinds() {
        assert!(
            model_files.contains(&format!("`{k}`")),
            "docs/model-files.md does not describe `{k}`"
        );
    }
    assert!(read("docs/index.md").contains("adding-a-joint.md"));
    // Every file the walkthrough names exists.
    let mut named = 0;
    for part in walkthrough.split('`').skip(1).step_by(2) {
        if part.starts_with("crates/") || part.starts_with("python/") || part.starts_with("docs/") {
            let path = part.split(':').next().unwrap();
            assert!(
                root().join(path).exists(),
                "{path}, named in docs/adding-a-joint.md"
            );
            named += 1;
        }
    }
    assert!(named >= 3);
}

/// The binding and the drawings work from the sketch, never from a kind.
#[test]
fn binding_and_drawings_name_no_kind() {
    let core_kinds = ["cam-follower", "flat-follower", "point-follower"];
    for file in [
        "crates/camlink-py/src/lib.rs",
        "python/camlink/viz/scene.py",
    ] {
        let text = read(file);
        for k in kinds().into_iter().chain(core_kinds) {
            assert!(
                !text.contains(&format!("\"{k}\"")),
                "{file} names the kind \"{k}\""
            );
        }
    }
}
