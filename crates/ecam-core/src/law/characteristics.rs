//! The characteristic values of a motion law, as cam-design tables list them.

use super::MotionLaw;

/// Peak magnitudes of a law's derivatives on `u ∈ [0, 1]` (dimensionless
/// factors: a segment rising `h` over `β` counts peaks at `cv·h/β`,
/// `ca·h/β²`, `cj·h/β³`).
///
/// They are counted as the published cam-design tables count them, for a rise
/// between two dwells: where a derivative jumps (at an end, where the law
/// meets the dwell, or inside), the next derivative is an impulse and its
/// factor is `f64::INFINITY`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct LawCharacteristics {
    /// Peak |velocity| factor Cv.
    pub cv: f64,
    /// Peak |acceleration| factor Ca (`INFINITY`: the velocity jumps).
    pub ca: f64,
    /// Peak |jerk| factor Cj (`INFINITY`: the acceleration jumps).
    pub cj: f64,
    /// Velocity is zero at both ends, so a rise joins dwells (and other such
    /// rises) with continuous velocity.
    pub zero_end_velocity: bool,
    /// Velocity and acceleration are zero at both ends, so joints with dwells
    /// (and other such rises) keep acceleration continuous too.
    pub zero_end_acceleration: bool,
}

impl MotionLaw {
    /// The law's published characteristic values.
    ///
    /// The modified laws' values are the exact peaks of the acceleration
    /// diagrams this crate uses (they agree with the published 4.888 / 61.43,
    /// 1.760 / 5.528 / 69.47 and MCV50's 1.28 / 8.01 / 201.4 to the digits
    /// printed); the S-type law is this crate's own definition (see
    /// [`MotionLaw::SType`]).
    pub const fn characteristics(self) -> LawCharacteristics {
        const INF: f64 = f64::INFINITY;
        const PI: f64 = core::f64::consts::PI;
        let (cv, ca, cj, zero_end_velocity, zero_end_acceleration) = match self {
            Self::ConstantVelocity => (1.0, INF, INF, false, false),
            Self::ConstantAcceleration => (2.0, 4.0, INF, true, false),
            Self::SimpleHarmonic => (PI / 2.0, PI * PI / 2.0, INF, true, false),
            Self::Cycloid => (2.0, 2.0 * PI, 4.0 * PI * PI, true, true),
            // 8π/(π+2) and 4π times that.
            Self::ModifiedTrapezoid => (
                2.0,
                4.888_123_762_813_258,
                61.425_974_812_367_315,
                true,
                true,
            ),
            // 4π/(π+4), 4π²/(π+4), 16π³/(π+4).
            Self::ModifiedSine => (
                1.759_603_385_953_770_5,
                5.527_957_070_544_09,
                69.466_357_288_724_27,
                true,
                true,
            ),
            // Amplitude from s(1/2) = 1/2 (see `law::piecewise`); Cv = Ca/2π, Cj = 8π·Ca.
            Self::ModifiedConstantVelocity => (
                1.275_258_172_902_711_3,
                8.012_683_414_843,
                201.380_698_812_892_38,
                true,
                true,
            ),
            // 10/√3 at u = 1/2 − √3/6.
            Self::Poly345 => (1.875, 5.773_502_691_896_258, 60.0, true, true),
            Self::Poly4567 => (2.1875, 7.513_188_404_399_289, 52.5, true, true),
            Self::Cubic => (1.5, 6.0, INF, true, false),
            Self::SType => (1.5, 6.75, 60.75, true, true),
        };
        LawCharacteristics {
            cv,
            ca,
            cj,
            zero_end_velocity,
            zero_end_acceleration,
        }
    }

    /// Peaks of `|v|`, `|a|`, `|j|` *inside* the rise, `0 < u < 1`: the
    /// law's own shape, without the impulses a jump at an end would make
    /// against a dwell (in a segment cam those belong to the joint, whose
    /// continuity is reported there). A jump inside the rise still counts:
    /// constant acceleration steps from +4 to −4 at mid-rise, an impulse of
    /// jerk (`INFINITY`).
    pub const fn interior_peaks(self) -> (f64, f64, f64) {
        const PI: f64 = core::f64::consts::PI;
        match self {
            Self::ConstantVelocity => (1.0, 0.0, 0.0),
            Self::ConstantAcceleration => (2.0, 4.0, f64::INFINITY),
            Self::SimpleHarmonic => (PI / 2.0, PI * PI / 2.0, PI * PI * PI / 2.0),
            Self::Cubic => (1.5, 6.0, 12.0),
            _ => {
                let c = self.characteristics();
                (c.cv, c.ca, c.cj)
            }
        }
    }
}
