//! Word groups `KnM`, `KnX`, `KnY` as source operands: n × 4 bits read as
//! a number, lowest bit first (FX digit specification).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use ecam_plc::il::{GroupKind, Instruction, Source, WordGroup, parse};
use ecam_plc::{Device, Plc};

fn plc(src: &str) -> Plc {
    Plc::new(parse(src, "t.il").unwrap()).unwrap()
}

fn word(plc: &Plc, n: u16) -> i16 {
    plc.devices().word(n).unwrap()
}

fn error(source: &str) -> String {
    parse(source, "prog.il").unwrap_err().to_string()
}

#[test]
fn word_groups_parse_as_sources() {
    let program = parse("LD M8000\nMOV k2x10 D0\n", "t.il").unwrap();
    assert_eq!(
        program.statements[1].instruction,
        Instruction::Move {
            width: ecam_plc::il::Width::Word,
            exec: ecam_plc::il::Exec::Continuous,
            src: Source::Group(WordGroup {
                kind: GroupKind::X,
                first: 8,
                digits: 2
            }),
            dst: Device::D(0),
        }
    );
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
        ("LD M8000\nMOV D0 K4M0\n", "MOV operand 2"),
    ] {
        let message = error(src);
        assert!(
            message.starts_with("prog.il:2: ") && message.contains(needle),
            "{src:?}: {message}"
        );
    }
}
