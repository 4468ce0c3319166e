//! Gearing (PLCopen `MC_GearIn`, `MC_GearInPos`, `MC_GearOut`): the slave
//! follows the master it sees at an exact ratio, beside (added to) a cam
//! and a superimposed move on the same axis.
//!
//! In gear the gear's part of the slave is the line
//! `anchor_slave + (master − anchor_master) × num / den`, an exact integer
//! ratio evaluated in fixed point and rounded once per tick: it does not
//! drift, in either direction, whatever the master does. Getting there:
//!
//! - `MC_GearIn` blends the velocity ratio from the one the gear has (0
//!   when it was out) to the new one over a master distance, exactly as a
//!   cam switch blends (`3u² − 2u³`, never outside the two ratios, the
//!   acceleration at most `1.5 |Δratio| / distance` per master count²);
//!   the distance is given, or sized for an acceleration limit at the
//!   master's speed then. The line is anchored where the blend ends, on a
//!   whole pulse (the fraction spread over the blend as in `blend.rs`).
//! - `MC_GearInPos` reaches the line through the sync point
//!   (`MasterSyncPosition`, `SlaveSyncPosition`) exactly there, with the
//!   ramp-in's quintic from where the gear's part stands, starting at
//!   `MasterStartDistance` before the sync position (or at once).
//! - `MC_GearOut` blends the ratio down to 0 over a distance (or holds at
//!   once) and leaves the part where it stands.

use core::num::NonZeroU64;

use crate::ramp::quintic;
use crate::timed_move::{ONE, to_units};
use crate::{CouplingError, Zoom, min_blend_distance};

/// How a gear changes its ratio.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GearRamp {
    /// At once: the position is continuous, the velocity steps.
    Immediate,
    /// Over this many master counts.
    Distance(NonZeroU64),
    /// Over the distance that keeps the slave's acceleration within this
    /// many pulses/s² at the master's speed when commanded
    /// ([`min_blend_distance`]); a master at rest changes at once.
    Acceleration(f64),
}

/// `MC_GearIn`: couple at `ratio` (`RatioNumerator / RatioDenominator`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GearIn {
    /// The exact ratio, signed.
    pub ratio: Zoom,
    /// How the slave gets to it.
    pub ramp: GearRamp,
}

/// `MC_GearInPos`: couple so that the gear's part is at `slave_sync` when
/// the master is at `master_sync`, then follow at `ratio`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GearInPos {
    /// The exact ratio, signed.
    pub ratio: Zoom,
    /// `MasterSyncPosition`, master counts.
    pub master_sync: i64,
    /// `SlaveSyncPosition`, pulses (of the gear's part).
    pub slave_sync: i64,
    /// `MasterStartDistance`: start the approach this far before the sync
    /// position; `None` starts it at once.
    pub master_start_distance: Option<NonZeroU64>,
}

/// `MC_GearOut`: leave the gear.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GearOut {
    /// How the ratio comes down to 0 ([`GearRamp::Immediate`]: the part
    /// holds at once).
    pub ramp: GearRamp,
}

/// Where the gear is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GearState {
    /// Not coupled; the part holds.
    #[default]
    Off,
    /// `MC_GearInPos` waiting for the master to reach the start distance.
    Waiting,
    /// Changing the ratio, or approaching the sync point (`StartSync`).
    Syncing,
    /// In gear (`InGear` / `InSync`).
    InGear,
    /// `MC_GearOut` bringing the ratio down.
    Leaving,
}

/// What the gear reports every tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GearStatus {
    /// Where the gear is.
    pub state: GearState,
    /// The gear's part of the slave, pulses.
    pub slave: i64,
    /// d(part)/d(master) now.
    pub velocity_ratio: f64,
}

/// The exact line of a gear.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Line {
    master: i128,
    slave: i64,
    num: i128,
    den: i128,
}

impl Line {
    fn new(master: i128, slave: i64, ratio: Option<Zoom>) -> Self {
        let (num, den) = ratio.map_or((0, 1), |r| {
            (i128::from(r.signed_num()), i128::from(r.den()))
        });
        Self {
            master,
            slave,
            num,
            den,
        }
    }

    fn ratio(&self) -> f64 {
        self.num as f64 / self.den as f64
    }

