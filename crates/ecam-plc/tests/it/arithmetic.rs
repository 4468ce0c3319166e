//! MUL/DIV/DMUL/DDIV, WAND/WOR/WXOR/DAND/DOR/DXOR and NEG with FX result
//! layouts, wrapping and the division-by-zero operation error.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use ecam_plc::Program;
use ecam_plc::{CODE_OPERAND, Device, Plc};

fn plc(src: &str) -> Plc {
    Plc::new(Program::parse(src, "t.il").unwrap()).unwrap()
}

/// Runs `body` once under M8000 and returns D0..D15 as unsigned words.
fn words_after(body: &str) -> Vec<u16> {
    let mut p = plc(&format!("LD M8000\n{body}\n"));
    let errors = p.scan();
    assert!(errors.is_empty(), "{errors:?}");
    (0..16)
        .map(|n| p.devices().word(n).unwrap() as u16)
        .collect()
}

fn error(source: &str) -> String {
    Program::parse(source, "prog.il").unwrap_err().to_string()
}

#[test]
fn mul_puts_the_32_bit_product_in_two_words() {
    // 1 000 000 = 0x000F_4240.
    assert_eq!(words_after("MUL K1000 K1000 D0")[..2], [0x4240, 0x000F]);
    assert_eq!(words_after("MUL K-2 K3 D0")[..2], [0xFFFA, 0xFFFF]);
    // 32767 × −32768 = −1 073 709 056 = 0xC000_8000.
    assert_eq!(words_after("MUL K32767 K-32768 D0")[..2], [0x8000, 0xC000]);
}

#[test]
fn dmul_puts_the_64_bit_product_in_four_words() {
    // 10^10 = 0x0000_0002_540B_E400.
    assert_eq!(
        words_after("DMUL K100000 K100000 D0")[..4],
        [0xE400, 0x540B, 0x0002, 0x0000]
    );
    assert_eq!(words_after("DMUL K-1 K1 D0")[..4], [0xFFFF; 4]);
    // (−2^31)² = 2^62.
    assert_eq!(
        words_after("DMUL H80000000 H80000000 D0")[..4],
        [0, 0, 0, 0x4000]
    );
}

#[test]
fn div_truncates_toward_zero_with_the_dividends_sign_on_the_remainder() {
    assert_eq!(
        words_after("DIV K-7 K2 D0")[..2],
        [(-3i16) as u16, (-1i16) as u16]
    );
    assert_eq!(words_after("DIV K7 K-2 D0")[..2], [(-3i16) as u16, 1]);
    // The FX3U programming manual's example: 5500 ÷ (−540) = −10 … 100.
    let w = words_after("DDIV K5500 K-540 D0");
    assert_eq!(w[..4], [(-10i16) as u16, 0xFFFF, 100, 0]);
    let w = words_after("DDIV K-100001 K10 D0");
    assert_eq!(w[..4], [(-10000i16) as u16, 0xFFFF, 0xFFFF, 0xFFFF]);
}

#[test]
fn division_by_zero_is_an_operation_error_and_leaves_the_result() {
    let mut p = plc("LD M8000\nMOV K0 D20\nDIV K5 D20 D10\nDDIV K5 K0 D12\n");
    p.devices_mut().set_word(10, 123).unwrap();
    p.devices_mut().set_word(11, 456).unwrap();
    p.devices_mut().set_dword(12, 7).unwrap();
    p.devices_mut().set_dword(14, 8).unwrap();
    let errors = p.scan();
    let lines: Vec<usize> = errors.iter().map(|e| e.line).collect();
    assert_eq!(lines, [3, 4]);
    assert_eq!(errors[0].error.code, CODE_OPERAND);
    assert_eq!(p.devices().word(8067), Ok(6705));
    assert!(p.devices().m(8067).unwrap());
    assert_eq!(p.devices().word(10), Ok(123));
    assert_eq!(p.devices().word(11), Ok(456));
    assert_eq!(p.devices().dword(12), Ok(7));
    assert_eq!(p.devices().dword(14), Ok(8));
}

