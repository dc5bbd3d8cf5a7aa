//! Forward dynamics with unilateral cam contacts: lift-off, flight and
//! impact (`docs/dynamics.md`, "Unilateral contacts").
//!
//! A `cam_follower` or `flat_follower` joint with [`Unilateral`] settings
//! is, at every time, either
//!
//! - **closed**: its equations hold, as in a bilateral run, and its normal
//!   force N (N, positive pressing) is watched; or
//! - **open**: its equations are released (the model integrated is the
//!   model without that joint) and the gap g (m, [`crate::curve::distance`])
//!   between its two features is watched.
//!
//! Events are located inside the step in which they happen, by bisection
//! on the step length from the step's start, to the joint's `event_tol`
//! (s): lift-off where N falls through zero, impact where g falls through
//! zero. A grazing approach — g positive at both ends of a step but
//! falling at its start and rising at its end — is caught by the cubic
//! Hermite interpolant of (g, ġ) over the step: when its least value is
//! negative, the step is cut there and the event located before it. A
//! normal force that dips below zero inside a step is caught likewise,
//! from the parabola through N at the last three step ends.
//!
//! At lift-off the joint opens and the integration restarts from the
//! end of the located interval. An impact is taken at the secant zero of
//! the gap inside that interval, from the step's interpolated state
//! there: the impulse of Newton's law with restitution e is
//! applied ([`super::impact`]); the contact stays open when the follower
//! separates, and closes (a plastic impact) when e = 0 or when the
//! approach speed is below the joint's `rest_speed`: a follower bouncing
//! ever lower comes to rest in finite time.
//!
//! A compliant contact (`Unilateral::compliant`) is open throughout: its
//! Hunt–Crossley force ([`crate::force::compliant_contact`]) is one of the
//! forces of every model, and no event is watched for it.
//!
//! Each combination of open joints is its own model (at most
//! [`MAX_UNILATERAL`] unilateral joints, 2^k models) with its own
//! integrator, created at the first switch to it. The full model's state
//! is kept for the outputs: an open joint's contact parameters are those
//! of the gap's witness points, their rates and its multipliers zero.
//! Steps are of the fixed size `settings.step` from the last event; an
//! output time inside a step is served by its interpolant
//! ([`Integrator::dense_between`]) in the model of that step. The
//! error-controlled mode is refused in a run with unilateral contacts.

use super::generalized_alpha::{
    arrived_within, fixed_step, steps_over, Integrator, Settings, Snapshot,
};
use super::impact;
use super::output::{self, DriftScratch, Scratch};
use super::stops::{self, Stop};
use super::system::{Augmented, System};
use crate::constraint::{Constraint, Equations};
use crate::contact::{ContactView, Contacts};
use crate::curve::contact::{self, face_normal_force};
use crate::curve::distance::{Features, Gap};
use crate::diagnose::gap_features;
use crate::force::compliant_contact::CompliantContact;
use crate::force::Force;
use crate::math::{perp, rot, V2};
use crate::model::{BodyId, Model, Unilateral};
use crate::quantity::{Channel, Quantity};
use crate::run::{
    self, AnalysisError, Crossing, Flight, Impact, Kind, PointOutput, Sink, StateView, Summary,
    Tick,
};

pub use crate::diagnose::OPEN_AT_START;

/// Events in a row, each close to the last, that count as an accumulation.
const MAX_BURST: usize = 1000;

/// Most unilateral joints in one model.
pub const MAX_UNILATERAL: usize = 6;

/// One unilateral joint and its state.
#[derive(Clone, Debug)]
struct Contact {
    joint: usize,
    bodies: [BodyId; 2],
    cam: BodyId,
    features: Watched,
    law: Unilateral,
    open: bool,
    /// The gap at the current state (open joints).
    gap: Option<Gap>,
    /// The flight under way.
    flight: Option<Flight>,
    /// (t, N) at the start of the step before, while closed.
    n_before: Option<(f64, f64)>,
}

impl Contact {
    /// The gap at body coordinates `q`, `qd` of bodies i and j.
    fn gap(&self, q: [[f64; 3]; 2], qd: [[f64; 3]; 2]) -> Gap {
        match &self.features {
            Watched::Curves(f) => f.gap(q, qd, self.gap.map(|g| g.params)),
            Watched::Stop(s) => s.gap(q, qd),
        }
    }

    /// The joint stop this contact is, if it is one.
    fn stop(&self) -> Option<&Stop> {
        match &self.features {
            Watched::Stop(s) => Some(s),
            Watched::Curves(_) => None,
        }
    }
}

/// What a unilateral joint's gap is measured between: the features of a
/// cam contact, or a joint's coordinate and its limit ([`super::stops`]).
#[derive(Clone, Debug)]
enum Watched {
    Curves(Features),
    Stop(Stop),
}

/// The normal force N (N) of closed contact joint `j` from its multipliers
/// `lam` (its rows): the force on body j along N, −Φ_{r_j}ᵀλ · N.
fn normal_force(model: &Model, j: usize, q_j: [f64; 3], lam: &[f64], n: V2) -> f64 {
    match &model.joints[j].constraint {
        Constraint::CamFollower(_) => contact::normal_force([lam[0], lam[1]], n),
        Constraint::FlatFollower(f) => face_normal_force(n, perp(rot(q_j[2], f.u_j)), lam[0]),
        _ => f64::NAN,
    }
}

/// Where model `mask` (bit k: unilateral joint k open) puts each
/// coordinate and row of the full model.
struct Layout {
    cols: Vec<Option<usize>>,
    rows: Vec<Option<usize>>,
}

impl Layout {
    fn new(full: &System, sub: &System, removed: &[usize]) -> Self {
        let fm = full.model;
        let mut cols = vec![None; full.n()];
        let mut rows = vec![None; full.m()];
        for b in 0..fm.bodies.len() {
            if let (Some(a), Some(c)) = (full.asm.body_col(b), sub.asm.body_col(b)) {
                for d in 0..3 {
                    cols[a + d] = Some(c + d);
                }
            }
        }
        let mut k = 0;
        for j in 0..fm.joints.len() {
            if removed.contains(&j) {
                continue;
            }
            let (a, c) = (full.asm.own_col(j), sub.asm.own_col(k));
            for o in 0..fm.joints[j].constraint.own_count() {
                cols[a + o] = Some(c + o);
            }
            for (r, s) in full.asm.rows_of(j).zip(sub.asm.rows_of(k)) {
                rows[r] = Some(s);
            }
            k += 1;
        }
        Layout { cols, rows }
    }
}

