//! `[machine]`: what a machine designer sizes from one cycle at the design
//! speed (`docs/machine.md`), as written in the file.

use schemars::JsonSchema;
use serde::Deserialize;

use super::{Num, Vec2};

/// `[machine]`: the input driver and its design speed, the flywheel's
/// speed band, the point the shaking moment is taken about, and the motor.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MachineSection {
    /// The input: a `revolute_angle` driver of a joint to the ground.
    pub driver: String,
    /// Design speed ω of the driven angle (rad/s), > 0; e.g. "2*pi*10"
    /// for 600 rpm.
    pub speed: Num,
    /// Coefficient of speed fluctuation C_s = (ω_max − ω_min)/ω the
    /// flywheel keeps to, > 0 (e.g. 0.02); omit for no flywheel.
    #[serde(default)]
    pub speed_band: Option<Num>,
    /// Samples per cycle, ≥ 8; default 360.
    #[serde(default)]
    pub steps: Option<usize>,
    /// The point [x, y] (m, global frame) the shaking moment is taken
    /// about; default the origin.
    #[serde(default)]
    pub moment_point: Option<Vec2>,
    /// Size the counterweights that fully balance the shaking force of a
    /// four-bar or slider-crank; default true.
    #[serde(default)]
    pub balance: Option<bool>,
    /// The motor and its gear.
    #[serde(default)]
    pub motor: Option<MotorSection>,
}

/// `[machine.motor]`: the motor's torque–speed curve and its gear.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MotorSection {
    /// The torque the motor can give at its shaft speed: pairs
    /// [speed (rad/s), torque (N·m)], speeds increasing, linear between.
    pub curve: Vec<Vec2>,
    /// n = ω_motor / ω_input, > 0; default 1 (direct drive).
    #[serde(default)]
    pub gear_ratio: Option<Num>,
    /// Continuous (rated) torque (N·m) the RMS torque is held to.
    #[serde(default)]
    pub rated_torque: Option<Num>,
    /// Rated power (W) the peak power is held to.
    #[serde(default)]
    pub rated_power: Option<Num>,
}
