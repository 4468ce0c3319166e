//! When a new table takes over a running cam ([`crate::CamAxis::switch_curve`]).
//!
//! PLCopen `MC_CamIn` knows two ways for a second cam to follow a running
//! one: `BufferMode` buffered (at the end of the running cam's cycle: the
//! next seam here) and aborting (at once); implementations add a start at
//! a master position. The position and at-once switches anchor the new
//! cam on the old one where they take effect and may blend between them
//! (see the `blend` module).

use core::num::NonZeroU64;

use crate::Zoom;

/// What happens when the master passes an activation position (a start
/// at a master position, a table switch at a master position) backwards,
/// e.g. when it reverses: the axis reports it either way
/// (`Events::activation_missed`, `TickOutput::activation_missed`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MissedActivation {
    /// Take effect there all the same (the behaviour without a policy).
    #[default]
    StartNow,
    /// Keep waiting for the next forward pass.
    NextPass,
}

/// Where a table handed to a running cam takes over.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SwitchAt {
    /// At the next seam the master crosses (PLCopen `BufferMode`
    /// buffered): the new table's cycle starts there. Without a blend the
    /// same as [`crate::CamAxis::queue_curve`].
    NextSeam {
        /// Master travel over which to blend from the old cam's velocity
        /// to the new one's, from the last whole master count before the
        /// seam; `None`: no blend (velocity continuous where the tables'
        /// slopes agree at the seam).
        blend: Option<NonZeroU64>,
    },
    /// When the master (unwrapped, before zoom) reaches or crosses
    /// `position`, in either direction, the new cam takes over exactly
    /// there, whichever tick passes it.
    MasterPosition {
        /// Master position in counts.
        position: i64,
        /// Master travel over which to blend onto the new cam; `None`
        /// switches without a blend (no position step, but a velocity step
        /// where the cams' velocities differ there).
        blend: Option<NonZeroU64>,
    },
    /// At once (PLCopen `BufferMode` aborting): at the master the axis
    /// followed last (where it stands when this is called), or, while that
    /// lies between two counts, at the next whole count the master reaches;
    /// the next tick carries it out.
    Now {
        /// As for [`SwitchAt::MasterPosition`].
        blend: Option<NonZeroU64>,
    },
}

/// What makes a waiting position or at-once switch fire.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Trigger {
    Position(i64),
    Now,
}

/// What takes over when a waiting switch fires.
#[derive(Clone, Debug)]
pub(crate) enum Takeover<C> {
    /// A new table.
    Table(C),
    /// The same table under a new master zoom
    /// ([`crate::CamAxis::change_master_scaling`]).
    MasterScaling(Zoom),
}

/// What a waiting switch did in one tick.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Fired {
    /// It takes effect at this master position.
    pub(crate) at: Option<i64>,
    /// Its position was passed backwards.
    pub(crate) missed: bool,
}

/// A table (or master scaling) waiting for its position or the next tick.
#[derive(Clone, Debug)]
pub(crate) struct Pending<C> {
    pub(crate) takeover: Takeover<C>,
    trigger: Trigger,
    pub(crate) blend: Option<NonZeroU64>,
}

impl<C> Pending<C> {
    /// A table waiting for `trigger`.
    pub(crate) fn new(takeover: Takeover<C>, trigger: Trigger, blend: Option<NonZeroU64>) -> Self {
        Self {
            takeover,
            trigger,
            blend,
        }
    }

    /// The master position where the switch takes effect, if it does in
    /// the tick from `previous` to `now` (see [`Trigger::fires`]); a due
    /// switch that waits for a blend's end becomes an at-once switch.
    pub(crate) fn fires(
        &mut self,
        previous: i128,
        now: i128,
        blending: bool,
        policy: MissedActivation,
        turn: Option<NonZeroU64>,
    ) -> Fired {
        let (fired, trigger) = self.trigger.fires(previous, now, blending, policy, turn);
        self.trigger = trigger;
        fired
    }

    /// What makes it fire.
    pub(crate) fn trigger(&self) -> Trigger {
        self.trigger
    }

    /// Replaces what makes it fire (the trigger [`Trigger::fires`] gave).
    pub(crate) fn set_trigger(&mut self, trigger: Trigger) {
        self.trigger = trigger;
    }
}

