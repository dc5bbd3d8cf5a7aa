//! The model file as written: serde structs shared by TOML and JSON.
//!
//! These structs mirror the file one to one and hold names and unevaluated
//! numbers; [`crate::resolve`] turns them into a core [`camlink_core::Model`].
//! Every table denies unknown keys, so a misspelt key is an error that names
//! it and lists the valid ones. The JSON Schema is derived from these structs,
//! and their doc comments become its descriptions.

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::fmt;

use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::Deserialize;

mod forces;
mod limits;
mod machine;
pub use forces::ForceSpec;
pub use limits::LimitsSpec;
pub use machine::{MachineSection, MotorSection};

/// A number, or a string holding an expression.
///
/// In a constant field the expression may use the file's parameters, `pi`
/// and functions such as `deg(30)`; in a driver's `f` it is a function of
/// time `t` (s).
#[derive(Clone, Debug, PartialEq)]
pub enum Num {
    Value(f64),
    Expr(String),
}

impl<'de> Deserialize<'de> for Num {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = Num;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number or an expression string")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Num, E> {
                Ok(Num::Value(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Num, E> {
                Ok(Num::Value(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Num, E> {
                Ok(Num::Value(v as f64))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Num, E> {
                Ok(Num::Expr(v.to_string()))
            }
        }
        d.deserialize_any(V)
    }
}

impl JsonSchema for Num {
    fn schema_name() -> Cow<'static, str> {
        "Number".into()
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "A number, or an expression string such as \"deg(30)\" or \"2*r\" using the file's parameters.",
            "anyOf": [{ "type": "number" }, { "type": "string" }]
        })
    }
}

/// A point given by name (declared in the body's `points`) or inline as
/// `[x, y]` in the body frame (m).
#[derive(Clone, Debug, PartialEq)]
pub enum PointRef {
    Name(String),
    Inline(Vec2),
}

impl<'de> Deserialize<'de> for PointRef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = PointRef;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a point name or an [x, y] pair")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<PointRef, E> {
                Ok(PointRef::Name(v.to_string()))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<PointRef, A::Error> {
                pair(seq).map(|v| PointRef::Inline(Vec2(v)))
            }
        }
        d.deserialize_any(V)
    }
}

impl JsonSchema for PointRef {
    fn schema_name() -> Cow<'static, str> {
        "PointRef".into()
    }
    fn json_schema(generator: &mut SchemaGenerator) -> Schema {
        let vec2 = generator.subschema_for::<Vec2>();
        json_schema!({
            "description": "A point of the body: the name of one of its `points`, or [x, y] in the body frame (m).",
            "anyOf": [{ "type": "string" }, vec2]
        })
    }
}

/// A planar vector `[x, y]` whose entries are numbers or expressions.
#[derive(Clone, Debug, PartialEq)]
pub struct Vec2(pub [Num; 2]);

impl<'de> Deserialize<'de> for Vec2 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Vec2;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("an [x, y] pair")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Vec2, A::Error> {
                pair(seq).map(Vec2)
            }
        }
        d.deserialize_seq(V)
    }
}

impl JsonSchema for Vec2 {
    fn schema_name() -> Cow<'static, str> {
        "Vec2".into()
    }
    fn json_schema(generator: &mut SchemaGenerator) -> Schema {
        let num = generator.subschema_for::<Num>();
        json_schema!({
            "description": "A planar vector [x, y].",
            "type": "array", "items": num, "minItems": 2, "maxItems": 2
        })
    }
}

/// Reads exactly two numbers from a sequence.
fn pair<'de, A: SeqAccess<'de>>(mut seq: A) -> Result<[Num; 2], A::Error> {
    let x: Num = seq
        .next_element()?
        .ok_or_else(|| de::Error::invalid_length(0, &"an [x, y] pair"))?;
    let y: Num = seq
        .next_element()?
        .ok_or_else(|| de::Error::invalid_length(1, &"an [x, y] pair"))?;
    let mut n = 2;
    while seq.next_element::<de::IgnoredAny>()?.is_some() {
        n += 1;
    }
    if n != 2 {
        return Err(de::Error::invalid_length(n, &"an [x, y] pair"));
    }
    Ok([x, y])
}

/// A map of names that rejects a name given twice. TOML parsers do this
/// themselves; JSON parsers keep the last value without a word.
fn unique_keys<'de, D, V>(d: D) -> Result<BTreeMap<String, V>, D::Error>
where
    D: Deserializer<'de>,
    V: Deserialize<'de>,
{
    struct Unique<V>(std::marker::PhantomData<V>);
    impl<'de, V: Deserialize<'de>> Visitor<'de> for Unique<V> {
        type Value = BTreeMap<String, V>;
        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            f.write_str("a map")
        }
        fn visit_map<A: de::MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
            let mut out = BTreeMap::new();
            while let Some(key) = map.next_key::<String>()? {
                if out.contains_key(&key) {
                    return Err(de::Error::custom(format_args!("duplicate key `{key}`")));
                }
                let value = map.next_value()?;
                out.insert(key, value);
            }
            Ok(out)
        }
    }
    d.deserialize_map(Unique(std::marker::PhantomData))
}

