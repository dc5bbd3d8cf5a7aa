//! What a number measures and in which unit: the quantity of every output
//! channel ([`Channel`]), the length and angle units a model file may be
//! written in ([`Units`]), and the factors between them and SI.
//!
//! Inside camlink every number is SI with angles in radians. A channel
//! carries its [`Quantity`] from where it is named, so that files, plots
//! and reports state its unit without guessing from the name, and can
//! show it in other units ([`Quantity::unit_in`]).

use std::fmt;

/// The kind of a number, which fixes its SI unit ([`Quantity::unit`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Quantity {
    /// s.
    Time,
    /// m.
    Length,
    /// rad.
    Angle,
    /// m/s.
    Velocity,
    /// rad/s.
    AngularVelocity,
    /// m/s².
    Acceleration,
    /// rad/s².
    AngularAcceleration,
    /// m/s³.
    Jerk,
    /// rad/s³.
    AngularJerk,
    /// N.
    Force,
    /// N·m.
    Torque,
    /// W.
    Power,
    /// J.
    Energy,
    /// A pure number (a contact's state, the parameter of a curve written
    /// as expressions): unit "1".
    Dimensionless,
    /// The largest constraint residual max |Φ|, over equations in m and in
    /// rad: "m or rad".
    Residual,
    /// The largest velocity residual max |Φ_q q̇ − ν|: "m/s or rad/s".
    ResidualRate,
}

impl Quantity {
    /// Every quantity, in declaration order.
    pub const ALL: [Quantity; 16] = [
        Quantity::Time,
        Quantity::Length,
        Quantity::Angle,
        Quantity::Velocity,
        Quantity::AngularVelocity,
        Quantity::Acceleration,
        Quantity::AngularAcceleration,
        Quantity::Jerk,
        Quantity::AngularJerk,
        Quantity::Force,
        Quantity::Torque,
        Quantity::Power,
        Quantity::Energy,
        Quantity::Dimensionless,
        Quantity::Residual,
        Quantity::ResidualRate,
    ];

    /// The name used in files and the binding, e.g. `"angular_velocity"`.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Time => "time",
            Quantity::Length => "length",
            Quantity::Angle => "angle",
            Quantity::Velocity => "velocity",
            Quantity::AngularVelocity => "angular_velocity",
            Quantity::Acceleration => "acceleration",
            Quantity::AngularAcceleration => "angular_acceleration",
            Quantity::Jerk => "jerk",
            Quantity::AngularJerk => "angular_jerk",
            Quantity::Force => "force",
            Quantity::Torque => "torque",
            Quantity::Power => "power",
            Quantity::Energy => "energy",
            Quantity::Dimensionless => "dimensionless",
            Quantity::Residual => "residual",
            Quantity::ResidualRate => "residual_rate",
        }
    }

    /// The quantity named `name` ([`Quantity::name`]).
    pub fn from_name(name: &str) -> Option<Quantity> {
        Quantity::ALL.into_iter().find(|q| q.name() == name)
    }

    /// The SI unit (angles in rad).
    pub fn unit(self) -> &'static str {
        self.unit_in(Units::SI).0
    }

    /// The time derivative of a length or an angle quantity (velocity of a
    /// length, …); `None` past the third derivative or for other kinds.
    pub fn rate(self) -> Option<Quantity> {
        Some(match self {
            Quantity::Length => Quantity::Velocity,
            Quantity::Velocity => Quantity::Acceleration,
            Quantity::Acceleration => Quantity::Jerk,
            Quantity::Angle => Quantity::AngularVelocity,
            Quantity::AngularVelocity => Quantity::AngularAcceleration,
            Quantity::AngularAcceleration => Quantity::AngularJerk,
            _ => return None,
        })
    }

    /// The unit of this quantity in `units` and the factor k that turns an
    /// SI value into it (value in `units` = k · SI value). Lengths and their
    /// rates follow `units.length`, angles and theirs `units.angle`; every
    /// other quantity stays SI (k = 1).
    pub fn unit_in(self, units: Units) -> (&'static str, f64) {
        // The unit's symbol among those of [`Length::ALL`] or [`Angle::ALL`].
        let length = |symbols: [&'static str; 4]| {
            let k = Length::ALL.iter().position(|&l| l == units.length);
            (symbols[k.unwrap_or(0)], units.length.per_metre())
        };
        let angle = |symbols: [&'static str; 2]| {
            let k = Angle::ALL.iter().position(|&a| a == units.angle);
            (symbols[k.unwrap_or(0)], 1.0 / units.angle.radians())
        };
        match self {
            Quantity::Time => ("s", 1.0),
            Quantity::Length => length(["m", "cm", "mm", "in"]),
            Quantity::Velocity => length(["m/s", "cm/s", "mm/s", "in/s"]),
            Quantity::Acceleration => length(["m/s²", "cm/s²", "mm/s²", "in/s²"]),
            Quantity::Jerk => length(["m/s³", "cm/s³", "mm/s³", "in/s³"]),
            Quantity::Angle => angle(["rad", "deg"]),
            Quantity::AngularVelocity => angle(["rad/s", "deg/s"]),
            Quantity::AngularAcceleration => angle(["rad/s²", "deg/s²"]),
            Quantity::AngularJerk => angle(["rad/s³", "deg/s³"]),
            Quantity::Force => ("N", 1.0),
            Quantity::Torque => ("N·m", 1.0),
            Quantity::Power => ("W", 1.0),
            Quantity::Energy => ("J", 1.0),
            Quantity::Dimensionless => ("1", 1.0),
            Quantity::Residual => ("m or rad", 1.0),
            Quantity::ResidualRate => ("m/s or rad/s", 1.0),
        }
    }
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An output channel: its name (`crank.omega`) and what it measures.
#[derive(Clone, Debug, PartialEq)]
pub struct Channel {
    pub name: String,
    pub quantity: Quantity,
}

