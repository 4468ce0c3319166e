//! Bits of data registers, `Dn.b`, as contacts and coils (FX3 family).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use ecam_plc::Program;
use ecam_plc::{Device, Plc};

fn plc(src: &str) -> Plc {
    Plc::new(Program::parse(src, "t.il").unwrap()).unwrap()
}

fn word(plc: &Plc, n: u16) -> u16 {
    plc.devices().word(n).unwrap() as u16
}

fn y(plc: &Plc, n: u16) -> bool {
    plc.devices().bit(Device::Y(n)).unwrap()
}

fn error(source: &str) -> String {
    Program::parse(source, "prog.il").unwrap_err().to_string()
}

#[test]
fn bad_word_bits_are_refused_at_their_line() {
    assert!(
        error("LD X0\nOUT D0.G\n").starts_with(
            "prog.il:2: OUT operand 1: `D0.G`: the bit number must be one hex digit 0-F"
        )
    );
    assert!(error("LD D0.10\n").starts_with("prog.il:1: LD operand 1: `D0.10`: the bit number"));
    assert!(error("LD X0\nSET M0.1\n").contains("only data registers D have addressable bits"));
    assert!(error("LD D8512.0\n").contains("out of range"));
    assert!(error("LD X0\nMOV D0.1 D2\n").contains("found D0.1"));
    assert!(error("LD X0\nPLS D0.1\n").contains("expected an output Y or a relay M, found D0.1"));
}

#[test]
fn a_contact_reads_one_bit_of_the_word() {
    // D2001 bit 0 is DECAM's "initialisation done", bit 1 "cycle complete".
    let mut p = plc("LD D2001.0\nOUT Y0\nLDI D2001.1\nOUT Y1\nLD X0\nOR D5.F\nOUT Y2\n");
    for (value, y0, y1) in [
        (0x0000u16, false, true),
        (0x0001, true, true),
        (0x0002, false, false),
        (0xFFFE, false, false),
    ] {
        p.devices_mut().set_word(2001, value as i16).unwrap();
        p.devices_mut().set_word(5, value as i16).unwrap();
        p.scan();
        assert_eq!((y(&p, 0), y(&p, 1)), (y0, y1), "D2001 = {value:04X}");
        assert_eq!(y(&p, 2), value & 0x8000 != 0, "D5 = {value:04X}");
    }
}

#[test]
fn coils_change_only_their_bit() {
    let mut p = plc("LD X0\nOUT D0.3\nLD X1\nSET D0.F\nLD X2\nRST D0.0\n");
    p.devices_mut().set_word(0, 0x0F01).unwrap();
    p.scan();
    // OUT with the power flow off clears bit 3; the rest stays.
    assert_eq!(word(&p, 0), 0x0F01 & !0x0008);
    p.devices_mut().set_bit(Device::X(0), true).unwrap();
    p.devices_mut().set_bit(Device::X(1), true).unwrap();
    p.scan();
    assert_eq!(word(&p, 0), 0x8F09);
    p.devices_mut().set_bit(Device::X(1), false).unwrap();
    p.devices_mut().set_bit(Device::X(2), true).unwrap();
    p.scan();
    // SET holds without its power flow; RST clears bit 0 only.
    assert_eq!(word(&p, 0), 0x8F08);
}

#[test]
fn edge_contacts_see_a_bit_change() {
    let mut p = plc("LDP D7.2\nOUT Y0\nLDF D7.2\nOUT Y1\n");
    let mut seen = Vec::new();
    for value in [0u16, 4, 4, 0, 0, 0xFFFF] {
        p.devices_mut().set_word(7, value as i16).unwrap();
        p.scan();
        seen.push((y(&p, 0), y(&p, 1)));
    }
    assert_eq!(
        seen,
        [
            (false, false),
            (true, false),
            (false, false),
            (false, true),
            (false, false),
            (true, false)
        ]
    );
}
