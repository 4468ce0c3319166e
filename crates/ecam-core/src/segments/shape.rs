//! A segment's solved shape in the normalised master `u ∈ [0, 1]`: slave
//! travel `S(u)` from the segment's first point and its derivatives in `u`
//! (a velocity ratio times the master span `β`, an acceleration times `β²`,
//! a jerk times `β³`), and the peaks of those derivatives from closed forms.

use core::f64::consts::PI;

use super::law::SegmentLaw;
use super::poly::{self, Polynomial};
use crate::{Kinematics, MotionLaw};

/// Boundary values of one end of a segment, in units of `u`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct End {
    pub v: f64,
    pub a: f64,
    pub j: f64,
}

/// A solved segment shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Shape {
    /// `S = rise · law(u)`.
    Rise { law: MotionLaw, rise: f64 },
    /// `S = Σ c[k] uᵏ`.
    Polynomial(Polynomial),
    /// `S = V0·u + D·I(u) + c·Cy(u)`, with `Cy` the cycloid, `I` its
    /// integral from 0, `D = V1 − V0`, `c = rise − (V0 + V1)/2`.
    VelocityCycloid { v0: f64, dv: f64, c: f64 },
}

const TAU: f64 = 2.0 * PI;

/// A normalised law value times the segment's rise.
fn scaled(k: Kinematics, rise: f64) -> Kinematics {
    Kinematics {
        s: rise * k.s,
        v: rise * k.v,
        a: rise * k.a,
        j: rise * k.j,
    }
}

impl Shape {
    /// Solves `law` over a segment rising `rise` (pulses) with the end values
    /// `start` and `end` (in units of `u`); values the law does not adapt
    /// to are ignored.
    pub fn solve(law: SegmentLaw, rise: f64, start: End, end: End) -> Self {
        match law {
            SegmentLaw::Rise(law) => Self::Rise { law, rise },
            SegmentLaw::Poly5 => Self::Polynomial(poly::solve(
                rise,
                &[0.0, start.v, start.a],
                &[rise, end.v, end.a],
            )),
            SegmentLaw::Poly7 => Self::Polynomial(poly::solve(
                rise,
                &[0.0, start.v, start.a, start.j],
                &[rise, end.v, end.a, end.j],
            )),
            SegmentLaw::VelocityCycloid => Self::VelocityCycloid {
                v0: start.v,
                dv: end.v - start.v,
                // ∫₀¹ Cy = 1/2 (the cycloid is point-symmetric), so the
                // velocity change covers (V0 + V1)/2 and the rise the rest.
                c: rise - 0.5 * (start.v + end.v),
            },
        }
    }

    /// `S, S', S'', S'''` at `u` (clamped onto `[0, 1]`).
    pub fn at(&self, u: f64) -> Kinematics {
        let u = if u.is_nan() { 0.0 } else { u.clamp(0.0, 1.0) };
        match *self {
            // At a knot of the law, the value after it (a joint belongs
            // to the piece starting there).
            Self::Rise { law, rise } => scaled(law.eval_after(u), rise),
            Self::Polynomial(p) => {
                let d1 = p.derivative();
                let d2 = d1.derivative();
                Kinematics {
                    s: p.at(u),
                    v: d1.at(u),
                    a: d2.at(u),
                    j: d2.derivative().at(u),
                }
            }
            Self::VelocityCycloid { v0, dv, c } => {
                // From the nearer end, so sin is exactly 0 at both ends
                // (and the acceleration there exactly the law's 0).
                let (sin, cos) = if u <= 0.5 {
                    (libm::sin(TAU * u), libm::cos(TAU * u))
                } else {
                    (-libm::sin(TAU * (1.0 - u)), libm::cos(TAU * (1.0 - u)))
                };
                let cy = u - sin / TAU;
                let integral = 0.5 * u * u + (cos - 1.0) / (TAU * TAU);
                Kinematics {
                    s: v0 * u + dv * integral + c * cy,
                    v: v0 + dv * cy + c * (1.0 - cos),
                    a: dv * (1.0 - cos) + c * TAU * sin,
                    j: dv * TAU * sin + c * TAU * TAU * cos,
                }
            }
        }
    }

    /// Where inside the segment the shape's acceleration steps: a rise
    /// law's knots ([`MotionLaw::acceleration_knots`]); the polynomials and
    /// the velocity cycloid are smooth inside.
    pub fn acceleration_knots(&self) -> &'static [f64] {
        match self {
            Self::Rise { law, .. } => law.acceleration_knots(),
            _ => &[],
        }
    }

    /// As [`Shape::at`], but at a knot the value just before it.
    pub fn at_before(&self, u: f64) -> Kinematics {
        match *self {
            Self::Rise { law, rise } => scaled(law.eval(u), rise),
            _ => self.at(u),
        }
    }

    /// Peaks of `|S'|`, `|S''|`, `|S'''|` over the segment (`INFINITY` for
    /// an impulse inside it), from closed forms: the rise laws' factors
    /// ([`MotionLaw::interior_peaks`]) times the rise; for a polynomial, the
    /// ends and the roots of the next derivative; for the velocity cycloid,
    /// the ends and the angles where the next derivative, a sum
    /// `P + Q cos θ + R sin θ` in `θ = 2πu`, vanishes.
    pub fn peaks(&self) -> (f64, f64, f64) {
        match *self {
            Self::Rise { law, rise } => {
                let (cv, ca, cj) = law.interior_peaks();
                let r = rise.abs();
                // A dwell (rise 0) has no impulse either.
                let scale = |c: f64| if r == 0.0 { 0.0 } else { c * r };
                (scale(cv), scale(ca), scale(cj))
            }
            Self::Polynomial(p) => {
                let d1 = p.derivative();
                let d2 = d1.derivative();
                (d1.max_abs(), d2.max_abs(), d2.derivative().max_abs())
            }
            Self::VelocityCycloid { dv, c, .. } => {
                // Roots of S'' = D − D cos θ + 2πc sin θ, S''' = 2πD sin θ
                // + 4π²c cos θ and S'''' = 4π²D cos θ − 8π³c sin θ.
                let peak = |pick: fn(&Kinematics) -> f64, (p, q, r): (f64, f64, f64)| {
                    trig_roots(p, q, r)
                        .into_iter()
                        .flatten()
                        .map(|theta| theta / TAU)
                        .chain([0.0, 1.0])
                        .map(|u| pick(&self.at(u)).abs())
                        .fold(0.0, f64::max)
                };
                (
                    peak(|k| k.v, (dv, -dv, TAU * c)),
                    peak(|k| k.a, (0.0, TAU * TAU * c, TAU * dv)),
                    peak(|k| k.j, (0.0, TAU * TAU * dv, -TAU * TAU * TAU * c)),
                )
            }
        }
    }
}

