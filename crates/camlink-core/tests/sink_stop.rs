//! A sink that fails stops the run with an error of kind `stopped` at the
//! time of the row it refused; the rows before it were delivered.

use crate::mechanisms;

use camlink_core::dynamics::integrator;
use camlink_core::kinematics;
use camlink_core::run::{time_grid, Channel, Kind, Settings, Sink, Stop};
use mechanisms::{pendulum, slider_crank};

/// Takes `limit` rows, then refuses.
struct Limited {
    limit: usize,
    rows: Vec<f64>,
}

impl Sink for Limited {
    fn begin(&mut self, _: &[Channel]) {}
    fn row(&mut self, t: f64, _: &[f64]) -> Result<(), Stop> {
        if self.rows.len() == self.limit {
            return Err(Stop("full".into()));
        }
        self.rows.push(t);
        Ok(())
    }
}

#[test]
fn a_refusing_sink_stops_kinematics_and_dynamics() {
    let times = time_grid(0.1, 0.01).unwrap();
    let mut sink = Limited {
        limit: 3,
        rows: Vec::new(),
    };
    let model = slider_crank(0.3, 2.0, true);
    let err = kinematics::run(&model, &times, &Settings::default(), &[], &mut sink).unwrap_err();
    assert_eq!(
        (err.kind, err.time, err.message.as_str()),
        (Kind::Stopped, times[3], "full")
    );
    assert_eq!(sink.rows, times[..3]);

    let mut sink = Limited {
        limit: 2,
        rows: Vec::new(),
    };
    let model = pendulum(0.5, 1.0, 0.1, 0.3, true);
    let err = integrator::run(&model, &times, &Default::default(), &[], &mut sink).unwrap_err();
    assert_eq!((err.kind, err.time), (Kind::Stopped, times[2]));
    assert_eq!(sink.rows, times[..2]);
}
