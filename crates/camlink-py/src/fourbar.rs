//! Binding of the four-bar checks of camlink-synth that the studio shows:
//! the Grashof class and the transmission angle. Converts only.

use camlink_synth::fourbar::{FourBar, Grashof};
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
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

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(fourbar_class, m)?)?;
    m.add_function(wrap_pyfunction!(fourbar_transmission, m)?)?;
    Ok(())
}
