//! From a `.adm` (and `.acf`) to camlink's model description.
//!
//! Every course type maps onto camlink constraints and forces whose
//! equations have the same solutions (see docs/simengine2d.md). The joint
//! kind a constraint type is read as comes from its line in the joint-kind
//! registry (`camlink_model::JOINT_KINDS`); [`TRANSLATIONS`] holds each
//! kind's translation:
//!
//! - `AbsoluteX`/`AbsoluteY`/`AbsoluteAngle` with a constant `fun` become
//!   `absolute_x`/`absolute_y`/`absolute_phi` joints, with a `fun` of `t`
//!   drivers of the same type. A constant `AbsoluteX` and `AbsoluteY` pair
//!   at the same point of one body becomes a `revolute` joint to a named
//!   ground point.
//! - `RevoluteJoint` → `revolute`.
//! - `TranslationalJoint` → `translational` with `angle` θ₀ the relative
//!   angle φ₂ − φ₁ at which A₁v′₁ ∥ A₂v′₂ (v₁⊥·v₂ = 0), the root nearest the
//!   initial placement.
//! - `RackPinion` → `rack_pinion` (rolling) with phase
//!   c = |sQ1 − sP1| + R₂(θ₁ − θ₂ + 3π/2), plus `revolute_translational`
//!   holding the pinion centre at R₂ to the left of the pitch line; each is
//!   the course's equation divided by |sQ1 − sP1|.
//! - `PointForce` → `point_force` (`local` for `LRF`), `Torque` → `torque`,
//!   `PointForceFile` → `point_force` with expressions of state translated
//!   from its MATLAB file (see [`super::mfile`]),
//!   `RSDA1` → `rsda` from the ground to body1, `RSDA2` → `rsda` from body1
//!   to body2.

use std::collections::{HashMap, HashSet};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use camlink_model::JOINT_KINDS;
use serde::de::DeserializeOwned;
use serde_json::Value;

use super::format::{self, Acf, Id, Number};
use super::item::Item;
use super::matlab;
use super::mfile;

/// A failure in the `.adm`: the field path in the file, the entry it
/// belongs to (e.g. `constraint 'crank_pin' (id 4)`) and what is wrong.
#[derive(Debug)]
pub(crate) struct AdmFail {
    pub path: String,
    pub label: Option<String>,
    pub message: String,
}

type R<T> = Result<T, AdmFail>;

/// Where an entry of the description comes from, so that an error found in
/// it later names the `.adm` entry and field.
#[derive(Clone, Debug)]
pub(crate) struct Origin {
    /// The entry's path in the description, e.g. `joints[2]`.
    pub prefix: String,
    /// The entry's path in the `.adm`, e.g. `constraints[3]`.
    pub adm_path: String,
    pub label: String,
    /// Description field → `.adm` field.
    pub fields: Vec<(&'static str, &'static str)>,
}

/// The description and the origin of its entries.
pub(crate) struct Built {
    pub doc: Item,
    pub origins: Vec<Origin>,
    /// What was read and ignored, as the course engine ignores it: each at
    /// its field, as an error would be.
    pub warnings: Vec<AdmFail>,
}

/// A course constraint's translation into camlink joints or drivers.
type Translate = fn(&mut Builder, &Entry) -> R<()>;

/// The translations of the course constraint types, by the joint kind
/// whose registry line ([`JOINT_KINDS`]) lists them, in the order errors
/// list the types. Each type has one translation: a `RackPinion`, listed
/// under `rack_pinion` and `revolute_translational`, is a `rack_pinion`
/// whose translation adds the `revolute_translational`.
const TRANSLATIONS: &[(&str, Translate)] = &[
    ("absolute_x", Builder::absolute_coord),
    ("absolute_y", Builder::absolute_coord),
    ("absolute_phi", Builder::absolute_angle),
    ("revolute", Builder::revolute),
    ("translational", Builder::translational),
    ("rack_pinion", Builder::rack_pinion),
];

/// The course constraint types the registry lists under `kind`.
fn course_types(kind: &str) -> &'static [&'static str] {
    JOINT_KINDS
        .iter()
        .find(|k| k.kind == kind)
        .map_or(&[], |k| k.course_types)
}

/// The kind a course constraint type is read as, and its translation.
fn translation(course: &str) -> Option<(&'static str, Translate)> {
    TRANSLATIONS
        .iter()
        .find(|(kind, _)| course_types(kind).contains(&course))
        .copied()
}

/// The constraint types read, as the error for an unknown type lists them.
pub fn constraint_types() -> Vec<&'static str> {
    TRANSLATIONS
        .iter()
        .flat_map(|(kind, _)| course_types(kind).iter().copied())
        .collect()
}

/// The advice for a `PointForceFile` that is not translated.
const ELSE: &str = "; or write the force as a [[forces]] entry of a converted model \
                    (`camlink convert`) or as a Python force (Model.with_force)";

/// The force types read.
pub const FORCE_TYPES: &[&str] = &["PointForce", "Torque", "RSDA1", "RSDA2", "PointForceFile"];

struct BodyOut {
    name: String,
    body: format::Body,
    /// Named points (body frame, m), in order of first use.
    points: Vec<(String, [f64; 2])>,
}

/// A constant AbsoluteX or AbsoluteY, waiting for its partner.
struct Pin {
    path: String,
    label: String,
    name: String,
    /// The camlink joint type: `absolute_x` or `absolute_y`.
    axis: &'static str,
    body: usize,
    s: [f64; 2],
    value: f64,
    text: Item,
}

/// A course constraint being translated: where it is in the `.adm`, its
/// course type and the joint kind the registry reads that type as.
struct Entry<'a> {
    v: &'a Value,
    /// Its path in the `.adm`: `constraints[k]`.
    path: &'a str,
    /// `constraint 'name' (id n)`, for errors.
    lab: &'a str,
    /// The course type, e.g. `AbsoluteX`.
    course: &'a str,
    /// The joint kind, e.g. `absolute_x`.
    kind: &'static str,
    name: Option<&'a str>,
    id: Option<&'a str>,
    /// The name when the file gives none: `constraint<id>`.
    fallback: &'a str,
}

