//! The course-file types of the joint-kind registry (`JOINT_KINDS`, issue
//! 28): the importer reads exactly those, and each becomes the kinds whose
//! registry lines list it.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use camlink_adm::{constraint_types, describe, Item};
use camlink_model::JOINT_KINDS;

/// Every `.adm` of the tests and the examples.
fn adm_files() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "adm") {
                out.push(path);
            }
        }
    }
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut out = Vec::new();
    walk(&dir.join("tests/adm"), &mut out);
    walk(&dir.join("../../examples/simengine2d"), &mut out);
    out.sort();
    out
}

/// The `type` of every joint and driver of a description.
fn kinds_in(doc: &Item) -> BTreeSet<String> {
    let Item::Table(top) = doc else {
        return BTreeSet::new();
    };
    top.iter()
        .filter(|(key, _)| key == "joints" || key == "drivers")
        .flat_map(|(_, list)| match list {
            Item::List(items) => items.as_slice(),
            _ => &[],
        })
        .filter_map(|item| match item {
            Item::Table(t) => t.iter().find(|(k, _)| k == "type"),
            _ => None,
        })
        .filter_map(|(_, v)| match v {
            Item::Str(s) => Some(s.clone()),
            _ => None,
        })
        .collect()
}

/// A course type listed in a registry line is read, and no other.
#[test]
fn the_importer_reads_the_course_types_of_the_registry() {
    let listed: BTreeSet<&str> = JOINT_KINDS
        .iter()
        .flat_map(|k| k.course_types.iter().copied())
        .collect();
    let read = constraint_types();
    assert_eq!(
        read.iter().copied().collect::<BTreeSet<_>>(),
        listed,
        "a course type listed in `joint_kinds!` needs its translation in camlink-adm's build.rs"
    );
    assert_eq!(
        read.len(),
        listed.len(),
        "a course type is read twice: {read:?}"
    );
}

/// A course file with a constraint of each listed type converts to a
/// description holding a joint or driver of every kind that lists it.
#[test]
fn every_course_type_becomes_the_kinds_that_list_it() {
    let described: Vec<(String, BTreeSet<String>)> = adm_files()
        .iter()
        .map(|path| {
            let text = std::fs::read_to_string(path).unwrap();
            let d = describe(path, None).unwrap_or_else(|e| panic!("{e}"));
            (text, kinds_in(&d.doc))
        })
        .collect();
    for entry in JOINT_KINDS {
        for course in entry.course_types {
            let used = format!("\"{course}\"");
            let files: Vec<_> = described
                .iter()
                .filter(|(text, _)| text.contains(&used))
                .collect();
            assert!(
                !files.is_empty(),
                "no course file of the tests uses {course}"
            );
            assert!(
                files.iter().any(|(_, kinds)| kinds.contains(entry.kind)),
                "no course file using {course} converts to a `{}`",
                entry.kind
            );
        }
    }
}
