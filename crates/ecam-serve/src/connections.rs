//! Who is connected, and who makes room when a cap is full.
//!
//! Every connection counts against the cap of its kind ([`Caps`]): Modbus
//! clients against the Modbus cap, HTTP connections against the HTTP cap,
//! and a live view (an HTTP connection upgraded to a WebSocket) against
//! both the HTTP cap and the live-view cap. When a newcomer finds its cap
//! full, the *idlest* connection of that cap is closed to make room: the
//! one whose client has been silent longest, those with a request being
//! worked on last. So a full cap never locks anyone out: a hundred silent
//! sockets, or sixty-four clients that ask once a minute, give way to the
//! operator panel that connects now, while a client that keeps asking
//! is never the one to go.
//!
//! Sans-IO: the server says when a client did something
//! ([`Activity::touch`]) and closes the connections this registry hands
//! back (`H`, whatever lets the server close one: a notifier, a channel).

use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

use crate::sync::lock;

/// What a connection is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A Modbus TCP client.
    Modbus,
    /// An HTTP connection (requests, keep-alive).
    Http,
    /// An HTTP connection upgraded to the live view's WebSocket.
    Live,
}

impl Kind {
    /// Whether a connection of this kind counts against the cap of `cap`.
    fn counts_for(self, cap: Kind) -> bool {
        match cap {
            Kind::Modbus => self == Kind::Modbus,
            Kind::Http => matches!(self, Kind::Http | Kind::Live),
            Kind::Live => self == Kind::Live,
        }
    }
}

/// Most connections of each kind kept at once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Caps {
    /// Modbus clients.
    pub modbus: usize,
    /// HTTP connections, live views included.
    pub http: usize,
    /// Live views.
    pub live: usize,
}

impl Caps {
    fn of(&self, kind: Kind) -> usize {
        match kind {
            Kind::Modbus => self.modbus,
            Kind::Http => self.http,
            Kind::Live => self.live,
        }
    }
}

/// When a connection's client last did something, and whether a request
/// of it is being worked on.
#[derive(Debug)]
pub struct Activity {
    epoch: Instant,
    /// ms from `epoch` to the client's last sign of life.
    last_ms: AtomicU64,
    /// Requests of this connection being worked on.
    busy: AtomicUsize,
}

impl Activity {
    fn new(epoch: Instant, now: Instant) -> Self {
        let activity = Self {
            epoch,
            last_ms: AtomicU64::new(0),
            busy: AtomicUsize::new(0),
        };
        activity.touch(now);
        activity
    }

    fn ms(&self, at: Instant) -> u64 {
        u64::try_from(at.saturating_duration_since(self.epoch).as_millis()).unwrap_or(u64::MAX)
    }

    /// The client did something at `now` (sent a request, answered a ping).
    pub fn touch(&self, now: Instant) {
        self.last_ms.fetch_max(self.ms(now), Ordering::Relaxed);
    }

    /// How long the client has been silent at `now`.
    pub fn idle_for(&self, now: Instant) -> Duration {
        Duration::from_millis(
            self.ms(now)
                .saturating_sub(self.last_ms.load(Ordering::Relaxed)),
        )
    }

    /// Marks a request as being worked on until the guard is dropped: the
    /// connection goes last when room must be made.
    pub fn busy(self: &Arc<Self>) -> Busy {
        self.busy.fetch_add(1, Ordering::Relaxed);
        Busy(Arc::clone(self))
    }

    fn is_busy(&self) -> bool {
        self.busy.load(Ordering::Relaxed) > 0
    }
}

/// A request being worked on (see [`Activity::busy`]).
#[derive(Debug)]
pub struct Busy(Arc<Activity>);

impl Drop for Busy {
    fn drop(&mut self) {
        self.0.busy.fetch_sub(1, Ordering::Relaxed);
    }
}

struct Open<H> {
    id: u64,
    kind: Kind,
    activity: Arc<Activity>,
    handle: H,
}

struct Table<H> {
    next_id: u64,
    open: Vec<Open<H>>,
    admitted: [u64; 3],
    evicted: [u64; 3],
}

fn slot(kind: Kind) -> usize {
    match kind {
        Kind::Modbus => 0,
        Kind::Http => 1,
        Kind::Live => 2,
    }
}

