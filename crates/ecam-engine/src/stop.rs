//! Stops: immediate (document 002 abrupt stop, document 003 start register
//! = 0) and at the end of the current cycle, forwards or backwards
//! (document 002 smooth stop, document 003 function register 4 bit 1).

use crate::coupling::{Geometry, Place};

/// How to stop a running cam.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopKind {
    /// The commanded position stays where it is now (a velocity step).
    Immediate,
    /// Keep following until the master reaches the end of the current cycle
    /// in either direction, then hold the slave at that cycle end. Requested
    /// while the master is exactly on a cycle end, it stops there at once.
    EndOfCycle,
}

/// Where an end-of-cycle stop requested at a place ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum StopAt {
    /// The place is on an end of its cycle: stop there now, the slave
    /// holding what it was last commanded. `completes_cycle` when that is
    /// the forward end seen from inside the cycle, whose completion no
    /// seam crossing has reported yet.
    Here { completes_cycle: bool },
    /// Inside a cycle: follow until the master reaches either end.
    Ahead(CycleEnd),
}

/// The two ends of the cycle that was current when an end-of-cycle stop
/// was requested.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct CycleEnd {
    k: i128,
    forward: i128,
    backward: i128,
}

impl CycleEnd {
    /// Where a stop requested at `place` (the last place followed) ends.
    ///
    /// A place exactly on a cycle end (`r_num` 0 or the whole period) is
    /// already at the end a smooth stop waits for, whichever way the master
    /// came or goes next: stopping there at once keeps boundary stops
    /// symmetric and finite. Treating such a place as the start of the next
    /// cycle instead would run one more whole cycle forwards, and waiting
    /// for the master to pass the start backwards would never end while it
    /// stands still there.
    pub(crate) fn of(geo: &Geometry, place: Place) -> StopAt {
        if place == Geometry::cycle_start(place.k) {
            StopAt::Here {
                completes_cycle: false,
            }
        } else if place == geo.cycle_end(place.k) {
            StopAt::Here {
                completes_cycle: true,
            }
        } else {
            StopAt::Ahead(Self {
                k: place.k,
                forward: geo.boundary(place.k, true),
                backward: geo.boundary(place.k, false),
            })
        }
    }

    /// Where the cam stops if table input `t_num` reached or passed an end,
    /// and whether that end is the forward one (a completed cycle).
    ///
    /// Reaching an end counts in both directions, so a master that comes
    /// to rest exactly on the cycle start stops the cam just as one resting
    /// on the cycle end does.
    pub(crate) fn reached(&self, geo: &Geometry, t_num: i128) -> Option<(Place, bool)> {
        if t_num >= self.forward {
            Some((geo.cycle_end(self.k), true))
        } else if t_num <= self.backward {
            Some((Geometry::cycle_start(self.k), false))
        } else {
            None
        }
    }

