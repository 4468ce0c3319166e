//! Motion laws: the normalised shapes a cam segment rises with.
//!
//! A law maps the normalised master `u ∈ [0, 1]` to the normalised slave
//! `s ∈ [0, 1]` with `s(0) = 0` and `s(1) = 1`; velocity, acceleration and
//! jerk are its derivatives in `u`, computed analytically (never by
//! differencing). A segment that rises by `h` over `β` master counts scales
//! them by `h/β`, `h/β²` and `h/β³` ([`Kinematics::scaled`]).
//!
//! ```
//! use ecam_core::law::MotionLaw;
//!
//! let k = MotionLaw::Cycloid.eval(0.5);
//! assert!((k.s - 0.5).abs() < 1e-12);
//! assert!((k.v - 2.0).abs() < 1e-12); // the cycloid's Cv
//! assert_eq!(MotionLaw::from_name("poly-345"), Some(MotionLaw::Poly345));
//! ```

mod characteristics;
mod piecewise;

use core::f64::consts::PI;
use core::fmt;
use core::str::FromStr;

pub use characteristics::LawCharacteristics;

use crate::Kinematics;
use piecewise::{Piece, first_half};

/// A normalised rise law (rise from rest to rest unless noted).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MotionLaw {
    /// Straight line `s = u`. Velocity jumps at both ends.
    ConstantVelocity,
    /// Parabolic: constant acceleration for the first half, constant
    /// deceleration for the second (the PLC's key-point curve type 0).
    ConstantAcceleration,
    /// `s = (1 − cos πu)/2`.
    SimpleHarmonic,
    /// `s = u − sin(2πu)/(2π)`; acceleration is zero at both ends
    /// (the PLC's key-point curve type 2).
    Cycloid,
    /// Modified trapezoid: constant acceleration blended by sine quarters
    /// (1/8 ramps), the minimum-acceleration standard law.
    ModifiedTrapezoid,
    /// Modified sine: a short sine quarter (1/8) into a long one (3/8).
    ModifiedSine,
    /// Modified constant velocity, MCV50: modified-sine style ramps over the
    /// first and last quarter, constant velocity over the middle half.
    ModifiedConstantVelocity,
    /// 3-4-5 polynomial `s = 10u³ − 15u⁴ + 6u⁵`.
    Poly345,
    /// 4-5-6-7 polynomial `s = 35u⁴ − 84u⁵ + 70u⁶ − 20u⁷`.
    Poly4567,
    /// Cubic `s = 3u² − 2u³`: zero end velocity, acceleration jumps at the ends.
    Cubic,
    /// S-type (jerk-limited) acceleration/deceleration, the PLC's key-point
    /// curve type 1: seven constant-jerk phases. Acceleration takes the first
    /// third (jerk up 1/9, hold 1/9, jerk down 1/9), constant velocity the
    /// middle third, deceleration the last third, mirrored.
    SType,
}

// Acceleration diagrams of the piecewise laws, first half only (see `piecewise`).
const MODIFIED_TRAPEZOID: [Piece; 3] = [
    Piece::SineUp {
        len: 0.125,
        omega: 4.0 * PI,
    },
    Piece::Jerk {
        len: 0.25,
        jerk: 0.0,
    },
    Piece::CosineDown {
        len: 0.125,
        omega: 4.0 * PI,
    },
];
const MODIFIED_SINE: [Piece; 2] = [
    Piece::SineUp {
        len: 0.125,
        omega: 4.0 * PI,
    },
    Piece::CosineDown {
        len: 0.375,
        omega: 4.0 * PI / 3.0,
    },
];
const MODIFIED_CONSTANT_VELOCITY: [Piece; 3] = [
    Piece::SineUp {
        len: 0.0625,
        omega: 8.0 * PI,
    },
    Piece::CosineDown {
        len: 0.1875,
        omega: 8.0 * PI / 3.0,
    },
    Piece::Jerk {
        len: 0.25,
        jerk: 0.0,
    },
];
const S_TYPE: [Piece; 4] = [
    Piece::Jerk {
        len: 1.0 / 9.0,
        jerk: 1.0,
    },
    Piece::Jerk {
        len: 1.0 / 9.0,
        jerk: 0.0,
    },
    Piece::Jerk {
        len: 1.0 / 9.0,
        jerk: -1.0,
    },
    Piece::Jerk {
        len: 0.5 - 3.0 / 9.0,
        jerk: 0.0,
    },
];

impl MotionLaw {
    /// Every law, in the order `ecam law --list` prints them.
    pub const ALL: [MotionLaw; 11] = [
        Self::ConstantVelocity,
        Self::ConstantAcceleration,
        Self::SimpleHarmonic,
        Self::Cycloid,
        Self::ModifiedTrapezoid,
        Self::ModifiedSine,
        Self::ModifiedConstantVelocity,
        Self::Poly345,
        Self::Poly4567,
        Self::Cubic,
        Self::SType,
    ];

