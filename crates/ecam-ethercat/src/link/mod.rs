//! The frames' way between ethercrab and the drives, driven by the thread
//! that waits for them.
//!
//! ethercrab's own `tx_rx_task` runs on a thread of its own behind
//! async-io's reactor, ends for good on the first reply it cannot place
//! (a late one), and leaves retransmitting a lost frame to a timeout of
//! tens of milliseconds. ecam does not use it: the caller's thread (the
//! real-time cycle once the segment runs) sends the frames ethercrab has
//! queued and reads the replies itself, with a deadline of its own. There
//! is no frame task left to die; a failing socket is counted and opened
//! again.
//!
//! Two ethercrab frame loops share the wire: the **acyclic** one (bring-up,
//! SDOs, state changes: ethercrab's timeouts and retries apply) and the
//! **cyclic** one (process data: no timeout of ethercrab's, no retry; the
//! cycle drops what has not come back by its deadline). Every frame
//! leaves with a tag in its source MAC address (loop and sequence number),
//! so a reply is handed only to the frame that is still waiting for it: a
//! late reply to a frame the cycle gave up on, or to a transmission
//! ethercrab has repeated, is discarded and counted, never mistaken for
//! the answer to a newer frame.

mod emulated;
mod socket;

use std::future::Future;
use std::pin::pin;
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll, Waker};
use std::time::{Duration, Instant};

use ethercrab::{PduRx, PduTx};

use crate::emulation::EmulatedSegment;
pub use emulated::EmulatedPort;
use emulated::FRAME_BYTES;
pub use socket::RawSocket;

/// EtherType of EtherCAT frames.
const ETHERCAT: [u8; 2] = [0x88, 0xA4];
/// Offset of the first datagram's index in an EtherCAT frame (Ethernet
/// header, EtherCAT header, command byte).
const FIRST_PDU_INDEX: usize = 14 + 2 + 1;
/// Source MAC byte 0 as ethercrab sends it; the first ESC sets bit 1
/// (locally administered) on the way back.
const PASSED_AN_ESC: u8 = 0x02;
/// Byte 1 of the source MAC marks the loop: these two values.
const LOOP_TAGS: [u8; 2] = [0xA0, 0xA1];
/// How often a vanished interface is looked for again.
const REOPEN_EVERY: Duration = Duration::from_millis(100);

/// Which of the two frame loops.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoopId {
    /// Bring-up, mailbox and state traffic.
    Acyclic = 0,
    /// Process data, once per cycle.
    Cyclic = 1,
}

/// Where frames go.
#[derive(Debug)]
enum Port {
    Socket {
        interface: String,
        socket: Option<RawSocket>,
        last_open: Instant,
    },
    Emulated(EmulatedPort),
}

/// Counts of the link since it opened.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LinkStats {
    /// Frames sent.
    pub sent: u64,
    /// Replies handed to the frame waiting for them.
    pub replies: u64,
    /// Replies that came back after their frame was given up (or a newer
    /// transmission answered): discarded.
    pub late_discarded: u64,
    /// Frames the interface refused to send (link down, no such device).
    pub send_errors: u64,
    /// Times the socket was opened again after the interface vanished.
    pub reopened: u64,
}

struct FrameLoop {
    tx: PduTx<'static>,
    rx: PduRx<'static>,
    /// The tag of the last transmission of each frame still waiting,
    /// by the index of its first datagram.
    waiting: [Option<u32>; 256],
}

/// Both frame loops and the port; the owner's thread moves the frames.
pub struct Link {
    port: Port,
    loops: [FrameLoop; 2],
    sequence: u32,
    buffer: Box<[u8; FRAME_BYTES]>,
    stats: LinkStats,
}

impl core::fmt::Debug for Link {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Link")
            .field("port", &self.port)
            .field("stats", &self.stats)
            .finish()
    }
}

/// Neither an interface nor emulated drives were given: there is no way to
/// the drives (the configuration file names itself in front of this).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NoTransport;

impl std::fmt::Display for NoTransport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("no interface; set interface = \"...\" or pass --emulated N")
    }
}

impl std::error::Error for NoTransport {}

/// A chosen transport and, when emulated, the segment (to inject faults).
pub type Chosen = (Transport, Option<Arc<Mutex<EmulatedSegment>>>);

/// The way to the drives a link opens.
#[derive(Clone, Debug)]
pub enum Transport {
    /// A network interface (raw socket; needs CAP_NET_RAW).
    Interface(String),
    /// An emulated segment in this process.
    Emulated(Arc<Mutex<EmulatedSegment>>),
}

