//! `ecam serve`'s listeners (feature `net`): the sockets and async tasks
//! around the rest of this crate, which holds everything they decide.
//!
//! - [`modbus`]: the Modbus TCP listener (one task per client),
//! - [`http`]: the HTTP API and the designer page (whose JSON answers are
//!   `ecam_design`'s),
//! - [`page`]: the designer page's files, as the binary hands them over,
//! - [`live`]: the live view's WebSocket,
//! - [`conn`]: an accepted connection in the registry (caps, who makes
//!   room),
//! - [`reply`]: the HTTP face's JSON answers.

pub mod conn;
pub mod http;
pub mod live;
pub mod modbus;
pub mod page;
pub mod reply;
