//! Cam switches (PLCopen `MC_DigitalCamSwitch`): up to 32 output tracks,
//! each on while a position lies on one of its cams, beside the four sync
//! windows of document 003.
//!
//! A cam ([`CamSwitch`]) is on from `first_on` to `last_on` (position
//! mode) or for a time after the position passes `first_on` (time mode),
//! in both directions of motion or only one. Per track ([`TrackOptions`]):
//! - on and off compensation times, as Beckhoff's `TRACK_REF` reads them:
//!   positive delays the edge, negative brings it forward (to make up for
//!   a valve's or a glue gun's dead time). At velocity `v` an edge at
//!   position `p` moves to `p + v × time`; moving backwards the on edge is
//!   `last_on` and the off edge `first_on`;
//! - a hysteresis: once a track has switched at a position, it switches
//!   again only after the position has moved at least that far from
//!   there, so an axis standing on an edge with a jittering encoder does
//!   not chatter.
//!
//! With a modulo the positions are places in the cycle (`0..modulo`) and a
//! cam with `first_on > last_on` wraps over the cycle's end; without one a
//! cam with `first_on > last_on` is inverted (on outside the range). The
//! outputs change once per tick: the tick is their time resolution. The
//! switches are handed in at every call (no allocation, bounded work:
//! one pass over them).

use core::num::NonZeroU64;

use crate::CouplingError;

/// Number of tracks.
pub const TRACKS: usize = 32;

/// Which motion a cam switches in (PLCopen `AxisDirection`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SwitchDirection {
    /// Both directions.
    #[default]
    Both,
    /// Only while the position moves forwards (standing: as it last moved).
    Positive,
    /// Only while it moves backwards.
    Negative,
}

/// How long a cam is on (PLCopen `CamSwitchMode`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SwitchMode {
    /// From `first_on` to this position.
    Position {
        /// `LastOnPosition`.
        last_on: i64,
    },
    /// For this many µs after the position passes `first_on` (`Duration`).
    Time {
        /// How long the output stays on.
        duration_us: u64,
    },
}

/// One cam of a track (PLCopen `MC_CAMSWITCH_REF` entry).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CamSwitch {
    /// `TrackNumber`, 0–31.
    pub track: u8,
    /// `FirstOnPosition`.
    pub first_on: i64,
    /// Position or time.
    pub mode: SwitchMode,
    /// `AxisDirection`.
    pub direction: SwitchDirection,
}

/// Options of one track (PLCopen `MC_TRACK_REF` entry).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TrackOptions {
    /// `OnCompensation`, µs: positive delays the on edge, negative brings it forward.
    pub on_compensation_us: i32,
    /// `OffCompensation`, µs: the same for the off edge.
    pub off_compensation_us: i32,
    /// `Hysteresis`: position units between two switchings of the track.
    pub hysteresis: u64,
}

/// `v` as a place in the cycle, or as it is without a modulo.
fn wrap(modulo: Option<NonZeroU64>, v: i64) -> i64 {
    match modulo {
        Some(m) => i128::from(v).rem_euclid(i128::from(m.get())) as i64,
        None => v,
    }
}

/// `p` lies on `[first, last]` (wrapping or inverted when first > last).
fn covers(modulo: Option<NonZeroU64>, first: i64, last: i64, p: i64) -> bool {
    match modulo {
        Some(m) => {
            let m = i128::from(m.get());
            let span = (i128::from(last) - i128::from(first)).rem_euclid(m);
            (i128::from(p) - i128::from(first)).rem_euclid(m) <= span
        }
        None if first <= last => first <= p && p <= last,
        None => p >= first || p <= last,
    }
}

/// The motion from `from` to `to` passes `edge` (reaching it counts).
fn passes(modulo: Option<NonZeroU64>, from: i64, to: i64, edge: i64) -> bool {
    let travel = i128::from(to) - i128::from(from);
    if travel == 0 {
        return false;
    }
    match modulo {
        Some(m) => {
            let m = i128::from(m.get());
            let ahead = if travel > 0 {
                (i128::from(edge) - i128::from(from)).rem_euclid(m)
            } else {
                (i128::from(from) - i128::from(edge)).rem_euclid(m)
            };
            ahead != 0 && ahead <= travel.abs()
        }
        None if travel > 0 => from < edge && edge <= to,
        None => to <= edge && edge < from,
    }
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Track {
    on: bool,
    timer_us: u64,
    switched_at: Option<i64>,
}

/// The state of a cam-switch group.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DigitalCamSwitch {
    modulo: Option<NonZeroU64>,
    options: [TrackOptions; TRACKS],
    tracks: [Track; TRACKS],
    last: Option<i64>,
    forward: bool,
    toggles: u64,
}

impl DigitalCamSwitch {
    /// A group comparing positions modulo `modulo` (a rotary axis), or as
    /// they are (`None`), with `options` per track.
    pub const fn new(modulo: Option<NonZeroU64>, options: [TrackOptions; TRACKS]) -> Self {
        Self {
            modulo,
            options,
            tracks: [Track {
                on: false,
                timer_us: 0,
                switched_at: None,
            }; TRACKS],
            last: None,
            forward: true,
            toggles: 0,
        }
    }

    /// Checks a set of cams.
    ///
    /// # Errors
    /// [`CouplingError::BadTrack`] for a track number of 32 or more.
    pub fn check(switches: &[CamSwitch]) -> Result<(), CouplingError> {
        if switches.iter().any(|s| usize::from(s.track) >= TRACKS) {
            return Err(CouplingError::BadTrack);
        }
        Ok(())
    }

