//! The raw socket a segment's frames travel on (`AF_PACKET`, Linux).
//!
//! Opened here rather than through ethercrab's `tx_rx_task`, so the
//! thread that runs the cycle sends and receives the frames itself: no
//! other thread (ethercrab's task, async-io's reactor) stands between a
//! reply and the cycle that waits for it.

use std::io;
use std::os::fd::{AsRawFd, IntoRawFd, OwnedFd};
use std::time::Duration;

use nix::errno::Errno;
use nix::poll::{PollFd, PollFlags, ppoll};
use nix::sys::socket::{AddressFamily, MsgFlags, SockFlag, SockProtocol, SockType, recv, send};
use nix::sys::time::TimeSpec;

/// A packet socket bound to one interface.
pub struct RawSocket {
    /// Our handle on the socket (a duplicate of the one pnet bound).
    fd: OwnedFd,
    /// pnet's halves own the bound descriptor; kept so it stays open.
    _pnet: (
        Box<dyn pnet_datalink::DataLinkSender>,
        Box<dyn pnet_datalink::DataLinkReceiver>,
    ),
}

impl core::fmt::Debug for RawSocket {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("RawSocket").field("fd", &self.fd).finish()
    }
}

impl RawSocket {
    /// Opens a raw socket on `interface` (needs root or `CAP_NET_RAW`).
    pub fn open(interface: &str) -> io::Result<Self> {
        let found = pnet_datalink::interfaces()
            .into_iter()
            .find(|i| i.name == interface)
            .ok_or_else(|| {
                io::Error::new(
                    io::ErrorKind::NotFound,
                    format!("no interface {interface:?}"),
                )
            })?;
        let socket = nix::sys::socket::socket(
            AddressFamily::Packet,
            SockType::Raw,
            SockFlag::SOCK_NONBLOCK,
            SockProtocol::EthAll,
        )?;
        let fd = nix::unistd::dup(&socket)?;
        // pnet binds the socket to the interface (the one step that needs
        // a raw sockaddr); both descriptors share the binding.
        let config = pnet_datalink::Config {
            read_timeout: Some(Duration::ZERO),
            write_timeout: Some(Duration::ZERO),
            socket_fd: Some(socket.into_raw_fd()),
            ..pnet_datalink::Config::default()
        };
        match pnet_datalink::channel(&found, config)? {
            pnet_datalink::Channel::Ethernet(tx, rx) => Ok(Self {
                fd,
                _pnet: (tx, rx),
            }),
            _ => Err(io::Error::other("not an Ethernet interface")),
        }
    }

    /// Sends one frame; never blocks.
    pub fn send(&self, frame: &[u8]) -> io::Result<()> {
        send(self.fd.as_raw_fd(), frame, MsgFlags::MSG_DONTWAIT)?;
        Ok(())
    }

    /// Reads one waiting frame into `buf`: its length, or `None` when
    /// nothing waits.
    pub fn recv(&self, buf: &mut [u8]) -> io::Result<Option<usize>> {
        match recv(self.fd.as_raw_fd(), buf, MsgFlags::MSG_DONTWAIT) {
            Ok(n) => Ok(Some(n)),
            Err(Errno::EAGAIN | Errno::EINTR) => Ok(None),
            Err(e) => Err(e.into()),
        }
    }

    /// Waits up to `timeout` for a frame to read; true when one waits.
    pub fn wait(&self, timeout: Duration) -> bool {
        let mut fds = [PollFd::new(
            std::os::fd::AsFd::as_fd(&self.fd),
            PollFlags::POLLIN,
        )];
        matches!(
            ppoll(&mut fds, Some(TimeSpec::from_duration(timeout)), None),
            Ok(n) if n > 0
        )
    }
}
