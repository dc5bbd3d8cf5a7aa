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
//! flywheel's inertia added to the input link and the motor's torque
//! applied to it — the motor curve through the gear, a torque of state of
//! the input speed, when the file gives a motor; otherwise a constant
//! torque equal to the cycle mean T̄ (the steady motor of the flywheel
//! formula) — started at the speed that centres the band on ω.
//!
//! [`Cycle`] runs the same cycle for other mass properties: the partial
//! balance ([`balance::scaled`]) weighs the shaking force against the
//! shaking moment and the input torque's swing ([`Figures`],
//! [`Figures::objective`]).

pub mod balance;
pub mod flywheel;
pub mod motor;

use crate::constraint::relative::RelCoord;
use crate::constraint::{BodyId, Constraint, Equations};
use crate::dynamics::{integrator, inverse};
use crate::force::point::Torque;
use crate::force::state::{Channel, StateExpr, StateForce};
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
    /// The motor law of the forward run: `"curve"` (the motor's curve
    /// through its gear) or `"mean_torque"` (a constant T̄).
    pub law: &'static str,
    /// Cycles run before the one measured (the motor curve's speed settles).
    pub settle_cycles: usize,
    /// The measured cycle of the forward run: its least, greatest and mean
    /// input speed (rad/s; the mean ω̄ = (max + min)/2 of the flywheel
    /// formula) and C_s = (max − min)/ω̄.
    pub omega_min: f64,
    pub omega_max: f64,
    pub omega_mean: f64,
    pub cs_run: f64,
    /// The least and greatest torque at the motor shaft over that cycle
    /// (N·m; T/n of the input torque), with the curve law.
    pub motor_torque: Option<(f64, f64)>,
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

fn channel(t: &Table, name: &str) -> Vec<f64> {
    t.channel(name).unwrap_or_default()
}

/// max |(x, y)| and its sample.
fn peak(x: &[f64], y: &[f64]) -> (f64, usize) {
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
}

/// Σ m g (N) of the moving bodies of `m`.
fn weight(m: &Model) -> V2 {
    let total: f64 = m.bodies.iter().skip(1).map(|b| b.mass).sum();
    [total * m.gravity[0], total * m.gravity[1]]
}

/// max |F_s − W| (N) over the samples.
fn peak_dynamic(x: &[f64], y: &[f64], w: V2) -> f64 {
    let x: Vec<f64> = x.iter().map(|v| v - w[0]).collect();
    let y: Vec<f64> = y.iter().map(|v| v - w[1]).collect();
    peak(&x, &y).0
}

/// One turn of a machine's input at its design speed by inverse dynamics,
/// ready to be run again with other mass properties (the same bodies,
/// joints and driver).
#[derive(Clone, Debug)]
pub struct Cycle {
    /// The model with the input driver at θ₀ + ω t.
    pub driven: Model,
    /// The input driver's name and index, and the link it turns.
    pub driver_name: String,
    pub driver: usize,
    pub crank: BodyId,
    /// ω (rad/s) and one turn 2π/ω (s).
    pub speed: f64,
    pub period: f64,
    /// Sample times over the turn (s) and the input angle θ = θ₀ + ω t at
    /// each (rad), both ends included.
    pub times: Vec<f64>,
    pub theta: Vec<f64>,
    /// The point the shaking moment is taken about (m, global frame).
    pub point: V2,
}

/// One run of a [`Cycle`]: the input torque T (N·m, the driver's effort),
/// the shaking force F_s (N) and its moment M_P about the cycle's point
/// (N·m) at each sample.
struct CycleRun {
    table: Table,
    torque: Vec<f64>,
    fx: Vec<f64>,
    fy: Vec<f64>,
    moment: Vec<f64>,
}

/// The figures a balance trades against each other.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Figures {
    /// max |F_s − W| (N): the shaking force less the weight.
    pub force: f64,
    /// max |M_P| (N·m): the shaking moment about the cycle's point.
    pub moment: f64,
    /// max T − min T (N·m): the swing of the input torque.
    pub torque_swing: f64,
}

