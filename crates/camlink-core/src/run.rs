//! The vocabulary of a run, shared by every analysis: solver settings,
//! output points and channels, sinks that receive rows as the run goes,
//! summaries, warnings and errors.

use crate::assembly::Assembly;
use crate::constraint::Equations;
use crate::contact::Contacts;
use crate::fmt_num::num;
use crate::math::{point, point_vel, rot, rot_d, V2};
use crate::model::{BodyId, Model};
pub use crate::quantity::Channel;
use crate::quantity::{self, Quantity};

/// Solver settings.
#[derive(Clone, Debug)]
pub struct Settings {
    /// Newton stops when max |Φ| ≤ tol (m or rad).
    pub tol: f64,
    /// Newton iterations allowed per time step.
    pub max_iter: usize,
    /// Also solve Φ_q q⃛ = η for the jerk and output it ([`jerk_channels`]).
    pub jerk: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            tol: 1e-10,
            max_iter: 25,
            jerk: false,
        }
    }
}

/// A body point whose motion is output, as channels
/// `<name>.x .y .vx .vy .ax .ay`.
#[derive(Clone, Debug)]
pub struct PointOutput {
    pub body: BodyId,
    /// Channel prefix, e.g. `coupler.P`.
    pub name: String,
    /// The point in the body frame (m).
    pub s: V2,
}

impl PointOutput {
    /// The output of the point named `"body.point"` in `model`; an error
    /// says what is wrong with the name.
    pub fn named(model: &Model, full: &str) -> Result<Self, String> {
        let (body, point) = full
            .split_once('.')
            .ok_or_else(|| format!("point '{full}' should be written as 'body.point'"))?;
        let id = model
            .body_id(body)
            .ok_or_else(|| format!("point '{full}': no body named '{body}'"))?;
        let b = model.body(id);
        let s = b.point(point).ok_or_else(|| {
            let known: Vec<&str> = b.points.iter().map(|p| p.name.as_str()).collect();
            format!(
                "point '{full}': body '{body}' has no point '{point}' (it has: {})",
                if known.is_empty() {
                    "none".to_string()
                } else {
                    known.join(", ")
                }
            )
        })?;
        Ok(PointOutput {
            body: id,
            name: full.to_string(),
            s,
        })
    }
}

/// Receives results as the run goes.
pub trait Sink {
    /// Called once before the first row with the channels (not `t`): their
    /// names and quantities.
    fn begin(&mut self, channels: &[Channel]);
    /// One time step: time t (s) and the values, in channel order. An error
    /// stops the run, which returns an [`AnalysisError`] of kind
    /// [`Kind::Stopped`] at `t`.
    fn row(&mut self, t: f64, values: &[f64]) -> Result<(), Stop>;
    /// Called at every step of an analysis between two rows (each
    /// integration step of forward dynamics), so that a sink can watch the
    /// clock and stop a run whose rows are far apart in wall time.
    fn tick(&mut self) -> Result<(), Stop> {
        Ok(())
    }
}

/// Why a [`Sink`] stopped the run (its receiver failed or was interrupted).
#[derive(Clone, Debug, PartialEq)]
pub struct Stop(pub String);

impl Stop {
    /// The run's error at time `t` (s).
    pub fn at(self, t: f64) -> AnalysisError {
        AnalysisError::new(Kind::Stopped, t, self.0)
    }
}

/// A sink that keeps everything in memory, row by row.
#[derive(Clone, Debug, Default)]
pub struct Table {
    pub channels: Vec<String>,
    /// What each channel measures, in the order of `channels`.
    pub quantities: Vec<Quantity>,
    pub t: Vec<f64>,
    /// Row-major values, `channels.len()` per step.
    pub values: Vec<f64>,
}

impl Table {
    /// The series of one channel.
    pub fn channel(&self, name: &str) -> Option<Vec<f64>> {
        let k = self.channels.iter().position(|c| c == name)?;
        let w = self.channels.len();
        Some(self.values.chunks(w).map(|row| row[k]).collect())
    }
}

