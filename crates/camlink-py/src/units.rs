//! Binding of the core's quantities and units ([`camlink_core::quantity`]):
//! the unit of a channel's quantity, in SI or in units a user asks for.
//! Converts only.

use camlink_core::quantity::{Length, Quantity, Units};
use pyo3::prelude::*;

use crate::ModelError;

/// `units` parsed ([`Units::parse`]), its error as a `ModelError`.
fn parse(units: &str) -> PyResult<Units> {
    Units::parse(units).map_err(ModelError::new_err)
}

/// The unit of `quantity` (a name such as `"velocity"`, as run results
/// give them) in `units` (`"mm,deg"`; default SI) and the factor k that
/// turns an SI value into it (value = k · SI value). Lengths and angles
/// and their rates follow `units`; forces, torques, energies … stay SI.
#[pyfunction]
#[pyo3(signature = (quantity, units = "m,rad"))]
fn quantity_unit(quantity: &str, units: &str) -> PyResult<(&'static str, f64)> {
    let q = Quantity::from_name(quantity).ok_or_else(|| {
        let known: Vec<&str> = Quantity::ALL.iter().map(|q| q.name()).collect();
        ModelError::new_err(format!(
            "unknown quantity '{quantity}' (known: {})",
            known.join(", ")
        ))
    })?;
    Ok(q.unit_in(parse(units)?))
}

/// `units` written as `"LENGTH,ANGLE"` (`"mm,deg"`), in the order the
/// core writes them; a `ModelError` naming what is accepted when they
/// are not units camlink knows.
#[pyfunction]
fn parse_units(units: &str) -> PyResult<(&'static str, &'static str)> {
    let u = parse(units)?;
    Ok((u.length.name(), u.angle.name()))
}

/// The length units camlink knows: symbol → metres in one unit.
#[pyfunction]
fn length_units() -> Vec<(&'static str, f64)> {
    Length::ALL.iter().map(|l| (l.name(), l.metres())).collect()
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(quantity_unit, m)?)?;
    m.add_function(wrap_pyfunction!(parse_units, m)?)?;
    m.add_function(wrap_pyfunction!(length_units, m)?)?;
    Ok(())
}
