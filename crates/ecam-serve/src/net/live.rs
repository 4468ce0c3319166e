//! `GET /api/live?block=2000&rate=20`: a WebSocket that streams one cam's
//! state ([`crate::LiveSample`] as JSON, one text message per sample)
//! while the page is open.
//!
//! The rate is bounded ([`crate::MAX_LIVE_RATE`]) and each sample is
//! taken only once the previous one is sent: a slow client gets fewer
//! samples, never a growing queue. A live view counts against the HTTP and
//! live-view caps ([`crate::Limits`]); it is pinged, and closed when
//! its client answers nothing for the live deadline (a page that stopped
//! reading) or takes longer than the send deadline over one sample. The
//! upgrade request passes the same Host/Origin guard as every other route
//! (a foreign page cannot open the socket); it is a read, so no token is
//! needed.

use std::collections::HashMap;
use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::{LiveRequest, LiveSample, Shared};
use axum::extract::ws::rejection::WebSocketUpgradeRejection;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::{Extension, Query, State};
use axum::http::StatusCode;
use axum::response::Response;
use tokio::time::MissedTickBehavior;

use super::conn::Conn;
use super::reply::error;

/// Upgrades to the live stream, or answers 400 for a bad query.
pub async fn live(
    State(shared): State<Arc<Shared>>,
    Extension(conn): Extension<Conn>,
    Query(query): Query<HashMap<String, String>>,
    upgrade: Result<WebSocketUpgrade, WebSocketUpgradeRejection>,
) -> Response {
    let request = match LiveRequest::parse(
        query.get("block").map(String::as_str),
        query.get("rate").map(String::as_str),
    ) {
        Ok(request) => request,
        Err(message) => return error(StatusCode::BAD_REQUEST, &message),
    };
    let Ok(upgrade) = upgrade else {
        return error(
            StatusCode::UPGRADE_REQUIRED,
            "the live view is a WebSocket: open it with a WebSocket client (the designer page does)",
        );
    };
    upgrade
        // Clients send nothing but pings and close frames.
        .max_message_size(4096)
        .on_upgrade(move |socket| stream(socket, shared, request, conn))
}

async fn stream(mut socket: WebSocket, shared: Arc<Shared>, request: LiveRequest, conn: Conn) {
    let limits = shared.info.limits;
    for close in conn.registration.become_live(Instant::now()) {
        close();
    }
    let period = Duration::from_micros(1_000_000 / u64::from(request.rate.max(1)));
    let mut ticks = tokio::time::interval(period);
    // A late send skips ticks rather than bursting to catch up.
    ticks.set_missed_tick_behavior(MissedTickBehavior::Skip);
    let mut pings = tokio::time::interval(limits.live_ping);
    let mut previous: Option<LiveSample> = None;
    loop {
        tokio::select! {
            incoming = socket.recv() => match incoming {
                Some(Ok(Message::Close(_)) | Err(_)) | None => return,
                // A pong, a ping (answered by the library): the page reads.
                Some(Ok(_)) => {
                    conn.touch();
                    continue;
                }
            },
            _ = pings.tick() => {
                if conn.registration.activity().idle_for(Instant::now()) > limits.live_idle {
                    // No answer to the last pings: the page stopped reading.
                    return;
                }
                if socket.send(Message::Ping(Default::default())).await.is_err() {
                    return;
                }
                continue;
            }
            () = conn.closed() => return,
            _ = ticks.tick() => {}
        }
        let sample = shared.image(|plc| LiveSample::read(plc, request.block));
        let text = sample.to_json(request.block, previous.as_ref()).to_string();
        previous = Some(sample);
        match tokio::time::timeout(limits.live_send, socket.send(Message::text(text))).await {
            Ok(Ok(())) => {}
            // Gone, or too slow to keep up: drop it.
            Ok(Err(_)) | Err(_) => return,
        }
    }
}
