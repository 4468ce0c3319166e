//! # ecam-ethercat: cam axes on CiA 402 servo drives over EtherCAT
//!
//! The fieldbus side of ecam. A [`ecam_engine::CamAxis`] computes each
//! cycle's commanded position; this crate carries it to servo drives in
//! cyclic synchronous position mode (CSP, CiA 402 mode 8) through the
//! `ethercrab` EtherCAT master, and brings status back through the
//! [`ecam_engine::drive::AxisDrive`] interface.
//!
//! - [`cia402`]: the drive state machine (statusword → state,
//!   request → controlword), both the master's and the drive's side.
//! - [`pdo`]: the CSP process data and its packing.
//! - [`drive`]: [`Cia402Drive`], a servo drive as an
//!   [`ecam_engine::drive::AxisDrive`].
//! - [`segment`]: bring-up to OP with distributed clocks (SYNC0 = the
//!   cycle) and one exchange per cycle.
//! - [`line`](mod@line): cams on drives, masters from the bus.
//! - [`follow`]: drives following a PLC's pulse outputs (`ecam serve
//!   --ethercat`).
//! - [`supervisor`]: enabling, the fault reaction and the fault reset,
//!   shared by both kinds of line.
//! - [`rt`]: the real-time cycle (absolute deadlines, `SCHED_FIFO`,
//!   pinning, lateness histogram).
//! - [`config`]: the TOML configurations (cams on drives; outputs to drives).
//! - [`emulation`] and [`link`]: emulated CSP drives, reachable by
//!   ethercrab in-process or over a network interface, for tests and for
//!   trying without hardware.
//!
//! The user guide is docs/ethercat.md; it says what was tested against
//! the emulation only.
//!
//! Use something else when you need a full PLC runtime with its own
//! motion kernel: this crate only runs cams on drives.
#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used))]

pub mod cia402;
pub mod coe;
pub mod config;
pub mod dc;
pub mod drive;
pub mod driver;
pub mod emulation;
mod error;
pub mod follow;
pub mod line;
pub mod link;
pub mod log_bridge;
pub mod monitor;
pub mod pdo;
mod poll_sleep;
pub mod rt;
pub mod segment;
pub mod startup;
mod stop_ramp;
pub mod summary;
pub mod supervisor;

pub use drive::Cia402Drive;
pub use error::EthercatError;
pub use link::LinkStats;
pub use segment::{CycleReport, Segment, SegmentConfig, Transport};
