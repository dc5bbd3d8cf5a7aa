//! The core model: validated and immutable.
//!
//! Units are SI throughout: metres, radians, seconds, kilograms,
//! kilogram-square-metres. Body 0 is the ground, named `ground`, fixed at
//! the origin of the global frame.

use std::collections::HashMap;

use crate::constraint::relative::{RelCoord, RelativeCoord};
pub use crate::constraint::BodyId;
use crate::constraint::{Constraint, Equations, MAX_OWN};
use crate::force::compliant_contact::HuntCrossley;
use crate::force::friction::Friction;
use crate::force::{Applied, Force};
use crate::function::TimeFn;
use crate::math::V2;

/// A named point fixed in a body, at `s` (m) in the body frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    pub name: String,
    pub s: V2,
}

/// A rigid body.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    pub name: String,
    /// Mass m (kg).
    pub mass: f64,
    /// Polar moment of inertia about the centroid J' (kg·m²).
    pub inertia: f64,
    /// Centroid position in the body frame (m).
    pub centroid: V2,
    /// Initial (or guessed) coordinates (x, y, φ) of the body frame (m, m, rad).
    pub q0: [f64; 3],
    /// Initial velocities (ẋ, ẏ, φ̇) (m/s, m/s, rad/s), used by dynamics.
    pub qd0: [f64; 3],
    pub points: Vec<Point>,
}

impl Body {
    /// A massless body at `q0` with no points.
    pub fn new(name: impl Into<String>, q0: [f64; 3]) -> Self {
        Body {
            name: name.into(),
            mass: 0.0,
            inertia: 0.0,
            centroid: [0.0, 0.0],
            q0,
            qd0: [0.0; 3],
            points: Vec::new(),
        }
    }

    /// The local vector of the named point.
    pub fn point(&self, name: &str) -> Option<V2> {
        self.points.iter().find(|p| p.name == name).map(|p| p.s)
    }
}

/// A named constraint: a joint or a driver.
#[derive(Clone, Debug)]
pub struct Joint {
    pub name: String,
    pub constraint: Constraint,
    /// Starting values of the joint's own coordinates, when the model gives them.
    pub own0: Option<[f64; MAX_OWN]>,
    /// True for a driving (rheonomic) constraint.
    pub driver: bool,
    /// `Some` for a cam contact that can open: forward dynamics releases
    /// it where its normal force would turn negative and closes it again
    /// at impact ([`crate::dynamics::unilateral`]).
    pub unilateral: Option<Unilateral>,
    /// `Some` for a joint with end stops on its coordinate ([`Limits`]).
    pub limits: Option<Limits>,
    /// `Some` for Coulomb friction in the joint (a revolute,
    /// translational or curve-contact joint; [`Model::friction_kinds`]).
    pub friction: Option<Friction>,
}

/// End stops on a joint's coordinate ([`crate::limits`]): a revolute's
/// angle θ = φ_j − φ_i (rad), a translational joint's stroke s (m) or a
/// revolute–translational pin's travel along its line (m). Forward
/// dynamics holds the coordinate in [lower, upper] with unilateral stops
/// ([`crate::dynamics::stops`]); kinematics warns when a driven motion
/// leaves the range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// The least value (rad or m); `None`: no stop below.
    pub lower: Option<f64>,
    /// The greatest value (rad or m); `None`: no stop above.
    pub upper: Option<f64>,
    /// How a stop is hit: restitution, rest speed (rad/s or m/s) and event
    /// tolerance of a rigid stop, or the Hunt–Crossley law of a compliant
    /// one (k in N·m/radⁿ or N/mⁿ, c in s/rad or s/m).
    pub law: Unilateral,
}

