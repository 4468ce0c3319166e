//! Carrying out a table switch or master-scaling change inside the
//! general tick: at the seam, at a master position or at once, with the
//! blend from the old cam onto the new one (where it lands:
//! `landing.rs`); and what a run that ends leaves behind.

use ecam_core::{CamCurve, Cursor};

use crate::coupling::{Engagement, Geometry, Place};
use crate::steady::Steady;
use crate::switch::Takeover;
use crate::{AxisConfig, EngineError};

use super::landing::{Landing, Old};
use super::phase::Engaged;
use super::prepared::{Plan, Prepared};
use super::underway::{Change, Next, Underway};
use super::{CamAxis, Coupled};

impl<C: CamCurve> CamAxis<C> {
    /// Ends a run: a table still queued is the one to restart with.
    pub(super) fn end_run(&mut self, engaged: Engaged<C>) {
        let (scaling, waiting) = match engaged.underway {
            Underway::RampIn(_, Some(change)) | Underway::Changing(change) => {
                change.into_leftovers()
            }
            Underway::RampIn(_, None) | Underway::Settled | Underway::Steady(_) => (None, None),
        };
        // The configuration already names the new scaling.
        if let Some(ramp) = scaling {
            self.geometry = ramp.target;
        }
        let next = match waiting.map(Next::into_takeover) {
            Some(Takeover::Table(curve)) => Some(curve),
            Some(Takeover::MasterScaling(zoom)) => {
                let config = AxisConfig {
                    master_zoom: zoom,
                    ..self.config
                };
                if let Ok(geometry) = Geometry::new(&self.curve, &config) {
                    self.config = config;
                    self.geometry = geometry;
                }
                None
            }
            None => None,
        };
        if let Some(curve) = next {
            match Geometry::new(&curve, &self.config) {
                Ok(geometry) => {
                    self.geometry = geometry;
                    self.cursor = Cursor::new();
                    self.retired = Some(core::mem::replace(&mut self.curve, curve));
                }
                // A table that no longer fits the configuration is handed
                // back as retired rather than freed in the tick.
                Err(_) => self.retired = Some(curve),
            }
        }
    }
}

