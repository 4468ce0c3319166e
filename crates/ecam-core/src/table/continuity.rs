//! How smooth a curve is where its pieces meet: the class [`super::steps`]
//! finds and [`super::Summary`] reports.

/// How smooth a curve is where its segments meet.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
pub enum Continuity {
    /// The position jumps at a joint.
    Discontinuous,
    /// Position continuous, velocity jumps at some joint (every point table
    /// whose points are not collinear).
    C0,
    /// Velocity continuous, acceleration jumps at some joint.
    C1,
    /// Acceleration continuous at every joint.
    C2,
    /// Jerk continuous too. [`super::Summary`] stops at `C2`; a segment cam's joint
    /// report ([`crate::segments::ContinuityReport`]) tells `C2` from `C3`.
    C3,
}

impl core::fmt::Display for Continuity {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            Self::Discontinuous => "discontinuous",
            Self::C0 => "C0",
            Self::C1 => "C1",
            Self::C2 => "C2",
            Self::C3 => "C3",
        })
    }
}