/// How a unilateral cam contact opens, flies and lands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unilateral {
    /// Newton's coefficient of restitution e ∈ [0, 1]: the normal
    /// separation speed after an impact is e times the approach speed.
    pub restitution: f64,
    /// Approach speed (m/s) below which an impact closes the contact
    /// (plastic): the end of a chatter of ever smaller bounces.
    pub rest_speed: f64,
    /// Time tolerance (s) of the located lift-off and impact events.
    pub event_tol: f64,
    /// `Some` for a compliant contact: a Hunt–Crossley normal force from
    /// the overlap instead of impacts and closed phases.
    pub compliant: Option<HuntCrossley>,
}

impl Limits {
    /// The coordinate a joint's limits bound, as the relative constraint
    /// Φ = c(q) − `value`: θ = φ_j − φ_i of a revolute, the stroke
    /// s = (A_i v'_i)ᵀ(r_j^P − r_i^P) of a translational joint, the travel
    /// (A_j v'_j)ᵀ(r_i^P − r_j^Q) of a revolute–translational pin along
    /// its line. `None` for a joint kind that has no limits.
    pub fn coordinate(c: &Constraint, value: f64) -> Option<RelativeCoord> {
        let f = TimeFn::Const(value);
        Some(match c {
            Constraint::Revolute(r) => RelativeCoord {
                body_i: r.body_i,
                s_i: r.s_i,
                body_j: r.body_j,
                s_j: r.s_j,
                coord: RelCoord::Phi,
                f,
            },
            Constraint::Translational(t) => RelativeCoord {
                body_i: t.body_i,
                s_i: t.s_i,
                body_j: t.body_j,
                s_j: t.s_j,
                coord: RelCoord::Along(t.v_i),
                f,
            },
            Constraint::RevoluteTranslational(p) => RelativeCoord {
                body_i: p.body_j,
                s_i: p.s_j,
                body_j: p.body_i,
                s_j: p.s_i,
                coord: RelCoord::Along(p.v_j),
                f,
            },
            _ => return None,
        })
    }

    /// The name and unit of the coordinate of [`coordinate`](Self::coordinate).
    pub fn coordinate_name(c: &Constraint) -> Option<(&'static str, &'static str)> {
        match c {
            Constraint::Revolute(_) => Some(("angle", "rad")),
            Constraint::Translational(_) => Some(("stroke", "m")),
            Constraint::RevoluteTranslational(_) => Some(("travel", "m")),
            _ => None,
        }
    }

    /// Checks the limits of a joint of constraint `c`: a kind that has
    /// them, finite values, lower < upper, at least one given, a law in
    /// range.
    pub fn validate(&self, c: &Constraint) -> Result<(), String> {
        if Self::coordinate_name(c).is_none() {
            return Err(format!(
                "a {} joint has no limits; revolute, translational and \
                 revolute_translational joints do",
                c.kind()
            ));
        }
        let num = crate::fmt_num::num;
        let values = [self.lower, self.upper];
        if values.iter().flatten().any(|v| !v.is_finite()) {
            return Err("limits must be finite numbers".into());
        }
        match values {
            [None, None] => return Err("limits need a lower or an upper value".into()),
            [Some(lo), Some(hi)] if lo >= hi => {
                return Err(format!(
                    "the lower limit {} must be below the upper limit {}",
                    num(lo),
                    num(hi)
                ))
            }
            _ => {}
        }
        let u = &self.law;
        if !(0.0..=1.0).contains(&u.restitution) {
            return Err(format!(
                "restitution must be between 0 and 1, not {}",
                num(u.restitution)
            ));
        }
        if !(u.event_tol > 0.0 && u.rest_speed >= 0.0) {
            return Err("event_tol must be positive and rest_speed not negative".into());
        }
        Ok(())
    }
}

impl Default for Unilateral {
    fn default() -> Self {
        Unilateral {
            restitution: 0.0,
            rest_speed: 1e-3,
            event_tol: 1e-9,
            compliant: None,
        }
    }
}

/// A mechanism: bodies (ground first), joints and drivers.
#[derive(Clone, Debug)]
pub struct Model {
    pub name: String,
    pub bodies: Vec<Body>,
    pub joints: Vec<Joint>,
    /// Gravity vector g (m/s²) in the global frame.
    pub gravity: V2,
    /// Applied forces: point forces and torques, springs, dampers, actuators.
    pub forces: Vec<Force>,
    /// What the description left to be chosen and deserves a look (a
    /// default value that the placement did not pin down), in the order
    /// found.
    pub warnings: Vec<ModelWarning>,
}

