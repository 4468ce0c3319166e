//! Carrying out a table switch or master-scaling change inside the
//! general tick: at the seam, at a master position or at once, with the
//! blend from the old cam onto the new one (where it lands:
//! `landing.rs`); and what a run that ends leaves behind.

use ecam_core::{CamCurve, Cursor};

use crate::coupling::{Engagement, Geometry, Place};
use crate::switch::Takeover;
use crate::{AxisConfig, EngineError};

use super::landing::{Landing, Old};
use super::phase::Engaged;
use super::{CamAxis, Coupled};

impl<C: CamCurve> CamAxis<C> {
    /// Ends a run: a table still queued is the one to restart with.
    pub(super) fn end_run(&mut self, engaged: Engaged<C>) {
        let Engaged {
            queued,
            pending,
            scaling,
            ..
        } = engaged;
        // The configuration already names the new scaling.
        if let Some(ramp) = scaling {
            self.geometry = ramp.target;
        }
        let mut next = queued.map(|(curve, _)| curve);
        match pending.map(|p| p.takeover) {
            Some(Takeover::Table(curve)) => next = Some(curve),
            Some(Takeover::MasterScaling(zoom)) => {
                let config = AxisConfig {
                    master_zoom: zoom,
                    ..self.config
                };
                if let Ok(geometry) = Geometry::new(&self.curve, &config) {
                    self.config = config;
                    self.geometry = geometry;
                }
            }
            None => {}
        }
        if let Some(curve) = next
            && let Ok(geometry) = Geometry::new(&curve, &self.config)
        {
            self.geometry = geometry;
            self.cursor = Cursor::new();
            self.retired = Some(core::mem::replace(&mut self.curve, curve));
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

    /// Carries out a waiting position or at-once switch at master `at`
    /// (`landing.rs` says where it lands).
    pub(super) fn switch_at(
        &mut self,
        engaged: &mut Engaged<C>,
        at: i64,
    ) -> Result<(), EngineError> {
        let Some(pending) = engaged.pending.as_ref() else {
            return Ok(());
        };
        let landing = self.old(&engaged.engagement).switch_at(
            *self.cursor,
            &pending.takeover,
            pending.blend,
            at,
        )?;
        engaged.plan = None;
        let takeover = engaged.pending.take().map(|p| p.takeover);
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
        // A seam crossed while a blend runs is not taken: the switch waits
        // for the next seam after the blend.
        if from.k == to.k
            || engaged.blend.is_some()
            || engaged.offsets.is_some()
            || engaged.scaling.is_some()
        {
            return Ok(false);
        }
        let Some((curve, then)) = engaged.queued.as_ref() else {
            return Ok(false);
        };
        let landing = self.old(&engaged.engagement).switch_at_seam(
            *self.cursor,
            curve,
            *then,
            engaged.seam_blend,
            from.k,
            to.k > from.k,
        )?;
        engaged.plan = None;
        engaged.seam_blend = None;
        let takeover = engaged
            .queued
            .take()
            .map(|(curve, _)| Takeover::Table(curve));
        self.land(engaged, landing, takeover)?;
        Ok(true)
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
        engaged.blend = landing.blend?;
        Ok(())
    }
}