/// The model with joints `removed` taken out.
fn without(model: &Model, removed: &[usize]) -> Model {
    let mut m = model.clone();
    m.joints = model
        .joints
        .iter()
        .enumerate()
        .filter(|(j, _)| !removed.contains(j))
        .map(|(_, j)| j.clone())
        .collect();
    m
}

/// The unilateral joints of `model`, checked.
/// `h` is the time step (s) and `t_span` the largest |t| of the run (s),
/// which bound each joint's `event_tol` ([`event_tol_bounds`]).
fn contacts(
    model: &Model,
    sys: &System,
    q: &[f64],
    h: f64,
    t_span: f64,
    stops: &[(usize, Stop)],
) -> Result<Vec<Contact>, AnalysisError> {
    let bad = |j: usize, what: &str| {
        AnalysisError::new(
            Kind::InvalidInput,
            0.0,
            format!("joint '{}': {what}", model.joints[j].name),
        )
    };
    let mut out = Vec::new();
    for (j, joint) in model.joints.iter().enumerate() {
        let Some(law) = joint.unilateral else {
            continue;
        };
        if joint.driver {
            return Err(bad(j, "a driver cannot be unilateral"));
        }
        let stop = stops.iter().find(|(k, _)| *k == j).map(|(_, s)| s);
        let view = ContactView::of(model, j);
        if view.is_none() && stop.is_none() {
            return Err(bad(
                j,
                "only cam_follower and flat_follower joints can be unilateral",
            ));
        }
        if !(0.0..=1.0).contains(&law.restitution) {
            return Err(bad(j, "restitution must be between 0 and 1"));
        }
        if !(law.event_tol > 0.0 && law.rest_speed >= 0.0) {
            return Err(bad(
                j,
                "event_tol must be positive and rest_speed not negative",
            ));
        }
        let (least, below) = event_tol_bounds(h, t_span);
        if law.compliant.is_none() && !(law.event_tol >= least && law.event_tol < below) {
            return Err(bad(
                j,
                &format!(
                    "event_tol = {} s must be at least {} s (the rounding of t over the \
                     run) and below the time step h = {} s (an event is located inside \
                     a step)",
                    crate::fmt_num::num(law.event_tol),
                    crate::fmt_num::num(least),
                    crate::fmt_num::num(below)
                ),
            ));
        }
        let (bodies, cam, features) = match (view, stop) {
            (Some(view), _) => {
                let x = sys.asm.local(model, j, q, &[], 0.0);
                let features = gap_features(model, j, x.q).map_err(|what| bad(j, what))?;
                (view.bodies, view.cam(model), Watched::Curves(features))
            }
            (None, Some(s)) => {
                let bodies = joint.constraint.bodies();
                (bodies, bodies[0], Watched::Stop(s.clone()))
            }
            (None, None) => unreachable!("checked above"),
        };
        out.push(Contact {
            joint: j,
            bodies,
            cam,
            features,
            law,
            open: false,
            gap: None,
            flight: None,
            n_before: None,
        });
    }
    if out.len() > MAX_UNILATERAL {
        return Err(AnalysisError::new(
            Kind::InvalidInput,
            0.0,
            format!("at most {MAX_UNILATERAL} unilateral joints in one model"),
        ));
    }
    Ok(out)
}

/// The bounds (s) of a joint's `event_tol` in a run of time step `h` (s)
/// whose times reach |t| ≤ `t_span` (s): at least 16 ε max(h, t_span),
/// which the bisection of a step's length and the times t₀ + τ it
/// tries can still resolve, and below h, the longest interval an event
/// is located in (at or above it every event would be placed at the end
/// of its step).
pub fn event_tol_bounds(h: f64, t_span: f64) -> (f64, f64) {
    (16.0 * f64::EPSILON * h.max(t_span), h)
}

/// What the event functions say at the end of a step.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Event {
    LiftOff(usize),
    Impact(usize),
}

/// A state of the full model, in its layout: positions q (m or rad),
/// velocities q̇, accelerations q̈ and multipliers λ.
#[derive(Clone, Debug, Default)]
struct FullState {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    lambda: Vec<f64>,
}

impl FullState {
    fn view(&self) -> StateView<'_> {
        StateView {
            q: &self.q,
            qd: &self.qd,
            qdd: &self.qdd,
        }
    }
}

/// The run's state: the full model's vectors, the models of the active
/// sets and their integrators.
struct Run<'a> {
    /// The run's start time (s).
    t0: f64,
    full: System<'a>,
    models: &'a [Model],
    layouts: Vec<Option<Layout>>,
    its: Vec<Option<Integrator<'a>>>,
    settings: Settings,
    mask: usize,
    contacts: Vec<Contact>,
    /// The full model's state at the active integrator's time.
    state: FullState,
    /// λ of the consistent accelerations (full layout), which the
    /// lift-off events watch.
    lam_watch: Vec<f64>,
    /// Per active set, an augmented matrix of its integrator's system for
    /// [`watch_forces`](Self::watch_forces), apart from the integrator's
    /// own, whose step factorization is kept.
    watch: Vec<Option<Augmented>>,
    /// Events in a row within 100 event tolerances of each other, and the
    /// time of the last.
    burst: (usize, f64),
    /// Scratch: the right-hand side of [`watch_forces`](Self::watch_forces)
    /// the gaps at the start of a step and the watched values there.
    rhs: Vec<f64>,
    gaps: Vec<Option<Gap>>,
    n0: Vec<Option<f64>>,
    /// The gaps at the start of the located interval of an event.
    gaps_lo: Vec<Option<Gap>>,
    /// Whether the step under way keeps its ends for a dense output.
    hold: bool,
    /// The active set of the last step kept, and its two ends: the start
    /// and the end before any event was handled.
    held: Option<usize>,
    held_start: Snapshot,
    held_end: Snapshot,
    /// A dense output in the full layout: the state and the gaps.
    out: FullState,
    out_gaps: Vec<Option<Gap>>,
    /// Scratch: q and q̇ at an impact (the active set's layout).
    event_q: Vec<f64>,
    event_qd: Vec<f64>,
    summary: Summary,
}

