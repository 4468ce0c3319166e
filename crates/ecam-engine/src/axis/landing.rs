//! What a table switch or master-scaling change lands on, worked out
//! before anything changes: the new geometry, the new engagement anchored
//! on the old cam, and the blend from the old cam onto the new one.
//!
//! The same functions serve the tick that carries a switch out
//! (`takeover.rs`) and the request that prepares it ahead of the cycle
//! (`plan.rs`): a prepared switch lands exactly where the tick would.

use core::num::NonZeroU64;

use ecam_core::{CamCurve, Cursor};

use crate::blend::{Blend, BlendEnd};
use crate::coupling::{Engagement, Geometry, Place};
use crate::switch::Takeover;
use crate::{AxisConfig, EngineError, SlaveAlign, Zoom};

use super::AfterPass;

/// The running cam a switch leaves: its table, geometry, configuration
/// and engagement (read only).
pub(super) struct Old<'a, C> {
    pub(super) curve: &'a C,
    pub(super) geometry: &'a Geometry,
    pub(super) config: &'a AxisConfig,
    pub(super) engagement: &'a Engagement,
}

/// Where a switch lands. The blend comes last and may fail on its own:
/// the tick then keeps the rest (as it always has) and reports the error.
#[derive(Clone, Debug)]
pub(super) struct Landing {
    pub(super) engagement: Engagement,
    pub(super) geometry: Geometry,
    /// The cursor on the table followed from then on.
    pub(super) cursor: Cursor,
    /// A master-scaling change's new scaling (the configuration takes it).
    pub(super) master_zoom: Option<Zoom>,
    pub(super) blend: Result<Option<Blend>, EngineError>,
}

/// The place of `master` under `geometry` (a one-shot held in its span).
pub(super) fn resolve_on(geometry: &Geometry, engagement: &Engagement, master: i64) -> Place {
    let mut t = engagement.table_input(geometry, master);
    if let Some((begin, end)) = engagement.span {
        t = t.clamp(begin, end);
    }
    geometry.locate(t)
}

impl<C: CamCurve> Old<'_, C> {
    /// A waiting position or at-once switch carried out at master `at`:
    /// the new cam aligned to the master as at engage and anchored on the
    /// old cam's position there; a blend then carries the slave from the
    /// old cam's velocity to the new cam's. `cursor` is the old table's.
    pub(super) fn switch_at(
        &self,
        mut cursor: Cursor,
        takeover: &Takeover<C>,
        blend: Option<NonZeroU64>,
        at: i64,
    ) -> Result<Landing, EngineError> {
        let place = resolve_on(self.geometry, self.engagement, at);
        let old = self
            .engagement
            .sample(self.geometry, self.curve, &mut cursor, place)?;
        let (engagement, geometry, master_zoom, curve) = match takeover {
            Takeover::Table(curve) => {
                let geometry = Geometry::new(curve, self.config)?;
                cursor = Cursor::new();
                let config = AxisConfig {
                    slave_align: SlaveAlign::Relative,
                    ..*self.config
                };
                let engagement =
                    Engagement::new(&geometry, &config, curve, &mut cursor, at, old.slave)?;
                (engagement, geometry, None, curve)
            }
            Takeover::MasterScaling(zoom) => {
                let config = AxisConfig {
                    master_zoom: *zoom,
                    ..*self.config
                };
                let geometry = Geometry::new(self.curve, &config)?;
                let mut engagement =
                    self.engagement
                        .with_master_rescaled(self.geometry, &geometry, at)?;
                let place = resolve_on(&geometry, &engagement, at);
                let new = engagement.sample(&geometry, self.curve, &mut cursor, place)?;
                // Anchored: the new table unit may round the phase.
                engagement.shift_output(i128::from(old.slave) - i128::from(new.slave))?;
                (engagement, geometry, Some(*zoom), self.curve)
            }
        };
        let blend = match blend {
            Some(distance) => blend_onto(
                &geometry,
                curve,
                &mut cursor,
                &engagement,
                (at, distance),
                (old.slave, old.velocity_ratio),
            )
            .map(Some),
            None => Ok(None),
        };
        Ok(Landing {
            engagement,
            geometry,
            cursor,
            master_zoom,
            blend,
        })
    }

    /// A table queued for the seam taking over at the seam of cycle
    /// `from_k` the master crosses (its end when `forward`, else its
    /// start): the new table's cycle starts there and the output goes on
    /// from the old cam's position at the seam. With a blend it starts at
    /// the last whole master count before the seam, on the old cam there.
    /// `cursor` is the old table's.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn switch_at_seam(
        &self,
        mut cursor: Cursor,
        curve: &C,
        then: AfterPass,
        blend: Option<NonZeroU64>,
        from_k: i128,
        forward: bool,
    ) -> Result<Landing, EngineError> {
        // The first boundary crossed: the end of the last cycle going
        // forwards, its start going backwards.
        let at_seam = if forward {
            self.geometry.cycle_end(from_k)
        } else {
            Geometry::cycle_start(from_k)
        };
        let old = self
            .engagement
            .sample(self.geometry, self.curve, &mut cursor, at_seam)?;
        // A blend starts at the last whole master count before the seam,
        // on the old cam there.
        let blend_from = match blend {
            Some(distance) => {
                let at = self
                    .engagement
                    .master_at_seam(self.geometry, from_k, forward);
                let place = resolve_on(self.geometry, self.engagement, at);
                // Exactly on the seam: seen from the old cycle's side.
                let there = if place.k == from_k {
                    self.engagement
                        .sample(self.geometry, self.curve, &mut cursor, place)?
                } else {
                    old
                };
                Some((at, distance, there.slave, there.velocity_ratio))
            }
            None => None,
        };
        let geometry = Geometry::new(curve, self.config)?;
        let mut cursor = Cursor::new();
        let mut engagement = self.engagement.across_seam(
            self.geometry,
            &geometry,
            curve,
            &mut cursor,
            from_k,
            forward,
            old.slave,
        )?;
        if then == AfterPass::Finish {
            engagement.finish_after_first_pass(&geometry, forward);
        }
        let blend = match blend_from {
            Some((at, distance, p0, v0)) => blend_onto(
                &geometry,
                curve,
                &mut cursor,
                &engagement,
                (at, distance),
                (p0, v0),
            )
            .map(Some),
            None => Ok(None),
        };
        Ok(Landing {
            engagement,
            geometry,
            cursor,
            master_zoom: None,
            blend,
        })
    }
}

/// A blend from the slave at `from.0` with velocity ratio `from.1` at
/// master `start.0` over `start.1` counts onto the (new) cam of
/// `engagement` on `geometry` and `curve`.
fn blend_onto<C: CamCurve>(
    geometry: &Geometry,
    curve: &C,
    cursor: &mut Cursor,
    engagement: &Engagement,
    start: (i64, NonZeroU64),
    from: (i64, f64),
) -> Result<Blend, EngineError> {
    let (at, distance) = start;
    let mut ends = [BlendEnd {
        slave: 0,
        velocity_ratio: 0.0,
    }; 2];
    for (end, master) in ends.iter_mut().zip(Blend::ends(at, distance.get())?) {
        let place = resolve_on(geometry, engagement, master);
        let cam = engagement.sample(geometry, curve, cursor, place)?;
        *end = BlendEnd {
            slave: cam.slave,
            velocity_ratio: cam.velocity_ratio,
        };
    }
    Blend::start(at, distance.get(), from.0, from.1, ends)
}
