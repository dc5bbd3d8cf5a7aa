//! What a machine designer sizes from one cycle at the design speed: the
//! shaking force and moment on the frame, the counterweights that balance
//! the shaking force, the flywheel that holds the speed in a band, and the
//! motor (`docs/machine.md`).
//!
//! [`analyse`] runs inverse dynamics over one turn of the input at the
//! design speed ω (the input driver's function replaced by θ₀ + ω t), then
//! sizes the flywheel ([`flywheel`]) and checks the motor ([`motor`]) from
//! the driver's effort, finds the counterweights ([`balance`]), and
//! confirms the flywheel by forward dynamics: the driver released, the
//! flywheel's inertia added to the input link and a constant motor torque
//! equal to the cycle mean T̄ applied to it (the steady motor law of the
//! flywheel formula), started at the speed that centres the band on ω.

pub mod balance;
pub mod flywheel;
pub mod motor;

use crate::constraint::relative::RelCoord;
use crate::constraint::{BodyId, Constraint, Equations};
use crate::dynamics::{integrator, inverse};
use crate::force::point::Torque;
use crate::force::Force;
use crate::function::TimeFn;
use crate::math::{cross, V2};
use crate::model::Model;
use crate::run::{AnalysisError, Kind, Settings, Table};

pub use balance::{Balance, Counterweight};
pub use motor::{Duty, Motor};

/// The `[machine]` table, evaluated. SI units.
#[derive(Clone, Debug, PartialEq)]
pub struct Spec {
    /// The driver of the input: a `revolute_angle` driver against the
    /// ground.
    pub driver: String,
    /// Design speed ω (rad/s) of the driven angle, > 0.
    pub speed: f64,
    /// Coefficient of speed fluctuation C_s = (ω_max − ω_min)/ω̄ the
    /// flywheel keeps to; `None`: no flywheel sizing.
    pub speed_band: Option<f64>,
    /// Samples per cycle.
    pub steps: usize,
    /// The point (global frame, m) the shaking moment is taken about.
    pub point: V2,
    /// Size the counterweights of a full force balance.
    pub balance: bool,
    pub motor: Option<Motor>,
}

impl Spec {
    pub const DEFAULT_STEPS: usize = 360;
}

/// One design check: a value against its limit.
#[derive(Clone, Debug, PartialEq)]
pub struct Check {
    pub name: &'static str,
    pub value: f64,
    pub limit: f64,
    /// How far inside the limit (positive) or past it (negative), in `unit`.
    pub margin: f64,
    pub unit: &'static str,
    pub ok: bool,
}

/// The shaking force and moment over the cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct Shaking {
    /// F_s (N, global frame) and M_P (N·m, about [`Spec::point`]) at each
    /// sample.
    pub fx: Vec<f64>,
    pub fy: Vec<f64>,
    pub moment: Vec<f64>,
    /// max |F_s| (N) and the input angle (rad) where it occurs.
    pub peak_force: f64,
    pub peak_at: f64,
    /// max |F_s − W| (N): the peak of the part that shakes.
    pub peak_dynamic: f64,
    /// max |M_P| (N·m).
    pub peak_moment: f64,
    /// Σ m g (N): the weight in F_s, the part that does not shake.
    pub weight: V2,
}

/// The flywheel and the forward run that checks it.
#[derive(Clone, Debug, PartialEq)]
pub struct FlywheelReport {
    /// T̄ (N·m), ΔE (J), the target C_s and I = ΔE/(C_s ω²) (kg·m²).
    pub mean_torque: f64,
    pub delta_e: f64,
    pub cs: f64,
    pub inertia: f64,
    /// Input angles (rad) of the highest and lowest speed.
    pub theta_max: f64,
    pub theta_min: f64,
    /// The forward run over two cycles: its least and greatest input
    /// speed (rad/s) and C_s = (max − min)/ω.
    pub omega_min: f64,
    pub omega_max: f64,
    pub cs_run: f64,
}