impl Entry<'_> {
    /// The `.adm` path of the entry's field `key`.
    fn field(&self, key: &str) -> String {
        format!("{}.{key}", self.path)
    }
}

/// The lists of the description that the reader appends to.
#[derive(Clone, Copy)]
enum Section {
    Joints,
    Drivers,
    Forces,
}

struct Builder {
    bodies: Vec<BodyOut>,
    by_id: HashMap<i64, usize>,
    ground: Vec<(String, [f64; 2])>,
    /// Names of joints, drivers and forces given so far.
    names: HashSet<String>,
    joints: Vec<Item>,
    drivers: Vec<Item>,
    forces: Vec<Item>,
    origins: Vec<Origin>,
    warnings: Vec<AdmFail>,
    /// The constant AbsoluteX and AbsoluteY read so far.
    pins: Vec<Pin>,
    /// The `.adm`'s folder, where a `PointForceFile`'s m-file is looked for
    /// (then in its parent).
    folder: Option<PathBuf>,
}

fn fail<T>(path: impl Into<String>, label: Option<&str>, message: impl Into<String>) -> R<T> {
    Err(AdmFail {
        path: path.into(),
        label: label.map(str::to_string),
        message: message.into(),
    })
}

/// Deserialises `v` into `T`, with the failing field's path below `path`.
fn parse<T: DeserializeOwned>(v: &Value, path: &str, label: Option<&str>) -> R<T> {
    serde_path_to_error::deserialize(v).map_err(|e| {
        let inner = camlink_model::text::field_path(e.path());
        let full = match (path.is_empty(), inner.is_empty()) {
            (_, true) => path.to_string(),
            (true, false) => inner,
            (false, false) if inner.starts_with('[') => format!("{path}{inner}"),
            (false, false) => format!("{path}.{inner}"),
        };
        AdmFail {
            path: full,
            label: label.map(str::to_string),
            message: e.into_inner().to_string(),
        }
    })
}

/// A name usable in camlink (letters, digits, `_` and `-`, not starting
/// with `-`): every other character, such as the space of `Long Rod`,
/// becomes `_`.
fn clean(name: &str) -> String {
    name.trim()
        .chars()
        .enumerate()
        .map(|(k, c)| {
            if c.is_alphanumeric() || c == '_' || (c == '-' && k > 0) {
                c
            } else {
                '_'
            }
        })
        .collect()
}

fn pair(v: [Number; 2]) -> [f64; 2] {
    [v[0].0, v[1].0]
}

fn is_none(fun: Option<&str>) -> bool {
    fun.is_none_or(|f| f.trim().is_empty() || f.trim().eq_ignore_ascii_case("NONE"))
}

/// The name of the revolute made of an AbsoluteX named `x` and an
/// AbsoluteY named `y`: their common beginning (`O` for `O_x`, `O_y`), else
/// `x+y`.
fn pin_name(x: &str, y: &str) -> String {
    let common: String = x
        .chars()
        .zip(y.chars())
        .take_while(|(a, b)| a == b)
        .map(|(a, _)| a)
        .collect();
    let common = common.trim_end_matches(['_', '-', ' ']);
    if common.is_empty() {
        format!("{x}+{y}")
    } else {
        common.to_string()
    }
}

/// An entry's name and id as written, read leniently for labels.
fn name_and_id(v: &Value) -> (Option<String>, Option<String>) {
    let name = v.get("name").and_then(Value::as_str).map(str::to_string);
    let id = v.get("id").map(|id| match id {
        Value::String(s) => s.clone(),
        other => other.to_string(),
    });
    (name, id)
}

fn label(kind: &str, name: Option<&str>, id: Option<&str>) -> String {
    match (name, id) {
        (Some(n), Some(i)) => format!("{kind} '{n}' (id {i})"),
        (Some(n), None) => format!("{kind} '{n}'"),
        (None, Some(i)) => format!("{kind} with id {i}"),
        (None, None) => kind.to_string(),
    }
}

/// A function of t as a description value: a number when it is a plain
/// number, else camlink expression text; and whether it uses t.
fn fun_item(src: &str, path: &str, label: &str) -> R<(Item, bool)> {
    let t = matlab::translate(src, true)
        .or_else(|e| fail(path, Some(label), format!("cannot read the function: {e}")))?;
    let item = match t.text.parse::<f64>() {
        Ok(v) if v.is_finite() => Item::Num(v),
        _ => Item::Str(t.text),
    };
    Ok((item, t.uses_t))
}

