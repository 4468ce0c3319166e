//! `ecam serve`: Modbus TCP (the address-map contract of docs/architecture.md)
//! and HTTP, driven against the real binary on ephemeral loopback ports.
//! Every wait is bounded, and every server is killed when its test ends.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::io::{BufRead as _, BufReader, Read as _, Write as _};
use std::net::{SocketAddr, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use serde_json::{Value, json};
use tokio_modbus::client::Context;
use tokio_modbus::prelude::*;

/// Longest any single step may take before the test fails.
const STEP: Duration = Duration::from_secs(20);

/// A running `ecam serve` on ephemeral loopback ports, killed (SIGKILL)
/// and reaped on drop. The other serve test modules use it too.
pub(crate) struct Server {
    child: Child,
    /// Its Modbus TCP address.
    pub(crate) modbus: SocketAddr,
    /// Its HTTP address.
    pub(crate) http: SocketAddr,
}

impl Server {
    /// Starts with its state in `state`.
    pub(crate) fn start(state: &Path, extra: &[&str]) -> Self {
        Self::start_with_stderr(Some(state), extra, Stdio::null())
    }

    /// Starts without `--state`.
    pub(crate) fn start_stateless(extra: &[&str]) -> Self {
        Self::start_with_stderr(None, extra, Stdio::null())
    }

    /// Starts with stderr going to the file `log` (truncated first).
    pub(crate) fn start_logged(state: &Path, extra: &[&str], log: &Path) -> Self {
        let file = std::fs::File::create(log).unwrap();
        Self::start_with_stderr(Some(state), extra, Stdio::from(file))
    }

    fn start_with_stderr(state: Option<&Path>, extra: &[&str], stderr: Stdio) -> Self {
        let mut command = Command::new(env!("CARGO_BIN_EXE_ecam"));
        command.args(["serve", "--modbus", "127.0.0.1:0", "--http", "127.0.0.1:0"]);
        if let Some(state) = state {
            command.arg("--state").arg(state);
        }
        let mut child = command
            .args(extra)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(stderr)
            .spawn()
            .unwrap();
        let stdout = child.stdout.take().unwrap();
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || {
            let mut reader = BufReader::new(stdout);
            for _ in 0..2 {
                let mut line = String::new();
                if reader.read_line(&mut line).unwrap_or(0) == 0 {
                    return;
                }
                let _ = tx.send(line);
            }
            // Keep the pipe open (and drained) while the server lives.
            let _ = std::io::copy(&mut reader, &mut std::io::sink());
        });
        let mut server = Self {
            child,
            modbus: "127.0.0.1:1".parse().unwrap(),
            http: "127.0.0.1:1".parse().unwrap(),
        };
        for _ in 0..2 {
            let line = rx
                .recv_timeout(STEP)
                .expect("ecam serve should print its addresses");
            let (kind, addr) = line.trim().split_once(' ').unwrap();
            match kind {
                "modbus" => server.modbus = addr.parse().unwrap(),
                "http" => server.http = addr.parse().unwrap(),
                other => panic!("unexpected line {other:?}"),
            }
        }
        server
    }

    /// The server's process id.
    pub(crate) fn pid(&self) -> u32 {
        self.child.id()
    }

    /// `kill -9` and wait for it to be gone.
    pub(crate) fn kill_9(mut self) {
        self.child.kill().unwrap();
        self.child.wait().unwrap();
    }

    /// SIGTERM (a clean stop) and wait for the process to end.
    #[cfg(unix)]
    fn terminate(mut self) {
        let pid = self.child.id().to_string();
        let sent = Command::new("kill").args(["-TERM", &pid]).status().unwrap();
        assert!(sent.success());
        let start = Instant::now();
        while self.child.try_wait().unwrap().is_none() {
            assert!(start.elapsed() < STEP, "ecam serve did not stop on SIGTERM");
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    fn is_running(&mut self) -> bool {
        self.child.try_wait().unwrap().is_none()
    }

    async fn client(&self) -> Context {
        tokio::time::timeout(STEP, tokio_modbus::client::tcp::connect(self.modbus))
            .await
            .unwrap()
            .unwrap()
    }

    fn http(&self, method: &str, path: &str, body: Option<&str>) -> (u16, String) {
        http(self.http, method, path, body)
    }

    pub(crate) fn get_json(&self, path: &str) -> Value {
        let (status, body) = self.http("GET", path, None);
        assert_eq!(status, 200, "GET {path}: {body}");
        serde_json::from_str(&body).unwrap()
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A fresh, empty state directory for one test.
fn state_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("serve-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

pub(crate) fn program(name: &str, source: &str) -> PathBuf {
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::write(&path, source).unwrap();
    path
}

/// One HTTP/1.1 request over a plain socket; returns status and body.
pub(crate) fn http(
    addr: SocketAddr,
    method: &str,
    path: &str,
    body: Option<&str>,
) -> (u16, String) {
    let mut stream = TcpStream::connect_timeout(&addr, STEP).unwrap();
    stream.set_read_timeout(Some(STEP)).unwrap();
    stream.set_write_timeout(Some(STEP)).unwrap();
    let body = body.unwrap_or("");
    write!(
        stream,
        "{method} {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\
         Content-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    let mut response = String::new();
    stream.read_to_string(&mut response).unwrap();
    let (head, body) = response.split_once("\r\n\r\n").unwrap();
    let status = head.split_whitespace().nth(1).unwrap().parse().unwrap();
    (status, body.to_string())
}

/// Sends one raw request PDU (transaction 7, unit 1) on `stream`; returns
/// the response PDU, or `None` when the server closed the connection.
fn raw_on(stream: &mut TcpStream, pdu: &[u8]) -> Option<Vec<u8>> {
    let len = (pdu.len() + 1) as u16;
    let mut frame = vec![0, 7, 0, 0];
    frame.extend_from_slice(&len.to_be_bytes());
    frame.push(1);
    frame.extend_from_slice(pdu);
    stream.write_all(&frame).ok()?;
    let mut header = [0u8; 7];
    stream.read_exact(&mut header).ok()?;
    assert_eq!(
        &header[..4],
        &[0, 7, 0, 0],
        "transaction and protocol echoed"
    );
    assert_eq!(header[6], 1, "unit id echoed");
    let len = u16::from_be_bytes([header[4], header[5]]) as usize;
    let mut body = vec![0u8; len - 1];
    stream.read_exact(&mut body).ok()?;
    Some(body)
}

fn connect_raw(addr: SocketAddr) -> TcpStream {
    let stream = TcpStream::connect_timeout(&addr, STEP).unwrap();
    stream.set_read_timeout(Some(STEP)).unwrap();
    stream
}

/// Whether the server closed `stream` (EOF), rather than answering.
fn closed(stream: &mut TcpStream) -> bool {
    let mut buf = [0u8; 16];
    matches!(stream.read(&mut buf), Ok(0) | Err(_))
}

/// Polls `check` until it holds (the PLC scans in real time), at most `STEP`.
async fn eventually(mut check: impl AsyncFnMut() -> bool) {
    let start = Instant::now();
    while !check().await {
        assert!(start.elapsed() < STEP, "condition not reached in time");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
}

#[tokio::test]
async fn every_area_reads_and_writes_over_modbus() {
    // Y7 follows M10, M11 follows X17, D102 copies D100: the program runs;
    // DPLSY emits 1 kHz on Y1, counted in D8142/D8143: the hardware ticks.
    let il = program(
        "serve-areas.il",
        "LD M10\nOUT Y7\nLD X17\nOUT M11\nLD M8000\nMOV D100 D102\n\
         LD M8000\nDPLSY K1000 K0 Y1\nEND\n",
    );
    let server = Server::start(
        &state_dir("areas"),
        &["--program", il.to_str().unwrap(), "--wire", "Y1:X0"],
    );
    let mut ctx = server.client().await;

    // D: holding registers at n; input registers mirror them.
    ctx.write_single_register(100, 1234).await.unwrap().unwrap();
    ctx.write_multiple_registers(200, &[1, 0xFFFF, 3])
        .await
        .unwrap()
        .unwrap();
    ctx.write_single_register(8511, 42).await.unwrap().unwrap();
    assert_eq!(
        ctx.read_holding_registers(100, 1).await.unwrap().unwrap(),
        [1234]
    );
    assert_eq!(
        ctx.read_holding_registers(200, 3).await.unwrap().unwrap(),
        [1, 0xFFFF, 3]
    );
    assert_eq!(
        ctx.read_input_registers(200, 3).await.unwrap().unwrap(),
        [1, 0xFFFF, 3]
    );
    assert_eq!(
        ctx.read_holding_registers(8511, 1).await.unwrap().unwrap(),
        [42]
    );
    assert_eq!(
        ctx.read_holding_registers(0, 125)
            .await
            .unwrap()
            .unwrap()
            .len(),
        125
    );

    // M: coils at n.
    ctx.write_multiple_coils(0, &[true, false, true])
        .await
        .unwrap()
        .unwrap();
    ctx.write_single_coil(10, true).await.unwrap().unwrap();
    ctx.write_single_coil(8511, true).await.unwrap().unwrap();
    assert_eq!(
        ctx.read_coils(0, 3).await.unwrap().unwrap()[..3],
        [true, false, true]
    );
    assert!(ctx.read_coils(8511, 1).await.unwrap().unwrap()[0]);

    // X (octal names): coils at 10000 + index, writable; X17 = 10015.
    ctx.write_single_coil(10015, true).await.unwrap().unwrap();
    assert_eq!(
        ctx.read_coils(10014, 3).await.unwrap().unwrap()[..3],
        [false, true, false]
    );

    // Y: coils at 12000 + index, driven by the program; D102 copied by it.
    eventually(async || {
        ctx.read_coils(12007, 1).await.unwrap().unwrap()[0]
            && ctx.read_coils(11, 1).await.unwrap().unwrap()[0]
            && ctx.read_holding_registers(102, 1).await.unwrap().unwrap() == [1234]
    })
    .await;
    assert_eq!(
        ctx.read_discrete_inputs(12006, 2).await.unwrap().unwrap()[..2],
        [false, true]
    );
    eventually(async || {
        let pulses = ctx.read_holding_registers(8142, 2).await.unwrap().unwrap();
        (u32::from(pulses[1]) << 16 | u32::from(pulses[0])) > 0
    })
    .await;

    // The same memory through HTTP, with the dump's names and formats.
    let values = server.get_json("/api/devices?names=D100,D201,DD200,M10,X17,Y7,D8511");
    assert_eq!(
        values,
        json!({"D100": 1234, "D201": -1, "DD200": -65535, "M10": 1, "X17": 1, "Y7": 1, "D8511": 42})
    );
}

#[tokio::test]
async fn bad_requests_get_the_exception_they_deserve() {
    let server = Server::start(&state_dir("exceptions"), &[]);
    let mut ctx = server.client().await;
    let address = Some(ExceptionCode::IllegalDataAddress);
    let value = Some(ExceptionCode::IllegalDataValue);

    // Past a device's end, and gaps between areas.
    assert_eq!(
        ctx.read_holding_registers(8511, 2).await.unwrap().err(),
        address
    );
    assert_eq!(
        ctx.read_holding_registers(8512, 1).await.unwrap().err(),
        address
    );
    assert_eq!(
        ctx.write_single_register(9000, 1).await.unwrap().err(),
        address
    );
    assert_eq!(
        ctx.write_multiple_registers(8510, &[1, 2, 3])
            .await
            .unwrap()
            .err(),
        address
    );
    assert_eq!(ctx.read_coils(8511, 2).await.unwrap().err(), address);
    assert_eq!(ctx.read_coils(9000, 1).await.unwrap().err(), address);
    assert_eq!(ctx.read_coils(10255, 2).await.unwrap().err(), address);
    assert_eq!(ctx.read_coils(12256, 1).await.unwrap().err(), address);
    assert_eq!(
        ctx.write_single_coil(11000, true).await.unwrap().err(),
        address
    );
    // Y is read only.
    assert_eq!(
        ctx.write_single_coil(12000, true).await.unwrap().err(),
        address
    );
    assert_eq!(
        ctx.write_multiple_coils(11999, &[true, true])
            .await
            .unwrap()
            .err(),
        address
    );
    assert_eq!(
        ctx.write_multiple_coils(12000, &[true; 8])
            .await
            .unwrap()
            .err(),
        address
    );
    // Quantity 0 and over the protocol maximum.
    assert_eq!(ctx.read_holding_registers(0, 0).await.unwrap().err(), value);
    assert_eq!(
        ctx.read_holding_registers(0, 126).await.unwrap().err(),
        value
    );
    assert_eq!(ctx.read_input_registers(0, 126).await.unwrap().err(), value);
    assert_eq!(ctx.read_coils(0, 0).await.unwrap().err(), value);
    assert_eq!(ctx.read_coils(0, 2001).await.unwrap().err(), value);
    // Nothing was written by the refused requests.
    assert_eq!(
        ctx.read_holding_registers(8510, 2).await.unwrap().unwrap(),
        [0, 0]
    );
    assert_eq!(
        ctx.read_coils(12000, 8).await.unwrap().unwrap()[..8],
        [false; 8]
    );

    let mut raw = connect_raw(server.modbus);
    // Unsupported functions: 01 (0x08 diagnostics, 0x2B device id, 0x16 mask write).
    assert_eq!(
        raw_on(&mut raw, &[0x08, 0, 0, 0x12, 0x34]).unwrap(),
        [0x88, 0x01]
    );
    assert_eq!(raw_on(&mut raw, &[0x2B, 0x0E, 1, 0]).unwrap(), [0xAB, 0x01]);
    assert_eq!(
        raw_on(&mut raw, &[0x16, 0, 0, 0xFF, 0xFF, 0, 0]).unwrap(),
        [0x96, 0x01]
    );
    // Quantity over the maximum for writes (1969 coils), with a consistent
    // byte count: 03. (124 registers do not fit in a 253-byte PDU at all.)
    let mut pdu = vec![0x0F, 0, 0, 0x07, 0xB1, 247];
    pdu.extend(std::iter::repeat_n(0u8, 247));
    assert_eq!(raw_on(&mut raw, &pdu).unwrap(), [0x8F, 0x03]);
    // A coil value other than 0xFF00 / 0x0000: 03.
    assert_eq!(
        raw_on(&mut raw, &[0x05, 0, 1, 0x12, 0x34]).unwrap(),
        [0x85, 0x03]
    );
    // Register write at the end of D, raw: echoed.
    assert_eq!(
        raw_on(&mut raw, &[0x06, 0x21, 0x3F, 0x12, 0x34]).unwrap(),
        [0x06, 0x21, 0x3F, 0x12, 0x34]
    );
}

#[tokio::test]
async fn malformed_frames_do_not_kill_the_server() {
    let mut server = Server::start(&state_dir("malformed"), &[]);

    // A quantity claiming more coils than the data holds (a panic in naive
    // decoders), a byte count that does not match, a truncated read: 03 on
    // a connection that stays open.
    let mut raw = connect_raw(server.modbus);
    assert_eq!(
        raw_on(&mut raw, &[0x0F, 0, 0, 0x07, 0xB0, 1, 0xFF]).unwrap(),
        [0x8F, 0x03]
    );
    assert_eq!(
        raw_on(&mut raw, &[0x10, 0, 0, 0x80, 0x00, 0]).unwrap(),
        [0x90, 0x03]
    );
    assert_eq!(raw_on(&mut raw, &[0x03, 0, 0]).unwrap(), [0x83, 0x03]);
    assert_eq!(
        raw_on(&mut raw, &[0x03, 0, 0, 0, 1, 0]).unwrap(),
        [0x83, 0x03]
    );
    assert_eq!(
        raw_on(&mut raw, &[0x03, 0, 0, 0, 1]).unwrap(),
        [0x03, 2, 0, 0]
    );

    // Not Modbus at all: the connection is closed.
    let mut garbage = connect_raw(server.modbus);
    garbage
        .write_all(b"GET / HTTP/1.1\r\nHost: x\r\n\r\n")
        .unwrap();
    assert!(closed(&mut garbage));
    // MBAP length 0, and a length over the 254 maximum.
    for header in [[0u8, 1, 0, 0, 0, 0, 1], [0, 1, 0, 0, 0x01, 0x00, 1]] {
        let mut bad = connect_raw(server.modbus);
        bad.write_all(&header).unwrap();
        assert!(closed(&mut bad));
    }
    // Half a frame, then the client goes away.
    let mut half = connect_raw(server.modbus);
    half.write_all(&[0, 1, 0, 0, 0, 6, 1, 0x03]).unwrap();
    drop(half);

    // Still serving, on old and new connections.
    assert_eq!(
        raw_on(&mut raw, &[0x03, 0, 0, 0, 1]).unwrap(),
        [0x03, 2, 0, 0]
    );
    let mut ctx = server.client().await;
    ctx.write_single_register(5, 55).await.unwrap().unwrap();
    assert_eq!(
        ctx.read_holding_registers(5, 1).await.unwrap().unwrap(),
        [55]
    );
    assert!(server.is_running());
    let status = server.get_json("/api/status");
    assert!(status["modbus"]["closed_malformed"].as_u64().unwrap() >= 3);
}

#[tokio::test]
async fn acknowledged_writes_survive_kill_9() {
    let dir = state_dir("durable");
    let server = Server::start(&dir, &[]);
    {
        let mut ctx = server.client().await;
        ctx.write_single_register(10, 1234).await.unwrap().unwrap();
        ctx.write_multiple_registers(20, &[7, 0xFFFE, 9])
            .await
            .unwrap()
            .unwrap();
        ctx.write_single_register(10, 4321).await.unwrap().unwrap();
        ctx.write_single_coil(5, true).await.unwrap().unwrap();
        ctx.write_multiple_coils(10002, &[true, false, true])
            .await
            .unwrap()
            .unwrap();
    }
    let (status, body) = server.http(
        "POST",
        "/api/devices",
        Some(r#"{"DD300": -70000, "M6": 1}"#),
    );
    assert_eq!(status, 200, "{body}");
    // The write returned: it is on disk. Kill without warning.
    server.kill_9();

    let server = Server::start(&dir, &[]);
    let mut ctx = server.client().await;
    assert_eq!(
        ctx.read_holding_registers(10, 1).await.unwrap().unwrap(),
        [4321]
    );
    assert_eq!(
        ctx.read_holding_registers(20, 3).await.unwrap().unwrap(),
        [7, 0xFFFE, 9]
    );
    assert_eq!(
        ctx.read_coils(4, 3).await.unwrap().unwrap()[..3],
        [false, true, true]
    );
    assert_eq!(
        ctx.read_coils(10002, 3).await.unwrap().unwrap()[..3],
        [true, false, true]
    );
    assert_eq!(
        server.get_json("/api/devices?names=DD300,D11"),
        json!({"DD300": -70000, "D11": 0})
    );
    // And again, after a second crash with nothing new written.
    server.kill_9();
    let server = Server::start(&dir, &[]);
    assert_eq!(
        server.get_json("/api/devices?names=D10,D21,M5,M6,X2"),
        json!({"D10": 4321, "D21": -2, "M5": 1, "M6": 1, "X2": 1})
    );
}

#[test]
fn http_api_and_designer_page() {
    let server = Server::start(&state_dir("http"), &[]);

    let (status, page) = server.http("GET", "/", None);
    assert_eq!(status, 200);
    assert!(page.contains("uPlot.iife.min.js") && page.contains("app.js"));
    let (status, js) = server.http("GET", "/app.js", None);
    assert_eq!(status, 200);
    assert!(js.contains("/api/law/"));
    assert_eq!(server.http("GET", "/style.css", None).0, 200);
    assert_eq!(server.http("GET", "/nope", None).0, 404);

    // Status: the PLC scans in real time.
    let first = server.get_json("/api/status");
    assert_eq!(first["scan_us"], 1000);
    assert_eq!(first["modbus"]["address"], server.modbus.to_string());
    let start = Instant::now();
    loop {
        let now = server.get_json("/api/status");
        if now["scans"].as_u64() > first["scans"].as_u64() {
            assert_eq!(now["running"], true);
            assert!(now["sim_time_us"].as_u64() > first["sim_time_us"].as_u64());
            break;
        }
        assert!(start.elapsed() < STEP, "the scan count should grow");
        std::thread::sleep(Duration::from_millis(20));
    }

    // Devices: set, read back, refuse what is read only or malformed.
    let (status, body) = server.http(
        "POST",
        "/api/devices",
        Some(r#"{"D2000": 5200, "DE106": 1.5, "M0": true, "X17": 1}"#),
    );
    assert_eq!(status, 200, "{body}");
    assert_eq!(
        serde_json::from_str::<Value>(&body).unwrap(),
        json!({"D2000": 5200, "DE106": 1.5, "M0": 1, "X17": 1})
    );
    assert_eq!(
        server.get_json("/api/devices?names=D2000:2,M0,X17,Y0"),
        json!({"D2000": 5200, "D2001": 0, "M0": 1, "X17": 1, "Y0": 0})
    );
    for (path, body) in [
        ("/api/devices?names=Q7", None),
        ("/api/devices?names=D8512", None),
        ("/api/devices", None),
    ] {
        assert_eq!(server.http("GET", path, body).0, 400, "{path}");
    }
    for body in [r#"{"Y7": 1}"#, r#"{"M0": 2}"#, "not json", r#"{"C231": 1}"#] {
        let (status, reply) = server.http("POST", "/api/devices", Some(body));
        assert_eq!(status, 400, "{body}");
        assert!(serde_json::from_str::<Value>(&reply).unwrap()["error"].is_string());
    }

    // Designer endpoints.
    let laws = server.get_json("/api/laws");
    assert_eq!(laws.as_array().unwrap().len(), 11);
    let law = server.get_json("/api/law/modified-sine?points=3");
    assert_eq!(law["u"], json!([0.0, 0.5, 1.0]));
    assert_eq!(law["s"][0], json!(0.0));
    assert_eq!(law["s"][2], json!(1.0));
    for key in ["v", "a", "j"] {
        assert_eq!(law[key].as_array().unwrap().len(), 3);
    }
    assert_eq!(server.http("GET", "/api/law/nope", None).0, 400);
    assert_eq!(server.http("GET", "/api/law/cycloid?points=1", None).0, 400);
    let generators = server.get_json("/api/generators");
    assert!(generators.as_array().unwrap().len() >= 4);
    let (status, body) = server.http(
        "POST",
        "/api/table/gen",
        Some(r#"{"generator": "rotary-cut", "params": {"master": 3000, "slave": 1000, "sync": 300, "ratio": "5/3"}}"#),
    );
    assert_eq!(status, 200, "{body}");
    let table: Value = serde_json::from_str(&body).unwrap();
    let master = table["master"].as_array().unwrap();
    assert_eq!(master.first(), Some(&json!(0)));
    assert_eq!(master.last(), Some(&json!(3000)));
    assert_eq!(
        table["slave"].as_array().unwrap().last(),
        Some(&json!(1000))
    );
    assert_eq!(table["velocity"].as_array().unwrap().len(), master.len());
    let (status, body) = server.http(
        "POST",
        "/api/table/gen",
        Some(r#"{"generator": "s-curve", "params": {"max_speed": 0}}"#),
    );
    assert_eq!(status, 400, "{body}");
    // Bounded work: 10^11 points is refused at once, not allocated.
    let (status, body) = server.http(
        "POST",
        "/api/table/gen",
        Some(r#"{"generator": "function", "params": {"expr": "x", "points": 100000000000}}"#),
    );
    assert_eq!(status, 400, "{body}");
    assert!(body.contains("limit"), "{body}");
}

/// The example of document 003, section 4.1.3: a cyclic cam on Y0, its
/// master the pulses of Y1 wired back into X0.
fn decam_cyclic() -> Vec<String> {
    let il = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plc/decam_cyclic.il");
    ["--program", il.to_str().unwrap(), "--wire", "Y1:X0"]
        .map(String::from)
        .to_vec()
}

/// Waits until `log` holds a line containing `needle`; returns the log.
fn log_line(log: &Path, needle: &str) -> String {
    let start = Instant::now();
    loop {
        let text = std::fs::read_to_string(log).unwrap_or_default();
        if text.lines().any(|l| l.contains(needle)) {
            return text;
        }
        assert!(
            start.elapsed() < STEP,
            "no line with {needle:?} on stderr:\n{text}"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Y0's output-pulse counter DD8140, which the cam drives.
async fn y0_pulses(ctx: &mut Context) -> i32 {
    let words = ctx.read_holding_registers(8140, 2).await.unwrap().unwrap();
    (u32::from(words[0]) | u32::from(words[1]) << 16) as i32
}

/// Waits until the cam has moved Y0 by more than 100 pulses.
async fn cam_moves(ctx: &mut Context) {
    let from = y0_pulses(ctx).await;
    eventually(async || (y0_pulses(ctx).await - from).abs() > 100).await;
}

#[tokio::test]
async fn writes_to_special_devices_act_live_but_are_not_restored() {
    let dir = state_dir("special");
    let log = dir.with_extension("log");
    let args = decam_cyclic();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let server = Server::start(&dir, &args);
    {
        let mut ctx = server.client().await;
        cam_moves(&mut ctx).await;
        // M8145: immediate stop of Y0's pulses. It acts at once ...
        ctx.write_single_coil(8145, true).await.unwrap().unwrap();
        ctx.write_single_register(8067, 6705)
            .await
            .unwrap()
            .unwrap();
        // ... alongside ordinary writes: D100/M10 not latched, D300/M600 latched.
        ctx.write_single_register(100, 42).await.unwrap().unwrap();
        ctx.write_single_register(300, 77).await.unwrap().unwrap();
        ctx.write_multiple_coils(10, &[true])
            .await
            .unwrap()
            .unwrap();
        ctx.write_single_coil(600, true).await.unwrap().unwrap();
        // One request across the boundary: D7999 is kept, D8000 is not.
        ctx.write_multiple_registers(7999, &[5, 6])
            .await
            .unwrap()
            .unwrap();
        tokio::time::sleep(Duration::from_millis(100)).await;
        let stopped = y0_pulses(&mut ctx).await;
        tokio::time::sleep(Duration::from_millis(300)).await;
        assert_eq!(y0_pulses(&mut ctx).await, stopped, "M8145 stops Y0 live");
        assert_eq!(
            ctx.read_holding_registers(8067, 1).await.unwrap().unwrap(),
            [6705]
        );
    }
    server.kill_9();

    let server = Server::start_logged(&dir, &args, &log);
    let stderr = log_line(&log, "values restored");
    let mut ctx = server.client().await;
    assert_eq!(
        ctx.read_coils(8145, 1).await.unwrap().unwrap()[..1],
        [false],
        "M8145 restored: {stderr}"
    );
    assert_eq!(
        ctx.read_holding_registers(8067, 1).await.unwrap().unwrap(),
        [0]
    );
    assert_eq!(
        server.get_json("/api/devices?names=D100,D300,M10,M600,D7999,D8000"),
        // D8000 is the watchdog time the PLC sets at power-on (200 ms).
        json!({"D100": 42, "D300": 77, "M10": 1, "M600": 1, "D7999": 5, "D8000": 200})
    );
    cam_moves(&mut ctx).await;
    assert!(!stderr.contains("skipped"), "{stderr}");
}

#[tokio::test]
async fn special_devices_in_an_old_state_directory_are_skipped_and_named() {
    let dir = state_dir("special-old");
    let log = dir.with_extension("log");
    std::fs::create_dir_all(&dir).unwrap();
    // What an older version kept after `M8145 = 1` and `D8067 = 6705`.
    std::fs::write(
        dir.join("snapshot.txt"),
        "# ecam serve snapshot\nD100 42;D8067 6705;M8145 1\n",
    )
    .unwrap();
    std::fs::write(dir.join("journal.log"), "M600 1\n").unwrap();
    let args = decam_cyclic();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let server = Server::start_logged(&dir, &args, &log);
    let stderr = log_line(&log, "values restored");
    assert!(
        stderr
            .lines()
            .any(|l| l.contains("not restoring D8067, M8145") && l.contains("special")),
        "{stderr}"
    );
    assert!(
        stderr.contains("2 values restored") && stderr.contains("2 skipped"),
        "{stderr}"
    );
    let mut ctx = server.client().await;
    assert_eq!(
        server.get_json("/api/devices?names=D100,M600,M8145,D8067"),
        json!({"D100": 42, "M600": 1, "M8145": 0, "D8067": 0})
    );
    cam_moves(&mut ctx).await;
    // Dropped by the compaction at start.
    let snapshot = std::fs::read_to_string(dir.join("snapshot.txt")).unwrap();
    assert!(
        !snapshot.contains("M8145") && !snapshot.contains("D8067"),
        "{snapshot}"
    );
}

#[cfg(unix)]
#[tokio::test]
async fn latched_values_the_program_wrote_survive_a_restart() {
    // While M0 is on the program writes D300 (latched), D50 (not latched),
    // sets M700 (latched) and counts C100 (latched) and C10 (not) up; each
    // rising edge of M1 adds one to D301 (latched).
    let il = program(
        "serve-latched.il",
        "LD M0\nMOV K1234 D300\nMOV K1234 D50\nSET M700\n\
         LD M8013\nAND M0\nOUT C100 K1000\nLD M8013\nAND M0\nOUT C10 K1000\n\
         LDP M1\nINC D301\nEND\n",
    );
    let args = ["--program", il.to_str().unwrap()];
    let dir = state_dir("latched");
    let log = dir.with_extension("log");
    let server = Server::start(&dir, &args);
    let mut ctx = server.client().await;
    ctx.write_single_coil(0, true).await.unwrap().unwrap();
    eventually(async || {
        server.get_json("/api/devices?names=C100")["C100"]
            .as_i64()
            .unwrap()
            >= 1
    })
    .await;
    ctx.write_single_coil(0, false).await.unwrap().unwrap();
    let counted = server.get_json("/api/devices?names=C100,C10");
    // Two saves later (one may have been under way), the final values are
    // on disk: then a crash loses nothing.
    let saves = server.get_json("/api/status")["state"]["latched_saves"]
        .as_u64()
        .unwrap();
    eventually(async || {
        server.get_json("/api/status")["state"]["latched_saves"]
            .as_u64()
            .unwrap()
            > saves + 1
    })
    .await;
    drop(ctx);
    server.kill_9();

    let server = Server::start(&dir, &args);
    assert_eq!(
        server.get_json("/api/devices?names=M0,D300,D50,M700,C100,C10"),
        json!({"M0": 0, "D300": 1234, "D50": 0, "M700": 1,
               "C100": counted["C100"], "C10": 0})
    );
    // A clean stop saves the program's last latched values: D301, counted
    // up just before SIGTERM (M1 is restored off, so no edge recounts it).
    let stopped_log = dir.with_extension("stop.log");
    server.kill_9();
    let server = Server::start_logged(&dir, &args, &stopped_log);
    let mut ctx = server.client().await;
    ctx.write_single_coil(1, true).await.unwrap().unwrap();
    eventually(async || server.get_json("/api/devices?names=D301")["D301"] == 1).await;
    ctx.write_single_coil(1, false).await.unwrap().unwrap();
    drop(ctx);
    server.terminate();
    log_line(&stopped_log, "latched values saved");
    let server = Server::start_logged(&dir, &args, &log);
    log_line(&log, "values restored");
    assert_eq!(
        server.get_json("/api/devices?names=D300,M700,D301,M1"),
        json!({"D300": 1234, "M700": 1, "D301": 1, "M1": 0})
    );
}

/// Reads a signed 32-bit register pair (low word first).
async fn dword(ctx: &mut Context, at: u16) -> i64 {
    let words = ctx.read_holding_registers(at, 2).await.unwrap().unwrap();
    i64::from((u32::from(words[0]) | u32::from(words[1]) << 16) as i32)
}

#[tokio::test]
async fn a_table_written_over_modbus_while_the_cam_runs_takes_over_at_the_seam() {
    // The rotary knife: ECAMTBX's rotary-cut table (3183 feed counts per
    // 1000 knife pulses) run as the cyclic cam.
    let dir = state_dir("table-edit");
    let il = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plc/rotary_knife.il");
    let server = Server::start(
        &dir,
        &["--program", il.to_str().unwrap(), "--wire", "Y1:X0"],
    );
    let mut ctx = server.client().await;
    cam_moves(&mut ctx).await;
    // One request: a straight table over the same cut, 2 points.
    let table: [u16; 10] = [2, 40, 0, 0, 0, 0, 3183, 0, 1000, 0];
    ctx.write_multiple_registers(2038, &table)
        .await
        .unwrap()
        .unwrap();
    // The knife never steps back, across the seam that takes the new table.
    let mut last = y0_pulses(&mut ctx).await;
    let start = Instant::now();
    let mut straight = 0;
    // Until 50 samples show the straight table (bounded; a loaded machine
    // takes fewer samples per second, so no wall-time window).
    while straight <= 50 && start.elapsed() < STEP {
        let now = y0_pulses(&mut ctx).await;
        assert!(now >= last, "the knife stepped back: {last} -> {now}");
        last = now;
        // On the straight table the knife's place in its revolution is
        // the feed's place in the cut × 1000 / 3183.
        let slave = dword(&mut ctx, 2019).await;
        let in_cut = dword(&mut ctx, 2027).await;
        let expected = (in_cut * 1000 + 1591) / 3183;
        if (slave - expected)
            .rem_euclid(1000)
            .min((expected - slave).rem_euclid(1000))
            <= 6
        {
            straight += 1;
        }
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    assert!(straight > 50, "the straight table runs: {straight} samples");
    let flags = ctx.read_holding_registers(2001, 1).await.unwrap().unwrap()[0];
    assert_eq!(flags & 0b1_0011_1000, 0, "no error flags: {flags:#b}");
}

/// Runs `ecam serve --state dir` expecting it to refuse to start; returns
/// its stderr (fails the test if it is still running after [`STEP`]).
fn refused_start(dir: &Path) -> String {
    let mut child = Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(["serve", "--modbus", "127.0.0.1:0", "--http", "127.0.0.1:0"])
        .arg("--state")
        .arg(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > STEP {
            let _ = child.kill();
            let _ = child.wait();
            panic!("ecam serve started on a damaged state directory");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let status = child.wait().unwrap();
    let mut stderr = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut stderr)
        .unwrap();
    assert!(!status.success(), "{stderr}");
    stderr
}

#[tokio::test]
async fn a_damaged_journal_stops_the_start_and_recover_state_drops_what_follows() {
    let dir = state_dir("damaged");
    let server = Server::start(&dir, &[]);
    {
        let mut ctx = server.client().await;
        for (register, value) in [(100, 1), (101, 2), (102, 3)] {
            ctx.write_single_register(register, value)
                .await
                .unwrap()
                .unwrap();
        }
    }
    server.kill_9();
    // A changed digit in the second record (D101 = 2 becomes 7).
    let journal = dir.join("journal.log");
    let text = std::fs::read_to_string(&journal).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 3, "{text}");
    assert!(lines[1].ends_with("D101 2"), "{text}");
    let damaged = text.replacen("D101 2", "D101 7", 1);
    std::fs::write(&journal, &damaged).unwrap();

    let stderr = refused_start(&dir);
    assert!(
        stderr.contains("journal.log:2: checksum mismatch") && stderr.contains("--recover-state"),
        "{stderr}"
    );
    // Refusing left the files as they were.
    assert_eq!(std::fs::read_to_string(&journal).unwrap(), damaged);

    let log = dir.with_extension("log");
    let server = Server::start_logged(&dir, &["--recover-state"], &log);
    let stderr = log_line(&log, "values restored");
    assert!(
        stderr.contains("journal.log:2: checksum mismatch: 2 records dropped"),
        "{stderr}"
    );
    assert!(
        stderr.contains("1 values restored") && stderr.contains("2 damaged records dropped"),
        "{stderr}"
    );
    assert!(stderr.contains("journal.log.damaged"), "{stderr}");
    assert_eq!(
        server.get_json("/api/devices?names=D100,D101,D102"),
        json!({"D100": 1, "D101": 0, "D102": 0})
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("journal.log.damaged")).unwrap(),
        damaged
    );
    server.kill_9();
    // The recovered state is consistent: a plain start takes it.
    let server = Server::start(&dir, &[]);
    assert_eq!(
        server.get_json("/api/devices?names=D100,D101"),
        json!({"D100": 1, "D101": 0})
    );
}

#[tokio::test]
async fn a_zeroed_journal_stops_the_start_and_recover_state_keeps_it_aside() {
    let dir = state_dir("zeroed");
    let server = Server::start(&dir, &[]);
    {
        let mut ctx = server.client().await;
        for (register, value) in [(100, 1), (101, 2)] {
            ctx.write_single_register(register, value)
                .await
                .unwrap()
                .unwrap();
        }
    }
    server.kill_9();
    // The file system kept the journal's length but lost its blocks.
    let journal = dir.join("journal.log");
    let length = std::fs::metadata(&journal).unwrap().len() as usize;
    assert!(length > 0);
    std::fs::write(&journal, vec![0u8; length]).unwrap();
    let stderr = refused_start(&dir);
    assert!(stderr.contains("journal.log:1: "), "{stderr}");
    assert!(stderr.contains("zeroed or overwritten"), "{stderr}");
    let log = dir.with_extension("log");
    let server = Server::start_logged(&dir, &["--recover-state"], &log);
    let said = log_line(&log, "--recover-state: ");
    assert!(said.contains("whatever it held is lost"), "{said}");
    assert!(dir.join("journal.log.damaged").exists());
    assert_eq!(
        server.get_json("/api/devices?names=D100:2"),
        json!({"D100": 0, "D101": 0})
    );
}

#[tokio::test]
async fn a_snapshot_cut_inside_a_number_stops_the_start() {
    let dir = state_dir("cut-snapshot");
    let server = Server::start(&dir, &[]);
    server
        .client()
        .await
        .write_multiple_registers(100, &[12345, 7])
        .await
        .unwrap()
        .unwrap();
    server.kill_9();
    // A clean start compacts the journal into the snapshot.
    Server::start(&dir, &[]).kill_9();
    let snapshot = dir.join("snapshot.txt");
    let text = std::fs::read_to_string(&snapshot).unwrap();
    let cut = text.find("12345").unwrap() + 2;
    std::fs::write(&snapshot, &text[..cut]).unwrap();
    let stderr = refused_start(&dir);
    assert!(stderr.contains("snapshot.txt:2: cut short"), "{stderr}");
}

#[cfg(unix)]
#[tokio::test]
async fn a_start_that_cannot_compact_serves_read_only() {
    let dir = state_dir("read-only");
    let server = Server::start(&dir, &[]);
    server
        .client()
        .await
        .write_single_register(100, 42)
        .await
        .unwrap()
        .unwrap();
    server.kill_9();
    let journal = std::fs::read_to_string(dir.join("journal.log")).unwrap();
    // The new snapshot cannot be written, as on a full disk.
    std::fs::create_dir(dir.join("snapshot.txt.tmp")).unwrap();
    let log = dir.with_extension("log");
    let server = Server::start_logged(&dir, &[], &log);
    let stderr = log_line(&log, "READ-ONLY");
    assert!(stderr.contains("every write is refused"), "{stderr}");
    let status = server.get_json("/api/status");
    assert!(
        status["state"]["read_only"]
            .as_str()
            .is_some_and(|r| r.contains("snapshot.txt.tmp")),
        "{status}"
    );
    let mut ctx = server.client().await;
    assert_eq!(
        ctx.read_holding_registers(100, 1).await.unwrap().unwrap(),
        [42]
    );
    assert_eq!(
        ctx.write_single_register(100, 1).await.unwrap().err(),
        Some(ExceptionCode::ServerDeviceFailure)
    );
    assert_eq!(
        ctx.read_holding_registers(100, 1).await.unwrap().unwrap(),
        [42]
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("journal.log")).unwrap(),
        journal
    );
    server.kill_9();
    std::fs::remove_dir(dir.join("snapshot.txt.tmp")).unwrap();
    let server = Server::start(&dir, &[]);
    assert!(server.get_json("/api/status")["state"]["read_only"].is_null());
    server
        .client()
        .await
        .write_single_register(100, 1)
        .await
        .unwrap()
        .unwrap();
}

#[tokio::test]
async fn a_table_loaded_over_http_is_one_write_and_waits_for_the_seam_while_running() {
    let dir = state_dir("table-load");
    let il = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plc/rotary_knife.il");
    let server = Server::start(
        &dir,
        &["--program", il.to_str().unwrap(), "--wire", "Y1:X0"],
    );
    let mut ctx = server.client().await;
    cam_moves(&mut ctx).await;
    let table = r#""points": [[0, 0], [3183, 1000]]"#;
    // The knife's cam runs: refused unless asked to switch at the seam.
    let (status, body) = server.http(
        "POST",
        "/api/table/load",
        Some(&format!(r#"{{"block": 2000, {table}}}"#)),
    );
    assert_eq!(status, 409, "{body}");
    let (status, body) = server.http(
        "POST",
        "/api/table/load",
        Some(&format!(
            r#"{{"block": 2000, {table}, "while_running": "at-seam"}}"#
        )),
    );
    assert_eq!(status, 200, "{body}");
    assert!(body.contains("\"switch\":\"at-seam\""), "{body}");
    assert_eq!(
        server.get_json("/api/devices?names=D2038,D2002"),
        json!({"D2038": 2, "D2002": 0})
    );
    // An idle block takes it at once; a bad table changes nothing.
    let (status, body) = server.http(
        "POST",
        "/api/table/load",
        Some(&format!(r#"{{"block": "D3000", {table}}}"#)),
    );
    assert_eq!(status, 200, "{body}");
    assert!(body.contains("\"switch\":\"now\""), "{body}");
    let (status, body) = server.http(
        "POST",
        "/api/table/load",
        Some(r#"{"block": 3000, "points": [[9, 0], [1, 1]]}"#),
    );
    assert_eq!(status, 400, "{body}");
    assert!(body.contains("6782"), "{body}");
    assert_eq!(
        server.get_json("/api/devices?names=D3038"),
        json!({"D3038": 2})
    );
    // The knife keeps turning forwards across the switch.
    let before = y0_pulses(&mut ctx).await;
    tokio::time::sleep(Duration::from_millis(500)).await;
    assert!(y0_pulses(&mut ctx).await > before);
}

#[test]
fn the_designers_table_facts_come_from_the_server() {
    let server = Server::start_stateless(&[]);
    // A DECAM block is named by what the device really is.
    let (status, body) = server.http("GET", "/api/block?name=D9000", None);
    assert_eq!(status, 400);
    assert!(
        body.contains("D9000 is past the last data register, D8511"),
        "{body}"
    );
    let (status, body) = server.http("GET", "/api/block?name=M100", None);
    assert_eq!(status, 400);
    assert!(body.contains("M100 is an auxiliary relay"), "{body}");
    assert_eq!(server.get_json("/api/block?name=2000")["block"], 2000);
    // Limits and option names.
    let limits = server.get_json("/api/limits");
    assert_eq!(limits["table_points"]["max"], 512);
    assert_eq!(limits["key_curves"][0], "constant-acceleration");
    // A point table checked, with its velocity steps; a file read and written.
    let (status, body) = server.http(
        "POST",
        "/api/table/check",
        Some(r#"{"points": [[0, 0], [10, 10], [40, 100], [50, 100]]}"#),
    );
    assert_eq!(status, 200, "{body}");
    let checked: Value = serde_json::from_str(&body).unwrap();
    assert_eq!(checked["steps"]["velocity"].as_array().unwrap().len(), 3);
    let (status, body) = server.http(
        "POST",
        "/api/table/read",
        Some(r#"{"name": "t.csv", "text": "master,slave\n0,0\n# c\n10,x\n"}"#),
    );
    assert_eq!(status, 400);
    assert!(body.contains("t.csv: line 4: slave `x`"), "{body}");
    let (status, body) = server.http(
        "POST",
        "/api/table/convert",
        Some(r#"{"format": "json", "points": [[0, 0], [100, 50]], "sync": [0, 10]}"#),
    );
    assert_eq!(status, 200, "{body}");
    assert!(
        body.contains(r#"\"low\": 0"#) || body.contains(r#"\"low\":0"#),
        "{body}"
    );
}
