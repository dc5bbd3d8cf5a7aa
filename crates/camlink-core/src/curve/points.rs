//! Points for splines from a CSV file.
//!
//! Two columns per row, separated by a comma, a semicolon, a tab or spaces:
//! (α, ρ) in rad and m for a polar profile, (x, y) in m for a planar
//! spline. Blank lines and lines starting with `#` are skipped; the first
//! remaining line is a header when its fields are not both numbers. Any
//! other row that is not two finite numbers is an error naming the file
//! and the line.

use std::path::Path;

use super::CurveError;
use crate::math::V2;

/// Reads the points of the CSV file at `path`.
pub fn read_points_csv(path: &Path) -> Result<Vec<V2>, CurveError> {
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| CurveError::Io {
        file: name.clone(),
        message: e.to_string(),
    })?;
    parse_points_csv(&text, &name)
}

/// Parses CSV `text`; `file` names the source in errors.
pub fn parse_points_csv(text: &str, file: &str) -> Result<Vec<V2>, CurveError> {
    let mut out = Vec::new();
    let mut first = true;
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        let err = |message: String| CurveError::Csv {
            file: file.to_string(),
            line: k + 1,
            message,
        };
        let numbers: Vec<Option<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
        let header = first && numbers.iter().all(|n| n.is_none());
        first = false;
        if header {
            continue;
        }
        if fields.len() != 2 {
            return Err(err(format!(
                "expected 2 columns, found {} in '{line}'",
                fields.len()
            )));
        }
        let mut p = [0.0; 2];
        for c in 0..2 {
            match numbers[c] {
                Some(v) if v.is_finite() => p[c] = v,
                _ => {
                    return Err(err(format!(
                        "column {} is not a finite number: '{}'",
                        c + 1,
                        fields[c]
                    )))
                }
            }
        }
        out.push(p);
    }
    if out.is_empty() {
        return Err(CurveError::Io {
            file: file.to_string(),
            message: "no points in the file".into(),
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_rows_with_and_without_header() {
        let a =
            parse_points_csv("alpha,rho\n0,1.0\n1.5, 1.2\n\n# note\n3;1.1\n", "cam.csv").unwrap();
        assert_eq!(a, vec![[0.0, 1.0], [1.5, 1.2], [3.0, 1.1]]);
        let b = parse_points_csv("0 1\n2\t3\n", "p.csv").unwrap();
        assert_eq!(b, vec![[0.0, 1.0], [2.0, 3.0]]);
    }

    #[test]
    fn names_file_and_line_of_a_bad_row() {
        let e = parse_points_csv("x,y\n0,1\n1,abc\n", "slot.csv").unwrap_err();
        assert_eq!(
            e,
            CurveError::Csv {
                file: "slot.csv".into(),
                line: 3,
                message: "column 2 is not a finite number: 'abc'".into()
            }
        );
        assert_eq!(
            e.to_string(),
            "slot.csv:3: column 2 is not a finite number: 'abc'"
        );
        let e = parse_points_csv("0,1\n1,2,3\n", "slot.csv").unwrap_err();
        assert!(
            e.to_string().starts_with("slot.csv:2: expected 2 columns"),
            "{e}"
        );
        let e = parse_points_csv("0,1\nx,y\n", "slot.csv").unwrap_err();
        assert!(e.to_string().starts_with("slot.csv:2:"), "{e}");
        assert!(parse_points_csv("x,y\n", "empty.csv").is_err());
    }

    #[test]
    fn reads_a_file_and_reports_a_missing_one() {
        let dir = std::env::temp_dir().join(format!("camlink-points-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("cam.csv");
        std::fs::write(&path, "0,1\n1,1.1\n").unwrap();
        assert_eq!(read_points_csv(&path).unwrap().len(), 2);
        std::fs::remove_dir_all(&dir).unwrap();
        let e = read_points_csv(&dir.join("none.csv")).unwrap_err();
        assert!(e.to_string().contains("none.csv"), "{e}");
    }
}
