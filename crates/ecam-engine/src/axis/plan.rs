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

use crate::blend::Blend;
use crate::coupling::{Engagement, Geometry};
use crate::steady::Steady;
use crate::switch::{Takeover, Trigger};
use crate::{Zoom, turn_position};

use super::CamAxis;
use super::landing::{Landing, Old, resolve_on};
use super::phase::{Engaged, Phase};

/// A prepared switch: for the switch waiting in `Engaged::pending` or
/// the table in `Engaged::queued`.
#[derive(Clone, Debug)]
pub(super) enum Plan {
    /// A position or at-once switch (or master-scaling change), by the
    /// master position it takes effect at.
    Switch {
        /// The old cam's constants it was prepared from.
        old: Steady,
        landings: [Option<(i64, Prepared)>; 2],
    },
    /// A table queued for the seam, crossing the end (`[0]`) or the start
    /// (`[1]`) of cycle `from_k`.
    Seam {
        old: Steady,
        from_k: i128,
        landings: [Option<Prepared>; 2],
    },
}

/// One prepared landing: where the cam stands after the switch.
#[derive(Clone, Debug)]
pub(super) struct Prepared {
    pub(super) engagement: Engagement,
    pub(super) geometry: Geometry,
    pub(super) cursor: ecam_core::Cursor,
    pub(super) master_zoom: Option<Zoom>,
    pub(super) blend: Option<Blend>,
    /// The new engagement's 64-bit constants (the lane follows it with them).
    pub(super) constants: Steady,
}

impl Prepared {
    /// A landing the lane can take: no error anywhere and constants in 64 bits.
    fn of(landing: Result<Landing, crate::EngineError>) -> Option<Self> {
        let landing = landing.ok()?;
        let constants = landing.engagement.steady(&landing.geometry)?;
        Some(Self {
            engagement: landing.engagement,
            geometry: landing.geometry,
            cursor: landing.cursor,
            master_zoom: landing.master_zoom,
            blend: landing.blend.ok()?,
            constants,
        })
    }
}

impl Plan {
    /// The landing prepared for a switch taking effect at master `at`
    /// from a cam with constants `old`.
    pub(super) fn switch_landing(&self, old: &Steady, at: i64) -> Option<(usize, &Prepared)> {
        match self {
            Self::Switch {
                old: from,
                landings,
            } if from.same(old) => landings
                .iter()
                .enumerate()
                .find_map(|(i, l)| l.as_ref().filter(|(a, _)| *a == at).map(|(_, p)| (i, p))),
            _ => None,
        }
    }

    /// The landing prepared for the seam of cycle `from_k` crossed
    /// `forward` (or backwards) from a cam with constants `old`.
    pub(super) fn seam_landing(
        &self,
        old: &Steady,
        from_k: i128,
        forward: bool,
    ) -> Option<(usize, &Prepared)> {
        match self {
            Self::Seam {
                old: from,
                from_k: k,
                landings,
            } if *k == from_k && from.same(old) => {
                let i = usize::from(!forward);
                landings.get(i)?.as_ref().map(|p| (i, p))
            }
            _ => None,
        }
    }

    /// Landing `i` of the plan.
    pub(super) fn landing(&self, i: usize) -> Option<&Prepared> {
        match self {
            Self::Switch { landings, .. } => landings.get(i)?.as_ref().map(|(_, p)| p),
            Self::Seam { landings, .. } => landings.get(i)?.as_ref(),
        }
    }
}

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
    /// (`Engaged::pending` or `Engaged::queued`); called by every request
    /// that sets one. Outside the cycle: this costs what the switch costs.
    pub(super) fn plan_waiting(&mut self) {
        let (Phase::Running(engaged) | Phase::Stopping(engaged, _)) = &mut self.phase else {
            return;
        };
        engaged.plan = None;
        let Some(old) = engaged.engagement.steady(&self.geometry) else {
            return;
        };
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
    if let Some(pending) = &engaged.pending {
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
    let (curve, then) = engaged.queued.as_ref()?;
    let from_k = engaged.place.k;
    let landings = [true, false].map(|forward| {
        let mut landing =
            from.switch_at_seam(cursor, curve, *then, engaged.seam_blend, from_k, forward);
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
