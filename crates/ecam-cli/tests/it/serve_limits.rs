//! `ecam serve` under the faults of issue 25, one test each, against the
//! real binary on loopback: live views that never answer, request bodies
//! that never come, design work abandoned by its client, a cap full of
//! quiet clients, a program that loops, and answers in the server's own
//! words. Every wait is bounded; the deadlines asserted are generous
//! (seconds where the server needs milliseconds), so a loaded CI machine
//! does not fail them.

use std::io::{Read as _, Write as _};
use std::net::{SocketAddr, TcpStream};
use std::time::{Duration, Instant};

use serde_json::Value;

use crate::serve::{Server, http, program};

/// Longest any single step may take before the test fails.
const STEP: Duration = Duration::from_secs(20);

fn connect(addr: SocketAddr) -> TcpStream {
    let s = TcpStream::connect_timeout(&addr, STEP).unwrap();
    s.set_read_timeout(Some(STEP)).unwrap();
    s.set_write_timeout(Some(STEP)).unwrap();
    s
}

/// A live view that never answers a ping: the WebSocket handshake of
/// `GET /api/live`, then nothing. `None` when the server closed it first.
pub(crate) fn silent_live_view(addr: SocketAddr) -> Option<TcpStream> {
    let mut s = TcpStream::connect_timeout(&addr, STEP).ok()?;
    s.set_read_timeout(Some(STEP)).ok()?;
    write!(
        s,
        "GET /api/live?block=2000&rate=50 HTTP/1.1\r\nHost: {addr}\r\nUpgrade: websocket\r\n\
         Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n\
         Sec-WebSocket-Version: 13\r\n\r\n"
    )
    .ok()?;
    let mut head = Vec::new();
    let mut byte = [0u8; 1];
    while !head.ends_with(b"\r\n\r\n") {
        match s.read(&mut byte) {
            Ok(1) => head.push(byte[0]),
            _ => return None,
        }
    }
    head.starts_with(b"HTTP/1.1 101").then_some(s)
}

/// A POST whose headers promise a body that never comes; `None` when the
/// server is not there.
pub(crate) fn silent_post(addr: SocketAddr) -> Option<TcpStream> {
    let mut s = TcpStream::connect_timeout(&addr, STEP).ok()?;
    s.set_read_timeout(Some(STEP)).ok()?;
    write!(
        s,
        "POST /api/devices HTTP/1.1\r\nHost: {addr}\r\nContent-Type: application/json\r\n\
         Content-Length: 100\r\n\r\n"
    )
    .ok()?;
    Some(s)
}

/// Reads holding register 0 on `s`; true when the server answered.
pub(crate) fn modbus_answers(s: &mut TcpStream) -> bool {
    if s.write_all(&[0, 1, 0, 0, 0, 6, 1, 3, 0, 0, 0, 1]).is_err() {
        return false;
    }
    let mut reply = [0u8; 11];
    s.read_exact(&mut reply).is_ok()
}

/// How long a new Modbus client and a new HTTP client each take to be
/// served (connect, ask, answer), or `None` if one is not served.
pub(crate) fn newcomers_served(
    modbus: SocketAddr,
    http: SocketAddr,
) -> (Option<Duration>, Option<Duration>) {
    let asked = Instant::now();
    let modbus = TcpStream::connect_timeout(&modbus, STEP)
        .ok()
        .and_then(|mut s| {
            s.set_read_timeout(Some(STEP)).ok()?;
            modbus_answers(&mut s).then(|| asked.elapsed())
        });
    let asked = Instant::now();
    let http = TcpStream::connect_timeout(&http, STEP)
        .ok()
        .and_then(|mut s| {
            s.set_read_timeout(Some(STEP)).ok()?;
            let addr = http;
            write!(
                s,
                "GET /api/status HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n"
            )
            .ok()?;
            let mut response = String::new();
            let _ = s.read_to_string(&mut response);
            response
                .starts_with("HTTP/1.1 200")
                .then(|| asked.elapsed())
        });
    (modbus, http)
}

