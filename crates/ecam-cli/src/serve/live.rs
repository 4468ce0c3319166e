//! `GET /api/live?block=2000&rate=20`: a WebSocket that streams one cam's
//! state ([`ecam_serve::LiveSample`] as JSON, one text message per sample)
//! while the page is open.
//!
//! The rate is bounded ([`ecam_serve::MAX_LIVE_RATE`]) and each sample is
//! taken only once the previous one is sent: a slow client gets fewer
//! samples, never a growing queue, and one that takes longer than
//! [`SEND_DEADLINE`] to take a sample is disconnected. The upgrade request
//! passes the same Host/Origin guard as every other route (a foreign page
//! cannot open the socket); it is a read, so no token is needed.

use std::collections::HashMap;
use std::sync::Arc;
use std::time::Duration;

use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::{Query, State};
use axum::http::StatusCode;
use axum::response::Response;
use ecam_serve::{LiveRequest, LiveSample, Shared};
use tokio::time::MissedTickBehavior;

use super::http::error;

/// Longest a client may take to accept one sample before it is dropped.
pub const SEND_DEADLINE: Duration = Duration::from_secs(5);

/// Upgrades to the live stream, or answers 400 for a bad query.
pub async fn live(
    State(shared): State<Arc<Shared>>,
    Query(query): Query<HashMap<String, String>>,
    upgrade: WebSocketUpgrade,
) -> Response {
    let request = match LiveRequest::parse(
        query.get("block").map(String::as_str),
        query.get("rate").map(String::as_str),
    ) {
        Ok(request) => request,
        Err(message) => return error(StatusCode::BAD_REQUEST, &message),
    };
    upgrade
        // Clients send nothing but pings and close frames.
        .max_message_size(4096)
        .on_upgrade(move |socket| stream(socket, shared, request))
}

async fn stream(mut socket: WebSocket, shared: Arc<Shared>, request: LiveRequest) {
    let period = Duration::from_micros(1_000_000 / u64::from(request.rate.max(1)));
    let mut ticks = tokio::time::interval(period);
    // A late send skips ticks rather than bursting to catch up.
    ticks.set_missed_tick_behavior(MissedTickBehavior::Skip);
    let mut previous: Option<LiveSample> = None;
    loop {
        tokio::select! {
            incoming = socket.recv() => match incoming {
                // Pings are answered by the library; anything else is ignored.
                Some(Ok(Message::Close(_)) | Err(_)) | None => return,
                Some(Ok(_)) => continue,
            },
            _ = ticks.tick() => {}
        }
        let sample = shared.image(|plc| LiveSample::read(plc, request.block));
        let text = sample.to_json(request.block, previous.as_ref()).to_string();
        previous = Some(sample);
        match tokio::time::timeout(SEND_DEADLINE, socket.send(Message::text(text))).await {
            Ok(Ok(())) => {}
            // Gone, or too slow to keep up: drop it.
            Ok(Err(_)) | Err(_) => return,
        }
    }
}