    /// How many times any track has switched (on or off) so far.
    pub const fn toggles(&self) -> u64 {
        self.toggles
    }

    /// One tick with the axis at `position`, `dt_us` after the last:
    /// the tracks' outputs, bit `i` for track `i`, masked by `enable`
    /// (PLCopen `EnableMask`).
    pub fn tick(&mut self, switches: &[CamSwitch], position: i64, dt_us: u32, enable: u32) -> u32 {
        let last = self.last.unwrap_or(position);
        self.last = Some(position);
        let travel = i128::from(position) - i128::from(last);
        if travel != 0 {
            self.forward = travel > 0;
        }
        let velocity = if dt_us == 0 {
            0.0
        } else {
            travel as f64 * 1e6 / f64::from(dt_us)
        };
        let mut wanted = [false; TRACKS];
        let modulo = self.modulo;
        for s in switches {
            let t = usize::from(s.track);
            let (Some(want), Some(options), Some(track)) = (
                wanted.get_mut(t),
                self.options.get(t),
                self.tracks.get_mut(t),
            ) else {
                continue;
            };
            let active = match s.direction {
                SwitchDirection::Both => true,
                SwitchDirection::Positive => self.forward,
                SwitchDirection::Negative => !self.forward,
            };
            if !active {
                continue;
            }
            let shift = |us: i32| {
                let d = libm::round(velocity * f64::from(us) * 1e-6);
                if d.is_finite() { d as i64 } else { 0 }
            };
            let (on, off) = (
                shift(options.on_compensation_us),
                shift(options.off_compensation_us),
            );
            match s.mode {
                SwitchMode::Position { last_on } => {
                    let (first, last) = if self.forward {
                        (s.first_on.saturating_add(on), last_on.saturating_add(off))
                    } else {
                        (s.first_on.saturating_add(off), last_on.saturating_add(on))
                    };
                    let (first, last) = (wrap(modulo, first), wrap(modulo, last));
                    *want |= covers(modulo, first, last, wrap(modulo, position));
                }
                SwitchMode::Time { duration_us } => {
                    let edge = s.first_on.saturating_add(on);
                    if passes(modulo, last, position, edge) {
                        track.timer_us = duration_us;
                    }
                }
            }
        }
        let mut out = 0u32;
        for (i, (track, want)) in self.tracks.iter_mut().zip(wanted).enumerate() {
            let want = want || track.timer_us > 0;
            track.timer_us = track.timer_us.saturating_sub(u64::from(dt_us));
            let hysteresis = self.options.get(i).map_or(0, |o| o.hysteresis);
            let free = track.switched_at.is_none_or(|at| {
                (i128::from(position) - i128::from(at)).unsigned_abs() >= u128::from(hysteresis)
            });
            if want != track.on && free {
                track.on = want;
                track.switched_at = Some(position);
                self.toggles += 1;
            }
            if track.on {
                out |= 1 << i;
            }
        }
        out & enable
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam(track: u8, first_on: i64, last_on: i64) -> CamSwitch {
        CamSwitch {
            track,
            first_on,
            mode: SwitchMode::Position { last_on },
            direction: SwitchDirection::Both,
        }
    }

    #[test]
    fn position_cams_with_compensation_and_wrap() {
        let mut options = [TrackOptions::default(); TRACKS];
        // Track 1 switches on 10 ms early.
        options[1].on_compensation_us = -10_000;
        let mut g = DigitalCamSwitch::new(NonZeroU64::new(3600), options);
        let cams = [cam(0, 100, 200), cam(1, 1000, 1100), cam(2, 3500, 50)];
        // 1000 units/s in 1 ms ticks.
        let mut on_at = [None; 3];
        for p in 0..4000i64 {
            let out = g.tick(&cams, p, 1000, u32::MAX);
            for (t, at) in on_at.iter_mut().enumerate() {
                if out & (1 << t) != 0 && at.is_none() {
                    *at = Some(p);
                }
            }
        }
        assert_eq!(on_at, [Some(100), Some(990), Some(0)]);
        assert!(DigitalCamSwitch::check(&[cam(32, 0, 1)]).is_err());
    }

    #[test]
    fn hysteresis_keeps_a_jittering_edge_quiet() {
        let mut options = [TrackOptions::default(); TRACKS];
        options[0].hysteresis = 3;
        let mut g = DigitalCamSwitch::new(None, options);
        let cams = [cam(0, 100, 200)];
        let mut outs = std::vec::Vec::new();
        for p in [98, 99, 100, 99, 100, 99, 101, 103, 96, 95] {
            outs.push(g.tick(&cams, p, 1000, 1));
        }
        assert_eq!(outs, [0, 0, 1, 1, 1, 1, 1, 1, 0, 0]);
    }

    #[test]
    fn time_cams_stay_on_for_their_duration() {
        let mut g = DigitalCamSwitch::new(None, [TrackOptions::default(); TRACKS]);
        let cams = [CamSwitch {
            track: 3,
            first_on: 50,
            mode: SwitchMode::Time { duration_us: 5000 },
            direction: SwitchDirection::Positive,
        }];
        let on: std::vec::Vec<bool> = (40..70)
            .map(|p| g.tick(&cams, p, 1000, u32::MAX) & 8 != 0)
            .collect();
        assert_eq!(on.iter().filter(|&&b| b).count(), 5);
        assert!(on[10]);
    }
}
