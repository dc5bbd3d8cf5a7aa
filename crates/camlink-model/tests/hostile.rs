//! Hostile input: every malformed model gets a clear message and never a
//! panic. The broken fixtures themselves are checked by `bad_models.rs`
//! (`tests/models/bad/expected.toml`); this file covers what needs more
//! than "fails to load with these words": inputs generated at test time,
//! models that load and then fail at check or run time
//! (`tests/models/errors/expected.toml`), the mass check dynamics calls,
//! the examples on `docs/errors.md`, and one test per fixed bug, named
//! after it.

use std::path::{Path, PathBuf};

use camlink_model::{load_path, load_str, Format, Loaded};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn load_toml(text: &str) -> Result<Loaded, String> {
    load_str(text, Format::Toml, "m.toml").map_err(|e| e.to_string())
}

fn load_json(text: &str) -> Result<Loaded, String> {
    load_str(text, Format::Json, "m.json").map_err(|e| e.to_string())
}

const ARM_TOML: &str = "[[bodies]]\nname = \"arm\"\n\n[[joints]]\ntype = \"revolute\"\nbody_i = \"ground\"\nbody_j = \"arm\"\n";
const ARM_JSON: &str = r#"{"bodies": [{"name": "arm"}], "joints": [{"type": "revolute", "body_i": "ground", "body_j": "arm"}]}"#;

#[test]
fn byte_order_mark_is_skipped() {
    // A BOM made every JSON file saved by Notepad a syntax error at 1:1.
    let json = format!("\u{feff}{ARM_JSON}");
    assert!(load_json(&json).is_ok(), "{:?}", load_json(&json).err());
    let toml = format!("\u{feff}{ARM_TOML}");
    assert!(load_toml(&toml).is_ok(), "{:?}", load_toml(&toml).err());
    // Positions after the BOM are those an editor shows.
    let err = load_json("\u{feff}{\n  \"bodies\": 3\n}").unwrap_err();
    assert!(err.starts_with("m.json:2:"), "{err}");
}