/// Waits for the server to close `s`; how long that took (reading, and so
/// dropping, whatever it sent).
fn closed_within(s: &mut TcpStream) -> Duration {
    let start = Instant::now();
    let mut buf = [0u8; 4096];
    loop {
        match s.read(&mut buf) {
            Ok(0) | Err(_) => return start.elapsed(),
            Ok(_) => assert!(start.elapsed() < STEP, "still open after {STEP:?}"),
        }
    }
}

fn status(server: &Server) -> Value {
    server.get_json("/api/status")
}

/// Polls the status until `check` holds; the last status seen.
fn status_until(server: &Server, check: impl Fn(&Value) -> bool) -> Value {
    let start = Instant::now();
    loop {
        let s = status(server);
        if check(&s) || start.elapsed() > STEP {
            return s;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[test]
fn live_views_count_against_the_cap_and_one_that_stops_reading_is_closed() {
    let server = Server::start_stateless(&["--max-connections", "4", "--idle-timeout", "2"]);
    let mut views: Vec<TcpStream> = (0..12)
        .filter_map(|_| silent_live_view(server.http))
        .collect();
    let (modbus, http) = newcomers_served(server.modbus, server.http);
    assert!(modbus.is_some() && http.is_some(), "{modbus:?} {http:?}");
    let s = status(&server);
    let open = s["connections"]["http"]["open"].as_u64().unwrap()
        + s["connections"]["live"]["open"].as_u64().unwrap();
    assert!(open <= 4, "{}", s["connections"]);
    assert!(
        s["connections"]["live"]["closed_for_room"]
            .as_u64()
            .unwrap()
            > 0
    );
    // The views still open answer no ping: each is closed within the live
    // deadline (2 s here) and a ping period.
    let view = views.last_mut().unwrap();
    assert!(closed_within(view) < Duration::from_secs(10));
}

#[test]
fn request_bodies_that_never_come_are_cut_off_and_give_way() {
    let server = Server::start_stateless(&["--max-connections", "4", "--idle-timeout", "2"]);
    let mut posts: Vec<TcpStream> = (0..4).filter_map(|_| silent_post(server.http)).collect();
    std::thread::sleep(Duration::from_millis(100));
    let (_, http) = newcomers_served(server.modbus, server.http);
    assert!(http.is_some(), "a full cap of silent POSTs gives way");
    // One left alone is answered 408 at the body deadline, and closed.
    let last = posts.last_mut().unwrap();
    let start = Instant::now();
    let mut response = String::new();
    let _ = last.read_to_string(&mut response);
    assert!(start.elapsed() < Duration::from_secs(10));
    assert!(
        response.is_empty() || response.starts_with("HTTP/1.1 408"),
        "{response}"
    );
    // Only the status request itself is left.
    let s = status_until(&server, |s| s["connections"]["http"]["open"] == 1);
    assert_eq!(s["connections"]["http"]["open"], 1, "{}", s["connections"]);
}

#[test]
fn a_full_modbus_cap_gives_way_to_a_newcomer_and_closes_the_idlest() {
    let server = Server::start_stateless(&["--max-connections", "3", "--idle-timeout", "60"]);
    let mut clients: Vec<TcpStream> = (0..3).map(|_| connect(server.modbus)).collect();
    for c in &mut clients {
        assert!(modbus_answers(c));
        std::thread::sleep(Duration::from_millis(50));
    }
    // The first asked longest ago: it makes room.
    assert!(modbus_answers(&mut clients[2]));
    let mut newcomer = connect(server.modbus);
    assert!(modbus_answers(&mut newcomer), "the newcomer is served");
    assert!(closed_within(&mut clients[0]) < STEP);
    assert!(modbus_answers(&mut clients[1]), "the others go on");
    assert!(modbus_answers(&mut clients[2]));
    assert_eq!(status(&server)["connections"]["modbus"]["open"], 3);
}

/// A function table the debug build needs minutes for: 100 001 points of
/// a 300-term expression (within a run's budget).
fn heavy_design_body() -> String {
    let expr = vec!["sin(x/1000)"; 300].join("+");
    format!(
        r#"{{"generator": "function", "params": {{"expr": "{expr}", "from": 0, "to": 10000000, "points": 100001}}}}"#
    )
}

fn post_raw(addr: SocketAddr, path: &str, body: &str) -> TcpStream {
    let mut s = connect(addr);
    write!(
        s,
        "POST {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\
         Content-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    s
}

#[test]
fn abandoned_design_work_stops_and_the_pool_is_bounded() {
    let server = Server::start_stateless(&["--design-timeout", "2"]);
    let body = heavy_design_body();
    // One client waits: 503 at the deadline.
    let asked = Instant::now();
    let mut waiting = post_raw(server.http, "/api/table/gen", &body);
    // Another hangs up once its work has begun.
    let leaving = post_raw(server.http, "/api/table/gen", &body);
    status_until(&server, |s| s["design"]["running"] == 2);
    drop(leaving);
    let mut response = String::new();
    waiting.read_to_string(&mut response).unwrap();
    assert!(response.starts_with("HTTP/1.1 503"), "{response}");
    assert!(response.contains("design deadline"), "{response}");
    assert!(asked.elapsed() < Duration::from_secs(15));
    // Both are stopped: nothing computes any more.
    let s = status_until(&server, |s| {
        s["design"]["running"] == 0 && s["design"]["cancelled"].as_u64() >= Some(2)
    });
    assert_eq!(s["design"]["running"], 0, "{}", s["design"]);
    assert!(
        s["design"]["cancelled"].as_u64() >= Some(2),
        "{}",
        s["design"]
    );
    // A burst: at most 2 compute, 8 wait, the rest are refused at once.
    let burst: Vec<TcpStream> = (0..14)
        .map(|_| post_raw(server.http, "/api/table/gen", &body))
        .collect();
    let s = status_until(&server, |s| s["design"]["refused_busy"].as_u64() >= Some(4));
    let design = &s["design"];
    assert!(design["running"].as_u64() <= Some(2), "{design}");
    assert!(design["waiting"].as_u64() <= Some(8), "{design}");
    assert!(design["refused_busy"].as_u64() >= Some(4), "{design}");
    drop(burst);
    let s = status_until(&server, |s| {
        s["design"]["running"] == 0 && s["design"]["waiting"] == 0
    });
    assert_eq!(s["design"]["running"], 0, "{}", s["design"]);
    // Light design work is still answered.
    let (code, _) = http(server.http, "GET", "/api/law/cycloid?points=11", None);
    assert_eq!(code, 200);
}

#[test]
fn a_looping_program_is_stopped_by_the_watchdog_while_modbus_answers() {
    // X0 on: a loop that never ends; D8000 = 3000 ms, so the scan runs for
    // 3 s of CPU before the watchdog stops it.
    let il = program(
        "watchdog.il",
        "LD M8000\nMOV K3000 D8000\nOUT Y7\nLDI X0\nCJ P1\nP0\nLD X0\nCJ P0\nP1\nEND\n",
    );
    let log = crate::common::scratch_dir("serve-watchdog").join("stderr.log");
    let state = crate::common::scratch_dir("serve-watchdog-state");
    let server = Server::start_logged(&state, &["--program", il.to_str().unwrap()], &log);
    let mut modbus = connect(server.modbus);
    assert!(modbus_answers(&mut modbus));
    // X0 on (coil 10000).
    modbus
        .write_all(&[0, 2, 0, 0, 0, 6, 1, 5, 0x27, 0x10, 0xFF, 0])
        .unwrap();
    let mut echo = [0u8; 12];
    modbus.read_exact(&mut echo).unwrap();
    let start = Instant::now();
    let mut worst = Duration::ZERO;
    let mut stopped = false;
    while start.elapsed() < Duration::from_secs(60) && !stopped {
        let asked = Instant::now();
        // M8061 (coil 8061).
        modbus
            .write_all(&[0, 3, 0, 0, 0, 6, 1, 1, 0x1F, 0x7D, 0, 1])
            .unwrap();
        let mut reply = [0u8; 10];
        modbus.read_exact(&mut reply).unwrap();
        worst = worst.max(asked.elapsed());
        stopped = reply[9] & 1 == 1;
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(stopped, "the watchdog stops the program");
    eprintln!(
        "watchdog after {:?}; slowest Modbus answer meanwhile {worst:?}",
        start.elapsed()
    );
    assert!(worst < Duration::from_secs(2), "{worst:?}");
    let s = status(&server);
    assert_eq!(s["plc"]["state"], "stopped", "{}", s["plc"]);
    assert!(s["plc"]["fault"].as_str().unwrap().contains("6105"));
    let devices = server.get_json("/api/devices?names=D8061,M8061,M8004,D8004,Y7,M8000");
    assert_eq!(
        devices,
        serde_json::json!({"D8061": 6105, "M8061": 1, "M8004": 1, "D8004": 8061, "Y7": 0, "M8000": 0})
    );
    let stderr = std::fs::read_to_string(&log).unwrap();
    assert!(
        stderr.contains("watchdog.il:8: watchdog timer error 6105"),
        "{stderr}"
    );
}

/// The error message of an answer, checked to be in the server's words.
fn refusal(addr: SocketAddr, path: &str, body: &str) -> String {
    let (code, text) = http(addr, "POST", path, Some(body));
    assert_eq!(code, 400, "{path} {body}: {text}");
    let value: Value = serde_json::from_str(&text).unwrap();
    let message = value["error"].as_str().unwrap().to_string();
    for library in [
        "EOF while parsing",
        "at line 1 column",
        "wlog",
        "invalid type: sequence",
    ] {
        assert!(!message.contains(library), "{message}");
    }
    assert!(
        !message.contains("--"),
        "no command-line wording: {message}"
    );
    assert!(message.len() < 400, "{} bytes: {message}", message.len());
    message
}

#[test]
fn answers_use_the_servers_words_and_quote_a_short_excerpt() {
    let server = Server::start_stateless(&[]);
    let http_addr = server.http;
    let m = refusal(http_addr, "/api/table/gen", "{");
    assert!(m.contains("line 1, column 1"), "{m}");
    let m = refusal(
        http_addr,
        "/api/table/gen",
        r#"{"generator": "function", "params": {}}"#,
    );
    assert!(m.contains("`expr`"), "{m}");
    let m = refusal(
        http_addr,
        "/api/table/gen",
        r#"{"generator": "function", "params": {"expr": "sinn(x)"}}"#,
    );
    assert!(m.contains("`sinn` is not a function"), "{m}");
    refusal(
        http_addr,
        "/api/table/gen",
        r#"{"generator": "function", "params": [1]}"#,
    );
    let huge = "7".repeat(1_000_000);
    let m = refusal(
        http_addr,
        "/api/devices",
        &format!(r#"{{"D100": "{huge}x"}}"#),
    );
    assert!(m.contains("(1000001 bytes)"), "{m}");
    let m = refusal(http_addr, "/api/devices", &format!(r#"{{"D{huge}": 1}}"#));
    assert!(m.contains("bytes)"), "{m}");
    // The live view without a WebSocket: JSON, not the library's text.
    let (code, text) = http(http_addr, "GET", "/api/live?block=2000", None);
    assert_eq!(code, 426);
    assert!(text.contains("\"error\""), "{text}");
    // A body over the size limit: JSON too, answered from its declared
    // length before a byte of it is sent (a client that wrote it all
    // would race the server's close).
    let mut stream = TcpStream::connect(http_addr).unwrap();
    stream
        .set_read_timeout(Some(Duration::from_secs(30)))
        .unwrap();
    write!(
        stream,
        "POST /api/keypoints HTTP/1.1\r\nHost: {http_addr}\r\nConnection: close\r\n\
         Content-Type: application/json\r\nContent-Length: 2200000\r\n\r\n"
    )
    .unwrap();
    let mut response = String::new();
    let _ = stream.read_to_string(&mut response);
    assert!(response.starts_with("HTTP/1.1 413"), "{response}");
    assert!(response.contains("\"error\""), "{response}");
}