/// Builds the description of `adm`, read from `folder` (where a
/// `PointForceFile`'s m-file is looked for); its `[analysis]` comes from
/// [`analysis`].
pub(crate) fn build(adm: &Value, folder: Option<&Path>) -> R<Built> {
    let Value::Object(top) = adm else {
        return fail("", None, "a .adm file is a JSON object");
    };
    let head: format::AdmTop = parse(adm, "", None)?;
    let mut b = Builder {
        bodies: Vec::new(),
        by_id: HashMap::new(),
        ground: Vec::new(),
        names: HashSet::new(),
        joints: Vec::new(),
        drivers: Vec::new(),
        forces: Vec::new(),
        origins: Vec::new(),
        warnings: Vec::new(),
        pins: Vec::new(),
        folder: folder.map(Path::to_path_buf),
    };
    let list = |key: &str| -> R<Vec<Value>> {
        match top.get(key) {
            None | Some(Value::Null) => Ok(Vec::new()),
            Some(Value::Array(a)) => Ok(a.clone()),
            // MATLAB writes a one-element array as the element itself.
            Some(v @ Value::Object(_)) => Ok(vec![v.clone()]),
            Some(_) => fail(key, None, "expected a list of entries"),
        }
    };
    let bodies = list("bodies")?;
    if bodies.is_empty() {
        return fail("bodies", None, "the model has no bodies");
    }
    b.bodies(&bodies)?;
    for (k, c) in list("constraints")?.iter().enumerate() {
        b.constraint(c, k)?;
    }
    b.pair_pins();
    for (k, f) in list("forces")?.iter().enumerate() {
        if f.as_object().is_some_and(|o| o.is_empty()) {
            b.warn(
                format!("forces[{k}]"),
                None,
                "an empty entry {} is ignored: it names no force".to_string(),
            );
            continue;
        }
        b.force(f, k)?;
    }
    if let Some(contacts) = top.get("contacts") {
        let n = match contacts {
            Value::Array(a) => a.len(),
            Value::Null => 0,
            _ => 1,
        };
        if n > 0 {
            b.warn(
                "contacts".to_string(),
                None,
                format!(
                    "{n} contact entr{} ignored: the course engine does not read `contacts`, \
                     and neither does camlink",
                    if n == 1 { "y is" } else { "ies are" }
                ),
            );
        }
    }

    let mut model = Item::Table(Vec::new());
    if let Some(name) = &head.name {
        model.push("name", Item::Str(name.clone()));
    }
    if let Some(g) = head.gravity {
        model.push("gravity", Item::pair(pair(g)));
    }
    let mut doc = Item::Table(Vec::new());
    if model != Item::Table(Vec::new()) {
        doc.push("model", model);
    }
    if !b.ground.is_empty() {
        let points = b.ground.iter().map(|(n, s)| (n.clone(), Item::pair(*s)));
        doc.push(
            "ground",
            Item::table([("points", Item::Table(points.collect()))]),
        );
    }
    let bodies: Vec<Item> = b.bodies.iter().map(body_item).collect();
    doc.push("bodies", Item::List(bodies));
    for (key, items) in [
        ("joints", b.joints),
        ("drivers", b.drivers),
        ("forces", b.forces),
    ] {
        if !items.is_empty() {
            doc.push(key, Item::List(items));
        }
    }
    Ok(Built {
        doc,
        origins: b.origins,
        warnings: b.warnings,
    })
}

fn body_item(b: &BodyOut) -> Item {
    let q0 = b.body.q0;
    let qd0 = b.body.qd0.unwrap_or([Number(0.0); 3]);
    let mut t = Item::table([
        ("name", Item::Str(b.name.clone())),
        ("mass", Item::Num(b.body.mass.map_or(0.0, |m| m.0))),
        ("inertia", Item::Num(b.body.jbar.map_or(0.0, |j| j.0))),
        ("position", Item::pair([q0[0].0, q0[1].0])),
        ("angle", Item::Num(q0[2].0)),
    ]);
    if qd0.iter().any(|v| v.0 != 0.0) {
        t.push("velocity", Item::pair([qd0[0].0, qd0[1].0]));
        t.push("omega", Item::Num(qd0[2].0));
    }
    if !b.points.is_empty() {
        let pts = b.points.iter().map(|(n, s)| (n.clone(), Item::pair(*s)));
        t.push("points", Item::Table(pts.collect()));
    }
    if let Some(corners) = b.body.vis.as_ref().and_then(rectangle) {
        t.push(
            "outline",
            Item::List(corners.into_iter().map(Item::pair).collect()),
        );
    }
    t
}

/// The corners of a body's one `vis` rectangle (`loc` its centre, `size`
/// [length, width] along the body's x and y axes; m), counter-clockwise;
/// `None` unless `vis.shapes` holds exactly one readable rectangle.
fn rectangle(vis: &Value) -> Option<Vec<[f64; 2]>> {
    let number = |v: &Value| match v {
        Value::Number(n) => n.as_f64(),
        Value::String(s) => format::constant(s).ok(),
        _ => None,
    };
    let pair = |v: Option<&Value>| -> Option<[f64; 2]> {
        match v? {
            Value::Array(a) if a.len() == 2 => Some([number(&a[0])?, number(&a[1])?]),
            _ => None,
        }
    };
    let shapes = match vis.get("shapes")? {
        Value::Array(a) => a.iter().collect::<Vec<_>>(),
        one @ Value::Object(_) => vec![one],
        _ => return None,
    };
    let [shape] = shapes.as_slice() else {
        return None;
    };
    let (loc, size) = (pair(shape.get("loc"))?, pair(shape.get("size"))?);
    let (hx, hy) = (size[0].abs() / 2.0, size[1].abs() / 2.0);
    if !(hx > 0.0
        && hy > 0.0
        && loc.iter().all(|v| v.is_finite())
        && hx.is_finite()
        && hy.is_finite())
    {
        return None;
    }
    Some(vec![
        [loc[0] - hx, loc[1] - hy],
        [loc[0] + hx, loc[1] - hy],
        [loc[0] + hx, loc[1] + hy],
        [loc[0] - hx, loc[1] + hy],
    ])
}

/// The `[analysis]` table of a `.acf`.
pub(crate) fn analysis(acf: &Value) -> R<Item> {
    let a: Acf = parse(acf, "", Some("analysis file"))?;
    let kind = match a.simulation.trim().to_ascii_lowercase().as_str() {
        "kinematics" => "kinematics",
        "dynamics" => "dynamics",
        "equilibrium" => "equilibrium",
        other => {
            return fail(
                "simulation",
                Some("analysis file"),
                format!(
                    "unknown simulation '{other}'; expected Kinematics, Dynamics or Equilibrium"
                ),
            )
        }
    };
    let mut t = Item::table([("type", Item::Str(kind.into()))]);
    if kind == "equilibrium" {
        return Ok(t);
    }
    let Some(tend) = a.tend else {
        return fail("tend", Some("analysis file"), "missing field `tend`");
    };
    let step = match (a.outputSteps, a.stepSize) {
        (Some(n), _) => {
            if n.0 < 1.0 || n.0.fract() != 0.0 {
                return fail(
                    "outputSteps",
                    Some("analysis file"),
                    format!(
                        "outputSteps is a whole number of output intervals ≥ 1, not {}",
                        camlink_core::fmt_num::num(n.0)
                    ),
                );
            }
            tend.0 / n.0
        }
        (None, Some(h)) => h.0,
        (None, None) => {
            return fail(
                "outputSteps",
                Some("analysis file"),
                "give outputSteps (output intervals over [0, tend]) or stepSize",
            )
        }
    };
    t.push("t_end", Item::Num(tend.0));
    t.push("step", Item::Num(step));
    if kind == "dynamics" {
        if let Some(h) = a.stepSize {
            t.push("h", Item::Num(h.0));
        }
    }
    Ok(t)
}

