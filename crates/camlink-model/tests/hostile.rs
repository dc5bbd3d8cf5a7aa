//! Hostile input: every malformed model gets a clear message and never a
//! panic. The broken fixtures themselves are checked by `bad_models.rs`
//! (`tests/models/bad/expected.toml`); this file covers what needs more
//! than "fails to load with these words": inputs generated at test time,
//! models that load and then fail at check or run time
//! (`tests/models/errors/expected.toml`), the mass check dynamics calls,
//! the examples on `docs/errors.md`, and one test per fixed bug, named
//! after it.

use std::path::{Path, PathBuf};

use camlink_core::fmt_num::num;
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
        assert!(err.contains("may contain only letters, digits"), "{err}");
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
                    .map(|w| format!("warning at t = {} s: {}", num(w.time), w.message))
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

/// A fresh folder under the system's temporary folder.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("camlink-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A cam whose polar spline reads its points from `file`.
fn cam_with_file(file: &str) -> String {
    format!(
        "[[bodies]]\nname = \"cam\"\n\n[[curves]]\nname = \"p\"\nbody = \"cam\"\n\
         source = \"spline\"\nkind = \"polar\"\nfile = \"{file}\"\n"
    )
}

const CIRCLE_CSV: &str = "alpha,rho\n0,1\n1,1\n2,1\n3,1\n4,1\n5,1\n";

#[test]
fn data_files_outside_the_model_folder_are_refused() {
    // `file = "../../etc/shadow"` read any file and printed a line of it.
    let root = scratch("outside");
    let models = root.join("models");
    std::fs::create_dir_all(models.join("data")).unwrap();
    std::fs::write(root.join("secret.csv"), "root:x:0:0:secret line\n").unwrap();
    std::fs::write(models.join("data/ok.csv"), CIRCLE_CSV).unwrap();
    let secret = root.join("secret.csv").display().to_string();
    for file in ["../secret.csv", "data/../../secret.csv", secret.as_str()] {
        let model = models.join("m.toml");
        std::fs::write(&model, cam_with_file(file)).unwrap();
        let err = load_path(&model).unwrap_err().to_string();
        assert!(
            err.contains("is outside the model's folder"),
            "{file}: {err}"
        );
        assert!(!err.contains("secret line"), "{err}");
        assert!(err.contains("curves[0].file"), "{err}");
        // Opting in reads it (and finds it is no points file).
        let opts = camlink_model::LoadOptions {
            allow_outside_data: true,
            ..Default::default()
        };
        let err = camlink_model::load_path_with(&model, &opts)
            .unwrap_err()
            .to_string();
        assert!(!err.contains("is outside"), "{err}");
    }
    // Inside the folder, also through `..` that stays inside.
    for file in ["data/ok.csv", "data/../data/ok.csv"] {
        let model = models.join("m.toml");
        std::fs::write(&model, cam_with_file(file)).unwrap();
        let loaded = load_path(&model).unwrap();
        assert_eq!(
            loaded.data_files,
            vec![std::fs::canonicalize(models.join("data/ok.csv")).unwrap()]
        );
    }
    std::fs::remove_dir_all(&root).unwrap();
}

#[cfg(unix)]
#[test]
fn symlinks_that_leave_the_model_folder_are_refused() {
    let root = scratch("symlink");
    let models = root.join("models");
    std::fs::create_dir_all(&models).unwrap();
    std::fs::write(root.join("outside.csv"), CIRCLE_CSV).unwrap();
    std::fs::write(models.join("inside.csv"), CIRCLE_CSV).unwrap();
    std::os::unix::fs::symlink(root.join("outside.csv"), models.join("away.csv")).unwrap();
    std::os::unix::fs::symlink(models.join("inside.csv"), models.join("here.csv")).unwrap();
    std::os::unix::fs::symlink(&root, models.join("up")).unwrap();
    let model = models.join("m.toml");
    for (file, ok) in [
        ("away.csv", false),
        ("up/outside.csv", false),
        ("here.csv", true),
    ] {
        std::fs::write(&model, cam_with_file(file)).unwrap();
        let got = load_path(&model);
        assert_eq!(got.is_ok(), ok, "{file}: {:?}", got.err());
    }
    std::fs::remove_dir_all(&root).unwrap();
}

