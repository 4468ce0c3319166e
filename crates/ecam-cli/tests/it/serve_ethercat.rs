//! `ecam serve --ethercat`: the PLC's pulse outputs on emulated CiA 402
//! drives, talked to as a user would: Modbus (input registers 20000…,
//! coils 14000/14001, the program's relays), HTTP (`/api/ethercat`), a
//! fault injected and cleared, SIGTERM with the summary line; and the
//! errors a bad configuration gets.

use std::io::{BufRead as _, BufReader};
use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use serde_json::Value;
use tokio_modbus::client::Context;
use tokio_modbus::prelude::*;

use crate::common::{ecam, fails, scratch_dir};

const STEP: Duration = Duration::from_secs(20);

/// A server with every stdout line kept (the summary comes at exit).
struct BusServer {
    child: Child,
    modbus: SocketAddr,
    http: SocketAddr,
    stdout: Arc<Mutex<Vec<String>>>,
}

impl BusServer {
    fn start(args: &[&str]) -> Self {
        let mut child = Command::new(env!("CARGO_BIN_EXE_ecam"))
            .args(["serve", "--modbus", "127.0.0.1:0", "--http", "127.0.0.1:0"])
            .args(args)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let stdout = child.stdout.take().unwrap();
        let lines = Arc::new(Mutex::new(Vec::new()));
        let keep = Arc::clone(&lines);
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines() {
                let Ok(line) = line else { return };
                keep.lock().unwrap().push(line);
            }
        });
        let start = Instant::now();
        while lines.lock().unwrap().len() < 2 {
            assert!(
                start.elapsed() < STEP,
                "ecam serve did not print its addresses"
            );
            std::thread::sleep(Duration::from_millis(20));
        }
        let addr = |kind: &str| -> SocketAddr {
            let lines = lines.lock().unwrap();
            let line = lines.iter().find(|l| l.starts_with(kind)).unwrap();
            line.split_once(' ').unwrap().1.parse().unwrap()
        };
        Self {
            modbus: addr("modbus"),
            http: addr("http"),
            child,
            stdout: lines,
        }
    }

    async fn client(&self) -> Context {
        tokio::time::timeout(STEP, tokio_modbus::client::tcp::connect(self.modbus))
            .await
            .unwrap()
            .unwrap()
    }

    fn http(&self, method: &str, path: &str, body: Option<&str>) -> (u16, String) {
        crate::serve::http(self.http, method, path, body)
    }

    fn snapshot(&self) -> Value {
        let (status, body) = self.http("GET", "/api/ethercat", None);
        assert_eq!(status, 200, "{body}");
        serde_json::from_str(&body).unwrap()
    }

    /// SIGTERM; waits for the exit and returns the last stdout line.
    fn terminate(mut self) -> String {
        let pid = self.child.id().to_string();
        assert!(
            Command::new("kill")
                .args(["-TERM", &pid])
                .status()
                .unwrap()
                .success()
        );
        let start = Instant::now();
        while self.child.try_wait().unwrap().is_none() {
            assert!(start.elapsed() < STEP, "ecam serve did not stop on SIGTERM");
            std::thread::sleep(Duration::from_millis(20));
        }
        // The reader thread may still be taking the last line.
        std::thread::sleep(Duration::from_millis(100));
        self.stdout
            .lock()
            .unwrap()
            .last()
            .cloned()
            .unwrap_or_default()
    }
}

