//! `ecam serve`: the PLC in real time behind Modbus TCP and HTTP.
//!
//! - [`map`]: the Modbus address map (the **contract** in ARCHITECTURE.md),
//! - [`pdu`]: Modbus request/response PDUs, checked byte by byte,
//! - [`modbus`]: the Modbus TCP listener (MBAP framing, one task per client),
//! - [`write`](mod@write): a batch of device writes, and its one-line text form,
//! - [`journal`]: durable writes (append-only journal + snapshot),
//! - [`retain`]: which devices `--state` keeps, and the latched image,
//! - [`state`]: the PLC shared by the scan loop and the servers,
//! - [`clock`]: the scan loop, paced by the wall clock,
//! - [`device_json`], [`design`], [`http`]: the HTTP API and the designer page.

pub mod clock;
pub mod design;
pub mod device_json;
pub mod http;
pub mod journal;
pub mod map;
pub mod modbus;
pub mod pdu;
pub mod retain;
pub mod state;
pub mod write;