impl Transport {
    /// `emulated` drives in this process (returned too, to inject faults),
    /// or else the configuration's `interface`; `None` when neither is
    /// given.
    pub fn choose(
        emulated: Option<u16>,
        interface: Option<&str>,
    ) -> Option<(Self, Option<Arc<Mutex<EmulatedSegment>>>)> {
        match (emulated, interface) {
            (Some(n), _) => {
                let segment = Arc::new(Mutex::new(EmulatedSegment::new(
                    usize::from(n),
                    crate::emulation::DriveBehaviour::default(),
                )));
                Some((Self::Emulated(Arc::clone(&segment)), Some(segment)))
            }
            (None, Some(interface)) => Some((Self::Interface(interface.to_string()), None)),
            (None, None) => None,
        }
    }

    /// [`Transport::choose`], or why there is no way to the drives.
    ///
    /// # Errors
    /// [`NoTransport`]: neither `emulated` nor `interface` is given.
    pub fn chosen(emulated: Option<u16>, interface: Option<&str>) -> Result<Chosen, NoTransport> {
        Self::choose(emulated, interface).ok_or(NoTransport)
    }

    /// The transport in words: the interface, or `emulated (N drives)`.
    pub fn describe(&self) -> String {
        match self {
            Self::Interface(name) => name.clone(),
            Self::Emulated(segment) => format!(
                "emulated ({} drives)",
                segment
                    .lock()
                    .unwrap_or_else(std::sync::PoisonError::into_inner)
                    .escs()
                    .len()
            ),
        }
    }
}

impl Link {
    /// Opens the transport for the two loops.
    ///
    /// # Errors
    /// The interface cannot be opened.
    pub fn open(
        transport: Transport,
        acyclic: (PduTx<'static>, PduRx<'static>),
        cyclic: (PduTx<'static>, PduRx<'static>),
    ) -> std::io::Result<Self> {
        let port = match transport {
            Transport::Interface(interface) => Port::Socket {
                socket: Some(RawSocket::open(&interface)?),
                interface,
                last_open: Instant::now(),
            },
            Transport::Emulated(segment) => Port::Emulated(EmulatedPort::new(segment)),
        };
        let frame_loop = |(tx, rx)| FrameLoop {
            tx,
            rx,
            waiting: [None; 256],
        };
        Ok(Self {
            port,
            loops: [frame_loop(acyclic), frame_loop(cyclic)],
            sequence: 0,
            buffer: Box::new([0; FRAME_BYTES]),
            stats: LinkStats::default(),
        })
    }

    /// Counts since the link opened.
    pub fn stats(&self) -> LinkStats {
        self.stats
    }

    /// Sends every frame either loop has queued.
    pub fn flush(&mut self) {
        for id in [LoopId::Cyclic, LoopId::Acyclic] {
            while let Some(frame) = self.loops[id as usize].tx.next_sendable_frame() {
                self.sequence = self.sequence.wrapping_add(1);
                let tag = self.sequence;
                let buffer = &mut self.buffer;
                let mut sent_len = 0;
                let result = frame.send_blocking(|bytes| {
                    let Some(out) = buffer.get_mut(..bytes.len()) else {
                        return Err(ethercrab::error::Error::SendFrame);
                    };
                    out.copy_from_slice(bytes);
                    if let Some(mac) = out.get_mut(7..12) {
                        mac[0] = LOOP_TAGS[id as usize];
                        mac[1..].copy_from_slice(&tag.to_be_bytes());
                    }
                    sent_len = bytes.len();
                    Ok(bytes.len())
                });
                if result.is_err() {
                    continue;
                }
                // ethercrab counts the frame as sent; if the wire refuses
                // it, its reply never comes and the waiting side decides.
                let first = usize::from(self.buffer.get(FIRST_PDU_INDEX).copied().unwrap_or(0));
                self.loops[id as usize].waiting[first] = Some(tag);
                match port_send(&mut self.port, &self.buffer[..sent_len], &mut self.stats) {
                    Ok(()) => self.stats.sent += 1,
                    Err(()) => self.stats.send_errors += 1,
                }
            }
        }
    }

