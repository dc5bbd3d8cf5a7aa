//! Reductions: the few numbers a study keeps of each run.
//!
//! A [`Reduction`] is declared by the user (a kind and the channel, joint,
//! bodies or time it reads) and computed by a [`Reducer`], a
//! [`Sink`] that folds each row into running values as the analysis writes
//! it, so that a study never holds a variant's full table. Nothing the user
//! writes is evaluated as code.

use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use camlink_core::fmt_num::apart;
use camlink_core::run::{Channel, Sink, Stop, Summary};
use serde::Deserialize;

/// One output of a run, as declared (`{ kind = "range", channel = "rocker.phi" }`).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Reduction {
    /// Largest |value| of a channel over the run.
    MaxAbs { channel: String },
    /// Largest value of a channel.
    Max { channel: String },
    /// Least value of a channel.
    Min { channel: String },
    /// Largest minus least value of a channel (the swing of an angle).
    Range { channel: String },
    /// The channel's value at `time` (s), linear between output times.
    At { channel: String, time: f64 },
    /// Least transmission angle (rad, 0 to π/2) between two bodies: the
    /// angle between their x axes, |φ_i − φ_j| folded into [0, π/2], so
    /// each body's frame lies along its link (coupler and rocker).
    LeastTransmissionAngle { bodies: [String; 2] },
    /// Largest `<joint>.pressure_angle` of a curve contact (rad).
    MaxPressureAngle { joint: String },
    /// Largest |`<driver>.effort`| (N·m or N) of an inverse or forward
    /// dynamic run: the peak driver torque or force.
    PeakEffort { driver: String },
    /// Time (s) where a cam follower first leaves its cam (of `joint`, or
    /// of any contact), NaN when it stays on.
    FirstLiftOff {
        #[serde(default)]
        joint: Option<String>,
    },
}

impl Reduction {
    /// Parses a declaration from JSON text; the error names the output.
    pub fn from_json(name: &str, text: &str) -> Result<Reduction, String> {
        let r: Reduction = serde_json::from_str(text).map_err(|e| {
            let msg = e.to_string();
            let msg = msg.rfind(" at line ").map_or(msg.as_str(), |k| &msg[..k]);
            format!("output '{name}': {msg}")
        })?;
        if let Reduction::At { time, .. } = &r {
            if !time.is_finite() {
                return Err(format!(
                    "output '{name}': time must be a finite number ({})",
                    camlink_core::fmt_num::num(*time)
                ));
            }
        }
        Ok(r)
    }

    /// The channels the reduction reads.
    fn channels(&self) -> Vec<String> {
        match self {
            Reduction::MaxAbs { channel }
            | Reduction::Max { channel }
            | Reduction::Min { channel }
            | Reduction::Range { channel }
            | Reduction::At { channel, .. } => vec![channel.clone()],
            Reduction::LeastTransmissionAngle { bodies } => {
                bodies.iter().map(|b| format!("{b}.phi")).collect()
            }
            Reduction::MaxPressureAngle { joint } => vec![format!("{joint}.pressure_angle")],
            Reduction::PeakEffort { driver } => vec![format!("{driver}.effort")],
            Reduction::FirstLiftOff { .. } => Vec::new(),
        }
    }
}

/// A named reduction and its running state.
#[derive(Clone, Debug)]
struct Slot {
    name: String,
    reduction: Reduction,
    /// Column of each channel read, in the values of a row.
    columns: Vec<usize>,
    /// Running value: the extreme so far, or the interpolated value.
    value: f64,
    /// Running least value (for `range`).
    low: f64,
    /// The previous row (t, value) for `at`.
    last: Option<(f64, f64)>,
    /// Times of the first and last rows, for an `at` outside the run.
    first_t: f64,
}

/// A sink that folds each row into the declared outputs.
#[derive(Clone, Debug)]
pub struct Reducer {
    slots: Vec<Slot>,
    /// An output naming a channel the run lacks.
    missing: Option<String>,
    rows: usize,
    last_t: f64,
    /// Checked at every row and tick: the run stops once it is past.
    deadline: Option<std::time::Instant>,
    /// Checked likewise: the run stops once it is set.
    stop: Option<Arc<AtomicBool>>,
}

impl Reducer {
    /// A reducer for `outputs`; `deadline` stops a run that takes too
    /// long, `stop` one that another thread stops.
    pub fn new(
        outputs: &[(String, Reduction)],
        deadline: Option<std::time::Instant>,
        stop: Option<Arc<AtomicBool>>,
    ) -> Self {
        let slots = outputs
            .iter()
            .map(|(name, r)| Slot {
                name: name.clone(),
                reduction: r.clone(),
                columns: Vec::new(),
                value: f64::NAN,
                low: f64::NAN,
                last: None,
                first_t: f64::NAN,
            })
            .collect();
        Reducer {
            slots,
            missing: None,
            rows: 0,
            last_t: f64::NAN,
            deadline,
            stop,
        }
    }

