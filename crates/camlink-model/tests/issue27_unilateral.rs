//! Issue 27, unilateral contacts: impacts are taken at the state
//! interpolated to the contact, a flight's greatest gap includes its
//! start, `event_tol` is bounded by the rounding of t and the step, and
//! the location of an event polls the sink like the steps do.

use camlink_core::dynamics::integrator;
use camlink_core::run::{time_grid, Channel, Kind, Sink, Stop, Summary, Table};
use camlink_model::{load_str, Format, Loaded};

const G: f64 = 9.81;

/// A disc of radius 0.1 m and mass 2 kg, its lowest point `h0` (m) above
/// a line on the ground (a cam_follower contact) with restitution `e`
/// and event tolerance `tol` (s).
fn disc_over_line(h0: f64, e: f64, tol: f64) -> Loaded {
    let text = format!(
        r#"
[model]
name = "disc over a line"
gravity = [0, -{G}]

[[bodies]]
name = "disc"
position = [0.3, {y}]
mass = 2
inertia = 0.01

[[curves]]
name = "rim"
body = "disc"
source = "circle"
centre = [0, 0]
radius = 0.1

[[curves]]
name = "floor"
body = "ground"
source = "line"
from = [-2, 0]
to = [2, 0]

[[joints]]
type = "cam_follower"
name = "contact"
curve_i = "floor"
curve_j = "rim"
unilateral = true
restitution = {e}
rest_speed = 0
event_tol = {tol:e}
"#,
        y = h0 + 0.1
    );
    load_str(&text, Format::Toml, "disc.toml").unwrap_or_else(|e| panic!("{e}"))
}

fn run(
    l: &Loaded,
    t_end: f64,
    h: f64,
    sink: &mut dyn Sink,
) -> Result<Summary, camlink_core::run::AnalysisError> {
    let times = time_grid(t_end, 1e-2).unwrap();
    let settings = integrator::Settings {
        step: h,
        tol: 1e-10,
        ..integrator::Settings::default()
    };
    integrator::run(&l.model, &times, &settings, &[], sink)
}

#[test]
fn issue27_impact_times_and_speeds_are_taken_at_the_contact() {
    // Dropped from h0 = 0.5 m with e = 0.9: impact k at approach speed
    // v₀ eᵏ, v₀ = √(2 g h0), at t₀ + Σ_{i<k} 2 v₀ eⁱ⁺¹/g, t₀ = √(2 h0/g).
    // Free flight under gravity is exact in the integrator (q̈ constant),
    // so the impacts are exact but for the location of the contact.
    let (h0, e) = (0.5, 0.9);
    let l = disc_over_line(h0, e, 1e-9);
    let v0 = (2.0 * G * h0).sqrt();
    let mut t = Table::default();
    let s = run(&l, 5.5, 1e-3, &mut t).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.impacts.len() >= 10, "{}", s.impacts.len());
    let mut t_k = (2.0 * h0 / G).sqrt();
    let (mut dt, mut dv) = (0.0f64, 0.0f64);
    for (k, imp) in s.impacts.iter().take(10).enumerate() {
        let v = v0 * e.powi(k as i32);
        dt = dt.max((imp.at.time - t_k).abs());
        dv = dv.max((imp.approach - v).abs());
        t_k += 2.0 * e * v / G;
    }
    eprintln!("first 10 impacts: time within {dt:e} s, approach within {dv:e} m/s");
    assert!(dt < 1e-12, "impact times off by {dt} s");
    assert!(dv < 1e-11 * v0, "approach speeds off by {dv} m/s");
    // The first flight starts at rest at its greatest gap.
    let first = &s.flights[0];
    assert_eq!(first.start.time, 0.0);
    assert_eq!(first.greatest_gap, h0);
    assert_eq!(first.greatest_at.time, 0.0);
}

/// A sink that counts the ticks and stops at tick `stop_at`.
struct Ticks {
    ticks: usize,
    rows: usize,
    stop_at: usize,
}

impl Sink for Ticks {
    fn begin(&mut self, _: &[Channel]) {}
    fn row(&mut self, _: f64, _: &[f64]) -> Result<(), Stop> {
        self.rows += 1;
        Ok(())
    }
    fn tick(&mut self) -> Result<(), Stop> {
        self.ticks += 1;
        if self.ticks == self.stop_at {
            return Err(Stop("interrupted".into()));
        }
        Ok(())
    }
}

#[test]
fn issue27_event_location_hears_the_sink() {
    // The disc meets the line at t = √(2 · 0.5/g) = 0.319 s, in step 320
    // of 1 ms: its location bisects that step to 1e-9 s, about 20 trial
    // steps, each of which polls the sink like a step does.
    let l = disc_over_line(0.5, 0.9, 1e-9);
    let mut count = Ticks {
        ticks: 0,
        rows: 0,
        stop_at: 0,
    };
    run(&l, 0.33, 1e-3, &mut count).unwrap();
    eprintln!("{} ticks for 330 steps", count.ticks);
    assert!(count.ticks >= 330 + 19, "{} ticks", count.ticks);
    // Stopped inside the location: the run ends there, with kind Stopped.
    let mut stop = Ticks {
        ticks: 0,
        rows: 0,
        stop_at: 330,
    };
    let err = run(&l, 0.33, 1e-3, &mut stop).unwrap_err();
    assert_eq!(err.kind, Kind::Stopped);
    assert_eq!(stop.rows, 32, "the rows up to 0.31 s");
}

#[test]
fn issue27_event_tol_bounds() {
    // Below the rounding of t (16 ε max(h, t_end)) the location could not
    // end; at or above the step h it would place every event at the end
    // of its step. Both are refused, naming the joint and the bounds.
    for tol in [1e-19, 1e-3, 2e-3] {
        let l = disc_over_line(0.5, 0.9, tol);
        let mut t = Table::default();
        let err = run(&l, 0.5, 1e-3, &mut t).unwrap_err();
        assert_eq!(err.kind, Kind::InvalidInput, "{tol}: {err}");
        let text = err.to_string();
        assert!(
            text.contains("joint 'contact'") && text.contains("event_tol"),
            "{text}"
        );
        assert!(text.contains("below the time step h = 0.001 s"), "{text}");
    }
    // Just inside: accepted.
    for tol in [1e-13, 9e-4] {
        let l = disc_over_line(0.5, 0.9, tol);
        let mut t = Table::default();
        let s = run(&l, 0.5, 1e-3, &mut t).unwrap_or_else(|e| panic!("{tol}: {e}"));
        assert_eq!(s.impacts.len(), 1);
    }
}
