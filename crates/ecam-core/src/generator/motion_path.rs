//! The exact (continuous) motion the generators design before sampling it
//! into a point table: a chain of ramps of the velocity ratio.
//!
//! Positions are `f64` here; the sampler rounds them to whole pulses and pins
//! the points that must be exact (table ends, sync-zone ends).

use alloc::vec::Vec;

use super::accel_curve::AccelCurve;
use crate::{Kinematics, TableError};

/// One piece of a path: part `[offset, offset + len]` of a ramp of the
/// velocity ratio from `v0` to `v1` over `ramp_len` master counts.
/// A piece with `v0 == v1` runs at constant velocity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Piece {
    pub master_start: f64,
    pub len: f64,
    pub slave_start: f64,
    pub v0: f64,
    pub v1: f64,
    ramp_len: f64,
    offset: f64,
    curve: AccelCurve,
}

impl Piece {
    /// Slave travel of the whole ramp from its start to ramp position `y`.
    fn ramp_distance(&self, y: f64) -> f64 {
        if self.ramp_len <= 0.0 {
            return self.v1 * y;
        }
        self.v0 * y + (self.v1 - self.v0) * self.ramp_len * self.curve.distance(y / self.ramp_len)
    }

    pub fn is_constant_velocity(&self) -> bool {
        self.v0 == self.v1
    }

    pub fn master_end(&self) -> f64 {
        self.master_start + self.len
    }

    pub fn slave_at(&self, master: f64) -> f64 {
        let x = (master - self.master_start).clamp(0.0, self.len);
        self.slave_start + self.ramp_distance(self.offset + x) - self.ramp_distance(self.offset)
    }

    #[cfg(test)]
    pub fn velocity_at(&self, master: f64) -> f64 {
        if self.ramp_len <= 0.0 {
            return self.v1;
        }
        let x = (master - self.master_start).clamp(0.0, self.len);
        self.v0 + (self.v1 - self.v0) * self.curve.velocity((self.offset + x) / self.ramp_len)
    }

    pub fn slave_end(&self) -> f64 {
        self.slave_at(self.master_end())
    }

    /// Slave position and its derivatives at `master` (clamped onto the
    /// piece), analytic: each derivative of the ramp's curve carries one more
    /// factor `1/ramp_len`.
    pub fn kinematics_at(&self, master: f64) -> Kinematics {
        let s = self.slave_at(master);
        if self.ramp_len <= 0.0 || self.is_constant_velocity() {
            return Kinematics {
                s,
                v: self.v1,
                a: 0.0,
                j: 0.0,
            };
        }
        let x = (master - self.master_start).clamp(0.0, self.len);
        let u = (self.offset + x) / self.ramp_len;
        let dv = self.v1 - self.v0;
        Kinematics {
            s,
            v: self.v0 + dv * self.curve.velocity(u),
            a: dv * self.curve.acceleration(u) / self.ramp_len,
            j: dv * self.curve.jerk(u) / (self.ramp_len * self.ramp_len),
        }
    }

    /// The same piece moving the other way (slave positions and velocities
    /// negated; negation is exact in floating point, so this is the exact
    /// mirror of the piece).
    fn mirrored(&self) -> Piece {
        Piece {
            slave_start: -self.slave_start,
            v0: -self.v0,
            v1: -self.v1,
            ..*self
        }
    }

    /// The two parts of this piece either side of `master` (inside it).
    fn split(&self, master: f64) -> (Piece, Piece) {
        let first_len = (master - self.master_start).clamp(0.0, self.len);
        let first = Piece {
            len: first_len,
            ..*self
        };
        let second = Piece {
            master_start: self.master_start + first_len,
            len: self.len - first_len,
            slave_start: self.slave_at(master),
            offset: self.offset + first_len,
            ..*self
        };
        (first, second)
    }
}

/// A ramp to append to a path: velocity ratio from `v0` to `v1` over `len`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ramp {
    pub v0: f64,
    pub v1: f64,
    pub len: f64,
}

/// A chain of pieces, each starting where the previous one ends.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Path {
    pieces: Vec<Piece>,
    master_end: f64,
    slave_end: f64,
}

