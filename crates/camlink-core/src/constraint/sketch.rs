//! What a drawing shows of a joint: a few marks on its two bodies, each in
//! its body's frame (m), from which the drawings, the viewer and the studio
//! draw every joint kind alike ([`super::Equations::sketch`]).

use crate::curve::Curve;
use crate::math::V2;

/// Which of a constraint's two bodies, i or j ([`super::Equations::bodies`]),
/// carries a mark.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    I,
    J,
}

/// How a curve of a contact is drawn: a closed `Cam` or `Roller` is filled
/// as that part; an open one is a plain curve; a `Slot` is a groove.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurveRole {
    Cam,
    Roller,
    Slot,
}

impl CurveRole {
    /// The drawn role of a curve that is `closed` or open: `"cam"`,
    /// `"roller"`, `"slot"`, or `"curve"` for an open cam or roller.
    pub fn drawn(self, closed: bool) -> &'static str {
        match (self, closed) {
            (CurveRole::Slot, _) => "slot",
            (CurveRole::Cam, true) => "cam",
            (CurveRole::Roller, true) => "roller",
            (_, false) => "curve",
        }
    }
}

/// One mark of a joint's drawing; points s′ and unit directions u′ in the
/// frame of the body that carries them (m).
#[derive(Clone, Copy, Debug)]
pub enum Mark<'a> {
    /// A pin joining point `s_i` of body i and point `s_j` of body j; both
    /// points belong to their bodies' drawn links.
    Pin { s_i: V2, s_j: V2 },
    /// A pin at point `s` of one body, running along something of the
    /// other (a line, a slot); the point belongs to its body's link.
    Slider { side: Side, s: V2 },
    /// A massless rod from point `s_i` of body i to point `s_j` of body j.
    Rod { s_i: V2, s_j: V2 },
    /// A prismatic guide: the line of body i through `s_i` along `v_i`,
    /// and the block of body j at `s_j`.
    Guide { s_i: V2, v_i: V2, s_j: V2 },
    /// A straight face (a follower face, a rack's pitch line, a line a pin
    /// runs on) through `s` along `u`.
    Face { side: Side, s: V2, u: V2 },
    /// A pitch circle of `radius` (m) about `s`; `internal` for a ring gear.
    Circle {
        side: Side,
        s: V2,
        radius: f64,
        internal: bool,
    },
    /// A curve the joint runs on, drawn in `role`.
    Curve {
        side: Side,
        curve: &'a Curve,
        role: CurveRole,
    },
}

/// The marks of one joint, in drawing order.
pub(crate) type Sketch<'a> = Vec<Mark<'a>>;
