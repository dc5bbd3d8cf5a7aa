//! simEngine2D's `.adm` and `.acf` records, as serde structs.
//!
//! Keys the course engine does not read (drawing data such as `vis`) are
//! ignored, as the course engine ignores them. Numbers may be written as
//! arithmetic in MATLAB syntax (`187/255`, `pi/2`); they are parsed as
//! constant expressions, never evaluated as code.

use serde::de::{self, Deserializer};
use serde::Deserialize;

use super::matlab;
use camlink_model::file::Num;

/// A number: a JSON number, or constant arithmetic in MATLAB syntax.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Number(pub f64);

impl<'de> Deserialize<'de> for Number {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = match Num::deserialize(d)? {
            Num::Value(v) => v,
            Num::Expr(src) => constant(&src).map_err(de::Error::custom)?,
        };
        if !v.is_finite() {
            return Err(de::Error::custom(format_args!(
                "value is not a finite number ({})",
                camlink_core::fmt_num::num(v)
            )));
        }
        Ok(Number(v))
    }
}

/// Evaluates constant MATLAB arithmetic such as `187/255` or `pi/2`.
pub(crate) fn constant(src: &str) -> Result<f64, String> {
    let t = matlab::translate(src, false).map_err(|e| format!("invalid number '{src}': {e}"))?;
    camlink_expr::eval_constant(&t.text, &Default::default())
        .map_err(|e| format!("invalid number '{src}': {}", e.message))
}

/// A body id, or nothing (`null`, or the key left out) for the ground.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Id(pub i64);

impl<'de> Deserialize<'de> for Id {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let Number(v) = Number::deserialize(d)?;
        if v.fract() != 0.0 || v.abs() > 1e15 {
            return Err(de::Error::custom(format_args!(
                "an id is an integer, not {}",
                camlink_core::fmt_num::num(v)
            )));
        }
        Ok(Id(v as i64))
    }
}

/// A body reference: an id, or `null` or `[]` (MATLAB's empty value) for
/// the ground, as is leaving the key out.
fn ground_or_id<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Id>, D::Error> {
    match serde_json::Value::deserialize(d)? {
        serde_json::Value::Null => Ok(None),
        serde_json::Value::Array(a) if a.is_empty() => Ok(None),
        v => Id::deserialize(v).map(Some).map_err(de::Error::custom),
    }
}

/// A function of time: text, or a bare number (a constant).
fn fun_text<'de, D: Deserializer<'de>>(d: D) -> Result<String, D::Error> {
    fun_from(serde_json::Value::deserialize(d)?).map_err(de::Error::custom)
}

/// An optional function of time; `null` is none.
fn opt_fun_text<'de, D: Deserializer<'de>>(d: D) -> Result<Option<String>, D::Error> {
    match serde_json::Value::deserialize(d)? {
        serde_json::Value::Null => Ok(None),
        v => fun_from(v).map(Some).map_err(de::Error::custom),
    }
}

fn fun_from(v: serde_json::Value) -> Result<String, String> {
    match v {
        serde_json::Value::String(s) => Ok(s),
        serde_json::Value::Number(n) => Ok(n.to_string()),
        other => Err(format!(
            "expected a function of t as text (\"sin(t)\") or a number, found {other}"
        )),
    }
}

/// The top level of a `.adm` file; `bodies`, `constraints` and `forces` are
/// read one entry at a time, so that an error can name the entry.
#[derive(Debug, Deserialize)]
pub(crate) struct AdmTop {
    #[serde(default)]
    pub name: Option<String>,
    #[serde(default)]
    pub gravity: Option<[Number; 2]>,
}

/// `bodies[]`: a rigid body whose frame sits at its centroid.
#[derive(Debug, Deserialize)]
pub(crate) struct Body {
    pub id: Id,
    #[serde(default)]
    pub mass: Option<Number>,
    /// Polar moment of inertia about the centroid (kg·m²).
    #[serde(default)]
    pub jbar: Option<Number>,
    /// [x, y, φ] (m, m, rad).
    pub q0: [Number; 3],
    /// [ẋ, ẏ, φ̇] (m/s, m/s, rad/s).
    #[serde(default)]
    pub qd0: Option<[Number; 3]>,
    /// Drawing data; its rectangles (`shapes[]` with `loc`, `size`) become
    /// the body's outline.
    #[serde(default)]
    pub vis: Option<serde_json::Value>,
}

/// `AbsoluteX`, `AbsoluteY`: x (or y) of `sP1` on `body1` equals `fun(t)`.
#[derive(Debug, Deserialize)]
#[allow(non_snake_case)]
pub(crate) struct AbsoluteCoord {
    pub body1: Id,
    pub sP1: [Number; 2],
    #[serde(deserialize_with = "fun_text")]
    pub fun: String,
}