/// Everything [`analyse`] finds.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    pub speed: f64,
    /// One cycle 2π/ω (s).
    pub period: f64,
    /// Input angle θ (rad) and the input torque T (N·m, the driver's
    /// effort) at each sample, both ends of the cycle included.
    pub theta: Vec<f64>,
    pub torque: Vec<f64>,
    pub shaking: Shaking,
    pub balance: Option<Result<Balance, String>>,
    /// max |F_s − W| (N) of the balanced model (its own weight W), by the
    /// same inverse dynamics.
    pub balanced_peak_force: Option<f64>,
    pub flywheel: Option<FlywheelReport>,
    pub duty: Duty,
    pub checks: Vec<Check>,
}

impl Report {
    pub fn ok(&self) -> bool {
        self.checks.iter().all(|c| c.ok)
    }
}

fn input(e: impl Into<String>) -> AnalysisError {
    AnalysisError::new(Kind::InvalidInput, 0.0, e)
}

/// The index of the input driver and its driven body (the one not the
/// ground), checked.
fn input_driver(model: &Model, spec: &Spec) -> Result<(usize, BodyId), AnalysisError> {
    let k = model
        .joints
        .iter()
        .position(|j| j.driver && j.name == spec.driver)
        .ok_or_else(|| input(format!("machine.driver: no driver named '{}'", spec.driver)))?;
    match &model.joints[k].constraint {
        Constraint::RelativeCoord(rc)
            if rc.coord == RelCoord::Phi && (rc.body_i.is_ground() || rc.body_j.is_ground()) =>
        {
            let b = if rc.body_i.is_ground() {
                rc.body_j
            } else {
                rc.body_i
            };
            Ok((k, b))
        }
        _ => Err(input(format!(
            "machine.driver: '{}' must drive the angle of a link against the ground \
             (a revolute_angle driver of a joint to the ground)",
            spec.driver
        ))),
    }
}

/// `model` with driver `k` at θ₀ + ω t.
fn at_speed(model: &Model, k: usize, omega: f64) -> Model {
    let mut m = model.clone();
    if let Constraint::RelativeCoord(rc) = &mut m.joints[k].constraint {
        rc.f = TimeFn::Linear {
            value: rc.f.value(0.0),
            rate: omega,
        };
    }
    m
}

fn cycle(model: &Model, times: &[f64]) -> Result<Table, AnalysisError> {
    let mut table = Table::default();
    inverse::run(model, times, &Settings::default(), &[], &mut table)?;
    Ok(table)
}

fn channel(t: &Table, name: &str) -> Vec<f64> {
    t.channel(name).unwrap_or_default()
}

