//! Changing the slave scaling while the cam runs (PLCopen `MC_CamIn`
//! `SlaveScaling` changed in sync): never as a step, but ramped in over a
//! master distance.
//!
//! Over `distance` master counts from where the change is asked (either
//! direction, `u = |master − from| / distance`) the command is
//! `(1 − w(u)) × cam_old + w(u) × cam_new` with the ramp-in's quintic `w`,
//! where both cams are the same table, engagement and offsets, zoomed by
//! the old and the new slave scaling: position and velocity are continuous
//! at both ends, and at `u = 1` the axis takes the new scaling into its
//! geometry, so the slave is exactly the cam with the new scaling on the
//! strokes it engaged with (zero drift afterwards; an axis engaged with the
//! new scaling from the start may stand whole strokes away, where the
//! start rule's rounded choice differs with the scaling).

use core::num::NonZeroU64;

use crate::MasterPosition;
use crate::coupling::Geometry;
use crate::master_ramp::{MasterRamp, quintic, quintic_slope};
use crate::rounding::{exact_f64, round_to_i64};

/// A slave-scaling change being ramped in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ScalingRamp {
    span: MasterRamp,
    /// The geometry with the new slave scaling.
    pub(crate) target: Geometry,
}

impl ScalingRamp {
    /// A ramp onto `target` from master `from` over `distance`.
    pub(crate) fn new(target: Geometry, from: i64, distance: NonZeroU64) -> Self {
        Self {
            span: MasterRamp::new(from, distance),
            target,
        }
    }

    /// The whole change has been ramped in at `master`.
    pub(crate) fn finished(&self, master: i64) -> bool {
        self.span.finished(master)
    }

    /// [`Self::finished`] for the position itself, fraction included.
    pub(crate) fn finished_at(&self, at: MasterPosition) -> bool {
        self.span.finished_at(at)
    }

    /// The command and velocity ratio at `master` from the two cams'
    /// positions and velocity ratios there.
    pub(crate) fn mix(&self, master: i64, old: (i64, f64), new: (i64, f64)) -> (i64, f64) {
        if self.finished(master) {
            return new;
        }
        let d = self.span.distance() as f64;
        let u = self.span.progress(master);
        let w = quintic(u);
        let gap = exact_f64(i128::from(new.0) - i128::from(old.0));
        let step = w * gap;
        // `libm::round(step) as i64`, the common case without its routine.
        let step = round_to_i64(step).unwrap_or_else(|| libm::round(step) as i64);
        let slave = old.0.saturating_add(step);
        let sign = if self.span.backwards(master) {
            -1.0
        } else {
            1.0
        };
        let ratio = (1.0 - w) * old.1 + w * new.1 + sign * quintic_slope(u) * gap / d;
        (slave, ratio)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::AxisConfig;
    use ecam_core::PointTable;

    #[test]
    fn the_mix_runs_from_the_old_cam_to_the_new() {
        let t = PointTable::from_pairs(&[(0, 0), (100, 100)]).unwrap();
        let geo = Geometry::new(&t, &AxisConfig::default()).unwrap();
        let ramp = ScalingRamp::new(geo, 0, NonZeroU64::new(100).unwrap());
        assert_eq!(ramp.mix(0, (10, 1.0), (20, 2.0)).0, 10);
        assert_eq!(ramp.mix(50, (10, 1.0), (20, 2.0)).0, 15);
        assert_eq!(ramp.mix(100, (10, 1.0), (20, 2.0)), (20, 2.0));
    }
}
