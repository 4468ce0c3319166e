//! `ecam serve`'s pieces that stay in the binary; the listeners are
//! [`ecam_serve::net`]'s.
//!
//! - [`assets`]: the designer page's files, compiled in,
//! - [`ethercat`]: the fieldbus cycle of `--ethercat` (the PLC's pulse
//!   outputs on CiA 402 drives).

pub mod assets;
pub mod ethercat;