    /// The part at master `x` (fixed point): exact, rounded once.
    fn at(&self, x: i128) -> i64 {
        // |x − master| < 2^97, × 65535 < 2^113: no overflow.
        let travel = x.saturating_sub(self.master).saturating_mul(self.num);
        let d = self.den * ONE;
        let step = if travel >= 0 {
            (travel + d / 2) / d
        } else {
            -((-travel + d / 2) / d)
        };
        clamp(i128::from(self.slave).saturating_add(step))
    }
}

/// A ratio blend in progress.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Blend {
    from: i128,
    distance: f64,
    p0: f64,
    v0: f64,
    v1: f64,
    /// The lines the blend ends on, forwards and backwards.
    ends: [Line; 2],
    residual: [f64; 2],
    leaving: bool,
}

/// `∫₀ᵘ (3t² − 2t³) dt`.
fn smoothstep_integral(u: f64) -> f64 {
    u * u * u * (1.0 - 0.5 * u)
}

impl Blend {
    fn new(from: i128, distance: NonZeroU64, p0: i64, v0: f64, ratio: Option<Zoom>) -> Self {
        let d = distance.get() as f64;
        let v1 = ratio.map_or(0.0, Zoom::ratio);
        let step = i128::from(distance.get()) * ONE;
        let mut ends = [Line::new(0, 0, ratio); 2];
        let mut residual = [0.0; 2];
        for (i, sign) in [1.0, -1.0].into_iter().enumerate() {
            let end = p0 as f64 + sign * d * 0.5 * (v0 + v1);
            // Rounded towards the travel so the spread fraction cannot
            // turn the slave back.
            let whole = if end >= p0 as f64 {
                libm::ceil(end)
            } else {
                libm::floor(end)
            };
            let whole = whole.clamp(-9.0e18, 9.0e18);
            if let (Some(e), Some(r)) = (ends.get_mut(i), residual.get_mut(i)) {
                *e = Line::new(
                    if sign > 0.0 { from + step } else { from - step },
                    whole as i64,
                    ratio,
                );
                *r = whole - end;
            }
        }
        Self {
            from,
            distance: d,
            p0: p0 as f64,
            v0,
            v1,
            ends,
            residual,
            leaving: ratio.is_none(),
        }
    }

    /// The part and its velocity ratio at `x`, or the line it ended on.
    fn at(&self, x: i128) -> Result<(i64, f64), Line> {
        let travelled = to_units(x - self.from);
        let side = usize::from(travelled < 0.0);
        let u = travelled.abs() / self.distance;
        if u >= 1.0 {
            return Err(self.ends.get(side).copied().unwrap_or(self.ends[0]));
        }
        let sign = if side == 0 { 1.0 } else { -1.0 };
        let dv = self.v1 - self.v0;
        let position = self.p0
            + sign * self.distance * (self.v0 * u + dv * smoothstep_integral(u))
            + self.residual.get(side).copied().unwrap_or(0.0) * quintic(u);
        let position = libm::round(position).clamp(-9.0e18, 9.0e18) as i64;
        Ok((position, self.v0 + dv * u * u * (3.0 - 2.0 * u)))
    }
}

/// What the gear is doing.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Phase {
    Off,
    Waiting {
        sync: Line,
        start: i128,
        forward: bool,
    },
    Approach {
        sync: Line,
        from: i128,
        span: f64,
        forward: bool,
        hold: i64,
    },
    Blend(Blend),
    Line(Line),
}

/// The gear's part of a slave axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Gear {
    phase: Phase,
    part: i64,
    ratio: f64,
}

impl Gear {
    pub(crate) const fn new() -> Self {
        Self {
            phase: Phase::Off,
            part: 0,
            ratio: 0.0,
        }
    }

    /// The blend distance a ramp asks for, changing the ratio by `gap` at
    /// master speed `speed` (counts/s).
    fn distance(ramp: GearRamp, gap: f64, speed: f64) -> Result<Option<NonZeroU64>, CouplingError> {
        match ramp {
            GearRamp::Immediate => Ok(None),
            GearRamp::Distance(d) => Ok(Some(d)),
            GearRamp::Acceleration(a) if a.is_finite() && a > 0.0 => {
                Ok(min_blend_distance(gap, speed, a))
            }
            GearRamp::Acceleration(_) => Err(CouplingError::BadLimit),
        }
    }

