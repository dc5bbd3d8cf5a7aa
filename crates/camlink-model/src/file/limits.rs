//! `limits` of a joint: end stops on its coordinate, as written in the
//! file (`docs/model-files.md`, "Joint limits").

use schemars::JsonSchema;
use serde::Deserialize;

use super::Num;

/// End stops on the joint's coordinate: a `revolute`'s angle
/// θ = φ_j − φ_i (rad), a `translational` joint's stroke (m, point_j from
/// point_i along the axis) or a `revolute_translational` pin's travel
/// along its line (m, from point_j). Forward dynamics stops the joint at
/// each limit given (rigid stops with restitution, or compliant ones with
/// a stiffness); kinematics warns when a driven motion leaves the range.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LimitsSpec {
    /// The least value (rad or m); omit for no stop below.
    #[serde(default)]
    pub lower: Option<Num>,
    /// The greatest value (rad or m), above `lower`; omit for no stop above.
    #[serde(default)]
    pub upper: Option<Num>,
    /// Coefficient of restitution e of a rigid stop, 0 (plastic, the
    /// default) to 1 (elastic): the joint leaves the stop at e times its
    /// approach speed.
    #[serde(default)]
    pub restitution: Option<Num>,
    /// Approach speed (rad/s or m/s) below which an impact on a rigid stop
    /// is plastic and the joint rests on it; default 1e-3.
    #[serde(default)]
    pub rest_speed: Option<Num>,
    /// Time tolerance (s) of the located impact and release events;
    /// default 1e-9.
    #[serde(default)]
    pub event_tol: Option<Num>,
    /// Stiffness k of a compliant stop (N·m/radⁿ for an angle, N/mⁿ for a
    /// stroke): a Hunt–Crossley force k δⁿ (1 + c δ̇) from the penetration
    /// δ past the limit instead of impacts.
    #[serde(default)]
    pub stiffness: Option<Num>,
    /// Exponent n of a compliant stop; default 1.5.
    #[serde(default)]
    pub exponent: Option<Num>,
    /// Damping factor c of a compliant stop (s/rad or s/m); default 0.
    #[serde(default)]
    pub damping: Option<Num>,
}
