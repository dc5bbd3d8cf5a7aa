//! `[machine]` evaluated and checked against the model: the input driver
//! exists and turns a link against the ground, the speed and the band are
//! positive, the motor curve is well formed and reaches the motor speed.

use std::collections::HashMap;

use camlink_core::constraint::relative::RelCoord;
use camlink_core::fmt_num::num;
use camlink_core::machine::{Motor, Spec};
use camlink_core::{Constraint, Model};

use super::{fail, parameters, R};
use crate::error::did_you_mean;
use crate::eval;
use crate::file::{ModelFile, Num, Vec2};

fn value(n: &Num, params: &HashMap<String, f64>, path: &str) -> R<f64> {
    let v = match n {
        Num::Value(v) => *v,
        Num::Expr(src) => eval::constant(src, params).or_else(|e| fail(path, e))?,
    };
    if !v.is_finite() {
        return fail(path, format!("value is not a finite number ({})", num(v)));
    }
    Ok(v)
}

fn positive(n: &Num, params: &HashMap<String, f64>, path: &str, what: &str) -> R<f64> {
    let v = value(n, params, path)?;
    if v <= 0.0 {
        return fail(path, format!("{what} must be positive ({})", num(v)));
    }
    Ok(v)
}

fn pair(v: &Vec2, params: &HashMap<String, f64>, path: &str) -> R<[f64; 2]> {
    Ok([
        value(&v.0[0], params, &format!("{path}[0]"))?,
        value(&v.0[1], params, &format!("{path}[1]"))?,
    ])
}

/// The `[machine]` table of `file` for `model`, or `None` without one.
pub(crate) fn machine(file: &ModelFile, model: &Model) -> R<Option<Spec>> {
    let Some(m) = &file.machine else {
        return Ok(None);
    };
    let params = parameters(&file.parameters)?;
    let drivers = || {
        model
            .joints
            .iter()
            .filter(|j| j.driver)
            .map(|j| j.name.as_str())
    };
    let Some(d) = model.joints.iter().find(|j| j.driver && j.name == m.driver) else {
        return fail(
            "machine.driver",
            format!(
                "no driver named '{}'{}",
                m.driver,
                did_you_mean(&m.driver, drivers())
            ),
        );
    };
    let turns = matches!(&d.constraint, Constraint::RelativeCoord(rc)
        if rc.coord == RelCoord::Phi && (rc.body_i.is_ground() || rc.body_j.is_ground()));
    if !turns {
        return fail(
            "machine.driver",
            format!(
                "driver '{}' must turn a link against the ground (a revolute_angle driver of a \
                 revolute joint to the ground)",
                m.driver
            ),
        );
    }
    let speed = positive(
        &m.speed,
        &params,
        "machine.speed",
        "the design speed (rad/s)",
    )?;
    let speed_band = match &m.speed_band {
        None => None,
        Some(n) => {
            let cs = value(n, &params, "machine.speed_band")?;
            if cs <= 0.0 {
                return fail(
                    "machine.speed_band",
                    format!(
                        "the coefficient of speed fluctuation is {}: a band of zero or less needs \
                         an infinite flywheel; give C_s > 0, e.g. 0.02 for ±1 %",
                        num(cs)
                    ),
                );
            }
            Some(cs)
        }
    };
    let steps = m.steps.unwrap_or(Spec::DEFAULT_STEPS);
    if steps < 8 {
        return fail(
            "machine.steps",
            format!("{steps} samples per cycle: give at least 8"),
        );
    }
    let point = match &m.moment_point {
        Some(v) => pair(v, &params, "machine.moment_point")?,
        None => [0.0, 0.0],
    };
    let motor = match &m.motor {
        None => None,
        Some(mo) => {
            let gear = match &mo.gear_ratio {
                Some(n) => positive(n, &params, "machine.motor.gear_ratio", "the gear ratio")?,
                None => 1.0,
            };
            let mut curve = Vec::new();
            for (k, p) in mo.curve.iter().enumerate() {
                let path = format!("machine.motor.curve[{k}]");
                let [w, t] = pair(p, &params, &path)?;
                if w < 0.0 || t < 0.0 {
                    return fail(path, "speed (rad/s) and torque (N·m) must not be negative");
                }
                if let Some(&(w0, _)) = curve.last() {
                    if w <= w0 {
                        return fail(
                            path,
                            format!("speeds must increase ({} after {})", num(w), num(w0)),
                        );
                    }
                }
                curve.push((w, t));
            }
            if curve.len() < 2 {
                return fail(
                    "machine.motor.curve",
                    "give at least two [speed, torque] points",
                );
            }
            let rated = |n: &Option<Num>, key: &str, what: &str| {
                n.as_ref()
                    .map(|n| positive(n, &params, &format!("machine.motor.{key}"), what))
                    .transpose()
            };
            let motor = Motor {
                curve,
                gear_ratio: gear,
                rated_torque: rated(&mo.rated_torque, "rated_torque", "the rated torque")?,
                rated_power: rated(&mo.rated_power, "rated_power", "the rated power")?,
            };
            let wm = gear * speed;
            if motor.available(wm).is_none() {
                return fail(
                    "machine.motor.curve",
                    format!(
                        "the motor curve spans {} to {} rad/s and never reaches the motor speed \
                         n ω = {} × {} = {} rad/s",
                        num(motor.curve[0].0),
                        num(motor.top_speed()),
                        num(gear),
                        num(speed),
                        num(wm)
                    ),
                );
            }
            Some(motor)
        }
    };
    Ok(Some(Spec {
        driver: m.driver.clone(),
        speed,
        speed_band,
        steps,
        point,
        balance: m.balance.unwrap_or(true),
        motor,
    }))
}