    /// The error of an output that names a channel the run lacks.
    pub fn missing(&self) -> Option<&str> {
        self.missing.as_deref()
    }

    /// The outputs of a finished run, in declaration order, or the error
    /// of one that cannot be computed.
    pub fn finish(&self, summary: &Summary) -> Result<Vec<f64>, String> {
        if let Some(m) = &self.missing {
            return Err(m.clone());
        }
        self.slots
            .iter()
            .map(|s| match &s.reduction {
                Reduction::Range { .. } => Ok(s.value - s.low),
                Reduction::At { time, .. } => {
                    if s.value.is_nan() {
                        // Enough digits to show how the time misses the run.
                        let (t_lo, lo) = apart(*time, s.first_t);
                        let (t_hi, hi) = apart(*time, self.last_t);
                        let t = if t_lo.len() >= t_hi.len() { t_lo } else { t_hi };
                        Err(format!(
                            "output '{}': time {t} s is outside the run ({lo} to {hi} s)",
                            s.name
                        ))
                    } else {
                        Ok(s.value)
                    }
                }
                Reduction::FirstLiftOff { joint } => Ok(summary
                    .lift_off
                    .iter()
                    .filter(|l| joint.as_ref().is_none_or(|j| &l.joint == j))
                    .map(|l| l.start.time)
                    .fold(f64::NAN, f64::min)),
                _ => Ok(s.value),
            })
            .collect()
    }

    fn check_deadline(&self) -> Result<(), Stop> {
        if self
            .stop
            .as_ref()
            .is_some_and(|s| s.load(Ordering::Relaxed))
        {
            return Err(Stop("the batch was stopped".into()));
        }
        match self.deadline {
            Some(d) if std::time::Instant::now() > d => Err(Stop(
                "the variant took longer than the study's time limit".into(),
            )),
            _ => Ok(()),
        }
    }
}

/// `|φ_i − φ_j|` folded into [0, π/2] (rad).
fn transmission_angle(phi_i: f64, phi_j: f64) -> f64 {
    let d = (phi_i - phi_j).sin().atan2((phi_i - phi_j).cos()).abs();
    if d > FRAC_PI_2 {
        PI - d
    } else {
        d
    }
}

impl Sink for Reducer {
    fn begin(&mut self, channels: &[Channel]) {
        for s in &mut self.slots {
            s.columns.clear();
            for c in s.reduction.channels() {
                match channels.iter().position(|n| n.name == c) {
                    Some(k) => s.columns.push(k),
                    None => {
                        self.missing.get_or_insert_with(|| {
                            format!(
                                "output '{}': the run has no channel '{c}' (see docs/python.md for channel names)",
                                s.name
                            )
                        });
                    }
                }
            }
        }
    }

    fn row(&mut self, t: f64, values: &[f64]) -> Result<(), Stop> {
        if let Some(m) = &self.missing {
            return Err(Stop(m.clone()));
        }
        let first = self.rows == 0;
        self.rows += 1;
        self.last_t = t;
        for s in &mut self.slots {
            if first {
                s.first_t = t;
            }
            let v = |k: usize| values[s.columns[k]];
            match &s.reduction {
                Reduction::MaxAbs { .. } | Reduction::PeakEffort { .. } => {
                    s.value = if first {
                        v(0).abs()
                    } else {
                        s.value.max(v(0).abs())
                    };
                }
                Reduction::Max { .. } | Reduction::MaxPressureAngle { .. } => {
                    s.value = if first { v(0) } else { s.value.max(v(0)) };
                }
                Reduction::Min { .. } => {
                    s.value = if first { v(0) } else { s.value.min(v(0)) };
                }
                Reduction::Range { .. } => {
                    let x = v(0);
                    (s.value, s.low) = if first {
                        (x, x)
                    } else {
                        (s.value.max(x), s.low.min(x))
                    };
                }
                Reduction::At { time, .. } => {
                    let x = v(0);
                    if t == *time {
                        s.value = x;
                    } else if let Some((t0, x0)) = s.last {
                        if t0 < *time && *time < t {
                            s.value = x0 + (x - x0) * (time - t0) / (t - t0);
                        }
                    }
                    s.last = Some((t, x));
                }
                Reduction::LeastTransmissionAngle { .. } => {
                    let mu = transmission_angle(v(0), v(1));
                    s.value = if first { mu } else { s.value.min(mu) };
                }
                Reduction::FirstLiftOff { .. } => {}
            }
        }
        self.check_deadline()
    }

