//! The `segments` generator: a cam designed as segments between
//! interpolation points ([`crate::segments`]), sampled into the point table
//! a PLC runs.
//!
//! ```
//! use ecam_core::CamCurve;
//! use ecam_core::generator::segments::{self, Params};
//!
//! let g = segments::generate(&Params::default())?;
//! assert_eq!(g.table.points().len(), 100);
//! assert_eq!(g.cam.continuity().cam.to_string(), "C2");
//! # Ok::<(), ecam_core::segments::SegmentError>(())
//! ```

use alloc::vec::Vec;

use crate::segments::{InterpolationPoint, SegmentCam, SegmentError, SegmentLaw, SegmentSpec};
use crate::{MotionLaw, PointTable};

/// The generator's parameters, as parameter files and requests give them.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Params {
    /// The first interpolation point (default: master 0, slave 0, free).
    pub start: InterpolationPoint,
    /// The segments, each with the law it follows to its end point, in
    /// master order.
    pub segment: Vec<SegmentSpec>,
    /// Points in the sampled table, 10–512 (the start point included).
    pub resolution: u16,
    /// Fill the free boundary values from the neighbours first
    /// ([`crate::segments::make_continuous`]).
    pub continuous: bool,
}

impl Default for Params {
    /// A pick-and-place cam over 3600 counts (a tenth of a degree each):
    /// wait at the pick, rise 5000 pulses with a modified sine, wait at the
    /// place, return with a poly-5.
    fn default() -> Self {
        let rise = |law| SegmentLaw::Rise(law);
        Self {
            start: InterpolationPoint::new(0, 0),
            segment: alloc::vec![
                SegmentSpec::new(rise(MotionLaw::Cycloid), 600, 0),
                SegmentSpec::new(rise(MotionLaw::ModifiedSine), 1800, 5000),
                SegmentSpec::new(rise(MotionLaw::Cycloid), 2400, 5000),
                SegmentSpec::new(SegmentLaw::Poly5, 3600, 0),
            ],
            resolution: 100,
            continuous: false,
        }
    }
}

/// A generated segment cam.
#[derive(Clone, Debug, PartialEq)]
pub struct Generated {
    /// The sampled point table.
    pub table: PointTable,
    /// The solved cam (after making it continuous, when asked).
    pub cam: SegmentCam,
    /// Points each segment got.
    pub resolutions: Vec<u16>,
    /// Master range of the first constant-velocity segment that moves: the
    /// synchronised zone of a knife or a saw.
    pub sync: Option<(i64, i64)>,
}

/// Solves and samples the cam `params` describe.
///
/// # Errors
/// What [`SegmentCam::new`] (or [`SegmentCam::continuous`]) refuses, naming
/// the point; a resolution the sampling refuses (6781, 6783).
pub fn generate(params: &Params) -> Result<Generated, SegmentError> {
    let cam = if params.continuous {
        SegmentCam::continuous(params.start, params.segment.clone())?
    } else {
        SegmentCam::new(params.start, params.segment.clone())?
    };
    let resolutions = cam.resolutions(params.resolution)?;
    let table = cam.sample(params.resolution)?;
    let mut from = cam.start().slave;
    let mut first_master = cam.start().master;
    let mut sync = None;
    for s in cam.segments() {
        if sync.is_none()
            && s.law == SegmentLaw::Rise(MotionLaw::ConstantVelocity)
            && s.slave != from
        {
            sync = Some((first_master, s.master));
        }
        from = s.slave;
        first_master = s.master;
    }
    Ok(Generated {
        table,
        cam,
        resolutions,
        sync,
    })
}