/// Shaking, balance, flywheel and motor of `model` at `spec`'s design speed.
pub fn analyse(model: &Model, spec: &Spec) -> Result<Report, AnalysisError> {
    let (k, crank) = input_driver(model, spec)?;
    let w = spec.speed;
    if !(w > 0.0 && w.is_finite()) {
        return Err(input("machine.speed: the design speed must be positive"));
    }
    let period = 2.0 * std::f64::consts::PI / w;
    let n = spec.steps.max(8);
    let times: Vec<f64> = (0..=n).map(|i| period * i as f64 / n as f64).collect();
    let driven = at_speed(model, k, w);
    let table = cycle(&driven, &times)?;
    let theta0 = match &driven.joints[k].constraint {
        Constraint::RelativeCoord(rc) => rc.f.value(0.0),
        _ => 0.0,
    };
    let theta: Vec<f64> = times.iter().map(|t| theta0 + w * t).collect();
    let torque = channel(&table, &format!("{}.effort", spec.driver));

    // Shaking force, and its moment moved from O to P: M_P = M_O − P × F.
    let (fx, fy) = (channel(&table, "shaking.fx"), channel(&table, "shaking.fy"));
    let moment: Vec<f64> = channel(&table, "shaking.moment")
        .iter()
        .zip(fx.iter().zip(&fy))
        .map(|(m, (x, y))| m - cross(spec.point, [*x, *y]))
        .collect();
    let peak = |x: &[f64], y: &[f64]| {
        x.iter()
            .zip(y)
            .enumerate()
            .fold((0.0f64, 0), |(p, at), (i, (a, b))| {
                let v = a.hypot(*b);
                if v > p {
                    (v, i)
                } else {
                    (p, at)
                }
            })
    };
    let (peak_force, at) = peak(&fx, &fy);
    let weight = |m: &Model| {
        let total: f64 = m.bodies.iter().skip(1).map(|b| b.mass).sum();
        [total * m.gravity[0], total * m.gravity[1]]
    };
    let dynamic = |x: &[f64], y: &[f64], w: V2| {
        let x: Vec<f64> = x.iter().map(|v| v - w[0]).collect();
        let y: Vec<f64> = y.iter().map(|v| v - w[1]).collect();
        peak(&x, &y).0
    };
    let w_model = weight(model);
    let shaking = Shaking {
        peak_force,
        peak_at: theta[at],
        peak_dynamic: dynamic(&fx, &fy, w_model),
        peak_moment: moment.iter().fold(0.0f64, |a, m| a.max(m.abs())),
        weight: w_model,
        fx,
        fy,
        moment,
    };

    // Counterweights, and the balanced model's shaking force.
    let (balance, balanced_peak_force) = if spec.balance {
        match balance::full_force_balance(model, crank) {
            Ok(b) => {
                let balanced = balance::apply(&driven, &b);
                let t = cycle(&balanced, &times)?;
                let (x, y) = (channel(&t, "shaking.fx"), channel(&t, "shaking.fy"));
                (Some(Ok(b)), Some(dynamic(&x, &y, weight(&balanced))))
            }
            Err(e) => (Some(Err(e)), None),
        }
    } else {
        (None, None)
    };

    let mut checks = Vec::new();
    let flywheel = match spec.speed_band {
        Some(cs) => Some(size_flywheel(
            model, spec, k, crank, &table, &theta, &torque, cs, period,
        )?),
        None => None,
    };
    if let Some(f) = &flywheel {
        checks.push(Check {
            name: "speed_band",
            value: f.cs_run,
            limit: f.cs,
            margin: f.cs - f.cs_run,
            unit: "",
            ok: f.cs_run <= f.cs,
        });
    }

    let speeds = vec![w; theta.len()];
    let gear = spec.motor.as_ref().map_or(1.0, |m| m.gear_ratio);
    let duty = motor::duty(gear, &theta, &speeds, &torque);
    if let Some(m) = &spec.motor {
        let wm = gear * w;
        let avail = m.available(wm).ok_or_else(|| {
            input(format!(
                "machine.motor.curve: the curve ends at {} rad/s, below the motor speed n ω = {} rad/s",
                crate::fmt_num::num(m.top_speed()),
                crate::fmt_num::num(wm)
            ))
        })?;
        checks.push(Check {
            name: "peak_torque",
            value: duty.peak_torque,
            limit: avail,
            margin: avail - duty.peak_torque,
            unit: "N·m",
            ok: duty.peak_torque <= avail,
        });
        if let Some(f) = &flywheel {
            let mean = (f.mean_torque / gear).abs();
            checks.push(Check {
                name: "mean_torque",
                value: mean,
                limit: avail,
                margin: avail - mean,
                unit: "N·m",
                ok: mean <= avail,
            });
        }
        if let Some(r) = m.rated_torque {
            checks.push(Check {
                name: "rms_torque",
                value: duty.rms_torque,
                limit: r,
                margin: r - duty.rms_torque,
                unit: "N·m",
                ok: duty.rms_torque <= r,
            });
        }
        if let Some(p) = m.rated_power {
            checks.push(Check {
                name: "peak_power",
                value: duty.peak_power,
                limit: p,
                margin: p - duty.peak_power,
                unit: "W",
                ok: duty.peak_power <= p,
            });
        }
    }
    Ok(Report {
        speed: w,
        period,
        theta,
        torque,
        shaking,
        balance,
        balanced_peak_force,
        flywheel,
        duty,
        checks,
    })
}

