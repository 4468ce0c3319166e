//! `ecam serve`'s listeners: the sockets and async tasks around
//! [`ecam_serve`], which holds everything they decide.
//!
//! - [`modbus`]: the Modbus TCP listener (one task per client),
//! - [`http`]: the HTTP API and the designer page (whose JSON answers are
//!   [`ecam_design`]'s),
//! - [`limits`]: connection caps and timeouts both listeners keep.

pub mod http;
pub mod limits;
pub mod modbus;
