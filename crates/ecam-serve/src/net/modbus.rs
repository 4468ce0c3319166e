//! The Modbus TCP listener: one task per client, reading MBAP frames and
//! answering them through [`crate`] (framing, codec, address map and
//! writes are all there; `docs/modbus.md` describes them).
//!
//! Refused writes are logged as warnings (target `ecam::modbus`). Every
//! request and its answer can be logged too, like a Modbus monitor's
//! communication window: target [`TRAFFIC`] at trace level, switched on by
//! `ecam serve --trace-modbus` or `RUST_LOG=ecam::modbus::traffic=trace`.

use std::io;
use std::sync::Arc;
use std::sync::atomic::Ordering;

use crate::{Exception, Kind, MbapHeader, Shared, answer_request, encode_response, parse_request};
use tokio::io::{AsyncReadExt as _, AsyncWriteExt as _};
use tokio::net::{TcpListener, TcpStream};
use tokio::time::timeout;

use super::conn::Conn;

/// The tracing target of the request/response log.
pub const TRAFFIC: &str = "ecam::modbus::traffic";

/// Accepts clients on `listener` for ever, within the server's limits: at
/// the cap, the idlest client makes room for the newcomer.
pub async fn serve(listener: TcpListener, shared: Arc<Shared>) {
    loop {
        match listener.accept().await {
            Ok((stream, peer)) => {
                let conn = Conn::admit(&shared, Kind::Modbus);
                shared
                    .stats
                    .modbus_connections
                    .fetch_add(1, Ordering::Relaxed);
                let shared = Arc::clone(&shared);
                tracing::debug!(target: "ecam::modbus", "client {peer} connected");
                tokio::spawn(async move {
                    tokio::select! {
                        () = connection(stream, &shared, &conn) => {}
                        () = conn.closed() => {
                            tracing::debug!(target: "ecam::modbus", "client {peer} closed to make room");
                        }
                    }
                    tracing::debug!(target: "ecam::modbus", "client {peer} gone");
                });
            }
            Err(err) => {
                // Out of file descriptors and the like: wait, do not spin.
                tracing::error!(target: "ecam::modbus", "accept: {err}");
                tokio::time::sleep(std::time::Duration::from_millis(100)).await;
            }
        }
    }
}

/// Serves one client until it disconnects, idles past the limit, sends half
/// a frame and stops, or sends something that is not Modbus.
async fn connection(mut stream: TcpStream, shared: &Arc<Shared>, conn: &Conn) {
    let _ = stream.set_nodelay(true);
    // Errors only mean the client went away (or was sent away).
    let _ = requests(&mut stream, shared, conn).await;
}

async fn requests(stream: &mut TcpStream, shared: &Arc<Shared>, conn: &Conn) -> io::Result<()> {
    let limits = shared.info.limits;
    let mut header = [0u8; MbapHeader::LEN];
    loop {
        // Idle between requests: up to `idle`; once a frame has begun, the
        // rest of it must follow within `partial`.
        let first = timeout(limits.idle, stream.read_exact(&mut header[..1]))
            .await
            .map_err(|_| io::ErrorKind::TimedOut)?;
        first?;
        timeout(limits.partial, stream.read_exact(&mut header[1..]))
            .await
            .map_err(|_| io::ErrorKind::TimedOut)??;
        let Some(header) = MbapHeader::parse(header) else {
            shared.stats.modbus_garbage.fetch_add(1, Ordering::Relaxed);
            return Ok(());
        };
        let mut request_pdu = vec![0u8; header.pdu_len];
        timeout(limits.partial, stream.read_exact(&mut request_pdu))
            .await
            .map_err(|_| io::ErrorKind::TimedOut)??;
        // A whole request: this client is not idle.
        conn.touch();
        let function = request_pdu.first().copied().unwrap_or(0);
        let parsed = parse_request(&request_pdu);
        let peer = stream.peer_addr().ok();
        let who = Who {
            peer,
            transaction: header.transaction,
            unit: header.unit,
        };
        match &parsed {
            Ok(request) => tracing::trace!(target: TRAFFIC, "{who} > {request}"),
            Err(_) => tracing::trace!(
                target: TRAFFIC,
                "{who} > {function:02X} (not understood: {} PDU bytes)",
                request_pdu.len()
            ),
        }
        let written =
            matches!(&parsed, Ok(r) if r.is_write()) || WRITE_FUNCTIONS.contains(&function);
        let reply = match parsed.clone() {
            Ok(request) if request.is_write() => {
                // The journal syncs to disk: keep that off the async workers.
                let shared = Arc::clone(shared);
                tokio::task::spawn_blocking(move || answer_request(&shared, &request))
                    .await
                    .unwrap_or(Err(Exception::ServerDeviceFailure))
            }
            Ok(request) => answer_request(shared, &request),
            Err(exception) => Err(exception),
        };
        match (&reply, &parsed) {
            (Ok(response), _) => tracing::trace!(target: TRAFFIC, "{who} < {response}"),
            (Err(exception), request) => {
                tracing::trace!(
                    target: TRAFFIC,
                    "{who} < {:02X} exception {exception}",
                    function | 0x80
                );
                if written {
                    match request {
                        Ok(request) => tracing::warn!(
                            target: "ecam::modbus",
                            "{who}: write refused: {request}: {exception}"
                        ),
                        Err(_) => tracing::warn!(
                            target: "ecam::modbus",
                            "{who}: write refused: function {function:02X}: {exception}"
                        ),
                    }
                }
            }
        }
        shared.stats.count_modbus_reply(&reply);
        let frame = header.frame(&encode_response(function, &reply));
        stream.write_all(&frame).await?;
    }
}

/// Function codes that write (05, 06, 0F, 10): a malformed one is still a
/// refused write.
const WRITE_FUNCTIONS: [u8; 4] = [0x05, 0x06, 0x0F, 0x10];

/// Who sent a frame, as log lines name it: `client 127.0.0.1:40312 tx 7 unit 1`.
struct Who {
    peer: Option<std::net::SocketAddr>,
    transaction: u16,
    unit: u8,
}

impl std::fmt::Display for Who {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.peer {
            Some(peer) => write!(f, "client {peer}")?,
            None => f.write_str("client ?")?,
        }
        write!(f, " tx {} unit {}", self.transaction, self.unit)
    }
}
