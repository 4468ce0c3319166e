//! The frames' way to an [`EmulatedSegment`] in the same process: a sent
//! frame is run through the segment at once and its reply waits in a
//! small ring until the time the segment says it comes back (at once, or
//! late when a test holds it), as a network interface would hand it over.

use std::sync::{Arc, Mutex, PoisonError};
use std::time::{Duration, Instant};

use crate::emulation::{EmulatedSegment, Reply};

/// Replies that may wait at once (more are dropped, as a full NIC ring).
const SLOTS: usize = 16;
/// Largest frame carried.
pub(crate) const FRAME_BYTES: usize = 1600;

#[derive(Debug)]
struct Slot {
    bytes: Box<[u8; FRAME_BYTES]>,
    len: usize,
    /// When the reply arrives; `None`: the slot is free.
    at: Option<Instant>,
}

/// An emulated segment as a port.
#[derive(Debug)]
pub struct EmulatedPort {
    segment: Arc<Mutex<EmulatedSegment>>,
    slots: Vec<Slot>,
}

impl EmulatedPort {
    /// A port onto `segment`.
    pub fn new(segment: Arc<Mutex<EmulatedSegment>>) -> Self {
        Self {
            segment,
            slots: (0..SLOTS)
                .map(|_| Slot {
                    bytes: Box::new([0; FRAME_BYTES]),
                    len: 0,
                    at: None,
                })
                .collect(),
        }
    }

    /// Runs `frame` through the segment; its reply (if any) is queued.
    pub fn send(&mut self, frame: &[u8]) {
        let Some(slot) = self.slots.iter_mut().find(|s| s.at.is_none()) else {
            return;
        };
        let Some(room) = slot.bytes.get_mut(..frame.len()) else {
            return;
        };
        room.copy_from_slice(frame);
        let reply = self
            .segment
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .process_in_place(room);
        if let Reply::After(delay) = reply {
            slot.len = frame.len();
            slot.at = Some(Instant::now() + delay);
        }
    }

    fn earliest(&self) -> Option<(usize, Instant)> {
        self.slots
            .iter()
            .enumerate()
            .filter_map(|(i, s)| s.at.map(|at| (i, at)))
            .min_by_key(|&(_, at)| at)
    }

    /// Copies the earliest reply that has arrived into `buf`.
    pub fn recv(&mut self, buf: &mut [u8]) -> Option<usize> {
        let (i, at) = self.earliest()?;
        if at > Instant::now() {
            return None;
        }
        let slot = &mut self.slots[i];
        slot.at = None;
        let n = slot.len.min(buf.len());
        buf[..n].copy_from_slice(&slot.bytes[..n]);
        Some(n)
    }

    /// Waits up to `timeout` for a reply to arrive.
    pub fn wait(&mut self, timeout: Duration) -> bool {
        let now = Instant::now();
        match self.earliest() {
            Some((_, at)) if at <= now => true,
            Some((_, at)) if at <= now + timeout => {
                std::thread::sleep(at - now);
                true
            }
            _ => {
                std::thread::sleep(timeout);
                false
            }
        }
    }
}