impl Path {
    /// An empty path starting at `(master, slave)`.
    pub fn starting_at(master: f64, slave: f64) -> Self {
        Self {
            pieces: Vec::new(),
            master_end: master,
            slave_end: slave,
        }
    }

    pub fn pieces(&self) -> &[Piece] {
        &self.pieces
    }

    #[cfg(test)]
    pub fn master_end(&self) -> f64 {
        self.master_end
    }

    fn push_piece(&mut self, piece: Piece) {
        if piece.len > 0.0 {
            self.master_end = piece.master_end();
            self.slave_end = piece.slave_end();
            self.pieces.push(piece);
        }
    }

    /// Appends a ramp (zero-length ramps are dropped).
    pub fn push(&mut self, ramp: Ramp, curve: AccelCurve) {
        self.push_piece(Piece {
            master_start: self.master_end,
            len: ramp.len,
            slave_start: self.slave_end,
            v0: ramp.v0,
            v1: ramp.v1,
            ramp_len: ramp.len,
            offset: 0.0,
            curve,
        });
    }

    /// Appends a constant-velocity piece.
    pub fn push_constant(&mut self, velocity: f64, len: f64) {
        self.push(
            Ramp {
                v0: velocity,
                v1: velocity,
                len,
            },
            AccelCurve::Uniform,
        );
    }

    pub fn extend(&mut self, ramps: &[Ramp], curve: AccelCurve) {
        for &r in ramps {
            self.push(r, curve);
        }
    }

    /// Slave position at `master` (clamped onto the path).
    pub fn slave_at(&self, master: f64) -> f64 {
        let i = self.pieces.partition_point(|p| p.master_start <= master);
        match self.pieces.get(i.saturating_sub(1)) {
            Some(p) => p.slave_at(master),
            None => self.slave_end,
        }
    }

    /// Slave position and derivatives at `master` (clamped onto the path).
    /// A master on a joint belongs to the piece starting there.
    pub fn kinematics_at(&self, master: f64) -> Kinematics {
        let i = self.pieces.partition_point(|p| p.master_start <= master);
        match self.pieces.get(i.saturating_sub(1)) {
            Some(p) => p.kinematics_at(master),
            None => Kinematics::at_rest(self.slave_end),
        }
    }

    /// The mirror image of this path: the same motion with the slave
    /// running the other way (what the generators do for negative strokes).
    pub fn mirrored(&self) -> Path {
        Path {
            pieces: self.pieces.iter().map(Piece::mirrored).collect(),
            master_end: self.master_end,
            slave_end: -self.slave_end,
        }
    }

    /// Appends `other`'s pieces moved by `master_shift` and `slave_shift`.
    pub fn append_shifted(&mut self, other: &Path, master_shift: f64, slave_shift: f64) {
        for p in &other.pieces {
            self.push_piece(Piece {
                master_start: p.master_start + master_shift,
                slave_start: p.slave_start + slave_shift,
                ..*p
            });
        }
    }

    /// Velocity ratio at `master` (clamped onto the path).
    #[cfg(test)]
    pub fn velocity_at(&self, master: f64) -> f64 {
        let i = self.pieces.partition_point(|p| p.master_start <= master);
        self.pieces
            .get(i.saturating_sub(1))
            .map_or(0.0, |p| p.velocity_at(master))
    }

    /// The same motion seen from a cycle that starts at master `x0` of this
    /// one: the part after `x0` first, then the part before it, moved on by
    /// one cycle (`cycle_master`, `stroke`); all slaves lowered by
    /// `slave_offset`. This path must start at (0, 0).
    pub fn rotated(&self, x0: f64, cycle_master: f64, stroke: f64, slave_offset: f64) -> Path {
        let mut before = Vec::new();
        let mut after = Vec::new();
        for p in &self.pieces {
            if p.master_end() <= x0 {
                before.push(*p);
            } else if p.master_start >= x0 {
                after.push(*p);
            } else {
                let (a, b) = p.split(x0);
                before.push(a);
                after.push(b);
            }
        }
        let mut out = Path::starting_at(0.0, self.slave_at(x0) - slave_offset);
        for p in after {
            out.push_piece(Piece {
                master_start: p.master_start - x0,
                slave_start: p.slave_start - slave_offset,
                ..p
            });
        }
        for p in before {
            out.push_piece(Piece {
                master_start: p.master_start + cycle_master - x0,
                slave_start: p.slave_start + stroke - slave_offset,
                ..p
            });
        }
        out
    }