/// A camlink model file.
#[derive(Clone, Debug, Default, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(title = "camlink model file")]
pub struct ModelFile {
    /// The JSON Schema this file follows (ignored by the loader).
    #[serde(rename = "$schema", default)]
    pub schema: Option<String>,
    /// Name and global settings.
    #[serde(default)]
    pub model: Option<ModelSection>,
    /// Named numbers usable in every numeric field and expression.
    #[serde(default, deserialize_with = "unique_keys")]
    pub parameters: BTreeMap<String, Num>,
    /// Points of the ground, the implicit fixed body named `ground`.
    #[serde(default)]
    pub ground: Option<GroundSection>,
    /// The moving bodies.
    #[serde(default)]
    pub bodies: Vec<BodySpec>,
    /// Curves attached to bodies: cam profiles, roller and follower shapes, slots.
    #[serde(default)]
    pub curves: Vec<CurveSpec>,
    /// Kinematic joints (time-independent constraints).
    #[serde(default)]
    pub joints: Vec<JointSpec>,
    /// Driving constraints: a coordinate as a function of time.
    #[serde(default)]
    pub drivers: Vec<DriverSpec>,
    /// Applied forces: point forces, torques, springs, dampers, actuators.
    #[serde(default)]
    pub forces: Vec<ForceSpec>,
    /// What to compute and output.
    #[serde(default)]
    pub analysis: Option<AnalysisSection>,
    /// Machine design: shaking, balancing, flywheel and motor sizing at a
    /// design speed (`camlink machine`).
    #[serde(default)]
    pub machine: Option<MachineSection>,
}

/// `[model]`: name and global settings.
#[derive(Clone, Debug, Default, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ModelSection {
    /// Model name; defaults to the file name without extension.
    #[serde(default)]
    pub name: Option<String>,
    /// Gravity vector g in the global frame (m/s², or the length unit of
    /// `units` per s²); default [0, -9.81] m/s².
    #[serde(default)]
    pub gravity: Option<Vec2>,
    /// The length and angle units the file's values are written in,
    /// e.g. `{ length = "mm", angle = "deg" }`; default metres and
    /// radians. Converted to SI on loading (docs/units.md lists the keys
    /// that follow them); masses, forces and inertias stay SI.
    #[serde(default)]
    pub units: Option<UnitsSpec>,
}

/// `[model] units`: the units of the file's lengths and angles.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct UnitsSpec {
    /// Unit of every length, position and length rate; default `m`.
    #[serde(default)]
    pub length: Option<LengthUnit>,
    /// Unit of every angle and angle rate; default `rad`.
    #[serde(default)]
    pub angle: Option<AngleUnit>,
}

/// A length unit of `[model] units`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, JsonSchema)]
pub enum LengthUnit {
    #[serde(rename = "m")]
    M,
    #[serde(rename = "cm")]
    Cm,
    #[serde(rename = "mm")]
    Mm,
    /// The inch, 25.4 mm.
    #[serde(rename = "in")]
    In,
}

/// An angle unit of `[model] units`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, JsonSchema)]
pub enum AngleUnit {
    #[serde(rename = "rad")]
    Rad,
    #[serde(rename = "deg")]
    Deg,
}

/// `[ground]`: the fixed body, whose frame is the global frame.
#[derive(Clone, Debug, Default, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GroundSection {
    /// Named ground points, `name = [x, y]` in the global frame (m).
    #[serde(default, deserialize_with = "unique_keys")]
    pub points: BTreeMap<String, Vec2>,
}

/// `[[bodies]]`: a rigid body.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Unique name (not `ground`, no `.`).
    pub name: String,
    /// Initial position [x, y] of the body frame's origin, global frame (m);
    /// default [0, 0], or the mean of the `global_points`.
    #[serde(default)]
    pub position: Option<Vec2>,
    /// Initial angle φ of the body frame (rad); default 0.
    #[serde(default)]
    pub angle: Option<Num>,
    /// Mass m (kg), ≥ 0; default 0 (enough for kinematics).
    #[serde(default)]
    pub mass: Option<Num>,
    /// Polar moment of inertia J' about the centroid (kg·m²), ≥ 0; default 0.
    #[serde(default)]
    pub inertia: Option<Num>,
    /// Centroid [x, y] in the body frame (m), or global with
    /// `global_points`; default: the frame origin.
    #[serde(default)]
    pub centroid: Option<Vec2>,
    /// Initial velocity [ẋ, ẏ] of the frame origin (m/s); default [0, 0].
    #[serde(default)]
    pub velocity: Option<Vec2>,
    /// Initial angular velocity φ̇ (rad/s); default 0.
    #[serde(default)]
    pub omega: Option<Num>,
    /// Named points, `name = [x, y]` in the body frame (m).
    #[serde(default, deserialize_with = "unique_keys")]
    pub points: BTreeMap<String, Vec2>,
    /// Named points by their global positions at the initial instant,
    /// `name = [x, y]` (m), instead of `points`. The body frame is placed by
    /// `position` and `angle` when given, else at the mean of these points
    /// with φ = 0; `centroid`, `outline` corners and points given as
    /// [x, y] in joints, forces and curves are then global too
    /// (docs/model-files.md, "Bodies in global coordinates").
    #[serde(default, deserialize_with = "unique_keys")]
    pub global_points: BTreeMap<String, Vec2>,
    /// The body's shape in drawings, instead of the one derived from its
    /// points: a closed polyline `[[x, y], …]` in the body frame (m, at
    /// least three corners) or the name of a closed curve on this body.
    #[serde(default)]
    pub outline: Option<OutlineSpec>,
}

