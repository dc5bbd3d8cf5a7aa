//! A user force that fails stops every dynamic analysis with an error of
//! kind `force_failed` naming the force and the time; equilibrium's Newton
//! search lets its sink stop it between iterations.

use crate::mechanisms;

use std::sync::Arc;

use camlink_core::constraint::absolute::{AbsoluteCoord, Coord};
use camlink_core::dynamics::{integrator, inverse, statics};
use camlink_core::force::callback::Callback;
use camlink_core::force::{Force, ForceError};
use camlink_core::run::{Channel, Kind, Sink, Stop, Table};
use camlink_core::TimeFn;
use mechanisms::pendulum;

/// A pendulum pushed sideways by a callback that fails from `t_fail` (s) on.
fn pushed_pendulum(t_fail: f64) -> camlink_core::Model {
    let mut model = pendulum(0.5, 2.0, 0.02, 0.3, true);
    let bob = model.body_id("bob").unwrap();
    model.add_force(Force::new(
        "push",
        Callback {
            body: bob,
            f: Arc::new(move |t, _q, _qd| {
                if t >= t_fail {
                    Err(ForceError("the user function raised ValueError".into()))
                } else {
                    Ok([1.0, 0.0, 0.0])
                }
            }),
        },
    ));
    model
}

#[test]
fn forward_dynamics_stops_at_the_failing_force() {
    let model = pushed_pendulum(0.05);
    let times: Vec<f64> = (0..=10).map(|k| 0.01 * k as f64).collect();
    let mut table = Table::default();
    let settings = integrator::Settings {
        step: 1e-3,
        ..Default::default()
    };
    let err = integrator::run(&model, &times, &settings, &[], &mut table).unwrap_err();
    assert_eq!(err.kind, Kind::ForceFailed, "{err}");
    assert!(err.message.contains("force 'push'"), "{err}");
    assert!(err.message.contains("ValueError"), "{err}");
    assert!((0.05..0.052).contains(&err.time), "{err}");
    // The rows before the failure are kept.
    assert_eq!(table.t, times[..5]);
}

#[test]
fn equilibrium_stops_at_the_failing_force() {
    let model = pushed_pendulum(0.0);
    let err = statics::solve(&model, 0.0, &Default::default()).unwrap_err();
    assert_eq!(err.kind, Kind::ForceFailed, "{err}");
    assert!(err.message.contains("force 'push'"), "{err}");
}

#[test]
fn inverse_dynamics_stops_at_the_failing_force() {
    let mut model = pushed_pendulum(0.02);
    let bob = model.body_id("bob").unwrap();
    model.add_joint(
        "hold",
        AbsoluteCoord {
            body: bob,
            s: [0.0, 0.0],
            coord: Coord::Phi,
            f: TimeFn::Const(0.3),
        },
    );
    let times: Vec<f64> = (0..=5).map(|k| 0.01 * k as f64).collect();
    let mut table = Table::default();
    let err = inverse::run(&model, &times, &Default::default(), &[], &mut table).unwrap_err();
    assert_eq!(err.kind, Kind::ForceFailed, "{err}");
    assert_eq!(err.time, 0.02, "{err}");
}

/// A sink that stops the run at its `budget`-th tick.
struct Interrupt {
    ticks: usize,
    budget: usize,
}

impl Sink for Interrupt {
    fn begin(&mut self, _channels: &[Channel]) {}
    fn row(&mut self, _t: f64, _values: &[f64]) -> Result<(), Stop> {
        Ok(())
    }
    fn tick(&mut self) -> Result<(), Stop> {
        self.ticks += 1;
        if self.ticks >= self.budget {
            Err(Stop("interrupted".into()))
        } else {
            Ok(())
        }
    }
}

#[test]
fn equilibrium_newton_checks_its_sink_between_iterations() {
    // Released 1 rad from hanging, the pendulum needs two iterations or more
    let model = pendulum(0.5, 2.0, 0.02, 1.0, true);
    let settings = statics::Settings::default();
    let done = statics::solve(&model, 0.0, &settings).unwrap();
    assert!(done.iterations >= 2, "{} iterations", done.iterations);
    let mut sink = Interrupt {
        ticks: 0,
        budget: 2,
    };
    let err = statics::run(&model, 0.0, &settings, &[], &mut sink).unwrap_err();
    assert_eq!(err.kind, Kind::Stopped, "{err}");
    assert_eq!(sink.ticks, 2);
}
