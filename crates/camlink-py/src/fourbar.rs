//! Binding of the four-bar checks of camlink-synth that the studio shows:
//! the Grashof class, the transmission angle and the dead-centre and
//! toggle marks. Converts only.

use camlink_synth::fourbar::{FourBar, Grashof};
use camlink_synth::marks::{self, LoopPins, ROW};
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// The Grashof class of a four-bar of links ground d, crank a, coupler b,
/// rocker c (m): `crank-rocker`, `rocker-crank`, `double-crank`,
/// `double-rocker`, `change-point` or `triple-rocker`.
#[pyfunction]
fn fourbar_class(ground: f64, crank: f64, coupler: f64, rocker: f64) -> &'static str {
    Grashof::classify(ground, crank, coupler, rocker).name()
}

/// The transmission angle μ (rad) of a four-bar of coupler b and rocker c
/// (m) at each diagonal E = |O₄ − A| (m): cos μ = (b² + c² − E²)/(2bc);
/// NaN where it does not assemble.
#[pyfunction]
fn fourbar_transmission<'py>(
    py: Python<'py>,
    coupler: f64,
    rocker: f64,
    diagonal: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let linkage = FourBar {
        o2: [0.0, 0.0],
        o4: [0.0, 0.0],
        crank: 0.0,
        coupler,
        rocker,
    };
    let mu: Vec<f64> = diagonal
        .as_slice()?
        .iter()
        .map(|&e| linkage.transmission(e))
        .collect();
    Ok(mu.into_pyarray(py))
}

/// The dead-centre and toggle positions passed between solved rows
/// ([`marks::marks`]): `t` (s), `motion` (rows × 18: the crank's and the
/// rocker's x, y, φ, then their rates, then their accelerations), `solved`
/// (one flag a row), the ground pivots `o2`, `o4` (global, m), A on the
/// crank and B on the rocker (their frames, m). Each mark as (t (s), kind,
/// crank body's angle φ (rad), x, y (m)), in time order.
#[pyfunction]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
fn fourbar_marks(
    t: PyReadonlyArray1<'_, f64>,
    motion: PyReadonlyArray2<'_, f64>,
    solved: PyReadonlyArray1<'_, bool>,
    o2: (f64, f64),
    o4: (f64, f64),
    a_on_crank: (f64, f64),
    b_on_rocker: (f64, f64),
) -> PyResult<Vec<(f64, &'static str, f64, f64, f64)>> {
    let (t, motion, solved) = (t.as_array(), motion.as_array(), solved.as_array());
    if motion.ncols() != ROW || motion.nrows() != t.len() || solved.len() != t.len() {
        return Err(PyValueError::new_err(format!(
            "fourbar_marks: {} times, motion {}×{} (want {ROW} columns a time), {} flags",
            t.len(),
            motion.nrows(),
            motion.ncols(),
            solved.len()
        )));
    }
    let pins = LoopPins {
        o2: [o2.0, o2.1],
        o4: [o4.0, o4.1],
        a_on_crank: [a_on_crank.0, a_on_crank.1],
        b_on_rocker: [b_on_rocker.0, b_on_rocker.1],
    };
    let found = marks::marks(
        &pins,
        &t.to_vec(),
        &motion.iter().copied().collect::<Vec<f64>>(),
        &solved.to_vec(),
    );
    Ok(found
        .into_iter()
        .map(|m| (m.t, m.kind.name(), m.crank, m.at[0], m.at[1]))
        .collect())
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(fourbar_class, m)?)?;
    m.add_function(wrap_pyfunction!(fourbar_transmission, m)?)?;
    m.add_function(wrap_pyfunction!(fourbar_marks, m)?)?;
    Ok(())
}