/// A body's drawn outline: corners of a closed polyline (body frame, m), or
/// the name of a closed curve carried by the body.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum OutlineSpec {
    Polyline(Vec<Vec2>),
    Curve(String),
}

/// Gear pair kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum GearKindSpec {
    /// Two external gears (they turn in opposite senses).
    #[default]
    External,
    /// Gear i runs inside ring gear j (same sense).
    Internal,
}

/// `[[joints]]`: a time-independent constraint, selected by `type`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum JointSpec {
    /// Point `point_i` of `body_i` coincides with `point_j` of `body_j` (2 equations).
    Revolute(RevoluteJoint),
    /// `point_j` slides on the line through `point_i` along `axis` (body i
    /// frame), and the relative angle φ_j − φ_i stays `angle` (2 equations).
    Translational(TranslationalJoint),
    /// A massless link of `length` between `point_i` and `point_j` (1 equation).
    RevoluteRevolute(RevoluteRevoluteJoint),
    /// Pin `point_i` of `body_i` runs on the line of `body_j` through
    /// `point_j` along `axis`, at signed `offset` to its left (1 equation).
    RevoluteTranslational(RevoluteTranslationalJoint),
    /// Global x of a body point is constant (1 equation).
    AbsoluteX(AbsoluteCoordJoint),
    /// Global y of a body point is constant (1 equation).
    AbsoluteY(AbsoluteCoordJoint),
    /// The body angle φ is constant (1 equation).
    AbsolutePhi(AbsolutePhiJoint),
    /// Distance from a body point to a ground point is constant (1 equation).
    AbsoluteDistance(AbsoluteDistanceJoint),
    /// x_j^P − x_i^P is constant (1 equation).
    RelativeX(RelativeCoordJoint),
    /// y_j^P − y_i^P is constant (1 equation).
    RelativeY(RelativeCoordJoint),
    /// φ_j − φ_i is constant (1 equation).
    RelativePhi(RelativePhiJoint),
    /// Distance between two body points is constant (1 equation).
    RelativeDistance(RelativeCoordJoint),
    /// Two gears rolling on their pitch circles (2 equations, 1 own coordinate).
    Gear(GearJoint),
    /// Pinion `body_i` rolls on the pitch line of rack `body_j` (1 equation).
    RackPinion(RackPinionJoint),
    /// Curve `curve_i` touches curve `curve_j` (2 equations for the shared
    /// point, 1 for collinear tangents; 2 own coordinates α_i, α_j).
    CamFollower(CamFollowerJoint),
    /// Curve `curve_i` touches the straight face of `body_j` (2 equations,
    /// 1 own coordinate α_i).
    FlatFollower(FlatFollowerJoint),
    /// Pin `point_i` of `body_i` runs in the slot `curve_j` (2 equations,
    /// 1 own coordinate α_j).
    PointFollower(PointFollowerJoint),
}

/// `revolute` joint: see [`JointSpec::Revolute`].
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RevoluteJoint {
    /// Unique joint name; default `<type>_<index>`.
    #[serde(default)]
    pub name: Option<String>,
    pub body_i: String,
    /// Default: the body origin [0, 0].
    #[serde(default)]
    pub point_i: Option<PointRef>,
    pub body_j: String,
    /// Default: the body origin [0, 0].
    #[serde(default)]
    pub point_j: Option<PointRef>,
    /// End stops on the angle θ = φ_j − φ_i (rad).
    #[serde(default)]
    pub limits: Option<LimitsSpec>,
    /// Coulomb friction in the joint (docs/friction.md).
    #[serde(default)]
    pub friction: Option<FrictionSpec>,
}

/// `translational` joint: see [`JointSpec::Translational`].
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct TranslationalJoint {
    #[serde(default)]
    pub name: Option<String>,
    pub body_i: String,
    #[serde(default)]
    pub point_i: Option<PointRef>,
    /// Sliding direction in body i's frame; normalised, must not be zero.
    pub axis: Vec2,
    pub body_j: String,
    #[serde(default)]
    pub point_j: Option<PointRef>,
    /// θ₀ = φ_j − φ_i (rad); default: its initial value (docs/model-files.md, "Defaults marked initial").
    #[serde(default)]
    pub angle: Option<Num>,
    /// End stops on the stroke (m): point_j from point_i along the axis.
    #[serde(default)]
    pub limits: Option<LimitsSpec>,
    /// Coulomb friction in the joint (docs/friction.md).
    #[serde(default)]
    pub friction: Option<FrictionSpec>,
}