/// A warning about a model found while it was built from its description.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelWarning {
    /// A stable name of what it is about, e.g. `"default_moved"`.
    pub kind: &'static str,
    /// Where in the description, e.g. `joints[3].offset`.
    pub field: String,
    pub message: String,
}

/// Why a model is not valid.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelError {
    #[error("duplicate body name '{0}'")]
    DuplicateBody(String),
    #[error("duplicate point name '{point}' on body '{body}'")]
    DuplicatePoint { body: String, point: String },
    #[error("duplicate joint name '{0}'")]
    DuplicateJoint(String),
    #[error("duplicate force name '{0}'")]
    DuplicateForce(String),
    #[error("joint '{joint}' refers to body number {body}, which does not exist")]
    NoSuchBody { joint: String, body: usize },
    #[error("joint '{0}' joins a body to itself")]
    SelfJoint(String),
    #[error("{what} is not a finite number ({})", crate::fmt_num::num(*.value))]
    NotFinite { what: String, value: f64 },
    #[error("{0}")]
    Invalid(String),
    #[error(
        "body '{body}': {what} is {value}; dynamics needs a positive mass and \
         moment of inertia for every moving body"
    )]
    MassProperty {
        body: String,
        what: &'static str,
        value: f64,
    },
    #[error("{}", not_grounded(.bodies, *.none_grounded))]
    NotGrounded {
        /// The moving bodies that no chain of joints ties to the ground.
        bodies: Vec<String>,
        /// True when no joint or driver touches the ground at all.
        none_grounded: bool,
    },
}

/// The shaking channels of the dynamic analyses (`dynamics::output`).
pub const SHAKING: [&str; 3] = ["shaking.fx", "shaking.fy", "shaking.moment"];

/// The namespace of [`SHAKING`]: no body, joint or driver may take this
/// name (a joint `shaking` would write its reaction into `shaking.fx`).
pub(crate) const SHAKING_NAME: &str = "shaking";

/// Why `name` cannot name a body, joint or driver (`what`), if it cannot.
pub fn reserved_name(name: &str, what: &str) -> Option<String> {
    (name == SHAKING_NAME).then(|| {
        format!(
            "{what} name '{name}' is reserved for the shaking channels {}; choose another name",
            SHAKING.join(", ")
        )
    })
}

impl Model {
    /// A model with only the ground.
    pub fn new(name: impl Into<String>) -> Self {
        Model {
            name: name.into(),
            bodies: vec![Body::new("ground", [0.0; 3])],
            joints: Vec::new(),
            gravity: [0.0, -9.81],
            forces: Vec::new(),
            warnings: Vec::new(),
        }
    }

    /// Adds an applied force.
    pub fn add_force(&mut self, force: Force) {
        self.forces.push(force);
    }

    /// Adds a body and returns its id.
    pub fn add_body(&mut self, body: Body) -> BodyId {
        self.bodies.push(body);
        BodyId(self.bodies.len() - 1)
    }

    /// Adds a scleronomic joint.
    pub fn add_joint(&mut self, name: impl Into<String>, c: impl Into<Constraint>) {
        self.joints.push(Joint {
            name: name.into(),
            constraint: c.into(),
            own0: None,
            driver: false,
            unilateral: None,
            limits: None,
            friction: None,
        });
    }

    /// Adds a driving constraint.
    pub fn add_driver(&mut self, name: impl Into<String>, c: impl Into<Constraint>) {
        self.joints.push(Joint {
            name: name.into(),
            constraint: c.into(),
            own0: None,
            driver: true,
            unilateral: None,
            limits: None,
            friction: None,
        });
    }

    pub fn body(&self, id: BodyId) -> &Body {
        &self.bodies[id.0]
    }