impl Builder {
    fn warn(&mut self, path: String, label: Option<&str>, message: String) {
        self.warnings.push(AdmFail {
            path,
            label: label.map(str::to_string),
            message,
        });
    }

    /// Registers a joint, driver or force name: the file's, else `fallback`;
    /// a name already taken gets `_<id>`, then a counter.
    fn unique(&mut self, given: Option<&str>, fallback: &str, id: Option<&str>) -> String {
        let base = given
            .map(clean)
            .filter(|n| !n.is_empty())
            .unwrap_or_else(|| fallback.to_string());
        let mut name = base.clone();
        if self.names.contains(&name) {
            if let Some(id) = id {
                name = format!("{base}_{}", clean(id));
            }
        }
        let mut n = 2;
        while self.names.contains(&name) {
            name = format!("{base}_{n}");
            n += 1;
        }
        self.names.insert(name.clone());
        name
    }

    fn bodies(&mut self, list: &[Value]) -> R<()> {
        let mut taken: HashSet<String> = HashSet::from(["ground".to_string()]);
        for (k, v) in list.iter().enumerate() {
            let path = format!("bodies[{k}]");
            let (name, id) = name_and_id(v);
            let lab = label("body", name.as_deref(), id.as_deref());
            let body: format::Body = parse(v, &path, Some(&lab))?;
            if let Some(&first) = self.by_id.get(&body.id.0) {
                return fail(
                    format!("{path}.id"),
                    Some(&lab),
                    format!("id {} is also the id of bodies[{first}]", body.id.0),
                );
            }
            let fallback = format!("body{}", body.id.0);
            let mut out = name
                .as_deref()
                .map(clean)
                .filter(|n| !n.is_empty())
                .unwrap_or(fallback.clone());
            if taken.contains(&out) {
                out = format!("{out}_{}", body.id.0);
            }
            let mut n = 2;
            while taken.contains(&out) {
                out = format!("{fallback}_{n}");
                n += 1;
            }
            for (field, value) in [("mass", body.mass), ("jbar", body.jbar)] {
                if value.is_some_and(|v| v.0 < 0.0) {
                    return fail(
                        format!("{path}.{field}"),
                        Some(&lab),
                        format!("{field} must not be negative"),
                    );
                }
            }
            taken.insert(out.clone());
            self.by_id.insert(body.id.0, self.bodies.len());
            self.bodies.push(BodyOut {
                name: out,
                body,
                points: Vec::new(),
            });
        }
        Ok(())
    }

    /// The body of an id; `None` (no id) is the ground.
    fn body(&self, id: Option<Id>, path: &str, lab: &str) -> R<Option<usize>> {
        match id {
            None => Ok(None),
            Some(Id(i)) => match self.by_id.get(&i) {
                Some(&k) => Ok(Some(k)),
                None => {
                    let mut ids: Vec<i64> = self.by_id.keys().copied().collect();
                    ids.sort_unstable();
                    let ids: Vec<String> = ids.iter().map(i64::to_string).collect();
                    fail(
                        path,
                        Some(lab),
                        format!("no body has id {i} (the body ids are {})", ids.join(", ")),
                    )
                }
            },
        }
    }

    fn body_name(&self, b: Option<usize>) -> Item {
        Item::Str(b.map_or("ground".to_string(), |k| self.bodies[k].name.clone()))
    }

    /// A named point of body `b` (the ground for `None`) at `s` (m):
    /// an existing point at the same place, else a new point named `hint`.
    fn point(&mut self, b: Option<usize>, s: [f64; 2], hint: &str) -> Item {
        let points = match b {
            Some(k) => &mut self.bodies[k].points,
            None => &mut self.ground,
        };
        // A body's joints at one place share its point; ground points stay
        // one per joint, named after it.
        if let Some((n, _)) = points.iter().find(|(_, p)| *p == s && b.is_some()) {
            return Item::Str(n.clone());
        }
        let mut name = hint.to_string();
        let mut n = 2;
        while points.iter().any(|(p, _)| *p == name) {
            name = format!("{hint}_{n}");
            n += 1;
        }
        points.push((name.clone(), s));
        Item::Str(name)
    }

    fn origin(
        &mut self,
        prefix: String,
        adm_path: &str,
        lab: &str,
        fields: Vec<(&'static str, &'static str)>,
    ) {
        self.origins.push(Origin {
            prefix,
            adm_path: adm_path.to_string(),
            label: lab.to_string(),
            fields,
        });
    }

    /// Appends `item` to the description's `joints`, `drivers` or `forces`
    /// and records where it came from.
    fn add(
        &mut self,
        section: Section,
        item: Item,
        path: &str,
        lab: &str,
        fields: Vec<(&'static str, &'static str)>,
    ) {
        let (key, list) = match section {
            Section::Joints => ("joints", &mut self.joints),
            Section::Drivers => ("drivers", &mut self.drivers),
            Section::Forces => ("forces", &mut self.forces),
        };
        let prefix = format!("{key}[{}]", list.len());
        list.push(item);
        self.origin(prefix, path, lab, fields);
    }