impl Drop for BusServer {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

async fn eventually(what: &str, mut check: impl AsyncFnMut() -> bool) {
    let start = Instant::now();
    while !check().await {
        assert!(start.elapsed() < STEP, "{what}: not reached in time");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
}

async fn input(ctx: &mut Context, address: u16, n: u16) -> Vec<u16> {
    ctx.read_input_registers(address, n).await.unwrap().unwrap()
}

fn i32_at(words: &[u16], at: usize) -> i64 {
    i64::from((u32::from(words[at]) | u32::from(words[at + 1]) << 16) as i32)
}

async fn line_state(ctx: &mut Context) -> u16 {
    input(ctx, 20001, 1).await[0]
}

async fn m(ctx: &mut Context, n: u16) -> bool {
    ctx.read_coils(n, 1).await.unwrap().unwrap()[0]
}

/// Drive `n`'s block: state, statusword, error code, flags, actual,
/// target, following error, output.
async fn drive(ctx: &mut Context, n: u16) -> Vec<u16> {
    input(ctx, 20016 + 16 * n, 16).await
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[tokio::test]
async fn pulse_outputs_drive_emulated_drives_over_modbus_and_http() {
    let dir = scratch_dir("serve-ethercat");
    // M0 starts a 1000-pulse train on Y0 at 2 kHz (half a second).
    let program = write(&dir, "train.il", "LD M0\nDPLSY K2000 K1000 Y0\n");
    let config = write(
        &dir,
        "line.toml",
        "cycle_us = 1000\nenable_at_start = false\nfault_relay = \"M100\"\n\
         running_relay = \"M101\"\n\
         [[output]]\npulse = \"Y0\"\ndrive = 0\nscale = [25, 2]\n\
         [[output]]\npulse = \"Y1\"\ndrive = 1\n",
    );
    let server = BusServer::start(&[
        "--program",
        program.to_str().unwrap(),
        "--ethercat",
        config.to_str().unwrap(),
        "--emulated",
        "2",
    ]);
    let mut ctx = server.client().await;

    // Waiting for the enable: stopped, coils off, the relays say so.
    eventually("first snapshot", async || {
        input(&mut ctx, 20000, 1).await[0] == 2
    })
    .await;
    assert_eq!(line_state(&mut ctx).await, 0);
    assert_eq!(
        ctx.read_coils(14000, 2).await.unwrap().unwrap(),
        vec![false, false]
    );
    assert!(!m(&mut ctx, 101).await);
    // A cycle a loaded host loses shows the drive as not answering for
    // that cycle: wait for one it answered.
    eventually("drive 0 answers", async || {
        drive(&mut ctx, 0).await[3] & 0b0001 == 0b0001
    })
    .await;
    let d0 = drive(&mut ctx, 0).await;
    assert_eq!(d0[10], 0, "drive 0 follows Y0");
    assert_eq!(d0[3] & 0b1010, 0b1000, "not enabled, follows");
    assert_eq!(d0[0], 1, "switch on disabled");

    // Enable over Modbus.
    ctx.write_single_coil(14000, true).await.unwrap().unwrap();
    eventually("running", async || line_state(&mut ctx).await == 2).await;
    assert!(m(&mut ctx, 14000).await);
    eventually("running relay", async || m(&mut ctx, 101).await).await;
    let d0 = drive(&mut ctx, 0).await;
    assert_eq!(d0[0], 4, "operation enabled");
    let start = i32_at(&d0, 4);

    // Run the pulse train: the drive moves exactly 1000 · 25/2 counts.
    ctx.write_single_coil(0, true).await.unwrap().unwrap();
    let goal = start + 12_500;
    eventually("the train's end", async || {
        let d = drive(&mut ctx, 0).await;
        i32_at(&d, 4) == goal && i32_at(&d, 6) == goal
    })
    .await;
    let pulses = ctx.read_holding_registers(8140, 2).await.unwrap().unwrap();
    assert_eq!(i32_at(&pulses, 0), 1000);
    let json = server.snapshot();
    assert_eq!(json["state"], "running");
    assert_eq!(json["drives"][0]["actual"], goal);
    assert_eq!(json["drives"][0]["state"], "operation enabled");
    assert_eq!(json["drives"][1]["output"], 1);

    // A fault on drive 1: the line stops, every place says so.
    let (status, body) = server.http(
        "POST",
        "/api/ethercat/fault",
        Some(r#"{"drive": 1, "code": 29952}"#),
    );
    assert_eq!(status, 202, "{body}");
    eventually("faulted", async || line_state(&mut ctx).await == 3).await;
    assert_eq!(
        ctx.read_coils(14000, 2).await.unwrap().unwrap(),
        vec![false, true]
    );
    eventually("fault relay", async || m(&mut ctx, 100).await).await;
    // The drive passes through "fault reaction active" (6) on its way.
    eventually("drive 1 in fault", async || {
        drive(&mut ctx, 1).await[0] == 7
    })
    .await;
    let d1 = drive(&mut ctx, 1).await;
    assert_eq!((d1[0], d1[2]), (7, 29952), "fault, its code");
    assert_ne!(d1[3] & 0b100, 0);
    assert_eq!(
        input(&mut ctx, 20002, 1).await[0],
        1,
        "one fault holds the line"
    );
    assert!(
        server.snapshot()["faults"][0]
            .as_str()
            .unwrap()
            .contains("drive 1")
    );

    // Reset and enable back to back, as a program would write them.
    ctx.write_multiple_coils(14000, &[false, true])
        .await
        .unwrap()
        .unwrap();
    ctx.write_single_coil(14000, true).await.unwrap().unwrap();
    eventually("running again", async || line_state(&mut ctx).await == 2).await;
    eventually("fault relay off", async || !m(&mut ctx, 100).await).await;
    eventually("running relay on", async || m(&mut ctx, 101).await).await;
    let d0 = drive(&mut ctx, 0).await;
    assert_eq!(i32_at(&d0, 4), goal, "re-enabling did not move the drive");

    // Outside the drives: exceptions, as for any gap.
    let past = ctx.read_input_registers(20048, 1).await.unwrap();
    assert_eq!(past, Err(ExceptionCode::IllegalDataAddress));
    let holding = ctx.read_holding_registers(20000, 1).await.unwrap();
    assert_eq!(holding, Err(ExceptionCode::IllegalDataAddress));
    let beyond = ctx.read_coils(14001, 2).await.unwrap();
    assert_eq!(beyond, Err(ExceptionCode::IllegalDataAddress));

    // A clean stop disables the drives and prints the summary.
    drop(ctx);
    let last = server.terminate();
    let summary: Value = serde_json::from_str(&last).unwrap_or_else(|e| panic!("{e}: {last}"));
    assert_eq!(summary["drives"], 2);
    assert_eq!(summary["state"], "stopped");
    assert_eq!(summary["faults"].as_array().unwrap().len(), 1);
    assert!(summary["cycles"].as_u64().unwrap() > 100);
    assert_eq!(summary["actual"][0], goal);
}

#[test]
fn without_ethercat_the_bus_areas_stay_gaps() {
    let server = BusServer::start(&[]);
    let (status, body) = server.http("GET", "/api/ethercat", None);
    assert_eq!(status, 404);
    assert!(body.contains("--ethercat"), "{body}");
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    runtime.block_on(async {
        let mut ctx = server.client().await;
        let reply = ctx.read_input_registers(20000, 1).await.unwrap();
        assert_eq!(reply, Err(ExceptionCode::IllegalDataAddress));
        let reply = ctx.write_single_coil(14000, true).await.unwrap();
        assert_eq!(reply, Err(ExceptionCode::IllegalDataAddress));
    });
}

#[test]
fn bad_bus_configurations_are_refused_with_the_reason() {
    let dir = scratch_dir("serve-ethercat-bad");
    let cases = [
        (
            "cycle_us = 1500\n[[output]]\npulse = \"Y0\"\ndrive = 0\n",
            "not a whole number of scan periods",
        ),
        (
            "cycle_us = 1000\n[[output]]\npulse = \"Y5\"\ndrive = 0\n",
            "Y0, Y1, Y2 and Y3",
        ),
        (
            "cycle_us = 1000\nfault_relay = \"D100\"\n[[output]]\npulse = \"Y0\"\ndrive = 0\n",
            "name an M relay",
        ),
        (
            "cycle_us = 1000\n[[output]]\npulse = \"Y0\"\ndrive = 3\n",
            "drive 3 does not exist (the segment has 2)",
        ),
        ("cycle_us = 1000\n", "no [[output]]"),
        (
            "cycle_us = 1000\n[[output]]\npulse = \"Y0\"\ndrive = 0\n",
            "no interface",
        ),
    ];
    for (i, (text, message)) in cases.iter().enumerate() {
        let config = write(&dir, &format!("bad{i}.toml"), text);
        let mut args = vec!["serve", "--modbus", "127.0.0.1:0", "--http", "127.0.0.1:0"];
        args.extend(["--ethercat", config.to_str().unwrap()]);
        if *message != "no interface" {
            args.extend(["--emulated", "2"]);
        }
        let err = fails(ecam(&args));
        assert!(err.contains(message), "{text}: {err}");
    }
    // --emulated needs --ethercat (a usage error, exit 2).
    let out = ecam(&["serve", "--emulated", "2"]);
    assert_eq!(out.status.code(), Some(2));
}