    fn change_ratio(
        &mut self,
        ratio: Option<Zoom>,
        ramp: GearRamp,
        x: i128,
        speed: f64,
    ) -> Result<(), CouplingError> {
        let v1 = ratio.map_or(0.0, Zoom::ratio);
        self.phase = match Self::distance(ramp, v1 - self.ratio, speed)? {
            Some(d) => Phase::Blend(Blend::new(x, d, self.part, self.ratio, ratio)),
            None if ratio.is_some() => Phase::Line(Line::new(x, self.part, ratio)),
            None => Phase::Off,
        };
        if matches!(self.phase, Phase::Off) {
            self.ratio = 0.0;
        }
        Ok(())
    }

    /// `MC_GearIn` at master `x` (fixed point), the master at `speed` counts/s.
    pub(crate) fn gear_in(&mut self, c: &GearIn, x: i128, speed: f64) -> Result<(), CouplingError> {
        self.change_ratio(Some(c.ratio), c.ramp, x, speed)
    }

    /// `MC_GearOut` at master `x`.
    pub(crate) fn gear_out(
        &mut self,
        c: &GearOut,
        x: i128,
        speed: f64,
    ) -> Result<(), CouplingError> {
        self.change_ratio(None, c.ramp, x, speed)
    }

    /// `MC_GearInPos` at master `x`, the master moving at `velocity`
    /// counts/s (its sign tells the way it approaches; at rest, the side of
    /// the sync position it is on).
    pub(crate) fn gear_in_pos(
        &mut self,
        c: &GearInPos,
        x: i128,
        velocity: f64,
    ) -> Result<(), CouplingError> {
        let m = i128::from(c.master_sync) * ONE;
        let sync = Line::new(m, c.slave_sync, Some(c.ratio));
        let forward = if velocity != 0.0 {
            velocity > 0.0
        } else {
            x <= m
        };
        let ahead = if forward { x <= m } else { x >= m };
        if !ahead {
            return Err(CouplingError::SyncPassed);
        }
        let start = match c.master_start_distance {
            Some(d) => {
                let d = i128::from(d.get()) * ONE;
                if forward { m - d } else { m + d }
            }
            None => x,
        };
        let started = if forward { x >= start } else { x <= start };
        self.phase = if x == m {
            Phase::Line(sync)
        } else if started {
            Phase::Approach {
                sync,
                from: x,
                span: to_units(m - x).abs(),
                forward,
                hold: self.part,
            }
        } else {
            Phase::Waiting {
                sync,
                start,
                forward,
            }
        };
        Ok(())
    }

    /// Holds the part where it stands (inhibit, stop).
    pub(crate) fn stop(&mut self) {
        self.phase = Phase::Off;
        self.ratio = 0.0;
    }

    /// The part at master `x` (fixed point); moves the phase on.
    pub(crate) fn at(&mut self, x: i128) -> i64 {
        let (part, ratio) = match self.phase {
            Phase::Off => (self.part, 0.0),
            Phase::Line(line) => (line.at(x), line.ratio()),
            Phase::Blend(blend) => match blend.at(x) {
                Ok(now) => now,
                Err(line) => {
                    self.phase = if blend.leaving {
                        Phase::Off
                    } else {
                        Phase::Line(line)
                    };
                    (line.at(x), line.ratio())
                }
            },
            Phase::Waiting {
                sync,
                start,
                forward,
            } => {
                let reached = if forward { x >= start } else { x <= start };
                if reached {
                    let span = to_units(sync.master - start).abs();
                    self.phase = Phase::Approach {
                        sync,
                        from: start,
                        span,
                        forward,
                        hold: self.part,
                    };
                    return self.at(x);
                }
                (self.part, 0.0)
            }
            Phase::Approach {
                sync,
                from,
                span,
                forward,
                hold,
            } => {
                let dir = if forward { 1.0 } else { -1.0 };
                let u = (dir * to_units(x - from) / span).clamp(0.0, 1.0);
                let done = if forward {
                    x >= sync.master
                } else {
                    x <= sync.master
                };
                if done || span <= 0.0 {
                    self.phase = Phase::Line(sync);
                    (sync.at(x), sync.ratio())
                } else {
                    let line = sync.at(x);
                    let w = quintic(u);
                    let gap = (hold as f64) - line as f64;
                    let part = libm::round(line as f64 + (1.0 - w) * gap);
                    let dw = 30.0 * u * u * (1.0 - u) * (1.0 - u);
                    let ratio = sync.ratio() * w - gap * dw * dir / span;
                    (part.clamp(-9.0e18, 9.0e18) as i64, ratio)
                }
            }
        };
        self.part = part;
        self.ratio = ratio;
        part
    }