    /// The law's name as the command line and file formats spell it.
    pub const fn name(self) -> &'static str {
        match self {
            Self::ConstantVelocity => "constant-velocity",
            Self::ConstantAcceleration => "constant-acceleration",
            Self::SimpleHarmonic => "simple-harmonic",
            Self::Cycloid => "cycloid",
            Self::ModifiedTrapezoid => "modified-trapezoid",
            Self::ModifiedSine => "modified-sine",
            Self::ModifiedConstantVelocity => "modified-constant-velocity",
            Self::Poly345 => "poly-345",
            Self::Poly4567 => "poly-4567",
            Self::Cubic => "cubic",
            Self::SType => "s-type",
        }
    }

    /// The law called `name` ([`MotionLaw::name`]); ASCII case is ignored.
    pub fn from_name(name: &str) -> Option<MotionLaw> {
        Self::ALL
            .into_iter()
            .find(|law| law.name().eq_ignore_ascii_case(name.trim()))
    }

    /// Position, velocity, acceleration and jerk at the normalised master `u`.
    ///
    /// `u` outside `[0, 1]` is clamped onto the nearer end (NaN counts as 0),
    /// and the derivatives are those at the clamped point.
    pub fn eval(self, u: f64) -> Kinematics {
        let u = if u.is_nan() { 0.0 } else { u.clamp(0.0, 1.0) };
        // Every law is point-symmetric about (1/2, 1/2): evaluate the first
        // half and mirror. This also makes s(0) = 0 and s(1) = 1 exact.
        if u <= 0.5 {
            self.first_half(u)
        } else {
            let k = self.first_half(1.0 - u);
            Kinematics {
                s: 1.0 - k.s,
                v: k.v,
                a: -k.a,
                j: k.j,
            }
        }
    }

    /// Where inside the rise (0 < u < 1) the law's acceleration steps: only
    /// the constant-acceleration law's, at its middle, where acceleration
    /// turns into deceleration. Every other law's acceleration is
    /// continuous inside the rise (its pieces meet with equal acceleration;
    /// only their jerk may step), and no law's velocity steps inside.
    /// [`crate::table::steps`] looks for impulses there.
    pub const fn acceleration_knots(self) -> &'static [f64] {
        match self {
            Self::ConstantAcceleration => &[0.5],
            _ => &[],
        }
    }

    /// As [`MotionLaw::eval`], but at a knot of
    /// [`MotionLaw::acceleration_knots`] the value just after it (`eval`
    /// gives the one just before the middle).
    pub fn eval_after(self, u: f64) -> Kinematics {
        let u = if u.is_nan() { 0.0 } else { u.clamp(0.0, 1.0) };
        if u < 0.5 {
            return self.first_half(u);
        }
        let k = self.first_half(1.0 - u);
        Kinematics {
            s: 1.0 - k.s,
            v: k.v,
            a: -k.a,
            j: k.j,
        }
    }

    /// The law on `0 ≤ u ≤ 1/2`.
    fn first_half(self, u: f64) -> Kinematics {
        match self {
            Self::ConstantVelocity => Kinematics {
                s: u,
                v: 1.0,
                a: 0.0,
                j: 0.0,
            },
            Self::ConstantAcceleration => Kinematics {
                s: 2.0 * u * u,
                v: 4.0 * u,
                a: 4.0,
                j: 0.0,
            },
            Self::SimpleHarmonic => {
                let (sin, cos) = (libm::sin(PI * u), libm::cos(PI * u));
                Kinematics {
                    s: (1.0 - cos) / 2.0,
                    v: PI / 2.0 * sin,
                    a: PI * PI / 2.0 * cos,
                    j: -PI * PI * PI / 2.0 * sin,
                }
            }
            Self::Cycloid => {
                let w = 2.0 * PI;
                let (sin, cos) = (libm::sin(w * u), libm::cos(w * u));
                Kinematics {
                    s: u - sin / w,
                    v: 1.0 - cos,
                    a: w * sin,
                    j: w * w * cos,
                }
            }
            Self::Poly345 => {
                let (u2, u3) = (u * u, u * u * u);
                Kinematics {
                    s: u3 * (10.0 - 15.0 * u + 6.0 * u2),
                    v: 30.0 * u2 * (1.0 - 2.0 * u + u2),
                    a: 60.0 * u * (1.0 - 3.0 * u + 2.0 * u2),
                    j: 60.0 * (1.0 - 6.0 * u + 6.0 * u2),
                }
            }
            Self::Poly4567 => {
                let (u2, u3) = (u * u, u * u * u);
                Kinematics {
                    s: u2 * u2 * (35.0 - 84.0 * u + 70.0 * u2 - 20.0 * u3),
                    v: u3 * (140.0 - 420.0 * u + 420.0 * u2 - 140.0 * u3),
                    a: u2 * (420.0 - 1680.0 * u + 2100.0 * u2 - 840.0 * u3),
                    j: u * (840.0 - 5040.0 * u + 8400.0 * u2 - 4200.0 * u3),
                }
            }
            Self::Cubic => Kinematics {
                s: u * u * (3.0 - 2.0 * u),
                v: 6.0 * u * (1.0 - u),
                a: 6.0 - 12.0 * u,
                j: -12.0,
            },
            Self::ModifiedTrapezoid => first_half(&MODIFIED_TRAPEZOID, u),
            Self::ModifiedSine => first_half(&MODIFIED_SINE, u),
            Self::ModifiedConstantVelocity => first_half(&MODIFIED_CONSTANT_VELOCITY, u),
            Self::SType => first_half(&S_TYPE, u),
        }
    }
}

