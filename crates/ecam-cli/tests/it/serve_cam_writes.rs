//! Writes from outside against running cams, through the real `ecam serve`
//! (docs/modbus.md, "Writes into cam blocks"), and the live view across a
//! table switch (docs/designer.md, "The live view").
//!
//! The rotary-knife example runs its cam from the block at D2000 (a
//! 100-point table: D2000..D2439).

use std::net::{SocketAddr, TcpStream};
use std::path::Path;
use std::time::{Duration, Instant};

use serde_json::{Value, json};
use tokio_modbus::prelude::*;
use tungstenite::client::IntoClientRequest as _;
use tungstenite::{Message, WebSocket};

use crate::serve::{Server, http};

const STEP: Duration = Duration::from_secs(20);

fn example(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/plc")
        .join(name)
        .to_str()
        .unwrap()
        .to_string()
}

fn knife() -> Server {
    Server::start_stateless(&["--program", &example("rotary_knife.il"), "--wire", "Y1:X0"])
}

fn get(server: &Server, names: &str) -> Value {
    let (status, body) = http(
        server.http,
        "GET",
        &format!("/api/devices?names={names}"),
        None,
    );
    assert_eq!(status, 200, "{body}");
    serde_json::from_str(&body).unwrap()
}

/// Waits (bounded) until the knife's cam runs and has moved the knife.
fn knife_turns(server: &Server) {
    let start = Instant::now();
    while get(server, "DD8140")["DD8140"].as_i64().unwrap() < 100 {
        assert!(start.elapsed() < STEP, "the knife should turn");
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn load(server: &Server, body: &str) -> (u16, Value) {
    let (status, text) = http(server.http, "POST", "/api/table/load", Some(body));
    (status, serde_json::from_str(&text).unwrap())
}

/// The issue's second case: the designer's "Write to PLC" aimed at D2001
/// while D2000's cam runs wrote over the running table (answered 200) and
/// the cam went on with garbage; D8000 wrote special registers. Both are
/// refused now and nothing changes.
#[test]
fn a_table_load_goes_only_where_the_program_keeps_its_cam_blocks() {
    let server = knife();
    knife_turns(&server);
    let table_words = "D2038:12";
    let before = get(&server, table_words);
    let specials = get(&server, "D8028:20");
    let points = r#""points": [[0, 0], [2500, 1000]]"#;

    let (status, body) = load(&server, &format!(r#"{{"block": 2001, {points}}}"#));
    assert_eq!(status, 409, "{body}");
    let message = body["error"].as_str().unwrap();
    assert!(message.contains("D2000"), "{message}");
    let (status, body) = load(
        &server,
        &format!(r#"{{"block": 2001, {points}, "while_running": "at-seam"}}"#),
    );
    assert_eq!(
        status, 409,
        "at-seam does not make an overlap right: {body}"
    );
    // Inside the special registers, or reaching them: never.
    for block in [8000, 7990] {
        let (status, body) = load(&server, &format!(r#"{{"block": {block}, {points}}}"#));
        assert_eq!(status, 400, "D{block}: {body}");
        assert!(body["error"].as_str().unwrap().contains("D8000"), "{body}");
    }
    assert_eq!(get(&server, table_words), before, "nothing was written");
    assert_eq!(
        get(&server, "D8028:20"),
        specials,
        "the special registers neither"
    );

    // The program's own block, switching at the seam, and a block clear of
    // it, are fine.
    let (status, body) = load(
        &server,
        &format!(r#"{{"block": 2000, {points}, "while_running": "at-seam"}}"#),
    );
    assert_eq!(
        (status, body["switch"].clone()),
        (200, json!("at-seam")),
        "{body}"
    );
    let (status, body) = load(&server, &format!(r#"{{"block": "D2440", {points}}}"#));
    assert_eq!(
        (status, body["switch"].clone()),
        (200, json!("now")),
        "{body}"
    );
    // The knife runs on, without an error.
    let flags = get(&server, "D2001")["D2001"].as_i64().unwrap();
    assert_eq!(flags & 0b1_0011_1000, 0, "{flags:#b}");
}

/// A write that would leave the running cam's table invalid is refused
/// with the block's own error, by Modbus (exception 03) and by HTTP (409
/// with the code), before anything changes; a valid one is taken at the
/// next seam as before.
#[tokio::test]
async fn a_write_that_would_break_the_running_table_is_refused() {
    let server = knife();
    knife_turns(&server);
    let mut ctx = tokio::time::timeout(STEP, tokio_modbus::client::tcp::connect(server.modbus))
        .await
        .unwrap()
        .unwrap();
    // Point 1's master (D2044/45) down to 0: not above point 0's.
    let before = ctx.read_holding_registers(2038, 12).await.unwrap().unwrap();
    assert_eq!(
        ctx.write_multiple_registers(2044, &[0, 0])
            .await
            .unwrap()
            .err(),
        Some(ExceptionCode::IllegalDataValue)
    );
    assert_eq!(
        ctx.write_single_register(2038, 1).await.unwrap().err(),
        Some(ExceptionCode::IllegalDataValue),
        "a point count of 1 (6783)"
    );
    assert_eq!(
        ctx.read_holding_registers(2038, 12).await.unwrap().unwrap(),
        before
    );
    let (status, body) = http(
        server.http,
        "POST",
        "/api/devices",
        Some(r#"{"DD2044": -5}"#),
    );
    assert_eq!(status, 409, "{body}");
    let body: Value = serde_json::from_str(&body).unwrap();
    assert_eq!(body["code"], 6782, "{body}");
    assert!(body["error"].as_str().unwrap().contains("D2044"), "{body}");
    assert_eq!(
        ctx.read_holding_registers(2038, 12).await.unwrap().unwrap(),
        before
    );
    // Other registers of the block, and a table that stays valid, are written.
    ctx.write_single_register(2004, 0).await.unwrap().unwrap();
    let table: [u16; 10] = [2, 40, 0, 0, 0, 0, 3183, 0, 1000, 0];
    ctx.write_multiple_registers(2038, &table)
        .await
        .unwrap()
        .unwrap();
    assert_eq!(get(&server, "D2038")["D2038"], 2);
}

/// Opens the live view of the block at D2000, fifty samples a second.
fn live(addr: SocketAddr) -> WebSocket<TcpStream> {
    let stream = TcpStream::connect_timeout(&addr, STEP).unwrap();
    stream.set_read_timeout(Some(STEP)).unwrap();
    let request = format!("ws://{addr}/api/live?block=2000&rate=50")
        .into_client_request()
        .unwrap();
    tungstenite::client(request, stream).unwrap().0
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

/// Reads samples until PLC time reaches `until_us`; checks every speed on
/// the way: the feed runs at 10 kHz, so the master's speed (counts per
/// second of PLC time) stays near 10000 through every seam and switch, and
/// the knife's never goes negative nor past the pulse ceiling. Gives the
/// table spans seen.
fn speeds_stay_true(socket: &mut WebSocket<TcpStream>, until_us: u64) -> Vec<i64> {
    let mut spans = Vec::new();
    let start = Instant::now();
    loop {
        let s = next_sample(socket);
        if s["running"] == true {
            if let Some(v) = s["master_velocity"].as_f64() {
                assert!((5_000.0..=15_000.0).contains(&v), "master speed {v}: {s}");
            }
            if let Some(v) = s["slave_velocity"].as_f64() {
                assert!((0.0..=200_000.0).contains(&v), "slave speed {v}: {s}");
            }
            let span = s["table_span"].as_i64().unwrap();
            if spans.last() != Some(&span) {
                spans.push(span);
            }
        }
        if s["time_us"].as_u64().unwrap() >= until_us {
            return spans;
        }
        assert!(start.elapsed() < STEP * 3, "PLC time should pass");
    }
}

/// The issue's third case, with the designer: a table of another cut length
/// written while the knife runs. The speeds are those of the cycle the cam
/// follows, the old one until the seam takes the new table (the feed's
/// speed went to about −1,000,000 counts/s when the new table's length was
/// used before the cam took it).
#[test]
fn the_live_view_stays_true_across_a_designer_write() {
    let server = knife();
    knife_turns(&server);
    let mut socket = live(server.http);
    let now = next_sample(&mut socket)["time_us"].as_u64().unwrap();
    speeds_stay_true(&mut socket, now + 200_000);
    let (status, body) = load(
        &server,
        r#"{"block": 2000, "points": [[0, 0], [500, 200], [2000, 1000]], "while_running": "at-seam"}"#,
    );
    assert_eq!(status, 200, "{body}");
    // The seam comes within one 3183-count cut: 0.32 s of feed.
    let spans = speeds_stay_true(&mut socket, now + 1_000_000);
    assert_eq!(spans, [3183, 2000], "the span changes at the seam, once");
}

/// The issue's third case, with the program switching tables
/// (`examples/plc/rotary_knife_switch.il`: 3183 → 2500 at feed 10000,
/// taken at the seam at 12732): the master's speed showed −65,000 counts/s
/// at the switch for a 10 kHz feed.
#[test]
fn the_live_view_stays_true_across_the_programs_table_switch() {
    let server = Server::start_stateless(&[
        "--program",
        &example("rotary_knife_switch.il"),
        "--wire",
        "Y1:X0",
        "--wire",
        "Y1:X1",
    ]);
    let mut socket = live(server.http);
    // The switch's seam comes at 1.27 s of PLC time.
    let spans = speeds_stay_true(&mut socket, 1_600_000);
    assert_eq!(spans, [3183, 2500], "{spans:?}");
}
