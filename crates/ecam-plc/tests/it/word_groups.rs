//! Word groups `KnM`, `KnX`, `KnY` as source operands (n × 4 bits read as
//! a number, lowest bit first: FX digit specification), and `KnM`/`KnY` as
//! destinations, which take only their own n × 4 bits.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use ecam_plc::Program;
use ecam_plc::{Device, Plc};

fn plc(src: &str) -> Plc {
    Plc::new(Program::parse(src, "t.il").unwrap()).unwrap()
}

fn word(plc: &Plc, n: u16) -> i16 {
    plc.devices().word(n).unwrap()
}

fn error(source: &str) -> String {
    Program::parse(source, "prog.il").unwrap_err().to_string()
}

#[test]
fn word_groups_read_their_bits_as_a_number() {
    let mut plc = plc(
        "LD M8000\nMOV K1X0 D0\nMOV K2M10 D1\nMOV K4M100 D2\nDMOV K4M100 D4\nDMOV K8M200 D6\nADD K1X0 K1 D8\nCMP K1X0 K5 M50\nLD= K1X0 K5\nOUT Y0\nEND\n",
    );
    let d = plc.devices_mut();
    d.set_bit(Device::X(0), true).unwrap();
    d.set_bit(Device::X(2), true).unwrap();
    d.set_bit(Device::X(4), true).unwrap(); // outside K1X0
    d.set_m(10, true).unwrap();
    d.set_m(17, true).unwrap();
    d.set_m(18, true).unwrap(); // outside K2M10
    d.set_m(115, true).unwrap(); // bit 15 of K4M100
    d.set_m(231, true).unwrap(); // bit 31 of K8M200
    assert!(plc.scan().is_empty());
    assert_eq!(word(&plc, 0), 5);
    assert_eq!(word(&plc, 1), 0x81);
    assert_eq!(word(&plc, 2), i16::MIN, "K4 is signed at 16 bit");
    assert_eq!(plc.devices().dword(4), Ok(0x8000), "and positive at 32 bit");
    assert_eq!(
        plc.devices().dword(6),
        Ok(i32::MIN),
        "K8 is signed at 32 bit"
    );
    assert_eq!(word(&plc, 8), 6);
    assert!(plc.devices().m(51).unwrap(), "CMP: equal");
    assert!(plc.devices().bit(Device::Y(0)).unwrap());
}

#[test]
fn bad_word_groups_fail_at_load() {
    for (src, needle) in [
        ("LD M8000\nMOV K9M0 D0\n", "1 to 8 digits"),
        ("LD M8000\nMOV K0M0 D0\n", "1 to 8 digits"),
        (
            "LD M8000\nMOV K5M0 D0\n",
            "16-bit instruction takes K1 to K4",
        ),
        ("LD M8000\nMOV K4M8510 D0\n", "runs past the last M"),
        ("LD M8000\nMOV K4D0 D0\n", "not a K constant"),
        (
            "LD M8000\nMOV D0 K4X0\n",
            "MOV operand 2: K4X0 is an input group",
        ),
        ("LD M8000\nMOV D0 K5Y0\n", "this result takes K1 to K4"),
        ("LD M8000\nDIV D0 K1 K5Y0\n", "this result takes K1 to K4"),
        ("LD M8000\nDMOV D0 K4X0Z0\n", "K4X0Z0 is an input group"),
    ] {
        let message = error(src);
        assert!(
            message.starts_with("prog.il:2: ") && message.contains(needle),
            "{src:?}: {message}"
        );
    }
}

/// The number held by `digits` × 4 M relays from `first`, lowest first.
fn m_group(plc: &Plc, first: u16, digits: u16) -> u32 {
    (0..digits * 4).fold(0u32, |value, i| {
        value | u32::from(plc.devices().m(first + i).unwrap()) << i
    })
}