    pub fn body_id(&self, name: &str) -> Option<BodyId> {
        self.bodies.iter().position(|b| b.name == name).map(BodyId)
    }

    pub fn joint(&self, name: &str) -> Option<&Joint> {
        self.joints.iter().find(|j| j.name == name)
    }

    /// Moving bodies (all but the ground).
    pub fn moving_bodies(&self) -> impl Iterator<Item = (BodyId, &Body)> {
        self.bodies
            .iter()
            .enumerate()
            .skip(1)
            .map(|(k, b)| (BodyId(k), b))
    }

    /// Checks names, references and numbers.
    pub fn validate(&self) -> Result<(), ModelError> {
        let mut seen = HashMap::new();
        for (k, b) in self.bodies.iter().enumerate() {
            if seen.insert(b.name.as_str(), k).is_some() {
                return Err(ModelError::DuplicateBody(b.name.clone()));
            }
            if let Some(e) = reserved_name(&b.name, "body") {
                return Err(ModelError::Invalid(e));
            }
            let mut pts = HashMap::new();
            for p in &b.points {
                if pts.insert(p.name.as_str(), ()).is_some() {
                    return Err(ModelError::DuplicatePoint {
                        body: b.name.clone(),
                        point: p.name.clone(),
                    });
                }
                finite(&format!("point '{}.{}'", b.name, p.name), &p.s)?;
            }
            finite(&format!("body '{}' position", b.name), &b.q0)?;
            finite(&format!("body '{}' velocity", b.name), &b.qd0)?;
            finite(
                &format!("body '{}' mass properties", b.name),
                &[b.mass, b.inertia, b.centroid[0], b.centroid[1]],
            )?;
        }
        let mut joints = HashMap::new();
        for j in &self.joints {
            if joints.insert(j.name.as_str(), ()).is_some() {
                return Err(ModelError::DuplicateJoint(j.name.clone()));
            }
            let what = if j.driver { "driver" } else { "joint" };
            if let Some(e) = reserved_name(&j.name, what) {
                return Err(ModelError::Invalid(e));
            }
            let [bi, bj] = j.constraint.bodies();
            for b in [bi, bj] {
                if b.0 >= self.bodies.len() {
                    return Err(ModelError::NoSuchBody {
                        joint: j.name.clone(),
                        body: b.0,
                    });
                }
            }
            if bi == bj {
                return Err(ModelError::SelfJoint(j.name.clone()));
            }
            if let Some(o) = &j.own0 {
                finite(&format!("joint '{}' starting parameters", j.name), o)?;
            }
            if let Some(l) = &j.limits {
                l.validate(&j.constraint)
                    .map_err(|e| ModelError::Invalid(format!("joint '{}': {e}", j.name)))?;
            }
            if let Some(f) = &j.friction {
                Self::check_friction(j, f)?;
            }
        }
        let mut forces = HashMap::new();
        for f in &self.forces {
            if forces.insert(f.name.as_str(), ()).is_some() {
                return Err(ModelError::DuplicateForce(f.name.clone()));
            }
            for &b in f.kind.bodies().iter().chain(f.kind.reads()) {
                if b.0 >= self.bodies.len() {
                    return Err(ModelError::Invalid(format!(
                        "force '{}' refers to body number {}, which does not exist",
                        f.name, b.0
                    )));
                }
            }
            f.kind
                .validate()
                .map_err(|e| ModelError::Invalid(format!("force '{}': {e}", f.name)))?;
        }
        finite("gravity", &self.gravity)
    }
}

