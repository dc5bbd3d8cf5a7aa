//! Which run settings each analysis takes, and how the settings of a run
//! follow from those given at the call, the file's `[analysis]` and the
//! defaults. A model file, the command line and the Python API all ask
//! here, so a setting means the same whichever way it came.

use camlink_core::dynamics::integrator::{Adaptive, Settings as IntegratorSettings};
use camlink_core::setting;

use crate::{AnalysisSpec, AnalysisType, DynamicsSpec};

/// The settings of the analyses that run over output times.
const GRID: [&str; 6] = ["t_end", "step", "times", "tol", "max_iter", "points"];

/// The settings of forward dynamics besides [`GRID`].
const INTEGRATOR: [&str; 7] = [
    "h",
    "rho_inf",
    "adaptive",
    "atol",
    "rtol",
    "h_min",
    "projection_tol",
];

/// The settings of the adaptive mode's error control: they need
/// `adaptive = true`.
pub const ERROR_CONTROL: [&str; 3] = ["atol", "rtol", "h_min"];

impl AnalysisType {
    /// Every analysis, in the order of the docs.
    pub const ALL: [AnalysisType; 4] = [
        AnalysisType::Kinematics,
        AnalysisType::InverseDynamics,
        AnalysisType::Equilibrium,
        AnalysisType::Dynamics,
    ];

    /// The analysis a file names `name` (`"inverse_dynamics"`…).
    pub fn from_name(name: &str) -> Option<AnalysisType> {
        AnalysisType::ALL.into_iter().find(|k| k.name() == name)
    }

    /// Whether this analysis takes the run setting `key` (an `[analysis]`
    /// key other than `type` and `output`).
    pub fn takes(self, key: &str) -> bool {
        let grid = GRID.contains(&key);
        match self {
            AnalysisType::Kinematics => grid || key == "jerk",
            AnalysisType::InverseDynamics => grid,
            AnalysisType::Equilibrium => ["time", "tol", "max_iter", "points"].contains(&key),
            AnalysisType::Dynamics => grid || INTEGRATOR.contains(&key),
        }
    }

    /// The run settings this analysis takes, in the order of the docs.
    pub fn settings(self) -> Vec<&'static str> {
        GRID.iter()
            .chain(["time", "jerk"].iter())
            .chain(INTEGRATOR.iter())
            .copied()
            .filter(|key| self.takes(key))
            .collect()
    }
}

/// The message for run setting `key` given to an analysis that does not
/// take it, `analysis` saying which one as the caller puts it (`the
/// kinematics analysis`, `type = "kinematics"`): it names the analyses
/// that take the key, e.g. "`rho_inf` does not apply to the kinematics
/// analysis (it is a setting of dynamics)".
pub fn not_applicable(key: &str, analysis: &str) -> String {
    let users: Vec<&str> = AnalysisType::ALL
        .into_iter()
        .filter(|k| k.takes(key))
        .map(AnalysisType::name)
        .collect();
    let hint = match users.split_last() {
        None => String::new(),
        Some((last, [])) => format!(" (it is a setting of {last})"),
        Some((last, rest)) => format!(" (it is a setting of {} and {last})", rest.join(", ")),
    };
    format!("`{key}` does not apply to {analysis}{hint}")
}

/// The message for an error-control setting `key` given without the
/// adaptive mode.
pub fn needs_adaptive(key: &str) -> String {
    format!("`{key}` sets the error control: it needs adaptive = true")
}

/// Forward-dynamics settings given at a call (Python arguments, command-line
/// options); each `None` takes the file's `[analysis]` value, else the
/// default.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DynamicsArgs {
    /// Output step (s), for the default integration step.
    pub step: Option<f64>,
    /// Integration step (s), the largest one when adaptive.
    pub h: Option<f64>,
    pub rho_inf: Option<f64>,
    pub adaptive: Option<bool>,
    /// Error control (m or rad, relative, s); only with the adaptive mode.
    pub atol: Option<f64>,
    pub rtol: Option<f64>,
    pub h_min: Option<f64>,
    /// Tolerance of the initial position projection (m or rad).
    pub projection_tol: Option<f64>,
    /// Newton tolerance on the corrections of q and q̇, and most iterations.
    pub tol: Option<f64>,
    pub max_iter: Option<usize>,
}

/// A run setting that breaks its rule: the key and what is wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct SettingError {
    pub key: &'static str,
    pub message: String,
}

impl DynamicsSpec {
    /// The integration step (s): `h`, else the output step `step` but at
    /// most [`DynamicsSpec::DEFAULT_H`], else `DEFAULT_H`.
    pub fn integration_step(h: Option<f64>, step: Option<f64>) -> f64 {
        h.unwrap_or_else(|| step.map_or(Self::DEFAULT_H, |s| s.min(Self::DEFAULT_H)))
    }
}

impl AnalysisSpec {
    /// The output step (s) when none is given: a hundredth of the end
    /// time `t_end` (s), or 1 s for a run that ends where it starts.
    pub fn default_step(t_end: f64) -> f64 {
        if t_end > 0.0 {
            t_end / 100.0
        } else {
            1.0
        }
    }

    /// The Newton tolerance and most iterations of a `kind` run: `tol` and
    /// `max_iter` if given, else the file's, else the defaults of `kind`.
    pub fn solver(
        &self,
        kind: AnalysisType,
        tol: Option<f64>,
        max_iter: Option<usize>,
    ) -> (f64, usize) {
        (
            tol.unwrap_or_else(|| self.tol_for(kind)),
            max_iter.unwrap_or_else(|| self.max_iter_for(kind)),
        )
    }