    /// [`CycleEnd::reached`] for the place (`k`, `r_num`) of the table
    /// input, in 64 bits (the lane's): the same answer, the end as a place.
    #[inline]
    pub(crate) fn reached_place(
        &self,
        geo: &Geometry,
        k: i64,
        r_num: i64,
    ) -> Option<(Place, bool)> {
        // t ≥ the forward boundary: a later cycle; t ≤ the backward one:
        // an earlier cycle, or this one's start itself.
        let k = i128::from(k);
        if k > self.k {
            Some((geo.cycle_end(self.k), true))
        } else if k < self.k || r_num == 0 {
            Some((Geometry::cycle_start(self.k), false))
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use ecam_core::PointTable;

    use crate::{AxisConfig, AxisState, CamAxis, Coupling, StopKind, TickInput, TickOutput};

    /// Incremental line: slave = 2 × master everywhere, cycle ends at every
    /// multiple of 100 (document 002's three-value table).
    fn incremental() -> CamAxis<PointTable> {
        let table = PointTable::from_pairs(&[(0, 0), (50, 100), (100, 200)]).unwrap();
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            ..AxisConfig::default()
        };
        let mut a = CamAxis::new(table, config).unwrap();
        a.arm().unwrap();
        a
    }

    fn tick(a: &mut CamAxis<PointTable>, master: i64) -> TickOutput {
        a.tick(&TickInput::at(master, 100))
    }

    /// Moves the master from `from` to `to` one count per tick; gives the
    /// number of cycle-completed events seen.
    fn travel(a: &mut CamAxis<PointTable>, from: i64, to: i64) -> usize {
        let step = if to >= from { 1 } else { -1 };
        let mut m = from;
        let mut cycles = 0;
        while m != to {
            m += step;
            cycles += usize::from(tick(a, m).events.cycle_completed);
        }
        cycles
    }

    #[test]
    fn a_stop_on_the_table_start_going_backwards_finishes_at_once() {
        let mut a = incremental();
        tick(&mut a, 0);
        travel(&mut a, 0, 60);
        travel(&mut a, 60, 0);
        a.stop(StopKind::EndOfCycle);
        assert_eq!(a.state(), AxisState::Finished);
        assert!(!a.state().is_active());
        // The master stands still on the table start: the stop is reported
        // once, the slave holds, and nothing more happens.
        let out = tick(&mut a, 0);
        assert!(out.events.stopped);
        assert!(!out.events.cycle_completed);
        assert_eq!(out.slave, 0);
        assert!(!tick(&mut a, 0).events.stopped);
        assert_eq!(tick(&mut a, -50).slave, 0);
    }

    #[test]
    fn a_stop_on_the_table_end_going_forwards_runs_no_extra_table() {
        let mut a = incremental();
        tick(&mut a, 0);
        // Reaching the end of the first table completes one cycle.
        assert_eq!(travel(&mut a, 0, 100), 1);
        a.stop(StopKind::EndOfCycle);
        assert_eq!(a.state(), AxisState::Finished);
        let out = tick(&mut a, 101);
        assert!(out.events.stopped);
        // That completion was reported when the master reached the end; the
        // stop does not report it twice.
        assert!(!out.events.cycle_completed);
        assert_eq!(out.slave, 200);
        assert_eq!(tick(&mut a, 250).slave, 200);
    }

    #[test]
    fn a_stop_that_comes_to_rest_on_the_cycle_start_finishes() {
        let mut a = incremental();
        tick(&mut a, 0);
        travel(&mut a, 0, 160);
        a.stop(StopKind::EndOfCycle);
        assert_eq!(a.state(), AxisState::Stopping);
        travel(&mut a, 160, 101);
        assert_eq!(a.state(), AxisState::Stopping);
        // Master exactly on the start of cycle 100..200, and stays there.
        let out = tick(&mut a, 100);
        assert_eq!(out.state, AxisState::Finished);
        assert!(out.events.stopped && !out.events.cycle_completed);
        assert_eq!(out.slave, 200);
    }

    #[test]
    fn every_smooth_stop_ends_within_one_table_at_the_nearest_end_ahead() {
        for at in -130..=230 {
            for forward in [true, false] {
                let mut a = incremental();
                tick(&mut a, 0);
                travel(&mut a, 0, at);
                a.stop(StopKind::EndOfCycle);
                let end = if at.rem_euclid(100) == 0 {
                    at
                } else if forward {
                    at.div_euclid(100) * 100 + 100
                } else {
                    at.div_euclid(100) * 100
                };
                // One whole table of travel is always enough.
                travel(&mut a, at, if forward { at + 100 } else { at - 100 });
                assert_eq!(a.state(), AxisState::Finished, "at {at} forward {forward}");
                assert_eq!(a.commanded(), 2 * end, "at {at} forward {forward}");
            }
        }
    }

    #[test]
    fn a_normal_cam_stopped_past_its_end_completes_the_cycle() {
        let table = PointTable::from_pairs(&[(0, 0), (100, 300)]).unwrap();
        let config = AxisConfig {
            coupling: Coupling::Normal,
            ..AxisConfig::default()
        };
        let mut a = CamAxis::new(table, config).unwrap();
        a.arm().unwrap();
        tick(&mut a, 0);
        travel(&mut a, 0, 150);
        a.stop(StopKind::EndOfCycle);
        let out = tick(&mut a, 150);
        assert_eq!(out.state, AxisState::Finished);
        assert!(out.events.stopped && out.events.cycle_completed);
        assert_eq!(out.slave, 300);
    }

    #[test]
    fn a_stop_on_a_periodic_seam_holds_without_a_jump() {
        // Periodic: the slave returns from 200 to 0 at each seam.
        let table = PointTable::from_pairs(&[(0, 0), (100, 200)]).unwrap();
        let config = AxisConfig {
            coupling: Coupling::Periodic,
            ..AxisConfig::default()
        };
        let mut a = CamAxis::new(table, config).unwrap();
        a.arm().unwrap();
        tick(&mut a, 0);
        travel(&mut a, 0, 100);
        let held = a.commanded();
        a.stop(StopKind::EndOfCycle);
        assert_eq!(tick(&mut a, 130).slave, held);
    }
}
