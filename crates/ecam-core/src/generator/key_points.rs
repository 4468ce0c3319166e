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
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CurveType {
    /// Code 0: constant acceleration (parabolic), what an unnamed curve means.
    #[default]
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

    /// All four, in code order.
    pub const ALL: [CurveType; 4] = [
        Self::ConstantAcceleration,
        Self::SType,
        Self::Cycloid,
        Self::ConstantSpeed,
    ];

    /// Every name and code [`CurveType::from_name`] accepts, for messages.
    pub const NAMES: &'static str =
        "constant-acceleration (0), s-type (1), cycloid (2), constant-speed (3)";

    /// The curve's name in key-point lines, parameter files and forms.
    pub const fn name(self) -> &'static str {
        match self {
            Self::ConstantAcceleration => "constant-acceleration",
            Self::SType => "s-type",
            Self::Cycloid => "cycloid",
            Self::ConstantSpeed => "constant-speed",
        }
    }

    /// The curve for a name or a code written as text (`"2"`).
    pub fn from_name(text: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|c| c.name() == text || text.parse() == Ok(c.code()))
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

super::choice_serde::choice_serde!(CurveType, "curve");

/// One key point: where a segment ends and how the slave gets there.
///
/// In parameter files and HTTP bodies a key point is a table
/// `{master, slave, curve, resolution}` (the last two optional); typed by
/// hand it is one line, see [`KeyPoint::parse_line`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeyPoint {
    /// Master position (counts), greater than the previous key point's.
    pub master: i64,
    /// Slave position (pulses) before the initial offset is added.
    pub slave: i64,
    /// Curve from the previous key point to this one.
    #[serde(default)]
    pub curve: CurveType,
    /// Points for this segment, 1–512; 0 shares what the total leaves.
    #[serde(default)]
    pub resolution: u16,
}

/// What is wrong with a key-point line (see [`KeyPoint::parse_line`]); the
/// front ends word the message, naming where the line came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineError<'a> {
    /// Fewer than two fields.
    TooFew,
    /// More than four fields.
    TooMany,
    /// The master (`what = "master"`) or slave is not an integer.
    NotInteger {
        /// `"master"` or `"slave"`.
        what: &'static str,
        /// The field as written.
        text: &'a str,
    },
    /// The curve is neither a name nor a code of [`CurveType`].
    UnknownCurve(&'a str),
    /// The resolution is not a number from 0 to 65535.
    BadResolution(&'a str),
}

/// The separators between a key-point line's fields: `:`, `,`, `;` and
/// white space (runs count as one).
const LINE_SEPARATORS: [char; 3] = [':', ',', ';'];

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

    /// Reads one key point typed as `MASTER SLAVE [CURVE [RESOLUTION]]`,
    /// the fields separated by `:`, `,`, `;` or white space: the syntax of
    /// `ecam table gen keypoints --key` and of the designer page's key-point
    /// box. CURVE is a [`CurveType`] name or code (constant acceleration
    /// when absent), RESOLUTION 0 (when absent) shares the total.
    ///
    /// ```
    /// use ecam_core::generator::key_points::{CurveType, KeyPoint};
    ///
    /// let k = KeyPoint::parse_line("1500:2000:cycloid:20").unwrap();
    /// assert_eq!((k.master, k.slave, k.curve, k.resolution), (1500, 2000, CurveType::Cycloid, 20));
    /// assert_eq!(KeyPoint::parse_line("600 0").unwrap().to_string(), "600 0 constant-acceleration");
    /// ```
    ///
    /// # Errors
    /// A [`LineError`] saying which field is wrong.
    pub fn parse_line(line: &str) -> Result<Self, LineError<'_>> {
        let mut fields = line
            .split(|c: char| c.is_whitespace() || LINE_SEPARATORS.contains(&c))
            .filter(|f| !f.is_empty());
        let (Some(master), Some(slave)) = (fields.next(), fields.next()) else {
            return Err(LineError::TooFew);
        };
        let master = master.parse().map_err(|_| LineError::NotInteger {
            what: "master",
            text: master,
        })?;
        let slave = slave.parse().map_err(|_| LineError::NotInteger {
            what: "slave",
            text: slave,
        })?;
        let curve = match fields.next() {
            Some(c) => CurveType::from_name(c).ok_or(LineError::UnknownCurve(c))?,
            None => CurveType::default(),
        };
        let resolution = match fields.next() {
            Some(r) => r.parse().map_err(|_| LineError::BadResolution(r))?,
            None => 0,
        };
        if fields.next().is_some() {
            return Err(LineError::TooMany);
        }
        Ok(Self {
            master,
            slave,
            curve,
            resolution,
        })
    }
}

/// The line [`KeyPoint::parse_line`] reads back: `MASTER SLAVE CURVE`, and
/// the resolution when it is not 0.
impl core::fmt::Display for KeyPoint {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "{} {} {}", self.master, self.slave, self.curve.name())?;
        if self.resolution != 0 {
            write!(f, " {}", self.resolution)?;
        }
        Ok(())
    }
}

/// Reads key points typed one per line ([`KeyPoint::parse_line`]); blank
/// lines are skipped.
///
/// # Errors
/// The first bad line's number (1-based) and what is wrong with it.
pub fn parse_lines(text: &str) -> Result<Vec<KeyPoint>, (usize, LineError<'_>)> {
    text.lines()
        .enumerate()
        .filter(|(_, line)| !line.trim().is_empty())
        .map(|(i, line)| KeyPoint::parse_line(line).map_err(|e| (i + 1, e)))
        .collect()
}

/// The K2 parameter block (`S0 + 2` onwards). Its serde form uses the keys
/// of [`schema::KEY_POINTS`](super::schema::KEY_POINTS) (`key`,
/// `resolution`, `initial_slave`); what it leaves out, or an empty `key`
/// list, keeps the `Default`.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(from = "ParamsForm")]
pub struct Params {
    /// Points in the table, 10–512 (`S0 + 2`).
    #[serde(rename = "resolution")]
    pub total_resolution: u16,
    /// Up to ten key points (`S0 + 8` onwards, six words each); key point 0
    /// is implicit at master 0.
    #[serde(rename = "key")]
    pub key_points: Vec<KeyPoint>,
    /// Initial slave position: added to every slave value, so the table
    /// starts there (the "starting offset of the slave").
    pub initial_slave: i64,
}

/// [`Params`] as written, before an empty key list means the default ones.
#[derive(serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
struct ParamsForm {
    key: Vec<KeyPoint>,
    resolution: u16,
    initial_slave: i64,
}

impl Default for ParamsForm {
    fn default() -> Self {
        let d = Params::default();
        Self {
            key: Vec::new(),
            resolution: d.total_resolution,
            initial_slave: d.initial_slave,
        }
    }
}

impl From<ParamsForm> for Params {
    fn from(form: ParamsForm) -> Self {
        let d = Params::default();
        Self {
            total_resolution: form.resolution,
            key_points: if form.key.is_empty() {
                d.key_points
            } else {
                form.key
            },
            initial_slave: form.initial_slave,
        }
    }
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
