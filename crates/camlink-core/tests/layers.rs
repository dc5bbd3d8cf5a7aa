//! The core's modules are layered: each imports only modules of its own or
//! an earlier layer, and no set of modules imports itself in a circle,
//! neither the top-level modules nor the submodules of one directory
//! (`dynamics::integrator`, `dynamics::unilateral`, …).
//!
//! The import graph is derived from the sources: every path in code (not
//! in comments) that starts `crate::`, `super::` or `self::`, resolved to
//! the module it names from the module of the file (or of the inline
//! `mod tests` it is in), is an edge between the two modules. Run with
//! `--nocapture` to print the graphs.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The layers, first to last.
const LAYERS: &[&[&str]] = &[
    &[
        "math",
        "fmt_num",
        "quantity",
        "names",
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

/// A module path, from the crate root: `dynamics/integrator.rs` is
/// `["dynamics", "integrator"]`, `dynamics/mod.rs` is `["dynamics"]`,
/// `lib.rs` the root `[]`.
fn module_of(rel: &Path) -> Vec<String> {
    let mut path: Vec<String> = rel
        .components()
        .map(|c| {
            c.as_os_str()
                .to_string_lossy()
                .trim_end_matches(".rs")
                .to_string()
        })
        .collect();
    if path.last().is_some_and(|l| l == "mod" || l == "lib") {
        path.pop();
    }
    path
}

/// The code of a file with comments removed, in runs of lines of one
/// module: the file's module, or an inline module (`mod tests {`) inside
/// it, which ends at the `}` of its indent (the sources are formatted by
/// rustfmt); each run with that module's path and whether it is test code
/// (inside a `#[cfg(test)]` module).
fn code_lines(text: &str, module: &[String]) -> Vec<(String, Vec<String>, bool)> {
    // The inline modules open at a line: indent, name, test code.
    let mut inline: Vec<(usize, String, bool)> = Vec::new();
    let mut out: Vec<(String, Vec<String>, bool)> = Vec::new();
    let mut cfg_test = false;
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        let indent = code.len() - code.trim_start().len();
        let trimmed = code.trim();
        if trimmed == "}" && inline.last().is_some_and(|(i, _, _)| *i == indent) {
            inline.pop();
        }
        let mut path = module.to_vec();
        path.extend(inline.iter().map(|(_, m, _)| m.clone()));
        let test = inline.iter().any(|(_, _, t)| *t);
        match out.last_mut() {
            Some((run, p, _)) if *p == path => {
                run.push('\n');
                run.push_str(code);
            }
            _ => out.push((code.to_string(), path, test)),
        }
        let head = trimmed
            .trim_start_matches("pub(crate) ")
            .trim_start_matches("pub ");
        if let Some(name) = head.strip_prefix("mod ").and_then(|r| r.strip_suffix(" {")) {
            inline.push((indent, name.trim().to_string(), cfg_test));
        }
        if !trimmed.is_empty() {
            cfg_test = trimmed == "#[cfg(test)]";
        }
    }
    out
}

/// The identifier at `b[i..]` (empty if none) and where it ends.
fn ident(b: &[u8], mut i: usize) -> (String, usize) {
    let start = i;
    while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
        i += 1;
    }
    (String::from_utf8_lossy(&b[start..i]).into_owned(), i)
}

fn skip_space(b: &[u8], mut i: usize) -> usize {
    while i < b.len() && b[i].is_ascii_whitespace() {
        i += 1;
    }
    i
}

/// The paths of a use tree at `b[i..]` (`a::b`, `a::{b, c::d}`, `{a, b}`,
/// `a::*`; `self` in a group is the path itself) and where it ends.
fn use_tree(b: &[u8], i: usize) -> (Vec<Vec<String>>, usize) {
    let i = skip_space(b, i);
    if b.get(i) == Some(&b'{') {
        let mut paths = Vec::new();
        let mut i = i + 1;
        loop {
            i = skip_space(b, i);
            match b.get(i) {
                None => return (paths, i),
                Some(b'}') => return (paths, i + 1),
                Some(b',') => i += 1,
                Some(_) => {
                    let (more, end) = use_tree(b, i);
                    if end == i {
                        // Not a use tree: the group ends here.
                        return (paths, i);
                    }
                    paths.extend(more);
                    i = end;
                }
            }
        }
    }
    let (name, end) = ident(b, i);
    if name.is_empty() || name == "self" {
        return (vec![Vec::new()], end);
    }
    if b[end..].starts_with(b"::") {
        let (rest, end) = use_tree(b, end + 2);
        let paths = rest
            .into_iter()
            .map(|r| std::iter::once(name.clone()).chain(r).collect())
            .collect();
        return (paths, end);
    }
    (vec![vec![name]], end)
}

