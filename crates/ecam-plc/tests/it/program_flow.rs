//! Program flow the FX way: CJ to pointer labels, CALL/SRET subroutines
//! after FEND, and the load-time checks that keep a program from jumping to
//! nowhere.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use ecam_plc::Program;
use ecam_plc::watchdog::CODE_WATCHDOG;
use ecam_plc::{CODE_CALL_NESTING, Device, Plc};

fn plc(src: &str) -> Plc {
    Plc::new(Program::parse(src, "t.il").unwrap()).unwrap()
}

fn word(plc: &Plc, n: u16) -> i16 {
    plc.devices().word(n).unwrap()
}

fn bit(plc: &Plc, device: Device) -> bool {
    plc.devices().bit(device).unwrap()
}

fn set(plc: &mut Plc, device: Device, on: bool) {
    plc.devices_mut().set_bit(device, on).unwrap();
}

fn error(source: &str) -> String {
    Program::parse(source, "prog.il").unwrap_err().to_string()
}

#[test]
fn cj_skips_instructions_which_keep_their_outputs() {
    // X0 on: the rung driving Y0 is skipped and Y0 keeps its last state.
    let mut plc = plc("LD X0\nCJ P0\nLD X1\nOUT Y0\nLD M8000\nINC D0\nP0\nLD M8000\nINC D1\nEND\n");
    set(&mut plc, Device::X(1), true);
    plc.scan();
    assert!(bit(&plc, Device::Y(0)));
    assert_eq!((word(&plc, 0), word(&plc, 1)), (1, 1));
    set(&mut plc, Device::X(0), true);
    set(&mut plc, Device::X(1), false);
    plc.scan();
    plc.scan();
    assert!(bit(&plc, Device::Y(0)), "a skipped OUT keeps its output");
    assert_eq!((word(&plc, 0), word(&plc, 1)), (1, 3));
    set(&mut plc, Device::X(0), false);
    plc.scan();
    assert!(!bit(&plc, Device::Y(0)));
    assert_eq!((word(&plc, 0), word(&plc, 1)), (2, 4));
}

#[test]
fn cjp_jumps_in_the_scan_its_condition_turns_on() {
    let mut plc = plc("LD X0\nCJP P5\nLD M8000\nINC D0\nP5\nEND\n");
    set(&mut plc, Device::X(0), true);
    plc.scan();
    plc.scan();
    plc.scan();
    assert_eq!(word(&plc, 0), 2);
}

#[test]
fn cj_p63_jumps_to_end() {
    let mut plc = plc("LD M8000\nINC D0\nLD X0\nCJ P63\nLD M8000\nINC D1\nEND\n");
    set(&mut plc, Device::X(0), true);
    plc.scan();
    assert_eq!((word(&plc, 0), word(&plc, 1)), (1, 0));
    let mut plc = plc_with_fend();
    set(&mut plc, Device::X(0), true);
    plc.scan();
    assert_eq!((word(&plc, 0), word(&plc, 1)), (1, 0));
}

fn plc_with_fend() -> Plc {
    plc("LD M8000\nINC D0\nLD X0\nCJ P63\nLD M8000\nINC D1\nFEND\nP0\nLD M8000\nINC D2\nSRET\n")
}

#[test]
fn call_runs_the_subroutine_and_returns_after_the_call() {
    let mut plc = plc(
        "LD X0\nCALL P3\nLD M8000\nMOV D0 D1\nFEND\nP3\nLD M8000\nINC D0\nCALL P4\nSRET\nP4\nLD M8000\nADD D2 K10 D2\nSRET\nEND\n",
    );
    plc.scan();
    assert_eq!((word(&plc, 0), word(&plc, 1), word(&plc, 2)), (0, 0, 0));
    set(&mut plc, Device::X(0), true);
    plc.scan();
    plc.scan();
    assert_eq!((word(&plc, 0), word(&plc, 1), word(&plc, 2)), (2, 2, 20));
}

