//! Comparison contacts LD= … ORD>=, 16 and 32 bit, signed as on the FX.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use ecam_plc::Program;
use ecam_plc::{Device, Plc};

fn plc(src: &str) -> Plc {
    Plc::new(Program::parse(src, "t.il").unwrap()).unwrap()
}

fn y(plc: &Plc, n: u16) -> bool {
    plc.devices().bit(Device::Y(n)).unwrap()
}

fn error(source: &str) -> String {
    Program::parse(source, "prog.il").unwrap_err().to_string()
}

const RELATIONS: [&str; 6] = ["=", "<>", ">", "<", ">=", "<="];

/// One rung per relation: `LD<rel> D0 D2` drives Y0..Y5.
fn six_rungs(width: &str) -> String {
    RELATIONS
        .iter()
        .enumerate()
        .map(|(i, rel)| format!("LD{width}{rel} D0 D2\nOUT Y{i}\n"))
        .collect()
}

#[test]
fn sixteen_bit_comparisons_are_signed() {
    let mut p = plc(&six_rungs(""));
    // (D0, D2) → = <> > < >= <=
    for (a, b, expected) in [
        (0i16, 0i16, [true, false, false, false, true, true]),
        (-1, 0, [false, true, false, true, false, true]),
        (1, 0, [false, true, true, false, true, false]),
        (i16::MIN, i16::MAX, [false, true, false, true, false, true]),
        (i16::MAX, i16::MIN, [false, true, true, false, true, false]),
    ] {
        p.devices_mut().set_word(0, a).unwrap();
        p.devices_mut().set_word(2, b).unwrap();
        p.scan();
        let got: Vec<bool> = (0..6).map(|i| y(&p, i)).collect();
        assert_eq!(got, expected, "D0 = {a}, D2 = {b}");
    }
}

#[test]
fn thirty_two_bit_comparisons_use_both_words() {
    let mut p = plc(&(six_rungs("D") + "LD< D0 K0\nOUT Y10\n"));
    // 0x0001_8000 = 98304: positive as 32 bits, its low word 0x8000 is −32768.
    p.devices_mut().set_dword(0, 0x0001_8000).unwrap();
    p.devices_mut().set_dword(2, 32768).unwrap();
    p.scan();
    let got: Vec<bool> = (0..6).map(|i| y(&p, i)).collect();
    assert_eq!(got, [false, true, true, false, true, false]);
    assert!(y(&p, 8), "the 16-bit LD< sees only the low word, −32768");
    p.devices_mut().set_dword(0, i32::MIN).unwrap();
    p.devices_mut().set_dword(2, i32::MAX).unwrap();
    p.scan();
    let got: Vec<bool> = (0..6).map(|i| y(&p, i)).collect();
    assert_eq!(got, [false, true, false, true, false, true]);
}

#[test]
fn constants_and_counters_compare_by_value() {
    let mut p = plc(
        "LD= D0 HFFFF\nOUT Y0\nLD>= C0 K10\nOUT Y1\nLDD> C235 K100000\nOUT Y2\nLDD= D4 HFFFFFFFF\nOUT Y3\n",
    );
    p.devices_mut().set_word(0, -1).unwrap();
    p.devices_mut().set_counter(0, 10).unwrap();
    p.devices_mut().set_counter(235, 100_001).unwrap();
    p.devices_mut().set_dword(4, -1).unwrap();
    p.scan();
    assert!(y(&p, 0) && y(&p, 1) && y(&p, 2) && y(&p, 3));
    p.devices_mut().set_counter(0, 9).unwrap();
    p.devices_mut().set_counter(235, 100_000).unwrap();
    p.devices_mut().set_dword(4, 0xFFFF).unwrap();
    p.scan();
    assert!(y(&p, 0) && !y(&p, 1) && !y(&p, 2) && !y(&p, 3));
}

#[test]
fn and_and_or_forms_join_the_power_flow() {
    let mut p = plc(
        "LD X0\nAND= D0 K3\nOUT Y0\nLD X0\nOR<> D0 K3\nOUT Y1\nLD> D0 K0\nANDD< D2 K0\nORD= D2 K7\nOUT Y2\n",
    );
    for (x0, d0, d2, y0, y1, y2) in [
        (false, 3i16, 0i32, false, false, false),
        (true, 3, 0, true, true, false),
        (true, 4, 0, false, true, false),
        (false, 4, -1, false, true, true),
        (false, 0, 7, false, true, true),
        (false, 0, -1, false, true, false),
    ] {
        p.devices_mut().set_bit(Device::X(0), x0).unwrap();
        p.devices_mut().set_word(0, d0).unwrap();
        p.devices_mut().set_dword(2, d2).unwrap();
        p.scan();
        assert_eq!(
            (y(&p, 0), y(&p, 1), y(&p, 2)),
            (y0, y1, y2),
            "X0 = {x0}, D0 = {d0}, DD2 = {d2}"
        );
    }
}

#[test]
fn bad_comparisons_are_refused_at_their_line() {
    assert!(
        error("LD X0\nOUT Y0\nLD= D0\n")
            .starts_with("prog.il:3: LD= expects 2 operands (S1 S2), found 1")
    );
    assert!(
        error("LD= D0 M0\nOUT Y0\n").contains(
            "LD= operand 2: expected a K/H constant, a D register, a counter C, a word group KnM/KnX/KnY, an index register V/Z or (16 bit) a timer T, found M0"
        )
    );
    assert!(error("LD= K40000 D0\nOUT Y0\n").contains("out of range (K-32768 to K32767)"));
    assert!(error("LDD= K1 D8511\nOUT Y0\n").contains("D8511 has no D8512"));
    assert!(
        error("AND= D0 K1\nOUT Y0\n").starts_with("prog.il:1: AND/OR contact has no power flow")
    );
    assert!(error("LD== D0 K1\n").starts_with("prog.il:1: unknown instruction `LD==`"));
    assert!(error("LD X0\nAND< C200 K1\nOUT Y0\n").starts_with(
        "prog.il:2: AND< operand 1: C200 is a 32-bit counter: use the 32-bit form ANDD<"
    ));
    assert!(error("LD= D0 K1\nLD X0\nOUT Y0\n").starts_with("prog.il:3: 2 logic blocks are open"));
}
