//! The emulated segment on a network interface: a thread answers the
//! EtherCAT frames arriving on an interface (one end of a veth pair, or a
//! spare NIC cabled to the master's), so the master runs its ordinary
//! raw-socket path against the emulation.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::{self, JoinHandle};
use std::time::Duration;

use nix::sched::{CloneFlags, setns};
use pnet_datalink::Channel;

use super::EmulatedSegment;

/// The emulation answering on an interface; stops when dropped.
#[derive(Debug)]
pub struct WireEmulation {
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl WireEmulation {
    /// Answers EtherCAT frames on `interface` with `segment`. With
    /// `netns` (a file such as `/run/netns/NAME`) the thread first enters
    /// that network namespace, where the interface lives. Needs root or
    /// CAP_NET_RAW (and CAP_SYS_ADMIN for the namespace).
    pub fn spawn(
        interface: &str,
        netns: Option<PathBuf>,
        segment: Arc<Mutex<EmulatedSegment>>,
    ) -> std::io::Result<Self> {
        let stop = Arc::new(AtomicBool::new(false));
        let stop_thread = Arc::clone(&stop);
        let name = interface.to_string();
        let (ready_tx, ready_rx) = mpsc::channel::<std::io::Result<()>>();
        let thread = thread::Builder::new()
            .name("ecam-ethercat-emulated-wire".into())
            .spawn(move || {
                // The drives answer at once on a loaded host too: ask for
                // SCHED_FIFO (refusal falls back to normal scheduling).
                let _ = crate::rt::configure_current_thread(&crate::rt::RtConfig {
                    period: Duration::from_millis(1),
                    fifo_priority: Some(70),
                    cpu: None,
                });
                let opened = open(&name, netns.as_ref());
                let (mut tx, mut rx) = match opened {
                    Ok(pair) => {
                        let _ = ready_tx.send(Ok(()));
                        pair
                    }
                    Err(e) => {
                        let _ = ready_tx.send(Err(e));
                        return;
                    }
                };
                while !stop_thread.load(Ordering::Acquire) {
                    let Ok(frame) = rx.next() else {
                        continue; // read timeout: check the stop flag
                    };
                    // Our own replies pass this socket too; an ESC has
                    // set their locally-administered source bit.
                    if frame.len() < 14 || frame[6] & 0x02 != 0 {
                        continue;
                    }
                    let reply = segment
                        .lock()
                        .unwrap_or_else(PoisonError::into_inner)
                        .process_frame(frame);
                    if let Some(reply) = reply {
                        let _ = tx.send_to(&reply, None);
                    }
                }
            })?;
        match ready_rx.recv() {
            Ok(Ok(())) => Ok(Self {
                stop,
                thread: Some(thread),
            }),
            Ok(Err(e)) => {
                let _ = thread.join();
                Err(e)
            }
            Err(_) => Err(std::io::Error::other("emulation thread ended during start")),
        }
    }
}

type Pair = (
    Box<dyn pnet_datalink::DataLinkSender>,
    Box<dyn pnet_datalink::DataLinkReceiver>,
);

fn open(name: &str, netns: Option<&PathBuf>) -> std::io::Result<Pair> {
    if let Some(path) = netns {
        let file = std::fs::File::open(path)?;
        setns(&file, CloneFlags::CLONE_NEWNET).map_err(std::io::Error::from)?;
    }
    let interface = pnet_datalink::interfaces()
        .into_iter()
        .find(|i| i.name == name)
        .ok_or_else(|| {
            std::io::Error::new(
                std::io::ErrorKind::NotFound,
                format!("no interface {name:?}"),
            )
        })?;
    let config = pnet_datalink::Config {
        read_timeout: Some(Duration::from_millis(10)),
        promiscuous: true,
        ..pnet_datalink::Config::default()
    };
    match pnet_datalink::channel(&interface, config)? {
        Channel::Ethernet(tx, rx) => Ok((tx, rx)),
        _ => Err(std::io::Error::other("not an Ethernet interface")),
    }
}

impl Drop for WireEmulation {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Release);
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}
