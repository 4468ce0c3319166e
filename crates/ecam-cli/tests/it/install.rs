//! What installs next to the binary and what it logs: shell completions,
//! man pages, log levels, the Modbus traffic trace and refused writes.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Command, Stdio};
use std::time::Duration;

use crate::common::{ecam, ok, scratch_dir};

#[test]
fn completions_for_each_shell_and_a_usage_error_for_others() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let script = ok(ecam(&["completions", shell]));
        assert!(
            script.contains("ecam") && script.contains("serve"),
            "{shell}"
        );
    }
    assert_eq!(ecam(&["completions", "tcsh"]).status.code(), Some(2));
}

#[test]
fn man_pages_cover_the_subcommands() {
    let page = ok(ecam(&["man"]));
    assert!(
        page.starts_with(".ie") || page.contains(".TH ecam 1"),
        "{page}"
    );
    assert!(page.contains("serve") && page.contains("completions"));
    let dir = scratch_dir("man");
    ok(ecam(&["man", "--dir", dir.to_str().unwrap()]));
    for name in ["ecam.1", "ecam-serve.1", "ecam-table-show.1"] {
        let text = std::fs::read_to_string(dir.join(name)).unwrap();
        assert!(text.contains(".TH"), "{name}");
    }
    let show = std::fs::read_to_string(dir.join("ecam-table-show.1")).unwrap();
    assert!(show.contains("master\\-speed"), "{show}");
}

/// Runs `ecam serve ARGS` on free loopback ports, writes coil 12000 (Y0,
/// read only: refused) and register 100 over Modbus, stops it, and returns
/// its stderr.
fn serve_and_write(args: &[&str]) -> String {
    let dir = scratch_dir(&format!("log-{}", args.join("_").replace('-', "")));
    let log = dir.join("stderr.log");
    let mut child = Command::new(env!("CARGO_BIN_EXE_ecam"))
        .args(["serve", "--modbus", "127.0.0.1:0", "--http", "127.0.0.1:0"])
        .args(args)
        .env_remove("RUST_LOG")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(std::fs::File::create(&log).unwrap())
        .spawn()
        .unwrap();
    let mut stdout = BufReader::new(child.stdout.take().unwrap());
    let mut line = String::new();
    stdout.read_line(&mut line).unwrap();
    let addr = line.trim().strip_prefix("modbus ").unwrap().to_string();
    let mut stream = TcpStream::connect(addr).unwrap();
    stream
        .set_read_timeout(Some(Duration::from_secs(10)))
        .unwrap();
    // tx 1: 05 write coil 12000 on; tx 2: 06 write register 100 = 3183.
    for frame in [
        [0, 1, 0, 0, 0, 6, 1, 5, 0x2E, 0xE0, 0xFF, 0],
        [0, 2, 0, 0, 0, 6, 1, 6, 0, 100, 0x0C, 0x6F],
    ] {
        stream.write_all(&frame).unwrap();
        let mut head = [0u8; 8];
        stream.read_exact(&mut head).unwrap();
        let mut rest = vec![0u8; usize::from(head[5]) - 2];
        stream.read_exact(&mut rest).unwrap();
    }
    drop(stream);
    // Give the log lines of the last answer a moment to be written.
    std::thread::sleep(Duration::from_millis(200));
    child.kill().unwrap();
    child.wait().unwrap();
    std::fs::read_to_string(&log).unwrap()
}

#[test]
fn refused_modbus_writes_are_logged_and_the_traffic_trace_shows_every_frame() {
    let log = serve_and_write(&["--trace-modbus"]);
    assert!(
        log.contains("write refused: 05 write coil 12000 = 1: illegal data address (02)"),
        "{log}"
    );
    assert!(
        log.contains("tx 1 unit 1 > 05 write coil 12000 = 1"),
        "{log}"
    );
    assert!(
        log.contains("tx 1 unit 1 < 85 exception illegal data address (02)"),
        "{log}"
    );
    assert!(
        log.contains("tx 2 unit 1 > 06 write register 100 = 3183"),
        "{log}"
    );
    assert!(log.contains("tx 2 unit 1 < done: 100 = 3183"), "{log}");
    assert!(log.contains("designer page at"), "{log}");
}

#[test]
fn quiet_keeps_warnings_and_no_trace_flag_no_traffic() {
    let log = serve_and_write(&["-q"]);
    assert!(log.contains("write refused: 05 write coil 12000"), "{log}");
    assert!(!log.contains("designer page at"), "{log}");
    assert!(!log.contains("06 write register"), "{log}");
    let log = serve_and_write(&["-qq"]);
    assert!(!log.contains("write refused"), "{log}");
}
