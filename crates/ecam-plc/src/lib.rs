//! # ecam-plc: the LX3V PLC face
//!
//! (Being written.)