impl<'a> Run<'a> {
    fn it(&mut self) -> &mut Integrator<'a> {
        self.its[self.mask]
            .as_mut()
            .expect("integrator of the active set")
    }

    fn removed(&self, mask: usize) -> Vec<usize> {
        (0..self.contacts.len())
            .filter(|k| mask & (1 << k) != 0)
            .map(|k| self.contacts[k].joint)
            .collect()
    }

    fn layout(&mut self, mask: usize) -> &Layout {
        if self.layouts[mask].is_none() {
            let sub = System::new(&self.models[mask]);
            let removed = self.removed(mask);
            self.layouts[mask] = Some(Layout::new(&self.full, &sub, &removed));
        }
        self.layouts[mask].as_ref().expect("layout")
    }

    /// Bodies i and j of contact `k` at the full state.
    fn bodies(&self, k: usize) -> ([[f64; 3]; 2], [[f64; 3]; 2]) {
        let mut q = [[0.0; 3]; 2];
        let mut qd = [[0.0; 3]; 2];
        for (s, b) in self.contacts[k].bodies.iter().enumerate() {
            if let Some(c) = self.full.asm.body_col(b.0) {
                q[s].copy_from_slice(&self.state.q[c..c + 3]);
                qd[s].copy_from_slice(&self.state.qd[c..c + 3]);
            }
        }
        (q, qd)
    }

    /// The full state from the active integrator; open joints' contact
    /// parameters from their gaps' witnesses.
    fn pull(&mut self) -> Result<(), AnalysisError> {
        let mask = self.mask;
        self.layout(mask);
        let layout = self.layouts[mask].as_ref().expect("layout");
        let s = self.its[mask].as_ref().expect("integrator").state();
        for (f, c) in layout.cols.iter().enumerate() {
            let (a, b, d) = match c {
                Some(c) => (s.q[*c], s.qd[*c], s.qdd[*c]),
                None => (self.state.q[f], 0.0, 0.0),
            };
            self.state.q[f] = a;
            self.state.qd[f] = b;
            self.state.qdd[f] = d;
        }
        for (f, r) in layout.rows.iter().enumerate() {
            self.state.lambda[f] = r.map_or(0.0, |r| s.lambda[r]);
        }
        for k in 0..self.contacts.len() {
            if !self.contacts[k].open {
                self.contacts[k].gap = None;
                continue;
            }
            let (q, qd) = self.bodies(k);
            let g = self.contacts[k].gap(q, qd);
            self.contacts[k].gap = Some(g);
            let j = self.contacts[k].joint;
            let o = self.full.asm.own_col(j);
            for s in 0..self.full.model.joints[j].constraint.own_count() {
                self.state.q[o + s] = g.params[s];
            }
        }
        if self.contacts.iter().any(|c| !c.open) {
            self.watch_forces()?;
        }
        Ok(())
    }

    /// λ of the consistent accelerations at the active integrator's state,
    /// [M Φ_qᵀ; Φ_q 0][q̈; λ] = [Q; γ], into `lam_watch` (full layout). The
    /// integrator's own λ is the generalized-α step's, whose q̈ after the
    /// very short steps of an event search carries the Newton tolerance
    /// divided by β h²; this one depends on (t, q, q̇) only.
    fn watch_forces(&mut self) -> Result<(), AnalysisError> {
        let mask = self.mask;
        let it = self.its[mask].as_ref().expect("integrator");
        if self.watch[mask].is_none() {
            let s = it.state();
            let aug = Augmented::new(&it.sys, &s.q)
                .map_err(|e| AnalysisError::new(Kind::Internal, s.t, e.to_string()))?;
            self.watch[mask] = Some(aug);
        }
        let aug = self.watch[mask].as_mut().expect("watch");
        it.consistent_into(aug, &mut self.rhs)?;
        let n = it.sys.n();
        let layout = self.layouts[mask].as_ref().expect("layout");
        for (f, r) in layout.rows.iter().enumerate() {
            self.lam_watch[f] = r.map_or(0.0, |r| self.rhs[n + r]);
        }
        Ok(())
    }

    /// Switches to active set `mask`, restarting its integrator from the
    /// full state at `t` with the velocity `qd` (full layout).
    fn switch(&mut self, mask: usize, t: f64, qd: &[f64]) -> Result<(), AnalysisError> {
        if self.its[mask].is_none() {
            // Made at the run's start, where the given placement holds,
            // then restarted from the state at t.
            let it = Integrator::starting_at(&self.models[mask], self.settings.clone(), self.t0)?;
            self.its[mask] = Some(it);
        }
        self.layout(mask);
        let layout = self.layouts[mask].as_ref().expect("layout");
        let it = self.its[mask].as_mut().expect("integrator");
        let (mut q, mut v) = (it.state().q.clone(), it.state().qd.clone());
        for (f, c) in layout.cols.iter().enumerate() {
            if let Some(c) = c {
                q[*c] = self.state.q[f];
                v[*c] = qd[f];
            }
        }
        it.restart(t, &q, &v)?;
        self.mask = mask;
        self.pull()?;
        Ok(())
    }

    /// The event values of contact `k` at the full state: N (closed) or g
    /// (open).
    fn value(&self, k: usize) -> f64 {
        let c = &self.contacts[k];
        if c.open {
            return c.gap.map_or(f64::INFINITY, |g| g.gap);
        }
        let rows = self.full.asm.rows_of(c.joint);
        let f = match &c.features {
            Watched::Stop(s) => return s.push(self.lam_watch[rows.start]),
            Watched::Curves(f) => f,
        };
        let (q, _) = self.bodies(k);
        let o = self.full.asm.own_col(c.joint);
        let own = [
            self.state.q[o],
            self.state.q.get(o + 1).copied().unwrap_or(0.0),
        ];
        normal_force(
            self.full.model,
            c.joint,
            q[1],
            &self.lam_watch[rows],
            f.normal(q, own),
        )
    }

    /// The earliest event at the current state (after a step): a closed
    /// contact with N < 0, an open one with g < 0 while approaching.
    fn event(&self) -> Option<Event> {
        (0..self.contacts.len()).find_map(|k| {
            let c = &self.contacts[k];
            if c.law.compliant.is_some() {
                return None;
            }
            let v = self.value(k);
            if c.open {
                let approaching = c.gap.is_some_and(|g| g.rate < 0.0);
                (v < 0.0 && approaching).then_some(Event::Impact(k))
            } else {
                (v < 0.0).then_some(Event::LiftOff(k))
            }
        })
    }

    /// The crossing record at time `t` of contact `k`.
    fn crossing(&self, k: usize, t: f64) -> Crossing {
        let cam = self.contacts[k].cam;
        let cam_angle = self
            .full
            .asm
            .body_col(cam.0)
            .map_or(0.0, |c| self.state.q[c + 2]);
        Crossing { time: t, cam_angle }
    }

    /// One step of length `h`, or up to the first event inside it, located
    /// and handled; `tick` is called before every trial of the location.
    fn step(&mut self, h: f64, snap: &mut Snapshot, tick: &mut Tick) -> Result<(), AnalysisError> {
        let mut gaps = std::mem::take(&mut self.gaps);
        gaps.clear();
        gaps.extend(self.contacts.iter().map(|c| c.gap));
        let done = self.step_from(h, snap, &gaps, tick);
        self.gaps = gaps;
        done
    }

    /// [`step`](Self::step) with the gaps at its start.
    fn step_from(
        &mut self,
        h: f64,
        snap: &mut Snapshot,
        gaps: &[Option<Gap>],
        tick: &mut Tick,
    ) -> Result<(), AnalysisError> {
        self.it().snapshot(snap);
        let t0 = self.it().state().t;
        let mut n0 = std::mem::take(&mut self.n0);
        n0.clear();
        n0.extend((0..self.contacts.len()).map(|k| self.watched(k).then(|| self.value(k))));
        let done = self.step_watched(h, snap, gaps, t0, &n0, tick);
        self.n0 = n0;
        done
    }

    /// [`step_from`](Self::step_from) with `n0`, the watched values at its
    /// start (t0, s).
    fn step_watched(
        &mut self,
        h: f64,
        snap: &mut Snapshot,
        gaps: &[Option<Gap>],
        t0: f64,
        n0: &[Option<f64>],
        tick: &mut Tick,
    ) -> Result<(), AnalysisError> {
        self.it().step(h)?;
        self.pull()?;
        let t1 = self.it().state().t;
        // A grazing approach between the step's ends; a normal force that
        // dips below zero between them (the parabola through N at the last
        // three step ends).
        let mut cut = None;
        if self.event().is_none() {
            for (k, &n0k) in n0.iter().enumerate() {
                let (Some((tm, nm)), Some(n)) = (self.contacts[k].n_before, n0k) else {
                    continue;
                };
                if !self.watched(k) {
                    continue;
                }
                if let Some(tau) = parabola_dip([tm, t0, t1], [nm, n, self.value(k)]) {
                    cut = Some(cut.map_or(tau, |c: f64| c.min(tau)));
                }
            }
            for (k, g0) in gaps.iter().enumerate() {
                let (Some(g0), Some(g1)) = (g0, self.contacts[k].gap) else {
                    continue;
                };
                if self.contacts[k].law.compliant.is_some() {
                    continue;
                }
                if let Some(tau) = hermite_dip(h, [g0.gap, g0.rate, g1.gap, g1.rate]) {
                    cut = Some(cut.map_or(tau, |c: f64| c.min(tau)));
                }
            }
        }
        let mut span = h;
        if let Some(tau) = cut {
            self.trial(snap, gaps, tau)?;
            if self.event().is_none() {
                // The interpolant dipped, the motion did not: keep the step.
                self.trial(snap, gaps, h)?;
                self.keep(snap);
                self.remember(t0, n0);
                return Ok(());
            }
            span = tau;
        }
        if self.event().is_none() {
            self.keep(snap);
            self.remember(t0, n0);
            return Ok(());
        }
        for c in &mut self.contacts {
            c.n_before = None;
        }
        // Bisection on the step length to the tightest event tolerance,
        // keeping the gaps at the start of the interval.
        let tol = self
            .contacts
            .iter()
            .filter(|c| c.law.compliant.is_none())
            .map(|c| c.law.event_tol)
            .fold(f64::INFINITY, f64::min);
        self.gaps_lo.clear();
        self.gaps_lo.extend_from_slice(gaps);
        let (mut lo, mut hi) = (0.0, span);
        while hi - lo > tol {
            tick()?;
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            self.trial(snap, gaps, mid)?;
            if self.event().is_some() {
                hi = mid;
            } else {
                lo = mid;
                for (g, c) in self.gaps_lo.iter_mut().zip(&self.contacts) {
                    *g = c.gap;
                }
            }
        }
        self.trial(snap, gaps, hi)?;
        self.keep(snap);
        match self.event() {
            Some(Event::LiftOff(k)) => {
                self.count_event(tol)?;
                self.lift_off(k)
            }
            Some(Event::Impact(k)) => {
                self.back_to_contact(k, t0, [lo, hi])?;
                self.count_event(tol)?;
                self.impact(k)
            }
            None => Ok(()),
        }
    }

    /// Moves the state back to where the gap of contact `k` is zero, in
    /// the located interval `[lo, hi]` (s from the step's start `t0`):
    /// the secant root of g between its ends, then the state there from
    /// the step's interpolant ([`Integrator::dense_output`]), on which the
    /// impact's time, approach speed and impulse are taken.
    fn back_to_contact(
        &mut self,
        k: usize,
        t0: f64,
        [lo, hi]: [f64; 2],
    ) -> Result<(), AnalysisError> {
        let (Some(a), Some(b)) = (self.gaps_lo[k], self.contacts[k].gap) else {
            return Ok(());
        };
        let f = if a.gap > b.gap {
            (a.gap / (a.gap - b.gap)).clamp(0.0, 1.0)
        } else {
            1.0
        };
        let t = t0 + lo + f * (hi - lo);
        let mask = self.mask;
        let it = self.its[mask].as_mut().expect("integrator");
        it.dense_output(t)?;
        let d = it.dense.as_ref().expect("dense output");
        let (q, qd) = (&mut self.event_q, &mut self.event_qd);
        q.clone_from(&d.q);
        qd.clone_from(&d.qd);
        it.restart(t, q, qd)?;
        self.pull()
    }

    /// Keeps the ends of the step just taken (before any event is handled)
    /// when [`hold`](Self::hold) is set: `start` and the active state.
    fn keep(&mut self, start: &Snapshot) {
        if !self.hold {
            return;
        }
        let mask = self.mask;
        self.held = Some(mask);
        self.held_start.copy_from(start);
        let it = self.its[mask].as_ref().expect("integrator");
        it.snapshot(&mut self.held_end);
    }

    /// The state at output time `t` (s) inside the step kept last into
    /// `out` and `out_gaps` (full layout, as [`pull`](Self::pull)), λ the
    /// consistent multipliers there; the active set's system for the
    /// energy and drift, with its q and q̇. None when no kept step holds t.
    fn dense_row(&mut self, t: f64) -> Result<Option<usize>, AnalysisError> {
        let Some(mask) = self.held else {
            return Ok(None);
        };
        let (a, b) = (&self.held_start, &self.held_end);
        if !(a.t() <= t && t <= b.t()) {
            return Ok(None);
        }
        let it = self.its[mask].as_mut().expect("integrator");
        it.dense_between(a, b, t)?;
        self.layout(mask);
        let layout = self.layouts[mask].as_ref().expect("layout");
        let it = self.its[mask].as_ref().expect("integrator");
        let d = it.dense.as_ref().expect("dense output");
        let FullState { q, qd, qdd, lambda } = &mut self.out;
        q.clone_from(&self.state.q);
        qd.resize(q.len(), 0.0);
        qdd.resize(q.len(), 0.0);
        lambda.resize(self.state.lambda.len(), 0.0);
        for (f, c) in layout.cols.iter().enumerate() {
            let (x, v, acc) = match c {
                Some(c) => (d.q[*c], d.qd[*c], d.qdd[*c]),
                None => (q[f], 0.0, 0.0),
            };
            q[f] = x;
            qd[f] = v;
            qdd[f] = acc;
        }
        for (f, r) in layout.rows.iter().enumerate() {
            lambda[f] = r.map_or(0.0, |r| d.lambda[r]);
        }
        self.out_gaps.clear();
        for k in 0..self.contacts.len() {
            if mask & (1 << k) == 0 {
                self.out_gaps.push(None);
                continue;
            }
            let mut bq = [[0.0; 3]; 2];
            let mut bqd = [[0.0; 3]; 2];
            for (s, body) in self.contacts[k].bodies.iter().enumerate() {
                if let Some(c) = self.full.asm.body_col(body.0) {
                    bq[s].copy_from_slice(&q[c..c + 3]);
                    bqd[s].copy_from_slice(&qd[c..c + 3]);
                }
            }
            let g = self.contacts[k].gap(bq, bqd);
            let j = self.contacts[k].joint;
            let (o, k) = (
                self.full.asm.own_col(j),
                self.full.model.joints[j].constraint.own_count(),
            );
            q[o..o + k].copy_from_slice(&g.params[..k]);
            self.out_gaps.push(Some(g));
        }
        Ok(Some(mask))
    }

    /// Counts an event at the current time; an accumulation of more than
    /// [`MAX_BURST`] events each within 100 event tolerances of the last
    /// (a contact switching without end) stops the run.
    fn count_event(&mut self, tol: f64) -> Result<(), AnalysisError> {
        let t = self.it().state().t;
        if t - self.burst.1 <= 100.0 * tol {
            self.burst.0 += 1;
        } else {
            self.burst.0 = 0;
        }
        self.burst.1 = t;
        if self.burst.0 > MAX_BURST {
            let names: Vec<String> = self
                .contacts
                .iter()
                .map(|c| self.full.model.joints[c.joint].name.clone())
                .collect();
            return Err(AnalysisError::new(
                Kind::NotConverged,
                t,
                format!(
                    "the unilateral contacts switch more than {MAX_BURST} times within \
                     {} s each: an accumulation of events; raise rest_speed so that \
                     slow impacts close the contact",
                    crate::fmt_num::num(100.0 * tol)
                ),
            )
            .at_joints(names, 0.0));
        }
        Ok(())
    }

    /// True when contact `k`'s normal force is watched: closed, not compliant.
    fn watched(&self, k: usize) -> bool {
        let c = &self.contacts[k];
        !c.open && c.law.compliant.is_none()
    }

    /// Keeps N at the start `t0` of the step just taken, for the next.
    fn remember(&mut self, t0: f64, n0: &[Option<f64>]) {
        for (c, n) in self.contacts.iter_mut().zip(n0) {
            c.n_before = n.filter(|_| !c.open).map(|n| (t0, n));
        }
    }

    /// From the snapshot, one step of length `h`.
    fn trial(
        &mut self,
        snap: &Snapshot,
        gaps: &[Option<Gap>],
        h: f64,
    ) -> Result<(), AnalysisError> {
        self.it().resume(snap);
        for (c, g) in self.contacts.iter_mut().zip(gaps) {
            c.gap = *g;
        }
        self.it().step(h)?;
        self.pull()?;
        Ok(())
    }

    /// A new flight of contact `k` from `at`.
    fn flight(&self, k: usize, at: Crossing) -> Flight {
        let model = self.full.model;
        Flight {
            joint: model.joints[self.contacts[k].joint].name.clone(),
            cam: model.bodies[self.contacts[k].cam.0].name.clone(),
            start: at,
            end: None,
            greatest_gap: 0.0,
            greatest_at: at,
        }
    }

    /// Opens contact `k` at the current state.
    fn lift_off(&mut self, k: usize) -> Result<(), AnalysisError> {
        let t = self.it().state().t;
        let at = self.crossing(k, t);
        self.contacts[k].open = true;
        self.contacts[k].gap = None;
        self.contacts[k].flight = Some(self.flight(k, at));
        let qd = self.state.qd.clone();
        self.switch(self.mask | (1 << k), t, &qd)
    }

    /// The impact of contact `k` at the current state.
    fn impact(&mut self, k: usize) -> Result<(), AnalysisError> {
        let t = self.it().state().t;
        let gap = self.contacts[k].gap.expect("open contact has a gap");
        let law = self.contacts[k].law;
        let approach = -gap.rate;
        let closes = law.restitution == 0.0 || approach < law.rest_speed;
        let e = if closes { 0.0 } else { law.restitution };
        // Close the contact at the impact position, then the impulse.
        let closed = self.mask & !(1 << k);
        let qd_before = self.state.qd.clone();
        self.contacts[k].open = false;
        self.switch(closed, t, &qd_before)?;
        let j = self.contacts[k].joint;
        let jm = self.removed_index(closed, j);
        let at = self.crossing(k, t);
        let layout = self.layouts[closed].as_ref().expect("layout");
        let it = self.its[closed].as_mut().expect("integrator");
        let mut v = vec![0.0; it.state().qd.len()];
        for (f, c) in layout.cols.iter().enumerate() {
            if let Some(c) = c {
                v[*c] = qd_before[f];
            }
        }
        let q = it.state().q.clone();
        let (sys, aug) = it.system_and_matrix();
        let rows = match &self.contacts[k].features {
            Watched::Stop(s) => Some(s.impact_rows().to_vec()),
            Watched::Curves(_) => impact::contact_rows(sys, jm, &q, gap.normal),
        };
        let out = rows.and_then(|rows| impact::solve(sys, aug, jm, &q, &v, t, &rows, gap.rate, e));
        let Some(out) = out else {
            return Err(AnalysisError::new(
                Kind::LockUp,
                t,
                format!(
                    "the impact of joint '{}' meets a singular matrix",
                    self.full.model.joints[j].name
                ),
            ));
        };
        if let Some(mut f) = self.contacts[k].flight.take() {
            f.end = Some(at);
            self.summary.flights.push(f);
        }
        let mut impact = Impact {
            joint: self.full.model.joints[j].name.clone(),
            at,
            approach,
            separation: 0.0,
            impulse: out.impulse,
            closed: closes,
        };
        if closes {
            it.restart(t, &q, &out.qd)?;
            self.pull()?;
        } else {
            // The follower leaves again: a new flight from the bounce.
            let mut qd_full = self.state.qd.clone();
            for (f, c) in layout.cols.iter().enumerate() {
                if let Some(c) = c {
                    qd_full[f] = out.qd[*c];
                }
            }
            self.contacts[k].open = true;
            self.contacts[k].gap = None;
            self.contacts[k].flight = Some(self.flight(k, at));
            self.switch(self.mask | (1 << k), t, &qd_full)?;
            impact.separation = self.contacts[k].gap.map_or(0.0, |g| g.rate);
        }
        self.summary.impacts.push(impact);
        Ok(())
    }

    /// The index of joint `j` in the model of `mask`.
    fn removed_index(&self, mask: usize, j: usize) -> usize {
        let removed = self.removed(mask);
        j - removed.iter().filter(|&&r| r < j).count()
    }

    /// Keeps the greatest gap of every flight under way.
    fn track_flights(&mut self, t: f64) {
        for k in 0..self.contacts.len() {
            let at = self.crossing(k, t);
            let c = &mut self.contacts[k];
            if let (Some(f), Some(g)) = (c.flight.as_mut(), c.gap) {
                if g.gap > f.greatest_gap {
                    f.greatest_gap = g.gap;
                    f.greatest_at = at;
                }
            }
        }
    }
}