    pub(crate) fn status(&self) -> GearStatus {
        GearStatus {
            state: match self.phase {
                Phase::Off => GearState::Off,
                Phase::Waiting { .. } => GearState::Waiting,
                Phase::Approach { .. } => GearState::Syncing,
                Phase::Blend(b) if b.leaving => GearState::Leaving,
                Phase::Blend(_) => GearState::Syncing,
                Phase::Line(_) => GearState::InGear,
            },
            slave: self.part,
            velocity_ratio: self.ratio,
        }
    }
}

fn clamp(v: i128) -> i64 {
    i64::try_from(v).unwrap_or(if v < 0 { i64::MIN } else { i64::MAX })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fixed(counts: i64) -> i128 {
        i128::from(counts) * ONE
    }

    #[test]
    fn gear_in_blends_then_follows_the_exact_line() {
        let mut g = Gear::new();
        let ratio = Zoom::signed(7, 3).unwrap();
        g.gear_in(
            &GearIn {
                ratio,
                ramp: GearRamp::Distance(NonZeroU64::new(3000).unwrap()),
            },
            0,
            0.0,
        )
        .unwrap();
        let mut last = 0;
        for m in 0..=3000 {
            let p = g.at(fixed(m));
            assert!(p >= last, "never back at {m}");
            last = p;
        }
        assert_eq!(g.status().state, GearState::InGear);
        // 3000 × 7/3 / 2 = 3500 where the blend ends, then exact 7/3.
        assert_eq!(g.at(fixed(3000)), 3500);
        assert_eq!(g.at(fixed(3003)), 3507);
        assert_eq!(g.at(fixed(3001)), 3502);
        assert_eq!(g.at(fixed(-3000)), 3500 - 14_000);
        assert_eq!(g.at(fixed(1_000_003_000)), 3500 + 2_333_333_333);
    }

    #[test]
    fn gear_in_pos_meets_the_sync_point() {
        let mut g = Gear::new();
        let c = GearInPos {
            ratio: Zoom::signed(2, 1).unwrap(),
            master_sync: 10_000,
            slave_sync: 50_000,
            master_start_distance: NonZeroU64::new(4000),
        };
        g.gear_in_pos(&c, 0, 1000.0).unwrap();
        assert_eq!(g.at(fixed(5000)), 0);
        assert_eq!(g.status().state, GearState::Waiting);
        assert_eq!(g.at(fixed(6000)), 0);
        g.at(fixed(8000));
        assert_eq!(g.status().state, GearState::Syncing);
        assert_eq!(g.at(fixed(10_000)), 50_000);
        assert_eq!(g.status().state, GearState::InGear);
        assert_eq!(g.at(fixed(10_050)), 50_100);
        assert_eq!(
            g.gear_in_pos(&c, fixed(20_000), 1000.0),
            Err(CouplingError::SyncPassed)
        );
    }

    #[test]
    fn gear_out_brings_the_ratio_to_zero_and_holds() {
        let mut g = Gear::new();
        let ratio = Zoom::signed(1, 1).unwrap();
        g.gear_in(
            &GearIn {
                ratio,
                ramp: GearRamp::Immediate,
            },
            0,
            0.0,
        )
        .unwrap();
        assert_eq!(g.at(fixed(1000)), 1000);
        g.gear_out(
            &GearOut {
                ramp: GearRamp::Distance(NonZeroU64::new(1000).unwrap()),
            },
            fixed(1000),
            0.0,
        )
        .unwrap();
        assert_eq!(g.status().state, GearState::Leaving);
        assert_eq!(g.at(fixed(2000)), 1500);
        assert_eq!(g.at(fixed(9000)), 1500);
        assert_eq!(g.status().state, GearState::Off);
        assert_eq!(
            g.gear_in(
                &GearIn {
                    ratio,
                    ramp: GearRamp::Acceleration(f64::NAN)
                },
                0,
                1.0
            ),
            Err(CouplingError::BadLimit)
        );
    }
}