#[test]
fn load_str_resolves_data_files_against_base_dir() {
    let dir = scratch("base-dir");
    std::fs::write(dir.join("cam.csv"), CIRCLE_CSV).unwrap();
    let opts = camlink_model::LoadOptions {
        base_dir: Some(dir.clone()),
        ..Default::default()
    };
    let text = cam_with_file("cam.csv");
    assert!(camlink_model::load_str_with(&text, Format::Toml, "<string>", &opts).is_ok());
    let err = load_toml(&text).unwrap_err();
    assert!(err.contains("cam.csv"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[cfg(unix)]
#[test]
fn data_file_that_is_a_device_or_fifo_is_refused_at_once() {
    // `file = "/dev/zero"` ate memory; a FIFO blocked for ever.
    let dir = scratch("device");
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.csv")).unwrap();
    let fifo = dir.join("fifo.csv");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    let opts = camlink_model::LoadOptions {
        allow_outside_data: true,
        ..Default::default()
    };
    let model = dir.join("m.toml");
    let mut names = vec!["zero.csv"];
    if made.map(|s| s.success()).unwrap_or(false) {
        names.push("fifo.csv");
    }
    for name in names {
        std::fs::write(&model, cam_with_file(name)).unwrap();
        // Refused from its metadata: a FIFO opened for reading would block.
        let err = camlink_model::load_path_with(&model, &opts)
            .unwrap_err()
            .to_string();
        assert!(err.contains("not a regular file"), "{name}: {err}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn names_that_break_outputs_are_refused() {
    // `arm,x` gave a CSV whose header did not match its rows; `=cmd` is a
    // spreadsheet formula; U+202E reversed the displayed text.
    for name in [
        "arm,x",
        "=cmd",
        "+1",
        "@a",
        "-x",
        "a\"b",
        "a b",
        "a\u{202e}b",
        "a;b",
    ] {
        let json = format!(
            r#"{{"bodies": [{{"name": {}}}]}}"#,
            serde_json::to_string(name).unwrap()
        );
        let err = load_json(&json).unwrap_err();
        assert!(err.contains("bodies[0].name: body name"), "{name}: {err}");
        assert!(!err.contains('\u{202e}'), "{err}");
    }
    for name in [
        "arm",
        "arm_2",
        "bras-gauche",
        "Kurbel\u{e4}",
        "\u{3b1}1",
        "\u{8f74}",
    ] {
        let json = format!(r#"{{"bodies": [{{"name": "{name}"}}]}}"#);
        assert!(
            load_json(&json).is_ok(),
            "{name}: {:?}",
            load_json(&json).err()
        );
    }
}

#[test]
fn duplicate_output_points_are_refused() {
    // `points = ["arm.P", "arm.P"]` gave duplicate CSV columns.
    let text = format!("{ARM_TOML}\n[analysis]\npoints = [\"arm.P\", \"arm.P\"]\n").replace(
        "name = \"arm\"\n",
        "name = \"arm\"\npoints = { P = [1, 0] }\n",
    );
    let err = load_toml(&text).unwrap_err();
    assert!(
        err.contains("analysis.points[1]: 'arm.P' is listed twice"),
        "{err}"
    );
}

/// A cam body with one curve of the given TOML fields.
fn cam_curve(fields: &str) -> Result<Loaded, String> {
    load_toml(&format!(
        "[[bodies]]\nname = \"cam\"\n\n[[curves]]\nname = \"p\"\nbody = \"cam\"\n{fields}\n"
    ))
}

#[test]
fn curves_that_do_not_close_jump_or_cover_are_refused_when_built() {
    // These loaded without a word and failed mid-run with a misleading message.
    let open_ends = "source = \"expression\"\nkind = \"parametric\"\nx = \"cos(s)\"\n\
                     y = \"sin(s)\"\nrange = [0, 6]\nclosed = true";
    let err = cam_curve(open_ends).unwrap_err();
    assert!(
        err.contains("curves[0]: curve 'p': the closed curve does not close"),
        "{err}"
    );
    let jump = "source = \"expression\"\nrho = \"if(a < pi, 0.5, 0.6)\"";
    let err = cam_curve(jump).unwrap_err();
    assert!(err.contains("curve 'p': the curve jumps by 0.1"), "{err}");
    assert!(err.contains("and 3.14159 (not continuous)"), "{err}");
    let corner = "source = \"expression\"\nrho = \"1 + 0.2*abs(a - pi)\"";
    let err = cam_curve(corner).unwrap_err();
    assert!(err.contains("curve 'p': the tangent turns by"), "{err}");
    let not_periodic = "source = \"expression\"\nrho = \"1 + a/10\"";
    let err = cam_curve(not_periodic).unwrap_err();
    assert!(err.contains("does not close"), "{err}");
    // 20° of points: the spline made up the other 340°.
    let narrow = "source = \"spline\"\nkind = \"polar\"\n\
                  points = [[0, 1], [0.1, 1.01], [0.2, 1.02], [0.349, 1.0]]";
    let err = cam_curve(narrow).unwrap_err();
    assert!(
        err.contains("curves[0].points: the points leave a gap of 340"),
        "{err}"
    );
    // Smooth closed curves still load.
    for ok in [
        "source = \"expression\"\nrho = \"1 + 0.2*cos(a)\"",
        "source = \"expression\"\nkind = \"parametric\"\nx = \"cos(s)\"\ny = \"sin(s)\"\n\
         range = [0, 6.283185307179586]\nclosed = true",
    ] {
        assert!(cam_curve(ok).is_ok(), "{ok}: {:?}", cam_curve(ok).err());
    }
}