#[test]
fn word_groups_take_results_and_keep_only_their_own_bits() {
    let mut plc = plc(concat!(
        "LD M8000\n",
        "MOV K-1 K2Y0\n", // Y0–Y7 on, Y10 untouched
        "MOV H1234 K4M0\n",
        "DMOV K-1 K8M100\n",
        "ADD K2M200 K1 K2M200\n",    // 255 + 1 = 256: the low 8 bits are 0
        "INCP K1M220\n",             // 15 + 1 wraps to 0 in one digit
        "DECP K1M230\n",             // 0 − 1 = −1: all four bits on
        "MUL K300 K300 K8M300\n",    // 90000 = 0x15F90
        "MUL K300 K300 K4M340\n",    // low 16 bits: 0x5F90
        "DIV K100 K7 K2M400\n",      // quotient 14; no remainder
        "NEGP K2M500\n",             // 1 → −1 → 0xFF in 8 bits
        "WAND H0F0F H00FF K4M600\n", // 0x000F
        "DMUL K100000 K100000 K8M700\n", // 10^10: the low 32 bits, 0x540BE400
        "END\n",
    ));
    let d = plc.devices_mut();
    for m in 200..208 {
        d.set_m(m, true).unwrap();
    }
    for m in 220..224 {
        d.set_m(m, true).unwrap();
    }
    d.set_m(500, true).unwrap();
    d.set_m(408, true).unwrap(); // past K2M400: stays
    assert!(plc.scan().is_empty());
    for y in 0..8 {
        assert!(plc.devices().bit(Device::Y(y)).unwrap(), "Y{y:o}");
    }
    assert!(
        !plc.devices().bit(Device::Y(8)).unwrap(),
        "Y10 is not in K2Y0"
    );
    assert_eq!(m_group(&plc, 0, 4), 0x1234);
    assert_eq!(m_group(&plc, 100, 8), u32::MAX);
    assert_eq!(m_group(&plc, 200, 2), 0);
    assert!(!plc.devices().m(208).unwrap(), "ADD wrote only 8 bits");
    assert_eq!(m_group(&plc, 220, 1), 0);
    assert_eq!(m_group(&plc, 230, 1), 0xF);
    assert_eq!(m_group(&plc, 300, 8), 90_000);
    assert_eq!(m_group(&plc, 340, 4), 0x5F90);
    assert_eq!(m_group(&plc, 400, 2), 14);
    assert!(plc.devices().m(408).unwrap());
    assert_eq!(m_group(&plc, 500, 2), 0xFF);
    assert_eq!(m_group(&plc, 600, 4), 0x000F);
    assert_eq!(m_group(&plc, 700, 8), 0x540B_E400);
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(crate::cases(200)))]

    /// `MOV K<v> KnM<first>` writes v's low n × 4 bits there and leaves
    /// every other relay as it was; reading the group back gives them.
    #[test]
    fn a_group_destination_writes_only_its_bits(
        value in proptest::prelude::any::<i16>(),
        digits in 1u16..=4,
        first in 1u16..200,
        around in proptest::prelude::any::<bool>(),
    ) {
        let src = format!("LD M8000\nMOV K{value} K{digits}M{first}\nMOV K{digits}M{first} D0\nEND\n");
        let mut plc = plc(&src);
        for m in 0..300 {
            plc.devices_mut().set_m(m, around).unwrap();
        }
        proptest::prop_assert!(plc.scan().is_empty());
        let bits = digits * 4;
        let mask = if bits == 16 { u32::MAX } else { (1u32 << bits) - 1 };
        let expected = u32::from(value as u16) & mask;
        proptest::prop_assert_eq!(m_group(&plc, first, digits), expected);
        for m in (0..first).chain(first + bits..300) {
            proptest::prop_assert_eq!(plc.devices().m(m).unwrap(), around, "M{}", m);
        }
        let read_back = if bits == 16 { i32::from(value) } else { expected as i32 };
        proptest::prop_assert_eq!(i32::from(word(&plc, 0)), read_back);
    }
}
