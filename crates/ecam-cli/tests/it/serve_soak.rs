//! A bounded soak of `ecam serve --state`: concurrent Modbus and HTTP
//! writers with malformed frames mixed in, `kill -9` while they write and
//! while the server recovers, and afterwards every acknowledged write is
//! there. Each round also throws issue 25's faults at it while the writers
//! write: live views that never answer, POSTs whose body never comes,
//! Modbus clients that fill the cap and go quiet, design requests
//! abandoned by their client, hostile bodies (answered briefly, in the
//! server's words), a program that loops until the watchdog stops it, and
//! a command-line run that would take hours; newcomers must still be
//! served. At the end the journal is zeroed: the start refuses it, and
//! `--recover-state` keeps it aside. Loopback only; about a minute.

use std::collections::HashMap;
use std::io::{Read as _, Write as _};
use std::net::{SocketAddr, TcpStream};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use crate::serve::{Server, http, program};
use crate::serve_limits::{modbus_answers, newcomers_served, silent_live_view, silent_post};

const TIMEOUT: Duration = Duration::from_secs(5);

/// Register -> (last acknowledged value, value possibly in flight).
type Ledger = Arc<Mutex<HashMap<u16, (u16, Option<u16>)>>>;

fn modbus_writer(addr: SocketAddr, first: u16, stop: Arc<AtomicBool>, ledger: Ledger) {
    let Ok(mut s) = TcpStream::connect_timeout(&addr, TIMEOUT) else {
        return;
    };
    let _ = s.set_read_timeout(Some(TIMEOUT));
    let mut value = 1u16;
    while !stop.load(Ordering::Relaxed) {
        let register = first + value % 8;
        ledger
            .lock()
            .unwrap()
            .entry(register)
            .or_insert((0, None))
            .1 = Some(value);
        let [rh, rl] = register.to_be_bytes();
        let [vh, vl] = value.to_be_bytes();
        if s.write_all(&[0, 1, 0, 0, 0, 6, 1, 6, rh, rl, vh, vl])
            .is_err()
        {
            return;
        }
        let mut reply = [0u8; 12];
        if s.read_exact(&mut reply).is_err() || reply[7] != 6 {
            return;
        }
        ledger.lock().unwrap().insert(register, (value, None));
        value = value.wrapping_add(1).max(1);
    }
}

fn http_writer(addr: SocketAddr, first: u16, stop: Arc<AtomicBool>, ledger: Ledger) {
    let mut value = 1u16;
    while !stop.load(Ordering::Relaxed) {
        let register = first + value % 4;
        ledger
            .lock()
            .unwrap()
            .entry(register)
            .or_insert((0, None))
            .1 = Some(value);
        let body = format!("{{\"D{register}\": {value}}}");
        let Ok(mut s) = TcpStream::connect_timeout(&addr, TIMEOUT) else {
            return;
        };
        let _ = s.set_read_timeout(Some(TIMEOUT));
        let request = format!(
            "POST /api/devices HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\
             Content-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
            body.len()
        );
        if s.write_all(request.as_bytes()).is_err() {
            return;
        }
        let mut response = String::new();
        let _ = s.read_to_string(&mut response);
        if !response.starts_with("HTTP/1.1 200") {
            return;
        }
        ledger.lock().unwrap().insert(register, (value, None));
        value = value.wrapping_add(1).max(1);
    }
}

