//! `ecam serve` holds up to careless and hostile clients: a cap on
//! connections (the idlest making room, `serve_limits.rs`), idle and
//! half-sent requests closed, and
//! a web face that refuses foreign hosts, foreign pages, non-JSON writes and
//! writes without the token. Loopback only; every wait is bounded.

use std::io::{Read as _, Write as _};
use std::net::{SocketAddr, TcpStream};
use std::time::{Duration, Instant};

use crate::serve::Server;

const STEP: Duration = Duration::from_secs(20);

fn connect(addr: SocketAddr) -> TcpStream {
    let s = TcpStream::connect_timeout(&addr, STEP).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    s
}

/// Reads holding register 0; true when the server answered.
fn modbus_answers(s: &mut TcpStream) -> bool {
    if s.write_all(&[0, 1, 0, 0, 0, 6, 1, 3, 0, 0, 0, 1]).is_err() {
        return false;
    }
    let mut reply = [0u8; 11];
    s.read_exact(&mut reply).is_ok()
}

/// Waits for the server to close `s`; gives how long that took.
fn closed_within(s: &mut TcpStream) -> Duration {
    let start = Instant::now();
    let mut buf = [0u8; 16];
    loop {
        match s.read(&mut buf) {
            Ok(0) | Err(_) => return start.elapsed(),
            Ok(_) => assert!(start.elapsed() < STEP, "still open"),
        }
    }
}

#[test]
fn idle_and_half_sent_modbus_requests_are_closed() {
    let server = Server::start_stateless(&["--max-connections", "3", "--idle-timeout", "1"]);
    let mut served: Vec<TcpStream> = (0..3).map(|_| connect(server.modbus)).collect();
    for s in &mut served {
        assert!(modbus_answers(s));
    }
    drop(served.remove(0));
    std::thread::sleep(Duration::from_millis(200));
    let mut again = connect(server.modbus);
    assert!(
        modbus_answers(&mut again),
        "a freed slot takes a new client"
    );
    // Idle past the limit: closed.
    assert!(closed_within(&mut again) < Duration::from_secs(5));
    // Half a frame, then nothing: closed.
    let mut half = connect(server.modbus);
    half.write_all(&[0, 1, 0]).unwrap();
    assert!(closed_within(&mut half) < Duration::from_secs(5));
}

fn http_raw(addr: SocketAddr, request: &str) -> (u16, String) {
    http_raw_within(addr, request, STEP)
}

/// As [`http_raw`], waiting up to `patience` for the answer (design work
/// in a debug build on a loaded host takes its time).
fn http_raw_within(addr: SocketAddr, request: &str, patience: Duration) -> (u16, String) {
    let mut s = connect(addr);
    // Design work runs at the lowest priority: on a busy machine it waits.
    s.set_read_timeout(Some(patience)).unwrap();
    s.write_all(request.as_bytes()).unwrap();
    let mut response = String::new();
    let _ = s.read_to_string(&mut response);
    let status = response
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    (status, response)
}

fn post(addr: SocketAddr, host: &str, extra_headers: &str, content_type: &str, body: &str) -> u16 {
    http_raw(
        addr,
        &format!(
            "POST /api/devices HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\n{extra_headers}\
             Content-Type: {content_type}\r\nContent-Length: {}\r\n\r\n{body}",
            body.len()
        ),
    )
    .0
}

fn d100(addr: SocketAddr) -> String {
    http_raw(
        addr,
        &format!(
            "GET /api/devices?names=D100 HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n"
        ),
    )
    .1
}

#[test]
fn the_web_face_refuses_foreign_hosts_pages_and_non_json_writes() {
    let server = Server::start_stateless(&[]);
    let http = server.http;
    let own = http.to_string();
    // DNS rebinding: another name for this address.
    let (status, _) = http_raw(
        http,
        "GET /api/status HTTP/1.1\r\nHost: evil.example:80\r\nConnection: close\r\n\r\n",
    );
    assert_eq!(status, 421);
    // A cross-site "simple" post (text/plain) and a foreign page's JSON post.
    assert_eq!(post(http, &own, "", "text/plain", r#"{"D100": 7}"#), 415);
    assert_eq!(
        post(
            http,
            &own,
            "Origin: http://evil.example\r\n",
            "application/json",
            r#"{"D100": 7}"#
        ),
        403
    );
    assert!(d100(http).contains("\"D100\": 0"), "{}", d100(http));
    // The page the server serves may write.
    let origin = format!("Origin: http://{own}\r\n");
    assert_eq!(
        post(http, &own, &origin, "application/json", r#"{"D100": 7}"#),
        200
    );
    assert!(d100(http).contains("\"D100\": 7"));
    // localhost names this server too.
    let local = format!("localhost:{}", http.port());
    assert_eq!(
        post(http, &local, "", "application/json", r#"{"D100": 8}"#),
        200
    );
}

#[test]
fn a_token_file_protects_writes() {
    let dir = crate::common::scratch_dir("serve-token");
    let token_file = dir.join("token");
    std::fs::write(&token_file, "s3cret-token-0123456789\n").unwrap();
    let server = Server::start_stateless(&["--token-file", token_file.to_str().unwrap()]);
    let own = server.http.to_string();
    assert_eq!(
        post(server.http, &own, "", "application/json", r#"{"D100": 5}"#),
        401
    );
    let wrong = "Authorization: Bearer nope\r\n";
    assert_eq!(
        post(
            server.http,
            &own,
            wrong,
            "application/json",
            r#"{"D100": 5}"#
        ),
        401
    );
    let right = "Authorization: Bearer s3cret-token-0123456789\r\n";
    assert_eq!(
        post(
            server.http,
            &own,
            right,
            "application/json",
            r#"{"D100": 5}"#
        ),
        200
    );
    // Reads need no token.
    assert!(d100(server.http).contains("\"D100\": 5"));
}

#[test]
fn design_work_does_not_hold_up_modbus() {
    let server = Server::start_stateless(&[]);
    let http = server.http;
    let own = http.to_string();
    let body = r#"{"generator": "function", "params": {"expr": "1000*sin(x/1000)+x/7", "from": 0, "to": 2000000, "points": 20000}}"#;
    let heavy: Vec<_> = (0..2)
        .map(|_| {
            let (own, body) = (own.clone(), body.to_string());
            std::thread::spawn(move || {
                let asked = Instant::now();
                let status = http_raw_within(
                    http,
                    &format!(
                        "POST /api/table/gen HTTP/1.1\r\nHost: {own}\r\nConnection: close\r\n\
                         Content-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
                        body.len()
                    ),
                    Duration::from_secs(120),
                )
                .0;
                (status, asked.elapsed())
            })
        })
        .collect();
    let mut modbus = connect(server.modbus);
    let mut worst = Duration::ZERO;
    let start = Instant::now();
    while start.elapsed() < Duration::from_millis(1500) {
        let asked = Instant::now();
        assert!(modbus_answers(&mut modbus));
        worst = worst.max(asked.elapsed());
        std::thread::sleep(Duration::from_millis(20));
    }
    let mut design = Duration::ZERO;
    for h in heavy {
        let (status, took) = h.join().unwrap();
        assert_eq!(status, 200);
        design = design.max(took);
    }
    // Held up behind the design work, an answer would wait about as long
    // as the work itself; a loaded host may delay any answer by scheduling,
    // so the bound grows with the work when the host is slow.
    let bound = Duration::from_secs(1).max(design / 2);
    assert!(
        worst < bound,
        "a Modbus answer took {worst:?} while the design work took {design:?}"
    );
}
