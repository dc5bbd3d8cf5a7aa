//! The joint kinds of the file format, one `[[joints]]` type each: how a
//! spec becomes a core constraint ([`JointKind::resolve`]) and which of its
//! values are lengths and angles ([`JointKind::to_si`]). The registry at
//! the bottom lists every kind once; `docs/adding-a-joint.md` walks through
//! adding one.

use super::{Ctx, R};
use crate::file::JointSpec;
use crate::units::Convert;

mod absolute;
mod cam_follower;
mod composite;
mod flat_follower;
mod gear;
mod point_follower;
mod relative;
mod revolute;
mod translational;

/// One joint kind of the file format.
pub(crate) trait JointKind {
    /// Checks the spec at `at.path` and adds its constraint to the model,
    /// with its limits, friction, unilateral law and the values it leaves
    /// to the initial placement.
    fn resolve(&self, cx: &mut Ctx, at: &At) -> R<()>;

    /// Converts the values written in the file's declared units (lengths
    /// in m, cm or mm; angles in rad or deg) to SI, in place.
    fn to_si(&mut self, u: &Convert);
}

/// Where a joint spec sits in the file: its type, its index `k` in
/// `[[joints]]` and its field path `joints[k]`.
pub(crate) struct At<'a> {
    pub kind: &'static str,
    pub k: usize,
    pub path: &'a str,
}

impl At<'_> {
    /// The name of a joint the file leaves unnamed: `<type>_<index>`.
    pub(crate) fn default_name(&self) -> String {
        format!("{}_{}", self.kind, self.k)
    }

    /// The path of field `key` of this joint.
    pub(crate) fn field(&self, key: &str) -> String {
        format!("{}.{key}", self.path)
    }
}

impl Ctx {
    /// Resolves `[[joints]]` entry `k`; a joint a driver cannot address by
    /// its geometry is recorded by its type.
    pub(super) fn joint(&mut self, j: &JointSpec, k: usize) -> R<()> {
        let path = format!("joints[{k}]");
        let (kind, spec) = j.kind();
        let first = self.model.joints.len();
        spec.resolve(
            self,
            &At {
                kind,
                k,
                path: &path,
            },
        )?;
        if let Some(added) = self.model.joints.get(first) {
            self.joints
                .entry(added.name.clone())
                .or_insert(super::JointInfo::Other(kind));
        }
        Ok(())
    }
}

/// A joint kind's entry in the registry.
#[derive(Clone, Copy, Debug)]
pub struct JointKindEntry {
    /// The `type` of `[[joints]]`.
    pub kind: &'static str,
    /// The course-file (`.adm`) constraint types the importer turns into
    /// this kind; empty when course files have no such constraint. The
    /// importer (camlink-adm) reads a course type as the kind listed here
    /// whose translation it holds.
    pub course_types: &'static [&'static str],
}

/// The registry: one line per joint kind, in the order of [`JointSpec`].
macro_rules! joint_kinds {
    ($($variant:ident => $kind:literal, course: [$($course:literal),*];)*) => {
        /// Every joint kind of the file format, in the order of [`JointSpec`].
        pub const JOINT_KINDS: &[JointKindEntry] = &[
            $(JointKindEntry { kind: $kind, course_types: &[$($course),*] }),*
        ];

        impl JointSpec {
            /// The `type` of this joint and its description.
            pub(crate) fn kind(&self) -> (&'static str, &dyn JointKind) {
                match self {
                    $(JointSpec::$variant(j) => ($kind, j)),*
                }
            }

            /// This joint's description, to convert its units in place.
            pub(crate) fn kind_mut(&mut self) -> &mut dyn JointKind {
                match self {
                    $(JointSpec::$variant(j) => j),*
                }
            }
        }
    };
}

joint_kinds! {
    Revolute => "revolute", course: ["RevoluteJoint"];
    Translational => "translational", course: ["TranslationalJoint"];
    RevoluteRevolute => "revolute_revolute", course: [];
    RevoluteTranslational => "revolute_translational", course: ["RackPinion"];
    AbsoluteX => "absolute_x", course: ["AbsoluteX"];
    AbsoluteY => "absolute_y", course: ["AbsoluteY"];
    AbsolutePhi => "absolute_phi", course: ["AbsoluteAngle"];
    AbsoluteDistance => "absolute_distance", course: [];
    RelativeX => "relative_x", course: [];
    RelativeY => "relative_y", course: [];
    RelativePhi => "relative_phi", course: [];
    RelativeDistance => "relative_distance", course: [];
    Gear => "gear", course: [];
    RackPinion => "rack_pinion", course: ["RackPinion"];
    CamFollower => "cam_follower", course: [];
    FlatFollower => "flat_follower", course: [];
    PointFollower => "point_follower", course: [];
}
