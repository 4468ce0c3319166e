//! What can be wrong with a segment cam: each error names the point
//! (point 0 is the start; segment `k` ends at point `k`).

use core::fmt;

use super::law::SegmentLaw;
use super::point::Quantity;
use crate::{CODE_PARAMETER, CODE_TABLE, TableError};

/// An invalid segment cam.
#[derive(Clone, Debug, PartialEq)]
pub enum SegmentError {
    /// No segment at all.
    NoSegments,
    /// A point's master is not greater than the previous point's.
    MasterNotIncreasing {
        /// The point.
        point: usize,
    },
    /// A position beyond ±2⁵², or a boundary value that is not a finite number.
    OutOfRange {
        /// The point.
        point: usize,
        /// What is out of range (`"master"`, `"slave"`, `"velocity"`, …).
        what: &'static str,
    },
    /// A segment's law cannot meet a value its point asks for.
    CannotMeet {
        /// The point.
        point: usize,
        /// Its master position.
        master: i64,
        /// The segment (1-based) that cannot meet it.
        segment: usize,
        /// That segment's law.
        law: SegmentLaw,
        /// The value concerned.
        quantity: Quantity,
        /// What the point asks for.
        wanted: f64,
        /// What the law gives there.
        gives: f64,
    },
    /// Making the cam continuous found two neighbouring laws that both fix a
    /// value at their point, differently.
    Conflict {
        /// The point.
        point: usize,
        /// Its master position.
        master: i64,
        /// The value concerned.
        quantity: Quantity,
        /// The segment arriving there, its law and the value it arrives with.
        arriving: (usize, SegmentLaw, f64),
        /// The segment leaving, its law and the value it leaves with.
        leaving: (usize, SegmentLaw, f64),
    },
    /// Sampling the cam into a table failed (resolution, 32-bit range).
    Table(TableError),
}

impl SegmentError {
    /// The PLC error code it maps onto (6781 parameter, 6782 table, 6783 count).
    pub const fn code(&self) -> u16 {
        match self {
            Self::NoSegments | Self::CannotMeet { .. } | Self::Conflict { .. } => CODE_PARAMETER,
            Self::MasterNotIncreasing { .. } | Self::OutOfRange { .. } => CODE_TABLE,
            Self::Table(e) => e.code(),
        }
    }
}

impl From<TableError> for SegmentError {
    fn from(e: TableError) -> Self {
        Self::Table(e)
    }
}

/// A number for messages: at most six decimals, trailing zeros dropped.
struct Short(f64);

impl fmt::Display for Short {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text = alloc::format!("{:.6}", self.0);
        let text = text.trim_end_matches('0').trim_end_matches('.');
        f.write_str(if text == "-0" { "0" } else { text })
    }
}

impl fmt::Display for SegmentError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let code = self.code();
        match self {
            Self::NoSegments => write!(
                f,
                "segment error ({code}): a cam needs at least one segment"
            ),
            Self::MasterNotIncreasing { point } => write!(
                f,
                "segment error ({code}) at point {point}: its master must be greater than point {}'s",
                point.saturating_sub(1)
            ),
            Self::OutOfRange { point, what } => write!(
                f,
                "segment error ({code}) at point {point}: the {what} is not a finite number or beyond ±2^52"
            ),
            Self::CannotMeet {
                point,
                master,
                segment,
                law,
                quantity,
                wanted,
                gives,
            } => write!(
                f,
                "segment error ({code}) at point {point} (master {master}): it asks for {quantity} {} {}, \
                 but segment {segment}'s law {law} gives {}; give that segment a law that adapts to the {quantity} \
                 ({}), or free the point's {quantity}",
                Short(*wanted),
                quantity.unit(),
                Short(*gives),
                adapting(*quantity),
            ),
            Self::Conflict {
                point,
                master,
                quantity,
                arriving,
                leaving,
            } => write!(
                f,
                "segment error ({code}) at point {point} (master {master}): segment {} ({}) arrives with {quantity} {} \
                 but segment {} ({}) leaves with {} {}; give one of them a law that adapts to the {quantity} ({})",
                arriving.0,
                arriving.1,
                Short(arriving.2),
                leaving.0,
                leaving.1,
                Short(leaving.2),
                quantity.unit(),
                adapting(*quantity),
            ),
            Self::Table(e) => e.fmt(f),
        }
    }
}

fn adapting(quantity: Quantity) -> &'static str {
    match quantity {
        Quantity::Velocity => SegmentLaw::ADAPTING,
        Quantity::Acceleration => "poly-5, poly-7",
        Quantity::Jerk => "poly-7",
    }
}

impl core::error::Error for SegmentError {}
