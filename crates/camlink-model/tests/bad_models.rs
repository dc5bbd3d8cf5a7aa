//! Every broken model in `tests/models/bad/` fails to load with the message
//! fragments listed for it in `tests/models/bad/expected.toml` (file name →
//! fragments). The CLI tests use the same table.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use camlink_model::{load_path, load_str, Format, MAX_FILE_SIZE};

fn bad_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/models/bad")
}

fn expected() -> BTreeMap<String, Vec<String>> {
    let text = std::fs::read_to_string(bad_dir().join("expected.toml")).expect("expected.toml");
    toml::from_str(&text).expect("expected.toml parses")
}

#[test]
fn every_bad_model_fails_with_its_message() {
    let table = expected();
    let mut failures = Vec::new();
    for (file, fragments) in &table {
        let path = bad_dir().join(file);
        assert!(
            path.exists(),
            "{file} is listed in expected.toml but missing"
        );
        let err = match load_path(&path) {
            Ok(_) => {
                failures.push(format!("{file}: loaded without error"));
                continue;
            }
            Err(e) => e.to_string(),
        };
        // The error names the file as given, relative paths included.
        let shown = err.replacen(&path.display().to_string(), file, 1);
        for frag in fragments {
            if !shown.contains(frag.as_str()) {
                failures.push(format!("{file}: missing {frag:?} in:\n{shown}"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn every_bad_model_is_listed() {
    let table = expected();
    for entry in std::fs::read_dir(bad_dir()).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        if name != "expected.toml" {
            assert!(
                table.contains_key(&name),
                "{name} has no entry in expected.toml"
            );
        }
    }
    assert!(table.len() >= 15);
}

#[test]
fn too_large_file() {
    let dir = std::env::temp_dir().join(format!("camlink-model-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("huge.toml");
    let f = std::fs::File::create(&path).unwrap();
    f.set_len(MAX_FILE_SIZE + 1).unwrap();
    let err = load_path(&path).unwrap_err().to_string();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(
        err.contains("huge.toml") && err.contains("too large"),
        "{err}"
    );

    let text = " ".repeat(MAX_FILE_SIZE as usize + 1);
    let err = load_str(&text, Format::Json, "big.json").unwrap_err();
    assert!(err.message.contains("too large"));
}

#[test]
fn missing_file() {
    let err = load_path(Path::new("no/such/model.toml")).unwrap_err();
    assert!(
        err.to_string()
            .starts_with("no/such/model.toml: cannot read"),
        "{err}"
    );
}

#[test]
fn error_parts_are_structured() {
    let path = bad_dir().join("unknown_body.toml");
    let err = load_path(&path).unwrap_err();
    assert_eq!(err.line, Some(16));
    assert_eq!(err.field.as_deref(), Some("joints[1].body_i"));
    assert!(err.message.contains("did you mean 'crank'"));
}

#[test]
fn issue30_did_you_mean_for_joint_types_and_keys() {
    let joint = |ty: &str, key: &str| {
        format!(
            r#"
[[bodies]]
name = "arm"

[[joints]]
type = "{ty}"
body_i = "ground"
{key} = "arm"
"#
        )
    };
    // A misspelt joint type, in TOML and in JSON.
    let e = camlink_model::load_str(
        &joint("revolut", "body_j"),
        camlink_model::Format::Toml,
        "m.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("unknown variant `revolut`"), "{e}");
    assert!(e.ends_with("(did you mean 'revolute'?)"), "{e}");
    let json = r#"{"bodies": [{"name": "arm"}], "joints": [{"type": "translationnal", "body_i": "ground", "body_j": "arm", "axis": [1, 0]}]}"#;
    let e = camlink_model::load_str(json, camlink_model::Format::Json, "m.json")
        .unwrap_err()
        .to_string();
    assert!(e.contains("(did you mean 'translational'?)"), "{e}");
    // A misspelt key of a joint.
    let e = camlink_model::load_str(
        &joint("revolute", "body_jj"),
        camlink_model::Format::Toml,
        "m.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("unknown field `body_jj`"), "{e}");
    assert!(e.ends_with("(did you mean 'body_j'?)"), "{e}");
    // Nothing close: no suggestion.
    let e = camlink_model::load_str(
        &joint("hinge", "body_j"),
        camlink_model::Format::Toml,
        "m.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(!e.contains("did you mean"), "{e}");
}

#[test]
fn issue30_did_you_mean_for_motion_laws_and_followers() {
    let cam = |follower: &str, law: &str| {
        format!(
            r#"
[[bodies]]
name = "cam"

[[curves]]
name = "lobe"
body = "cam"
source = "motion"
follower = "{follower}"
base_radius = 0.03
roller_radius = 0.01
segments = [
  {{ law = "{law}", span = "pi", lift = 0.01 }},
  {{ law = "cycloidal", span = "pi", lift = -0.01 }},
]
"#
        )
    };
    let e = camlink_model::load_str(
        &cam("translating-roler", "cycloidal"),
        camlink_model::Format::Toml,
        "m.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(e.ends_with("(did you mean 'translating-roller'?)"), "{e}");
    let e = camlink_model::load_str(
        &cam("translating-roller", "cycloidl"),
        camlink_model::Format::Toml,
        "m.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(e.ends_with("(did you mean 'cycloidal'?)"), "{e}");
}