impl Sink for Table {
    fn begin(&mut self, channels: &[Channel]) {
        self.channels = quantity::names(channels);
        self.quantities = channels.iter().map(|c| c.quantity).collect();
    }
    fn row(&mut self, t: f64, values: &[f64]) -> Result<(), Stop> {
        self.t.push(t);
        self.values.extend_from_slice(values);
        Ok(())
    }
}

/// How a run went.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Summary {
    pub steps: usize,
    pub newton_iterations: usize,
    pub factorizations: usize,
    /// Steps retried as two half steps.
    pub halvings: usize,
    /// The warnings, in the order they arose.
    pub warnings: Vec<Warning>,
    /// How assembly moved each body from its given placement:
    /// (body, [Δx, Δy, Δφ] in m, m, rad), for bodies that moved.
    pub assembly_moves: Vec<(String, [f64; 3])>,
    /// Intervals where a cam contact's normal force is negative (the
    /// follower would leave the cam), by start time; each is also a
    /// warning. Filled by inverse and forward dynamics.
    pub lift_off: Vec<LiftOff>,
    /// The flights of the unilateral cam contacts in forward dynamics, by
    /// start time.
    pub flights: Vec<Flight>,
    /// The impacts of the unilateral cam contacts, in time order.
    pub impacts: Vec<Impact>,
    /// Forward dynamics: the drift over the rows written.
    pub drift: Option<Drift>,
}

/// How far a forward-dynamics run left what it should keep, over its rows:
/// the largest |E − E(t₀)| of the total energy (J), the largest |Φ| (m or
/// rad) and the largest |Φ_q q̇ − ν| (m/s or rad/s).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Drift {
    pub energy: f64,
    pub constraint: f64,
    pub velocity: f64,
}

/// A flight of a unilateral cam contact: from lift-off (or a bounce) to
/// the next impact.
#[derive(Clone, Debug, PartialEq)]
pub struct Flight {
    pub joint: String,
    /// The cam body's name.
    pub cam: String,
    /// The located lift-off or the bounce that starts the flight.
    pub start: Crossing,
    /// The located impact that ends it; `None` when the run ends in flight.
    pub end: Option<Crossing>,
    /// The greatest gap (m) at the step ends of the flight, and where.
    pub greatest_gap: f64,
    pub greatest_at: Crossing,
}

/// An impact of a unilateral cam contact (Newton's restitution law).
#[derive(Clone, Debug, PartialEq)]
pub struct Impact {
    pub joint: String,
    pub at: Crossing,
    /// Normal approach speed before the impact, −ġ⁻ (m/s, positive).
    pub approach: f64,
    /// Normal separation speed after it, ġ⁺ (m/s; 0 when the contact closes).
    pub separation: f64,
    /// The normal impulse on the follower side (N·s, positive).
    pub impulse: f64,
    /// True when the contact closed (a plastic impact, or an approach
    /// slower than the rest speed).
    pub closed: bool,
}