    fn tick(&mut self) -> Result<(), Stop> {
        self.check_deadline()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use camlink_core::quantity::Quantity;

    fn reduce(outputs: &[(&str, &str)], rows: &[(f64, [f64; 2])]) -> Result<Vec<f64>, String> {
        let outputs: Vec<(String, Reduction)> = outputs
            .iter()
            .map(|(n, j)| Ok((n.to_string(), Reduction::from_json(n, j)?)))
            .collect::<Result<_, String>>()?;
        let mut r = Reducer::new(&outputs, None, None);
        r.begin(&[
            Channel::new("a.phi", Quantity::Angle),
            Channel::new("b.phi", Quantity::Angle),
        ]);
        for (t, v) in rows {
            r.row(*t, v).map_err(|s| s.0)?;
        }
        r.finish(&Summary::default())
    }

    const ROWS: [(f64, [f64; 2]); 3] = [(0.0, [1.0, 0.0]), (0.5, [-3.0, 2.0]), (1.0, [2.0, 0.5])];

    #[test]
    fn extremes_range_and_interpolated_value() {
        let out = reduce(
            &[
                ("m", r#"{"kind": "max_abs", "channel": "a.phi"}"#),
                ("hi", r#"{"kind": "max", "channel": "a.phi"}"#),
                ("lo", r#"{"kind": "min", "channel": "a.phi"}"#),
                ("r", r#"{"kind": "range", "channel": "b.phi"}"#),
                ("at", r#"{"kind": "at", "channel": "a.phi", "time": 0.75}"#),
                ("at0", r#"{"kind": "at", "channel": "b.phi", "time": 0}"#),
                ("lift", r#"{"kind": "first_lift_off"}"#),
            ],
            &ROWS,
        )
        .unwrap();
        assert_eq!(out[..6], [3.0, 2.0, -3.0, 2.0, -0.5, 0.0]);
        assert!(out[6].is_nan());
    }

    #[test]
    fn transmission_angle_folds_into_a_quarter_turn() {
        let out = reduce(
            &[(
                "mu",
                r#"{"kind": "least_transmission_angle", "bodies": ["a", "b"]}"#,
            )],
            &[(0.0, [2.0, 0.5]), (1.0, [0.1 + PI, 0.0])],
        )
        .unwrap();
        assert!((out[0] - 0.1).abs() < 1e-12, "{out:?}");
        assert!((transmission_angle(1.0, 0.0) - 1.0).abs() < 1e-15);
        assert!((transmission_angle(0.0, 2.0) - (PI - 2.0)).abs() < 1e-15);
        assert!((transmission_angle(7.0, 0.0) - (7.0 - 2.0 * PI)).abs() < 1e-12);
    }

    #[test]
    fn unknown_channel_kind_and_field_are_named() {
        let e = reduce(&[("s", r#"{"kind": "range", "channel": "c.phi"}"#)], &ROWS).unwrap_err();
        assert!(
            e.starts_with("output 's': the run has no channel 'c.phi'"),
            "{e}"
        );
        let e = reduce(&[("s", r#"{"kind": "rnage", "channel": "a.phi"}"#)], &ROWS).unwrap_err();
        assert!(e.starts_with("output 's': unknown variant `rnage`"), "{e}");
        let e = reduce(&[("s", r#"{"kind": "max", "chanel": "a.phi"}"#)], &ROWS).unwrap_err();
        assert!(e.contains("chanel"), "{e}");
        let e = reduce(
            &[("s", r#"{"kind": "at", "channel": "a.phi", "time": 5}"#)],
            &ROWS,
        )
        .unwrap_err();
        assert_eq!(e, "output 's': time 5 s is outside the run (0 to 1 s)");
    }

    /// Issue 27: a time outside the run is written short (1e-300, not 298
    /// digits), with the digits that tell it from the run's first time.
    #[test]
    fn issue27_time_outside_the_run_is_readable() {
        let at = |t: &str| format!(r#"{{"kind": "at", "channel": "a.phi", "time": {t}}}"#);
        let rows = [(1e-7, [1.0, 0.0]), (1.0, [2.0, 0.5])];
        let e = reduce(&[("s", &at("1e-300"))], &rows).unwrap_err();
        assert_eq!(
            e,
            "output 's': time 1e-300 s is outside the run (1e-7 to 1 s)"
        );
        let e = reduce(
            &[("s", &at("1.0000000000000001e-7"))],
            &[(1.0000000000000002e-7, [1.0, 0.0]), (1.0, [2.0, 0.5])],
        )
        .unwrap_err();
        assert_eq!(
            e,
            "output 's': time 1.0000000000000001e-7 s is outside the run \
             (1.0000000000000002e-7 to 1 s)"
        );
    }
}
