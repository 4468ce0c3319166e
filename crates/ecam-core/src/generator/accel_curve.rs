//! The acceleration curves of the cut generators ([`AccelCurve`]).

use core::f64::consts::PI;

use crate::TableError;

/// How a ramp's velocity ratio goes from its start value to its end value.
///
/// The three acceleration curves of the rotary-cut and flying-saw generators
/// (ECAMTBX K100/K101, parameter P6 low word), also used for the ramps of the
/// S-curve generator.
///
/// A curve shapes how the velocity ratio changes from `v0` to `v1` over a
/// ramp: `v(u) = v0 + (v1 − v0)·h(u)` for the normalised ramp position
/// `u ∈ [0, 1]`, with `h(0) = 0` and `h(1) = 1`.
///
/// The manual names the codes only ("0: uniform curve, 1: uniform
/// acceleration curve, 2: B type curve"). Our reading, chosen so that every
/// curve keeps the velocity continuous (a generator whose velocity jumped at
/// the sync boundaries would defeat its purpose):
/// - **0 uniform**: the velocity changes uniformly (linearly), i.e. constant
///   acceleration inside the ramp — the trapezoidal velocity profile;
/// - **1 uniform acceleration**: the acceleration rises and falls uniformly
///   (linearly), i.e. the jerk-limited S-type ramp. The same manual's key-point
///   appendix (K2) calls its S-type curve "uniform acceleration" too;
/// - **2 B type**: a bell-shaped acceleration `1 − cos 2πu` (cycloidal ramp):
///   acceleration and jerk both start and end at zero.
///
/// Every `h` is point-symmetric, `h(u) + h(1 − u) = 1`, so a ramp always covers
/// `(v0 + v1)/2 · length`, whatever the curve: the generators' distance
/// budget does not depend on the curve chosen.
///
/// ```
/// use ecam_core::generator::AccelCurve;
///
/// let c = AccelCurve::from_code(1)?;
/// assert_eq!(c, AccelCurve::UniformAcceleration);
/// assert!((c.velocity(0.5) - 0.5).abs() < 1e-12);
/// assert!((c.distance(1.0) - 0.5).abs() < 1e-12);
/// # Ok::<(), ecam_core::TableError>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum AccelCurve {
    /// Code 0: velocity changes linearly (constant acceleration).
    #[default]
    Uniform,
    /// Code 1: acceleration changes linearly (S-type, jerk-limited).
    UniformAcceleration,
    /// Code 2: bell-shaped acceleration (cycloidal ramp).
    BType,
}

impl AccelCurve {
    /// All three curves, in code order.
    pub const ALL: [AccelCurve; 3] = [Self::Uniform, Self::UniformAcceleration, Self::BType];

    /// The curve for the P6 low-word code.
    ///
    /// # Errors
    /// [`TableError::Parameter`] (6781) for a code other than 0, 1 or 2.
    pub fn from_code(code: u16) -> Result<Self, TableError> {
        match code {
            0 => Ok(Self::Uniform),
            1 => Ok(Self::UniformAcceleration),
            2 => Ok(Self::BType),
            _ => Err(TableError::Parameter {
                name: "acceleration curve (P6 low word)",
                reason: "must be 0 (uniform), 1 (uniform acceleration) or 2 (B type)",
            }),
        }
    }

    /// Every name and code [`AccelCurve::from_name`] accepts, for messages.
    pub const NAMES: &'static str =
        "uniform (0), uniform-acceleration (1, alias s-type), b-type (2)";

