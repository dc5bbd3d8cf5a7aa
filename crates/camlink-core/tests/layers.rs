//! The core's modules are layered: each imports only modules of its own or
//! an earlier layer, and no set of modules imports itself in a circle.
//!
//! The import graph is derived from the sources: every `crate::<module>`
//! path in code (not in comments) of a file under `src/<module>` or
//! `src/<module>.rs` is an edge from that top-level module to `<module>`.
//! Run with `--nocapture` to print the graph.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The layers, first to last.
const LAYERS: &[&[&str]] = &[
    &[
        "math",
        "fmt_num",
        "quantity",
        "cam",
        "curve",
        "function",
        "motion",
        "newton",
        "lu_program",
    ],
    &["constraint", "force"],
    &["model"],
    &["assembly", "linsolve"],
    &["contact"],
    &["run", "setting", "limits"],
    &["design", "diagnose", "cam_limits", "cam_contact"],
    &["kinematics", "cam_mechanism"],
    &["dynamics"],
    &["machine"],
];

type Graph = BTreeMap<String, BTreeSet<String>>;

fn layer(module: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&module))
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).expect("readable source directory") {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The modules named by `crate::<name>` in one line of code, comments
/// removed.
fn crate_paths(line: &str) -> Vec<String> {
    let code = line.split("//").next().unwrap_or("");
    let mut names = Vec::new();
    let mut rest = code;
    while let Some(k) = rest.find("crate::") {
        let before = rest[..k].chars().next_back();
        rest = &rest[k + "crate::".len()..];
        // `camlink_core::…` and the like are not `crate::` paths.
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        // Paths into `{…}` groups (`crate::{a, b}`) list their modules.
        if name.is_empty() && rest.starts_with('{') {
            let group = rest[1..].split('}').next().unwrap_or("");
            for item in group.split(',') {
                let item = item.trim();
                let first: String = item
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if !first.is_empty() {
                    names.push(first);
                }
            }
        } else if !name.is_empty() {
            names.push(name);
        }
    }
    names
}

/// The import graph of the core: top-level module → modules it uses.
fn import_graph(src: &Path) -> Graph {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let mut graph = Graph::new();
    for file in files {
        let rel = file.strip_prefix(src).expect("file under src");
        let first = rel.components().next().expect("non-empty path");
        let module = first
            .as_os_str()
            .to_string_lossy()
            .trim_end_matches(".rs")
            .to_string();
        if module == "lib" {
            continue;
        }
        let text = fs::read_to_string(&file).expect("readable source file");
        let uses = graph.entry(module.clone()).or_default();
        for line in text.lines() {
            let trimmed = line.trim_start();
            if trimmed.starts_with("//") {
                continue;
            }
            for name in crate_paths(line) {
                if name != module {
                    uses.insert(name);
                }
            }
        }
    }
    graph
}

/// A cycle of the graph, if it has one.
fn find_cycle(graph: &Graph) -> Option<Vec<String>> {
    #[derive(Clone, Copy, PartialEq)]
    enum Mark {
        New,
        Open,
        Done,
    }
    fn visit(
        node: &str,
        graph: &Graph,
        marks: &mut BTreeMap<String, Mark>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        marks.insert(node.to_string(), Mark::Open);
        path.push(node.to_string());
        for next in graph.get(node).into_iter().flatten() {
            match marks.get(next.as_str()).copied().unwrap_or(Mark::New) {
                Mark::Open => {
                    let start = path.iter().position(|n| n == next).unwrap_or(0);
                    let mut cycle = path[start..].to_vec();
                    cycle.push(next.clone());
                    return Some(cycle);
                }
                Mark::New => {
                    if let Some(c) = visit(next, graph, marks, path) {
                        return Some(c);
                    }
                }
                Mark::Done => {}
            }
        }
        path.pop();
        marks.insert(node.to_string(), Mark::Done);
        None
    }
    let mut marks = BTreeMap::new();
    for node in graph.keys() {
        if marks.get(node.as_str()).copied().unwrap_or(Mark::New) == Mark::New {
            if let Some(c) = visit(node, graph, &mut marks, &mut Vec::new()) {
                return Some(c);
            }
        }
    }
    None
}

/// Every edge that points to a later layer, and every module missing from
/// the layers.
fn violations(graph: &Graph) -> Vec<String> {
    let mut out = Vec::new();
    for (from, uses) in graph {
        let Some(lf) = layer(from) else {
            out.push(format!("module '{from}' is in no layer"));
            continue;
        };
        for to in uses {
            match layer(to) {
                None => out.push(format!("'{from}' uses '{to}', which is in no layer")),
                Some(lt) if lt > lf => out.push(format!(
                    "'{from}' (layer {}) uses '{to}' (layer {}), a later layer",
                    lf + 1,
                    lt + 1
                )),
                _ => {}
            }
        }
    }
    out
}

fn core_graph() -> Graph {
    import_graph(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"))
}

#[test]
fn the_core_imports_only_earlier_layers_without_a_cycle() {
    let graph = core_graph();
    for l in LAYERS {
        for m in *l {
            let uses: Vec<&str> = graph
                .get(*m)
                .into_iter()
                .flatten()
                .map(String::as_str)
                .collect();
            println!("{m:>10} -> {}", uses.join(", "));
        }
    }
    assert!(graph.contains_key("kinematics") && graph.contains_key("math"));
    assert_eq!(find_cycle(&graph), None, "the core has an import cycle");
    let v = violations(&graph);
    assert!(
        v.is_empty(),
        "imports against the layers:\n{}",
        v.join("\n")
    );
}

#[test]
fn the_checks_see_a_cycle_and_an_upward_import() {
    let mut graph = Graph::new();
    graph
        .entry("kinematics".into())
        .or_default()
        .insert("design".into());
    graph
        .entry("design".into())
        .or_default()
        .insert("kinematics".into());
    let cycle = find_cycle(&graph).expect("a cycle");
    assert_eq!(cycle.first(), cycle.last());
    let v = violations(&graph);
    assert_eq!(v.len(), 1, "{v:?}");
    assert!(
        v[0].contains("'design' (layer 7) uses 'kinematics'"),
        "{v:?}"
    );
}

#[test]
fn crate_paths_are_read_from_code_only() {
    assert_eq!(crate_paths("use crate::model::{Body, Model};"), ["model"]);
    assert_eq!(
        crate_paths("use crate::{run, model::Model};"),
        ["run", "model"]
    );
    assert_eq!(
        crate_paths("let j = crate::diagnose::f(x); // crate::dynamics"),
        ["diagnose"]
    );
    assert!(crate_paths("use camlink_core::kinematics;").is_empty());
}

/// The readers of curve contacts see them through `contact::ContactView`
/// only: none of them names a contact joint's kind outside its tests, so a
/// new contact joint is one file and one line in `constraints!`.
#[test]
fn contact_readers_name_no_contact_joint() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    for file in ["contact.rs", "design.rs", "dynamics/contact_force.rs"] {
        let text = fs::read_to_string(src.join(file)).expect("readable source file");
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        for kind in ["CamFollower", "FlatFollower", "PointFollower"] {
            assert!(
                !code.contains(kind),
                "{file} names {kind}: read the contact through ContactView"
            );
        }
    }
}
