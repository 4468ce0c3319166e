//! `ecam serve`'s listeners: the sockets and async tasks around
//! [`ecam_serve`], which holds everything they decide.
//!
//! - [`modbus`]: the Modbus TCP listener (one task per client),
//! - [`http`]: the HTTP API and the designer page,
//! - [`design`]: the designer's JSON endpoints.

pub mod design;
pub mod http;
pub mod modbus;