/// What an output row is made from: the full model's state at time t
/// (the active integrator's, or its dense output inside a step), and the
/// active set's system with its own q and q̇ for the energy and drift.
struct Row<'r, 'm> {
    state: &'r FullState,
    t: f64,
    full: &'r System<'m>,
    sys: &'r System<'m>,
    /// q and q̇ of the active set's system.
    own_q: &'r [f64],
    own_qd: &'r [f64],
}

/// The run's output scratch and the places of its channels.
struct Fill<'r, 'm> {
    model: &'m Model,
    view: Contacts,
    points: &'r [PointOutput],
    scratch: Scratch,
    drift: DriftScratch,
    normal_at: Vec<Option<usize>>,
    /// Ends of the kinematic channels and of the dynamic ones.
    nk: usize,
    nd: usize,
}

impl Row<'_, '_> {
    /// Fills `values` at this state; `states` gives each unilateral
    /// contact's (open, gap).
    fn fill(
        &self,
        f: &mut Fill,
        contacts: &[Contact],
        states: impl Iterator<Item = (bool, Option<Gap>)>,
        values: &mut [f64],
    ) {
        let (nk, nd) = (f.nk, f.nd);
        run::fill_outputs(
            f.model,
            &self.full.asm,
            &f.view,
            self.state.view(),
            f.points,
            &mut values[..nk],
        );
        let forces = output::fill_forces(
            self.full,
            &mut f.scratch,
            &self.state.q,
            &self.state.qd,
            &self.state.lambda,
            self.t,
            &mut values[nk..nd],
        );
        // Energy and drift of the model in force: its potential includes
        // the compliant contacts' and an open joint's equations are released.
        values[nk + forces..nd].copy_from_slice(&output::energy_and_drift(
            self.sys,
            &mut f.drift,
            self.own_q,
            self.own_qd,
            self.t,
        ));
        for (k, (c, (open, gap))) in contacts.iter().zip(states).enumerate() {
            values[nd + 2 * k] = gap.map_or(0.0, |g| g.gap);
            values[nd + 2 * k + 1] = if open { 0.0 } else { 1.0 };
            // A compliant contact: its force, and closed while overlapping.
            if let (Some(law), Some(g), Some(at)) = (c.law.compliant, gap, f.normal_at[k]) {
                values[at] = law.force(-g.gap, -g.rate);
                values[nd + 2 * k + 1] = if g.gap < 0.0 { 1.0 } else { 0.0 };
            } else if let (Some(s), Some(at)) = (c.stop(), f.normal_at[k]) {
                // A rigid stop: −σλ while closed.
                let row = self.full.asm.rows_of(c.joint).start;
                values[at] = if open {
                    0.0
                } else {
                    s.push(self.state.lambda[row])
                };
            }
        }
    }
}