impl Figures {
    /// J = w_F F/F₀ + w_M M/M₀ + w_T ΔT/ΔT₀: the figures weighted, each
    /// relative to the reference's (F₀, M₀, ΔT₀: the unbalanced machine's),
    /// so that the reference scores w_F + w_M + w_T. A reference figure
    /// below 1e-12 of its unit counts as 1 (nothing to normalise by).
    pub fn objective(&self, reference: &Figures, weights: [f64; 3]) -> f64 {
        let rel = |v: f64, r: f64| if r > 1e-12 { v / r } else { v };
        weights[0] * rel(self.force, reference.force)
            + weights[1] * rel(self.moment, reference.moment)
            + weights[2] * rel(self.torque_swing, reference.torque_swing)
    }
}

impl Cycle {
    /// The cycle of `model` at `spec`'s design speed, checked.
    pub fn new(model: &Model, spec: &Spec) -> Result<Cycle, AnalysisError> {
        let (k, crank) = input_driver(model, spec)?;
        let w = spec.speed;
        if !(w > 0.0 && w.is_finite()) {
            return Err(input("machine.speed: the design speed must be positive"));
        }
        let period = 2.0 * std::f64::consts::PI / w;
        let n = spec.steps.max(8);
        let times: Vec<f64> = (0..=n).map(|i| period * i as f64 / n as f64).collect();
        let driven = at_speed(model, k, w);
        let theta0 = match &driven.joints[k].constraint {
            Constraint::RelativeCoord(rc) => rc.f.value(0.0),
            _ => 0.0,
        };
        let theta = times.iter().map(|t| theta0 + w * t).collect();
        Ok(Cycle {
            driven,
            driver_name: spec.driver.clone(),
            driver: k,
            crank,
            speed: w,
            period,
            times,
            theta,
            point: spec.point,
        })
    }

    /// Inverse dynamics of `model` (the driven model, or it with other mass
    /// properties) over the cycle. Shaking moment moved from O to P:
    /// M_P = M_O − P × F.
    fn run(&self, model: &Model) -> Result<CycleRun, AnalysisError> {
        let mut table = Table::default();
        inverse::run(model, &self.times, &Settings::default(), &[], &mut table)?;
        let torque = channel(&table, &format!("{}.effort", self.driver_name));
        let (fx, fy) = (channel(&table, "shaking.fx"), channel(&table, "shaking.fy"));
        let moment = channel(&table, "shaking.moment")
            .iter()
            .zip(fx.iter().zip(&fy))
            .map(|(m, (x, y))| m - cross(self.point, [*x, *y]))
            .collect();
        Ok(CycleRun {
            table,
            torque,
            fx,
            fy,
            moment,
        })
    }

    /// The balance figures of `model` (the driven model, or it with other
    /// mass properties) over the cycle.
    pub fn figures(&self, model: &Model) -> Result<Figures, AnalysisError> {
        let r = self.run(model)?;
        Ok(figures_of(&r, weight(model)))
    }
}

fn figures_of(r: &CycleRun, w: V2) -> Figures {
    let (lo, hi) = r
        .torque
        .iter()
        .fold((f64::MAX, f64::MIN), |(lo, hi), t| (lo.min(*t), hi.max(*t)));
    Figures {
        force: peak_dynamic(&r.fx, &r.fy, w),
        moment: r.moment.iter().fold(0.0f64, |a, m| a.max(m.abs())),
        torque_swing: hi - lo,
    }
}