#[test]
fn fend_ends_the_main_program() {
    // Without a CALL the subroutine after FEND never runs.
    let mut plc = plc("LD M8000\nINC D0\nFEND\nP0\nLD M8000\nINC D1\nSRET\n");
    plc.scan();
    assert_eq!((word(&plc, 0), word(&plc, 1)), (1, 0));
}

#[test]
fn call_inside_an_mps_branch_restores_the_branch() {
    let mut plc = plc("LD X0\nMPS\nAND X1\nCALL P0\nMPP\nOUT Y0\nFEND\nP0\nLDI X0\nOUT Y1\nSRET\n");
    set(&mut plc, Device::X(0), true);
    set(&mut plc, Device::X(1), true);
    plc.scan();
    assert!(bit(&plc, Device::Y(0)));
    assert!(!bit(&plc, Device::Y(1)));
}

#[test]
fn endless_backward_jump_stops_the_program_on_the_watchdog() {
    let mut plc = plc(
        "LD M8000\nOUT Y7\nDPLSY K10000 K0 Y1\nLDI X0\nCJ P1\nP0\nLD M8000\nINC D0\nLD M8000\nCJ P0\nP1\nEND\n",
    );
    plc.scan();
    plc.hardware_tick(1000);
    assert!(plc.fault().is_none());
    assert_eq!(plc.devices().dword(8142), Ok(10), "Y1 pulses at 10 kHz");
    set(&mut plc, Device::X(0), true);
    assert!(
        plc.scan().is_empty(),
        "the watchdog is not an operation error"
    );
    let fault = plc.fault().expect("stopped by the watchdog");
    assert_eq!(fault.code(), CODE_WATCHDOG);
    assert_eq!(fault.line(), 10, "the line of the CJ that loops");
    assert!(fault.to_string().contains("D8000 = 200 ms"), "{fault}");
    // The FX's error stop: M8061/D8061, M8004/D8004, outputs off, M8000 off.
    assert!(bit(&plc, Device::M(8061)));
    assert_eq!(word(&plc, 8061), 6105);
    assert!(bit(&plc, Device::M(8004)));
    assert_eq!(word(&plc, 8004), 8061);
    assert!(!bit(&plc, Device::Y(7)));
    assert!(!bit(&plc, Device::M(8000)) && bit(&plc, Device::M(8001)));
    assert!(!bit(&plc, Device::M(8067)), "no operation error");
    // 0.2 µs per instruction: the scan stopped just after 10⁶ of them.
    assert_eq!(word(&plc, 8010), 2000, "200.0 ms in D8010 (0.1 ms)");
    plc.hardware_tick(1000);
    assert_eq!(plc.devices().dword(8142), Ok(10), "Y1's pulses stopped");
    // Stopped: the program no longer runs.
    let d0 = word(&plc, 0);
    assert!(plc.scan().is_empty());
    assert_eq!(word(&plc, 0), d0);
    assert!(!bit(&plc, Device::M(8000)));
}

#[test]
fn the_watchdog_time_is_d8000_as_the_program_sets_it() {
    // About 150 000 instructions a scan: 30 ms of modeled time.
    let source =
        "LD M8000\nMOV K20 D8000\nMOV K0 D0\nP0\nLD M8000\nINC D0\nLD< D0 K30000\nCJ P0\nEND\n";
    let mut plc = plc(source);
    assert_eq!(word(&plc, 8000), 200, "200 ms at power-on");
    // The first scan began with 200 ms: it finishes.
    plc.scan();
    assert!(plc.fault().is_none());
    assert_eq!((word(&plc, 8000), word(&plc, 0)), (20, 30000));
    let first = word(&plc, 8010);
    assert!((290..=310).contains(&first), "D8010 = {first} (0.1 ms)");
    // The next one is timed against 20 ms.
    plc.scan();
    let fault = plc.fault().expect("30 ms is over D8000 = 20 ms");
    assert!(fault.to_string().contains("D8000 = 20 ms"), "{fault}");
    assert!(word(&plc, 0) < 30000, "stopped inside the loop");
    assert_eq!(word(&plc, 8012), first, "the longest scan");
    assert!(word(&plc, 8011) <= word(&plc, 8010));
}

