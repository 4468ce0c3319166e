//! Changing the coupling's offsets while the cam runs (PLCopen `MC_CamIn`
//! `MasterOffset` and `SlaveOffset` changed in sync): never as a step, but
//! ramped in over a master distance.
//!
//! Over `distance` master counts from where the change is asked (either
//! direction, `u = |master − from| / distance`) the offsets move by
//! `w(u) × change` with the quintic `w(u) = 10u³ − 15u⁴ + 6u⁵` (the
//! ramp-in's law): position, velocity and acceleration stay continuous at
//! both ends. The ramped part is rounded to whole table units (master) and
//! pulses (slave) at every master position; at `u = 1` the whole change is
//! taken into the coupling's integer offsets, so the final value is exact
//! and the cam is again a pure function of the master (zero drift).

use core::num::NonZeroU64;

use crate::coupling::Engagement;
use crate::master_ramp::{MasterRamp, quintic};
use crate::rounding::{exact_f64, round_to_i128};
use crate::{EngineError, MasterPosition};

/// A change of offsets for [`crate::CamAxis::change_offsets`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OffsetChange {
    /// Added to the table input (table counts, after master zoom): PLCopen
    /// `MasterOffset`, as [`crate::MasterAlign::Offset`]. Positive moves
    /// the cam's profile to earlier master positions.
    pub master: i64,
    /// Added to the commanded slave (pulses): PLCopen `SlaveOffset`, as
    /// [`crate::SlaveAlign::Offset`].
    pub slave: i64,
    /// Master travel (before zoom, either direction) over which the change
    /// is ramped in. The slave's extra velocity peaks at
    /// `1.875 × slave / distance` (plus the cam's slope times
    /// `1.875 × master / distance` in table counts), which is what the
    /// distance is chosen for: a ramp shorter than that bound allows can
    /// reverse the slave, as the change then asks.
    pub distance: NonZeroU64,
}

/// A change being ramped in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct OffsetRamp {
    span: MasterRamp,
    /// Table-input change in × master-zoom-denominator units.
    input_num: i128,
    output: i128,
}

impl OffsetRamp {
    /// A ramp of `change` from master `from`; `mden` is the master zoom's
    /// denominator (the table-input unit).
    pub(crate) fn new(change: OffsetChange, from: i64, mden: i128) -> Self {
        Self {
            span: MasterRamp::new(from, change.distance),
            input_num: i128::from(change.master).saturating_mul(mden),
            output: i128::from(change.slave),
        }
    }

    /// The whole change has been ramped in at `master`.
    /// The engagement the ramp ends on: `engagement` with the whole
    /// change (what [`OffsetRamp::apply`] gives once it is finished).
    pub(crate) fn ended(&self, engagement: &Engagement) -> Result<Engagement, EngineError> {
        engagement.shifted(self.input_num, self.output)
    }

    pub(crate) fn finished(&self, master: i64) -> bool {
        self.span.finished(master)
    }

    /// [`Self::finished`] for the position itself, fraction included.
    pub(crate) fn finished_at(&self, at: MasterPosition) -> bool {
        self.span.finished_at(at)
    }

    /// The engagement with the part of the change ramped in at `master`.
    pub(crate) fn apply(
        &self,
        engagement: &Engagement,
        master: i64,
    ) -> Result<Engagement, EngineError> {
        let (input, output) = self.parts(master);
        engagement.shifted(input, output)
    }

    /// The part of the change ramped in at `master`: table input (×
    /// master-zoom-denominator units) and output pulses.
    #[inline]
    pub(crate) fn parts(&self, master: i64) -> (i128, i128) {
        if self.finished(master) {
            (self.input_num, self.output)
        } else {
            let w = quintic(self.span.progress(master));
            let part = |v: i128| round_to_i128(exact_f64(v) * w);
            (part(self.input_num), part(self.output))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ramp_completes_exactly_at_its_distance() {
        let change = OffsetChange {
            master: 0,
            slave: 1000,
            distance: NonZeroU64::new(100).unwrap(),
        };
        let ramp = OffsetRamp::new(change, 50, 1);
        assert!(!ramp.finished(149));
        assert!(ramp.finished(150));
        assert!(ramp.finished(-50));
    }
}
