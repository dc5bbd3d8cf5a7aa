//! Rows of numbers as CSV text: the shortest decimal that reads back to the
//! same double (`0.3`, not `0.29999999999999999`), written by `zmij`.

use numpy::PyReadonlyArray2;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

/// Appends the shortest text of `v` that parses back to `v` and reads as
/// a float: `-0.0` as `0.0`, whole numbers with `.0` (so that a column of
/// whole numbers is not read as integers by pandas and spreadsheets),
/// `nan`, `inf` and `-inf` as NumPy, pandas and Python read them.
pub(crate) fn push_number(out: &mut Vec<u8>, buf: &mut zmij::Buffer, v: f64) {
    if v.is_nan() {
        out.extend_from_slice(b"nan");
    } else if v.is_infinite() {
        out.extend_from_slice(if v > 0.0 { b"inf" } else { b"-inf" });
    } else if v == 0.0 {
        out.extend_from_slice(b"0.0");
    } else {
        out.extend_from_slice(buf.format_finite(v).as_bytes());
    }
}

/// The rows of a 2-D array as CSV lines (comma-separated, `\n`-ended),
/// formatted with the GIL released. The array is read in place through its
/// strides, whatever its layout: a run's column-major chunk is not copied
/// (the few rows sharing a cache line across its columns are read one
/// after another).
#[pyfunction]
pub(crate) fn csv_rows<'py>(
    py: Python<'py>,
    rows: PyReadonlyArray2<'py, f64>,
) -> PyResult<Bound<'py, PyBytes>> {
    let view = rows.as_array();
    let text = py.detach(|| {
        let mut out = Vec::with_capacity(view.len() * 20);
        let mut buf = zmij::Buffer::new();
        for row in view.rows() {
            for (k, &v) in row.iter().enumerate() {
                if k > 0 {
                    out.push(b',');
                }
                push_number(&mut out, &mut buf, v);
            }
            out.push(b'\n');
        }
        out
    });
    Ok(PyBytes::new(py, &text))
}