/// The paths from the crate root named in `code` (one line or more,
/// comments removed) of module `here`: `crate::a::b`, `super::a` (from
/// the parent of `here`, once per `super`) and `self::a`, each with the
/// items that follow it (`crate::{a, b::C}` names `a` and `b::C`).
fn paths(code: &str, here: &[String]) -> Vec<Vec<String>> {
    let b = code.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        // `camlink_core::…` and the like are not paths of this crate.
        let word = i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_');
        let rest = &b[i..];
        let base = if !word {
            None
        } else if rest.starts_with(b"crate::") {
            i += "crate::".len();
            Some(Vec::new())
        } else if rest.starts_with(b"self::") {
            i += "self::".len();
            Some(here.to_vec())
        } else if rest.starts_with(b"super::") {
            let mut base = here.to_vec();
            while b[i..].starts_with(b"super::") {
                base.pop();
                i += "super::".len();
            }
            Some(base)
        } else {
            None
        };
        let Some(base) = base else {
            i += 1;
            continue;
        };
        let (tails, end) = use_tree(b, i);
        for tail in tails {
            let mut path = base.clone();
            path.extend(tail);
            out.push(path);
        }
        i = end.max(i);
    }
    out
}

/// The top-level modules named by `crate::<name>` in one line of code,
/// comments removed, each once.
fn crate_paths(line: &str) -> Vec<String> {
    let code = line.split("//").next().unwrap_or("");
    let mut names: Vec<String> = Vec::new();
    for name in paths(code, &[])
        .into_iter()
        .filter_map(|p| p.into_iter().next())
    {
        if !names.contains(&name) {
            names.push(name);
        }
    }
    names
}

/// The sources under `src`: each file's path relative to it, and its text.
fn sources(src: &Path) -> Vec<(PathBuf, String)> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    files
        .into_iter()
        .map(|f| {
            let text = fs::read_to_string(&f).expect("readable source file");
            let rel = f.strip_prefix(src).expect("file under src").to_path_buf();
            (rel, text)
        })
        .collect()
}

/// The import graph of modules at most `depth` deep: every path a file
/// names, cut to the longest module of at most `depth` segments that it
/// starts with, is an edge from the file's module, cut likewise (`depth`
/// 1: top-level module → top-level modules it uses; 2: also
/// `dynamics::integrator` → `dynamics::unilateral`), from the code of
/// test modules too when `tests`. Items of the crate root are in no
/// module.
fn module_graph(files: &[(PathBuf, String)], depth: usize, tests: bool) -> Graph {
    let modules: BTreeSet<Vec<String>> = files
        .iter()
        .flat_map(|(rel, _)| {
            let m = module_of(rel);
            (1..=m.len()).map(move |k| m[..k].to_vec())
        })
        .collect();
    let cut = |path: &[String]| -> Option<String> {
        (1..=depth.min(path.len()))
            .rev()
            .map(|k| &path[..k])
            .find(|p| modules.contains(*p))
            .map(|p| p.join("::"))
    };
    let mut graph = Graph::new();
    for (rel, text) in files {
        let module = module_of(rel);
        let Some(from) = cut(&module) else {
            continue;
        };
        let uses = graph.entry(from.clone()).or_default();
        for (code, here, test) in code_lines(text, &module) {
            if test && !tests {
                continue;
            }
            for path in paths(&code, &here) {
                if let Some(to) = cut(&path).filter(|to| *to != from) {
                    uses.insert(to);
                }
            }
        }
    }
    graph
}

/// The import graph of the core: top-level module → modules it uses.
fn import_graph(src: &Path) -> Graph {
    module_graph(&sources(src), 1, true)
}