/// A run with unilateral contacts as the output loop drives it: steps
/// of h from the last landing or event, and the output scratch.
struct UnilateralRun<'a, 'r> {
    r: Run<'a>,
    fill: Fill<'r, 'a>,
    /// The state at the start of the step being taken.
    snap: Snapshot,
    h_max: f64,
    /// The active set of the step that holds the output time reached,
    /// when it lies inside that step.
    inside: Option<usize>,
}

impl run::Analysis for UnilateralRun<'_, '_> {
    fn reach(&mut self, t: f64, prev: Option<f64>, tick: &mut Tick) -> Result<(), AnalysisError> {
        let (r, h_max) = (&mut self.r, self.h_max);
        if prev.is_some() {
            // Steps of h from the last landing or event; one that would
            // land on t short of a whole step goes past it, keeping its
            // ends for the output there.
            let done = arrived_within(t, h_max);
            while t - r.it().state().t > done {
                tick()?;
                let left = t - r.it().state().t;
                r.hold = steps_over(left, h_max);
                let h = if r.hold {
                    h_max
                } else {
                    fixed_step(left, h_max)
                };
                r.step(h, &mut self.snap, tick)?;
                let now = r.it().state().t;
                r.track_flights(now);
            }
        }
        // Past t: the state there from the step that holds it.
        self.inside = if r.it().state().t - t > arrived_within(t, h_max) {
            r.dense_row(t)?
        } else {
            None
        };
        if self.inside.is_none() {
            r.pull()?;
        }
        Ok(())
    }

