//! The Modbus TCP listener: one task per client, reading MBAP frames and
//! answering them through [`ecam_serve`] (framing, codec, address map and
//! writes are all there; `docs/modbus.md` describes them).

use std::io;
use std::sync::Arc;
use std::sync::atomic::Ordering;

use ecam_serve::{Exception, MbapHeader, Shared, answer_request, encode_response, parse_request};
use tokio::io::{AsyncReadExt as _, AsyncWriteExt as _};
use tokio::net::{TcpListener, TcpStream};
use tokio::time::timeout;

use super::limits::ConnectionLimits;

/// Accepts clients on `listener` for ever, within `limits`.
pub async fn serve(listener: TcpListener, shared: Arc<Shared>, limits: ConnectionLimits) {
    loop {
        match listener.accept().await {
            Ok((stream, _)) => {
                let Some(slot) = limits.admit() else {
                    // At the cap: the newest goes, the served ones stay.
                    drop(stream);
                    continue;
                };
                shared
                    .stats
                    .modbus_connections
                    .fetch_add(1, Ordering::Relaxed);
                let (shared, limits) = (Arc::clone(&shared), limits.clone());
                tokio::spawn(async move {
                    connection(stream, &shared, &limits).await;
                    drop(slot);
                });
            }
            Err(err) => {
                // Out of file descriptors and the like: wait, do not spin.
                eprintln!("ecam serve: modbus accept: {err}");
                tokio::time::sleep(std::time::Duration::from_millis(100)).await;
            }
        }
    }
}

/// Serves one client until it disconnects, idles past the limit, sends half
/// a frame and stops, or sends something that is not Modbus.
async fn connection(mut stream: TcpStream, shared: &Arc<Shared>, limits: &ConnectionLimits) {
    let _ = stream.set_nodelay(true);
    // Errors only mean the client went away (or was sent away).
    let _ = requests(&mut stream, shared, limits).await;
}

async fn requests(
    stream: &mut TcpStream,
    shared: &Arc<Shared>,
    limits: &ConnectionLimits,
) -> io::Result<()> {
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
        let function = request_pdu.first().copied().unwrap_or(0);
        let reply = match parse_request(&request_pdu) {
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
        shared.stats.count_modbus_reply(&reply);
        let frame = header.frame(&encode_response(function, &reply));
        stream.write_all(&frame).await?;
    }
}