/// The graph inside the directory module `parent` (`dynamics`): its
/// submodules and the imports between them.
fn inner_graph(graph: &Graph, parent: &str) -> Graph {
    let inside = |m: &str| m.starts_with(&format!("{parent}::"));
    graph
        .iter()
        .filter(|(from, _)| inside(from))
        .map(|(from, uses)| {
            let uses = uses.iter().filter(|to| inside(to)).cloned().collect();
            (from.clone(), uses)
        })
        .collect()
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

fn core_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn core_graph() -> Graph {
    import_graph(&core_src())
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

/// The submodules of each directory (`dynamics/`, `constraint/`, …)
/// import one another without a cycle: unilateral contact is a layer over
/// the integrator, which does not know it. (Test modules are left out:
/// the tests of one constraint use the finite-difference checks of
/// `constraint::check`, whose own tests use constraints.)
#[test]
fn the_submodules_of_each_directory_import_without_a_cycle() {
    let graph = module_graph(&sources(&core_src()), 2, false);
    let parents: BTreeSet<&str> = graph
        .keys()
        .filter_map(|m| m.split_once("::").map(|(p, _)| p))
        .collect();
    assert!(parents.contains("dynamics") && parents.contains("constraint"));
    for parent in parents {
        let inner = inner_graph(&graph, parent);
        if parent == "dynamics" {
            for (m, uses) in &inner {
                let uses: Vec<&str> = uses.iter().map(String::as_str).collect();
                println!("{m:>30} -> {}", uses.join(", "));
            }
        }
        assert_eq!(find_cycle(&inner), None, "{parent} has an import cycle");
    }
    // `super::` paths are followed.
    let unilateral = &graph["dynamics::unilateral"];
    assert!(
        unilateral.contains("dynamics::generalized_alpha"),
        "{unilateral:?}"
    );
}

/// A cycle planted between two submodules through `super::` paths, one of
/// them in a group and over two lines, is found.
#[test]
fn a_planted_cycle_of_super_paths_is_found() {
    let files = [
        ("dynamics/mod.rs", "pub mod a;\npub mod b;\n"),
        ("dynamics/a.rs", "use super::{\n    b::{self, B},\n};\n"),
        ("dynamics/b.rs", "fn f() {\n    super::a::g();\n}\n"),
        ("model.rs", "pub struct Model;\n"),
    ]
    .map(|(p, t)| (PathBuf::from(p), t.to_string()));
    let graph = module_graph(&files, 2, false);
    assert_eq!(
        graph["dynamics::a"],
        BTreeSet::from(["dynamics::b".to_string()])
    );
    let cycle = find_cycle(&inner_graph(&graph, "dynamics")).expect("a cycle");
    assert_eq!(cycle.first(), cycle.last());
    assert_eq!(cycle.len(), 3, "{cycle:?}");
    // Without the planted edge, none.
    let mut files = files;
    files[2].1 = "fn f() {}\n".into();
    assert_eq!(find_cycle(&module_graph(&files, 2, false)), None);
}

/// `super::` and `self::` resolve from the module of the file, or of the
/// inline module a line is in.
#[test]
fn super_paths_resolve_from_their_module() {
    let here = ["dynamics".to_string(), "unilateral".to_string()];
    let p = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    assert_eq!(
        paths("use super::integrator::{run, Settings};", &here),
        [
            p(&["dynamics", "integrator", "run"]),
            p(&["dynamics", "integrator", "Settings"])
        ]
    );
    assert_eq!(
        paths("super::super::math::dot(a, b)", &here),
        [p(&["math", "dot"])]
    );
    assert_eq!(
        paths("use self::x::Y;", &here),
        [p(&["dynamics", "unilateral", "x", "Y"])]
    );
    assert!(paths("let s = Self::new(); camlink_core::run::x();", &here).is_empty());
    let text = "use super::a;\n#[cfg(test)]\nmod tests {\n    use super::*;\n    use super::super::b;\n}\nuse super::c;\n";
    let runs = code_lines(text, &here);
    let tests: Vec<bool> = runs.iter().map(|r| r.2).collect();
    assert_eq!(tests, [false, true, false]);
    let found: Vec<Vec<String>> = runs.iter().flat_map(|(c, h, _)| paths(c, h)).collect();
    assert_eq!(
        found,
        [
            p(&["dynamics", "a"]),
            p(&["dynamics", "unilateral"]),
            p(&["dynamics", "b"]),
            p(&["dynamics", "c"]),
        ]
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