    /// The pieces that start at or after `master` (used to splice a new
    /// beginning onto a path whose pieces have a boundary at `master`).
    pub fn pieces_from(&self, master: f64) -> impl Iterator<Item = &Piece> {
        self.pieces.iter().filter(move |p| p.master_start >= master)
    }

    /// The pieces that end at or before `master`.
    pub fn pieces_until(&self, master: f64) -> impl Iterator<Item = &Piece> {
        self.pieces.iter().filter(move |p| p.master_end() <= master)
    }

    /// Appends pieces that already carry their absolute positions.
    pub fn append_pieces<'a>(&mut self, pieces: impl Iterator<Item = &'a Piece>) {
        for p in pieces {
            self.push_piece(*p);
        }
    }
}

/// Which way a transition had to bend to cover its distance.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Bend {
    /// Up to a peak (or down to a trough) and back, no cruise.
    Triangle,
    /// Capped by the maximum ratio: ramps, cruise at the maximum, ramps.
    CruiseAtMax,
    /// Down to standstill, dwell, and up again.
    Dwell,
}

/// A transition from velocity ratio `v0` to `v1` over `len` master counts
/// covering `distance` slave pulses, never above `v_max` nor below zero.
///
/// Shape: two ramps of equal length meeting at the velocity that makes the
/// distance come out (`2·distance/len − (v0 + v1)/2`); if that velocity is
/// above `v_max` the ramps shorten and a cruise at `v_max` fills the middle;
/// if it is below zero the ramps shorten to reach standstill and a dwell fills
/// the middle. Each ramp covers its mean velocity times its length whatever
/// the curve (see [`AccelCurve`]), so the distance is met exactly.
pub(crate) fn transition(
    v0: f64,
    v1: f64,
    len: f64,
    distance: f64,
    v_max: f64,
) -> Result<(Bend, Vec<Ramp>), TableError> {
    let steps = TableError::Infeasible {
        reason: "the motion between sync zones would need a velocity jump: lengthen the non-synchronised part",
    };
    if !(v0 >= 0.0 && v1 >= 0.0 && v0 <= v_max && v1 <= v_max && distance >= 0.0) {
        return Err(TableError::Infeasible {
            reason: "the sync ratio is above the max ratio",
        });
    }
    if len <= 0.0 {
        return if distance == 0.0 && v0 == v1 {
            Ok((Bend::Triangle, Vec::new()))
        } else {
            Err(steps)
        };
    }
    let mean_ends = 0.5 * (v0 + v1);
    let peak = 2.0 * distance / len - mean_ends;
    if peak > v_max {
        if distance >= v_max * len {
            return Err(TableError::Infeasible {
                reason: "the slave cannot cover its length within the max ratio: raise the max ratio or lengthen the master",
            });
        }
        let ramp = (v_max * len - distance) / (v_max - mean_ends);
        if !(ramp > 0.0 && ramp.is_finite()) {
            return Err(steps);
        }
        let ramp = ramp.min(0.5 * len);
        Ok((
            Bend::CruiseAtMax,
            alloc::vec![
                Ramp {
                    v0,
                    v1: v_max,
                    len: ramp
                },
                Ramp {
                    v0: v_max,
                    v1: v_max,
                    len: len - 2.0 * ramp
                },
                Ramp {
                    v0: v_max,
                    v1,
                    len: ramp
                },
            ],
        ))
    } else if peak < 0.0 {
        let ramp = 2.0 * distance / (v0 + v1);
        if !(ramp > 0.0 && ramp.is_finite()) {
            return Err(steps);
        }
        let ramp = ramp.min(0.5 * len);
        Ok((
            Bend::Dwell,
            alloc::vec![
                Ramp {
                    v0,
                    v1: 0.0,
                    len: ramp
                },
                Ramp {
                    v0: 0.0,
                    v1: 0.0,
                    len: len - 2.0 * ramp
                },
                Ramp {
                    v0: 0.0,
                    v1,
                    len: ramp
                },
            ],
        ))
    } else if v0 == v1 && (peak - v0).abs() <= 1e-12 * v0.max(1.0) {
        // Already at the right mean speed: one constant-velocity piece.
        Ok((Bend::Triangle, alloc::vec![Ramp { v0, v1, len }]))
    } else {
        Ok((
            Bend::Triangle,
            alloc::vec![
                Ramp {
                    v0,
                    v1: peak,
                    len: 0.5 * len
                },
                Ramp {
                    v0: peak,
                    v1,
                    len: 0.5 * len
                }
            ],
        ))
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn path_of(ramps: &[Ramp], curve: AccelCurve) -> Path {
        let mut p = Path::starting_at(0.0, 0.0);
        p.extend(ramps, curve);
        p
    }

    #[test]
    fn transitions_cover_their_distance_in_every_bend() {
        // (v0, v1, len, distance, v_max, expected bend)
        let cases = [
            (1.0, 1.0, 100.0, 150.0, 10.0, Bend::Triangle),
            (1.0, 1.0, 100.0, 60.0, 10.0, Bend::Triangle),
            (1.0, 1.0, 100.0, 100.0, 10.0, Bend::Triangle),
            (1.0, 1.0, 100.0, 20.0, 10.0, Bend::Dwell),
            (1.0, 1.0, 100.0, 400.0, 5.0, Bend::CruiseAtMax),
            (0.0, 2.0, 50.0, 10.0, 5.0, Bend::Dwell),
            (2.0, 0.0, 50.0, 80.0, 5.0, Bend::Triangle),
        ];
        for (v0, v1, len, d, vmax, bend) in cases {
            for curve in AccelCurve::ALL {
                let (b, ramps) = transition(v0, v1, len, d, vmax).unwrap();
                assert_eq!(b, bend);
                let p = path_of(&ramps, curve);
                assert!((p.master_end() - len).abs() < 1e-9);
                assert!((p.slave_at(len) - d).abs() < 1e-9, "{b:?} {curve:?}");
                assert!((p.velocity_at(0.0) - v0).abs() < 1e-12);
                assert!((p.velocity_at(len) - v1).abs() < 1e-9);
                for i in 0..=1000 {
                    let v = p.velocity_at(len * f64::from(i) / 1000.0);
                    assert!((-1e-12..=vmax + 1e-12).contains(&v));
                }
            }
        }
    }

    #[test]
    fn infeasible_transitions_are_refused() {
        assert!(transition(1.0, 1.0, 100.0, 600.0, 5.0).is_err());
        assert!(transition(1.0, 1.0, 100.0, 0.0, 5.0).is_err());
        assert!(transition(6.0, 1.0, 100.0, 50.0, 5.0).is_err());
        assert!(transition(1.0, 1.0, 0.0, 3.0, 5.0).is_err());
    }

    #[test]
    fn rotation_keeps_the_motion() {
        let mut p = Path::starting_at(0.0, 0.0);
        p.push_constant(2.0, 10.0);
        let (_, ramps) = transition(2.0, 2.0, 90.0, 60.0, 10.0).unwrap();
        p.extend(&ramps, AccelCurve::BType);
        let stroke = p.slave_at(100.0);
        assert!((stroke - 80.0).abs() < 1e-9);
        let r = p.rotated(37.5, 100.0, stroke, 5.0);
        for i in 0..=200 {
            let m = f64::from(i) / 2.0;
            let orig = if m + 37.5 <= 100.0 {
                p.slave_at(m + 37.5)
            } else {
                p.slave_at(m - 62.5) + stroke
            };
            assert!((r.slave_at(m) - (orig - 5.0)).abs() < 1e-9, "at {m}");
        }
        assert!((r.master_end() - 100.0).abs() < 1e-12);
    }
}