/// `revolute_revolute` joint: see [`JointSpec::RevoluteRevolute`].
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RevoluteRevoluteJoint {
    #[serde(default)]
    pub name: Option<String>,
    pub body_i: String,
    #[serde(default)]
    pub point_i: Option<PointRef>,
    pub body_j: String,
    #[serde(default)]
    pub point_j: Option<PointRef>,
    /// Link length L (m), > 0; default: the initial distance.
    #[serde(default)]
    pub length: Option<Num>,
}

/// `revolute_translational` joint: see [`JointSpec::RevoluteTranslational`].
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RevoluteTranslationalJoint {
    #[serde(default)]
    pub name: Option<String>,
    /// The body carrying the pin.
    pub body_i: String,
    #[serde(default)]
    pub point_i: Option<PointRef>,
    /// The body carrying the line.
    pub body_j: String,
    #[serde(default)]
    pub point_j: Option<PointRef>,
    /// Line direction in body j's frame; normalised, must not be zero.
    pub axis: Vec2,
    /// Signed offset c of the pin to the left of the line (m); default: its initial value (docs/model-files.md, "Defaults marked initial").
    #[serde(default)]
    pub offset: Option<Num>,
    /// End stops on the pin's travel along the line from point_j (m).
    #[serde(default)]
    pub limits: Option<LimitsSpec>,
}

/// `gear` joint: see [`JointSpec::Gear`].
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GearJoint {
    #[serde(default)]
    pub name: Option<String>,
    pub body_i: String,
    /// Centre of gear i; default the body origin.
    #[serde(default)]
    pub point_i: Option<PointRef>,
    /// Pitch radius R_i (m), > 0.
    pub radius_i: Num,
    pub body_j: String,
    /// Centre of gear j; default the body origin.
    #[serde(default)]
    pub point_j: Option<PointRef>,
    /// Pitch radius R_j (m), > 0.
    pub radius_j: Num,
    /// `external` (default) or `internal` (body j is the ring gear).
    #[serde(default)]
    pub kind: GearKindSpec,
    /// Phase constant c (m); default: the initial placement.
    #[serde(default)]
    pub phase: Option<Num>,
}

/// `rack_pinion` joint: see [`JointSpec::RackPinion`].
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RackPinionJoint {
    #[serde(default)]
    pub name: Option<String>,
    /// The pinion.
    pub body_i: String,
    /// Pinion centre; default the body origin.
    #[serde(default)]
    pub point_i: Option<PointRef>,
    /// Pitch radius R (m), > 0.
    pub radius: Num,
    /// The rack.
    pub body_j: String,
    /// A point of the pitch line; default the body origin.
    #[serde(default)]
    pub point_j: Option<PointRef>,
    /// Rack direction in body j's frame; normalised, must not be zero.
    pub axis: Vec2,
    /// Phase constant c (m); default: the initial placement.
    #[serde(default)]
    pub phase: Option<Num>,
}

/// `cam_follower` joint: two curves in contact.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CamFollowerJoint {
    #[serde(default)]
    pub name: Option<String>,
    /// The name of curve C_i (usually the cam); its body is body i.
    pub curve_i: String,
    /// The name of curve C_j (usually the follower or roller); its body is body j.
    pub curve_j: String,
    /// Starting guess of the contact parameter on C_i (rad on a polar
    /// profile, the curve's parameter otherwise); default: found from the
    /// initial placement.
    #[serde(default)]
    pub alpha_i: Option<Num>,
    /// Starting guess of the contact parameter on C_j; default: found.
    #[serde(default)]
    pub alpha_j: Option<Num>,
    /// True when the contact can open: forward dynamics lets the follower
    /// leave the cam where the normal force would turn negative, fly, and
    /// land with Newton's restitution law (`docs/dynamics.md`).
    #[serde(default)]
    pub unilateral: bool,
    /// Coefficient of restitution e of a unilateral contact, 0 (plastic,
    /// the default) to 1 (elastic).
    #[serde(default)]
    pub restitution: Option<Num>,
    /// Approach speed (m/s) below which an impact closes a unilateral
    /// contact; default 1e-3.
    #[serde(default)]
    pub rest_speed: Option<Num>,
    /// Time tolerance (s) of a unilateral contact's lift-off and impact
    /// events; default 1e-9.
    #[serde(default)]
    pub event_tol: Option<Num>,
    /// Stiffness k (N/mⁿ) of a compliant unilateral contact: a
    /// Hunt–Crossley force k δⁿ (1 + c δ̇) from the overlap δ instead of
    /// impacts.
    #[serde(default)]
    pub stiffness: Option<Num>,
    /// Exponent n of a compliant contact; default 1.5 (Hertz).
    #[serde(default)]
    pub exponent: Option<Num>,
    /// Damping factor c (s/m) of a compliant contact; default 0.
    #[serde(default)]
    pub damping: Option<Num>,
    /// Coulomb friction at the contact (docs/friction.md).
    #[serde(default)]
    pub friction: Option<FrictionSpec>,
}