    /// Reads constraint `k`: the joint kind whose registry line lists its
    /// course type, and that kind's translation.
    fn constraint(&mut self, v: &Value, k: usize) -> R<()> {
        let path = format!("constraints[{k}]");
        let (name, id) = name_and_id(v);
        let lab = label("constraint", name.as_deref(), id.as_deref());
        let p = path.as_str();
        let Some(course) = v.get("type") else {
            return fail(
                format!("{p}.type"),
                Some(&lab),
                format!(
                    "missing field `type` (one of {})",
                    constraint_types().join(", ")
                ),
            );
        };
        let course = course.as_str().unwrap_or_default();
        let Some((kind, translate)) = translation(course) else {
            return fail(
                format!("{p}.type"),
                Some(&lab),
                format!(
                    "unknown constraint type '{course}'; the supported types are {}",
                    constraint_types().join(", ")
                ),
            );
        };
        let fallback = format!(
            "constraint{}",
            id.as_deref().map(clean).unwrap_or_else(|| k.to_string())
        );
        let entry = Entry {
            v,
            path: p,
            lab: &lab,
            course,
            kind,
            name: name.as_deref(),
            id: id.as_deref(),
            fallback: &fallback,
        };
        translate(self, &entry)
    }

    /// The joint, driver or force name of an entry: its own, else its
    /// fallback, made unique.
    fn name_of(&mut self, e: &Entry) -> String {
        self.unique(e.name, e.fallback, e.id)
    }

    /// The `fun` of an `AbsoluteX`, `AbsoluteY` or `AbsoluteAngle`, which
    /// must be given: its value and whether it uses t.
    fn driving_fun(e: &Entry, fun: &str) -> R<(Item, bool)> {
        let path = e.field("fun");
        if is_none(Some(fun)) {
            return fail(
                path,
                Some(e.lab),
                format!("{} needs a fun: a constant or a function of t", e.course),
            );
        }
        fun_item(fun, &path, e.lab)
    }

    /// `AbsoluteX`/`AbsoluteY` → a driver of the kind (`absolute_x`,
    /// `absolute_y`) for a function of t; for a constant a pin, which
    /// [`Builder::pair_pins`] places.
    fn absolute_coord(&mut self, e: &Entry) -> R<()> {
        let c: format::AbsoluteCoord = parse(e.v, e.path, Some(e.lab))?;
        let body = self
            .body(Some(c.body1), &e.field("body1"), e.lab)?
            .unwrap_or_default();
        let (f, uses_t) = Self::driving_fun(e, &c.fun)?;
        let s = pair(c.sP1);
        let name = self.name_of(e);
        if uses_t {
            let point = self.point(Some(body), s, &name);
            let item = Item::table([
                ("name", Item::Str(name)),
                ("type", Item::Str(e.kind.into())),
                ("body", self.body_name(Some(body))),
                ("point", point),
                ("f", f),
            ]);
            self.add(
                Section::Drivers,
                item,
                e.path,
                e.lab,
                vec![("body", "body1"), ("point", "sP1"), ("f", "fun")],
            );
        } else {
            let value = match &f {
                Item::Str(text) => camlink_expr::eval_constant(text, &Default::default())
                    .or_else(|err| fail(e.field("fun"), Some(e.lab), err.message))?,
                Item::Num(v) => *v,
                _ => f64::NAN,
            };
            self.pins.push(Pin {
                path: e.path.to_string(),
                label: e.lab.to_string(),
                name,
                axis: e.kind,
                body,
                s,
                value,
                text: f,
            });
        }
        Ok(())
    }

    /// `AbsoluteAngle` → `absolute_phi`: a joint holding a constant, a
    /// driver for a function of t.
    fn absolute_angle(&mut self, e: &Entry) -> R<()> {
        let c: format::AbsoluteAngle = parse(e.v, e.path, Some(e.lab))?;
        let body = self.body(Some(c.body1), &e.field("body1"), e.lab)?;
        let (f, uses_t) = Self::driving_fun(e, &c.fun)?;
        let name = self.name_of(e);
        let mut item = Item::table([
            ("name", Item::Str(name)),
            ("type", Item::Str(e.kind.into())),
            ("body", self.body_name(body)),
        ]);
        if uses_t {
            item.push("f", f);
            self.add(
                Section::Drivers,
                item,
                e.path,
                e.lab,
                vec![("body", "body1"), ("f", "fun")],
            );
        } else {
            item.push("value", f);
            self.add(
                Section::Joints,
                item,
                e.path,
                e.lab,
                vec![("body", "body1"), ("value", "fun")],
            );
        }
        Ok(())
    }

    /// `RevoluteJoint` → `revolute`.
    fn revolute(&mut self, e: &Entry) -> R<()> {
        let (c, b1, b2) = self.joint_of::<format::Revolute>(e)?;
        let name = self.name_of(e);
        let p1 = self.point(b1, pair(c.sP1), &name);
        let p2 = self.point(b2, pair(c.sP2), &name);
        let item = Item::table([
            ("name", Item::Str(name)),
            ("type", Item::Str(e.kind.into())),
            ("body_i", self.body_name(b1)),
            ("point_i", p1),
            ("body_j", self.body_name(b2)),
            ("point_j", p2),
        ]);
        self.add(
            Section::Joints,
            item,
            e.path,
            e.lab,
            vec![
                ("body_i", "body1"),
                ("point_i", "sP1"),
                ("body_j", "body2"),
                ("point_j", "sP2"),
            ],
        );
        Ok(())
    }

