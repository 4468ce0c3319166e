//! # ecam-ethercat: cam axes on CiA 402 servo drives over EtherCAT
//!
//! The fieldbus side of ecam. A [`ecam_engine::CamAxis`] computes each
//! cycle's commanded position; this crate carries it to servo drives in
//! cyclic synchronous position mode (CSP, CiA 402 mode 8) through the
//! `ethercrab` EtherCAT master, and brings status back through the
//! [`ecam_engine::drive::AxisDrive`] interface.
//!
//! - [`cia402`]: the drive state machine (statusword → state,
//!   request → controlword).
//!
//! Use something else when you need a full PLC runtime with its own
//! motion kernel: this crate only runs cams on drives.
#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used))]

pub mod cia402;
pub mod config;
pub mod drive;
pub mod emulation;
mod error;
pub mod line;
pub mod link;
pub mod pdo;
pub mod rt;
pub mod segment;

pub use drive::Cia402Drive;
pub use error::EthercatError;
pub use segment::{CycleReport, Segment, SegmentConfig, Transport};