#[test]
fn backward_jump_that_terminates_is_a_loop() {
    // A loop within one scan: D0 counts to 10.
    let mut plc = plc("P1\nLD M8000\nINC D0\nLD< D0 K10\nCJ P1\nEND\n");
    assert!(plc.scan().is_empty());
    assert_eq!(word(&plc, 0), 10);
}

#[test]
fn nesting_is_checked_at_load_and_at_run_time() {
    let mut src = String::from("LD M8000\nCALL P0\nFEND\n");
    for n in 0..6 {
        src.push_str(&format!("P{n}\nLD M8000\nINC D{n}\n"));
        if n < 5 {
            src.push_str(&format!("CALL P{}\n", n + 1));
        }
        src.push_str("SRET\n");
    }
    let message = error(&src);
    assert!(message.contains("nested deeper than 5 levels"), "{message}");
    assert!(message.starts_with("prog.il:"), "{message}");
    // Five levels are fine.
    let src = src.replace("CALL P5\n", "");
    let mut plc = plc(&src);
    assert!(plc.scan().is_empty());
    assert_eq!(word(&plc, 4), 1);
    let _ = CODE_CALL_NESTING;
}

#[test]
fn flow_errors_name_file_and_line() {
    for (src, line, needle) in [
        ("LD X0\nCJ P7\nEND\n", 2, "no label P7"),
        (
            "P1\nLD X0\nOUT Y0\nP1\nEND\n",
            4,
            "duplicate label P1: already at line 1",
        ),
        (
            "LD X0\nCALL P1\nP1\nLD X0\nOUT Y0\nFEND\n",
            2,
            "must come after FEND",
        ),
        (
            "LD X0\nCALL P1\nFEND\nP1\nLD X0\nOUT Y0\n",
            4,
            "never returns",
        ),
        ("LD X0\nOUT Y0\nSRET\nFEND\n", 3, "SRET in the main program"),
        (
            "LD X0\nCJ P1\nFEND\nP1\nLD X0\nOUT Y0\nSRET\n",
            2,
            "other side of FEND",
        ),
        (
            "LD X0\nCALL P1\nFEND\nP1\nLD X0\nCALL P1\nSRET\n",
            6,
            "recursive",
        ),
        ("LD X0\nCJ P128\n", 2, "out of range"),
        ("LD X0\nCJ D0\n", 2, "expected a pointer"),
        ("LD X0\nCJ\n", 2, "expects 1 operand"),
        ("P63\nLD X0\nOUT Y0\n", 1, "END pointer"),
        ("LD X0\nCALL P63\n", 2, "END pointer"),
        ("P3 LD X0\n", 1, "stands alone"),
        ("FEND K1\n", 1, "takes no operands"),
        ("CJ P1\nP1\n", 1, "no power flow"),
    ] {
        let message = error(src);
        assert!(
            message.starts_with(&format!("prog.il:{line}: ")) && message.contains(needle),
            "{src:?}: {message}"
        );
    }
}

#[test]
fn many_subroutines_calling_each_other_load_in_linear_time() {
    // 120 subroutines, each calling the 60 after it: each is looked at once.
    let mut src = String::from("LD M8000\nCALL P0\nFEND\n");
    for n in 0..120u32 {
        src.push_str(&format!("P{n}\nLD M8000\n"));
        for m in (n + 1..120).take(60) {
            if m != 63 {
                src.push_str(&format!("CALL P{m}\n"));
            }
        }
        src.push_str("SRET\n");
    }
    let src = src.replace("P63\nLD M8000\n", "P127\nLD M8000\n");
    let started = std::time::Instant::now();
    let message = error(&src);
    assert!(message.contains("nested deeper than 5 levels"), "{message}");
    assert!(started.elapsed() < std::time::Duration::from_secs(5));
}