impl Model {
    /// The joint kinds that take friction, as model files name them.
    pub(crate) fn friction_kinds() -> &'static [&'static str] {
        &[
            "revolute",
            "translational",
            "point_follower",
            "cam_follower",
            "flat_follower",
        ]
    }

    /// Friction only on a joint (not a driver) of a kind that takes it,
    /// a pin radius only on a revolute, valid numbers.
    fn check_friction(j: &Joint, f: &Friction) -> Result<(), ModelError> {
        let invalid = |m: String| ModelError::Invalid(format!("joint '{}': {m}", j.name));
        let c = &j.constraint;
        let takes = !j.driver
            && matches!(
                c,
                Constraint::Revolute(_)
                    | Constraint::Translational(_)
                    | Constraint::PointFollower(_)
                    | Constraint::CamFollower(_)
                    | Constraint::FlatFollower(_)
            );
        if !takes {
            return Err(invalid(format!(
                "a {} {} takes no friction (friction is modelled in {} joints)",
                c.kind(),
                if j.driver { "driver" } else { "joint" },
                Self::friction_kinds().join(", ")
            )));
        }
        if f.radius != 0.0 && !matches!(c, Constraint::Revolute(_)) {
            return Err(invalid(
                "a friction radius is the pin radius of a revolute joint; a sliding \
                 joint's friction is μ times its normal force"
                    .into(),
            ));
        }
        f.validate().map_err(invalid)
    }
}

fn finite(what: &str, v: &[f64]) -> Result<(), ModelError> {
    match v.iter().find(|x| !x.is_finite()) {
        Some(&value) => Err(ModelError::NotFinite {
            what: what.to_string(),
            value,
        }),
        None => Ok(()),
    }
}

/// The message of [`ModelError::NotGrounded`].
fn not_grounded(bodies: &[String], none_grounded: bool) -> String {
    const SHOWN: usize = 5;
    let mut names: Vec<String> = bodies
        .iter()
        .take(SHOWN)
        .map(|b| format!("'{b}'"))
        .collect();
    if bodies.len() > SHOWN {
        names.push(format!("{} more", bodies.len() - SHOWN));
    }
    let list = names.join(", ");
    if none_grounded {
        format!(
            "no joint or driver ties the mechanism to the ground (bodies {list}); \
             join a body to a ground point or drive one of its coordinates"
        )
    } else {
        format!(
            "no chain of joints or drivers ties bodies {list} to the ground; \
             join one of them to the mechanism or to a ground point"
        )
    }
}

impl Model {
    /// Checks that every moving body has a finite, positive mass m and
    /// moment of inertia J', as forward and inverse dynamics need; names the
    /// first body that does not. Kinematics needs no mass.
    pub fn check_mass_properties(&self) -> Result<(), ModelError> {
        for (_, b) in self.moving_bodies() {
            for (what, value) in [
                ("mass m (kg)", b.mass),
                ("moment of inertia J' (kg·m²)", b.inertia),
            ] {
                if !(value.is_finite() && value > 0.0) {
                    return Err(ModelError::MassProperty {
                        body: b.name.clone(),
                        what,
                        value,
                    });
                }
            }
        }
        Ok(())
    }