/// `flat_follower` joint: a curve on a straight face.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FlatFollowerJoint {
    #[serde(default)]
    pub name: Option<String>,
    /// The name of the cam curve C_i; its body is body i.
    pub curve_i: String,
    /// The body carrying the flat face.
    pub body_j: String,
    /// A point of the face; default the body origin.
    #[serde(default)]
    pub point_j: Option<PointRef>,
    /// Direction of the face in body j's frame; normalised, must not be zero.
    pub axis: Vec2,
    /// Starting guess of the contact parameter on C_i; default: the cam
    /// point nearest the face.
    #[serde(default)]
    pub alpha_i: Option<Num>,
    /// True when the contact can open: forward dynamics lets the follower
    /// leave the cam where the normal force would turn negative, fly, and
    /// land with Newton's restitution law (`docs/dynamics.md`).
    #[serde(default)]
    pub unilateral: bool,
    /// Coefficient of restitution e of a unilateral contact, 0 (plastic,
    /// the default) to 1 (elastic).
    #[serde(default)]
    pub restitution: Option<Num>,
    /// Approach speed (m/s) below which an impact closes a unilateral
    /// contact; default 1e-3.
    #[serde(default)]
    pub rest_speed: Option<Num>,
    /// Time tolerance (s) of a unilateral contact's lift-off and impact
    /// events; default 1e-9.
    #[serde(default)]
    pub event_tol: Option<Num>,
    /// Stiffness k (N/mⁿ) of a compliant unilateral contact: a
    /// Hunt–Crossley force k δⁿ (1 + c δ̇) from the overlap δ instead of
    /// impacts.
    #[serde(default)]
    pub stiffness: Option<Num>,
    /// Exponent n of a compliant contact; default 1.5 (Hertz).
    #[serde(default)]
    pub exponent: Option<Num>,
    /// Damping factor c (s/m) of a compliant contact; default 0.
    #[serde(default)]
    pub damping: Option<Num>,
    /// Coulomb friction at the contact (docs/friction.md).
    #[serde(default)]
    pub friction: Option<FrictionSpec>,
}

/// `point_follower` joint: a pin in a slot.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PointFollowerJoint {
    #[serde(default)]
    pub name: Option<String>,
    /// The body carrying the pin.
    pub body_i: String,
    /// The pin; default the body origin.
    #[serde(default)]
    pub point_i: Option<PointRef>,
    /// The name of the slot curve C_j; its body is body j.
    pub curve_j: String,
    /// Starting guess of the pin's parameter on C_j; default: the slot
    /// point nearest the pin.
    #[serde(default)]
    pub alpha_j: Option<Num>,
    /// Coulomb friction at the contact (docs/friction.md).
    #[serde(default)]
    pub friction: Option<FrictionSpec>,
}

/// `friction = { mu = 0.1, radius = 0.01 }`: Coulomb friction in a
/// `revolute`, `translational`, `point_follower`, `cam_follower` or
/// `flat_follower` joint, by a regularised law (docs/friction.md).
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FrictionSpec {
    /// Friction coefficient μ, ≥ 0: the friction force is μ times the
    /// joint's normal force N.
    pub mu: Num,
    /// Pin radius r (m), ≥ 0, of a revolute joint (required there, refused
    /// elsewhere): the friction torque is μ r N, N the pin force.
    #[serde(default)]
    pub radius: Option<Num>,
    /// Transition speed v_s (m/s), > 0: below this slip speed the law is a
    /// cubic through zero, and a stuck joint creeps at less than v_s;
    /// default 1e-4.
    #[serde(default)]
    pub transition_speed: Option<Num>,
}

/// Whether a curve is a polar profile ρ(α) or a parametric curve (x(s), y(s)).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum CurveKind {
    /// ρ(α) about `centre`; parameter: the angle α (rad); always closed.
    Polar,
    /// (x(s), y(s)); parameter: length along the curve (m), or `s` of an expression.
    Parametric,
}

