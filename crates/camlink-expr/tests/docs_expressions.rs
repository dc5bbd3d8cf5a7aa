//! docs/expressions.md against the implementation: every function is
//! listed with its signature, every signature listed exists, and every
//! example evaluates to the value shown.

use std::collections::{BTreeSet, HashMap};
use std::path::Path;

fn doc() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/expressions.md");
    std::fs::read_to_string(path).unwrap()
}

/// Table rows `| … |` split into trimmed cells.
fn rows(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .filter(|l| l.starts_with('|') && !l.starts_with("|---"))
        .map(|l| {
            // `\|` inside a cell is a literal bar.
            l.replace("\\|", "¦")
                .trim_matches('|')
                .split('|')
                .map(|c| c.trim().replace('¦', "|"))
                .collect()
        })
        .collect()
}

fn code(cell: &str) -> Option<&str> {
    cell.strip_prefix('`')?.strip_suffix('`')
}

#[test]
fn every_function_is_documented_and_nothing_else() {
    let text = doc();
    let documented: BTreeSet<String> = rows(&text)
        .iter()
        .filter_map(|r| code(&r[0]).map(str::to_string))
        .filter(|c| c.contains('(') && !c.starts_with("if("))
        .collect();
    let implemented: BTreeSet<String> = camlink_expr::functions().map(|(_, sig)| sig).collect();
    let missing: Vec<_> = implemented.difference(&documented).collect();
    let unknown: Vec<_> = documented.difference(&implemented).collect();
    assert!(
        missing.is_empty(),
        "not in docs/expressions.md: {missing:?}"
    );
    assert!(
        unknown.is_empty(),
        "documented but not implemented: {unknown:?}"
    );
}

#[test]
fn every_example_evaluates_to_its_value() {
    let text = doc();
    let mut checked = 0;
    for r in rows(&text) {
        let n = r.len();
        if n < 2 {
            continue;
        }
        let (Some(src), Ok(want)) = (code(&r[n - 2]), r[n - 1].parse::<f64>()) else {
            continue;
        };
        let got = camlink_expr::eval_constant(src, &HashMap::new())
            .unwrap_or_else(|e| panic!("`{src}`: {}", e.render(src)));
        assert!(
            (got - want).abs() <= 1e-15 * want.abs().max(1.0),
            "`{src}` = {got}, the page says {want}"
        );
        checked += 1;
    }
    assert!(checked >= 30, "only {checked} examples found");
}
