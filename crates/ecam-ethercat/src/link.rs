//! Carries ethercrab's frames to an [`EmulatedSegment`] in the same
//! process: a thread takes each frame ethercrab queues (`PduTx`), runs it
//! through the segment and hands the reply back (`PduRx`), as a network
//! interface would.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::task::{Wake, Waker};
use std::thread::{self, JoinHandle, Thread};
use std::time::Duration;

use ethercrab::{PduRx, PduTx};

use crate::emulation::EmulatedSegment;
use crate::rt::{RtConfig, configure_current_thread};

/// Wakes the link thread when ethercrab queues a frame.
struct Unpark(Thread);

impl Wake for Unpark {
    fn wake(self: Arc<Self>) {
        self.0.unpark();
    }

    fn wake_by_ref(self: &Arc<Self>) {
        self.0.unpark();
    }
}

/// The running in-process link; stops its thread when dropped.
#[derive(Debug)]
pub struct InProcessLink {
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl InProcessLink {
    /// Starts the link thread between ethercrab and `segment`.
    pub fn spawn(
        mut tx: PduTx<'static>,
        mut rx: PduRx<'static>,
        segment: Arc<Mutex<EmulatedSegment>>,
        rt: RtConfig,
    ) -> std::io::Result<Self> {
        let stop = Arc::new(AtomicBool::new(false));
        let stop_thread = Arc::clone(&stop);
        let thread = thread::Builder::new()
            .name("ecam-ethercat-emulated-link".into())
            .spawn(move || {
                // Refusal falls back to normal scheduling.
                let _ = configure_current_thread(&rt);
                let waker = Waker::from(Arc::new(Unpark(thread::current())));
                while !stop_thread.load(Ordering::Acquire) && !tx.should_exit() {
                    tx.replace_waker(&waker);
                    let mut busy = false;
                    while let Some(frame) = tx.next_sendable_frame() {
                        busy = true;
                        let mut reply = None;
                        let sent = frame.send_blocking(|bytes| {
                            let mut segment =
                                segment.lock().unwrap_or_else(PoisonError::into_inner);
                            reply = segment.process_frame(bytes);
                            Ok(bytes.len())
                        });
                        if let (Ok(_), Some(reply)) = (sent, reply) {
                            // A reply ethercrab no longer waits for (timed
                            // out) is dropped, as on a real interface.
                            let _ = rx.receive_frame(&reply);
                        }
                    }
                    if !busy {
                        thread::park_timeout(Duration::from_millis(1));
                    }
                }
            })?;
        Ok(Self {
            stop,
            thread: Some(thread),
        })
    }
}

impl Drop for InProcessLink {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Release);
        if let Some(thread) = self.thread.take() {
            thread.thread().unpark();
            let _ = thread.join();
        }
    }
}