    /// The curve's name in parameter files, flags and forms.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::UniformAcceleration => "uniform-acceleration",
            Self::BType => "b-type",
        }
    }

    /// The curve for a name, the alias `s-type`, or a P6 low-word code
    /// written as text (`"1"`).
    pub fn from_name(text: &str) -> Option<Self> {
        match text {
            "0" | "uniform" => Some(Self::Uniform),
            "1" | "uniform-acceleration" | "s-type" => Some(Self::UniformAcceleration),
            "2" | "b-type" => Some(Self::BType),
            _ => None,
        }
    }

    /// The P6 low-word code of this curve.
    pub const fn code(self) -> u16 {
        match self {
            Self::Uniform => 0,
            Self::UniformAcceleration => 1,
            Self::BType => 2,
        }
    }

    /// Normalised velocity change `h(u)`, from 0 at `u = 0` to 1 at `u = 1`.
    /// `u` is clamped onto `[0, 1]`.
    pub fn velocity(self, u: f64) -> f64 {
        let u = u.clamp(0.0, 1.0);
        match self {
            Self::Uniform => u,
            Self::UniformAcceleration => {
                if u < 0.5 {
                    2.0 * u * u
                } else {
                    let w = 1.0 - u;
                    1.0 - 2.0 * w * w
                }
            }
            Self::BType => u - libm::sin(2.0 * PI * u) / (2.0 * PI),
        }
    }

    /// Normalised distance `∫₀ᵘ h`, from 0 at `u = 0` to ½ at `u = 1`.
    /// Outside `[0, 1]` it continues with the end velocity (0 before, 1 after).
    pub fn distance(self, u: f64) -> f64 {
        if u <= 0.0 {
            return 0.0;
        }
        if u >= 1.0 {
            return 0.5 + (u - 1.0);
        }
        match self {
            Self::Uniform => 0.5 * u * u,
            Self::UniformAcceleration => {
                if u < 0.5 {
                    2.0 * u * u * u / 3.0
                } else {
                    let w = 1.0 - u;
                    u - 0.5 + 2.0 * w * w * w / 3.0
                }
            }
            Self::BType => 0.5 * u * u + (libm::cos(2.0 * PI * u) - 1.0) / (4.0 * PI * PI),
        }
    }

    /// Normalised acceleration `dh/du`, the slope of [`AccelCurve::velocity`].
    /// `u` is clamped onto `[0, 1]`; the value is the one at the clamped point.
    ///
    /// A ramp from `v0` to `v1` over `len` master counts has the acceleration
    /// `(v1 − v0)·dh/du / len`.
    pub fn acceleration(self, u: f64) -> f64 {
        let u = u.clamp(0.0, 1.0);
        match self {
            Self::Uniform => 1.0,
            Self::UniformAcceleration => {
                if u < 0.5 {
                    4.0 * u
                } else {
                    4.0 * (1.0 - u)
                }
            }
            Self::BType => 1.0 - libm::cos(2.0 * PI * u),
        }
    }

    /// Normalised jerk `d²h/du²`, the slope of [`AccelCurve::acceleration`].
    /// `u` is clamped onto `[0, 1]`. Where the acceleration has a corner
    /// (the S-type ramp's peak at `u = ½`) the value is the one after it,
    /// as a table's joint belongs to the section starting there. The
    /// uniform curve's jerk is zero inside the ramp: its acceleration steps
    /// at the ramp's ends, an impulse of jerk no finite value describes.
    pub fn jerk(self, u: f64) -> f64 {
        let u = u.clamp(0.0, 1.0);
        match self {
            Self::Uniform => 0.0,
            Self::UniformAcceleration => {
                if u < 0.5 {
                    4.0
                } else {
                    -4.0
                }
            }
            Self::BType => 2.0 * PI * libm::sin(2.0 * PI * u),
        }
    }

    /// Peak of `dh/du`: how much steeper than a linear ramp the curve gets
    /// (1 for uniform, 2 for the other two).
    pub const fn peak_acceleration_factor(self) -> f64 {
        match self {
            Self::Uniform => 1.0,
            Self::UniformAcceleration | Self::BType => 2.0,
        }
    }
}