/// What kind of error or warning a run reports: a stable name that
/// programs match instead of the message (`docs/errors.md` lists them).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// Settings or times an analysis cannot use (a step ≤ 0, times that do
    /// not increase), or a model it cannot run (no moving body, a body not
    /// connected to the ground).
    InvalidInput,
    /// Fewer equations than coordinates in an analysis that needs every
    /// degree of freedom driven (kinematics, inverse dynamics).
    NotDriven,
    /// More equations than coordinates, or equations that depend on each
    /// other where the analysis needs them independent.
    Redundant,
    /// The mechanism cannot be assembled from the given placement.
    NotAssembled,
    /// Newton's method did not converge within its iterations.
    NotConverged,
    /// The constraint Jacobian (or the matrix of a Newton step) is singular:
    /// the mechanism is locked, at a singular position, or a driver pushes
    /// it past its reach.
    LockUp,
    /// The solution jumped away from continuous motion: a singular position
    /// was crossed or the assembly branch changed.
    BranchJump,
    /// Equations, velocities, accelerations or forces are not finite.
    NotFinite,
    /// The mass matrix is singular on the constraints.
    SingularMass,
    /// A contact ran off the end of an open curve.
    OffCurve,
    /// A flat face touches a concave part of its cam, or a roller a hollow
    /// narrower than itself.
    Undercut,
    /// A solver could not be set up (a matrix pattern faer refuses, or no
    /// memory for it): a bug to report.
    Internal,
    /// A user function computing a force failed (a Python force callback
    /// raised); the message names the force.
    ForceFailed,
    /// The receiver of the results stopped the run (an interrupt, a failing
    /// callback that takes the rows).
    Stopped,
    /// Warning: Φ_q is close to singular (a toggle or dead-centre position).
    NearSingular,
    /// Warning: a cam contact's normal force is negative; the follower
    /// would leave the cam.
    LiftOff,
    /// Warning: a driven motion takes a joint's coordinate out of its
    /// limits (kinematics follows its drivers; [`crate::limits`]).
    LimitExceeded,
}

impl Kind {
    /// Every kind, in declaration order.
    pub const ALL: [Kind; 17] = [
        Kind::InvalidInput,
        Kind::NotDriven,
        Kind::Redundant,
        Kind::NotAssembled,
        Kind::NotConverged,
        Kind::LockUp,
        Kind::BranchJump,
        Kind::NotFinite,
        Kind::SingularMass,
        Kind::OffCurve,
        Kind::Undercut,
        Kind::Internal,
        Kind::ForceFailed,
        Kind::Stopped,
        Kind::NearSingular,
        Kind::LiftOff,
        Kind::LimitExceeded,
    ];

    /// True for the kinds of a [`Warning`] (the run went on); false for
    /// those of an [`AnalysisError`].
    pub fn is_warning(self) -> bool {
        matches!(
            self,
            Kind::NearSingular | Kind::LiftOff | Kind::LimitExceeded
        )
    }

    /// The stable name, e.g. `not_converged`.
    pub fn name(self) -> &'static str {
        match self {
            Kind::InvalidInput => "invalid_input",
            Kind::NotDriven => "not_driven",
            Kind::Redundant => "redundant",
            Kind::NotAssembled => "not_assembled",
            Kind::NotConverged => "not_converged",
            Kind::LockUp => "lock_up",
            Kind::BranchJump => "branch_jump",
            Kind::NotFinite => "not_finite",
            Kind::SingularMass => "singular_mass",
            Kind::OffCurve => "off_curve",
            Kind::Undercut => "undercut",
            Kind::Internal => "internal",
            Kind::ForceFailed => "force_failed",
            Kind::Stopped => "stopped",
            Kind::NearSingular => "near_singular",
            Kind::LiftOff => "lift_off",
            Kind::LimitExceeded => "limit_exceeded",
        }
    }
}

impl std::fmt::Display for Kind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A warning of a run: the run went on, but a result may need care.
#[derive(Clone, Debug, PartialEq)]
pub struct Warning {
    pub kind: Kind,
    /// Time (s) where it arose.
    pub time: f64,
    /// Joints involved (may be empty).
    pub joints: Vec<String>,
    pub message: String,
}

/// An analysis that cannot proceed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("at t = {} s: {message}", crate::fmt_num::num(*.time))]
pub struct AnalysisError {
    /// What went wrong, as a stable name (`docs/errors.md`).
    pub kind: Kind,
    /// Time (s) of the step that failed.
    pub time: f64,
    pub message: String,
    /// Joints whose equations are involved.
    pub joints: Vec<String>,
    /// Largest |Φ| at failure (m or rad).
    pub residual: f64,
}

