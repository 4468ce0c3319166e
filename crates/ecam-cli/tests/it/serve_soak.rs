//! A bounded soak of `ecam serve --state`: concurrent Modbus and HTTP
//! writers with malformed frames mixed in, `kill -9` while they write and
//! while the server recovers, and afterwards every acknowledged write is
//! there. Loopback only; a few seconds in all.

use std::collections::HashMap;
use std::io::{Read as _, Write as _};
use std::net::{SocketAddr, TcpStream};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use crate::serve::Server;

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

#[test]
fn acknowledged_writes_survive_kill_9_under_concurrent_and_hostile_clients() {
    let state = crate::common::scratch_dir("serve-soak");
    let ledger: Ledger = Arc::new(Mutex::new(HashMap::new()));
    for round in 0..4u16 {
        let server = Server::start(&state, &[]);
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
        std::thread::sleep(Duration::from_millis(800 + 200 * u64::from(round)));
        server.kill_9();
        stop.store(true, Ordering::Relaxed);
        for w in workers {
            w.join().unwrap();
        }
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
    server.kill_9();
}