/// `[[curves]]`: a named curve on a body, selected by `source`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(tag = "source", rename_all = "snake_case", deny_unknown_fields)]
pub enum CurveSpec {
    /// A circle of `radius` about `centre`.
    Circle {
        /// Unique curve name.
        name: String,
        /// The body carrying the curve (may be `ground`).
        body: String,
        /// `polar` (default; parameter α in rad) or `parametric` (arc length in m).
        #[serde(default)]
        kind: Option<CurveKind>,
        /// Centre, a point of the body; default the body origin.
        #[serde(default)]
        centre: Option<PointRef>,
        /// Radius (m), > 0.
        radius: Num,
        /// Parametric only: the angle (rad, body frame) where s = 0; default 0.
        #[serde(default)]
        start: Option<Num>,
    },
    /// The straight segment from `from` to `to` (parametric, open; s in m from `from`).
    Line {
        name: String,
        body: String,
        /// Start point (a point of the body).
        from: PointRef,
        /// End point (a point of the body).
        to: PointRef,
    },
    /// An arc of `radius` about `centre` from angle `start` to `end` (parametric, open; s in m).
    Arc {
        name: String,
        body: String,
        /// Centre; default the body origin.
        #[serde(default)]
        centre: Option<PointRef>,
        /// Radius (m), > 0.
        radius: Num,
        /// Start angle (rad, body frame).
        start: Num,
        /// End angle (rad); counterclockwise when end > start; at most one turn.
        end: Num,
    },
    /// A profile written as expressions: polar `rho` in `a`, or parametric `x`, `y` in `s`.
    Expression {
        name: String,
        body: String,
        /// Inferred from the keys given (`rho` → polar, `x`/`y` → parametric).
        #[serde(default)]
        kind: Option<CurveKind>,
        /// Polar: the centre Q; default the body origin.
        #[serde(default)]
        centre: Option<PointRef>,
        /// Polar: ρ(a) (m) as an expression of the angle `a` (rad), e.g.
        /// "if(a <= 2*pi/3, 5/4 - cos(3*a)/4, 1)"; evaluated for a in [0, 2π).
        #[serde(default)]
        rho: Option<String>,
        /// Parametric: x(s) (m) in the body frame.
        #[serde(default)]
        x: Option<String>,
        /// Parametric: y(s) (m) in the body frame.
        #[serde(default)]
        y: Option<String>,
        /// Parametric: the parameter range [s0, s1], s0 < s1.
        #[serde(default)]
        range: Option<Vec2>,
        /// Parametric: true when the curve closes (period s1 − s0); default false.
        #[serde(default)]
        closed: Option<bool>,
    },
    /// A polar profile ρ(α) = a0 + Σ (a_k cos kα + b_k sin kα), k = 1, 2, …
    Fourier {
        name: String,
        body: String,
        /// The centre Q; default the body origin.
        #[serde(default)]
        centre: Option<PointRef>,
        /// Mean radius a0 (m).
        a0: Num,
        /// Cosine coefficients a_1, a_2, … (m).
        #[serde(default)]
        a: Vec<Num>,
        /// Sine coefficients b_1, b_2, … (m).
        #[serde(default)]
        b: Vec<Num>,
    },
    /// A cubic spline (C², periodic when closed) through points given inline or in a CSV file.
    Spline {
        name: String,
        body: String,
        /// `polar`: points are (α, ρ) in rad and m, periodic; `parametric`: (x, y) in m.
        kind: CurveKind,
        /// Polar: the centre Q; default the body origin.
        #[serde(default)]
        centre: Option<PointRef>,
        /// The points, inline.
        #[serde(default)]
        points: Option<Vec<Vec2>>,
        /// A CSV file of points (two columns), relative to the model file.
        #[serde(default)]
        file: Option<String>,
        /// Parametric: true for a closed (periodic) curve; default false.
        #[serde(default)]
        closed: Option<bool>,
    },
    /// A cam surface synthesised from a motion program (docs/cam-design.md):
    /// the profile that moves `follower` through `segments` as the body turns
    /// about its origin; parameter: the cam angle θ (rad); closed.
    Motion {
        name: String,
        body: String,
        /// `translating-roller`, `translating-flat`, `oscillating-roller` or `oscillating-flat`.
        follower: String,
        /// Base circle radius R_b (m): the least radius of the cam surface.
        base_radius: Num,
        /// `ccw` (default) or `cw`: the sense in which the cam turns.
        #[serde(default)]
        rotation: Option<String>,
        /// Translating roller: offset ε of the stem (m); default 0.
        #[serde(default)]
        offset: Option<Num>,
        /// Roller radius (m), for roller followers.
        #[serde(default)]
        roller_radius: Option<Num>,
        /// Oscillating followers: distance d from the cam centre to the arm's pivot (m).
        #[serde(default)]
        pivot_distance: Option<Num>,
        /// Oscillating roller: arm length L, pivot to roller centre (m).
        #[serde(default)]
        arm_length: Option<Num>,
        /// Oscillating flat face: distance e of the face from the pivot (m); default 0.
        #[serde(default)]
        face_offset: Option<Num>,
        /// `surface` (default): the cam surface; `pitch`: a roller's pitch curve.
        #[serde(default)]
        curve: Option<String>,
        /// The motion program, in order from θ = 0; spans add up to 2π.
        segments: Vec<MotionSegmentSpec>,
    },
}