impl<C: CamCurve> Coupled<'_, C> {
    /// The running cam as a switch leaves it.
    fn old<'a>(&'a self, engagement: &'a Engagement) -> Old<'a, C> {
        Old {
            curve: &*self.curve,
            geometry: &*self.geometry,
            config: &*self.config,
            engagement,
        }
    }

    /// The landing prepared for this switch where the general tick
    /// carries it out (`find` picks it from the plan), when the old cam's
    /// constants are the ones it was prepared from: what
    /// `landing.rs` would work out there, taken as the lane takes it
    /// (`plan.rs`). `None` leaves it to `landing.rs`: no plan, none for
    /// here, or the reference route (`prepared` off).
    fn prepared_landing(
        &self,
        engaged: &Engaged<C>,
        find: impl for<'p> FnOnce(&'p Plan, &Steady) -> Option<(usize, &'p Prepared)>,
    ) -> Option<Landing> {
        if !self.prepared {
            return None;
        }
        let plan = engaged.plan.as_ref()?;
        let old = engaged.engagement.steady(self.geometry)?;
        let (_, prepared) = find(plan, &old)?;
        Some(Landing {
            engagement: prepared.engagement,
            geometry: prepared.geometry,
            cursor: prepared.cursor,
            master_zoom: prepared.master_zoom,
            blend: Ok(prepared.blend),
        })
    }

    /// Carries out a waiting position or at-once switch at master `at`
    /// (`landing.rs` says where it lands); the switch keeps waiting if its
    /// landing fails.
    pub(super) fn switch_at(
        &mut self,
        engaged: &mut Engaged<C>,
        at: i64,
    ) -> Result<(), EngineError> {
        let Some(Change::Waiting(Next::Switch(pending))) = engaged.underway.change() else {
            return Ok(());
        };
        let prepared = self.prepared_landing(engaged, |plan, old| plan.switch_landing(old, at));
        let landing = match prepared {
            Some(landing) => landing,
            None => self.old(&engaged.engagement).switch_at(
                *self.cursor,
                &pending.takeover,
                pending.blend,
                at,
            )?,
        };
        engaged.plan = None;
        let takeover = engaged.underway.take_switch().map(|p| p.takeover);
        self.land(engaged, landing, takeover)
    }

    /// Takes a queued table over at the seam between the last place and
    /// `to`, if one waits (`landing.rs` says where it lands); gives
    /// whether it did.
    pub(super) fn switch_at_seam(
        &mut self,
        engaged: &mut Engaged<C>,
        to: Place,
    ) -> Result<bool, EngineError> {
        let from = engaged.place;
        // Only a table waiting alone is taken: beside a ramp or a blend it
        // waits for the next seam after their end.
        if from.k == to.k {
            return Ok(false);
        }
        let Some(Change::Waiting(Next::Seam(queued))) = engaged.underway.change() else {
            return Ok(false);
        };
        let forward = to.k > from.k;
        let prepared =
            self.prepared_landing(engaged, |plan, old| plan.seam_landing(old, from.k, forward));
        let landing = match prepared {
            Some(landing) => landing,
            None => self.old(&engaged.engagement).switch_at_seam(
                *self.cursor,
                &queued.curve,
                queued.then,
                queued.blend,
                from.k,
                forward,
            )?,
        };
        engaged.plan = None;
        let takeover = engaged
            .underway
            .take_seam_table()
            .map(|queued| Takeover::Table(queued.curve));
        self.land(engaged, landing, takeover)?;
        Ok(true)
    }

    /// What the tick at whole count `next` commands when it takes the
    /// table queued for the seam of cycle `from_k` with a blend (its end
    /// when `forward`, its start when a negative master zoom runs the
    /// cycles backwards): the blend's command there (a ramp-in on top).
    /// `None` when no table waits with a blend, or when the landing fails
    /// (the tick that lands reports it).
    ///
    /// The ticks between the last whole count before such a seam and the
    /// next one move towards this value: the blend starts at that last
    /// count, on the old cam there, so it does not pass through the seam's
    /// own value. Aimed at the seam instead, the slave could go past where
    /// the blend then starts from and step back (a coarse master's estimate
    /// crossing the seam between whole counts).
    pub(super) fn seam_blend_aim(
        &self,
        engaged: &Engaged<C>,
        from_k: i128,
        forward: bool,
        next: i64,
    ) -> Option<i64> {
        let Some(Change::Waiting(Next::Seam(queued))) = engaged.underway.change() else {
            return None;
        };
        queued.blend?;
        let landing = self
            .old(&engaged.engagement)
            .switch_at_seam(
                *self.cursor,
                &queued.curve,
                queued.then,
                queued.blend,
                from_k,
                forward,
            )
            .ok()?;
        let blended = landing.blend.ok()??.command(next).ok()?.slave;
        Some(
            engaged
                .ramp_in()
                .and_then(|ramp| ramp.blend(next, blended))
                .unwrap_or(blended),
        )
    }

    /// Puts a landing in place: the new engagement, geometry and table
    /// (the old one retired) or scaling, then its blend (whose error, if
    /// any, is reported with the rest in place).
    fn land(
        &mut self,
        engaged: &mut Engaged<C>,
        landing: Landing,
        takeover: Option<Takeover<C>>,
    ) -> Result<(), EngineError> {
        engaged.engagement = landing.engagement;
        *self.geometry = landing.geometry;
        *self.cursor = landing.cursor;
        match takeover {
            Some(Takeover::Table(curve)) => {
                *self.retired = Some(core::mem::replace(self.curve, curve));
            }
            Some(Takeover::MasterScaling(_)) | None => {}
        }
        if let Some(zoom) = landing.master_zoom {
            self.config.master_zoom = zoom;
        }
        // The switch taken, nothing changes beside the ramp-in: the blend
        // (if any) begins.
        if let Some(blend) = landing.blend? {
            engaged.underway.begin(Change::Blend(blend, None))?;
        }
        Ok(())
    }
}