    fn fill(&mut self, t: f64, values: &mut [f64]) -> Result<(), AnalysisError> {
        let r = &mut self.r;
        if let Some(mask) = self.inside {
            let it = r.its[mask].as_ref().expect("integrator");
            let d = it.dense.as_ref().expect("dense output");
            let opens = (0..r.contacts.len()).map(|k| mask & (1 << k) != 0);
            let state = Row {
                state: &r.out,
                t,
                full: &r.full,
                sys: &it.sys,
                own_q: &d.q,
                own_qd: &d.qd,
            };
            let states = opens.zip(r.out_gaps.iter().copied());
            state.fill(&mut self.fill, &r.contacts, states, values);
            return Ok(());
        }
        let it = r.its[r.mask].as_ref().expect("integrator");
        let s = it.state();
        let state = Row {
            state: &r.state,
            t: s.t,
            full: &r.full,
            sys: &it.sys,
            own_q: &s.q,
            own_qd: &s.qd,
        };
        let states = r.contacts.iter().map(|c| (c.open, c.gap));
        state.fill(&mut self.fill, &r.contacts, states, values);
        Ok(())
    }
}

/// The time τ ∈ (0, h) where the cubic Hermite interpolant of g with
/// values and slopes [g₀, ġ₀, g₁, ġ₁] at 0 and h is least, when that
/// least value is negative and the ends are not.
fn hermite_dip(h: f64, [g0, d0, g1, d1]: [f64; 4]) -> Option<f64> {
    if !(g0 >= 0.0 && g1 >= 0.0 && d0 < 0.0 && d1 > 0.0) {
        return None;
    }
    // g(s) = a s³ + b s² + c s + d on s ∈ [0, 1], slopes scaled by h.
    let (m0, m1) = (d0 * h, d1 * h);
    let a = 2.0 * g0 + m0 - 2.0 * g1 + m1;
    let b = -3.0 * g0 - 2.0 * m0 + 3.0 * g1 - m1;
    let c = m0;
    let value = |s: f64| ((a * s + b) * s + c) * s + g0;
    // g′(s) = 3a s² + 2b s + c = 0 at a minimum (g″ = 6a s + 2b > 0);
    // the roots in the stable form q = −(b + sign(b) √(b² − 3ac)):
    // c/q and q/(3a).
    let disc = b * b - 3.0 * a * c;
    if disc < 0.0 {
        return None;
    }
    let q = -(b + b.signum() * disc.sqrt());
    let s = [c / q, q / (3.0 * a)]
        .into_iter()
        .filter(|s| s.is_finite() && *s > 0.0 && *s < 1.0 && 6.0 * a * s + 2.0 * b > 0.0)
        .fold(f64::NAN, f64::min);
    (s > 0.0 && s < 1.0 && value(s) < 0.0).then_some(s * h)
}

