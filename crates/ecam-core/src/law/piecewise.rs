//! Laws whose acceleration is built from pieces (sine arcs, constant-jerk
//! ramps), integrated in closed form.
//!
//! The modified trapezoid, modified sine, modified constant velocity and
//! S-type laws are all defined in the cam literature by their acceleration
//! diagram. Rather than hard-coding each law's position polynomial, each piece
//! is integrated exactly (sine quarters: closed-form integrals; constant
//! jerk: the cubic) and chained, starting at rest. The amplitude that makes the half
//! rise reach exactly `s = 1/2` is found by running the unit-amplitude chain
//! once; every law here is point-symmetric about `(1/2, 1/2)`, so only the
//! first half is described.

use crate::Kinematics;

/// One piece of an acceleration diagram over the first half of a rise.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Piece {
    /// Constant jerk: acceleration continues from the previous piece and
    /// changes by `jerk` per unit of `u` (`jerk = 0` holds it).
    Jerk {
        /// Width in `u`.
        len: f64,
        /// Jerk (unit amplitude).
        jerk: f64,
    },
    /// Rising sine quarter: `a(τ) = sin(ω τ)` (unit amplitude), from 0 up
    /// to the peak when `ω · len = π/2`.
    SineUp {
        /// Width in `u`.
        len: f64,
        /// Angular rate ω, radians per unit of `u`.
        omega: f64,
    },
    /// Falling cosine quarter: `a(τ) = cos(ω τ)`, from the peak down to 0
    /// when `ω · len = π/2`.
    CosineDown {
        /// Width in `u`.
        len: f64,
        /// Angular rate ω, radians per unit of `u`.
        omega: f64,
    },
}

impl Piece {
    fn len(self) -> f64 {
        match self {
            Self::Jerk { len, .. } | Self::SineUp { len, .. } | Self::CosineDown { len, .. } => len,
        }
    }

    /// Kinematics `tau` into this piece, given position, velocity and
    /// acceleration at its start.
    fn at(self, s0: f64, v0: f64, a0: f64, tau: f64) -> Kinematics {
        match self {
            Self::Jerk { jerk, .. } => Kinematics {
                s: s0 + v0 * tau + a0 * tau * tau / 2.0 + jerk * tau * tau * tau / 6.0,
                v: v0 + a0 * tau + jerk * tau * tau / 2.0,
                a: a0 + jerk * tau,
                j: jerk,
            },
            Self::SineUp { omega, .. } => {
                let (sin, cos) = (libm::sin(omega * tau), libm::cos(omega * tau));
                Kinematics {
                    s: s0 + v0 * tau + tau / omega - sin / (omega * omega),
                    v: v0 + (1.0 - cos) / omega,
                    a: sin,
                    j: omega * cos,
                }
            }
            Self::CosineDown { omega, .. } => {
                let (sin, cos) = (libm::sin(omega * tau), libm::cos(omega * tau));
                Kinematics {
                    s: s0 + v0 * tau + (1.0 - cos) / (omega * omega),
                    v: v0 + sin / omega,
                    a: cos,
                    j: -omega * sin,
                }
            }
        }
    }
}

/// Unit-amplitude kinematics at `u` (0 ≤ u ≤ 1/2) and at the end of the half.
fn run(pieces: &[Piece], u: f64) -> (Kinematics, Kinematics) {
    let (mut s, mut v, mut a) = (0.0, 0.0, 0.0);
    let mut start = 0.0;
    let mut at_u = None;
    let mut last = Kinematics::default();
    for (i, &piece) in pieces.iter().enumerate() {
        let end = start + piece.len();
        let is_last = i + 1 == pieces.len();
        if at_u.is_none() && (u <= end || is_last) {
            at_u = Some(piece.at(s, v, a, (u - start).max(0.0)));
        }
        last = piece.at(s, v, a, piece.len());
        (s, v, a) = (last.s, last.v, last.a);
        start = end;
    }
    (at_u.unwrap_or(last), last)
}

/// The normalised first half of a rise (0 ≤ u ≤ 1/2) described by `pieces`,
/// scaled so that `s(1/2) = 1/2`.
pub(crate) fn first_half(pieces: &[Piece], u: f64) -> Kinematics {
    let (k, half) = run(pieces, u);
    let gain = if half.s > 0.0 { 0.5 / half.s } else { 0.0 };
    Kinematics {
        s: k.s * gain,
        v: k.v * gain,
        a: k.a * gain,
        j: k.j * gain,
    }
}
