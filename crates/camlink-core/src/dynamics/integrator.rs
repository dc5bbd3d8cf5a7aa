//! Forward dynamics of a model with output at given times.
//!
//! The equations M(q) q̈ + Φ_qᵀλ = Q(q, q̇, t), Φ(q, t) = 0 are integrated
//! by the implicit index-3 generalized-α method of
//! [`super::generalized_alpha`] ([`Integrator`]). A model with unilateral
//! contacts or joint stops runs through [`super::unilateral`], a layer of
//! events (lift-off, flight, impact, end stops) over that integrator; any
//! other runs on one integrator here. Both write the same channels
//! ([`super::output`]) and the run's drift ([`super::drift`]).

pub use super::generalized_alpha::{
    Adaptive, Coeffs, Dense, Diagnostics, Integrator, Settings, Snapshot, State,
};

use super::contact_force::LiftOffWatch;
use super::output::{self, Scratch};
use crate::contact::Contacts;
use crate::model::Model;
use crate::run::{self, AnalysisError, PointOutput, Sink, Summary};

/// `settings` for a run with output at `times`: a fixed step, or the
/// largest step of the error control, longer than the longest output
/// interval is cut to it (steps between output times, landing on them,
/// rather than one step past many; a first trial step of the error control
/// that fails is then shortened like any other).
fn on_output_times(settings: &Settings, times: &[f64]) -> Settings {
    let longest = times.windows(2).map(|w| w[1] - w[0]).fold(0.0f64, f64::max);
    let mut s = settings.clone();
    // (A step that is not a number stays one, for the check of the step.)
    if longest > 0.0 && s.step > longest {
        s.step = longest;
    }
    s
}

/// Forward dynamics with output at `times` (increasing; the first is the
/// start time): the kinematic channels, then reactions, driver efforts,
/// energy and drift ([`super::output`]). Rows reach `sink` as each output
/// time is reached, so a run that fails keeps everything before.
pub fn run(
    model: &Model,
    times: &[f64],
    settings: &Settings,
    points: &[PointOutput],
    sink: &mut dyn Sink,
) -> Result<Summary, AnalysisError> {
    let mut watch = super::drift::DriftWatch::new(sink);
    let settings = &on_output_times(settings, times);
    let mut summary =
        if model.joints.iter().any(|j| j.unilateral.is_some()) || super::stops::any(model) {
            super::unilateral::run(model, times, settings, points, &mut watch)?
        } else {
            run_bilateral(model, times, settings, points, &mut watch)?
        };
    summary.drift = watch.drift();
    Ok(summary)
}

/// [`run`] of a model without unilateral contacts or joint stops.
fn run_bilateral(
    model: &Model,
    times: &[f64],
    settings: &Settings,
    points: &[PointOutput],
    sink: &mut dyn Sink,
) -> Result<Summary, AnalysisError> {
    let t0 = times.first().copied().unwrap_or(0.0);
    let it = Integrator::starting_at(model, settings.clone(), t0)?;
    let mut names = run::channels(model, points);
    let nk = names.len();
    names.extend(output::channels(model));
    let mut r = BilateralRun {
        model,
        points,
        nk,
        contacts: Contacts::new(model),
        lift_off: LiftOffWatch::new(model, &names),
        scratch: Scratch::new(&it.sys),
        h_next: settings.step,
        lambda: vec![0.0; it.sys.m()],
        inside: false,
        it,
    };
    run::output_loop(&mut r, times, &names, sink)?;
    let mut summary = r.it.diagnostics().summary.clone();
    r.lift_off.report(&mut summary);
    Ok(summary)
}

/// A forward-dynamics run without unilateral contacts or joint stops as
/// the output loop drives it.
struct BilateralRun<'a, 'm> {
    model: &'m Model,
    points: &'a [PointOutput],
    /// The number of kinematic channels, before the dynamic ones.
    nk: usize,
    contacts: Contacts,
    lift_off: LiftOffWatch,
    scratch: Scratch,
    /// The next step of the error control (s).
    h_next: f64,
    /// The multipliers of a row.
    lambda: Vec<f64>,
    /// Whether the output time reached lies inside the last step.
    inside: bool,
    it: Integrator<'m>,
}

impl run::Analysis for BilateralRun<'_, '_> {
    fn reach(
        &mut self,
        t: f64,
        prev: Option<f64>,
        tick: &mut run::Tick,
    ) -> Result<(), AnalysisError> {
        self.inside = prev.is_some() && self.it.advance_to_output(t, &mut self.h_next, tick)?;
        Ok(())
    }

    fn fill(&mut self, _t: f64, values: &mut [f64]) -> Result<(), AnalysisError> {
        let (it, nk) = (&mut self.it, self.nk);
        let (model, asm) = (self.model, &it.sys.asm);
        // An output time inside a step: the state there, its multipliers
        // of minimum norm ([`Integrator::dense_output`]).
        if let (true, Some(d)) = (self.inside, &it.dense) {
            run::fill_outputs(
                model,
                asm,
                &self.contacts,
                d.view(),
                self.points,
                &mut values[..nk],
            );
            output::fill(
                &it.sys,
                &mut self.scratch,
                &d.q,
                &d.qd,
                &d.lambda,
                d.t,
                &mut values[nk..],
            );
            return Ok(());
        }
        run::fill_outputs(
            model,
            asm,
            &self.contacts,
            it.state().view(),
            self.points,
            &mut values[..nk],
        );
        // Reactions of a redundant model: the minimum-norm split.
        if it.redundant.is_some() {
            it.min_norm_multipliers(&mut self.lambda)?;
        } else {
            self.lambda.copy_from_slice(&it.state().lambda);
        }
        let s = it.state();
        output::fill(
            &it.sys,
            &mut self.scratch,
            &s.q,
            &s.qd,
            &self.lambda,
            s.t,
            &mut values[nk..],
        );
        Ok(())
    }

    fn observe(&mut self, t: f64, values: &[f64]) {
        self.lift_off.observe(t, values);
    }
}