/// The time τ − t₀ ∈ (0, t₁ − t₀) where the parabola through (t_k, N_k),
/// k = −1, 0, 1, is least, when that least value is negative and the
/// three values are not.
fn parabola_dip([tm, t0, t1]: [f64; 3], [nm, n0, n1]: [f64; 3]) -> Option<f64> {
    if !(nm >= 0.0 && n0 >= 0.0 && n1 >= 0.0 && tm < t0 && t0 < t1) {
        return None;
    }
    // N(t) = N₀ + f₋₀ (t − t₀) + a (t − t₀)(t − t₋₁), divided differences.
    let f_m0 = (n0 - nm) / (t0 - tm);
    let f_01 = (n1 - n0) / (t1 - t0);
    let a = (f_01 - f_m0) / (t1 - tm);
    if a <= 0.0 {
        return None;
    }
    let tv = 0.5 * (t0 + tm) - f_m0 / (2.0 * a);
    let value = n0 + f_m0 * (tv - t0) + a * (tv - t0) * (tv - tm);
    (tv > t0 && tv < t1 && value < 0.0).then_some(tv - t0)
}

/// Forward dynamics of a model with unilateral contacts, output as
/// [`super::integrator::run`], with the channels `<joint>.gap` (m) and
/// `<joint>.state` (1 closed, 0 open) of every unilateral joint after the
/// others, and the flights and impacts in the summary.
pub fn run(
    model: &Model,
    times: &[f64],
    settings: &Settings,
    points: &[PointOutput],
    sink: &mut dyn Sink,
) -> Result<Summary, AnalysisError> {
    let t0 = times.first().copied().unwrap_or(0.0);
    if settings.adaptive.is_some() {
        return Err(AnalysisError::new(
            Kind::InvalidInput,
            t0,
            "the error-controlled mode (adaptive) is not available with unilateral \
             contacts: run with fixed steps h, the events being located to event_tol",
        ));
    }
    // Joint limits as stops: unilateral joints of the model run.
    let (expanded, stops) = stops::expand(model)?;
    let model = &expanded;
    let full = System::new(model);
    let (n, m) = (full.n(), full.m());
    let q0 = full.asm.initial_q(model);
    let mut qd0 = vec![0.0; n];
    for (id, b) in model.moving_bodies() {
        let c = full.asm.body_col(id.0).expect("moving body");
        qd0[c..c + 3].copy_from_slice(&b.qd0);
    }
    let t_span = times.iter().fold(0.0f64, |a, t| a.max(t.abs()));
    let contacts = contacts(model, &full, &q0, settings.step, t_span, &stops)?;
    let k = contacts.len();
    let all: Vec<usize> = contacts.iter().map(|c| c.joint).collect();
    let models: Vec<Model> = (0..1usize << k)
        .map(|mask| {
            let removed: Vec<usize> = (0..k)
                .filter(|b| mask & (1 << b) != 0)
                .map(|b| all[b])
                .collect();
            let mut m = without(model, &removed);
            // A compliant contact acts through its Hunt–Crossley force (a
            // compliant stop's is a force of the model already).
            for c in contacts.iter() {
                if let (Some(law), Watched::Curves(features)) = (c.law.compliant, &c.features) {
                    let force = CompliantContact {
                        bodies: c.bodies,
                        features: features.clone(),
                        law,
                    };
                    let name = format!("{}.contact", model.joints[c.joint].name);
                    m.add_force(Force::new(name, force));
                }
            }
            m
        })
        .collect();
    let mut r = Run {
        t0,
        full,
        models: &models,
        layouts: (0..1 << k).map(|_| None).collect(),
        its: (0..1 << k).map(|_| None).collect(),
        settings: settings.clone(),
        mask: 0,
        contacts,
        state: FullState {
            q: q0,
            qd: qd0,
            qdd: vec![0.0; n],
            lambda: vec![0.0; m],
        },
        lam_watch: vec![0.0; m],
        watch: (0..1 << k).map(|_| None).collect(),
        burst: (0, f64::NEG_INFINITY),
        rhs: Vec::new(),
        gaps: Vec::new(),
        n0: Vec::new(),
        gaps_lo: Vec::new(),
        hold: false,
        held: None,
        held_start: Snapshot::default(),
        held_end: Snapshot::default(),
        out: FullState::default(),
        out_gaps: Vec::new(),
        event_q: Vec::new(),
        event_qd: Vec::new(),
        summary: Summary::default(),
    };
    // Compliant contacts are always released; contacts apart at the given
    // placement start open, in flight.
    for c in 0..k {
        let (q, qd) = r.bodies(c);
        if r.contacts[c].law.compliant.is_some() {
            r.mask |= 1 << c;
            r.contacts[c].open = true;
        } else if r.contacts[c].gap(q, qd).gap > OPEN_AT_START {
            r.mask |= 1 << c;
            r.contacts[c].open = true;
            let at = r.crossing(c, t0);
            r.contacts[c].flight = Some(r.flight(c, at));
        }
    }
    r.its[r.mask] = Some(Integrator::starting_at(
        &models[r.mask],
        settings.clone(),
        t0,
    )?);
    r.pull()?;
    // A flight under way at the start has its greatest gap there so far.
    r.track_flights(t0);
    // A contact that pulls at the start opens at once.
    while let Some(Event::LiftOff(k)) = r.event() {
        r.lift_off(k)?;
    }
    let mut names = run::channels(model, points);
    let nk = names.len();
    names.extend(output::channels(model));
    let nd = names.len();
    for c in &r.contacts {
        let name = &model.joints[c.joint].name;
        // A revolute's stop (its push a moment) has an angle for its gap.
        let gap = match c.stop() {
            Some(s) if s.load == "moment" => Quantity::Angle,
            _ => Quantity::Length,
        };
        names.push(Channel::new(format!("{name}.gap"), gap));
        names.push(Channel::new(
            format!("{name}.state"),
            Quantity::Dimensionless,
        ));
    }
    for c in &r.contacts {
        if let Some(s) = c.stop() {
            let quantity = if s.load == "moment" {
                Quantity::Torque
            } else {
                Quantity::Force
            };
            names.push(Channel::new(
                format!("{}.{}", model.joints[c.joint].name, s.load),
                quantity,
            ));
        }
    }
    // Where each unilateral joint's normal force channel is: a stop's
    // push into its range.
    let normal_at: Vec<Option<usize>> = r
        .contacts
        .iter()
        .map(|c| {
            let kind = c.stop().map_or("normal_force", |s| s.load);
            let name = format!("{}.{kind}", model.joints[c.joint].name);
            names.iter().position(|n| n.name == name)
        })
        .collect();
    let fill = Fill {
        model,
        view: Contacts::new(model),
        points,
        scratch: Scratch::new(&r.full),
        drift: DriftScratch::new(m),
        normal_at,
        nk,
        nd,
    };
    let mut u = UnilateralRun {
        r,
        fill,
        snap: Snapshot::default(),
        h_max: settings.step,
        inside: None,
    };
    run::output_loop(&mut u, times, &names, sink)?;
    let mut r = u.r;
    // Flights under way at the end (a stop's time off its limit is no
    // flight), then the solver counts of every model.
    let mut summary = std::mem::take(&mut r.summary);
    for c in &mut r.contacts {
        if let Some(f) = c.flight.take() {
            summary.flights.push(f);
        }
    }
    let stop_names: Vec<&str> = r
        .contacts
        .iter()
        .filter(|c| c.stop().is_some())
        .map(|c| model.joints[c.joint].name.as_str())
        .collect();
    summary
        .flights
        .retain(|f| !stop_names.contains(&f.joint.as_str()));
    summary
        .flights
        .sort_by(|a, b| a.start.time.total_cmp(&b.start.time));
    for it in r.its.iter().flatten() {
        let s = &it.diagnostics().summary;
        summary.steps += s.steps;
        summary.newton_iterations += s.newton_iterations;
        summary.factorizations += s.factorizations;
        for w in &s.warnings {
            if !summary.warnings.contains(w) {
                summary.warnings.push(w.clone());
            }
        }
    }
    Ok(summary)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hermite_dip_finds_the_least_value_of_a_parabola() {
        // g(t) = (t − 0.3)² − 0.01 on [0, 1]: least −0.01 at 0.3, ends
        // positive, slopes −0.6 and 1.4. The cubic through these is g.
        let g = |t: f64| (t - 0.3) * (t - 0.3) - 0.01;
        let tau = hermite_dip(1.0, [g(0.0), -0.6, g(1.0), 1.4]).expect("a dip");
        assert!((tau - 0.3).abs() < 1e-12, "{tau}");
        // Shifted up by 0.02 it stays positive: no dip.
        assert_eq!(
            hermite_dip(1.0, [g(0.0) + 0.02, -0.6, g(1.0) + 0.02, 1.4]),
            None
        );
        // Rising at the start: not an approach.
        assert_eq!(hermite_dip(1.0, [0.1, 0.6, 0.1, 1.4]), None);
    }

    #[test]
    fn parabola_dip_finds_the_vertex_between_the_last_two_points() {
        // N(t) = 4 (t − 2.5)² − 1 through t = 1, 2, 3 (values 8, 0, 0):
        // vertex at 2.5, N = −1, inside the last step [2, 3].
        let n = |t: f64| 4.0 * (t - 2.5) * (t - 2.5) - 1.0;
        let tau = parabola_dip([1.0, 2.0, 3.0], [n(1.0), n(2.0), n(3.0)]).expect("a dip");
        assert!((tau - 0.5).abs() < 1e-12, "{tau}");
        // The vertex in the step before: not this step's.
        let m = |t: f64| 4.0 * (t - 1.5) * (t - 1.5) + 0.5;
        assert_eq!(
            parabola_dip([1.0, 2.0, 3.0], [m(1.0), m(2.0), m(3.0)]),
            None
        );
        // A vertex above zero: no dip.
        let p = |t: f64| 4.0 * (t - 2.5) * (t - 2.5) + 0.1;
        assert_eq!(
            parabola_dip([1.0, 2.0, 3.0], [p(1.0), p(2.0), p(3.0)]),
            None
        );
    }
}