    /// Waits until `deadline` for a reply and hands every reply that has
    /// arrived to its frame; true when at least one was handed over.
    pub fn pump(&mut self, deadline: Instant) -> bool {
        let mut delivered = false;
        loop {
            while let Some(n) = self.receive() {
                delivered |= self.deliver(n);
            }
            if delivered {
                return true;
            }
            let now = Instant::now();
            if now >= deadline || !self.wait(deadline - now) {
                // One last look: a reply may have landed with the timeout.
                while let Some(n) = self.receive() {
                    delivered |= self.deliver(n);
                }
                return delivered;
            }
        }
    }

    /// Forgets the frames of `id` still waiting: a reply that comes for
    /// them later is discarded.
    pub fn forget(&mut self, id: LoopId) {
        self.loops[id as usize].waiting = [None; 256];
    }

    /// Hands a received frame to the loop and frame waiting for it.
    fn deliver(&mut self, n: usize) -> bool {
        let frame = &self.buffer[..n];
        if n <= FIRST_PDU_INDEX || frame[12..14] != ETHERCAT || frame[6] & PASSED_AN_ESC == 0 {
            // Not EtherCAT, or our own frame on its way out.
            return false;
        }
        let Some(id) = LOOP_TAGS.iter().position(|&t| t == frame[7]) else {
            return false;
        };
        let tag = u32::from_be_bytes([frame[8], frame[9], frame[10], frame[11]]);
        let first = usize::from(frame[FIRST_PDU_INDEX]);
        let frame_loop = &mut self.loops[id];
        if frame_loop.waiting[first] != Some(tag) {
            self.stats.late_discarded += 1;
            return false;
        }
        frame_loop.waiting[first] = None;
        match frame_loop.rx.receive_frame(frame) {
            Ok(_) => {
                self.stats.replies += 1;
                true
            }
            Err(_) => {
                self.stats.late_discarded += 1;
                false
            }
        }
    }

    fn receive(&mut self) -> Option<usize> {
        match &mut self.port {
            Port::Emulated(port) => port.recv(&mut self.buffer[..]),
            Port::Socket { socket, .. } => socket
                .as_ref()?
                .recv(&mut self.buffer[..])
                .unwrap_or_default(),
        }
    }

    fn wait(&mut self, timeout: Duration) -> bool {
        match &mut self.port {
            Port::Emulated(port) => port.wait(timeout),
            Port::Socket {
                socket: Some(socket),
                ..
            } => socket.wait(timeout),
            Port::Socket { socket: None, .. } => {
                std::thread::sleep(timeout);
                false
            }
        }
    }
}

/// Sends one frame; a socket whose interface has vanished is opened again
/// (at most every [`REOPEN_EVERY`]).
fn port_send(port: &mut Port, frame: &[u8], stats: &mut LinkStats) -> Result<(), ()> {
    match port {
        Port::Emulated(port) => {
            port.send(frame);
            Ok(())
        }
        Port::Socket {
            interface,
            socket,
            last_open,
        } => {
            if socket.is_none() && last_open.elapsed() >= REOPEN_EVERY {
                *last_open = Instant::now();
                if let Ok(opened) = RawSocket::open(interface) {
                    *socket = Some(opened);
                    stats.reopened += 1;
                }
            }
            let Some(open) = socket.as_ref() else {
                return Err(());
            };
            match open.send(frame) {
                Ok(()) => Ok(()),
                Err(e) => {
                    // ENODEV/ENXIO: the interface is gone (deleted or
                    // renamed); look for it again. ENETDOWN: wait for it.
                    if matches!(e.raw_os_error(), Some(19) | Some(6)) {
                        *socket = None;
                        *last_open = Instant::now();
                    }
                    Err(())
                }
            }
        }
    }
}

/// How long [`run`] waits for a reply before polling the future again
/// (ethercrab's timers are checked when it is polled).
const POLL_EVERY: Duration = Duration::from_millis(1);

/// Runs an ethercrab future to completion on this thread, moving its
/// frames through `link`. `None` when `deadline` passes first (the future
/// is dropped: its frames are released and their replies will be
/// discarded).
pub fn run<F: Future>(link: &mut Link, future: F, deadline: Instant) -> Option<F::Output> {
    let mut future = pin!(future);
    let mut cx = Context::from_waker(Waker::noop());
    loop {
        if let Poll::Ready(out) = future.as_mut().poll(&mut cx) {
            return Some(out);
        }
        link.flush();
        let now = Instant::now();
        if now >= deadline {
            return None;
        }
        link.pump(deadline.min(now + POLL_EVERY));
    }
}