super::choice_serde::choice_serde!(AccelCurve, "acceleration curve");

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn codes_round_trip_and_bad_code_is_6781() {
        for c in AccelCurve::ALL {
            assert_eq!(AccelCurve::from_code(c.code()), Ok(c));
            assert_eq!(AccelCurve::from_name(c.name()), Some(c));
        }
        assert_eq!(
            AccelCurve::from_name("s-type"),
            Some(AccelCurve::UniformAcceleration)
        );
        assert_eq!(AccelCurve::from_code(3).unwrap_err().code(), 6781);
    }

    #[test]
    fn ends_and_point_symmetry() {
        for c in AccelCurve::ALL {
            assert_eq!(c.velocity(0.0), 0.0);
            assert!((c.velocity(1.0) - 1.0).abs() < 1e-12);
            assert!((c.distance(1.0) - 0.5).abs() < 1e-12);
            for i in 0..=100 {
                let u = f64::from(i) / 100.0;
                assert!((c.velocity(u) + c.velocity(1.0 - u) - 1.0).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn distance_is_the_integral_of_velocity() {
        for c in AccelCurve::ALL {
            let n = 20_000;
            let mut sum = 0.0;
            for i in 0..n {
                let u = (f64::from(i) + 0.5) / f64::from(n);
                sum += c.velocity(u) / f64::from(n);
                if i % 1000 == 999 {
                    let end = f64::from(i + 1) / f64::from(n);
                    assert!((sum - c.distance(end)).abs() < 1e-8, "{c:?} at {end}");
                }
            }
        }
    }

    /// Central difference of `f` at `u`, step `h`.
    fn slope(f: impl Fn(f64) -> f64, u: f64, h: f64) -> f64 {
        (f(u + h) - f(u - h)) / (2.0 * h)
    }

    #[test]
    fn acceleration_and_jerk_are_the_derivatives() {
        let h = 1e-6;
        for c in AccelCurve::ALL {
            // Stay a step away from the ends and from the S-type's corner at ½.
            for i in 1..200 {
                let u = f64::from(i) / 200.0;
                if (u - 0.5).abs() < 2.0 * h {
                    continue;
                }
                let a = slope(|u| c.velocity(u), u, h);
                assert!((a - c.acceleration(u)).abs() < 1e-6, "{c:?} a at {u}");
                let j = slope(|u| c.acceleration(u), u, h);
                assert!((j - c.jerk(u)).abs() < 1e-5, "{c:?} j at {u}");
            }
        }
    }

    #[test]
    fn acceleration_ends_and_peaks() {
        // Uniform: a step at both ends; S-type and B-type start and end at rest.
        assert_eq!(AccelCurve::Uniform.acceleration(0.0), 1.0);
        for c in [AccelCurve::UniformAcceleration, AccelCurve::BType] {
            assert_eq!(c.acceleration(0.0), 0.0);
            assert!(c.acceleration(1.0).abs() < 1e-12);
            assert!((c.acceleration(0.5) - c.peak_acceleration_factor()).abs() < 1e-12);
        }
        assert_eq!(AccelCurve::UniformAcceleration.jerk(0.25), 4.0);
        assert_eq!(AccelCurve::UniformAcceleration.jerk(0.5), -4.0);
        assert!(AccelCurve::BType.jerk(0.0).abs() < 1e-12);
        // Clamped outside the ramp.
        assert_eq!(AccelCurve::UniformAcceleration.acceleration(-1.0), 0.0);
        assert_eq!(AccelCurve::Uniform.jerk(2.0), 0.0);
    }

    #[test]
    fn peak_slope_matches_the_factor() {
        for c in AccelCurve::ALL {
            let mut peak: f64 = 0.0;
            for i in 0..1000 {
                let u0 = f64::from(i) / 1000.0;
                let u1 = f64::from(i + 1) / 1000.0;
                peak = peak.max((c.velocity(u1) - c.velocity(u0)) * 1000.0);
            }
            assert!(
                (peak - c.peak_acceleration_factor()).abs() < 0.01,
                "{c:?}: {peak}"
            );
        }
    }
}
