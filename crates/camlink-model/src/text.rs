//! Reading and placing text, for the readers of other formats that build
//! a [`crate::file::ModelFile`] or files of their own (the course-file
//! importer `camlink-adm`, cam design files in `camlink-cam`): a file's
//! text within [`MAX_FILE_SIZE`], the 1-based (line, column) of a byte
//! offset, the byte span of a field path in JSON text, and a serde path
//! written as errors write field paths (`joints[2].body_i`).

use std::io::Read;
use std::path::Path;

pub use crate::error::line_col;
use crate::error::LoadError;
pub use crate::locate::json_span;
use crate::{at, MAX_FILE_SIZE};

/// The text of a file, at most [`MAX_FILE_SIZE`] bytes of UTF-8; errors
/// name the file.
pub fn read_text(path: &Path) -> Result<String, LoadError> {
    let source = path.display().to_string();
    let meta = std::fs::metadata(path)
        .map_err(|e| LoadError::file(&source, format!("cannot read: {e}")))?;
    if meta.len() > MAX_FILE_SIZE {
        return Err(too_large(&source, Some(meta.len())));
    }
    // A device or a pipe reports no length: read at most one byte past the limit.
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_FILE_SIZE + 1).read_to_end(&mut bytes))
        .map_err(|e| LoadError::file(&source, format!("cannot read: {e}")))?;
    if bytes.len() as u64 > MAX_FILE_SIZE {
        return Err(too_large(&source, None));
    }
    let text = String::from_utf8(bytes).map_err(|e| {
        let valid = e.utf8_error().valid_up_to();
        let before = String::from_utf8_lossy(&e.as_bytes()[..valid]);
        at(
            &before,
            &source,
            Some(valid),
            None,
            format!("not UTF-8 text (byte {valid}); save the file as UTF-8"),
        )
    })?;
    Ok(text)
}

/// The error for a text of `len` bytes (`None`: unknown, more than the
/// limit) from `source`, longer than [`MAX_FILE_SIZE`].
pub fn too_large(source: &str, len: Option<u64>) -> LoadError {
    let size = len.map_or("more than the limit".to_string(), |n| format!("{n} bytes"));
    LoadError::file(
        source,
        format!("file is too large ({size}; the limit is {MAX_FILE_SIZE} bytes)"),
    )
}

/// Field path as written in our errors: `joints[2].body_i`.
pub fn field_path(p: &serde_path_to_error::Path) -> String {
    use serde_path_to_error::Segment;
    let mut out = String::new();
    for seg in p.iter() {
        match seg {
            Segment::Seq { index } => out.push_str(&format!("[{index}]")),
            Segment::Map { key } | Segment::Enum { variant: key } => {
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(key);
            }
            Segment::Unknown => {}
        }
    }
    out
}