/// Shaking, balance, flywheel and motor of `model` at `spec`'s design speed.
pub fn analyse(model: &Model, spec: &Spec) -> Result<Report, AnalysisError> {
    let cycle = Cycle::new(model, spec)?;
    let (w, period) = (cycle.speed, cycle.period);
    let run = cycle.run(&cycle.driven)?;
    let theta = cycle.theta.clone();
    let torque = run.torque.clone();

    let (peak_force, at) = peak(&run.fx, &run.fy);
    let w_model = weight(model);
    let shaking = Shaking {
        peak_force,
        peak_at: theta[at],
        peak_dynamic: peak_dynamic(&run.fx, &run.fy, w_model),
        peak_moment: run.moment.iter().fold(0.0f64, |a, m| a.max(m.abs())),
        weight: w_model,
        fx: run.fx.clone(),
        fy: run.fy.clone(),
        moment: run.moment.clone(),
    };

    // Counterweights, and the balanced model's shaking force.
    let (balance, balanced_peak_force) = if spec.balance {
        match balance::full_force_balance(model, cycle.crank) {
            Ok(b) => {
                let balanced = balance::apply(&cycle.driven, &b);
                let f = cycle.figures(&balanced)?;
                (Some(Ok(b)), Some(f.force))
            }
            Err(e) => (Some(Err(e)), None),
        }
    } else {
        (None, None)
    };

    let mut checks = Vec::new();
    let flywheel = match spec.speed_band {
        Some(cs) => Some(size_flywheel(model, spec, &cycle, &run.table, &torque, cs)?),
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
        // The run's mean speed within the band about the design speed.
        let half = 0.5 * f.cs * w;
        let off = f.omega_mean - w;
        checks.push(Check {
            name: "run_speed",
            value: f.omega_mean,
            limit: if off < 0.0 { w - half } else { w + half },
            margin: half - off.abs(),
            unit: "rad/s",
            ok: off.abs() <= half,
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
        match &flywheel {
            // Without a flywheel the motor drives the whole fluctuation.
            None => checks.push(Check {
                name: "peak_torque",
                value: duty.peak_torque,
                limit: avail,
                margin: avail - duty.peak_torque,
                unit: "N·m",
                ok: duty.peak_torque <= avail,
            }),
            // With one it gives the mean at the design speed; the run
            // shows the rest.
            // A mean of zero is zero to rounding (64 ε of the peak).
            Some(f) => {
                let mean = (f.mean_torque / gear).abs();
                let rounding = 64.0 * f64::EPSILON * duty.peak_torque;
                checks.push(Check {
                    name: "mean_torque",
                    value: mean,
                    limit: avail,
                    margin: avail - mean,
                    unit: "N·m",
                    ok: mean <= avail + rounding,
                });
            }
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

/// The motor's curve through its gear as a torque of state on the input
/// link: T_in = s n T_m(n s ω_link), where ω_link is the link's angular
/// speed, s = ±1 the sign of the driven angle against the link's angle,
/// and T_m linear between the curve's points and along its first and
/// last segments beyond them (past the last point a motor whose curve
/// ends at zero torque brakes).
fn motor_law(m: &Motor, link: BodyId, sign: f64) -> Result<StateForce, AnalysisError> {
    let c = &m.curve;
    let bad = || input("machine.motor.curve: give at least two points with increasing speeds");
    if c.len() < 2 {
        return Err(bad());
    }
    // The motor speed u = n s ω_link, then nested if() over the segments,
    // each written as t₀ + slope (u − w₀).
    let n = sign * m.gear_ratio;
    let u = format!("(({n:e})*w)");
    let seg = |p: &[(f64, f64)]| {
        let ((w0, t0), (w1, t1)) = (p[0], p[1]);
        let slope = (t1 - t0) / (w1 - w0);
        format!("({t0:e}) + ({slope:e})*({u} - ({w0:e}))")
    };
    let mut expr = seg(&c[c.len() - 2..]);
    for k in (0..c.len() - 2).rev() {
        expr = format!(
            "if({u} < ({:e}), {}, {expr})",
            c[k + 1].0,
            seg(&c[k..k + 2])
        );
    }
    let src = format!("({n:e})*({expr})");
    let parsed = camlink_expr::Expr::parse_inputs(&src, &["w"], &Default::default())
        .map_err(|e| input(format!("machine.motor.curve: {e}")))?;
    Ok(StateForce {
        reads: Vec::new(),
        body_i: link,
        s_i: [0.0; 2],
        body_j: BodyId::GROUND,
        s_j: [0.0; 2],
        f: [None, None],
        torque: Some(StateExpr {
            expr: std::sync::Arc::new(parsed),
            channels: vec![Channel::Body {
                slot: 0,
                c: 2,
                rate: true,
            }],
        }),
        local: false,
    })
}

/// Cycles of the forward run before the measured one: five time
/// constants τ = I_in / (n² |dT_m/dω_m|) of the motor curve at the design
/// speed (I_in the input link's inertia with the flywheel), at least one,
/// at most [`MAX_SETTLE`].
fn settle_cycles(m: Option<&Motor>, inertia: f64, w: f64, period: f64) -> usize {
    let Some(m) = m else { return 1 };
    let wm = m.gear_ratio * w;
    let h = 1e-6 * wm.max(1.0);
    let slope = match (m.available(wm - h), m.available(wm + h)) {
        (Some(a), Some(b)) => (b - a) / (2.0 * h),
        _ => 0.0,
    };
    let damping = m.gear_ratio * m.gear_ratio * slope.abs();
    if damping <= 0.0 {
        return MAX_SETTLE;
    }
    ((5.0 * inertia / damping / period).ceil() as usize).clamp(1, MAX_SETTLE)
}

/// Most cycles the flywheel's forward run settles for.
pub(crate) const MAX_SETTLE: usize = 10;

/// The flywheel for band `cs`, and a forward run with it.
fn size_flywheel(
    model: &Model,
    spec: &Spec,
    cycle: &Cycle,
    table: &Table,
    torque: &[f64],
    cs: f64,
) -> Result<FlywheelReport, AnalysisError> {
    if !(cs > 0.0 && cs.is_finite()) {
        return Err(input(
            "machine.speed_band: the coefficient of speed fluctuation must be positive \
             (a band of zero needs an infinite flywheel)",
        ));
    }
    let (w, period, k, crank) = (cycle.speed, cycle.period, cycle.driver, cycle.crank);
    let theta = &cycle.theta;
    let fl = flywheel::fluctuation(theta, torque);
    let inertia = flywheel::inertia(fl.delta_e, cs, w);
    let sign = crank_sign(model, k);
    // Forward run: driver released, flywheel on the input link, the motor.
    let mut m = model.clone();
    m.joints.remove(k);
    m.bodies[crank.0].inertia += inertia;
    let (law, motor) = match &spec.motor {
        Some(mo) => (
            "curve",
            Force::new("machine_motor", motor_law(mo, crank, sign)?),
        ),
        None => (
            "mean_torque",
            Force::new(
                "machine_motor",
                Torque {
                    body: crank,
                    t: TimeFn::Const(sign * fl.mean_torque),
                },
            ),
        ),
    };
    m.add_force(motor);
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
    let settle = settle_cycles(spec.motor.as_ref(), m.bodies[crank.0].inertia, w, period);
    let n = theta.len() - 1;
    let times: Vec<f64> = (0..=(settle + 1) * n)
        .map(|i| period * i as f64 / n as f64)
        .collect();
    let settings = integrator::Settings {
        step: period / n as f64,
        ..integrator::Settings::default()
    };
    let mut run = Table::default();
    integrator::run(&m, &times, &settings, &[], &mut run)?;
    // The last cycle: the input speed's extremes.
    let omega = channel(&run, &format!("{}.omega", model.bodies[crank.0].name));
    let last = &omega[omega.len().saturating_sub(n + 1)..];
    let speed: Vec<f64> = last.iter().map(|v| sign * v).collect();
    let (lo, hi) = speed
        .iter()
        .fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(*v), hi.max(*v)));
    let mean = 0.5 * (lo + hi);
    let motor_torque = spec.motor.as_ref().map(|mo| {
        speed.iter().fold((f64::MAX, f64::MIN), |(a, b), v| {
            let t = curve_torque(mo, mo.gear_ratio * v);
            (a.min(t), b.max(t))
        })
    });
    Ok(FlywheelReport {
        mean_torque: fl.mean_torque,
        delta_e: fl.delta_e,
        cs,
        inertia,
        theta_max: fl.theta_min,
        theta_min: fl.theta_max,
        law,
        settle_cycles: settle,
        omega_min: lo,
        omega_max: hi,
        omega_mean: mean,
        cs_run: (hi - lo) / mean,
        motor_torque,
    })
}

/// The curve's torque at motor speed `u` (rad/s), extended along its
/// first and last segments as in [`motor_law`].
fn curve_torque(m: &Motor, u: f64) -> f64 {
    let c = &m.curve;
    let k = c
        .windows(2)
        .position(|p| u < p[1].0)
        .unwrap_or(c.len().saturating_sub(2));
    let ((w0, t0), (w1, t1)) = (c[k], c[(k + 1).min(c.len() - 1)]);
    if w1 > w0 {
        t0 + (t1 - t0) / (w1 - w0) * (u - w0)
    } else {
        t0
    }
}

/// +1 when the driver's angle is the driven body's (ground is body i),
/// −1 when it is the ground's relative to it.
fn crank_sign(model: &Model, k: usize) -> f64 {
    match model.joints[k].constraint.bodies() {
        [i, _] if i.is_ground() => 1.0,
        _ => -1.0,
    }
}