impl AnalysisError {
    /// An error of `kind` at `time` (s) with no joint named and no residual.
    pub fn new(kind: Kind, time: f64, message: impl Into<String>) -> Self {
        AnalysisError {
            kind,
            time,
            message: message.into(),
            joints: Vec::new(),
            residual: 0.0,
        }
    }

    /// The same error with the joints involved and the largest |Φ| (m or
    /// rad).
    pub(crate) fn at_joints(mut self, joints: Vec<String>, residual: f64) -> Self {
        self.joints = joints;
        self.residual = residual;
        self
    }
}

/// What is called before every step of an analysis: the sink's
/// [`Sink::tick`], whose error (an interrupt) stops the run.
pub(crate) type Tick<'a> = dyn FnMut() -> Result<(), AnalysisError> + 'a;

/// An analysis as the output loop drives it ([`output_loop`]).
pub(crate) trait Analysis {
    /// Reaches output time `t` (s) from the previous one, `prev` (None at
    /// the first), calling `tick` before every step.
    fn reach(&mut self, t: f64, prev: Option<f64>, tick: &mut Tick) -> Result<(), AnalysisError>;

    /// The row of the channels at `t`, reached, into `values`.
    fn fill(&mut self, t: f64, values: &mut [f64]) -> Result<(), AnalysisError>;

    /// Sees the row at `t` once it is written (watches over the run).
    fn observe(&mut self, _t: f64, _values: &[f64]) {}
}

/// The output loop of every analysis: the channels `names` to `sink`,
/// then, for each output time in turn (checked to increase,
/// [`check_next_time`]), the analysis reaches it and its row goes to
/// `sink` at once, so a run that fails keeps every row before.
pub(crate) fn output_loop(
    analysis: &mut dyn Analysis,
    times: &[f64],
    names: &[Channel],
    sink: &mut dyn Sink,
) -> Result<(), AnalysisError> {
    sink.begin(names);
    let mut values = vec![0.0; names.len()];
    let mut prev = None;
    for &t in times {
        check_next_time(prev, t)?;
        analysis.reach(t, prev, &mut || sink.tick().map_err(|s| s.at(t)))?;
        analysis.fill(t, &mut values)?;
        sink.row(t, &values).map_err(|s| s.at(t))?;
        analysis.observe(t, &values);
        prev = Some(t);
    }
    Ok(())
}

/// Checks that output time `t` (s) follows the previous one, `prev`
/// (`None` for the first): an `invalid_input` error when it does not
/// increase or is NaN.
pub(crate) fn check_next_time(prev: Option<f64>, t: f64) -> Result<(), AnalysisError> {
    match prev {
        Some(p) if t <= p || t.is_nan() => Err(AnalysisError::new(
            Kind::InvalidInput,
            t,
            not_increasing(t, p),
        )),
        _ => Ok(()),
    }
}

/// Checks a run's output times (s) before it starts: at least one, all
/// finite, each after the one before. The error is the index of the first
/// time that breaks the rule and what is wrong (the message
/// [`check_next_time`] gives for times that do not increase).
pub fn check_times(times: &[f64]) -> Result<(), (usize, String)> {
    if times.is_empty() {
        return Err((0, "times must be a non-empty list of numbers".into()));
    }
    for (k, &t) in times.iter().enumerate() {
        if !t.is_finite() {
            return Err((k, "times must be finite numbers".into()));
        }
        if k > 0 && t <= times[k - 1] {
            return Err((k, not_increasing(t, times[k - 1])));
        }
    }
    Ok(())
}

/// The message for output time `t` (s) that does not follow `prev`.
fn not_increasing(t: f64, prev: f64) -> String {
    format!("times must increase, but {} follows {}", num(t), num(prev))
}