impl Channel {
    pub fn new(name: impl Into<String>, quantity: Quantity) -> Self {
        Channel {
            name: name.into(),
            quantity,
        }
    }

    /// The SI unit ([`Quantity::unit`]).
    pub fn unit(&self) -> &'static str {
        self.quantity.unit()
    }
}

impl AsRef<str> for Channel {
    fn as_ref(&self) -> &str {
        &self.name
    }
}

/// The names of `channels`, in order.
pub fn names(channels: &[Channel]) -> Vec<String> {
    channels.iter().map(|c| c.name.clone()).collect()
}

/// A unit of length.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Length {
    M,
    Cm,
    Mm,
    /// The inch, 0.0254 m exactly.
    In,
}

impl Length {
    pub const ALL: [Length; 4] = [Length::M, Length::Cm, Length::Mm, Length::In];

    /// The symbol, e.g. `"mm"`.
    pub fn name(self) -> &'static str {
        match self {
            Length::M => "m",
            Length::Cm => "cm",
            Length::Mm => "mm",
            Length::In => "in",
        }
    }

    /// Metres in one unit.
    pub fn metres(self) -> f64 {
        match self {
            Length::M => 1.0,
            Length::Cm => 0.01,
            Length::Mm => 0.001,
            Length::In => 0.0254,
        }
    }

    /// Units in one metre, exact for m, cm and mm (divide by it to turn a
    /// value in this unit into metres: 25 / 1000 is the nearest double to
    /// 0.025, which 25 · 0.001 is not always).
    pub(crate) fn per_metre(self) -> f64 {
        match self {
            Length::M => 1.0,
            Length::Cm => 100.0,
            Length::Mm => 1000.0,
            Length::In => 1.0 / 0.0254,
        }
    }

    pub fn parse(text: &str) -> Option<Length> {
        Length::ALL.into_iter().find(|l| l.name() == text)
    }
}

/// A unit of angle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Angle {
    Rad,
    Deg,
}

impl Angle {
    pub const ALL: [Angle; 2] = [Angle::Rad, Angle::Deg];

    pub fn name(self) -> &'static str {
        match self {
            Angle::Rad => "rad",
            Angle::Deg => "deg",
        }
    }

    /// Radians in one unit.
    pub fn radians(self) -> f64 {
        match self {
            Angle::Rad => 1.0,
            Angle::Deg => std::f64::consts::PI / 180.0,
        }
    }

    pub fn parse(text: &str) -> Option<Angle> {
        Angle::ALL.into_iter().find(|a| a.name() == text)
    }
}

