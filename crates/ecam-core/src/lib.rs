//! # ecam-core: designing cams
//!
//! Everything about a cam that does not move: normalised motion laws, cam
//! tables (point tables, evenly spaced tables, segment profiles), the table
//! generators of the LX3V PLC's `ECAMTBX` instruction, and validation with
//! the PLC's error codes. No I/O, no clocks: pure functions over `alloc`.
//!
//! The engine (`ecam-engine`) runs any [`CamCurve`]; this crate makes them.
//!
//! ```
//! use ecam_core::{CamCurve, Cursor, PointTable};
//!
//! // Document 001's four-point table.
//! let table = PointTable::from_pairs(&[(0, 500), (10000, 1500), (20000, 1000), (30000, 2000)])?;
//! let mut cursor = Cursor::new();
//! assert_eq!(table.position(5000.0, &mut cursor), 1000.0);
//! assert_eq!(table.stroke(), 1500);
//! # Ok::<(), ecam_core::TableError>(())
//! ```
//!
//! Designing with motion laws (see `docs/design.md`):
//!
//! ```
//! use ecam_core::{CamCurve, CamPoint, Cursor, MotionLaw, Segment, SegmentProfile};
//!
//! let cam = SegmentProfile::new(
//!     CamPoint::new(0, 0),
//!     vec![
//!         Segment::new(9000, 0, MotionLaw::Cycloid),          // dwell
//!         Segment::new(18000, 3600, MotionLaw::ModifiedSine), // rise by 3600
//!         Segment::new(36000, 0, MotionLaw::Poly345),         // return
//!     ],
//! )?;
//! let mut cursor = Cursor::new();
//! let k = cam.eval(13500.0, &mut cursor);
//! assert_eq!(k.s, 1800.0);
//! let table = cam.sample(200)?; // the 200-point table a PLC runs
//! assert_eq!(table.points().len(), 200);
//! # Ok::<(), ecam_core::TableError>(())
//! ```
#![no_std]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

pub mod budget;
mod curve;
pub mod drive_check;
mod error;
pub mod excerpt;
#[cfg(feature = "std")]
#[doc(hidden)]
pub mod fuzz;
pub mod generator;
#[cfg(feature = "std")]
pub mod io;
mod kinematics;
pub mod law;
pub mod limits;
pub mod register_image;
pub mod script_line;
pub mod segments;
pub mod table;

pub use curve::{CamCurve, Cursor};
pub use error::{CODE_PARAMETER, CODE_SECTION_COUNT, CODE_TABLE, TableError};
pub use kinematics::Kinematics;
pub use law::MotionLaw;
pub use table::{CamPoint, CamTable, PointTable, Segment, SegmentProfile, UniformTable};