    /// `TranslationalJoint` → `translational`, with `angle` θ₀ the root of
    /// v₁⊥·v₂ = 0 nearest the initial φ₂ − φ₁.
    fn translational(&mut self, e: &Entry) -> R<()> {
        let (c, b1, b2) = self.joint_of::<format::Translational>(e)?;
        let (v1, v2) = (pair(c.vP1), pair(c.vP2));
        for (field, v) in [("vP1", v1), ("vP2", v2)] {
            if v[0] == 0.0 && v[1] == 0.0 {
                return fail(e.field(field), Some(e.lab), "the direction vector is zero");
            }
        }
        // θ₀: the root of v₁⊥·v₂ = 0 nearest the initial φ₂ − φ₁.
        let phi = |b: Option<usize>| b.map_or(0.0, |k| self.bodies[k].body.q0[2].0);
        let base = v1[1].atan2(v1[0]) - v2[1].atan2(v2[0]);
        let turns = ((phi(b2) - phi(b1) - base) / PI).round();
        let angle = base + turns * PI;
        let name = self.name_of(e);
        let p1 = self.point(b1, pair(c.sP1), &name);
        let p2 = self.point(b2, pair(c.sP2), &name);
        let item = Item::table([
            ("name", Item::Str(name)),
            ("type", Item::Str(e.kind.into())),
            ("body_i", self.body_name(b1)),
            ("point_i", p1),
            ("axis", Item::pair(v1)),
            ("body_j", self.body_name(b2)),
            ("point_j", p2),
            ("angle", Item::Num(angle)),
        ]);
        self.add(
            Section::Joints,
            item,
            e.path,
            e.lab,
            vec![
                ("body_i", "body1"),
                ("point_i", "sP1"),
                ("axis", "vP1"),
                ("body_j", "body2"),
                ("point_j", "sP2"),
                ("angle", "vP2"),
            ],
        );
        Ok(())
    }

    /// `RackPinion` → `rack_pinion` (rolling) with phase
    /// c = |sQ1 − sP1| + R₂(θ₁ − θ₂ + 3π/2), then a `revolute_translational`
    /// holding the pinion centre at R₂ to the left of the pitch line.
    fn rack_pinion(&mut self, e: &Entry) -> R<()> {
        let (c, rack, pinion) = self.joint_of::<format::RackPinion>(e)?;
        let (sp, sq) = (pair(c.sP1), pair(c.sQ1));
        let axis = [sq[0] - sp[0], sq[1] - sp[1]];
        let length = axis[0].hypot(axis[1]);
        if length == 0.0 {
            return fail(
                e.field("sQ1"),
                Some(e.lab),
                "sQ1 equals sP1: the pitch line has no direction",
            );
        }
        let r = c.R2.0;
        if r <= 0.0 {
            return fail(
                e.field("R2"),
                Some(e.lab),
                format!(
                    "the pitch radius R2 must be positive ({} m)",
                    camlink_core::fmt_num::num(r)
                ),
            );
        }
        let phase = length + r * (c.theta1.0 - c.theta2.0 + 1.5 * PI);
        let name = self.name_of(e);
        let centre_name = self.unique(Some(&format!("{name}_centre")), "", None);
        let line = self.point(rack, sp, &format!("{name}_P"));
        self.point(rack, sq, &format!("{name}_Q"));
        let centre = self.point(pinion, pair(c.sP2), &name);
        let rolling = Item::table([
            ("name", Item::Str(name)),
            ("type", Item::Str(e.kind.into())),
            ("body_i", self.body_name(pinion)),
            ("point_i", centre.clone()),
            ("radius", Item::Num(r)),
            ("body_j", self.body_name(rack)),
            ("point_j", line.clone()),
            ("axis", Item::pair(axis)),
            ("phase", Item::Num(phase)),
        ]);
        let fields = vec![
            ("body_i", "body2"),
            ("point_i", "sP2"),
            ("radius", "R2"),
            ("body_j", "body1"),
            ("point_j", "sP1"),
            ("axis", "sQ1"),
            ("phase", "theta1"),
        ];
        self.add(Section::Joints, rolling, e.path, e.lab, fields);
        let on_line = Item::table([
            ("name", Item::Str(centre_name)),
            ("type", Item::Str("revolute_translational".into())),
            ("body_i", self.body_name(pinion)),
            ("point_i", centre),
            ("body_j", self.body_name(rack)),
            ("point_j", line),
            ("axis", Item::pair(axis)),
            ("offset", Item::Num(r)),
        ]);
        let fields = vec![
            ("body_i", "body2"),
            ("point_i", "sP2"),
            ("body_j", "body1"),
            ("point_j", "sP1"),
            ("axis", "sQ1"),
            ("offset", "R2"),
        ];
        self.add(Section::Joints, on_line, e.path, e.lab, fields);
        Ok(())
    }

    /// A joint between `body1` and `body2` read from entry `e`, with its bodies.
    /// The course engine reads every constraint's `fun` and never uses a
    /// joint's: a constant `fun` is ignored with a warning, a function of t
    /// (which would mean a motion the joint cannot impose) is refused.
    fn joint_of<T: DeserializeOwned + format::TwoBodies>(
        &mut self,
        e: &Entry,
    ) -> R<(T, Option<usize>, Option<usize>)> {
        let (p, lab, kind) = (e.path, e.lab, e.course);
        let c: T = parse(e.v, p, Some(lab))?;
        if let Some(fun) = c.fun().filter(|f| !is_none(Some(f))) {
            let path = e.field("fun");
            let (_, uses_t) = fun_item(fun, &path, lab)?;
            if uses_t {
                return fail(
                    path,
                    Some(lab),
                    format!(
                        "a {kind} takes no function of time, but fun is \"{fun}\"; the course \
                         engine ignores a {kind}'s fun, so this motion would not be imposed: \
                         drive it with an AbsoluteX, AbsoluteY or AbsoluteAngle, and write \
                         \"NONE\" here"
                    ),
                );
            }
            self.warn(
                path,
                Some(lab),
                format!("fun \"{fun}\" is ignored: the course engine does not use a {kind}'s fun"),
            );
        }
        let (b1, b2) = c.bodies();
        let (k1, k2) = self.two_bodies(b1, b2, p, lab)?;
        Ok((c, k1, k2))
    }

    /// body1 and body2 (either may be the ground, not both, not the same).
    fn two_bodies(
        &self,
        b1: Option<Id>,
        b2: Option<Id>,
        p: &str,
        lab: &str,
    ) -> R<(Option<usize>, Option<usize>)> {
        let k1 = self.body(b1, &format!("{p}.body1"), lab)?;
        let k2 = self.body(b2, &format!("{p}.body2"), lab)?;
        if k1 == k2 {
            let what = if k1.is_none() {
                "both bodies are the ground (body1 and body2 are missing)"
            } else {
                "body1 and body2 are the same body"
            };
            return fail(format!("{p}.body2"), Some(lab), what);
        }
        Ok((k1, k2))
    }