/// The joints whose equations have the largest residuals |Φ| above `tol`,
/// worst first and at most five, with the largest residual (m or rad); a
/// NaN residual counts as infinite. `phi` is Φ at the failure.
pub(crate) fn worst_joints(
    model: &Model,
    asm: &Assembly,
    phi: &[f64],
    tol: f64,
) -> (Vec<String>, f64) {
    let mut worst: Vec<(f64, usize)> = Vec::new();
    for j in 0..model.joints.len() {
        let r = asm.rows_of(j).map(|k| phi[k].abs()).fold(0.0, |a: f64, b| {
            if b.is_nan() {
                f64::INFINITY
            } else {
                a.max(b)
            }
        });
        if r > tol {
            worst.push((r, j));
        }
    }
    worst.sort_by(|a, b| b.0.total_cmp(&a.0));
    let joints = worst
        .iter()
        .take(5)
        .map(|&(_, j)| model.joints[j].name.clone())
        .collect();
    (joints, worst.first().map_or(0.0, |w| w.0))
}

/// The number of steps of `step` (s) in [0, `t_end`] (s) of
/// [`time_grid`]: ⌊t_end/step + 1e-9⌋, so that an end time within rounding
/// of a multiple of the step is on the grid. For a positive step and
/// t_end ≥ 0.
pub fn grid_steps(t_end: f64, step: f64) -> f64 {
    (t_end / step + 1e-9).floor()
}

/// Checks a grid's step and end time (s): the step positive, the end
/// time ≥ 0, both finite; the error says which.
pub fn check_grid(t_end: f64, step: f64) -> Result<(), String> {
    use crate::fmt_num::num;
    if !(step.is_finite() && step > 0.0) {
        return Err(format!(
            "the time step must be a positive number, not {}",
            num(step)
        ));
    }
    if !(t_end.is_finite() && t_end >= 0.0) {
        return Err(format!(
            "the end time must be a number ≥ 0, not {}",
            num(t_end)
        ));
    }
    Ok(())
}

/// Times 0, h, 2h, … up to `t_end` (inclusive, within rounding).
pub fn time_grid(t_end: f64, step: f64) -> Result<Vec<f64>, String> {
    use crate::fmt_num::{count, num};
    check_grid(t_end, step)?;
    let steps = grid_steps(t_end, step);
    if steps > 100_000_000.0 {
        return Err(format!(
            "{} steps ({} s at {} s) is more than 100 million; use a larger step",
            count(steps),
            num(t_end),
            num(step)
        ));
    }
    let n = steps as usize;
    Ok((0..=n).map(|k| k as f64 * step).collect())
}

/// The output channels of a run: per moving body `x y phi vx vy omega ax
/// ay alpha`, per output point `x y vx vy ax ay`, each joint's own
/// coordinates, then the contacts' ([`Contacts::channels`]).
pub fn channels(model: &Model, points: &[PointOutput]) -> Vec<Channel> {
    use Quantity::*;
    let mut out = Vec::new();
    for (_, b) in model.moving_bodies() {
        for (c, q) in [
            ("x", Length),
            ("y", Length),
            ("phi", Angle),
            ("vx", Velocity),
            ("vy", Velocity),
            ("omega", AngularVelocity),
            ("ax", Acceleration),
            ("ay", Acceleration),
            ("alpha", AngularAcceleration),
        ] {
            out.push(Channel::new(format!("{}.{c}", b.name), q));
        }
    }
    for p in points {
        for (c, q) in [
            ("x", Length),
            ("y", Length),
            ("vx", Velocity),
            ("vy", Velocity),
            ("ax", Acceleration),
            ("ay", Acceleration),
        ] {
            out.push(Channel::new(format!("{}.{c}", p.name), q));
        }
    }
    for j in &model.joints {
        for k in 0..j.constraint.own_count() {
            let n = j.constraint.own_names().get(k).copied().unwrap_or("own");
            out.push(Channel::new(
                format!("{}.{n}", j.name),
                j.constraint.own_quantity(k),
            ));
        }
    }
    out.extend(Contacts::new(model).channels(model));
    out
}