impl<H> Table<H> {
    fn count(&self, cap: Kind) -> usize {
        self.open.iter().filter(|o| o.kind.counts_for(cap)).count()
    }

    /// Removes the idlest connection that counts against `cap`, but
    /// `keep`; busy ones go last.
    fn evict_idlest(&mut self, cap: Kind, keep: Option<u64>, now: Instant) -> Option<H> {
        let at = self
            .open
            .iter()
            .enumerate()
            .filter(|(_, o)| o.kind.counts_for(cap) && Some(o.id) != keep)
            .max_by_key(|(_, o)| {
                (
                    !o.activity.is_busy(),
                    o.activity.idle_for(now),
                    std::cmp::Reverse(o.id),
                )
            })
            .map(|(at, _)| at)?;
        let gone = self.open.swap_remove(at);
        self.evicted[slot(gone.kind)] += 1;
        Some(gone.handle)
    }

    /// Makes room under `cap` for one more (keeping `keep`).
    fn make_room(&mut self, caps: Caps, cap: Kind, keep: Option<u64>, now: Instant) -> Vec<H> {
        let mut evicted = Vec::new();
        while self.count(cap) >= caps.of(cap).max(1) {
            match self.evict_idlest(cap, keep, now) {
                Some(handle) => evicted.push(handle),
                None => break,
            }
        }
        evicted
    }
}

/// The open connections of a server, by kind.
pub struct Connections<H> {
    caps: Caps,
    epoch: Instant,
    table: Mutex<Table<H>>,
}

/// A connection admitted (see [`Connections::admit`]); it leaves the
/// registry when this is dropped.
pub struct Registration<H> {
    id: u64,
    activity: Arc<Activity>,
    registry: Arc<Connections<H>>,
}

impl<H> Registration<H> {
    /// This connection's activity.
    pub fn activity(&self) -> &Arc<Activity> {
        &self.activity
    }

    /// The connection becomes a live view: it now counts against the
    /// live-view cap too, and the connections closed to make room are
    /// returned.
    pub fn become_live(&self, now: Instant) -> Vec<H> {
        let mut table = lock(&self.registry.table);
        let evicted = table.make_room(self.registry.caps, Kind::Live, Some(self.id), now);
        if let Some(open) = table.open.iter_mut().find(|o| o.id == self.id) {
            if open.kind != Kind::Live {
                open.kind = Kind::Live;
                table.admitted[slot(Kind::Live)] += 1;
            }
        }
        evicted
    }
}

impl<H> Drop for Registration<H> {
    fn drop(&mut self) {
        let mut table = lock(&self.registry.table);
        if let Some(at) = table.open.iter().position(|o| o.id == self.id) {
            table.open.swap_remove(at);
        }
    }
}

impl<H> Connections<H> {
    /// A registry keeping at most `caps` connections.
    pub fn new(caps: Caps) -> Self {
        Self {
            caps,
            epoch: Instant::now(),
            table: Mutex::new(Table {
                next_id: 0,
                open: Vec::new(),
                admitted: [0; 3],
                evicted: [0; 3],
            }),
        }
    }

    /// The caps.
    pub fn caps(&self) -> Caps {
        self.caps
    }

    /// Admits a new connection of `kind` at `now`, closed through `handle`
    /// when it must make room later; returns its registration and the
    /// connections to close now to make room for it (the idlest of its
    /// cap, when the cap is full).
    pub fn admit(
        self: &Arc<Self>,
        kind: Kind,
        handle: H,
        now: Instant,
    ) -> (Registration<H>, Vec<H>) {
        let mut table = lock(&self.table);
        let mut evicted = table.make_room(self.caps, kind, None, now);
        if kind == Kind::Live {
            evicted.extend(table.make_room(self.caps, Kind::Http, None, now));
        }
        let id = table.next_id;
        table.next_id += 1;
        let activity = Arc::new(Activity::new(self.epoch, now));
        table.open.push(Open {
            id,
            kind,
            activity: Arc::clone(&activity),
            handle,
        });
        table.admitted[slot(kind)] += 1;
        drop(table);
        (
            Registration {
                id,
                activity,
                registry: Arc::clone(self),
            },
            evicted,
        )
    }

    /// Connections of `kind` open now.
    pub fn open(&self, kind: Kind) -> usize {
        lock(&self.table)
            .open
            .iter()
            .filter(|o| o.kind == kind)
            .count()
    }

