//! Counters the FX3U way, through IL: C0–C199 16-bit up counters, C200–C234
//! 32-bit up/down counters whose direction is M8200+n, ring-wrapping at 32
//! bits; contacts latched at counts and RST as on the FX3U.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use ecam_plc::Program;
use ecam_plc::{Device, Plc};

fn plc(src: &str) -> Plc {
    Plc::new(Program::parse(src, "t.il").unwrap()).unwrap()
}

fn set(plc: &mut Plc, device: Device, on: bool) {
    plc.devices_mut().set_bit(device, on).unwrap();
}

fn y0(plc: &Plc) -> bool {
    plc.devices().bit(Device::Y(0)).unwrap()
}

/// One scan with X0 at `level`.
fn pulse(plc: &mut Plc, level: bool) {
    set(plc, Device::X(0), level);
    assert!(plc.scan().is_empty());
}

#[test]
fn sixteen_bit_counter_counts_edges_stops_at_set_value_and_resets() {
    let mut plc = plc("LD X0\nOUT C0 K3\nLD C0\nOUT Y0\nLD X1\nRST C0\nEND\n");
    for _ in 0..2 {
        pulse(&mut plc, true);
        pulse(&mut plc, true); // a held input counts once
        pulse(&mut plc, false);
    }
    assert_eq!(plc.devices().counter(0), Ok(2));
    assert!(!y0(&plc));
    pulse(&mut plc, true);
    assert_eq!(plc.devices().counter(0), Ok(3));
    assert!(
        y0(&plc),
        "the contact switches when the count reaches the set value"
    );
    pulse(&mut plc, false);
    pulse(&mut plc, true);
    assert_eq!(plc.devices().counter(0), Ok(3), "stops at the set value");
    set(&mut plc, Device::X(1), true);
    pulse(&mut plc, false);
    assert_eq!(plc.devices().counter(0), Ok(0));
    pulse(&mut plc, false);
    assert!(
        !y0(&plc),
        "RST turns the contact off (seen by the next scan's LD C0)"
    );
    // While RST is on the counter does not count (RST after OUT in the scan).
    pulse(&mut plc, true);
    assert_eq!(plc.devices().counter(0), Ok(0));
}

#[test]
fn sixteen_bit_set_value_from_a_register() {
    let mut plc = plc("LD M8000\nMOV K2 D5\nLD X0\nOUT C10 D5\nLD C10\nOUT Y0\nEND\n");
    pulse(&mut plc, true);
    pulse(&mut plc, false);
    assert!(!y0(&plc));
    pulse(&mut plc, true);
    assert!(y0(&plc));
}

#[test]
fn thirty_two_bit_counter_counts_up_and_down_by_m8200_n() {
    let mut plc = plc("LD X0\nOUT C200 K2\nLD C200\nOUT Y0\nEND\n");
    pulse(&mut plc, true);
    pulse(&mut plc, false);
    assert!(!y0(&plc));
    pulse(&mut plc, true);
    assert_eq!(plc.devices().counter(200), Ok(2));
    assert!(y0(&plc), "on at value ≥ set value, counting up");
    pulse(&mut plc, false);
    pulse(&mut plc, true);
    assert_eq!(
        plc.devices().counter(200),
        Ok(3),
        "a 32-bit counter goes past its set value"
    );
    assert!(y0(&plc));
    plc.devices_mut().set_m(8200, true).unwrap();
    for expected in [2, 1] {
        pulse(&mut plc, false);
        pulse(&mut plc, true);
        assert_eq!(plc.devices().counter(200), Ok(expected));
    }
    assert!(!y0(&plc), "off below the set value, counting down");
    for _ in 0..3 {
        pulse(&mut plc, false);
        pulse(&mut plc, true);
    }
    assert_eq!(
        plc.devices().counter(200),
        Ok(-2),
        "32-bit counters go negative"
    );
}

#[test]
fn thirty_two_bit_counter_is_a_ring() {
    let mut plc = plc("LD X0\nOUT C234 K5\nEND\n");
    plc.devices_mut().set_counter(234, i32::MAX).unwrap();
    pulse(&mut plc, true);
    assert_eq!(plc.devices().counter(234), Ok(i32::MIN));
}