/// The jerk channels of a run with [`Settings::jerk`], after those of
/// [`channels`]: `<body>.jx .jy .jphi` for every moving body (m/s³, m/s³,
/// rad/s³), then `<point>.jx .jy` for every output point (m/s³).
pub(crate) fn jerk_channels(model: &Model, points: &[PointOutput]) -> Vec<Channel> {
    use Quantity::*;
    let mut out = Vec::new();
    for (_, b) in model.moving_bodies() {
        for (c, q) in [("jx", Jerk), ("jy", Jerk), ("jphi", AngularJerk)] {
            out.push(Channel::new(format!("{}.{c}", b.name), q));
        }
    }
    for p in points {
        for c in ["jx", "jy"] {
            out.push(Channel::new(format!("{}.{c}", p.name), Jerk));
        }
    }
    out
}

/// The motion at one time, in an assembly's layout: positions q (m or
/// rad), velocities q̇ (m/s or rad/s) and accelerations q̈ (m/s² or
/// rad/s²).
#[derive(Clone, Copy, Debug)]
pub(crate) struct StateView<'a> {
    pub q: &'a [f64],
    pub qd: &'a [f64],
    pub qdd: &'a [f64],
}

/// Fills the channels of [`channels`] from the state (q, q̇, q̈): bodies,
/// points, own coordinates, then contact outputs.
pub(crate) fn fill_outputs(
    model: &Model,
    asm: &Assembly,
    contacts: &Contacts,
    state: StateView,
    points: &[PointOutput],
    out: &mut [f64],
) {
    let body = |v: &[f64], id: BodyId| -> [f64; 3] {
        match asm.body_col(id.0) {
            Some(c) => [v[c], v[c + 1], v[c + 2]],
            None => [0.0; 3],
        }
    };
    let mut k = 0;
    for (id, _) in model.moving_bodies() {
        for v in [state.q, state.qd, state.qdd] {
            out[k..k + 3].copy_from_slice(&body(v, id));
            k += 3;
        }
    }
    for p in points {
        let (q, qd, qdd) = (
            body(state.q, p.body),
            body(state.qd, p.body),
            body(state.qdd, p.body),
        );
        let r = point(q, p.s);
        let v = point_vel(q, qd, p.s);
        // r̈^P = r̈ + B s' φ̈ − A s' φ̇²
        let (a, b) = (rot(q[2], p.s), rot_d(q[2], p.s));
        let acc = [
            qdd[0] + b[0] * qdd[2] - a[0] * qd[2] * qd[2],
            qdd[1] + b[1] * qdd[2] - a[1] * qd[2] * qd[2],
        ];
        out[k..k + 6].copy_from_slice(&[r[0], r[1], v[0], v[1], acc[0], acc[1]]);
        k += 6;
    }
    for (j, joint) in model.joints.iter().enumerate() {
        let c = asm.own_col(j);
        for o in 0..joint.constraint.own_count() {
            out[k] = state.q[c + o];
            k += 1;
        }
    }
    contacts.fill(model, asm, state.q, &mut out[k..]);
}

/// A time and the cam angle then.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// t (s).
    pub time: f64,
    /// φ of the cam body (rad); 0 for a cam fixed to the ground.
    pub cam_angle: f64,
}

/// An interval where a cam contact's normal force is negative: the
/// follower would leave the cam.
#[derive(Clone, Debug, PartialEq)]
pub struct LiftOff {
    pub joint: String,
    /// The cam body's name.
    pub cam: String,
    /// Where N falls through zero: interpolated linearly between the last
    /// output time with N ≥ 0 and the first with N < 0 (the first output
    /// time when the run starts with N < 0).
    pub start: Crossing,
    /// Where N rises through zero again, interpolated likewise; `None`
    /// when the run ends with N < 0.
    pub end: Option<Crossing>,
    /// The least normal force in the interval (N, negative) and where.
    pub least: f64,
    pub least_at: Crossing,
}

