//! Timers T0–T255 against the scan clock, hand-computed the FX way: the
//! value grows when `OUT Tn` runs, by the time since it last ran.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use ecam_plc::Program;
use ecam_plc::sim::{RunLength, Timing, run};
use ecam_plc::{Device, Plc};

fn plc(src: &str) -> Plc {
    Plc::new(Program::parse(src, "t.il").unwrap()).unwrap()
}

fn scans(plc: &mut Plc, scan_us: u32, n: u64) {
    let timing = Timing {
        scan_us,
        tick_us: scan_us,
    };
    let errors = run(plc, timing, RunLength::Scans(n), |_| {}).unwrap();
    assert!(errors.is_empty(), "{errors:?}");
}

fn t(plc: &Plc, n: u16) -> (i16, bool) {
    let timers = plc.devices().timers();
    (timers.value(n).unwrap(), timers.contact(n).unwrap())
}

fn set(plc: &mut Plc, device: Device, on: bool) {
    plc.devices_mut().set_bit(device, on).unwrap();
}

fn error(source: &str) -> String {
    Program::parse(source, "prog.il").unwrap_err().to_string()
}

#[test]
fn a_100ms_timer_times_out_at_the_scan_past_its_set_value() {
    // Scan k runs at t = 10k ms; T0 K10 is 1 s.
    let mut p = plc("LD M8000\nOUT T0 K10\nLD T0\nOUT Y0\n");
    scans(&mut p, 10_000, 100);
    assert_eq!(t(&p, 0), (9, false), "t = 990 ms");
    scans(&mut p, 10_000, 1);
    assert_eq!(t(&p, 0), (10, true), "t = 1000 ms");
    assert!(p.devices().bit(Device::Y(0)).unwrap());
    scans(&mut p, 10_000, 50);
    assert_eq!(t(&p, 0), (10, true), "the value stops at the set value");
}

#[test]
fn a_scan_longer_than_the_clock_carries_the_remainder() {
    // 30 ms scans on a 10 ms timer: +3 per scan; 34 × 3 = 102 ≥ 100.
    let mut p = plc("LD M8000\nOUT T200 K100\n");
    scans(&mut p, 30_000, 34);
    assert_eq!(t(&p, 200), (99, false));
    scans(&mut p, 30_000, 1);
    assert_eq!(t(&p, 200), (100, true), "stops at 100, not 102");
    // 7 ms scans on a 100 ms timer: 15 scans = 105 ms → 1 unit, 5 ms carried.
    let mut p = plc("LD M8000\nOUT T1 K3\n");
    scans(&mut p, 7_000, 16);
    assert_eq!(t(&p, 1), (1, false));
    scans(&mut p, 7_000, 14);
    assert_eq!(t(&p, 1), (2, false), "t = 203 ms: no time lost to rounding");
}

#[test]
fn an_ordinary_timer_restarts_when_its_coil_goes_off() {
    let mut p = plc("LD X0\nOUT T10 K5\n");
    set(&mut p, Device::X(0), true);
    scans(&mut p, 100_000, 4);
    assert_eq!(t(&p, 10), (3, false));
    set(&mut p, Device::X(0), false);
    scans(&mut p, 100_000, 1);
    assert_eq!(t(&p, 10), (0, false));
    set(&mut p, Device::X(0), true);
    scans(&mut p, 100_000, 6);
    assert_eq!(t(&p, 10), (5, true));
}

#[test]
fn a_retentive_1ms_timer_keeps_its_value_until_rst() {
    let mut p = plc("LD X0\nOUT T246 K50\nLD X1\nRST T246\n");
    set(&mut p, Device::X(0), true);
    scans(&mut p, 1_000, 30);
    assert_eq!(t(&p, 246), (29, false));
    set(&mut p, Device::X(0), false);
    scans(&mut p, 1_000, 10);
    assert_eq!(t(&p, 246), (29, false), "off time does not count");
    set(&mut p, Device::X(0), true);
    scans(&mut p, 1_000, 21);
    assert_eq!(t(&p, 246), (49, false));
    scans(&mut p, 1_000, 1);
    assert_eq!(t(&p, 246), (50, true));
    set(&mut p, Device::X(0), false);
    scans(&mut p, 1_000, 1);
    assert_eq!(t(&p, 246), (50, true), "the contact stays on too");
    set(&mut p, Device::X(1), true);
    scans(&mut p, 1_000, 1);
    assert_eq!(t(&p, 246), (0, false));
}

#[test]
fn set_value_zero_turns_the_contact_on_at_the_first_out() {
    let mut p = plc("LD T1\nOUT Y1\nLD X0\nOUT T1 K0\nLD T1\nOUT Y0\n");
    set(&mut p, Device::X(0), true);
    scans(&mut p, 1_000, 1);
    assert_eq!(t(&p, 1), (0, true));
    assert!(p.devices().bit(Device::Y(0)).unwrap());
    assert!(
        !p.devices().bit(Device::Y(1)).unwrap(),
        "a contact before the OUT sees it in the next scan"
    );
    scans(&mut p, 1_000, 1);
    assert!(p.devices().bit(Device::Y(1)).unwrap());
}

#[test]
fn the_value_is_a_word_and_the_set_value_may_be_a_register() {
    let mut p = plc("LD M8000\nOUT T3 D10\nMOV T3 D0\nLD>= T3 K2\nOUT Y0\n");
    p.devices_mut().set_word(10, 4).unwrap();
    scans(&mut p, 100_000, 3);
    assert_eq!(p.devices().word(0), Ok(2));
    assert!(p.devices().bit(Device::Y(0)).unwrap());
    assert_eq!(t(&p, 3), (2, false));
    // A negative set value in the register is an operand error (6705).
    p.devices_mut().set_word(10, -1).unwrap();
    let errors = run(&mut p, Timing::default(), RunLength::Scans(1), |_| {}).unwrap();
    assert_eq!(errors.len(), 1);
    assert_eq!(errors[0].line, 2);
    assert_eq!(p.devices().word(8067), Ok(6705));
}

#[test]
fn bad_timer_operands_are_refused_at_their_line() {
    assert!(error("LD X0\nOUT T0\n").starts_with("prog.il:2: OUT T0 needs a set value"));
    assert!(error("LD X0\nOUT T256 K1\n").contains("`T256` is out of range (timers T0-T255)"));
    assert!(error("LD X0\nOUT T0 K-1\n").contains("set value -1 is out of range for a timer"));
    assert!(error("LD X0\nOUT T0 K40000\n").contains("out of range (K-32768 to K32767)"));
    assert!(error("LD X0\nOUT T0 C0\n").contains("expected a K/H constant or a D register"));
    assert!(error("LD X0\nSET T0\n").contains("found T0"));
    assert!(error("LD X0\nDMOV T0 D0\n").contains("found T0"));
    assert!(Program::parse("LD T0\nOUT Y0\nLD X0\nRST T0\n", "t.il").is_ok());
}