/// `AbsoluteAngle`: φ of `body1` equals `fun(t)`.
#[derive(Debug, Deserialize)]
pub(crate) struct AbsoluteAngle {
    pub body1: Id,
    #[serde(deserialize_with = "fun_text")]
    pub fun: String,
}

/// `RevoluteJoint`: `sP1` on `body1` coincides with `sP2` on `body2`.
#[derive(Debug, Deserialize)]
#[allow(non_snake_case)]
pub(crate) struct Revolute {
    #[serde(default, deserialize_with = "ground_or_id")]
    pub body1: Option<Id>,
    pub sP1: [Number; 2],
    #[serde(default, deserialize_with = "ground_or_id")]
    pub body2: Option<Id>,
    pub sP2: [Number; 2],
    #[serde(default, deserialize_with = "opt_fun_text")]
    pub fun: Option<String>,
}

/// `TranslationalJoint` (Haug): v₁⊥·d = 0 and v₁⊥·v₂ = 0.
#[derive(Debug, Deserialize)]
#[allow(non_snake_case)]
pub(crate) struct Translational {
    #[serde(default, deserialize_with = "ground_or_id")]
    pub body1: Option<Id>,
    pub sP1: [Number; 2],
    pub vP1: [Number; 2],
    #[serde(default, deserialize_with = "ground_or_id")]
    pub body2: Option<Id>,
    pub sP2: [Number; 2],
    pub vP2: [Number; 2],
    #[serde(default, deserialize_with = "opt_fun_text")]
    pub fun: Option<String>,
}

/// `RackPinion`: rack `body1` (pitch line through `sP1`, `sQ1`), pinion
/// `body2` (centre `sP2`, pitch radius `R2`).
#[derive(Debug, Deserialize)]
#[allow(non_snake_case)]
pub(crate) struct RackPinion {
    #[serde(default, deserialize_with = "ground_or_id")]
    pub body1: Option<Id>,
    pub sP1: [Number; 2],
    pub sQ1: [Number; 2],
    #[serde(default, deserialize_with = "ground_or_id")]
    pub body2: Option<Id>,
    pub sP2: [Number; 2],
    pub R2: Number,
    pub theta1: Number,
    pub theta2: Number,
    #[serde(default, deserialize_with = "opt_fun_text")]
    pub fun: Option<String>,
}

/// A joint between `body1` and `body2` that takes no function.
pub(crate) trait TwoBodies {
    fn bodies(&self) -> (Option<Id>, Option<Id>);
    fn fun(&self) -> Option<&str>;
}

macro_rules! two_bodies {
    ($($t:ty),*) => {$(
        impl TwoBodies for $t {
            fn bodies(&self) -> (Option<Id>, Option<Id>) {
                (self.body1, self.body2)
            }
            fn fun(&self) -> Option<&str> {
                self.fun.as_deref()
            }
        }
    )*};
}

two_bodies!(Revolute, Translational, RackPinion);

/// `PointForce`: (funX, funY) at `sP1` of `body1`, global (`GRF`) or body
/// (`LRF`) components.
#[derive(Debug, Deserialize)]
#[allow(non_snake_case)]
pub(crate) struct PointForce {
    pub body1: Id,
    pub sP1: [Number; 2],
    pub frame: String,
    #[serde(default, deserialize_with = "opt_fun_text")]
    pub funX: Option<String>,
    #[serde(default, deserialize_with = "opt_fun_text")]
    pub funY: Option<String>,
}

/// `Torque`: fun(t) on `body1`.
#[derive(Debug, Deserialize)]
pub(crate) struct Torque {
    pub body1: Id,
    #[serde(deserialize_with = "fun_text")]
    pub fun: String,
}

/// `RSDA1` (body to ground) and `RSDA2` (between two bodies).
#[derive(Debug, Deserialize)]
pub(crate) struct Rsda {
    #[serde(default, deserialize_with = "ground_or_id")]
    pub body1: Option<Id>,
    #[serde(default, deserialize_with = "ground_or_id")]
    pub body2: Option<Id>,
    pub theta0: Number,
    pub k: Number,
    pub c: Number,
    #[serde(default, deserialize_with = "opt_fun_text")]
    pub fun: Option<String>,
}

/// `PointForceFile`: a force at `sP1` of `body1` computed by the MATLAB
/// function `mfile`, in the frame `frame` (`GRF` or `LRF`).
#[derive(Debug, Deserialize)]
#[allow(non_snake_case)]
pub(crate) struct PointForceFile {
    pub body1: Id,
    pub sP1: [Number; 2],
    pub frame: String,
    #[serde(default)]
    pub mfile: Option<String>,
}

/// A `.acf` analysis file.
#[derive(Debug, Deserialize)]
#[allow(non_snake_case)]
pub(crate) struct Acf {
    pub simulation: String,
    #[serde(default)]
    pub tend: Option<Number>,
    #[serde(default)]
    pub stepSize: Option<Number>,
    #[serde(default)]
    pub outputSteps: Option<Number>,
}
