//! # ecam-plc: the LX3V PLC face
//!
//! (Being written.)

pub mod devices;
pub mod operation_error;
