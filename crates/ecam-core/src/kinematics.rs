//! The value a cam curve gives at one master position.

/// Slave position and its first three derivatives with respect to the master.
///
/// For a normalised motion law the derivatives are taken with respect to the
/// normalised master `u`; for a cam table they are taken with respect to the
/// master position in counts (so `v` is the slave/master velocity ratio).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Kinematics {
    /// Position (displacement).
    pub s: f64,
    /// First derivative: velocity ratio.
    pub v: f64,
    /// Second derivative: acceleration.
    pub a: f64,
    /// Third derivative: jerk.
    pub j: f64,
}

impl Kinematics {
    /// A point at rest at `s`.
    pub const fn at_rest(s: f64) -> Self {
        Self {
            s,
            v: 0.0,
            a: 0.0,
            j: 0.0,
        }
    }

    /// Maps a normalised law value onto a segment that rises by `stroke` over
    /// `span` master counts, starting from `base`.
    ///
    /// The chain rule gives each derivative one more factor of `1/span`.
    pub fn scaled(self, base: f64, stroke: f64, span: f64) -> Self {
        let inv = 1.0 / span;
        Self {
            s: base + stroke * self.s,
            v: stroke * self.v * inv,
            a: stroke * self.a * inv * inv,
            j: stroke * self.j * inv * inv * inv,
        }
    }
}