impl fmt::Display for MotionLaw {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not one of [`MotionLaw::ALL`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownLaw;

impl fmt::Display for UnknownLaw {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("unknown motion law; `ecam law --list` shows the names")
    }
}

impl core::error::Error for UnknownLaw {}

impl FromStr for MotionLaw {
    type Err = UnknownLaw;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::from_name(s).ok_or(UnknownLaw)
    }
}

impl serde::Serialize for MotionLaw {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> serde::Deserialize<'de> for MotionLaw {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Name;
        impl serde::de::Visitor<'_> for Name {
            type Value = MotionLaw;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a motion law name such as \"cycloid\"")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<MotionLaw, E> {
                MotionLaw::from_name(v).ok_or_else(|| E::custom(UnknownLaw))
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
    fn acceleration_steps_inside_a_rise_only_at_the_listed_knots() {
        // A fine scan: wherever a and a little further differ by more than
        // the jerk explains, the law's acceleration steps there.
        let n = 72_000;
        for law in MotionLaw::ALL {
            let mut found = alloc::vec::Vec::new();
            for i in 1..n {
                let (u0, u1) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
                let (k0, k1) = (law.eval_after(u0), law.eval_after(u1));
                let h = u1 - u0;
                let explained = h * k0.j.abs().max(k1.j.abs()) + 1e-9;
                if (k1.a - k0.a).abs() > 10.0 * explained {
                    found.push(u1);
                }
                assert!((k1.v - k0.v).abs() < 10.0 * h * k0.a.abs().max(k1.a.abs()) + 1e-9);
            }
            assert_eq!(found, law.acceleration_knots(), "{law}");
            for &u in law.acceleration_knots() {
                let (before, after) = (law.eval(u), law.eval_after(u));
                assert_eq!((before.s, before.v), (after.s, after.v), "{law}");
                assert!((after.a - before.a).abs() > 1.0, "{law}");
            }
        }
        assert_eq!(MotionLaw::ConstantAcceleration.eval_after(0.5).a, -4.0);
    }

    /// Sampled peaks of |v|, |a|, |j| over [0, 1], grid hitting every piece boundary.
    fn sampled_peaks(law: MotionLaw) -> (f64, f64, f64) {
        let n = 144_000; // divisible by 8, 9, 16 and 3
        (0..=n).fold((0.0f64, 0.0f64, 0.0f64), |(v, a, j), i| {
            let k = law.eval(i as f64 / n as f64);
            (v.max(k.v.abs()), a.max(k.a.abs()), j.max(k.j.abs()))
        })
    }

    #[test]
    fn characteristics_match_sampled_peaks() {
        for law in MotionLaw::ALL {
            let c = law.characteristics();
            let (v, a, j) = sampled_peaks(law);
            let close = |published: f64, sampled: f64| {
                (published - sampled).abs() <= 1e-6 * published.max(1.0)
            };
            assert!(close(c.cv, v), "{law}: Cv {} vs sampled {v}", c.cv);
            if c.ca.is_finite() {
                assert!(close(c.ca, a), "{law}: Ca {} vs sampled {a}", c.ca);
            } else {
                // Infinite Ca: the velocity jumps at an end (joined to a dwell).
                assert!(law.eval(0.0).v != 0.0, "{law}");
            }
            if c.cj.is_finite() {
                assert!(close(c.cj, j), "{law}: Cj {} vs sampled {j}", c.cj);
            } else {
                // Infinite Cj: acceleration jumps at an end or at mid-rise.
                let jumps_at_end = law.eval(0.0).a != 0.0 || law.eval(0.0).v != 0.0;
                let jumps_mid = (law.eval(0.5 - 1e-9).a - law.eval(0.5 + 1e-9).a).abs() > 1.0;
                assert!(jumps_at_end || jumps_mid, "{law}");
            }
            assert_eq!(c.zero_end_velocity, law.eval(0.0).v.abs() < 1e-12, "{law}");
            assert_eq!(
                c.zero_end_acceleration,
                c.zero_end_velocity && law.eval(0.0).a.abs() < 1e-9 && law.eval(1.0).a.abs() < 1e-9,
                "{law}"
            );
        }
    }

    #[test]
    #[allow(clippy::approx_constant)] // the published, rounded figures on purpose
    fn published_values() {
        let c = |law: MotionLaw| law.characteristics();
        let near = |x: f64, y: f64, tol: f64| (x - y).abs() <= tol;
        assert!(near(c(MotionLaw::Cycloid).ca, 6.283, 1e-3));
        assert!(near(c(MotionLaw::SimpleHarmonic).cv, 1.571, 1e-3));
        assert!(near(c(MotionLaw::SimpleHarmonic).ca, 4.935, 1e-3));
        assert!(near(c(MotionLaw::ModifiedTrapezoid).ca, 4.888, 1e-3));
        assert!(near(c(MotionLaw::ModifiedTrapezoid).cj, 61.43, 1e-2));
        assert!(near(c(MotionLaw::ModifiedSine).cv, 1.760, 1e-3));
        assert!(near(c(MotionLaw::ModifiedSine).ca, 5.528, 1e-3));
        assert!(near(c(MotionLaw::ModifiedSine).cj, 69.47, 1e-2));
        assert!(near(c(MotionLaw::ModifiedConstantVelocity).cv, 1.28, 1e-2));
        assert!(near(c(MotionLaw::ModifiedConstantVelocity).ca, 8.01, 1e-2));
        assert!(near(c(MotionLaw::ModifiedConstantVelocity).cj, 201.4, 0.1));
        assert!(near(c(MotionLaw::Poly345).ca, 5.774, 1e-3));
        assert!(near(c(MotionLaw::Poly4567).ca, 7.513, 1e-3));
        assert_eq!(c(MotionLaw::ConstantAcceleration).ca, 4.0);
        assert_eq!(c(MotionLaw::Cubic).ca, 6.0);
    }

    #[test]
    fn derivatives_agree_with_differences_of_the_level_below() {
        let h = 1e-6;
        for law in MotionLaw::ALL {
            for i in 1..200 {
                let u = i as f64 / 200.0 + 0.001_23;
                if u + h >= 1.0 {
                    continue;
                }
                let (k0, k1) = (law.eval(u - h), law.eval(u + h));
                let k = law.eval(u);
                let tol = |scale: f64| 1e-4 * scale.max(1.0);
                assert!(
                    (k.v - (k1.s - k0.s) / (2.0 * h)).abs() < tol(k.v.abs()),
                    "{law} v at {u}"
                );
                assert!(
                    (k.a - (k1.v - k0.v) / (2.0 * h)).abs() < tol(k.a.abs()),
                    "{law} a at {u}"
                );
                assert!(
                    (k.j - (k1.a - k0.a) / (2.0 * h)).abs() < tol(k.j.abs()) * 10.0,
                    "{law} j at {u}"
                );
            }
        }
    }

    #[test]
    fn ends_are_exact_and_motion_is_monotonic() {
        for law in MotionLaw::ALL {
            assert_eq!(law.eval(0.0).s, 0.0, "{law}");
            assert_eq!(law.eval(1.0).s, 1.0, "{law}");
            assert!((law.eval(0.5).s - 0.5).abs() < 1e-12, "{law}");
            let mut last = 0.0;
            for i in 0..=1000 {
                let s = law.eval(i as f64 / 1000.0).s;
                assert!(s >= last - 1e-15, "{law} falls at {i}");
                last = s;
            }
        }
    }

    #[test]
    fn out_of_range_input_is_clamped() {
        for law in MotionLaw::ALL {
            assert_eq!(law.eval(-3.0).s, 0.0);
            assert_eq!(law.eval(f64::INFINITY).s, 1.0);
            assert_eq!(law.eval(f64::NAN).s, 0.0);
        }
    }

    #[test]
    fn names_round_trip() {
        for law in MotionLaw::ALL {
            assert_eq!(MotionLaw::from_name(law.name()), Some(law));
            assert_eq!(law.name().parse::<MotionLaw>(), Ok(law));
        }
        assert_eq!(MotionLaw::from_name("Cycloid"), Some(MotionLaw::Cycloid));
        assert_eq!(MotionLaw::from_name("sine"), None);
    }
}