/// The flywheel for band `cs`, and a forward run with it.
#[allow(clippy::too_many_arguments)]
fn size_flywheel(
    model: &Model,
    spec: &Spec,
    k: usize,
    crank: BodyId,
    table: &Table,
    theta: &[f64],
    torque: &[f64],
    cs: f64,
    period: f64,
) -> Result<FlywheelReport, AnalysisError> {
    if !(cs > 0.0 && cs.is_finite()) {
        return Err(input(
            "machine.speed_band: the coefficient of speed fluctuation must be positive \
             (a band of zero needs an infinite flywheel)",
        ));
    }
    let w = spec.speed;
    let fl = flywheel::fluctuation(theta, torque);
    let inertia = flywheel::inertia(fl.delta_e, cs, w);
    // Forward run: driver released, flywheel on the input link, torque T̄.
    let mut m = model.clone();
    m.joints.remove(k);
    m.bodies[crank.0].inertia += inertia;
    m.add_force(Force::new(
        "machine_motor",
        Torque {
            body: crank,
            t: TimeFn::Const(fl.mean_torque),
        },
    ));
    // Start at the state of the design-speed run at t = 0 with the speed
    // that centres the band. The flywheel's energy is ½Iω² − E(θ) + const
    // (E(θ₀) = 0), so ½Iω₀² = ½Iω² + (E_max + E_min)/2.
    let (emax, emin) = (
        fl.energy.iter().cloned().fold(f64::MIN, f64::max),
        fl.energy.iter().cloned().fold(f64::MAX, f64::min),
    );
    let w0 = if inertia > 0.0 {
        (w * w + (emax + emin) / inertia).max(0.0).sqrt()
    } else {
        w
    };
    for (i, b) in m.bodies.iter_mut().enumerate().skip(1) {
        let name = &model.bodies[i].name;
        let at0 = |c: &str| table.channel(&format!("{name}.{c}")).map_or(0.0, |v| v[0]);
        b.q0 = [at0("x"), at0("y"), at0("phi")];
        let s = w0 / w;
        b.qd0 = [s * at0("vx"), s * at0("vy"), s * at0("omega")];
    }
    let n = theta.len() - 1;
    let times: Vec<f64> = (0..=2 * n).map(|i| period * i as f64 / n as f64).collect();
    let settings = integrator::Settings {
        step: period / n as f64,
        ..integrator::Settings::default()
    };
    let mut run = Table::default();
    integrator::run(&m, &times, &settings, &[], &mut run)?;
    let omega = channel(&run, &format!("{}.omega", model.bodies[crank.0].name));
    let sign = if crank_sign(model, k) < 0.0 {
        -1.0
    } else {
        1.0
    };
    let (mut lo, mut hi) = (f64::MAX, f64::MIN);
    for v in omega.iter().map(|v| sign * v) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    Ok(FlywheelReport {
        mean_torque: fl.mean_torque,
        delta_e: fl.delta_e,
        cs,
        inertia,
        theta_max: fl.theta_min,
        theta_min: fl.theta_max,
        omega_min: lo,
        omega_max: hi,
        cs_run: (hi - lo) / w,
    })
}

/// +1 when the driver's angle is the driven body's (ground is body i),
/// −1 when it is the ground's relative to it.
fn crank_sign(model: &Model, k: usize) -> f64 {
    match model.joints[k].constraint.bodies() {
        [i, _] if i.is_ground() => 1.0,
        _ => -1.0,
    }
}