#[cfg(unix)]
#[test]
fn device_file_is_refused_without_reading_it_all() {
    // A model path that is a link to /dev/zero (length 0, endless content)
    // used to be read until memory ran out.
    let dir = std::env::temp_dir().join(format!("camlink-hostile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let link = dir.join("zero.toml");
    let _ = std::fs::remove_file(&link);
    std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
    // Read in full, /dev/zero would exhaust memory: the error proves the
    // loader stopped at the size cap.
    let err = load_path(&link).unwrap_err().to_string();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(err.contains("zero.toml: file is too large"), "{err}");
}

#[test]
fn not_utf8_error_names_the_line() {
    // The error gave only a byte offset.
    let path = root().join("tests/models/bad/not_utf8.toml");
    let err = load_path(&path).unwrap_err();
    assert_eq!((err.line, err.column), (Some(3), Some(10)), "{err}");
    assert!(err.message.contains("save the file as UTF-8"), "{err}");
}

#[test]
fn json_error_columns_are_one_based() {
    // serde_json's column 0 for an empty file showed as `m.json:1:0`.
    let err = load_json("").unwrap_err();
    assert!(err.starts_with("m.json:1:1: syntax error"), "{err}");
    let err = load_json("{\"bodies\": [\n").unwrap_err();
    assert!(!err.contains(":0:"), "{err}");
}

#[test]
fn control_characters_in_messages_are_escaped() {
    // A name with an escape sequence was printed raw, so a model file
    // could clear or retitle the terminal that showed its error.
    let json = r#"{"bodies": [{"name": "arm"}], "joints": [{"type": "revolute", "body_i": "ground", "body_j": "x\u001b]0;owned\u0007\u202e"}]}"#;
    let err = load_json(json).unwrap_err();
    assert!(
        !err.chars().any(|c| c.is_control() || c == '\u{202e}'),
        "{err:?}"
    );
    assert!(
        err.contains(r"no body named 'x\u{1b}]0;owned\u{7}\u{202e}'"),
        "{err}"
    );
    // Newlines of a multi-line message stay.
    let err = load_toml("[[bodies]]\nname = \"arm\"\nangle = \"sinn(1)\"\n").unwrap_err();
    assert!(err.contains("\n    sinn(1)\n    ^^^^"), "{err}");
}

#[test]
fn control_character_in_a_name_is_an_error() {
    // A tab or a line break in a body name went into the output channel
    // names and broke CSV headers.
    for name in ["a\tb", "a\nb", "a\u{1b}c", "a\u{0}"] {
        let json = format!(
            r#"{{"bodies": [{{"name": {}}}]}}"#,
            serde_json::to_string(name).unwrap()
        );
        let err = load_json(&json).unwrap_err();
        assert!(err.contains("bodies[0].name: body name"), "{err}");
        assert!(err.contains("may not contain control characters"), "{err}");
    }
    let err =
        load_toml("[[bodies]]\nname = \"arm\"\npoints = { \"P\\u0007\" = [0, 0] }\n").unwrap_err();
    assert!(err.contains("point name"), "{err}");
}

#[test]
fn json_duplicate_keys_are_an_error() {
    // JSON maps (parameters, points) silently kept the last of two values.
    let err =
        load_json(r#"{"parameters": {"r": 1, "r": 2}, "bodies": [{"name": "arm"}]}"#).unwrap_err();
    assert!(err.contains("parameters: duplicate key `r`"), "{err}");
    let err = load_json(r#"{"bodies": [{"name": "arm", "points": {"A": [0, 0], "A": [1, 0]}}]}"#)
        .unwrap_err();
    assert!(err.contains("bodies[0].points: duplicate key `A`"), "{err}");
    let err = load_json(
        r#"{"ground": {"points": {"O": [0, 0], "O": [0, 0]}}, "bodies": [{"name": "arm"}]}"#,
    )
    .unwrap_err();
    assert!(err.contains("duplicate key `O`"), "{err}");
    // Fields of a table were already checked by serde.
    let err = load_json(r#"{"bodies": [{"name": "arm", "name": "leg"}]}"#).unwrap_err();
    assert!(err.contains("duplicate field `name`"), "{err}");
    // TOML rejects duplicates itself.
    let err = load_toml("[parameters]\nr = 1\nr = 2\n").unwrap_err();
    assert!(err.contains("duplicate key"), "{err}");
}

#[test]
fn repeated_output_time_is_a_load_error() {
    // `times = [0, 0.5, 0.5]` loaded, then the run stopped with "times
    // must increase"; the loader now says so, at the line.
    let err =
        load_toml("[[bodies]]\nname = \"arm\"\n[analysis]\ntimes = [0, 0.5, 0.5]\n").unwrap_err();
    assert!(
        err.starts_with("m.toml:4:") && err.contains("analysis.times[2]: times must increase"),
        "{err}"
    );
}

/// A chain of `n` pendulum links, each pinned to the one before, as JSON.
fn chain_json(n: usize) -> String {
    let bodies: Vec<String> = (0..n)
        .map(|k| format!(r#"{{"name": "b{k}", "position": [{k}, 0]}}"#))
        .collect();
    let joints: Vec<String> = (0..n)
        .map(|k| {
            let prev = if k == 0 {
                "ground".to_string()
            } else {
                format!("b{}", k - 1)
            };
            format!(
                r#"{{"type": "revolute", "body_i": "{prev}", "point_i": [1, 0], "body_j": "b{k}"}}"#
            )
        })
        .collect();
    format!(
        "{{\"bodies\": [\n{}\n],\n\"joints\": [\n{}\n]}}",
        bodies.join(",\n"),
        joints.join(",\n")
    )
}

#[test]
fn hundred_thousand_bodies_load_quickly() {
    // Body names were looked up by a linear scan per joint reference:
    // quadratic in the model size (9 minutes for this file), which no test
    // run waits out. No time is asserted: the machines are shared.
    let text = chain_json(100_000);
    assert!(text.len() < camlink_model::MAX_FILE_SIZE as usize);
    let loaded = load_str(&text, Format::Json, "chain.json").unwrap();
    assert_eq!(loaded.model.bodies.len(), 100_001);
    assert_eq!(loaded.model.check_grounded(), Ok(()));
}

/// What happens to a model that loads, at `stage`: the error or warning
/// text, or a description of the diagnosis.
fn outcome(loaded: &Loaded, stage: &str) -> String {
    use camlink_core::kinematics::run;
    use camlink_core::run::{time_grid, Settings, Table};
    let a = &loaded.analysis;
    match stage {
        "run" | "warning" => {
            let times = match (&a.times, a.t_end, a.step) {
                (Some(t), _, _) => t.clone(),
                (None, Some(end), Some(step)) => time_grid(end, step).unwrap(),
                _ => vec![0.0],
            };
            let settings = Settings {
                tol: a.tol,
                max_iter: a.max_iter,
                ..Settings::default()
            };
            let mut table = Table::default();
            match run(&loaded.model, &times, &settings, &[], &mut table) {
                Err(e) => format!("error: {e}\njoints: {:?}", e.joints),
                Ok(s) => s
                    .warnings
                    .iter()
                    .map(|w| format!("warning at t = {} s: {}", w.time, w.message))
                    .collect::<Vec<_>>()
                    .join("\n"),
            }
        }
        "check" => {
            let d = camlink_core::diagnose::diagnose(&loaded.model, 0.0, a.tol);
            let mut out = format!(
                "{} coordinates, {} equations, rank {}, {} degree(s) of freedom\n",
                d.coordinates, d.equations, d.rank, d.dof
            );
            for r in &d.redundant {
                let on: Vec<String> = r
                    .depends_on
                    .iter()
                    .map(|(e, c)| format!("{c:+.3}·{e}"))
                    .collect();
                out += &format!("redundant: {} = {}\n", r.equation, on.join(" "));
            }
            for m in &d.free_motions {
                let on: Vec<String> = m.iter().map(|(c, v)| format!("{c} {v:+.2}")).collect();
                out += &format!("free motion: {}\n", on.join(", "));
            }
            out
        }
        "dynamics" => match loaded.model.check_mass_properties() {
            Ok(()) => "ok".into(),
            Err(e) => format!("error: {e}"),
        },
        other => panic!("unknown stage {other:?}"),
    }
}

#[derive(serde::Deserialize)]
struct Expect {
    stage: String,
    fragments: Vec<String>,
}

#[test]
fn every_error_model_gives_its_message() {
    let dir = root().join("tests/models/errors");
    let text = std::fs::read_to_string(dir.join("expected.toml")).unwrap();
    let table: std::collections::BTreeMap<String, Vec<Expect>> = toml::from_str(&text).unwrap();
    let mut failures = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        if name != "expected.toml" && !table.contains_key(&name) {
            failures.push(format!("{name} has no entry in expected.toml"));
        }
    }
    for (file, expects) in &table {
        let loaded = load_path(&dir.join(file)).unwrap_or_else(|e| panic!("{e}"));
        for x in expects {
            let got = outcome(&loaded, &x.stage);
            if std::env::var_os("CAMLINK_SHOW").is_some() {
                eprintln!("== {file} [{}]\n{got}", x.stage);
            }
            for frag in &x.fragments {
                if !got.contains(frag.as_str()) {
                    failures.push(format!("{file} [{}]: missing {frag:?} in:\n{got}", x.stage));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn mass_check_passes_a_model_with_masses() {
    let four_bar = load_path(&root().join("tests/models/four_bar.toml")).unwrap();
    assert_eq!(four_bar.model.check_mass_properties(), Ok(()));
    // Zero mass is fine for kinematics: the same model without masses runs.
    let err = load_toml(ARM_TOML)
        .unwrap()
        .model
        .check_mass_properties()
        .unwrap_err();
    assert!(
        err.to_string().starts_with("body 'arm': mass m (kg) is 0"),
        "{err}"
    );
}

/// The message a referenced example gives: its load error for a file under
/// `tests/models/bad/`, else what `stage` reports.
fn documented_outcome(file: &str, stage: &str) -> String {
    let path = root().join(file);
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    match load_path(&path) {
        Err(e) => e
            .to_string()
            .replacen(&path.display().to_string(), &name, 1),
        Ok(loaded) => outcome(&loaded, stage),
    }
}

#[test]
fn docs_errors_page_matches_real_output() {
    // Each `<!-- output: FILE STAGE -->` marker in docs/errors.md is
    // followed by a ```text block that must appear, line by line, in what
    // FILE really gives at STAGE ("load" for files that do not load).
    let page = std::fs::read_to_string(root().join("docs/errors.md")).unwrap();
    let lines: Vec<&str> = page.lines().collect();
    let mut checked = 0;
    let mut failures = Vec::new();
    for (k, line) in lines.iter().enumerate() {
        let Some(rest) = line.trim().strip_prefix("<!-- output:") else {
            continue;
        };
        let mut words = rest.trim_end_matches("-->").split_whitespace();
        let (file, stage) = (words.next().unwrap(), words.next().unwrap_or("load"));
        assert!(
            root().join(file).exists(),
            "docs/errors.md names missing {file}"
        );
        assert!(
            lines[k + 1].starts_with("```text"),
            "no text block after {line}"
        );
        let got = documented_outcome(file, stage);
        if std::env::var_os("CAMLINK_SHOW").is_some() {
            eprintln!("== {file} [{stage}]\n{got}");
        }
        for shown in lines[k + 2..].iter().take_while(|l| !l.starts_with("```")) {
            let shown = shown.trim_end();
            if !shown.is_empty() && shown != "..." && !got.contains(shown) {
                failures.push(format!("{file} [{stage}]: {shown:?} not in:\n{got}"));
            }
        }
        checked += 1;
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    assert!(checked >= 20, "only {checked} examples checked");
}
