//! BMOV, FMOV/DFMOV, ZCP/DZCP and SFTL/SFTR against hand-computed FX3U results.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use ecam_plc::Plc;
use ecam_plc::{IndexReg, Program};

fn plc(src: &str) -> Plc {
    Plc::new(Program::parse(src, "t.il").unwrap()).unwrap()
}

fn words(plc: &Plc, from: u16, n: u16) -> Vec<i16> {
    (from..from + n)
        .map(|d| plc.devices().word(d).unwrap())
        .collect()
}

fn error(source: &str) -> String {
    Program::parse(source, "prog.il").unwrap_err().to_string()
}

#[test]
fn bmov_copies_a_block_even_onto_itself_shifted() {
    let mut plc = plc("LD M8000\nBMOVP D0 D10 K4\nBMOVP D20 D21 K3\nBMOVP D31 D30 K3\nEND\n");
    let d = plc.devices_mut();
    for (n, v) in [(0, 1), (1, 2), (2, 3), (3, 4), (4, 5)] {
        d.set_word(n, v).unwrap();
    }
    for (n, v) in [(20, 7), (21, 8), (22, 9), (31, 4), (32, 5), (33, 6)] {
        d.set_word(n, v).unwrap();
    }
    assert!(plc.scan().is_empty());
    assert_eq!(words(&plc, 10, 5), [1, 2, 3, 4, 0], "exactly n words");
    // Overlapping blocks end as if copied through a buffer.
    assert_eq!(words(&plc, 20, 4), [7, 7, 8, 9]);
    assert_eq!(words(&plc, 30, 4), [4, 5, 6, 6]);
}

#[test]
fn fmov_fills_words_and_dfmov_pairs() {
    let mut plc = plc("LD M8000\nFMOV K-3 D0 K3\nDFMOV K70000 D10 K2\nFMOV K9 D20Z0 D100\nEND\n");
    let d = plc.devices_mut();
    d.set_word(100, 2).unwrap();
    d.set_index_register(IndexReg::Z(0), 5).unwrap();
    assert!(plc.scan().is_empty());
    assert_eq!(words(&plc, 0, 4), [-3, -3, -3, 0]);
    assert_eq!(plc.devices().dword(10), Ok(70000));
    assert_eq!(plc.devices().dword(12), Ok(70000));
    assert_eq!(plc.devices().word(14), Ok(0));
    assert_eq!(words(&plc, 24, 4), [0, 9, 9, 0], "D20Z0 = D25, n from D100");
}

#[test]
fn a_block_past_d8511_or_a_bad_n_moves_nothing() {
    let mut plc = plc(concat!(
        "LD M8000\n",
        "BMOV D0 D8510 K3\n",
        "FMOV K1 D0 D100\n",
        "DFMOV K1 D8509 K2\n",
        "BMOV D0Z0 D10 K2\n",
        "END\n",
    ));
    let d = plc.devices_mut();
    d.set_word(0, 5).unwrap();
    d.set_word(100, 0).unwrap();
    d.set_index_register(IndexReg::Z(0), 8511).unwrap();
    let errors = plc.scan();
    let codes: Vec<(usize, u16)> = errors.iter().map(|e| (e.line, e.error.code)).collect();
    assert_eq!(
        codes,
        [(2, 6706), (3, 6705), (4, 6706), (5, 6706)],
        "{errors:?}"
    );
    assert_eq!(words(&plc, 8508, 4), [0, 0, 0, 0]);
    assert_eq!(words(&plc, 10, 2), [0, 0]);
}

#[test]
fn zcp_sets_below_inside_above() {
    let mut plc = plc(concat!(
        "LD M8000\n",
        "ZCP K10 K20 D0 M0\n",
        "ZCP K10 K20 D1 M10\n",
        "ZCP K10 K20 D2 M20\n",
        "ZCP K20 K10 D3 M30\n", // limits swapped: the upper is taken as 20
        "DZCP K-100000 K100000 D4 M40\n",
        "END\n",
    ));
    let d = plc.devices_mut();
    d.set_word(0, 9).unwrap();
    d.set_word(1, 20).unwrap();
    d.set_word(2, 21).unwrap();
    d.set_word(3, 15).unwrap();
    d.set_dword(4, -100_000).unwrap();
    assert!(plc.scan().is_empty());
    let bits = |plc: &Plc, m: u16| [m, m + 1, m + 2].map(|m| plc.devices().m(m).unwrap());
    assert_eq!(bits(&plc, 0), [true, false, false]);
    assert_eq!(
        bits(&plc, 10),
        [false, true, false],
        "the limits are inside"
    );
    assert_eq!(bits(&plc, 20), [false, false, true]);
    assert_eq!(bits(&plc, 30), [true, false, false], "15 < 20 = 20");
    assert_eq!(bits(&plc, 40), [false, true, false]);
}