    /// Places the constant AbsoluteX/AbsoluteY constraints: a pair at the
    /// same point of one body becomes a revolute to a ground point; the
    /// others stay single `absolute_x`/`absolute_y` joints.
    fn pair_pins(&mut self) {
        let pins = std::mem::take(&mut self.pins);
        let mut used = vec![false; pins.len()];
        for a in 0..pins.len() {
            if used[a] {
                continue;
            }
            let x = &pins[a];
            let partner = (a + 1..pins.len()).find(|&c| {
                let y = &pins[c];
                !used[c]
                    && y.body == x.body
                    && y.s == x.s
                    && x.axis != y.axis
                    && x.value.is_finite()
                    && y.value.is_finite()
            });
            used[a] = true;
            let prefix = format!("joints[{}]", self.joints.len());
            match partner {
                Some(c) => {
                    used[c] = true;
                    let (px, py) = if x.axis == "absolute_x" {
                        (x, &pins[c])
                    } else {
                        (&pins[c], x)
                    };
                    let name = self.unique(Some(&pin_name(&px.name, &py.name)), "pin", None);
                    let ground = self.point(
                        None,
                        [px.value, py.value],
                        &format!("{}_pin", self.bodies[px.body].name),
                    );
                    let point = self.point(Some(px.body), px.s, &name);
                    self.joints.push(Item::table([
                        ("name", Item::Str(name)),
                        ("type", Item::Str("revolute".into())),
                        ("body_i", Item::Str("ground".into())),
                        ("point_i", ground),
                        ("body_j", self.body_name(Some(px.body))),
                        ("point_j", point),
                    ]));
                    for pin in [px, py] {
                        let fields =
                            vec![("body_j", "body1"), ("point_j", "sP1"), ("point_i", "fun")];
                        self.origin(prefix.clone(), &pin.path, &pin.label, fields);
                    }
                }
                None => {
                    let point = self.point(Some(x.body), x.s, &x.name);
                    self.joints.push(Item::table([
                        ("name", Item::Str(x.name.clone())),
                        ("type", Item::Str(x.axis.into())),
                        ("body", self.body_name(Some(x.body))),
                        ("point", point),
                        ("value", x.text.clone()),
                    ]));
                    let fields = vec![("body", "body1"), ("point", "sP1"), ("value", "fun")];
                    self.origin(prefix, &x.path, &x.label, fields);
                }
            }
        }
    }

