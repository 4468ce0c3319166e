//! The law a segment follows, and which boundary values it can meet.

use core::fmt;

use crate::MotionLaw;

/// A segment's motion law: one of the normalised rise laws, or a law
/// solved for the boundary values at its two points (VDI 2143's
/// polynomials and a velocity-to-velocity law).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SegmentLaw {
    /// A normalised rise law ([`MotionLaw`]) scaled onto the segment: its
    /// end values are the law's (a rest-to-rest law arrives and leaves at
    /// rest; constant velocity at `rise/span`).
    Rise(MotionLaw),
    /// Polynomial of degree 5 solved for position, velocity and
    /// acceleration at both points (any boundary values: rest–rest,
    /// rest–velocity, velocity–velocity, reversal, motion–motion).
    Poly5,
    /// Polynomial of degree 7 solved for position, velocity, acceleration
    /// and jerk at both points (a cam continuous in jerk, C3).
    Poly7,
    /// Velocity to velocity: the velocity changes from the first point's to
    /// the second's along the cycloid's shape while a cycloidal rise makes
    /// up the remaining travel. Acceleration is zero at both points (ours,
    /// see `docs/design.md`).
    VelocityCycloid,
}

/// Which boundary values a law takes from its points (the others it makes
/// itself, and a point that asks for a different one is refused).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Adapts {
    /// Takes the points' velocities.
    pub velocity: bool,
    /// Takes the points' accelerations.
    pub acceleration: bool,
    /// Takes the points' jerks.
    pub jerk: bool,
}

impl SegmentLaw {
    /// Every law, in the order lists show them: the solved laws, then the rise laws.
    pub const ALL: [SegmentLaw; 14] = [
        Self::Poly5,
        Self::Poly7,
        Self::VelocityCycloid,
        Self::Rise(MotionLaw::ConstantVelocity),
        Self::Rise(MotionLaw::ConstantAcceleration),
        Self::Rise(MotionLaw::SimpleHarmonic),
        Self::Rise(MotionLaw::Cycloid),
        Self::Rise(MotionLaw::ModifiedTrapezoid),
        Self::Rise(MotionLaw::ModifiedSine),
        Self::Rise(MotionLaw::ModifiedConstantVelocity),
        Self::Rise(MotionLaw::Poly345),
        Self::Rise(MotionLaw::Poly4567),
        Self::Rise(MotionLaw::Cubic),
        Self::Rise(MotionLaw::SType),
    ];

    /// Names of the laws that adapt to a point's velocity, for messages.
    pub const ADAPTING: &'static str = "poly-5, poly-7, vv-cycloid";

    /// The law's name in files, flags and the designer.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Rise(law) => law.name(),
            Self::Poly5 => "poly-5",
            Self::Poly7 => "poly-7",
            Self::VelocityCycloid => "vv-cycloid",
        }
    }

    /// The law called `name` (ASCII case ignored).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|law| law.name().eq_ignore_ascii_case(name.trim()))
    }

    /// Which boundary values it takes from its points.
    pub const fn adapts(self) -> Adapts {
        let (velocity, acceleration, jerk) = match self {
            Self::Rise(_) => (false, false, false),
            Self::Poly5 => (true, true, false),
            Self::Poly7 => (true, true, true),
            Self::VelocityCycloid => (true, false, false),
        };
        Adapts {
            velocity,
            acceleration,
            jerk,
        }
    }
}

impl fmt::Display for SegmentLaw {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl serde::Serialize for SegmentLaw {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> serde::Deserialize<'de> for SegmentLaw {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Name;
        impl serde::de::Visitor<'_> for Name {
            type Value = SegmentLaw;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a segment law name such as \"poly-5\"")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<SegmentLaw, E> {
                SegmentLaw::from_name(v).ok_or_else(|| {
                    E::custom(alloc::format!(
                        "unknown segment law {v:?}; use poly-5, poly-7, vv-cycloid or a motion law (`ecam law --list`)"
                    ))
                })
            }
        }
        deserializer.deserialize_str(Name)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_cover_every_motion_law() {
        for law in SegmentLaw::ALL {
            assert_eq!(SegmentLaw::from_name(law.name()), Some(law));
        }
        for law in MotionLaw::ALL {
            assert_eq!(
                SegmentLaw::from_name(law.name()),
                Some(SegmentLaw::Rise(law))
            );
        }
        assert_eq!(SegmentLaw::from_name("POLY-5"), Some(SegmentLaw::Poly5));
        assert_eq!(SegmentLaw::from_name("poly-6"), None);
    }
}
