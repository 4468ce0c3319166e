//! The emulated ESC's mailbox (ETG1000.4 section 6.7.3): SM0 takes the
//! master's request, which the drive answers at once; SM1 hands out one
//! message at a time — a reply, an emergency — and the next waits in a
//! small queue until the master has read the one before (a read that
//! reaches the last byte of SM1 empties it).

/// Where SM0 (master → drive) starts.
pub const MAILBOX_OUT_START: u16 = 0x1000;
/// Where SM1 (drive → master) starts.
pub const MAILBOX_IN_START: u16 = 0x1080;
/// Bytes of each mailbox.
pub const MAILBOX_SIZE: usize = 128;
/// Messages that may wait for SM1 (more are dropped, as a drive whose
/// queue is full drops emergencies).
const WAITING: usize = 4;

/// Messages waiting for SM1, in a fixed ring (no allocation: the
/// emulation may run on the cycle's thread).
#[derive(Clone, Debug)]
pub(crate) struct Outbox {
    slots: [[u8; MAILBOX_SIZE]; WAITING],
    head: usize,
    len: usize,
    /// The drive's own mailbox counter (1–7).
    counter: u8,
}

impl Outbox {
    pub(crate) fn new() -> Self {
        Self {
            slots: [[0; MAILBOX_SIZE]; WAITING],
            head: 0,
            len: 0,
            counter: 0,
        }
    }

    /// A cleared slot at the back of the queue to write a message into;
    /// `None` when the queue is full.
    pub(crate) fn push(&mut self) -> Option<&mut [u8; MAILBOX_SIZE]> {
        if self.len == WAITING {
            return None;
        }
        let slot = &mut self.slots[(self.head + self.len) % WAITING];
        slot.fill(0);
        self.len += 1;
        Some(slot)
    }

    /// Moves the oldest message into `sm1`, with the drive's next counter
    /// value; false when none waits.
    pub(crate) fn pop_into(&mut self, sm1: &mut [u8]) -> bool {
        if self.len == 0 {
            return false;
        }
        let slot = &self.slots[self.head];
        let n = sm1.len().min(MAILBOX_SIZE);
        sm1[..n].copy_from_slice(&slot[..n]);
        self.counter = self.counter % 7 + 1;
        if let Some(b) = sm1.get_mut(5) {
            *b = (*b & 0x8F) | (self.counter << 4);
        }
        self.head = (self.head + 1) % WAITING;
        self.len -= 1;
        true
    }

    /// Drops every waiting message (the ESC went back to INIT).
    pub(crate) fn clear(&mut self) {
        self.len = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_wait_in_order_and_get_counters() {
        let mut o = Outbox::new();
        for k in 1..=5u8 {
            if let Some(slot) = o.push() {
                slot[6] = k;
            }
        }
        let mut sm1 = [0u8; MAILBOX_SIZE];
        let mut seen = Vec::new();
        while o.pop_into(&mut sm1) {
            seen.push((sm1[6], sm1[5] >> 4));
        }
        assert_eq!(
            seen,
            vec![(1, 1), (2, 2), (3, 3), (4, 4)],
            "the fifth dropped"
        );
        o.push();
        o.clear();
        assert!(!o.pop_into(&mut sm1));
    }
}
