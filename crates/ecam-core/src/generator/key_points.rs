//! ECAMTBX K2: a table from up to ten key points (document 000's appendix
//! "Customize the specified key point to generate the table").
//!
//! The cam starts at master 0 and the slave's initial offset; each key point
//! ends a segment that the slave crosses along one of four curve types. The
//! table is then sampled as the PC editor's table dialog does (document 003
//! §6.2), which the appendix says K2 reproduces: a total resolution of 10 to
//! 512 points, per-key-point resolutions, unset ones sharing the rest.
//!
//! ```
//! use ecam_core::CamCurve;
//! use ecam_core::generator::key_points::{self, Params};
//!
//! // The appendix's application case (the `Default`).
//! let generated = key_points::generate(&Params::default())?;
//! assert_eq!(generated.table.points().len(), 100);
//! assert_eq!(generated.table.master_last(), 2000);
//! # Ok::<(), ecam_core::TableError>(())
//! ```

use alloc::vec::Vec;

use crate::table::{MAX_SEGMENT_RESOLUTION, MAX_TOTAL_RESOLUTION, MIN_TOTAL_RESOLUTION};
use crate::{CamPoint, MotionLaw, PointTable, Segment, SegmentProfile, TableError};

/// Most key points the parameter block holds.
pub const MAX_KEY_POINTS: usize = 10;

/// The four curve types a key point's segment can follow (`*1` in the
/// appendix's parameter table).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum CurveType {
    /// Code 0: constant acceleration (parabolic).
    ConstantAcceleration,
    /// Code 1: S-type acceleration and deceleration (jerk-limited).
    SType,
    /// Code 2: cycloid.
    Cycloid,
    /// Code 3: constant speed.
    ConstantSpeed,
}

impl CurveType {
    /// The curve type stored as `code` in the parameter block; `None` for
    /// anything but 0–3 (the PLC reports that as 6781).
    pub const fn from_code(code: i32) -> Option<Self> {
        match code {
            0 => Some(Self::ConstantAcceleration),
            1 => Some(Self::SType),
            2 => Some(Self::Cycloid),
            3 => Some(Self::ConstantSpeed),
            _ => None,
        }
    }

    /// The parameter-block code.
    pub const fn code(self) -> u16 {
        match self {
            Self::ConstantAcceleration => 0,
            Self::SType => 1,
            Self::Cycloid => 2,
            Self::ConstantSpeed => 3,
        }
    }

    /// The motion law the segment follows.
    pub const fn law(self) -> MotionLaw {
        match self {
            Self::ConstantAcceleration => MotionLaw::ConstantAcceleration,
            Self::SType => MotionLaw::SType,
            Self::Cycloid => MotionLaw::Cycloid,
            Self::ConstantSpeed => MotionLaw::ConstantVelocity,
        }
    }
}

/// One key point: where a segment ends and how the slave gets there.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct KeyPoint {
    /// Master position (counts), greater than the previous key point's.
    pub master: i64,
    /// Slave position (pulses) before the initial offset is added.
    pub slave: i64,
    /// Curve from the previous key point to this one.
    pub curve: CurveType,
    /// Points for this segment, 1–512; 0 shares what the total leaves.
    pub resolution: u16,
}

impl KeyPoint {
    /// A key point whose segment shares the resolution.
    pub const fn new(master: i64, slave: i64, curve: CurveType) -> Self {
        Self {
            master,
            slave,
            curve,
            resolution: 0,
        }
    }
}

/// The K2 parameter block (`S0 + 2` onwards).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Params {
    /// Points in the table, 10–512 (`S0 + 2`).
    pub total_resolution: u16,
    /// Up to ten key points (`S0 + 8` onwards, six words each); key point 0
    /// is implicit at master 0.
    pub key_points: Vec<KeyPoint>,
    /// Initial slave position: added to every slave value, so the table
    /// starts there (the "starting offset of the slave").
    pub initial_slave: i64,
}