/// One segment of a `motion` curve's program.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MotionSegmentSpec {
    /// `dwell`, `constant-velocity`, `simple-harmonic`, `cycloidal`,
    /// `modified-trapezoid`, `modified-sine`, `3-4-5`, `4-5-6-7` or `polynomial`.
    pub law: String,
    /// Span of cam angle (rad), > 0.
    pub span: Num,
    /// Lift (m; rad of swing for an oscillating follower); default 0.
    #[serde(default)]
    pub lift: Option<Num>,
    /// `polynomial`: derivatives at the start.
    #[serde(default)]
    pub start: Option<MotionEndSpec>,
    /// `polynomial`: derivatives at the end.
    #[serde(default)]
    pub end: Option<MotionEndSpec>,
}

/// End conditions of a fitted polynomial segment: s′, s″, s‴ per radian of cam angle.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MotionEndSpec {
    #[serde(default)]
    pub velocity: Option<Num>,
    #[serde(default)]
    pub acceleration: Option<Num>,
    #[serde(default)]
    pub jerk: Option<Num>,
}

/// `absolute_x` / `absolute_y` joint.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AbsoluteCoordJoint {
    #[serde(default)]
    pub name: Option<String>,
    pub body: String,
    /// Default: the body origin.
    #[serde(default)]
    pub point: Option<PointRef>,
    /// The held coordinate (m); default: its initial value (docs/model-files.md, "Defaults marked initial").
    #[serde(default)]
    pub value: Option<Num>,
}

/// `absolute_phi` joint.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AbsolutePhiJoint {
    #[serde(default)]
    pub name: Option<String>,
    pub body: String,
    /// The held angle (rad); default: its initial value (docs/model-files.md, "Defaults marked initial").
    #[serde(default)]
    pub value: Option<Num>,
}

/// `absolute_distance` joint.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AbsoluteDistanceJoint {
    #[serde(default)]
    pub name: Option<String>,
    pub body: String,
    #[serde(default)]
    pub point: Option<PointRef>,
    /// The ground point C: a name from `[ground] points` or [x, y] (m).
    pub ground_point: PointRef,
    /// The held distance (m), > 0; default: its initial value (docs/model-files.md, "Defaults marked initial").
    #[serde(default)]
    pub distance: Option<Num>,
}

/// `relative_x` / `relative_y` / `relative_distance` joint.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RelativeCoordJoint {
    #[serde(default)]
    pub name: Option<String>,
    pub body_i: String,
    #[serde(default)]
    pub point_i: Option<PointRef>,
    pub body_j: String,
    #[serde(default)]
    pub point_j: Option<PointRef>,
    /// The held difference or distance (m); default: its initial value (docs/model-files.md, "Defaults marked initial").
    #[serde(default)]
    pub value: Option<Num>,
}

/// `relative_phi` joint.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RelativePhiJoint {
    #[serde(default)]
    pub name: Option<String>,
    pub body_i: String,
    pub body_j: String,
    /// The held φ_j − φ_i (rad); default: its initial value (docs/model-files.md, "Defaults marked initial").
    #[serde(default)]
    pub value: Option<Num>,
}

/// `[[drivers]]`: a coordinate prescribed as f(t), selected by `type`.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum DriverSpec {
    /// x of a body point = f(t) (m).
    AbsoluteX(AbsoluteCoordDriver),
    /// y of a body point = f(t) (m).
    AbsoluteY(AbsoluteCoordDriver),
    /// φ of a body = f(t) (rad).
    AbsolutePhi(AbsolutePhiDriver),
    /// Distance from a body point to a ground point = f(t) (m).
    AbsoluteDistance(AbsoluteDistanceDriver),
    /// x_j^P − x_i^P = f(t) (m).
    RelativeX(RelativeCoordDriver),
    /// y_j^P − y_i^P = f(t) (m).
    RelativeY(RelativeCoordDriver),
    /// φ_j − φ_i = f(t) (rad).
    RelativePhi(RelativePhiDriver),
    /// Distance between two body points = f(t) (m).
    RelativeDistance(RelativeCoordDriver),
    /// The angle φ_j − φ_i of the named revolute joint = f(t) (rad).
    RevoluteAngle(JointDriver),
    /// Travel of the named translational joint's point_j from its point_i
    /// along the axis = f(t) (m).
    TranslationalTravel(JointDriver),
    /// The contact parameter α_j of the named point_follower joint = f(t):
    /// travel along its curve (rad on a polar slot, m on a line, arc,
    /// circle or spline slot).
    CurveTravel(JointDriver),
}

/// `absolute_x` / `absolute_y` driver.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AbsoluteCoordDriver {
    #[serde(default)]
    pub name: Option<String>,
    pub body: String,
    #[serde(default)]
    pub point: Option<PointRef>,
    /// f(t): a number or an expression in `t` (s).
    pub f: Num,
}

/// `absolute_phi` driver.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AbsolutePhiDriver {
    #[serde(default)]
    pub name: Option<String>,
    pub body: String,
    /// f(t) (rad): a number or an expression in `t` (s).
    pub f: Num,
}

/// `absolute_distance` driver.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AbsoluteDistanceDriver {
    #[serde(default)]
    pub name: Option<String>,
    pub body: String,
    #[serde(default)]
    pub point: Option<PointRef>,
    /// The ground point C: a name from `[ground] points` or [x, y] (m).
    pub ground_point: PointRef,
    /// f(t) (m): a number or an expression in `t` (s).
    pub f: Num,
}

