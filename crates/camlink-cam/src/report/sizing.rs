//! The sizing checks of a design report: Hertz contact stress, camshaft
//! torque and roller bearing life (`[contact]`), the return spring's coil
//! clash and surge (`[spring]`) and the follower train's vibration
//! (`[vibration]`), each at the running speed of `[dynamics]`; and the
//! figures behind them, in SI.

use std::f64::consts::TAU;

use camlink_core::cam::spring::Installed;
use camlink_core::cam::vibration::{self, Chain};
use camlink_core::cam::Cam;
use camlink_core::cam_contact::{self, BearingSpec};

use super::{analysis, train, Check, ReportError};
use crate::design::Design;
use crate::limits::RPM;
use camlink_core::fmt_num::{num, num_digits};

/// The figures behind the sizing checks (SI); `None` where the design
/// file has no such table.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sizing {
    pub contact: Option<ContactFigures>,
    pub bearing: Option<BearingFigures>,
    pub spring: Option<SpringFigures>,
    pub vibration: Option<VibrationFigures>,
}

/// Contact stress and camshaft torque over a turn at the running speed.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactFigures {
    /// Largest Hertz contact pressure p_max (Pa) and where (deg).
    pub max_pressure: f64,
    pub max_pressure_at_deg: f64,
    /// Contact half-width b (m) there (a crowned roller's ellipse
    /// semi-axis along the profile).
    pub half_width: f64,
    /// Contact modulus E* (Pa).
    pub modulus: f64,
    /// Peak camshaft torque (N·m) and where (deg), and its RMS (N·m).
    pub peak_torque: f64,
    pub peak_torque_at_deg: f64,
    pub rms_torque: f64,
}

/// A roller bearing's life at the running speed.
#[derive(Clone, Debug, PartialEq)]
pub struct BearingFigures {
    /// Equivalent (cubic-mean) load P (N).
    pub equivalent_load: f64,
    /// Roller turns per cam turn.
    pub roller_turns: f64,
    /// L10 life in roller revolutions and in cam turns.
    pub l10_revolutions: f64,
    pub l10_turns: f64,
    /// L10 life (h) at the running speed.
    pub l10_hours: f64,
}

/// The return spring as installed and its surge ratio.
#[derive(Clone, Debug, PartialEq)]
pub struct SpringFigures {
    /// Rate, preload, solid height, shortest length, clash margin, active
    /// mass, surge frequency (Hz) and index.
    pub installed: Installed,
    /// Surge frequency over the forcing frequency at the highest speed.
    pub surge_ratio: f64,
}

/// Residual vibration after one segment.
#[derive(Clone, Debug, PartialEq)]
pub struct Residual {
    pub segment: usize,
    /// Amplitude (m, or rad of an oscillating follower).
    pub amplitude: f64,
    /// Cam angle (deg) of the largest deviation.
    pub at_deg: f64,
}

/// The polydyne program's figures (m or rad).
#[derive(Clone, Debug, PartialEq)]
pub struct Polydyne {
    /// Largest departure of the follower (offset by its static
    /// deflection) from the program s.
    pub max_departure: f64,
    /// Largest correction of the cam displacement over s.
    pub max_correction: f64,
}

/// The follower train's vibration over the last turn.
#[derive(Clone, Debug, PartialEq)]
pub struct VibrationFigures {
    /// Largest |deviation| of the last mass from the program (m or rad).
    pub max_deviation: f64,
    pub residual: Vec<Residual>,
    /// Least dynamic contact force (N).
    pub min_contact: f64,
    pub polydyne: Option<Polydyne>,
}