/// The angles `θ ∈ (0, 2π)` where `p + q cos θ + r sin θ = 0`: with
/// `q cos θ + r sin θ = ρ cos(θ − φ)`, `θ = φ ± acos(−p/ρ)`.
fn trig_roots(p: f64, q: f64, r: f64) -> [Option<f64>; 2] {
    let rho = libm::hypot(q, r);
    if rho == 0.0 || (p / rho).abs() > 1.0 {
        return [None, None];
    }
    let phi = libm::atan2(r, q);
    let alpha = libm::acos(-p / rho);
    let wrap = |theta: f64| {
        let t = theta - TAU * libm::floor(theta / TAU);
        (t > 0.0 && t < TAU).then_some(t)
    };
    [wrap(phi + alpha), wrap(phi - alpha)]
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn sampled(shape: &Shape) -> (f64, f64, f64) {
        let n = 200_000;
        (0..=n).fold((0.0f64, 0.0f64, 0.0f64), |(v, a, j), i| {
            let k = shape.at(i as f64 / n as f64);
            (v.max(k.v.abs()), a.max(k.a.abs()), j.max(k.j.abs()))
        })
    }

    #[test]
    fn velocity_cycloid_meets_its_ends_and_its_derivatives_agree() {
        let start = End {
            v: 3.0,
            a: 9.0,
            j: 9.0,
        };
        let end = End {
            v: 0.5,
            a: 9.0,
            j: 9.0,
        };
        let s = Shape::solve(SegmentLaw::VelocityCycloid, 2.0, start, end);
        let (k0, k1) = (s.at(0.0), s.at(1.0));
        assert!(k0.s.abs() < 1e-15 && (k1.s - 2.0).abs() < 1e-12);
        assert!((k0.v - 3.0).abs() < 1e-12 && (k1.v - 0.5).abs() < 1e-12);
        assert!(k0.a.abs() < 1e-12 && k1.a.abs() < 1e-12);
        let h = 1e-6;
        for i in 1..100 {
            let u = f64::from(i) / 100.0;
            let (lo, k, hi) = (s.at(u - h), s.at(u), s.at(u + h));
            assert!((k.v - (hi.s - lo.s) / (2.0 * h)).abs() < 1e-6);
            assert!((k.a - (hi.v - lo.v) / (2.0 * h)).abs() < 1e-5);
            assert!((k.j - (hi.a - lo.a) / (2.0 * h)).abs() < 1e-4);
        }
    }

    #[test]
    fn closed_form_peaks_match_dense_samples() {
        let shapes = [
            Shape::solve(
                SegmentLaw::VelocityCycloid,
                2.0,
                End {
                    v: 3.0,
                    ..End::default()
                },
                End {
                    v: 0.5,
                    ..End::default()
                },
            ),
            Shape::solve(
                SegmentLaw::VelocityCycloid,
                1.0,
                End {
                    v: 1.0,
                    ..End::default()
                },
                End {
                    v: 1.0,
                    ..End::default()
                },
            ),
            Shape::solve(
                SegmentLaw::VelocityCycloid,
                -1.0,
                End {
                    v: 0.0,
                    ..End::default()
                },
                End {
                    v: 2.0,
                    ..End::default()
                },
            ),
            Shape::solve(
                SegmentLaw::Poly5,
                1.0,
                End {
                    v: 1.0,
                    a: -2.0,
                    j: 0.0,
                },
                End {
                    v: 3.0,
                    a: 0.0,
                    j: 0.0,
                },
            ),
            Shape::solve(
                SegmentLaw::Poly7,
                -2.0,
                End {
                    v: 1.0,
                    a: 0.5,
                    j: 3.0,
                },
                End {
                    v: 0.0,
                    a: 0.0,
                    j: 0.0,
                },
            ),
            Shape::Rise {
                law: MotionLaw::Cycloid,
                rise: -3.0,
            },
        ];
        for s in shapes {
            let (v, a, j) = s.peaks();
            let (sv, sa, sj) = sampled(&s);
            let near = |x: f64, y: f64| (x - y).abs() <= 1e-6 * x.abs().max(1.0);
            assert!(
                near(v, sv) && near(a, sa) && near(j, sj),
                "{s:?}: {:?} vs {:?}",
                (v, a, j),
                (sv, sa, sj)
            );
        }
    }
}
