//! `GET /api/live`: the live view's WebSocket against the real `ecam serve`
//! running the rotary-knife example: samples arrive at the asked rate, show
//! the knife turning, and the upgrade passes the HTTP face's Host/Origin
//! guard like every other route.

use std::net::{SocketAddr, TcpStream};
use std::path::Path;
use std::time::{Duration, Instant};

use serde_json::Value;
use tungstenite::client::IntoClientRequest as _;
use tungstenite::{Message, WebSocket};

use crate::serve::Server;

const STEP: Duration = Duration::from_secs(20);

fn knife() -> Server {
    let il = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plc/rotary_knife.il");
    Server::start_stateless(&["--program", il.to_str().unwrap(), "--wire", "Y1:X0"])
}

/// Opens `path` as a WebSocket with `origin` (or none); the handshake's
/// error (with the HTTP status) when the server refuses.
fn open(
    addr: SocketAddr,
    path: &str,
    origin: Option<&str>,
) -> Result<WebSocket<TcpStream>, tungstenite::Error> {
    let stream = TcpStream::connect_timeout(&addr, STEP).unwrap();
    stream.set_read_timeout(Some(STEP)).unwrap();
    let mut request = format!("ws://{addr}{path}").into_client_request().unwrap();
    if let Some(origin) = origin {
        request
            .headers_mut()
            .insert("Origin", origin.parse().unwrap());
    }
    match tungstenite::client(request, stream) {
        Ok((socket, _)) => Ok(socket),
        Err(tungstenite::HandshakeError::Failure(err)) => Err(err),
        Err(tungstenite::HandshakeError::Interrupted(_)) => panic!("blocking socket"),
    }
}

fn next_sample(socket: &mut WebSocket<TcpStream>) -> Value {
    loop {
        match socket.read().unwrap() {
            Message::Text(text) => return serde_json::from_str(&text).unwrap(),
            Message::Ping(_) | Message::Pong(_) => continue,
            other => panic!("unexpected message {other:?}"),
        }
    }
}

fn refused_with(result: Result<WebSocket<TcpStream>, tungstenite::Error>) -> u16 {
    match result {
        Err(tungstenite::Error::Http(response)) => response.status().as_u16(),
        Err(other) => panic!("refused without a status: {other}"),
        Ok(_) => panic!("the upgrade should be refused"),
    }
}

#[test]
fn the_live_view_streams_the_turning_knife_at_the_asked_rate() {
    let server = knife();
    let own = format!("http://{}", server.http);
    let mut socket = open(server.http, "/api/live?block=2000&rate=10", Some(&own)).unwrap();
    let first = next_sample(&mut socket);
    assert_eq!(first["block"], 2000);
    assert!(
        first["slave_velocity"].is_null(),
        "no speed before two samples"
    );
    assert_eq!(first["sync_output"]["device"], "Y0");

    // The knife turns forwards: its slave position grows and the speed
    // (counts per second of PLC time) is positive once it follows.
    let start = Instant::now();
    let mut samples = vec![first];
    loop {
        let sample = next_sample(&mut socket);
        let moved = sample["running"] == true
            && sample["mode"] == "cyclic"
            && sample["slave_velocity"].as_f64().is_some_and(|v| v > 0.0)
            && sample["master_velocity"].as_f64().is_some_and(|v| v > 0.0);
        samples.push(sample);
        if moved && samples.len() >= 12 {
            break;
        }
        assert!(start.elapsed() < STEP, "the knife should be seen turning");
    }
    // Ten samples a second: twelve take at least 1.1 s of wall time
    // (no timing upper bound: a loaded machine may be slow).
    assert!(
        start.elapsed() >= Duration::from_millis(1000),
        "{:?}",
        start.elapsed()
    );
    let times: Vec<u64> = samples
        .iter()
        .map(|s| s["time_us"].as_u64().unwrap())
        .collect();
    assert!(times.windows(2).all(|w| w[0] <= w[1]), "{times:?}");
    socket.close(None).unwrap();
}

#[test]
fn the_live_socket_is_guarded_like_every_route() {
    let server = knife();
    // A foreign page may not open it; nor may a rebinding host name.
    assert_eq!(
        refused_with(open(
            server.http,
            "/api/live?block=2000",
            Some("http://evil.example")
        )),
        403
    );
    let stream = TcpStream::connect_timeout(&server.http, STEP).unwrap();
    let mut request = format!("ws://{}/api/live?block=2000", server.http)
        .into_client_request()
        .unwrap();
    request
        .headers_mut()
        .insert("Host", "rebind.example:80".parse().unwrap());
    match tungstenite::client(request, stream) {
        Err(tungstenite::HandshakeError::Failure(tungstenite::Error::Http(r))) => {
            assert_eq!(r.status().as_u16(), 421);
        }
        _ => panic!("a foreign Host should be refused"),
    }
    // Bad queries are answered 400 before any upgrade.
    for path in [
        "/api/live",
        "/api/live?block=x",
        "/api/live?block=8500",
        "/api/live?block=2000&rate=0",
        "/api/live?block=2000&rate=1000",
    ] {
        assert_eq!(refused_with(open(server.http, path, None)), 400, "{path}");
    }
}

#[test]
fn a_client_that_never_reads_does_not_hold_up_the_others() {
    let server = knife();
    // Fifty samples a second into a socket nobody reads.
    let _stalled = open(server.http, "/api/live?block=2000&rate=50", None).unwrap();
    std::thread::sleep(Duration::from_millis(300));
    let mut reader = open(server.http, "/api/live?block=2000&rate=50", None).unwrap();
    let a = next_sample(&mut reader)["scans"].as_u64().unwrap();
    let start = Instant::now();
    loop {
        let b = next_sample(&mut reader)["scans"].as_u64().unwrap();
        if b > a {
            break;
        }
        assert!(start.elapsed() < STEP, "the PLC should go on scanning");
    }
}