/// The length and angle units of a model file or of an output.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Units {
    pub length: Length,
    pub angle: Angle,
}

impl Default for Units {
    fn default() -> Self {
        Units::SI
    }
}

impl Units {
    /// Metres and radians.
    pub const SI: Units = Units {
        length: Length::M,
        angle: Angle::Rad,
    };

    /// True for metres and radians.
    pub fn is_si(self) -> bool {
        self == Units::SI
    }

    /// Units written `LENGTH,ANGLE` (`"mm,deg"`), either part alone
    /// (`"mm"`, `"deg"`: the other stays SI), or `"si"`. The error lists
    /// what is accepted.
    pub fn parse(text: &str) -> Result<Units, String> {
        let mut units = Units::SI;
        let bad = || {
            format!(
                "units '{text}': give a length unit ({}) and an angle unit ({}), \
                 e.g. 'mm,deg'",
                Length::ALL.map(Length::name).join(", "),
                Angle::ALL.map(Angle::name).join(", ")
            )
        };
        if text.trim().eq_ignore_ascii_case("si") {
            return Ok(units);
        }
        let (mut length, mut angle) = (false, false);
        for part in text.split(',').map(str::trim) {
            if let (Some(l), false) = (Length::parse(part), length) {
                units.length = l;
                length = true;
            } else if let (Some(a), false) = (Angle::parse(part), angle) {
                units.angle = a;
                angle = true;
            } else {
                return Err(bad());
            }
        }
        Ok(units)
    }

    /// `"mm,deg"`.
    pub fn text(self) -> String {
        format!("{},{}", self.length.name(), self.angle.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_parse_both_parts_in_any_order_and_alone() {
        let mm_deg = Units {
            length: Length::Mm,
            angle: Angle::Deg,
        };
        assert_eq!(Units::parse("mm,deg"), Ok(mm_deg));
        assert_eq!(Units::parse(" deg , mm "), Ok(mm_deg));
        assert_eq!(
            Units::parse("mm").map(|u| u.angle),
            Ok(Angle::Rad),
            "the angle stays rad"
        );
        assert_eq!(Units::parse("si"), Ok(Units::SI));
        for bad in ["", "mm,mm", "ft,deg", "mm,deg,rad", "grad"] {
            let e = Units::parse(bad).unwrap_err();
            assert!(e.contains("m, cm, mm, in") && e.contains("rad, deg"), "{e}");
        }
        assert_eq!(mm_deg.text(), "mm,deg");
    }

    #[test]
    fn unit_in_scales_lengths_angles_and_their_rates_only() {
        let mm_deg = Units::parse("mm,deg").unwrap();
        assert_eq!(Quantity::Length.unit_in(mm_deg), ("mm", 1000.0));
        assert_eq!(Quantity::Acceleration.unit_in(mm_deg), ("mm/s²", 1000.0));
        let (u, k) = Quantity::AngularVelocity.unit_in(mm_deg);
        assert_eq!(u, "deg/s");
        assert!((k - 180.0 / std::f64::consts::PI).abs() < 1e-12);
        for q in [
            Quantity::Force,
            Quantity::Torque,
            Quantity::Energy,
            Quantity::Time,
        ] {
            assert_eq!(q.unit_in(mm_deg), (q.unit(), 1.0), "{q}");
        }
        let inch = Units::parse("in").unwrap();
        assert!((Quantity::Jerk.unit_in(inch).1 * 0.0254 - 1.0).abs() < 1e-15);
    }

    #[test]
    fn every_quantity_has_a_name_that_reads_back_and_a_unit() {
        for q in Quantity::ALL {
            assert_eq!(Quantity::from_name(q.name()), Some(q));
            assert!(!q.unit().is_empty());
        }
        // The rates of lengths and angles are the quantities of their units.
        assert_eq!(Quantity::Length.rate(), Some(Quantity::Velocity));
        assert_eq!(
            Quantity::AngularAcceleration.rate(),
            Some(Quantity::AngularJerk)
        );
        assert_eq!(Quantity::Force.rate(), None);
    }
}
