//! Every cap and deadline of `ecam serve`, with its default, in one place
//! (`docs/modbus.md`, "Connections, limits and web safety", lists them
//! from here; `GET /api/status` shows them under `limits`).
//!
//! Two options set them: `--max-connections N` (the caps) and
//! `--idle-timeout S`, which also shortens every other client deadline
//! that is longer than it, so one short value makes a test (or a
//! suspicious network) strict everywhere. `--design-timeout S` sets the
//! design requests' deadline.

use std::time::Duration;

use serde_json::{Value, json};

use crate::connections::Caps;

/// Connections each listener keeps at once, by default.
pub const DEFAULT_MAX_CONNECTIONS: usize = 64;
/// Live views (WebSockets) kept at once, within the HTTP cap.
pub const MAX_LIVE_VIEWS: usize = 16;
/// A Modbus client with no request for this long is closed, by default.
pub const DEFAULT_IDLE: Duration = Duration::from_secs(60);
/// The rest of a Modbus frame once begun, HTTP request headers, and an
/// idle HTTP keep-alive connection.
pub const PARTIAL: Duration = Duration::from_secs(10);
/// An HTTP request body, from the end of its headers.
pub const BODY: Duration = Duration::from_secs(10);
/// A live view whose client answers no ping for this long is closed.
pub const LIVE_IDLE: Duration = Duration::from_secs(15);
/// A live view may take this long to accept one sample.
pub const LIVE_SEND: Duration = Duration::from_secs(5);
/// Largest HTTP request body, bytes.
pub const MAX_BODY_BYTES: usize = 2 * 1024 * 1024;
/// A design request not answered within this long is answered 503 and
/// its work stopped, by default.
pub const DEFAULT_DESIGN_DEADLINE: Duration = Duration::from_secs(30);
/// Design requests computed at once.
pub const DESIGN_WORKERS: usize = 2;
/// Design requests waiting for a worker; beyond, 503 at once.
pub const DESIGN_QUEUE: usize = 8;

/// The caps and deadlines one server keeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Connections per listener (Modbus; HTTP with live views).
    pub max_connections: usize,
    /// Live views, within the HTTP cap.
    pub max_live_views: usize,
    /// A Modbus client with no request for this long is closed.
    pub idle: Duration,
    /// The rest of a Modbus frame once begun, HTTP headers, an idle HTTP
    /// keep-alive connection.
    pub partial: Duration,
    /// An HTTP request body, from the end of its headers.
    pub body: Duration,
    /// A live view that answers no ping for this long is closed.
    pub live_idle: Duration,
    /// How often a live view is pinged.
    pub live_ping: Duration,
    /// Longest a live view may take to accept one sample.
    pub live_send: Duration,
    /// A design request is answered (503 if need be) within this long.
    pub design_deadline: Duration,
}

impl Limits {
    /// The limits for `--max-connections max_connections --idle-timeout
    /// idle --design-timeout design_deadline`.
    pub fn new(max_connections: usize, idle: Duration, design_deadline: Duration) -> Self {
        let live_idle = idle.min(LIVE_IDLE);
        Self {
            max_connections,
            max_live_views: MAX_LIVE_VIEWS.min(max_connections),
            idle,
            partial: idle.min(PARTIAL),
            body: idle.min(BODY),
            live_idle,
            live_ping: live_idle / 3,
            live_send: idle.min(LIVE_SEND),
            design_deadline,
        }
    }

    /// The caps of the connection registry.
    pub fn caps(&self) -> Caps {
        Caps {
            modbus: self.max_connections,
            http: self.max_connections,
            live: self.max_live_views,
        }
    }

    /// For `GET /api/status`.
    pub fn json(&self) -> Value {
        let s = |d: Duration| d.as_secs_f64();
        json!({
            "max_connections": self.max_connections,
            "max_live_views": self.max_live_views,
            "idle_s": s(self.idle),
            "partial_request_s": s(self.partial),
            "body_s": s(self.body),
            "live_idle_s": s(self.live_idle),
            "live_send_s": s(self.live_send),
            "max_body_bytes": MAX_BODY_BYTES,
            "design_deadline_s": s(self.design_deadline),
            "design_workers": DESIGN_WORKERS,
            "design_queue": DESIGN_QUEUE,
        })
    }
}

impl Default for Limits {
    fn default() -> Self {
        Self::new(
            DEFAULT_MAX_CONNECTIONS,
            DEFAULT_IDLE,
            DEFAULT_DESIGN_DEADLINE,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_short_idle_timeout_shortens_every_client_deadline() {
        let d = Limits::default();
        assert_eq!((d.partial, d.body, d.live_idle), (PARTIAL, BODY, LIVE_IDLE));
        let short = Limits::new(3, Duration::from_secs(1), DEFAULT_DESIGN_DEADLINE);
        assert_eq!(short.partial, Duration::from_secs(1));
        assert_eq!(short.body, Duration::from_secs(1));
        assert_eq!(short.live_idle, Duration::from_secs(1));
        assert!(short.live_ping < short.live_idle);
        assert_eq!(short.caps().live, 3);
    }
}