/// Appends the limits of contact stress, bearing life, spring and
/// vibration to `out`, and returns the figures behind them; nothing
/// without `[dynamics]`.
pub(super) fn checks(
    design: &Design,
    cam: &Cam,
    out: &mut Vec<Check>,
) -> Result<Sizing, ReportError> {
    let mut info = Sizing::default();
    let Some(d) = &design.dynamics else {
        return Ok(info);
    };
    let lim = &design.limits;
    let rpm = d.speed / RPM;
    let top = d.redline.unwrap_or(d.speed) / RPM;
    let lunit = if design.oscillating() { "rad" } else { "m" };

    // Hertz contact stress, camshaft torque and the roller's bearing.
    if let Some(c) = &design.contact {
        let spec = cam_contact::ContactSpec {
            width: c.width,
            modulus: c.modulus,
            crown: c.crown,
        };
        let bearing = c.rating.map(|rating| BearingSpec {
            rating,
            exponent: c.exponent,
        });
        let s = cam_contact::stress(cam, &train(d), d.speed, &spec, bearing.as_ref())
            .map_err(analysis)?;
        let (p, at) = (s.max_pressure.value, s.max_pressure.theta);
        let limit = lim.max_contact_stress;
        let margin = limit.map(|l| (l - p) / 1e6);
        let half = num_digits(s.half_width_at_max * 1e3, 4);
        let shape = match c.crown {
            None => format!(
                "contact half-width {half} mm over {} mm",
                num_digits(c.width * 1e3, 4)
            ),
            Some(crown) => format!(
                "crowned roller (crown radius {} mm): contact ellipse semi-axis {half} mm \
                 along the profile",
                num_digits(crown * 1e3, 4)
            ),
        };
        out.push(Check::new(
            format!("Hertz contact stress at {} rpm", num(rpm)),
            p / 1e6,
            limit.map(|l| l / 1e6),
            margin,
            "MPa",
            Some(at.to_degrees()),
            margin.is_none_or(|m| m >= 0.0),
            format!("{shape}, {} on {}", c.materials.0, c.materials.1),
        ));
        let (tq, tat) = (s.peak_torque.value, s.peak_torque.theta);
        out.push(Check::new(
            format!("camshaft torque at {} rpm", num(rpm)),
            tq,
            None,
            None,
            "N·m",
            Some(tat.to_degrees()),
            true,
            format!("RMS {} N·m", num(s.rms_torque)),
        ));
        info.contact = Some(ContactFigures {
            max_pressure: p,
            max_pressure_at_deg: at.to_degrees(),
            half_width: s.half_width_at_max,
            modulus: c.modulus,
            peak_torque: tq,
            peak_torque_at_deg: tat.to_degrees(),
            rms_torque: s.rms_torque,
        });
        if let Some(b) = &s.bearing {
            let hours = b.l10_turns / (rpm * 60.0);
            let limit = lim.min_bearing_life_hours;
            let margin = limit.map(|l| hours - l);
            out.push(Check::new(
                format!("roller bearing L10 life at {} rpm", num(rpm)),
                hours,
                limit,
                margin,
                "h",
                None,
                margin.is_none_or(|m| m >= 0.0),
                format!(
                    "equivalent load {} N, {} million roller revolutions, {} roller turns per \
                     cam turn",
                    num(b.equivalent_load),
                    num(b.l10_revolutions / 1e6),
                    num_digits(b.roller_turns, 4)
                ),
            ));
            info.bearing = Some(BearingFigures {
                equivalent_load: b.equivalent_load,
                roller_turns: b.roller_turns,
                l10_revolutions: b.l10_revolutions,
                l10_turns: b.l10_turns,
                l10_hours: hours,
            });
        }
    }

    // The return spring: coil clash at the largest lift, surge.
    if let Some(sp) = &design.spring {
        let f = &sp.figures;
        let limit = lim.min_coil_clearance;
        let margin = f.clash_margin - limit.unwrap_or(0.0);
        out.push(Check::new(
            "spring coil-clash margin at the largest lift",
            f.clash_margin,
            Some(limit.unwrap_or(0.0)),
            Some(margin),
            "m",
            None,
            margin >= 0.0,
            format!(
                "shortest {} mm, solid height {} mm",
                num(f.shortest * 1e3),
                num(f.solid * 1e3)
            ),
        ));
        let ratio = f.surge / (top / 60.0);
        let need = lim.min_surge_ratio;
        out.push(Check::new(
            format!("spring surge / forcing frequency at {} rpm", num(top)),
            ratio,
            Some(need),
            Some(ratio - need),
            "",
            None,
            ratio >= need,
            format!(
                "surge {} Hz, rate {} N/m, preload {} N, active mass {} kg, index {}",
                num(f.surge),
                num(f.rate),
                num(f.preload),
                num_digits(f.mass, 4),
                num_digits(f.index, 3)
            ),
        ));
        info.spring = Some(SpringFigures {
            installed: *f,
            surge_ratio: ratio,
        });
    }

    // The follower train's vibration: dynamic contact force, residuals.
    if let Some(v) = &design.vibration {
        let chain = Chain {
            masses: v.masses.clone(),
            stiffness: v.stiffness.clone(),
            damping: v.damping.clone(),
            spring_rate: d.spring_rate,
            preload: d.preload,
        };
        let program = &cam.program;
        let r =
            vibration::simulate(program, &chain, d.speed, v.steps, v.turns).map_err(analysis)?;
        let k = arg_min(&r.contact);
        let least = r.contact.get(k).copied().unwrap_or(f64::NAN);
        let at = r.theta.get(k).copied().unwrap_or(f64::NAN);
        out.push(Check::new(
            format!(
                "least dynamic contact force at {} rpm ({}-mass train)",
                num(rpm),
                v.masses.len()
            ),
            least,
            Some(0.0),
            Some(least),
            "N",
            Some(at.to_degrees()),
            least > 0.0,
            "",
        ));
        let limit = lim.max_residual_vibration;
        let mut residual = Vec::with_capacity(r.residual.len());
        for x in &r.residual {
            let margin = limit.map(|l| l - x.amplitude);
            out.push(Check::new(
                format!("residual vibration after segment {}", x.segment),
                x.amplitude,
                limit,
                margin,
                lunit,
                Some(x.theta.to_degrees()),
                margin.is_none_or(|m| m >= 0.0),
                "",
            ));
            residual.push(Residual {
                segment: x.segment,
                amplitude: x.amplitude,
                at_deg: x.theta.to_degrees(),
            });
        }
        let mut figures = VibrationFigures {
            max_deviation: max_abs(r.deviation.iter().copied()),
            residual,
            min_contact: least,
            polydyne: None,
        };
        if v.polydyne {
            // The program corrected for the one-mass train at this speed.
            let y = vibration::polydyne(program, &chain, d.speed).map_err(analysis)?;
            let q = vibration::simulate_input(program, &y, &chain, d.speed, v.steps, v.turns)
                .map_err(analysis)?;
            let x = q.position.last().map_or(&[][..], Vec::as_slice);
            let offset = d.preload / (v.stiffness[0] + d.spring_rate);
            let s: Vec<f64> = q.theta.iter().map(|t| program.eval(t % TAU)[0]).collect();
            let departure = max_abs(x.iter().zip(&s).map(|(x, s)| x + offset - s));
            let correction = max_abs(q.input.iter().zip(&s).map(|(y, s)| y - s));
            out.push(Check::new(
                format!(
                    "polydyne program at {} rpm: follower's departure from s",
                    num(rpm)
                ),
                departure,
                None,
                None,
                lunit,
                None,
                true,
                match design.oscillating() {
                    true => format!(
                        "cam displacement corrected by up to {} rad",
                        num_digits(correction, 4)
                    ),
                    false => format!(
                        "cam displacement corrected by up to {} mm",
                        num_digits(correction * 1e3, 4)
                    ),
                },
            ));
            figures.polydyne = Some(Polydyne {
                max_departure: departure,
                max_correction: correction,
            });
        }
        info.vibration = Some(figures);
    }
    Ok(info)
}

/// Index of the least value (the first NaN if there is one: a NaN
/// figure is the one to report); 0 for an empty slice.
fn arg_min(v: &[f64]) -> usize {
    let mut best = 0;
    for (k, &x) in v.iter().enumerate() {
        if x.is_nan() {
            return k;
        }
        if x < v[best] {
            best = k;
        }
    }
    best
}

/// The largest |x| (NaN if any x is NaN: the figure is then unknown).
fn max_abs(v: impl Iterator<Item = f64>) -> f64 {
    v.fold(f64::NEG_INFINITY, |m, x| {
        if m.is_nan() || x.is_nan() {
            f64::NAN
        } else {
            m.max(x.abs())
        }
    })
}
