//! Forward dynamics of a model with output at given times.
//!
//! The equations M(q) q̈ + Φ_qᵀλ = Q(q, q̇, t), Φ(q, t) = 0 are integrated
//! by the implicit index-3 generalized-α method of
//! [`super::generalized_alpha`] ([`Integrator`]). A model with unilateral
//! contacts or joint stops runs through [`super::unilateral`], a layer of
//! events (lift-off, flight, impact, end stops) over that integrator; any
//! other runs on one integrator here. Both write the same channels
//! ([`super::output`]) and the run's drift ([`super::drift`]).

pub use super::generalized_alpha::{Adaptive, Coeffs, Dense, Integrator, Settings, Snapshot};

use super::contact_force::LiftOffWatch;
use super::output::{self, Scratch};
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
    let mut it = Integrator::starting_at(model, settings.clone(), t0)?;
    let contacts = crate::contact::Contacts::new(model);
    let mut names = run::channels(model, points);
    let nk = names.len();
    names.extend(output::channels(model));
    sink.begin(&names);
    let mut lift_off = LiftOffWatch::new(model, &names);
    let mut values = vec![0.0; names.len()];
    let mut scratch = Scratch::new(&it.sys);
    let mut h_next = settings.step;
    let mut lambda = vec![0.0; it.sys.m()];
    for (k, &t) in times.iter().enumerate() {
        let mut inside = false;
        if k > 0 {
            run::check_next_time(Some(times[k - 1]), t)?;
            inside =
                it.advance_to_output(t, &mut h_next, &mut || sink.tick().map_err(|s| s.at(t)))?;
        }
        // An output time inside a step: the state there, its multipliers
        // of minimum norm ([`Integrator::dense_output`]).
        if let (true, Some(d)) = (inside, &it.dense) {
            run::fill_outputs(
                model,
                &it.sys.asm,
                &contacts,
                [&d.q, &d.qd, &d.qdd],
                points,
                &mut values[..nk],
            );
            let (q, qd, lam) = (&d.q, &d.qd, &d.lambda);
            output::fill(&it.sys, &mut scratch, q, qd, lam, d.t, &mut values[nk..]);
            sink.row(t, &values).map_err(|s| s.at(t))?;
            lift_off.observe(t, &values);
            continue;
        }
        run::fill_outputs(
            model,
            &it.sys.asm,
            &contacts,
            [&it.q, &it.qd, &it.qdd],
            points,
            &mut values[..nk],
        );
        // Reactions of a redundant model: the minimum-norm split.
        if it.redundant.is_some() {
            it.min_norm_multipliers(&mut lambda)?;
        } else {
            lambda.copy_from_slice(&it.lambda);
        }
        output::fill(
            &it.sys,
            &mut scratch,
            &it.q,
            &it.qd,
            &lambda,
            it.t,
            &mut values[nk..],
        );
        sink.row(t, &values).map_err(|s| s.at(t))?;
        lift_off.observe(t, &values);
    }
    let mut summary = it.summary.clone();
    lift_off.report(&mut summary);
    Ok(summary)
}