#[test]
fn bad_block_and_zone_operands_fail_at_load() {
    for (src, needle) in [
        (
            "LD M8000\nBMOV D0 D10 K0\n",
            "n = 0 is out of range (K1 to K512)",
        ),
        ("LD M8000\nBMOV D0 D10 K513\n", "n = 513 is out of range"),
        ("LD M8000\nDBMOV D0 D10 K1\n", "BMOV has no 32-bit D form"),
        (
            "LD M8000\nFMOV K1 K4M0 K1\n",
            "FMOV operand 2: expected a D register",
        ),
        ("LD M8000\nFMOV K1 D0 M0\n", "FMOV operand 3"),
        ("LD M8000\nZCP K1 K2 D0\n", "ZCP expects 4 operands"),
        ("LD M8000\nZCP K1 K2 D0 M8510\n", "the two bits after it"),
        ("LD M8000\nZCP K1 K2 D0 D5\n", "ZCP operand 4"),
    ] {
        let message = error(src);
        assert!(
            message.starts_with("prog.il:2: ") && message.contains(needle),
            "{src:?}: {message}"
        );
    }
}

fn m_bits(plc: &Plc, first: u16, n: u16) -> Vec<u8> {
    (first..first + n)
        .map(|m| u8::from(plc.devices().m(m).unwrap()))
        .collect()
}

#[test]
fn sftl_and_sftr_shift_the_block_and_fill_from_s() {
    let mut plc = plc("LD M8000\nSFTLP X0 M0 K8 K2\nSFTRP X0 M10 K8 K2\nEND\n");
    let d = plc.devices_mut();
    d.set_bit(ecam_plc::Device::X(0), true).unwrap();
    for m in [1, 2, 10, 17] {
        d.set_m(m, true).unwrap();
    }
    assert!(plc.scan().is_empty());
    // Left: X0, X1 enter at M0, M1; M0–M5 move to M2–M7; M6, M7 are lost.
    assert_eq!(m_bits(&plc, 0, 8), [1, 0, 0, 1, 1, 0, 0, 0]);
    // Right: M12–M17 move to M10–M15; X0, X1 enter at M16, M17.
    assert_eq!(m_bits(&plc, 10, 8), [0, 0, 0, 0, 0, 1, 1, 0]);
    assert!(plc.scan().is_empty());
    assert_eq!(
        m_bits(&plc, 0, 8),
        [1, 0, 0, 1, 1, 0, 0, 0],
        "the P forms shift once per rising edge"
    );
}

#[test]
fn a_continuous_shift_moves_every_scan() {
    let mut plc = plc("LD M8000\nSFTL M100 M0 K4 K1\nEND\n");
    plc.devices_mut().set_m(100, true).unwrap();
    for expected in [[1, 0, 0, 0], [1, 1, 0, 0], [1, 1, 1, 0]] {
        assert!(plc.scan().is_empty());
        assert_eq!(m_bits(&plc, 0, 4), expected);
    }
}

#[test]
fn bad_shift_operands_fail_at_load() {
    for (src, needle) in [
        ("LD M8000\nSFTL X0 M0 K4 K5\n", "n2 = 5 is more than n1 = 4"),
        (
            "LD M8000\nSFTL X0 M0 K0 K0\n",
            "expected a K constant 1 to 1024",
        ),
        (
            "LD M8000\nSFTL X0 M0 K1025 K1\n",
            "expected a K constant 1 to 1024",
        ),
        (
            "LD M8000\nSFTL X0 X10 K4 K1\n",
            "SFTL operand 2: expected an output Y or a relay M",
        ),
        (
            "LD M8000\nSFTR D0 M0 K4 K1\n",
            "SFTR operand 1: expected an X, Y or M bit",
        ),
        (
            "LD M8000\nSFTR X0 M8500 K16 K1\n",
            "16 bits from M8500 run past the last device",
        ),
        ("LD M8000\nDSFTL X0 M0 K4 K1\n", "SFTL has no 32-bit D form"),
    ] {
        let message = error(src);
        assert!(
            message.starts_with("prog.il:2: ") && message.contains(needle),
            "{src:?}: {message}"
        );
    }
}