/// `relative_x` / `relative_y` / `relative_distance` driver.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RelativeCoordDriver {
    #[serde(default)]
    pub name: Option<String>,
    pub body_i: String,
    #[serde(default)]
    pub point_i: Option<PointRef>,
    pub body_j: String,
    #[serde(default)]
    pub point_j: Option<PointRef>,
    /// f(t) (m): a number or an expression in `t` (s).
    pub f: Num,
}

/// `relative_phi` driver.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RelativePhiDriver {
    #[serde(default)]
    pub name: Option<String>,
    pub body_i: String,
    pub body_j: String,
    /// f(t) (rad): a number or an expression in `t` (s).
    pub f: Num,
}

/// `revolute_angle` / `translational_travel` driver.
#[derive(Clone, Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct JointDriver {
    #[serde(default)]
    pub name: Option<String>,
    /// Name of the driven joint (revolute, translational or point_follower, by driver type).
    pub joint: String,
    /// f(t) (rad or m): a number or an expression in `t` (s).
    pub f: Num,
}

/// `[analysis]`: which analysis, its time grid, solver settings and output
/// points.
#[derive(Clone, Debug, Default, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AnalysisSection {
    /// The analysis to run; default "kinematics".
    #[serde(default, rename = "type")]
    pub kind: Option<AnalysisType>,
    /// End time (s), ≥ 0; the run starts at t = 0. Not for "equilibrium".
    #[serde(default)]
    pub t_end: Option<Num>,
    /// Output step (s), > 0. Not for "equilibrium".
    #[serde(default)]
    pub step: Option<Num>,
    /// Explicit output times (s), increasing; instead of `t_end`/`step`.
    /// Not for "equilibrium".
    #[serde(default)]
    pub times: Option<Vec<Num>>,
    /// "equilibrium" only: the time (s) at which drivers and forces are
    /// evaluated; default 0.
    #[serde(default)]
    pub time: Option<Num>,
    /// Newton tolerance; default 1e-10 (on |Φ|, or on the force balance for
    /// "equilibrium"), 1e-6 for "dynamics" (on the corrections of q and q̇).
    #[serde(default)]
    pub tol: Option<Num>,
    /// Most Newton iterations per step; default 25 (kinematics, inverse
    /// dynamics), 100 (equilibrium), 12 (dynamics).
    #[serde(default)]
    pub max_iter: Option<u32>,
    /// Body points to output as "body.point" (x, y, vx, vy, ax, ay).
    #[serde(default)]
    pub points: Vec<String>,
    /// "kinematics" only: also solve for the jerk (Φ_q q⃛ = η) and output
    /// `<body>.jx`, `.jy` (m/s³), `.jphi` (rad/s³) and, for each output
    /// point, `<point>.jx`, `.jy`; default false.
    #[serde(default)]
    pub jerk: Option<bool>,
    /// "dynamics" only: integration time step h (s), > 0; the largest step
    /// when `adaptive`. Default: the output `step`, but at most 1e-3.
    #[serde(default)]
    pub h: Option<Num>,
    /// "dynamics" only: spectral radius at infinity ρ∞ ∈ [0, 1] of the
    /// generalized-α method (1: no numerical damping); default 0.8.
    #[serde(default)]
    pub rho_inf: Option<Num>,
    /// "dynamics" only: error-controlled variable steps; default false.
    #[serde(default)]
    pub adaptive: Option<bool>,
    /// With `adaptive`: absolute local-error tolerance (m or rad), ≥ 0;
    /// default 1e-6.
    #[serde(default)]
    pub atol: Option<Num>,
    /// With `adaptive`: relative local-error tolerance, ≥ 0; default 0.
    #[serde(default)]
    pub rtol: Option<Num>,
    /// With `adaptive`: smallest step (s), > 0; default 1e-8.
    #[serde(default)]
    pub h_min: Option<Num>,
    /// "dynamics" only: tolerance of the initial position projection
    /// (m or rad), > 0; default 1e-12.
    #[serde(default)]
    pub projection_tol: Option<Num>,
}

/// The analyses a model file can ask for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum AnalysisType {
    /// Positions, velocities and accelerations of a driven model.
    #[default]
    Kinematics,
    /// Joint reactions and driver efforts along the driven motion.
    InverseDynamics,
    /// The configuration where the forces balance, and the reactions there.
    Equilibrium,
    /// Forward dynamics: the motion the forces produce.
    Dynamics,
}

impl AnalysisType {
    /// The name used in files, e.g. `"inverse_dynamics"`.
    pub fn name(self) -> &'static str {
        match self {
            AnalysisType::Kinematics => "kinematics",
            AnalysisType::InverseDynamics => "inverse_dynamics",
            AnalysisType::Equilibrium => "equilibrium",
            AnalysisType::Dynamics => "dynamics",
        }
    }
}