    /// Checks that a chain of joints or drivers links every moving body to
    /// the ground, as a kinematic analysis needs: a group of bodies joined
    /// only among themselves can translate freely as a whole.
    pub fn check_grounded(&self) -> Result<(), ModelError> {
        // Union–find over bodies, one union per joint.
        let mut parent: Vec<usize> = (0..self.bodies.len()).collect();
        fn root(parent: &mut [usize], mut k: usize) -> usize {
            while parent[k] != k {
                parent[k] = parent[parent[k]];
                k = parent[k];
            }
            k
        }
        for j in &self.joints {
            let [bi, bj] = j.constraint.bodies();
            if bi.0 >= parent.len() || bj.0 >= parent.len() {
                continue;
            }
            let (ri, rj) = (root(&mut parent, bi.0), root(&mut parent, bj.0));
            parent[ri.max(rj)] = ri.min(rj);
        }
        let loose: Vec<String> = (1..self.bodies.len())
            .filter(|&k| root(&mut parent, k) != 0)
            .map(|k| self.bodies[k].name.clone())
            .collect();
        if loose.is_empty() {
            return Ok(());
        }
        Err(ModelError::NotGrounded {
            none_grounded: loose.len() + 1 == self.bodies.len(),
            bodies: loose,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::relative::{RelCoord, RelativeCoord};
    use crate::constraint::revolute::Revolute;
    use crate::function::TimeFn;

    fn pin(bi: BodyId, bj: BodyId) -> Revolute {
        Revolute {
            body_i: bi,
            s_i: [0.0, 0.0],
            body_j: bj,
            s_j: [0.0, 0.0],
        }
    }

    #[test]
    fn issue32_shaking_names_are_refused() {
        let mut m = Model::new("m");
        let a = m.add_body(Body::new("a", [0.0; 3]));
        m.add_joint("shaking", pin(BodyId::GROUND, a));
        let msg = m.validate().unwrap_err().to_string();
        assert!(msg.starts_with("joint name 'shaking' is reserved"), "{msg}");
        let mut m = Model::new("m");
        let a = m.add_body(Body::new("shaking", [0.0; 3]));
        m.add_joint("p0", pin(BodyId::GROUND, a));
        let msg = m.validate().unwrap_err().to_string();
        assert!(msg.starts_with("body name 'shaking' is reserved"), "{msg}");
    }

    #[test]
    fn grounded_chain_passes() {
        let mut m = Model::new("m");
        let a = m.add_body(Body::new("a", [0.0; 3]));
        let b = m.add_body(Body::new("b", [0.0; 3]));
        m.add_joint("p0", pin(BodyId::GROUND, a));
        m.add_joint("p1", pin(a, b));
        assert_eq!(m.check_grounded(), Ok(()));
    }

    #[test]
    fn no_ground_at_all_is_named() {
        let mut m = Model::new("m");
        let a = m.add_body(Body::new("a", [0.0; 3]));
        let b = m.add_body(Body::new("b", [0.0; 3]));
        m.add_joint("p1", pin(a, b));
        m.add_driver(
            "turn",
            RelativeCoord {
                body_i: a,
                s_i: [0.0, 0.0],
                body_j: b,
                s_j: [0.0, 0.0],
                coord: RelCoord::Phi,
                f: TimeFn::Const(0.0),
            },
        );
        let msg = m.check_grounded().unwrap_err().to_string();
        assert!(
            msg.starts_with("no joint or driver ties the mechanism to the ground"),
            "{msg}"
        );
        assert!(msg.contains("'a', 'b'"), "{msg}");
    }

    #[test]
    fn a_loose_group_is_named() {
        let mut m = Model::new("m");
        let a = m.add_body(Body::new("a", [0.0; 3]));
        let b = m.add_body(Body::new("b", [0.0; 3]));
        let c = m.add_body(Body::new("c", [0.0; 3]));
        m.add_joint("p0", pin(BodyId::GROUND, a));
        m.add_joint("p1", pin(b, c));
        let err = m.check_grounded().unwrap_err();
        assert_eq!(
            err,
            ModelError::NotGrounded {
                bodies: vec!["b".into(), "c".into()],
                none_grounded: false
            }
        );
        assert!(
            err.to_string().contains("bodies 'b', 'c' to the ground"),
            "{err}"
        );
    }

    #[test]
    fn mass_properties_name_the_body() {
        let mut m = Model::new("m");
        let mut a = Body::new("a", [0.0; 3]);
        a.mass = 1.0;
        a.inertia = 0.1;
        m.add_body(a);
        assert_eq!(m.check_mass_properties(), Ok(()));
        let mut b = Body::new("coupler", [0.0; 3]);
        b.mass = 2.0;
        m.add_body(b);
        let msg = m.check_mass_properties().unwrap_err().to_string();
        assert!(
            msg.starts_with("body 'coupler': moment of inertia J' (kg·m²) is 0;"),
            "{msg}"
        );
        m.bodies[2].mass = -1.0;
        let msg = m.check_mass_properties().unwrap_err().to_string();
        assert!(msg.contains("mass m (kg) is -1"), "{msg}");
        m.bodies[2].mass = f64::NAN;
        assert!(m.check_mass_properties().is_err());
    }
}
