//! `[[forces]]`: applied forces, as written in the file.

use schemars::JsonSchema;
use serde::Deserialize;

use super::{Num, PointRef};

/// `[[forces]]`: an applied force, selected by `type`. Magnitudes are
/// numbers or expressions of time `t` (s); those of `point_force` and
/// `torque` may also read the motion of the bodies they act on (a force
/// of state: docs/forces-of-state.md).
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ForceSpec {
    /// A force (fx, fy) at a body point: global components, or body-frame
    /// components (turning with the body) when `local = true`.
    PointForce {
        /// Unique force name; default `<type>_<index>`.
        #[serde(default)]
        name: Option<String>,
        body: String,
        /// Point of application; default the body origin.
        #[serde(default)]
        point: Option<PointRef>,
        /// f_x(t) (N); default 0.
        #[serde(default)]
        fx: Option<Num>,
        /// f_y(t) (N); default 0.
        #[serde(default)]
        fy: Option<Num>,
        /// Components in the body frame instead of the global frame; default false.
        #[serde(default)]
        local: bool,
        /// The body that takes the reaction −F (at `reaction_point`); default
        /// none (the ground). Its motion may be read by the expressions.
        #[serde(default)]
        reaction: Option<String>,
        /// Where −F acts on the reaction body; needed with `reaction` and a
        /// force.
        #[serde(default)]
        reaction_point: Option<PointRef>,
    },
    /// A pure torque T(t) on a body (N·m, counter-clockwise positive).
    Torque {
        #[serde(default)]
        name: Option<String>,
        body: String,
        /// T (N·m): of time, or of the motion of the bodies it acts on.
        torque: Num,
        /// The body that takes the reaction −T; default none (the ground).
        /// Its motion may be read by the expression.
        #[serde(default)]
        reaction: Option<String>,
    },
    /// Translational spring–damper–actuator between `point_i` and
    /// `point_j`: tension f = k (l − l₀) + c l̇ + f_a(t), pulling the points
    /// together when positive.
    Tsda {
        #[serde(default)]
        name: Option<String>,
        body_i: String,
        #[serde(default)]
        point_i: Option<PointRef>,
        body_j: String,
        #[serde(default)]
        point_j: Option<PointRef>,
        /// k (N/m), ≥ 0; default 0.
        #[serde(default)]
        stiffness: Option<Num>,
        /// l₀ (m), ≥ 0; default: the initial distance.
        #[serde(default)]
        free_length: Option<Num>,
        /// c (N·s/m), ≥ 0; default 0.
        #[serde(default)]
        damping: Option<Num>,
        /// f_a(t) (N), tension positive; default 0.
        #[serde(default)]
        actuator: Option<Num>,
    },
    /// Rotational spring–damper–actuator between two bodies: with
    /// θ = φ_j − φ_i, T = k (θ − θ₀) + c θ̇ + T_a(t) acts as +T on body i and
    /// −T on body j. With only `damping` it is viscous friction in a
    /// revolute joint between the bodies.
    Rsda {
        #[serde(default)]
        name: Option<String>,
        body_i: String,
        body_j: String,
        /// k (N·m/rad), ≥ 0; default 0.
        #[serde(default)]
        stiffness: Option<Num>,
        /// θ₀ (rad); default: the initial φ_j − φ_i.
        #[serde(default)]
        free_angle: Option<Num>,
        /// c (N·m·s/rad), ≥ 0; default 0.
        #[serde(default)]
        damping: Option<Num>,
        /// T_a(t) (N·m); default 0.
        #[serde(default)]
        actuator: Option<Num>,
    },
    /// Viscous friction in a revolute or translational joint, named by
    /// `joint`: a torque −c θ̇ against the relative turning of a revolute
    /// (an RSDA with only damping), a force −c ṡ against the sliding of a
    /// translational joint, acting at its point on body j.
    ViscousFriction {
        #[serde(default)]
        name: Option<String>,
        /// The revolute or translational joint.
        joint: String,
        /// c, ≥ 0: N·m·s/rad for a revolute, N·s/m for a translational.
        damping: Num,
    },
}