    /// For `GET /api/status`: per kind, open now, admitted and closed to
    /// make room since the start, and the cap.
    pub fn json(&self) -> Value {
        let table = lock(&self.table);
        let kind = |kind: Kind| {
            json!({
                "open": table.open.iter().filter(|o| o.kind == kind).count(),
                "cap": self.caps.of(kind),
                "admitted": table.admitted[slot(kind)],
                "closed_for_room": table.evicted[slot(kind)],
            })
        };
        json!({"modbus": kind(Kind::Modbus), "http": kind(Kind::Http), "live": kind(Kind::Live)})
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    const CAPS: Caps = Caps {
        modbus: 3,
        http: 3,
        live: 2,
    };

    fn at(t0: Instant, ms: u64) -> Instant {
        t0 + Duration::from_millis(ms)
    }

    #[test]
    fn a_full_cap_closes_the_idlest_for_the_newcomer() {
        let registry = Arc::new(Connections::new(CAPS));
        let t0 = Instant::now();
        let (a, none) = registry.admit(Kind::Modbus, "a", at(t0, 0));
        let (b, _) = registry.admit(Kind::Modbus, "b", at(t0, 10));
        let (c, _) = registry.admit(Kind::Modbus, "c", at(t0, 20));
        assert!(none.is_empty());
        // "a" asked last; "b" has been silent longest.
        a.activity().touch(at(t0, 50_000));
        c.activity().touch(at(t0, 40_000));
        let (_d, evicted) = registry.admit(Kind::Modbus, "d", at(t0, 60_000));
        assert_eq!(evicted, ["b"]);
        assert_eq!(registry.open(Kind::Modbus), 3);
        drop(b); // closing the evicted one later changes nothing
        assert_eq!(registry.open(Kind::Modbus), 3);
        // HTTP has its own cap.
        let (_h, evicted) = registry.admit(Kind::Http, "h", at(t0, 60_000));
        assert!(evicted.is_empty());
    }

    #[test]
    fn busy_connections_go_last_and_a_freed_slot_needs_no_eviction() {
        let registry = Arc::new(Connections::new(CAPS));
        let t0 = Instant::now();
        let (a, _) = registry.admit(Kind::Http, "a", at(t0, 0));
        let (b, _) = registry.admit(Kind::Http, "b", at(t0, 1000));
        let (_c, _) = registry.admit(Kind::Http, "c", at(t0, 2000));
        let working = a.activity().busy();
        let (_d, evicted) = registry.admit(Kind::Http, "d", at(t0, 3000));
        assert_eq!(evicted, ["b"], "a computes a design: b goes");
        drop(working);
        drop(b);
        drop(_d);
        let (_e, evicted) = registry.admit(Kind::Http, "e", at(t0, 4000));
        assert!(evicted.is_empty());
    }

    #[test]
    fn live_views_count_against_both_caps() {
        let registry = Arc::new(Connections::new(CAPS));
        let t0 = Instant::now();
        let (h, _) = registry.admit(Kind::Http, "h", at(t0, 0));
        let (l1, _) = registry.admit(Kind::Http, "l1", at(t0, 1));
        assert!(l1.become_live(at(t0, 2)).is_empty());
        let (l2, _) = registry.admit(Kind::Http, "l2", at(t0, 3));
        assert!(l2.become_live(at(t0, 4)).is_empty());
        h.activity().touch(at(t0, 5000));
        l2.activity().touch(at(t0, 5000));
        // The HTTP cap (3) is full: l1, silent since it opened, goes.
        let (l3, evicted) = registry.admit(Kind::Http, "l3", at(t0, 6000));
        assert_eq!(evicted, ["l1"]);
        assert!(l3.become_live(at(t0, 6000)).is_empty(), "2 live views fit");
        let (l4, evicted) = registry.admit(Kind::Http, "l4", at(t0, 7000));
        assert_eq!(evicted, ["h"], "h and l2 tie; the older goes");
        // The live cap (2) is full: l2 is its idlest.
        assert_eq!(l4.become_live(at(t0, 7000)), ["l2"]);
        assert_eq!(registry.open(Kind::Live), 2);
        let status = registry.json();
        assert_eq!(status["live"]["closed_for_room"], 2);
        assert_eq!(status["http"]["closed_for_room"], 1);
        assert_eq!(status["live"]["open"], 2);
    }
}
