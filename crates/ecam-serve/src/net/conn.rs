//! One accepted connection as the listeners hold it: its place in
//! [`crate::Connections`] (which decides caps and who makes room) and
//! the signal that closes it when the registry chooses it.

use std::sync::Arc;
use std::time::Instant;

use crate::{Closer, Kind, Registration, Shared};
use tokio::sync::Notify;

/// An admitted connection; it leaves the registry when the last clone is
/// dropped (an HTTP connection's task, or the live view it became).
#[derive(Clone)]
pub struct Conn {
    /// Its registration (activity, live-view upgrade).
    pub registration: Arc<Registration<Closer>>,
    close: Arc<Notify>,
}

impl Conn {
    /// Admits a connection of `kind`, closing the ones that make room.
    pub fn admit(shared: &Shared, kind: Kind) -> Self {
        let close = Arc::new(Notify::new());
        let notify = Arc::clone(&close);
        let closer: Closer = Arc::new(move || notify.notify_one());
        let (registration, evicted) = shared.connections.admit(kind, closer, Instant::now());
        evicted.iter().for_each(|close| close());
        Self {
            registration: Arc::new(registration),
            close,
        }
    }

    /// The client did something now.
    pub fn touch(&self) {
        self.registration.activity().touch(Instant::now());
    }

    /// Resolves when the registry chose this connection to make room.
    pub async fn closed(&self) {
        self.close.notified().await;
    }
}