impl Trigger {
    /// The master position where a switch waiting for this trigger takes
    /// effect, if it does in the tick from `previous` to `now` (fixed
    /// point: counts × 2^32 plus the fraction), and the trigger it waits
    /// for afterwards. A switch always takes effect at a whole count that
    /// lies between the two, so the old cam is followed up to it and the
    /// new one from it, also while the master stands between two counts
    /// (an at-once switch then waits for the next whole count). While
    /// `blending`, a due switch waits for the blend to end and then takes
    /// effect as an at-once switch. Changes nothing itself, so a caller
    /// can look before it commits.
    #[inline]
    pub(crate) fn fires(
        self,
        previous: i128,
        now: i128,
        blending: bool,
        policy: MissedActivation,
        turn: Option<NonZeroU64>,
    ) -> (Fired, Self) {
        let (low, high) = (previous.min(now), previous.max(now));
        let mut missed = false;
        let at = match self {
            Self::Position(p) => {
                // On a single-turn master, the turn's place of `p` at or
                // beyond the whole count at `previous` in the direction of
                // travel (worked out only there: a linear master's `p` is
                // the position itself).
                let p = match turn {
                    None => p,
                    Some(_) => {
                        let forward = now >= previous;
                        let from = if forward {
                            (previous + ((1 << 32) - 1)) >> 32
                        } else {
                            previous >> 32
                        };
                        let from = i64::try_from(from).unwrap_or(if from < 0 {
                            i64::MIN
                        } else {
                            i64::MAX
                        });
                        crate::turn_position::nearest(p, turn, from, forward)
                    }
                };
                let fixed = i128::from(p) << 32;
                let passed = low <= fixed && fixed <= high;
                missed = passed && now < previous;
                (passed && (!missed || policy == MissedActivation::StartNow)).then_some(p)
            }
            Self::Now => {
                // The first whole count the master reaches from `previous`.
                let first = if now >= previous {
                    (previous + ((1 << 32) - 1)) >> 32
                } else {
                    previous >> 32
                };
                let fixed = first << 32;
                if low <= fixed && fixed <= high {
                    i64::try_from(first).ok()
                } else {
                    None
                }
            }
        };
        if at.is_some() && blending {
            return (Fired { at: None, missed }, Self::Now);
        }
        (Fired { at, missed }, self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ONE: i128 = 1 << 32;

    #[test]
    fn a_position_fires_where_it_is_crossed_either_way() {
        let mut p = Pending::new(Takeover::Table(()), Trigger::Position(100), None);
        assert_eq!(
            p.fires(0, 99 * ONE, false, MissedActivation::StartNow, None)
                .at,
            None
        );
        assert_eq!(
            p.fires(99 * ONE, 150 * ONE, false, MissedActivation::StartNow, None)
                .at,
            Some(100)
        );
        let mut p = Pending::new(Takeover::Table(()), Trigger::Position(100), None);
        // Backwards, between 101 and 100: not yet.
        assert_eq!(
            p.fires(
                101 * ONE,
                100 * ONE + 5,
                false,
                MissedActivation::StartNow,
                None
            )
            .at,
            None
        );
        assert_eq!(
            p.fires(
                100 * ONE + 5,
                100 * ONE,
                false,
                MissedActivation::StartNow,
                None
            )
            .at,
            Some(100)
        );
    }

    #[test]
    fn at_once_takes_the_first_whole_count_reached() {
        let mut p = Pending::new(Takeover::Table(()), Trigger::Now, None);
        assert_eq!(
            p.fires(7 * ONE, 9 * ONE, false, MissedActivation::StartNow, None)
                .at,
            Some(7)
        );
        let mut p = Pending::new(Takeover::Table(()), Trigger::Now, None);
        assert_eq!(
            p.fires(
                7 * ONE + 3,
                7 * ONE + 9,
                false,
                MissedActivation::StartNow,
                None
            )
            .at,
            None
        );
        assert_eq!(
            p.fires(
                7 * ONE + 9,
                8 * ONE + 1,
                false,
                MissedActivation::StartNow,
                None
            )
            .at,
            Some(8)
        );
        let mut p = Pending::new(Takeover::Table(()), Trigger::Now, None);
        assert_eq!(
            p.fires(
                -7 * ONE + 3,
                -8 * ONE,
                false,
                MissedActivation::StartNow,
                None
            )
            .at,
            Some(-7)
        );
    }

    #[test]
    fn a_backward_pass_is_reported_and_follows_the_policy() {
        let mut p = Pending::new(Takeover::Table(()), Trigger::Position(100), None);
        let fired = p.fires(120 * ONE, 90 * ONE, false, MissedActivation::NextPass, None);
        assert_eq!(
            fired,
            Fired {
                at: None,
                missed: true
            }
        );
        let fired = p.fires(90 * ONE, 130 * ONE, false, MissedActivation::NextPass, None);
        assert_eq!(
            fired,
            Fired {
                at: Some(100),
                missed: false
            }
        );
        let mut p = Pending::new(Takeover::Table(()), Trigger::Position(100), None);
        let fired = p.fires(120 * ONE, 90 * ONE, false, MissedActivation::StartNow, None);
        assert_eq!(
            fired,
            Fired {
                at: Some(100),
                missed: true
            }
        );
    }

    #[test]
    fn a_switch_due_during_a_blend_waits_for_its_end() {
        let mut p = Pending::new(Takeover::Table(()), Trigger::Position(100), None);
        assert_eq!(
            p.fires(90 * ONE, 110 * ONE, true, MissedActivation::StartNow, None)
                .at,
            None
        );
        assert_eq!(
            p.fires(110 * ONE, 120 * ONE, true, MissedActivation::StartNow, None)
                .at,
            None
        );
        assert_eq!(
            p.fires(
                120 * ONE,
                130 * ONE,
                false,
                MissedActivation::StartNow,
                None
            )
            .at,
            Some(120)
        );
    }
}
