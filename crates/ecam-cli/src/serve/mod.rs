//! `ecam serve`'s listeners: the sockets and async tasks around
//! [`ecam_serve`], which holds everything they decide.
//!
//! - [`modbus`]: the Modbus TCP listener (one task per client),
//! - [`http`]: the HTTP API and the designer page (whose JSON answers are
//!   [`ecam_design`]'s),
//! - [`assets`]: the designer page's files, compiled in,
//! - [`ethercat`]: the fieldbus cycle of `--ethercat` (the PLC's pulse
//!   outputs on CiA 402 drives),
//! - [`live`]: the live view's WebSocket,
//! - [`conn`]: an accepted connection in `ecam_serve`'s registry (caps,
//!   who makes room),
//! - [`reply`]: the HTTP face's JSON answers.

pub mod assets;
pub mod conn;
pub mod ethercat;
pub mod http;
pub mod live;
pub mod modbus;
pub mod reply;
