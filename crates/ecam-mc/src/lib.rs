//! # ecam-mc: the motion-controller (Repeat-type) face
//!
//! Document 001's E-CAM as a motion controller offers it: a slave axis
//! follows a master axis through a (master, slave) point table of type
//! [`CamType::Normal`], [`CamType::Periodic`] or [`CamType::Repeat`]; a
//! master may be a single-turn axis ([`MotionController::set_single_turn`]),
//! which wraps over its encoder range. The cam runs on `ecam-engine`:
//! Repeat is its repeat coupling (with the "less than one user unit" rule
//! from the slave's [`UserUnit`]), a Repeat cam on a single-turn master
//! starts at the nearest equivalent slave position, and a table that does
//! not cover the turn is extended with its end values.
//!
//! Use it to run document 001-style cams from Rust, or from a text script
//! ([`script`], what `ecam mc run` runs); for the PLC or
//! motion-processor faces see `ecam-plc` and `ecam-pmd`.
//!
//! ```
//! use ecam_core::PointTable;
//! use ecam_mc::{CamType, ECamData, MotionController};
//!
//! // Document 001's table, Repeat type: the slave is continuous at the seam.
//! let table = PointTable::from_pairs(&[(0, 500), (10000, 1500), (20000, 1000), (30000, 2000)])?;
//! let mut mc = MotionController::new(2);
//! mc.start_ecam(ECamData { master_axis: 0, slave_axis: 1, cam_type: CamType::Repeat, table })?;
//! assert_eq!(mc.position(1)?, 500);
//! for master in (0..=40000).step_by(1000) {
//!     mc.drive(0, master, 1)?;
//! }
//! assert_eq!(mc.position(1)?, 3000); // 1500 (one stroke) + 1500 (table at 10000)
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod cam_type;
mod controller;
mod error;
#[doc(hidden)]
pub mod fuzz;
pub mod script;
mod units;

pub use cam_type::CamType;
pub use controller::{ECamData, MotionController};
pub use error::McError;
pub use units::{SingleTurn, UserUnit};
