//! camlink studies: many variants of one model, run in parallel.
//!
//! [`run_batch`] takes a loaded model, a list of parameter sets and the
//! outputs to keep ([`Reduction`]s); it builds each variant with
//! [`Loaded::with_parameters`], runs the model file's `[analysis]` on it
//! and folds the rows into the outputs as they are computed, on all cores
//! (rayon). Each variant ends as a [`Outcome`]: its outputs, or the
//! error that stopped it; one failing variant never stops the others.

#![warn(unreachable_pub)]

mod analysis;
pub mod declaration;
pub mod reduce;

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use camlink_model::Loaded;
use rayon::prelude::*;

pub use analysis::run_file_analysis;
pub use reduce::{Reducer, Reduction};

/// How a variant ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Every output computed.
    Ok,
    /// The parameters do not give a valid model (a point that cannot be
    /// resolved, a value out of range).
    ModelError,
    /// The analysis could not proceed (no assembly, no convergence, a
    /// singular Jacobian, the time limit).
    AnalysisError,
    /// An output cannot be computed (a channel the run lacks, a time
    /// outside the run).
    OutputError,
    /// A bug in camlink (a caught panic).
    InternalError,
    /// The batch was stopped before the variant finished
    /// ([`BatchSettings::stop`]); its outcome is not a result.
    Stopped,
}

impl Status {
    /// The statuses a variant's row of study results can hold: every one
    /// but [`Status::Stopped`], whose outcome is not a result.
    pub const RESULTS: [Status; 5] = [
        Status::Ok,
        Status::ModelError,
        Status::AnalysisError,
        Status::OutputError,
        Status::InternalError,
    ];

    /// The stable name written into study results.
    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::ModelError => "model_error",
            Status::AnalysisError => "analysis_error",
            Status::OutputError => "output_error",
            Status::InternalError => "internal_error",
            Status::Stopped => "stopped",
        }
    }
}

/// The outcome of one variant.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// One value per output, in declaration order; NaN where not computed.
    pub values: Vec<f64>,
    pub status: Status,
    /// What went wrong (empty when `status` is `Ok`).
    pub error: String,
}

/// Execution settings of a batch.
#[derive(Clone, Debug, Default)]
pub struct BatchSettings {
    /// Threads to use; `None`: all cores (rayon's global pool).
    pub threads: Option<usize>,
    /// Wall time allowed per variant; a variant past it is stopped and
    /// recorded as an analysis error.
    pub time_limit: Option<Duration>,
    /// Set from another thread to stop the batch (Ctrl-C): the runs going
    /// on stop at their next step and the variants not started are skipped,
    /// each recorded as [`Status::Stopped`].
    pub stop: Option<Arc<AtomicBool>>,
}

/// Runs every parameter set of `variants` (name, value pairs) on `base`
/// and reduces each run to `outputs`; the outcomes come back in the order
/// of `variants`.
pub fn run_batch(
    base: &Loaded,
    variants: &[Vec<(String, f64)>],
    outputs: &[(String, Reduction)],
    settings: &BatchSettings,
) -> Result<Vec<Outcome>, String> {
    let work = || {
        variants
            .par_iter()
            .with_max_len(1)
            .map(|v| run_one(base, v, outputs, settings))
            .collect()
    };
    match settings.threads {
        None => Ok(work()),
        Some(n) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n.max(1))
                .build()
                .map_err(|e| format!("cannot start {n} threads: {e}"))?;
            Ok(pool.install(work))
        }
    }
}

/// One variant, a panic included, as an [`Outcome`].
pub(crate) fn run_one(
    base: &Loaded,
    values: &[(String, f64)],
    outputs: &[(String, Reduction)],
    settings: &BatchSettings,
) -> Outcome {
    let failed = |status: Status, error: String| Outcome {
        values: vec![f64::NAN; outputs.len()],
        status,
        error,
    };
    let stopped = || {
        settings
            .stop
            .as_ref()
            .is_some_and(|s| s.load(Ordering::Relaxed))
    };
    if stopped() {
        return failed(Status::Stopped, "the batch was stopped".into());
    }
    let result = catch_unwind(AssertUnwindSafe(|| {
        let model = match base.with_parameters(values) {
            Ok(m) => m,
            Err(e) => return failed(Status::ModelError, e.to_string()),
        };
        let deadline = settings.time_limit.map(|d| Instant::now() + d);
        let mut reducer = Reducer::new(outputs, deadline, settings.stop.clone());
        let summary = match run_file_analysis(&model, &mut reducer) {
            Ok(s) => s,
            Err(e) => {
                return match reducer.missing() {
                    _ if stopped() => failed(Status::Stopped, "the batch was stopped".into()),
                    Some(m) => failed(Status::OutputError, m.to_string()),
                    None => failed(Status::AnalysisError, e),
                };
            }
        };
        match reducer.finish(&summary) {
            Ok(values) => Outcome {
                values,
                status: Status::Ok,
                error: String::new(),
            },
            Err(e) => failed(Status::OutputError, e),
        }
    }));
    result.unwrap_or_else(|payload| {
        let what = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".to_string());
        failed(Status::InternalError, format!("internal error: {what}"))
    })
}

#[cfg(test)]
mod tests {
    use super::Status;

    #[test]
    fn the_result_statuses_are_every_status_but_stopped() {
        // A new status fails to compile here until it is placed.
        let written = |s: Status| match s {
            Status::Ok
            | Status::ModelError
            | Status::AnalysisError
            | Status::OutputError
            | Status::InternalError => true,
            Status::Stopped => false,
        };
        let all = [
            Status::Ok,
            Status::ModelError,
            Status::AnalysisError,
            Status::OutputError,
            Status::InternalError,
            Status::Stopped,
        ];
        let want: Vec<Status> = all.into_iter().filter(|&s| written(s)).collect();
        assert_eq!(Status::RESULTS.to_vec(), want);
    }
}