impl Default for Params {
    /// Document 000's application case: dwell to 600, rise to 2000 by 1500,
    /// dwell to 1700, back to 600 by 1900 and to 0 by 2000, constant
    /// acceleration everywhere, total resolution 100, all shared.
    fn default() -> Self {
        use CurveType::ConstantAcceleration as Ca;
        Self {
            total_resolution: 100,
            key_points: alloc::vec![
                KeyPoint::new(600, 0, Ca),
                KeyPoint::new(1500, 2000, Ca),
                KeyPoint::new(1700, 2000, Ca),
                KeyPoint::new(1900, 600, Ca),
                KeyPoint::new(2000, 0, Ca),
            ],
            initial_slave: 0,
        }
    }
}

/// What K2 produces.
#[derive(Clone, Debug, PartialEq)]
pub struct Generated {
    /// The sampled table (what ECAMTBX writes at `D1 + 38`).
    pub table: PointTable,
    /// Key-point tables have no synchronised zone.
    pub sync: Option<(i64, i64)>,
    /// The exact curve the table samples.
    pub profile: SegmentProfile,
    /// Points each segment got.
    pub resolutions: Vec<u16>,
}

/// Checks the parameters and builds the table.
///
/// # Errors
/// - [`TableError::Parameter`] (6781): no key point or more than ten; a
///   total resolution below 10; a key point resolution above 512; set
///   resolutions that exceed the total or leave nothing for the others; a
///   segment shorter in master counts than its points;
/// - [`TableError::MasterNotIncreasing`] (6782) naming the key point (1-based)
///   whose master is not greater than the previous one (the first must be
///   above 0);
/// - [`TableError::ValueOutOfRange`] (6782) naming the key point whose
///   master or offset slave is not a 32-bit register value;
/// - [`TableError::SectionCount`] (6783): a total resolution above 512.
pub fn generate(params: &Params) -> Result<Generated, TableError> {
    let count = params.key_points.len();
    if !(1..=MAX_KEY_POINTS).contains(&count) {
        return Err(TableError::Parameter {
            name: "key points number",
            reason: "must be between 1 and 10",
        });
    }
    if params.total_resolution < MIN_TOTAL_RESOLUTION {
        return Err(TableError::Parameter {
            name: "total resolution",
            reason: "must be between 10 and 512",
        });
    }
    if params.total_resolution > MAX_TOTAL_RESOLUTION {
        return Err(TableError::SectionCount {
            count: usize::from(params.total_resolution),
            min: usize::from(MIN_TOTAL_RESOLUTION),
            max: usize::from(MAX_TOTAL_RESOLUTION),
        });
    }
    let fits = |v: i64| i32::try_from(v).is_ok();
    if !fits(params.initial_slave) {
        return Err(TableError::ValueOutOfRange { section: 0 });
    }
    let mut previous_master = 0;
    let mut segments = Vec::with_capacity(count);
    for (i, kp) in params.key_points.iter().enumerate() {
        let section = i + 1;
        let slave = kp.slave.checked_add(params.initial_slave);
        let (Some(slave), true) = (slave, fits(kp.master)) else {
            return Err(TableError::ValueOutOfRange { section });
        };
        if !fits(slave) {
            return Err(TableError::ValueOutOfRange { section });
        }
        if kp.master <= previous_master {
            return Err(TableError::MasterNotIncreasing { section });
        }
        if kp.resolution > MAX_SEGMENT_RESOLUTION {
            return Err(TableError::Parameter {
                name: "key point resolution",
                reason: "must be between 0 (shared) and 512",
            });
        }
        previous_master = kp.master;
        segments.push(Segment {
            master_end: kp.master,
            slave_end: slave,
            law: kp.curve.law(),
            resolution: (kp.resolution != 0).then_some(kp.resolution),
        });
    }
    let profile = SegmentProfile::new(CamPoint::new(0, params.initial_slave), segments)?;
    let resolutions = profile.resolutions(params.total_resolution)?;
    let table = profile.sample(params.total_resolution)?;
    Ok(Generated {
        table,
        sync: None,
        profile,
        resolutions,
    })
}