#[test]
fn a_16_bit_contact_is_latched_until_rst() {
    // Set value from D5; X1 raises it to 10, X2 overwrites the current value.
    let mut plc = plc(concat!(
        "LD M8000\nMOVP K3 D5\n",
        "LD X0\nOUT C0 D5\n",
        "LD C0\nOUT Y0\n",
        "LD X1\nMOV K10 D5\n",
        "LD X2\nMOV K1 C0\n",
        "LD X3\nRST C0\n",
        "END\n",
    ));
    for _ in 0..3 {
        pulse(&mut plc, true);
        pulse(&mut plc, false);
    }
    assert!(y0(&plc));
    set(&mut plc, Device::X(1), true);
    pulse(&mut plc, false);
    pulse(&mut plc, false);
    assert!(y0(&plc), "a larger set value does not turn the contact off");
    set(&mut plc, Device::X(2), true);
    pulse(&mut plc, false);
    pulse(&mut plc, false);
    assert_eq!(plc.devices().counter(0), Ok(1));
    assert!(y0(&plc), "nor does writing the current value");
    set(&mut plc, Device::X(2), false);
    pulse(&mut plc, true);
    assert_eq!(plc.devices().counter(0), Ok(2), "counting resumes to K10");
    assert!(y0(&plc));
    set(&mut plc, Device::X(3), true);
    pulse(&mut plc, false);
    pulse(&mut plc, false);
    assert!(!y0(&plc), "RST turns it off");
    assert_eq!(plc.devices().counter(0), Ok(0));
}

#[test]
fn a_32_bit_contact_moves_only_when_counting() {
    let mut plc = plc(concat!(
        "LD X0\nOUT C210 K5\n",
        "LD C210\nOUT Y0\n",
        "LD X1\nDMOV K100 C210\n",
        "LD X2\nRST C210\n",
        "END\n",
    ));
    let count = |plc: &mut Plc| {
        pulse(plc, true);
        pulse(plc, false);
    };
    for _ in 0..4 {
        count(&mut plc);
    }
    assert!(!y0(&plc));
    set(&mut plc, Device::X(1), true);
    pulse(&mut plc, false);
    set(&mut plc, Device::X(1), false);
    pulse(&mut plc, false);
    assert_eq!(plc.devices().counter(210), Ok(100));
    assert!(
        !y0(&plc),
        "DMOV past the set value: off until the next count"
    );
    count(&mut plc);
    assert_eq!(plc.devices().counter(210), Ok(101));
    assert!(y0(&plc), "a count up at ≥ set value turns it on");
    plc.devices_mut().set_m(8210, true).unwrap();
    set(&mut plc, Device::X(1), true);
    pulse(&mut plc, false);
    set(&mut plc, Device::X(1), false);
    // From 6, counting down: on at 5 (the set value), off at 4.
    plc.devices_mut().set_counter(210, 6).unwrap();
    count(&mut plc);
    assert_eq!(plc.devices().counter(210), Ok(5));
    assert!(y0(&plc), "still at the set value");
    count(&mut plc);
    assert_eq!(plc.devices().counter(210), Ok(4));
    assert!(!y0(&plc), "off when a count down leaves it below");
    set(&mut plc, Device::X(2), true);
    pulse(&mut plc, false);
    assert_eq!(plc.devices().counter(210), Ok(0));
}

#[test]
fn a_ring_wrap_while_counting_up_keeps_the_contact_on() {
    let mut plc = plc("LD X0\nOUT C234 K5\nLD C234\nOUT Y0\nEND\n");
    plc.devices_mut().set_counter(234, i32::MAX - 1).unwrap();
    pulse(&mut plc, true);
    pulse(&mut plc, false);
    assert_eq!(plc.devices().counter(234), Ok(i32::MAX));
    assert!(y0(&plc));
    pulse(&mut plc, true);
    pulse(&mut plc, false);
    assert_eq!(plc.devices().counter(234), Ok(i32::MIN), "32-bit ring");
    assert!(y0(&plc), "counting up never turns the contact off");
    // Counting down from −2147483648 wraps to 2147483647: not below K5.
    plc.devices_mut().set_m(8234, true).unwrap();
    pulse(&mut plc, true);
    pulse(&mut plc, false);
    assert_eq!(plc.devices().counter(234), Ok(i32::MAX));
    assert!(y0(&plc));
}
