//! The steady tick with a ramp-in on top: a cam easing in from where the
//! slave held, with nothing else under way, at a whole master count. The
//! cam comes from the lane's 64-bit constants in one call, as on a settled
//! cam, and the ramp goes on top exactly as the fast lane (`lane.rs`) and
//! the general tick put it, so a ramp-in tick costs a steady tick and the
//! ramp's blend, not the lane's whole dispatch (docs/engine.md,
//! "Benchmarks": the worst tick). The steady-vs-general property test
//! compares it with the general tick.

use ecam_core::{CamCurve, Cursor};

use crate::coupling::Geometry;
use crate::{Events, MasterPosition};

use super::lane_constants::LaneConstants;
use super::phase::Engaged;
use super::underway::Underway;
use super::{FollowSample, step_to};

impl<C: CamCurve> Engaged<C> {
    /// One tick at whole master count `master` of a cam whose ramp-in is
    /// all that runs, with the lane's constants taken; `None` (nothing
    /// changed) leaves the tick to the lane: anything else under way, no
    /// constants, or a value that leaves 64 bits. Out of line: the
    /// ticks that are not ramp-ins only check `Underway::ramps_in_alone`.
    #[inline(never)]
    pub(super) fn ramp_in_tick(
        &mut self,
        master: i64,
        curve: &C,
        cursor: &mut Cursor,
        geometry: &Geometry,
        events: &mut Events,
    ) -> Option<FollowSample> {
        let Self {
            engagement,
            place,
            followed,
            underway,
            lane,
            ..
        } = self;
        let Underway::RampIn(ramp, None) = underway else {
            return None;
        };
        // The engaging tick leaves them to this one (`engage.rs`), taken
        // in place.
        let constants = match lane {
            Some(lane) => &lane.cam,
            None => {
                &lane
                    .insert(LaneConstants {
                        cam: engagement.steady(geometry)?,
                        target: None,
                    })
                    .cam
            }
        };
        let cam = constants.sample(master, curve, cursor)?;
        let (slave, velocity_ratio, ramping) = match ramp.blend(master, cam.slave) {
            Some(blended) => (blended, cam.velocity_ratio * ramp.weight(master), true),
            None => (cam.slave, cam.velocity_ratio, false),
        };
        let ended = ramp.finished_at(MasterPosition {
            counts: master,
            fraction: 0,
        });
        let sample = FollowSample::of_steady(&cam, constants, slave, velocity_ratio, !ramping);
        step_to(
            place,
            followed,
            &cam,
            i128::from(master) << 32,
            geometry.jumps_at_seam,
            events,
        );
        if ended {
            // Settled from here: the steady tick's constants are the lane's.
            let constants = *constants;
            underway.end_ramp_in();
            underway.settle(Some(constants));
        }
        Some(sample)
    }
}
