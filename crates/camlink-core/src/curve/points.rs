//! Points for splines from a CSV file.
//!
//! Two columns per row, separated by a comma, a semicolon, a tab or spaces:
//! (α, ρ) in rad and m for a polar profile, (x, y) in m for a planar
//! spline. Blank lines and lines starting with `#` are skipped; the first
//! remaining line is a header when its fields are not both numbers. Any
//! other row that is not two finite numbers is an error naming the file
//! and the line, quoting at most [`EXCERPT_CHARS`] characters of it,
//! escaped, so that a file that is not what it was said to be (a password
//! file, one endless line) cannot print itself into a terminal.
//!
//! Only a regular file of at most [`MAX_POINTS_FILE_SIZE`] bytes is read:
//! a device, a pipe or a directory is refused without being opened.

use std::io::Read;
use std::path::Path;

use super::CurveError;
use crate::math::V2;

/// Largest points file read (bytes), the limit of a model file.
pub const MAX_POINTS_FILE_SIZE: u64 = 16 * 1024 * 1024;

/// Most characters of a line quoted in an error.
pub(crate) const EXCERPT_CHARS: usize = 24;

/// Reads the points of the CSV file at `path`: a regular file of at most
/// [`MAX_POINTS_FILE_SIZE`] bytes of UTF-8 text.
pub fn read_points_csv(path: &Path) -> Result<Vec<V2>, CurveError> {
    let name = path.display().to_string();
    let io = |message: String| CurveError::Io {
        file: name.clone(),
        message,
    };
    // Checked before opening: opening a FIFO blocks until a writer comes.
    let meta = std::fs::metadata(path).map_err(|e| io(format!("cannot read: {e}")))?;
    if !meta.is_file() {
        return Err(io("not a regular file".into()));
    }
    if meta.len() > MAX_POINTS_FILE_SIZE {
        return Err(io(too_large(Some(meta.len()))));
    }
    // The file may grow after the check: read at most one byte past the limit.
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_POINTS_FILE_SIZE + 1).read_to_end(&mut bytes))
        .map_err(|e| io(format!("cannot read: {e}")))?;
    if bytes.len() as u64 > MAX_POINTS_FILE_SIZE {
        return Err(io(too_large(None)));
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        let valid = e.utf8_error().valid_up_to();
        let line = 1 + e.as_bytes()[..valid]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        CurveError::Csv {
            file: name.clone(),
            line,
            message: "not UTF-8 text; save the file as UTF-8".into(),
        }
    })?;
    parse_points_csv(&text, &name)
}

fn too_large(len: Option<u64>) -> String {
    let size = len.map_or("more than the limit".to_string(), |n| format!("{n} bytes"));
    format!("file is too large ({size}; the limit is {MAX_POINTS_FILE_SIZE} bytes)")
}

/// At most [`EXCERPT_CHARS`] characters of `text`, with control characters,
/// quotes and backslashes escaped and `…` marking a cut.
pub fn excerpt(text: &str) -> String {
    let mut out = String::new();
    for c in text.chars().take(EXCERPT_CHARS) {
        // escape_debug leaves bidirectional overrides as they are.
        if matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}') {
            out.extend(c.escape_unicode());
        } else {
            out.extend(c.escape_debug());
        }
    }
    if text.chars().nth(EXCERPT_CHARS).is_some() {
        out.push('…');
    }
    out
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
                "expected 2 columns, found {} in '{}'",
                fields.len(),
                excerpt(line)
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
                        excerpt(fields[c])
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

    #[test]
    fn quotes_a_short_escaped_excerpt_of_a_bad_line() {
        // A long line was quoted whole, and control characters raw.
        let long = format!("0,1\n{}\n", "x".repeat(5_000_000));
        let e = parse_points_csv(&long, "p.csv").unwrap_err().to_string();
        assert!(e.len() < 120, "{} characters", e.len());
        assert!(e.starts_with("p.csv:2: "), "{e}");
        let e = parse_points_csv("0,1\n\u{1b}[2J\u{202e}x:y:z\n", "p.csv")
            .unwrap_err()
            .to_string();
        assert!(!e.contains('\u{1b}') && !e.contains('\u{202e}'), "{e}");
        assert!(e.contains("\\u{1b}") && e.contains("\\u{202e}"), "{e}");
    }

    #[cfg(unix)]
    #[test]
    fn refuses_devices_and_pipes_without_reading_them() {
        // /dev/zero was read until memory ran out.
        let e = read_points_csv(Path::new("/dev/zero"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("not a regular file"), "{e}");
        let e = read_points_csv(Path::new("/tmp")).unwrap_err().to_string();
        assert!(e.contains("not a regular file"), "{e}");
    }

    #[test]
    fn refuses_a_file_over_the_size_limit() {
        let dir = std::env::temp_dir().join(format!("camlink-points-big-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("big.csv");
        let f = std::fs::File::create(&path).unwrap();
        f.set_len(MAX_POINTS_FILE_SIZE + 1).unwrap();
        let e = read_points_csv(&path).unwrap_err().to_string();
        std::fs::remove_dir_all(&dir).unwrap();
        assert!(e.contains("file is too large"), "{e}");
    }
}
