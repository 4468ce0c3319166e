//! How many connections `ecam serve` keeps, and for how long an idle or
//! half-sent one may hold a socket: without a cap, a thousand idle sockets
//! exhaust the process' file limit and lock every client out.
//!
//! At the cap the *newest* connection is closed at once; the ones already
//! served keep working, so the operator panel that was connected first is
//! never the one pushed out.

use std::sync::Arc;
use std::time::Duration;

use tokio::sync::{OwnedSemaphorePermit, Semaphore};

/// The limits of one listener.
#[derive(Clone, Debug)]
pub struct ConnectionLimits {
    slots: Arc<Semaphore>,
    /// A connection with no request for this long is closed.
    pub idle: Duration,
    /// A request (Modbus frame after its first byte, HTTP header) must be
    /// complete within this long.
    pub partial: Duration,
}

impl ConnectionLimits {
    /// At most `max` connections at a time; `idle` and `partial` as above.
    pub fn new(max: usize, idle: Duration, partial: Duration) -> Self {
        Self {
            slots: Arc::new(Semaphore::new(max)),
            idle,
            partial,
        }
    }

    /// A slot for a new connection, or `None` at the cap (refuse it).
    pub fn admit(&self) -> Option<OwnedSemaphorePermit> {
        Arc::clone(&self.slots).try_acquire_owned().ok()
    }
}
