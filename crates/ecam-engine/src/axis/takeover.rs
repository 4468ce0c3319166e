//! Carrying out a table switch or master-scaling change inside the tick:
//! at the seam, at a master position or at once, with the blend from the
//! old cam onto the new one; and what a run that ends leaves behind.

use core::num::NonZeroU64;

use ecam_core::{CamCurve, Cursor};

use crate::blend::{Blend, BlendEnd};
use crate::coupling::{Engagement, Geometry, Place};
use crate::switch::Takeover;
use crate::{AxisConfig, EngineError, SlaveAlign};

use super::phase::Engaged;
use super::{AfterPass, CamAxis, Coupled};

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
    /// The place of `master` under `geometry` (a one-shot held in its span).
    pub(super) fn resolve_on(
        &self,
        geometry: &Geometry,
        engagement: &Engagement,
        master: i64,
    ) -> Place {
        let mut t = engagement.table_input(geometry, master);
        if let Some((begin, end)) = engagement.span {
            t = t.clamp(begin, end);
        }
        geometry.locate(t)
    }

    /// Carries out a waiting position or at-once switch at master `at`:
    /// the new cam is aligned to the master as at engage and anchored on
    /// the old cam's position there; a blend then carries the slave from
    /// the old cam's velocity to the new cam's.
    pub(super) fn switch_at(
        &mut self,
        engaged: &mut Engaged<C>,
        at: i64,
    ) -> Result<(), EngineError> {
        let Some(pending) = engaged.pending.take() else {
            return Ok(());
        };
        let place = self.resolve(&engaged.engagement, None, at).place;
        let old = engaged
            .engagement
            .sample(self.geometry, &*self.curve, self.cursor, place)?;
        match pending.takeover {
            Takeover::Table(curve) => {
                let geometry = Geometry::new(&curve, self.config)?;
                let mut cursor = Cursor::new();
                let config = AxisConfig {
                    slave_align: SlaveAlign::Relative,
                    ..*self.config
                };
                let engagement =
                    Engagement::new(&geometry, &config, &curve, &mut cursor, at, old.slave)?;
                engaged.engagement = engagement;
                *self.geometry = geometry;
                *self.cursor = cursor;
                *self.retired = Some(core::mem::replace(self.curve, curve));
            }
            Takeover::MasterScaling(zoom) => {
                let config = AxisConfig {
                    master_zoom: zoom,
                    ..*self.config
                };
                let geometry = Geometry::new(&*self.curve, &config)?;
                let mut engagement =
                    engaged
                        .engagement
                        .with_master_rescaled(self.geometry, &geometry, at)?;
                let place = self.resolve_on(&geometry, &engagement, at);
                let new = engagement.sample(&geometry, &*self.curve, self.cursor, place)?;
                // Anchored: the new table unit may round the phase.
                engagement.shift_output(i128::from(old.slave) - i128::from(new.slave))?;
                engaged.engagement = engagement;
                *self.geometry = geometry;
                *self.config = config;
            }
        }
        engaged.blend = match pending.blend {
            Some(distance) => {
                let engagement = engaged.engagement;
                Some(self.blend_onto(&engagement, at, distance, old.slave, old.velocity_ratio)?)
            }
            None => None,
        };
        Ok(())
    }

    /// Takes a queued table over at the seam between the last place and
    /// `to`, if one waits; gives back the engagement on the new table.
    pub(super) fn switch_at_seam(
        &mut self,
        engaged: &mut Engaged<C>,
        to: Place,
    ) -> Result<bool, EngineError> {
        let from = engaged.place;
        // A seam crossed while a blend runs is not taken: the switch waits
        // for the next seam after the blend.
        if from.k == to.k
            || engaged.queued.is_none()
            || engaged.blend.is_some()
            || engaged.offsets.is_some()
            || engaged.scaling.is_some()
        {
            return Ok(false);
        }
        let forward = to.k > from.k;
        // The first boundary crossed: the end of the last cycle going
        // forwards, its start going backwards.
        let at_seam = if forward {
            self.geometry.cycle_end(from.k)
        } else {
            Geometry::cycle_start(from.k)
        };
        let old = engaged
            .engagement
            .sample(self.geometry, &*self.curve, self.cursor, at_seam)?;
        let Some((curve, then)) = engaged.queued.take() else {
            return Ok(false);
        };
        // A blend starts at the last whole master count before the seam,
        // on the old cam there.
        let blend_from = match engaged.seam_blend.take() {
            Some(distance) => {
                let at = engaged
                    .engagement
                    .master_at_seam(self.geometry, from.k, forward);
                let place = self.resolve(&engaged.engagement, None, at).place;
                // Exactly on the seam: seen from the old cycle's side.
                let there = if place.k == from.k {
                    engaged
                        .engagement
                        .sample(self.geometry, &*self.curve, self.cursor, place)?
                } else {
                    old
                };
                Some((at, distance, there.slave, there.velocity_ratio))
            }
            None => None,
        };
        let geometry = Geometry::new(&curve, self.config)?;
        let mut cursor = Cursor::new();
        let mut next = engaged.engagement.across_seam(
            self.geometry,
            &geometry,
            &curve,
            &mut cursor,
            from.k,
            forward,
            old.slave,
        )?;
        if then == AfterPass::Finish {
            next.finish_after_first_pass(&geometry, forward);
        }
        *self.geometry = geometry;
        *self.cursor = cursor;
        *self.retired = Some(core::mem::replace(self.curve, curve));
        engaged.engagement = next;
        if let Some((at, distance, p0, v0)) = blend_from {
            engaged.blend = Some(self.blend_onto(&engaged.engagement, at, distance, p0, v0)?);
        }
        Ok(true)
    }

    /// A blend from the slave at `p0` with velocity ratio `v0` at master
    /// `at` onto the (new) cam of `engagement`.
    fn blend_onto(
        &mut self,
        engagement: &Engagement,
        at: i64,
        distance: NonZeroU64,
        p0: i64,
        v0: f64,
    ) -> Result<Blend, EngineError> {
        let mut ends = [BlendEnd {
            slave: 0,
            velocity_ratio: 0.0,
        }; 2];
        for (end, master) in ends.iter_mut().zip(Blend::ends(at, distance.get())?) {
            let place = self.resolve(engagement, None, master).place;
            let cam = engagement.sample(self.geometry, &*self.curve, self.cursor, place)?;
            *end = BlendEnd {
                slave: cam.slave,
                velocity_ratio: cam.velocity_ratio,
            };
        }
        Blend::start(at, distance.get(), p0, v0, ends)
    }
}