impl LiftOff {
    /// The report, as the run summary's warning:
    ///
    /// `bucket: normal force < 0, the follower would leave cam 'camshaft'
    /// (jump) from t = 0.012345 s (cam angle 1.2345 rad, 70.7316°) to
    /// t = 0.015 s (cam angle 1.9 rad, 108.862°); least −12.3 N at
    /// t = 0.0137 s (cam angle 1.57 rad, 89.9544°)`
    ///
    /// The degrees are the cam angle folded into [0°, 360°); every number
    /// has at most six significant digits ([`crate::fmt_num`]).
    pub fn message(&self) -> String {
        let at = |c: &Crossing| {
            format!(
                "t = {} s (cam angle {} rad, {}°)",
                num(c.time),
                num(c.cam_angle),
                num(c.cam_angle.to_degrees().rem_euclid(360.0))
            )
        };
        let end = match &self.end {
            Some(e) => format!("to {}", at(e)),
            None => "to the end of the run".to_string(),
        };
        format!(
            "{}: normal force < 0, the follower would leave cam '{}' (jump) from {} {}; \
             least {} N at {}",
            self.joint,
            self.cam,
            at(&self.start),
            end,
            num(self.least),
            at(&self.least_at)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn output_times_are_checked_before_and_during_a_run_with_one_message() {
        assert!(check_times(&[0.0, 0.1, 0.2]).is_ok());
        assert_eq!(
            check_times(&[0.0, 0.5, 0.5]),
            Err((2, "times must increase, but 0.5 follows 0.5".into()))
        );
        let during = check_next_time(Some(0.5), 0.5).unwrap_err();
        assert_eq!(during.message, check_times(&[0.5, 0.5]).unwrap_err().1);
        assert_eq!(during.kind, Kind::InvalidInput);
        assert_eq!(check_times(&[]).unwrap_err().0, 0);
        assert_eq!(
            check_times(&[0.0, f64::NAN]),
            Err((1, "times must be finite numbers".into()))
        );
    }

    /// The kinds listed in `docs/errors.md`, between `<!-- kinds -->` and
    /// `<!-- /kinds -->`, as (name, "error" or "warning").
    fn documented_kinds() -> Vec<(String, String)> {
        let page = include_str!("../../../docs/errors.md");
        let table = page
            .split("<!-- kinds -->")
            .nth(1)
            .and_then(|rest| rest.split("<!-- /kinds -->").next())
            .expect("docs/errors.md has a table of kinds");
        table
            .lines()
            .filter_map(|line| {
                let cells: Vec<&str> = line.split('|').map(str::trim).collect();
                let name = cells.get(1)?.strip_prefix('`')?.strip_suffix('`')?;
                Some((name.to_string(), cells.get(2)?.to_string()))
            })
            .collect()
    }

    #[test]
    fn points_are_resolved_by_name_with_a_reason_when_they_are_not() {
        use crate::model::{Body, Point};
        let mut m = Model::new("m");
        let mut arm = Body::new("arm", [0.0; 3]);
        arm.points.push(Point {
            name: "tip".into(),
            s: [1.0, 0.5],
        });
        let id = m.add_body(arm);
        let p = PointOutput::named(&m, "arm.tip").unwrap();
        assert_eq!((p.body, p.name.as_str(), p.s), (id, "arm.tip", [1.0, 0.5]));
        let err = |full: &str| PointOutput::named(&m, full).unwrap_err();
        assert_eq!(err("tip"), "point 'tip' should be written as 'body.point'");
        assert_eq!(err("leg.tip"), "point 'leg.tip': no body named 'leg'");
        assert_eq!(
            err("arm.toe"),
            "point 'arm.toe': body 'arm' has no point 'toe' (it has: tip)"
        );
    }

    #[test]
    fn every_kind_is_documented_once_as_error_or_warning() {
        let want: Vec<(String, String)> = Kind::ALL
            .iter()
            .map(|k| {
                let level = if k.is_warning() { "warning" } else { "error" };
                (k.name().to_string(), level.to_string())
            })
            .collect();
        assert_eq!(documented_kinds(), want);
    }
}