    fn force(&mut self, v: &Value, k: usize) -> R<()> {
        let path = format!("forces[{k}]");
        let (name, id) = name_and_id(v);
        let lab = label("force", name.as_deref(), id.as_deref());
        let p = path.as_str();
        let Some(kind) = v.get("type") else {
            return fail(
                format!("{p}.type"),
                Some(&lab),
                format!("missing field `type` (one of {})", FORCE_TYPES.join(", ")),
            );
        };
        let kind = kind.as_str().unwrap_or_default();
        let fallback = format!(
            "force{}",
            id.as_deref().map(clean).unwrap_or_else(|| k.to_string())
        );
        let opt_fun = |fun: Option<&str>, field: &str| -> R<Item> {
            match fun {
                f if is_none(f) => Ok(Item::Num(0.0)),
                Some(f) => fun_item(f, &format!("{p}.{field}"), &lab).map(|(i, _)| i),
                None => Ok(Item::Num(0.0)),
            }
        };
        match kind {
            "PointForce" => {
                let f: format::PointForce = parse(v, p, Some(&lab))?;
                let body = self.body(Some(f.body1), &format!("{p}.body1"), &lab)?;
                let local = match f.frame.trim().to_ascii_uppercase().as_str() {
                    "GRF" => false,
                    "LRF" => true,
                    other => return fail(format!("{p}.frame"), Some(&lab), format!("unknown frame '{other}'; expected \"GRF\" (global) or \"LRF\" (body-fixed)")),
                };
                let fx = opt_fun(f.funX.as_deref(), "funX")?;
                let fy = opt_fun(f.funY.as_deref(), "funY")?;
                let name = self.unique(name.as_deref(), &fallback, id.as_deref());
                let point = self.point(body, pair(f.sP1), &name);
                let item = Item::table([
                    ("name", Item::Str(name)),
                    ("type", Item::Str("point_force".into())),
                    ("body", self.body_name(body)),
                    ("point", point),
                    ("fx", fx),
                    ("fy", fy),
                    ("local", Item::Bool(local)),
                ]);
                self.add(
                    Section::Forces,
                    item,
                    p,
                    &lab,
                    vec![
                        ("body", "body1"),
                        ("point", "sP1"),
                        ("fx", "funX"),
                        ("fy", "funY"),
                    ],
                );
            }
            "Torque" => {
                let f: format::Torque = parse(v, p, Some(&lab))?;
                let body = self.body(Some(f.body1), &format!("{p}.body1"), &lab)?;
                let t = opt_fun(Some(&f.fun), "fun")?;
                let name = self.unique(name.as_deref(), &fallback, id.as_deref());
                let item = Item::table([
                    ("name", Item::Str(name)),
                    ("type", Item::Str("torque".into())),
                    ("body", self.body_name(body)),
                    ("torque", t),
                ]);
                self.add(
                    Section::Forces,
                    item,
                    p,
                    &lab,
                    vec![("body", "body1"), ("torque", "fun")],
                );
            }
            "RSDA1" | "RSDA2" => {
                let f: format::Rsda = parse(v, p, Some(&lab))?;
                let (bi, bj) = if kind == "RSDA1" {
                    let b = self.body(f.body1, &format!("{p}.body1"), &lab)?;
                    if b.is_none() {
                        return fail(format!("{p}.body1"), Some(&lab), "missing field `body1`");
                    }
                    (None, b)
                } else {
                    self.two_bodies(f.body1, f.body2, p, &lab)?
                };
                for (field, value) in [("k", f.k.0), ("c", f.c.0)] {
                    if value < 0.0 {
                        return fail(
                            format!("{p}.{field}"),
                            Some(&lab),
                            format!("{field} must not be negative ({value})"),
                        );
                    }
                }
                let actuator = opt_fun(f.fun.as_deref(), "fun")?;
                let name = self.unique(name.as_deref(), &fallback, id.as_deref());
                let item = Item::table([
                    ("name", Item::Str(name)),
                    ("type", Item::Str("rsda".into())),
                    ("body_i", self.body_name(bi)),
                    ("body_j", self.body_name(bj)),
                    ("stiffness", Item::Num(f.k.0)),
                    ("free_angle", Item::Num(f.theta0.0)),
                    ("damping", Item::Num(f.c.0)),
                    ("actuator", actuator),
                ]);
                let fields = if kind == "RSDA1" {
                    vec![
                        ("body_j", "body1"),
                        ("stiffness", "k"),
                        ("free_angle", "theta0"),
                        ("damping", "c"),
                        ("actuator", "fun"),
                    ]
                } else {
                    vec![
                        ("body_i", "body1"),
                        ("body_j", "body2"),
                        ("stiffness", "k"),
                        ("free_angle", "theta0"),
                        ("damping", "c"),
                        ("actuator", "fun"),
                    ]
                };
                self.add(Section::Forces, item, p, &lab, fields);
            }
            "PointForceFile" => {
                let f: format::PointForceFile = parse(v, p, Some(&lab))?;
                let body = self.body(Some(f.body1), &format!("{p}.body1"), &lab)?;
                let local = match f.frame.trim().to_ascii_uppercase().as_str() {
                    "GRF" => false,
                    "LRF" => true,
                    other => return fail(format!("{p}.frame"), Some(&lab), format!("unknown frame '{other}'; expected \"GRF\" (global) or \"LRF\" (body-fixed)")),
                };
                let mpath = format!("{p}.mfile");
                let Some(m) = f.mfile.as_deref().map(str::trim).filter(|m| !m.is_empty()) else {
                    return fail(mpath, Some(&lab), "missing field `mfile`: the name of the MATLAB function that computes the force");
                };
                if !mfile::is_identifier(m) {
                    return fail(
                        mpath,
                        Some(&lab),
                        format!(
                            "mfile '{m}' is not a MATLAB function name (a letter, then letters, digits and _); \
                             the file <mfile>.m is looked for only in the model's folder and its parent{ELSE}"
                        ),
                    );
                }
                let file = format!("{m}.m");
                let dir = self
                    .folder
                    .clone()
                    .filter(|d| !d.as_os_str().is_empty())
                    .unwrap_or_else(|| PathBuf::from("."));
                let places = [dir.join(&file), dir.join("..").join(&file)];
                let Some(found) = places.iter().find(|f| f.is_file()) else {
                    return fail(
                        mpath,
                        Some(&lab),
                        format!(
                            "PointForceFile computes its force with the MATLAB function '{m}', and there is no file {file} \
                             in the model's folder ({}) or its parent, where the course engine finds it{ELSE}",
                            dir.display()
                        ),
                    );
                };
                let shown = found.display().to_string();
                let src = camlink_model::text::read_text(found)
                    .or_else(|e| fail(mpath.clone(), Some(&lab), e.to_string()))?;
                let Some(bk) = body else {
                    return fail(
                        format!("{p}.body1"),
                        Some(&lab),
                        "a PointForceFile acts on a body, not the ground",
                    );
                };
                let bname = self.bodies[bk].name.clone();
                if !mfile::is_identifier(&bname) {
                    return fail(
                        format!("{p}.body1"),
                        Some(&lab),
                        format!("the body name '{bname}' cannot be read in an expression (channels such as {bname}_x need a name of letters, digits and _)"),
                    );
                }
                let force = mfile::translate(&src, &shown, &bname).or_else(|e| {
                    fail(
                        mpath.clone(),
                        Some(&lab),
                        format!("cannot translate the MATLAB force function: {e}"),
                    )
                })?;
                let num = |s: &str| match s.parse::<f64>() {
                    Ok(v) if v.is_finite() => Item::Num(v),
                    _ => Item::Str(s.to_string()),
                };
                let name = self.unique(name.as_deref(), &fallback, id.as_deref());
                let point = self.point(body, pair(f.sP1), &name);
                self.warn(
                    mpath.clone(),
                    Some(&lab),
                    format!(
                        "the force is translated from the MATLAB file {shown} into a point_force of state: fx = {}, fy = {}{}",
                        force.fx,
                        force.fy,
                        if local { " (body-fixed)" } else { "" }
                    ),
                );
                let item = Item::table([
                    ("name", Item::Str(name)),
                    ("type", Item::Str("point_force".into())),
                    ("body", self.body_name(body)),
                    ("point", point),
                    ("fx", num(&force.fx)),
                    ("fy", num(&force.fy)),
                    ("local", Item::Bool(local)),
                ]);
                self.add(
                    Section::Forces,
                    item,
                    p,
                    &lab,
                    vec![
                        ("body", "body1"),
                        ("point", "sP1"),
                        ("fx", "mfile"),
                        ("fy", "mfile"),
                    ],
                );
            }
            other => {
                return fail(
                    format!("{p}.type"),
                    Some(&lab),
                    format!(
                        "unknown force type '{other}'; the supported types are {}",
                        FORCE_TYPES.join(", ")
                    ),
                )
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A translation is reached only through its kind's registry line.
    #[test]
    fn every_translated_kind_lists_its_course_types() {
        for (kind, _) in TRANSLATIONS {
            assert!(
                !course_types(kind).is_empty(),
                "the importer translates `{kind}`, but its line in `joint_kinds!` lists no course type"
            );
        }
    }
}