fn garbage(addr: SocketAddr, stop: Arc<AtomicBool>) {
    let frames: [&[u8]; 4] = [
        &[0, 1, 0, 0, 0, 2, 1, 0x0F],
        &[0, 1, 0, 5, 0, 6, 1, 3, 0, 0, 0, 1],
        &[0xFF; 12],
        &[0, 1, 0, 0, 0, 6, 1, 16, 0, 0, 0, 200],
    ];
    let mut i = 0;
    while !stop.load(Ordering::Relaxed) {
        if let Ok(mut s) = TcpStream::connect_timeout(&addr, TIMEOUT) {
            let _ = s.set_read_timeout(Some(Duration::from_millis(100)));
            let _ = s.write_all(frames[i % frames.len()]);
            let mut sink = [0u8; 64];
            let _ = s.read(&mut sink);
        }
        i += 1;
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// Issue 25's faults, over and over until `stop`; `served` counts the
/// times a newcomer was served meanwhile.
fn faults(server: (SocketAddr, SocketAddr), stop: Arc<AtomicBool>, served: Arc<Mutex<u32>>) {
    let (modbus, http_addr) = server;
    let heavy = format!(
        r#"{{"generator": "function", "params": {{"expr": "{}", "to": 10000000, "points": 100001}}}}"#,
        vec!["sin(x/1000)"; 300].join("+")
    );
    let mut held: Vec<TcpStream> = Vec::new();
    let mut i = 0u32;
    while !stop.load(Ordering::Relaxed) {
        // Live views that never answer a ping, silent POSTs, quiet Modbus
        // clients: more than the caps.
        held.extend((0..20).filter_map(|_| silent_live_view(http_addr)));
        held.extend((0..10).filter_map(|_| silent_post(http_addr)));
        for _ in 0..20 {
            if let Ok(mut s) = TcpStream::connect_timeout(&modbus, TIMEOUT) {
                let _ = s.set_read_timeout(Some(TIMEOUT));
                if modbus_answers(&mut s) {
                    held.push(s);
                }
            }
        }
        // Design work abandoned by its client.
        if let Ok(mut s) = TcpStream::connect_timeout(&http_addr, TIMEOUT) {
            let _ = write!(
                s,
                "POST /api/table/gen HTTP/1.1\r\nHost: {http_addr}\r\nContent-Type: application/json\r\n\
                 Content-Length: {}\r\n\r\n{heavy}",
                heavy.len()
            );
            std::thread::sleep(Duration::from_millis(50));
        }
        // A hostile body: answered 400, briefly, in the server's words
        // (unless the server was just killed).
        let huge = format!(r#"{{"D{}": 1}}"#, "9".repeat(200_000 + i as usize));
        if let Some((code, text)) = try_post(http_addr, "/api/devices", &huge) {
            assert_eq!(code, 400, "{text}");
            assert!(text.len() < 400, "{} bytes", text.len());
        }
        if let (Some(_), Some(_)) = newcomers_served(modbus, http_addr) {
            *served.lock().unwrap() += 1;
        }
        held.truncate(200);
        i += 1;
    }
}

#[test]
fn acknowledged_writes_survive_kill_9_under_concurrent_and_hostile_clients() {
    let state = crate::common::scratch_dir("serve-soak");
    let ledger: Ledger = Arc::new(Mutex::new(HashMap::new()));
    // X0 on (written by one round, restored in the next): a loop the
    // watchdog stops, at once at the next start.
    let il = program(
        "soak.il",
        "LD M8000\nOUT Y7\nLDI X0\nCJ P1\nP0\nLD X0\nCJ P0\nP1\nEND\n",
    );
    let endless = program("soak-endless.il", "P0\nLD M8000\nCJ P0\n");
    for round in 0..4u16 {
        let server = Server::start(
            &state,
            &[
                "--program",
                il.to_str().unwrap(),
                "--max-connections",
                "32",
                "--idle-timeout",
                "3",
            ],
        );
        let (modbus, http) = (server.modbus, server.http);
        let stop = Arc::new(AtomicBool::new(false));
        let mut workers = Vec::new();
        for w in 0..3u16 {
            let (stop, ledger) = (Arc::clone(&stop), Arc::clone(&ledger));
            workers.push(std::thread::spawn(move || {
                modbus_writer(modbus, 1000 + 10 * w, stop, ledger)
            }));
        }
        {
            let (stop, ledger) = (Arc::clone(&stop), Arc::clone(&ledger));
            workers.push(std::thread::spawn(move || {
                http_writer(http, 1100, stop, ledger)
            }));
        }
        {
            let stop = Arc::clone(&stop);
            workers.push(std::thread::spawn(move || garbage(modbus, stop)));
        }
        let served = Arc::new(Mutex::new(0u32));
        {
            let (stop, served) = (Arc::clone(&stop), Arc::clone(&served));
            workers.push(std::thread::spawn(move || {
                faults((modbus, http), stop, served)
            }));
        }
        // A command-line run that would loop for hours without the
        // watchdog and the run's budget.
        let mut cli = Command::new(env!("CARGO_BIN_EXE_ecam"))
            .args([
                "plc",
                "run",
                endless.to_str().unwrap(),
                "--ms",
                "100000",
                "--dump",
                "M8061",
            ])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(3000 + 500 * u64::from(round)));
        if round == 1 {
            // X0 on: the program loops until the watchdog stops it.
            let mut s = TcpStream::connect_timeout(&modbus, TIMEOUT).unwrap();
            let _ = s.set_read_timeout(Some(TIMEOUT));
            s.write_all(&[0, 9, 0, 0, 0, 6, 1, 5, 0x27, 0x10, 0xFF, 0])
                .unwrap();
            let mut echo = [0u8; 12];
            s.read_exact(&mut echo).unwrap();
            let asked = std::time::Instant::now();
            let mut stopped = false;
            while !stopped && asked.elapsed() < Duration::from_secs(20) {
                // M8061 (coil 8061), read while the writers write.
                s.write_all(&[0, 9, 0, 0, 0, 6, 1, 1, 0x1F, 0x7D, 0, 1])
                    .unwrap();
                let mut reply = [0u8; 10];
                s.read_exact(&mut reply).unwrap();
                stopped = reply[9] & 1 == 1;
                std::thread::sleep(Duration::from_millis(50));
            }
            assert!(stopped, "the watchdog stopped the looping program");
        }
        let asked = std::time::Instant::now();
        while cli.try_wait().unwrap().is_none() && asked.elapsed() < Duration::from_secs(20) {
            std::thread::sleep(Duration::from_millis(50));
        }
        let cli_done = cli.try_wait().unwrap().is_some();
        if !cli_done {
            let _ = cli.kill();
        }
        let mut out = String::new();
        cli.stdout.take().unwrap().read_to_string(&mut out).unwrap();
        cli.wait().unwrap();
        assert!(cli_done, "plc run of an endless loop still runs");
        assert_eq!(out.trim(), r#"{"M8061": 1}"#, "stopped by the watchdog");
        server.kill_9();
        stop.store(true, Ordering::Relaxed);
        for w in workers {
            w.join().unwrap();
        }
        assert!(
            *served.lock().unwrap() > 0,
            "no newcomer served in round {round}"
        );
        // Killed again while it recovers (before it serves anyone).
        let mut recovering = Command::new(env!("CARGO_BIN_EXE_ecam"))
            .args(["serve", "--modbus", "127.0.0.1:0", "--http", "127.0.0.1:0"])
            .arg("--state")
            .arg(&state)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(10 * u64::from(round)));
        recovering.kill().unwrap();
        recovering.wait().unwrap();
    }
    let server = Server::start(&state, &[]);
    let status = server.get_json("/api/status");
    let http = server.http;
    let ledger = ledger.lock().unwrap();
    assert!(
        ledger.values().filter(|(v, _)| *v != 0).count() > 10,
        "writes were made"
    );
    for (&register, &(acknowledged, in_flight)) in ledger.iter() {
        let mut s = TcpStream::connect_timeout(&http, TIMEOUT).unwrap();
        let _ = s.set_read_timeout(Some(TIMEOUT));
        write!(
            s,
            "GET /api/devices?names=D{register} HTTP/1.1\r\nHost: {http}\r\nConnection: close\r\n\r\n"
        )
        .unwrap();
        let mut response = String::new();
        s.read_to_string(&mut response).unwrap();
        let body = response.split("\r\n\r\n").nth(1).unwrap_or("");
        let value: serde_json::Value = serde_json::from_str(body).unwrap();
        let got = value[format!("D{register}")].as_i64().unwrap();
        let allowed: Vec<i64> = [Some(acknowledged), in_flight]
            .into_iter()
            .flatten()
            .map(i64::from)
            .collect();
        assert!(
            allowed.contains(&got),
            "D{register}: {got}, acknowledged {acknowledged}, in flight {in_flight:?}"
        );
    }
    assert_eq!(status["plc"]["state"], "run", "no program: nothing to stop");
    server.kill_9();

    // The journal zeroed (its blocks lost): refused with file:line, or
    // kept aside by --recover-state.
    let journal = state.join("journal.log");
    let mut length = std::fs::metadata(&journal).unwrap().len();
    if length == 0 {
        let server = Server::start(&state, &[]);
        assert!(http_write(server.http));
        server.kill_9();
        length = std::fs::metadata(&journal).unwrap().len();
    }
    std::fs::write(&journal, vec![0u8; usize::try_from(length).unwrap()]).unwrap();
    let refused = Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args([
            "serve",
            "--modbus",
            "127.0.0.1:0",
            "--http",
            "127.0.0.1:0",
            "--state",
        ])
        .arg(&state)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success());
    assert!(
        stderr.contains("journal.log:1: ") && stderr.contains("zeroed"),
        "{stderr}"
    );
    let server = Server::start(&state, &["--recover-state"]);
    assert!(state.join("journal.log.damaged").exists());
    server.kill_9();
}

/// One POST; its status and body, or `None` when the server is gone.
fn try_post(addr: SocketAddr, path: &str, body: &str) -> Option<(u16, String)> {
    let mut s = TcpStream::connect_timeout(&addr, TIMEOUT).ok()?;
    s.set_read_timeout(Some(TIMEOUT)).ok()?;
    write!(
        s,
        "POST {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\
         Content-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
        body.len()
    )
    .ok()?;
    let mut response = String::new();
    s.read_to_string(&mut response).ok()?;
    let (head, body) = response.split_once("\r\n\r\n")?;
    let status = head.split_whitespace().nth(1)?.parse().ok()?;
    Some((status, body.to_string()))
}

/// One acknowledged HTTP write.
fn http_write(addr: SocketAddr) -> bool {
    http(addr, "POST", "/api/devices", Some(r#"{"D1199": 5}"#)).0 == 200
}
