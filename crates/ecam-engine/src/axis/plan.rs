//! Switches prepared when they are asked for, outside the control cycle.
//!
//! A table switch at a master position or at once, a master-scaling
//! change and a table queued for the seam land where `landing.rs` says:
//! the new geometry (a new table's is checked and derived), the new
//! engagement anchored on the old cam, the blend's two ends on the new
//! cam. All of it depends only on the old cam's constants, on the new
//! table or scaling and on where the switch takes effect. So the request
//! works it out for the places where the switch can take effect next
//! (one or two master positions, or the seams either side of the cycle
//! the master is in) and the tick that carries the switch out only puts
//! the prepared landing in place (the fast lane, `lane.rs`).
//!
//! A prepared landing is used only when the switch takes effect where
//! it was prepared for and the old cam's constants are still the ones it
//! was prepared from (they change with a blend that ends in between, for
//! instance); otherwise the general tick works the switch out itself, as
//! it always did. The steady-vs-general property test drives both.

use ecam_core::CamCurve;

use crate::coupling::Geometry;
use crate::steady::Steady;
use crate::switch::{Takeover, Trigger};
use crate::turn_position;

use super::CamAxis;
use super::landing::{Old, resolve_on};
use super::lane_constants::LaneConstants;
use super::phase::{Engaged, Phase};
use super::prepared::{Plan, Prepared};

/// The whole master counts a switch waiting for `trigger` can take effect
/// at next, from the master followed last (`followed`, counts × 2^32
/// plus the fraction): the first one reached going forwards and going
/// backwards (`Trigger::fires`).
fn candidates(
    followed: i128,
    trigger: Trigger,
    turn: Option<core::num::NonZeroU64>,
) -> [Option<i64>; 2] {
    let down = i64::try_from(followed >> 32).ok();
    let up = i64::try_from((followed + ((1 << 32) - 1)) >> 32).ok();
    let [forward, backward] = match trigger {
        Trigger::Now => [up, down],
        Trigger::Position(p) => [
            up.map(|from| turn_position::nearest(p, turn, from, true)),
            down.map(|from| turn_position::nearest(p, turn, from, false)),
        ],
    };
    [forward, backward.filter(|b| Some(*b) != forward)]
}

impl<C: CamCurve> CamAxis<C> {
    /// Prepares the switch or seam table now waiting in the running cam
    /// (`Engaged::underway`); called by every request
    /// that sets one. Outside the cycle: this costs what the switch costs.
    pub(super) fn plan_waiting(&mut self) {
        let (Phase::Running(engaged) | Phase::Stopping(engaged, _)) = &mut self.phase else {
            return;
        };
        engaged.plan = None;
        let Some(old) = engaged.engagement.steady(&self.geometry) else {
            return;
        };
        // The lane follows the old cam until the switch with the same
        // constants, taken here if missing rather than in the cycle.
        if engaged.lane.is_none() {
            engaged.lane = Some(LaneConstants {
                cam: old,
                target: None,
            });
        }
        let from = Old {
            curve: &self.curve,
            geometry: &self.geometry,
            config: &self.config,
            engagement: &engaged.engagement,
        };
        engaged.plan = plan(&from, self.cursor, engaged, old);
    }
}

/// The plan for what waits in `engaged`, from the cam `from` with
/// constants `old`.
fn plan<C: CamCurve>(
    from: &Old<'_, C>,
    cursor: ecam_core::Cursor,
    engaged: &Engaged<C>,
    old: Steady,
) -> Option<Plan> {
    let change = engaged.underway.change()?;
    if let Some(pending) = change.pending() {
        let landings = candidates(engaged.followed, pending.trigger(), from.config.single_turn)
            .map(|at| {
                let at = at?;
                let mut landing = from.switch_at(cursor, &pending.takeover, pending.blend, at);
                if let Ok(landing) = &mut landing {
                    // The cursor where the new cam starts (the blend's ends
                    // left it elsewhere): the switch tick's lookup is a hit.
                    let curve = match &pending.takeover {
                        Takeover::Table(curve) => curve,
                        Takeover::MasterScaling(_) => from.curve,
                    };
                    let place = resolve_on(&landing.geometry, &landing.engagement, at);
                    curve.eval(landing.geometry.table_x(place), &mut landing.cursor);
                }
                Some((at, Prepared::of(landing)?))
            });
        return Some(Plan::Switch { old, landings });
    }
    let queued = change.queued()?;
    let (curve, then) = (&queued.curve, &queued.then);
    let from_k = engaged.place.k;
    let landings = [true, false].map(|forward| {
        let mut landing = from.switch_at_seam(cursor, curve, *then, queued.blend, from_k, forward);
        if let Ok(landing) = &mut landing {
            // The cursor where the new table's cycle starts, seen from the
            // side the master comes from.
            let place = if forward {
                Geometry::cycle_start(0)
            } else {
                landing.geometry.cycle_end(-1)
            };
            curve.eval(landing.geometry.table_x(place), &mut landing.cursor);
        }
        Prepared::of(landing)
    });
    Some(Plan::Seam {
        old,
        from_k,
        landings,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const ONE: i128 = 1 << 32;

    #[test]
    fn the_candidates_are_where_the_trigger_fires_either_way() {
        assert_eq!(candidates(7 * ONE, Trigger::Now, None), [Some(7), None]);
        assert_eq!(
            candidates(7 * ONE + 5, Trigger::Now, None),
            [Some(8), Some(7)]
        );
        assert_eq!(
            candidates(7 * ONE, Trigger::Position(100), None),
            [Some(100), None]
        );
        // On a 1000-count turn: the equivalents either side.
        let turn = core::num::NonZeroU64::new(1000);
        assert_eq!(
            candidates(1500 * ONE, Trigger::Position(100), turn),
            [Some(2100), Some(1100)]
        );
    }
}
