//! The steady tick between whole master counts: a settled cam whose
//! master reading carries a fraction (an exact time base, or a coarse
//! master's estimate). The general tick's rule is kept exactly: the
//! command at the whole count, moved along the straight line to the next
//! count's command by the fraction. Here both commands come from the
//! steady tick's 64-bit constants, so such a tick costs two steady
//! samples instead of the general tick's two 128-bit ones and the
//! constants taken again (docs/engine.md, "Benchmarks"). Across a seam the
//! general tick aims at the seam itself, which is a place, not a master
//! count: that tick is left to it. The steady-vs-general property test
//! compares the two.

use ecam_core::{CamCurve, Cursor};

use crate::Events;

use super::phase::Engaged;
use super::{FollowSample, step_to};

impl<C: CamCurve> Engaged<C> {
    /// One tick of a settled cam at whole count `master` plus `fraction`
    /// (of 2³²), with the steady tick's constants taken; `None` (nothing
    /// changed) leaves the tick to the general path: no constants, the
    /// next count across a seam, or a value that leaves 64 bits.
    #[inline(never)]
    pub(super) fn between_counts_tick(
        &mut self,
        master: i64,
        fraction: u32,
        curve: &C,
        cursor: &mut Cursor,
        jumps_at_seam: bool,
        events: &mut Events,
    ) -> Option<FollowSample> {
        let constants = self.underway.steady()?;
        let cam = constants.sample(master, curve, cursor)?;
        let next = constants.sample(master.saturating_add(1), curve, cursor)?;
        if next.k != cam.k {
            return None;
        }
        let gap = i128::from(next.slave) - i128::from(cam.slave);
        let step = (gap * i128::from(fraction) + (1 << 31)) >> 32;
        let slave = i64::try_from(i128::from(cam.slave) + step).ok()?;
        let sample = FollowSample::of_steady(&cam, constants, slave, cam.velocity_ratio, true);
        let followed = (i128::from(master) << 32) | i128::from(fraction);
        step_to(
            &mut self.place,
            &mut self.followed,
            &cam,
            followed,
            jumps_at_seam,
            events,
        );
        Some(sample)
    }
}
