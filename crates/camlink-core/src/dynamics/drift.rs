//! The drift of a forward-dynamics run, folded from its rows as they are
//! written: how far the total energy wandered from its first value and how
//! far the positions and velocities left the constraints. Every writer of
//! the run (memory, a file, a study's reducer) gets the same figures in the
//! run's [`Summary`].

use crate::quantity::Channel;
use crate::run::{Drift, Sink, Stop};

/// A [`Sink`] that passes every row on to `inner` and keeps, of the
/// channels `energy.total` (J), `constraint.residual` (max |Φ|, m or rad)
/// and `constraint.velocity` (max |Φ_q q̇ − ν|, m/s or rad/s), the largest
/// |E − E(t₀)| and the largest residuals over the rows.
pub struct DriftWatch<'a> {
    inner: &'a mut dyn Sink,
    /// Column of each watched channel: energy, residual, velocity residual.
    columns: [Option<usize>; 3],
    first_energy: Option<f64>,
    drift: Drift,
    rows: usize,
}

impl<'a> DriftWatch<'a> {
    pub fn new(inner: &'a mut dyn Sink) -> DriftWatch<'a> {
        DriftWatch {
            inner,
            columns: [None; 3],
            first_energy: None,
            drift: Drift::default(),
            rows: 0,
        }
    }

    /// The drift over the rows written; `None` before the first row.
    pub fn drift(&self) -> Option<Drift> {
        (self.rows > 0).then_some(self.drift)
    }
}

impl Sink for DriftWatch<'_> {
    fn begin(&mut self, channels: &[Channel]) {
        let column = |name: &str| channels.iter().position(|c| c.name == name);
        self.columns = [
            column("energy.total"),
            column("constraint.residual"),
            column("constraint.velocity"),
        ];
        self.inner.begin(channels);
    }

    fn row(&mut self, t: f64, values: &[f64]) -> Result<(), Stop> {
        let [energy, residual, velocity] = self.columns;
        if let Some(k) = energy {
            let e0 = *self.first_energy.get_or_insert(values[k]);
            self.drift.energy = self.drift.energy.max((values[k] - e0).abs());
        }
        if let Some(k) = residual {
            self.drift.constraint = self.drift.constraint.max(values[k]);
        }
        if let Some(k) = velocity {
            self.drift.velocity = self.drift.velocity.max(values[k]);
        }
        self.rows += 1;
        self.inner.row(t, values)
    }

    fn tick(&mut self) -> Result<(), Stop> {
        self.inner.tick()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::Table;

    #[test]
    fn folds_the_watched_channels_and_passes_every_row_on() {
        let mut table = Table::default();
        let mut watch = DriftWatch::new(&mut table);
        assert_eq!(watch.drift(), None);
        let names: Vec<Channel> = [
            "a",
            "energy.total",
            "constraint.residual",
            "constraint.velocity",
        ]
        .iter()
        .map(|s| Channel::new(*s, crate::quantity::Quantity::Dimensionless))
        .collect();
        watch.begin(&names);
        watch.row(0.0, &[9.0, 2.0, 1e-12, 3e-12]).unwrap();
        watch.row(0.1, &[9.0, 2.5, 4e-12, 1e-12]).unwrap();
        watch.row(0.2, &[9.0, 1.25, 2e-12, 2e-12]).unwrap();
        let d = watch.drift().unwrap();
        assert_eq!((d.energy, d.constraint, d.velocity), (0.75, 4e-12, 3e-12));
        assert_eq!(table.t, vec![0.0, 0.1, 0.2]);
        assert_eq!(table.values.len(), 12);
    }
}