#[test]
fn a_quotient_past_the_signed_range_is_an_operation_error() {
    let mut p = plc("LD M8000\nDIV K-32768 K-1 D0\nDDIV H80000000 K-1 D2\n");
    p.devices_mut().set_word(0, 11).unwrap();
    p.devices_mut().set_dword(2, 22).unwrap();
    let errors = p.scan();
    let lines: Vec<usize> = errors.iter().map(|e| e.line).collect();
    assert_eq!(lines, [2, 3]);
    assert_eq!(p.devices().word(0), Ok(11));
    assert_eq!(p.devices().dword(2), Ok(22));
    // Just inside the range divides normally.
    assert_eq!(words_after("DIV K-32768 K1 D0")[..2], [0x8000, 0]);
    assert_eq!(words_after("DIV K-32767 K-1 D0")[..2], [0x7FFF, 0]);
}

#[test]
fn word_logic_16_and_32_bit() {
    assert_eq!(words_after("WAND H0F0F HFF00 D0")[0], 0x0F00);
    assert_eq!(words_after("WOR H0F0F HFF00 D0")[0], 0xFF0F);
    assert_eq!(words_after("WXOR H0F0F HFF00 D0")[0], 0xF00F);
    assert_eq!(
        words_after("DAND HFFFF0000 H12345678 D0")[..2],
        [0x0000, 0x1234]
    );
    assert_eq!(
        words_after("DOR HFFFF0000 H12345678 D0")[..2],
        [0x5678, 0xFFFF]
    );
    assert_eq!(
        words_after("DXOR HFFFF0000 H12345678 D0")[..2],
        [0x5678, 0xEDCB]
    );
}

#[test]
fn neg_is_twos_complement_and_wraps() {
    assert_eq!(words_after("MOV K5 D0\nNEG D0")[0], (-5i16) as u16);
    assert_eq!(words_after("MOV K-32768 D0\nNEG D0")[0], 0x8000);
    assert_eq!(words_after("DMOV H80000000 D0\nDNEG D0")[..2], [0, 0x8000]);
    assert_eq!(
        words_after("DMOV K-70000 D0\nDNEG D0")[..2],
        [0x1170, 0x0001]
    );
    let mut p = plc("LD M8000\nMOV K9 C0\nNEG C0\n");
    p.scan();
    assert_eq!(p.devices().counter(0), Ok(-9));
}

#[test]
fn pulse_forms_run_once_per_rising_edge() {
    let mut p = plc(
        "LD X0\nNEGP D0\nMULP D0 K2 D2\nDIVP K100 D0 D4\nWXORP D6 HFFFF D6\nDXORP D8 K1 D8\nDMULP D8 K3 D10\nDDIVP K7 K2 D14\n",
    );
    p.devices_mut().set_word(0, 5).unwrap();
    p.devices_mut().set_bit(Device::X(0), true).unwrap();
    for _ in 0..3 {
        p.scan();
    }
    let d = |n: u16| p.devices().word(n).unwrap();
    assert_eq!(d(0), -5, "NEGP once, not three times");
    assert_eq!((d(2), d(3)), (-10, -1));
    assert_eq!((d(4), d(5)), (-20, 0));
    assert_eq!(d(6), -1);
    assert_eq!(p.devices().dword(8), Ok(1));
    assert_eq!(p.devices().dword(10), Ok(3));
    assert_eq!(
        (p.devices().dword(14), p.devices().dword(16)),
        (Ok(3), Ok(1))
    );
}

#[test]
fn bad_operands_are_refused_at_their_line() {
    assert!(error("LD X0\nDWAND K1 K2 D0\n").starts_with("prog.il:2: unknown instruction `DWAND`"));
    assert!(error("LD X0\nMUL K1 K2 D8511\n").contains("the result takes 2 registers from D8511"));
    assert!(error("LD X0\nDMUL K1 K2 D8509\n").contains("the result takes 4 registers from D8509"));
    assert!(Program::parse("LD X0\nDDIV K1 K2 D8508\n", "t.il").is_ok());
    assert!(
        error("LD X0\nDIV K1 K2 C0\n").contains(
            "DIV operand 3: expected a D register or a word group KnM/KnY (optionally index-modified), found C0"
        )
    );
    assert!(error("LD X0\nMUL K40000 K2 D0\n").contains("out of range (K-32768 to K32767)"));
    assert!(error("LD X0\nWAND K1 K2 K3\n").contains(
        "expected a D register, a counter C, an index register V/Z or a word group KnM/KnY"
    ));
    assert!(error("LD X0\nNEG K1\n").contains("NEG operand 1: expected a D register, a counter C"));
    assert!(error("LD X0\nDNEG D8511\n").contains("D8511 has no D8512"));
    assert!(error("LD X0\nWAND K1 D0\n").contains("WAND expects 3 operands (S1 S2 D), found 2"));
}