    /// The integrator settings of a forward-dynamics run given `args`
    /// (see [`DynamicsArgs`]), each checked by its rule
    /// ([`camlink_core::setting`]); error-control settings need the
    /// adaptive mode.
    pub fn integrator_settings_with(
        &self,
        args: &DynamicsArgs,
    ) -> Result<IntegratorSettings, SettingError> {
        let d = &self.dynamics;
        let check = |key: &'static str, v: f64| {
            setting::check(key, v).map_err(|message| SettingError { key, message })
        };
        let adaptive = args.adaptive.unwrap_or(d.adaptive.is_some());
        let given = [args.atol, args.rtol, args.h_min];
        if !adaptive {
            if let Some(k) = given.iter().position(Option::is_some) {
                let key = ERROR_CONTROL[k];
                return Err(SettingError {
                    key,
                    message: needs_adaptive(key),
                });
            }
        }
        let step = DynamicsSpec::integration_step(args.h.or(d.h), args.step.or(self.step));
        check("h", step)?;
        let rho_inf = args.rho_inf.unwrap_or(d.rho_inf);
        check("rho_inf", rho_inf)?;
        let projection_tol = args.projection_tol.unwrap_or(d.projection_tol);
        check("projection_tol", projection_tol)?;
        let (tol, max_iter) = self.solver(AnalysisType::Dynamics, args.tol, args.max_iter);
        check("tol", tol)?;
        check("max_iter", max_iter as f64)?;
        let adaptive = if adaptive {
            let file = d.adaptive.clone().unwrap_or(Adaptive {
                atol: DynamicsSpec::DEFAULT_ATOL,
                rtol: DynamicsSpec::DEFAULT_RTOL,
                h_min: DynamicsSpec::DEFAULT_H_MIN,
            });
            let atol = args.atol.unwrap_or(file.atol);
            let rtol = args.rtol.unwrap_or(file.rtol);
            setting::check_error_control(atol, rtol).map_err(|message| SettingError {
                key: "atol",
                message,
            })?;
            let h_min = args.h_min.unwrap_or(file.h_min);
            check("h_min", h_min)?;
            Some(Adaptive { atol, rtol, h_min })
        } else {
            None
        };
        Ok(IntegratorSettings {
            step,
            rho_inf,
            tol,
            max_iter,
            projection_tol,
            adaptive,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_analysis_takes_its_settings() {
        use AnalysisType::*;
        assert_eq!(
            Kinematics.settings(),
            ["t_end", "step", "times", "tol", "max_iter", "points", "jerk"]
        );
        assert_eq!(
            Equilibrium.settings(),
            ["tol", "max_iter", "points", "time"]
        );
        assert!(Dynamics.takes("atol") && !InverseDynamics.takes("h"));
        assert_eq!(
            not_applicable("t_end", "the equilibrium analysis"),
            "`t_end` does not apply to the equilibrium analysis \
             (it is a setting of kinematics, inverse_dynamics and dynamics)"
        );
        assert_eq!(
            not_applicable("time", "type = \"dynamics\""),
            "`time` does not apply to type = \"dynamics\" (it is a setting of equilibrium)"
        );
        assert_eq!(
            not_applicable("colour", "x"),
            "`colour` does not apply to x"
        );
        for k in AnalysisType::ALL {
            assert_eq!(AnalysisType::from_name(k.name()), Some(k));
        }
    }

    #[test]
    fn the_default_output_step_is_a_hundredth_of_the_run() {
        assert_eq!(AnalysisSpec::default_step(2.0), 0.02);
        assert_eq!(AnalysisSpec::default_step(0.0), 1.0);
    }

    #[test]
    fn the_default_step_follows_the_output_step_up_to_a_millisecond() {
        assert_eq!(DynamicsSpec::integration_step(None, None), 1e-3);
        assert_eq!(DynamicsSpec::integration_step(None, Some(0.01)), 1e-3);
        assert_eq!(DynamicsSpec::integration_step(None, Some(2e-4)), 2e-4);
        assert_eq!(DynamicsSpec::integration_step(Some(0.05), Some(2e-4)), 0.05);
    }

    #[test]
    fn call_settings_override_the_file_and_error_control_needs_adaptive() {
        let spec = AnalysisSpec {
            kind: AnalysisType::Dynamics,
            step: Some(5e-4),
            ..AnalysisSpec::default()
        };
        let s = spec
            .integrator_settings_with(&DynamicsArgs::default())
            .unwrap();
        assert_eq!(s, spec.integrator_settings());
        assert_eq!(s.step, 5e-4);
        let args = DynamicsArgs {
            rtol: Some(1e-3),
            ..DynamicsArgs::default()
        };
        let e = spec.integrator_settings_with(&args).unwrap_err();
        assert_eq!(e.key, "rtol");
        assert_eq!(
            e.message,
            "`rtol` sets the error control: it needs adaptive = true"
        );
        let args = DynamicsArgs {
            adaptive: Some(true),
            rtol: Some(1e-3),
            ..DynamicsArgs::default()
        };
        let a = spec
            .integrator_settings_with(&args)
            .unwrap()
            .adaptive
            .unwrap();
        assert_eq!(
            (a.atol, a.rtol, a.h_min),
            (
                DynamicsSpec::DEFAULT_ATOL,
                1e-3,
                DynamicsSpec::DEFAULT_H_MIN
            )
        );
        let args = DynamicsArgs {
            adaptive: Some(true),
            atol: Some(0.0),
            ..DynamicsArgs::default()
        };
        assert_eq!(
            spec.integrator_settings_with(&args).unwrap_err().key,
            "atol"
        );
        let args = DynamicsArgs {
            rho_inf: Some(1.5),
            ..DynamicsArgs::default()
        };
        assert_eq!(
            spec.integrator_settings_with(&args).unwrap_err().key,
            "rho_inf"
        );
    }
}
